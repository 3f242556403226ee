/* keys_sdl — keyboard buttons and window close from an SDL window (private
 * to board/). Space/Enter/S = START, Escape/Backspace/X = STOP; closing the
 * window posts CUB_EV_QUIT. Only call while an SDL window is open. */
#ifndef CUB_BOARD_KEYS_SDL_H
#define CUB_BOARD_KEYS_SDL_H

#include <stdint.h>

#include "cub/loop.h"

/* Drain SDL's event queue into the loop (events stamped now_us). Keys
 * become button edges only if map_keys (not while a script drives them). */
void cub_keys_sdl_poll(cub_loop *loop, int64_t now_us, int map_keys);

#endif

/* keys_sdl — SDL keyboard and window events as loop events. */
#include "keys_sdl.h"

#include <SDL.h>

/* -1 for keys that are not buttons. */
static int key_button(SDL_Keycode k)
{
    switch (k) {
    case SDLK_SPACE:
    case SDLK_RETURN:
    case SDLK_KP_ENTER:
    case SDLK_s:
        return CUB_BUTTON_START;
    case SDLK_ESCAPE:
    case SDLK_BACKSPACE:
    case SDLK_x:
        return CUB_BUTTON_STOP;
    default:
        return -1;
    }
}

static void post(cub_loop *loop, int64_t now_us, int32_t type, int32_t a)
{
    cub_event ev = {.t_us = now_us, .type = type, .a = a};
    (void)cub_loop_post(loop, &ev); /* a full queue drops it; the loop counts drops */
}

void cub_keys_sdl_poll(cub_loop *loop, int64_t now_us, int map_keys)
{
    SDL_Event e;
    while (SDL_PollEvent(&e)) {
        if (e.type == SDL_QUIT) {
            post(loop, now_us, CUB_EV_QUIT, 0);
        } else if (map_keys && (e.type == SDL_KEYDOWN || e.type == SDL_KEYUP) && !e.key.repeat) {
            /* Key repeat is not a new press: a held key is one long press. */
            int b = key_button(e.key.keysym.sym);
            if (b >= 0) {
                post(loop, now_us, e.type == SDL_KEYDOWN ? CUB_EV_BUTTON_DOWN : CUB_EV_BUTTON_UP,
                     b);
            }
        }
    }
}

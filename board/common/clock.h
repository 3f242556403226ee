/* clock — the monotonic clock under cub_board_now_us (private to board/).
 * Board time is microseconds since the board opened: the board keeps the
 * origin, these give the raw monotonic time. */
#ifndef CUB_BOARD_CLOCK_H
#define CUB_BOARD_CLOCK_H

#include <stdint.h>

/* CLOCK_MONOTONIC in microseconds (never jumps with wall-clock changes). */
int64_t cub_clock_mono_us(void);
/* Sleep until CLOCK_MONOTONIC reaches t_mono_us; returns at once if past. */
void cub_clock_sleep_until_mono_us(int64_t t_mono_us);

#endif

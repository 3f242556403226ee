/* clock — board time (private to board/): microseconds since the board
 * started, read from CLOCK_MONOTONIC, or virtual.
 *
 * A virtual clock moves only when the loop sleeps, and then jumps straight
 * to the wake-up time: every tick lands exactly on its grid time and the run
 * goes as fast as the machine can. Replays use it so that the same recording
 * gives the same event log on every machine (fakenect still hands out one
 * recorded frame per poll, in order). */
#ifndef CUB_BOARD_CLOCK_H
#define CUB_BOARD_CLOCK_H

#include <stdint.h>

typedef struct cub_board_clock {
    int64_t origin_mono_us; /* board time 0, on CLOCK_MONOTONIC */
    int is_virtual;
    int64_t virtual_now_us;
} cub_board_clock;

/* Start the clock at board time 0 now. */
void cub_board_clock_start(cub_board_clock *c, int is_virtual);
/* Board time now. */
int64_t cub_board_clock_now_us(const cub_board_clock *c);
/* Wait until board time t_us (a virtual clock just moves there). */
void cub_board_clock_sleep_until_us(cub_board_clock *c, int64_t t_us);

/* CLOCK_MONOTONIC in microseconds (never jumps with wall-clock changes). */
int64_t cub_clock_mono_us(void);
/* Sleep until CLOCK_MONOTONIC reaches t_mono_us; returns at once if past. */
void cub_clock_sleep_until_mono_us(int64_t t_mono_us);

#endif

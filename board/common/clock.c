/* clock — CLOCK_MONOTONIC in microseconds, and an absolute sleep on it. */
#define _POSIX_C_SOURCE 200809L

#include "clock.h"

#include <errno.h>
#include <time.h>

int64_t cub_clock_mono_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

void cub_clock_sleep_until_mono_us(int64_t t_mono_us)
{
    if (t_mono_us <= cub_clock_mono_us()) {
        return;
    }
    struct timespec ts = {
        .tv_sec = (time_t)(t_mono_us / 1000000),
        .tv_nsec = (long)(t_mono_us % 1000000) * 1000,
    };
    /* An absolute deadline: a signal that interrupts us does not stretch it. */
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL) == EINTR) {
    }
}

void cub_board_clock_start(cub_board_clock *c, int is_virtual)
{
    c->origin_mono_us = cub_clock_mono_us();
    c->is_virtual = is_virtual;
    c->virtual_now_us = 0;
}

int64_t cub_board_clock_now_us(const cub_board_clock *c)
{
    return c->is_virtual ? c->virtual_now_us : cub_clock_mono_us() - c->origin_mono_us;
}

void cub_board_clock_sleep_until_us(cub_board_clock *c, int64_t t_us)
{
    if (!c->is_virtual) {
        cub_clock_sleep_until_mono_us(c->origin_mono_us + t_us);
    } else if (t_us > c->virtual_now_us) {
        c->virtual_now_us = t_us;
    }
}

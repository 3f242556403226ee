/* The depth sources that need no Kinect: the built-in empty scene (every
 * pixel "no reading", frames on a 30 Hz grid of board time) and "off". */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "clock.h"
#include "depth.h"

static cub_board_clock real_clock; /* started at 0: a real clock */

static void test_off_has_no_source(void **state)
{
    cub_depth *d = (cub_depth *)1;
    char err[128];
    assert_int_equal(cub_depth_open(CUB_DEPTH_OFF, &real_clock, &d, err, sizeof err), CUB_OK);
    assert_null(d);
    assert_string_equal(cub_depth_name(d), "off");
    cub_depth_frame f;
    assert_int_equal(cub_depth_poll(d, &f), CUB_ERR_DEVICE);
    assert_int_equal(cub_depth_open((cub_depth_mode)42, &real_clock, &d, err, sizeof err), CUB_ERR_ARG);
    assert_non_null(strstr(err, "unknown depth mode 42"));
}

/* k-th frame of the 30 Hz grid: exactly k * 1e6 / 30 us. */
static int on_grid(int64_t t_us)
{
    int64_t k = (t_us * CUB_DEPTH_EMPTY_PERIOD_DEN + CUB_DEPTH_EMPTY_PERIOD_NUM_US / 2) /
                CUB_DEPTH_EMPTY_PERIOD_NUM_US;
    return k * CUB_DEPTH_EMPTY_PERIOD_NUM_US / CUB_DEPTH_EMPTY_PERIOD_DEN == t_us;
}

/* On a virtual clock, polled at the very microsecond each frame falls
 * due (due times round down: 33333, 66666, 100000 us ...) and one before:
 * each due frame is handed out once, in order, never an earlier one again. */
static void test_empty_scene_frame_on_its_due_microsecond(void **state)
{
    (void)state;
    cub_board_clock clock;
    cub_board_clock_start(&clock, 1);
    cub_depth *d;
    char err[128];
    assert_int_equal(cub_depth_open(CUB_DEPTH_EMPTY, &clock, &d, err, sizeof err), CUB_OK);
    cub_depth_frame f;
    for (int64_t k = 0; k < 40; k++) {
        int64_t due = k * CUB_DEPTH_EMPTY_PERIOD_NUM_US / CUB_DEPTH_EMPTY_PERIOD_DEN;
        if (k > 0) {
            cub_board_clock_sleep_until_us(&clock, due - 1);
            assert_int_equal(cub_depth_poll(d, &f), CUB_ERR_EMPTY);
        }
        cub_board_clock_sleep_until_us(&clock, due);
        assert_int_equal(cub_depth_poll(d, &f), CUB_OK);
        assert_int_equal(f.seq, (uint32_t)k);
        assert_int_equal(f.t_us, due);
    }
    cub_depth_close(d);
}

static void test_empty_scene_frames_at_30hz_all_no_reading(void **state)
{
    cub_board_clock clock;
    cub_board_clock_start(&clock, 0);
    int64_t origin = clock.origin_mono_us;
    cub_depth *d;
    char err[128];
    assert_int_equal(cub_depth_open(CUB_DEPTH_EMPTY, &clock, &d, err, sizeof err), CUB_OK);
    assert_string_equal(cub_depth_name(d), "empty");
    enum { FRAMES = 12 };
    int64_t t_prev = -1;
    int got = 0, polls = 0;
    cub_depth_frame f;
    while (got < FRAMES) {
        cub_err e = cub_depth_poll(d, &f);
        polls++;
        if (e == CUB_ERR_EMPTY) {
            cub_clock_sleep_until_mono_us(cub_clock_mono_us() + 5000);
            continue;
        }
        assert_int_equal(e, CUB_OK);
        assert_int_equal(f.seq, (uint32_t)got);
        assert_true(f.t_us > t_prev);
        assert_true(on_grid(f.t_us));
        assert_int_equal(f.timestamp, (uint32_t)(f.t_us * 60));
        assert_int_equal(f.accel[0] | f.accel[1] | f.accel[2], 0);
        for (int i = 0; i < CUB_DEPTH_W * CUB_DEPTH_H; i++) {
            if (f.raw[i] != CUB_DEPTH_NO_READING) {
                fail_msg("pixel %d of frame %d is %u, not 2047", i, got, f.raw[i]);
            }
        }
        t_prev = f.t_us;
        got++;
    }
    int64_t span_us = cub_clock_mono_us() - origin;
    printf("depth empty: %d frames, first t=0 last t=%.6f s (%.2f Hz), %d polls in %.3f s\n",
           got, t_prev / 1e6, (got - 1) / (t_prev / 1e6), polls, span_us / 1e6);
    cub_depth_close(d);
}

/* Polled late, the empty scene hands out only the newest due frame. */
static void test_empty_scene_late_poll_gives_newest(void **state)
{
    cub_board_clock clock;
    cub_board_clock_start(&clock, 0);
    clock.origin_mono_us -= 1000000; /* the board opened 1 s ago */
    cub_depth *d;
    char err[128];
    assert_int_equal(cub_depth_open(CUB_DEPTH_EMPTY, &clock, &d, err, sizeof err), CUB_OK);
    cub_depth_frame f;
    assert_int_equal(cub_depth_poll(d, &f), CUB_OK);
    assert_int_equal(f.seq, 0);
    assert_true(f.t_us >= 1000000 - 33334);
    assert_true(on_grid(f.t_us));
    cub_depth_close(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_off_has_no_source),
        cmocka_unit_test(test_empty_scene_frame_on_its_due_microsecond),
        cmocka_unit_test(test_empty_scene_frames_at_30hz_all_no_reading),
        cmocka_unit_test(test_empty_scene_late_poll_gives_newest),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

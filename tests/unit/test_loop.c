/* loop: the event queue, the log formatter, timers and the fixed tick. */
#include <limits.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "cub/fx.h"
#include "cub/loop.h"

/* ---- a fake clock and recorder used as the loop's hooks ---------------- */

typedef struct harness {
    int64_t now_us;
    int64_t stall_us;        /* added to the clock once, at the next wait */
    cub_event handled[64];
    int handled_count;
    int64_t tick_times[64];
    int tick_count;
    char lines[16][CUB_LOG_LINE_MAX];
    int line_count;
    int post_on_handle;      /* handle() posts a user event for each button */
    cub_event to_poll[8];    /* pushed at the next poll */
    int to_poll_count;
} harness;

static int64_t h_now(void *u) { return ((harness *)u)->now_us; }
static void h_wait(void *u, int64_t t)
{
    harness *h = u;
    if (t > h->now_us) h->now_us = t;
    h->now_us += h->stall_us;
    h->stall_us = 0;
}
static void h_poll(void *u, cub_loop *loop, int64_t now)
{
    harness *h = u;
    for (int i = 0; i < h->to_poll_count; i++) cub_loop_post(loop, &h->to_poll[i]);
    h->to_poll_count = 0;
}
static void h_handle(void *u, cub_loop *loop, const cub_event *ev)
{
    harness *h = u;
    if (h->handled_count < 64) h->handled[h->handled_count++] = *ev;
    if (h->post_on_handle && ev->type == CUB_EV_BUTTON_DOWN) {
        cub_event e = {.t_us = ev->t_us, .type = CUB_EV_USER};
        cub_loop_post(loop, &e);
    }
}
static void h_tick(void *u, cub_loop *loop, int64_t t)
{
    harness *h = u;
    if (h->tick_count < 64) h->tick_times[h->tick_count++] = t;
}
static void h_sink(void *u, const char *line, size_t len)
{
    harness *h = u;
    if (h->line_count < 16) {
        assert_int_equal(strlen(line), len);
        snprintf(h->lines[h->line_count++], CUB_LOG_LINE_MAX, "%s", line);
    }
}

static cub_loop_hooks hooks_for(harness *h)
{
    cub_loop_hooks k = {.user = h, .now_us = h_now, .poll = h_poll, .handle = h_handle,
                        .tick = h_tick, .wait_until = h_wait};
    return k;
}

static cub_event slots[64];
static cub_loop loop;

static void make_loop(harness *h, uint32_t tick_us)
{
    memset(h, 0, sizeof *h);
    h->now_us = 1000000;
    cub_loop_desc d = {.tick_us = tick_us, .log_sink = h_sink, .log_user = h};
    assert_int_equal(cub_loop_init(&loop, &d, slots, sizeof slots), CUB_OK);
}

/* ---- queue ------------------------------------------------------------- */

static void test_queue_rejects_bad_capacity(void **s)
{
    cub_queue q;
    cub_event buf[8];
    assert_int_equal(cub_queue_init(&q, buf, 0), CUB_ERR_ARG);
    assert_int_equal(cub_queue_init(&q, buf, 1), CUB_ERR_ARG);
    assert_int_equal(cub_queue_init(&q, buf, 6), CUB_ERR_ARG);
    assert_int_equal(cub_queue_init(&q, NULL, 8), CUB_ERR_ARG);
    assert_int_equal(cub_queue_init(NULL, buf, 8), CUB_ERR_ARG);
}

static void test_queue_is_fifo_and_counts_drops_when_full(void **s)
{
    cub_queue q;
    cub_event buf[4], ev = {0}, out;
    assert_int_equal(cub_queue_init(&q, buf, 4), CUB_OK);
    assert_int_equal(cub_queue_pop(&q, &out), CUB_ERR_EMPTY);
    for (int i = 0; i < 4; i++) {
        ev.a = i;
        assert_int_equal(cub_queue_push(&q, &ev), CUB_OK);
    }
    ev.a = 99;
    assert_int_equal(cub_queue_push(&q, &ev), CUB_ERR_FULL);
    assert_int_equal(q.dropped, 1);
    assert_int_equal(cub_queue_count(&q), 4);
    for (int i = 0; i < 4; i++) {
        assert_int_equal(cub_queue_pop(&q, &out), CUB_OK);
        assert_int_equal(out.a, i);
    }
    assert_int_equal(cub_queue_pop(&q, &out), CUB_ERR_EMPTY);
}

static void test_queue_survives_index_wraparound(void **s)
{
    cub_queue q;
    cub_event buf[8], ev = {0}, out;
    assert_int_equal(cub_queue_init(&q, buf, 8), CUB_OK);
    q.head = q.tail = UINT32_MAX - 5; /* free-running indices about to wrap */
    for (int round = 0; round < 100; round++) {
        for (int i = 0; i < 3; i++) {
            ev.a = round * 3 + i;
            assert_int_equal(cub_queue_push(&q, &ev), CUB_OK);
        }
        for (int i = 0; i < 3; i++) {
            assert_int_equal(cub_queue_pop(&q, &out), CUB_OK);
            assert_int_equal(out.a, round * 3 + i);
        }
    }
    assert_int_equal(cub_queue_count(&q), 0);
}

/* ---- formatter --------------------------------------------------------- */

static void check_format(const char *expect, const char *got)
{
    assert_string_equal(got, expect);
}

static void test_format_integers_strings_and_q16(void **s)
{
    char b[128];
    cub_log_format(b, sizeof b, "%d %d %u %x %lld", -42, INT_MIN, 4000000000u, 255u,
                   (long long)-9000000000LL);
    check_format("-42 -2147483648 4000000000 ff -9000000000", b);
    cub_log_format(b, sizeof b, "d=%q d=%q d=%q d=%q", (int)26214, (int)-98304, 0,
                   (int)CUB_Q16_INT(12));
    check_format("d=0.400 d=-1.500 d=0.000 d=12.000", b);
    cub_log_format(b, sizeof b, "%s|%s|%c|100%%|%z", "clap", (const char *)NULL, 'x');
    check_format("clap|(null)|x|100%|%z", b);
}

static void test_format_cuts_long_output_and_terminates(void **s)
{
    char b[8];
    size_t n = cub_log_format(b, sizeof b, "%s", "abcdefghijkl");
    assert_int_equal(n, 7);
    check_format("abcdefg", b);
    assert_int_equal(cub_log_format(b, 0, "x"), 0);
}

static void test_log_line_has_time_source_event_details(void **s)
{
    harness h = {0};
    cub_log log = {.sink = h_sink, .user = &h};
    cub_log_event(&log, 12433999, "coach", "switch", "from=%s@%d to=%s@%d d=%q via=%s", "clap",
                  17, "correct_clap", 3, 13763, "direct");
    cub_log_event(&log, 5000, "loop", "start", NULL);
    assert_int_equal(log.lines, 2);
    check_format("t=12.433 coach switch from=clap@17 to=correct_clap@3 d=0.210 via=direct",
                 h.lines[0]);
    check_format("t=0.005 loop start", h.lines[1]);
}

/* ---- timers and the tick ----------------------------------------------- */

static void test_loop_init_rejects_small_memory(void **s)
{
    cub_loop l;
    cub_event few[4];
    cub_loop_desc d = {.queue_capacity = 8};
    assert_int_equal(cub_loop_mem_size(&d), 8 * sizeof(cub_event));
    assert_int_equal(cub_loop_init(&l, &d, few, sizeof few), CUB_ERR_NOMEM);
    d.queue_capacity = 12;
    cub_event more[16];
    assert_int_equal(cub_loop_init(&l, &d, more, sizeof more), CUB_ERR_ARG);
    assert_int_equal(cub_loop_init(&l, NULL, NULL, 0), CUB_ERR_ARG);
}

static void test_ticks_sit_on_a_fixed_grid(void **s)
{
    harness h;
    make_loop(&h, 0); /* default 33333 us */
    cub_loop_hooks k = hooks_for(&h);
    assert_int_equal(cub_loop_run(&loop, &k, 5), CUB_OK);
    assert_int_equal(h.tick_count, 5);
    for (int i = 0; i < 5; i++) assert_int_equal(h.tick_times[i], 1000000 + i * 33333);
}

static void test_stall_skips_ticks_and_logs_overrun(void **s)
{
    harness h;
    make_loop(&h, 10000);
    cub_loop_hooks k = hooks_for(&h);
    assert_int_equal(cub_loop_step(&loop, &k), CUB_OK); /* t = 1.000 */
    h.stall_us = 100000;                                /* 10 ticks lost */
    assert_int_equal(cub_loop_step(&loop, &k), CUB_OK);
    assert_int_equal(h.line_count, 1);
    assert_non_null(strstr(h.lines[0], "loop overrun skipped_ticks="));
    /* The tick after the stall is back on the grid, close to real time. */
    assert_int_equal((h.tick_times[1] - 1000000) % 10000, 0);
    assert_true(h.now_us - h.tick_times[1] < 10000);
}

static void test_timer_one_shot_and_periodic(void **s)
{
    harness h;
    make_loop(&h, 10000);
    cub_loop_hooks k = hooks_for(&h);
    assert_int_equal(cub_loop_timer_start(&loop, 0, 0, 10, 0), CUB_ERR_ARG);
    assert_int_equal(cub_loop_timer_start(&loop, 1, h.now_us, 25000, 0), CUB_OK);
    assert_int_equal(cub_loop_timer_start(&loop, 2, h.now_us, 20000, 20000), CUB_OK);
    assert_int_equal(cub_loop_run(&loop, &k, 7), CUB_OK); /* ticks at +0 .. +60 ms */
    /* Expect: t2@20, t1@25, t2@40, t2@60 — in time order. */
    int64_t want_t[] = {1020000, 1025000, 1040000, 1060000};
    int want_id[] = {2, 1, 2, 2};
    assert_int_equal(h.handled_count, 4);
    for (int i = 0; i < 4; i++) {
        assert_int_equal(h.handled[i].type, CUB_EV_TIMER);
        assert_int_equal(h.handled[i].a, want_id[i]);
        assert_int_equal(h.handled[i].t_us, want_t[i]);
    }
    cub_loop_timer_stop(&loop, 2);
    assert_int_equal(cub_loop_run(&loop, &k, 5), CUB_OK);
    assert_int_equal(h.handled_count, 4);
}

static void test_late_periodic_timer_fires_once_with_missed_count(void **s)
{
    harness h;
    make_loop(&h, 10000);
    cub_loop_hooks k = hooks_for(&h);
    /* A 1 us period can never keep up with a 10 ms tick: one event per tick,
     * carrying how many periods it missed, never a flood. */
    assert_int_equal(cub_loop_timer_start(&loop, 9, h.now_us, 0, 1), CUB_OK);
    assert_int_equal(cub_loop_run(&loop, &k, 3), CUB_OK);
    assert_int_equal(h.handled_count, 3);
    assert_int_equal(h.handled[0].b, 0);
    assert_int_equal(h.handled[1].b, 9999); /* 10000 periods fell due, one fired */
    assert_int_equal(loop.queue.dropped, 0);
    assert_int_equal(cub_loop_timer_start(&loop, 9, 0, INT64_MAX, 0), CUB_ERR_ARG);
    assert_int_equal(cub_loop_timer_start(&loop, 9, INT64_MAX, 1, 0), CUB_ERR_ARG);
}

static void test_log_time_handles_extremes(void **s)
{
    harness h = {0};
    cub_log log = {.sink = h_sink, .user = &h};
    cub_log_event(&log, INT64_MIN, "a", "b", NULL);
    cub_log_event(&log, -1500, "a", "b", NULL);
    check_format("t=-9223372036854.775 a b", h.lines[0]);
    check_format("t=-0.001 a b", h.lines[1]);
}

static void test_timer_table_full(void **s)
{
    harness h;
    make_loop(&h, 10000);
    for (int i = 1; i <= CUB_LOOP_MAX_TIMERS; i++)
        assert_int_equal(cub_loop_timer_start(&loop, i, 0, 1000, 0), CUB_OK);
    assert_int_equal(cub_loop_timer_start(&loop, 100, 0, 1000, 0), CUB_ERR_FULL);
    /* Restarting an existing id needs no new slot. */
    assert_int_equal(cub_loop_timer_start(&loop, 3, 0, 5000, 0), CUB_OK);
}

static void test_events_posted_while_handling_run_next_tick(void **s)
{
    harness h;
    make_loop(&h, 10000);
    cub_loop_hooks k = hooks_for(&h);
    h.post_on_handle = 1;
    h.to_poll[0] = (cub_event){.t_us = 1000000, .type = CUB_EV_BUTTON_DOWN, .a = CUB_BUTTON_START};
    h.to_poll_count = 1;
    assert_int_equal(cub_loop_step(&loop, &k), CUB_OK);
    assert_int_equal(h.handled_count, 1);
    assert_int_equal(cub_loop_step(&loop, &k), CUB_OK);
    assert_int_equal(h.handled_count, 2);
    assert_int_equal(h.handled[1].type, CUB_EV_USER);
}

static void test_quit_event_ends_the_loop(void **s)
{
    harness h;
    make_loop(&h, 10000);
    cub_loop_hooks k = hooks_for(&h);
    assert_int_equal(cub_loop_step(&loop, &k), CUB_OK);
    h.to_poll[0] = (cub_event){.type = CUB_EV_QUIT};
    h.to_poll_count = 1;
    assert_int_equal(cub_loop_step(&loop, &k), CUB_ERR_END);
    assert_int_equal(cub_loop_step(&loop, &k), CUB_ERR_END);
    assert_int_equal(h.tick_count, 2); /* the quitting tick still renders */
    assert_int_equal(cub_loop_run(&loop, &k, 0), CUB_OK);
}

static void test_full_queue_logs_a_drop(void **s)
{
    harness h;
    make_loop(&h, 10000);
    cub_event ev = {.type = CUB_EV_DEPTH_FRAME};
    for (int i = 0; i < 64; i++) assert_int_equal(cub_loop_post(&loop, &ev), CUB_OK);
    assert_int_equal(cub_loop_post(&loop, &ev), CUB_ERR_FULL);
    assert_int_equal(h.line_count, 1);
    assert_non_null(strstr(h.lines[0], "loop dropped type=depth_frame dropped=1"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_queue_rejects_bad_capacity),
        cmocka_unit_test(test_queue_is_fifo_and_counts_drops_when_full),
        cmocka_unit_test(test_queue_survives_index_wraparound),
        cmocka_unit_test(test_format_integers_strings_and_q16),
        cmocka_unit_test(test_format_cuts_long_output_and_terminates),
        cmocka_unit_test(test_log_line_has_time_source_event_details),
        cmocka_unit_test(test_loop_init_rejects_small_memory),
        cmocka_unit_test(test_ticks_sit_on_a_fixed_grid),
        cmocka_unit_test(test_stall_skips_ticks_and_logs_overrun),
        cmocka_unit_test(test_timer_one_shot_and_periodic),
        cmocka_unit_test(test_late_periodic_timer_fires_once_with_missed_count),
        cmocka_unit_test(test_log_time_handles_extremes),
        cmocka_unit_test(test_timer_table_full),
        cmocka_unit_test(test_events_posted_while_handling_run_next_tick),
        cmocka_unit_test(test_quit_event_ends_the_loop),
        cmocka_unit_test(test_full_queue_logs_a_drop),
    };
    return cmocka_run_group_tests_name("loop", tests, NULL, NULL);
}

/* The scripted judge timeline: bad lines first, then what good lines give. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "timeline.h"

static void expect_error(const char *text, const char *needle)
{
    cub_timeline *t = NULL;
    char err[300];
    assert_int_equal(cub_timeline_parse(text, strlen(text), "t.txt", &t, err, sizeof err),
                     CUB_ERR_FORMAT);
    assert_null(t);
    printf("timeline: bad -> %s\n", err);
    if (!strstr(err, needle)) fail_msg("error '%s' lacks '%s'", err, needle);
}

static void test_bad_lines_name_file_line_and_problem(void **s)
{
    expect_error("1.0 wrong\n2.0 dance\n", "t.txt:2: unknown event \"dance\"");
    expect_error("soon wrong\n", "t.txt:1: expected `<seconds> <what>`");
    expect_error("2.0 wrong\n1.0 right\n", "t.txt:2: time 1 s comes before");
    expect_error("-1 wrong\n", "t.txt:1: time -1 s is not in");
    expect_error("nan wrong\n", "t.txt:1: time nan s is not in");
    expect_error("1.0 wrong now\n", "t.txt:1: unexpected \"now\" after \"wrong\"");
    expect_error("1.0\n", "t.txt:1: expected `<seconds> <what>`");
    char nul[] = "1.0 wrong\n\0\n";
    cub_timeline *t;
    char err[300];
    assert_int_equal(cub_timeline_parse(nul, sizeof nul - 1, "t.txt", &t, err, sizeof err),
                     CUB_ERR_FORMAT);
    assert_non_null(strstr(err, "t.txt:2: contains a NUL byte"));
    assert_int_equal(cub_timeline_load("/no/such/timeline", &t, err, sizeof err), CUB_ERR_IO);
}

static void test_events_come_in_time_order_when_due(void **s)
{
    const char *text = "# a session\n"
                       "  0.5 clap   # wakes the coach\n"
                       "12.0 wrong\r\n"
                       "12.0 right\n"
                       "\n"
                       "20 nobody\n"
                       "26.25 player";
    cub_timeline *t = NULL;
    char err[300];
    assert_int_equal(cub_timeline_parse(text, strlen(text), "t.txt", &t, err, sizeof err),
                     CUB_OK);
    assert_int_equal(cub_timeline_count(t), 5);
    cub_event ev;
    assert_int_equal(cub_timeline_next(t, 400000, &ev), 0); /* not due yet */
    assert_int_equal(cub_timeline_next(t, 500000, &ev), 1);
    assert_int_equal(ev.type, CUB_EV_CLAP);
    assert_int_equal(ev.t_us, 500000);
    assert_int_equal(cub_timeline_next(t, 30000000, &ev), 1);
    assert_int_equal(ev.type, CUB_EV_VERDICT);
    assert_int_equal(ev.a, -1);
    assert_int_equal(ev.b, 0);
    assert_int_equal(cub_timeline_next(t, 30000000, &ev), 1);
    assert_int_equal(ev.b, 1);
    assert_int_equal(cub_timeline_next(t, 30000000, &ev), 1);
    assert_int_equal(ev.type, CUB_EV_PLAYER);
    assert_int_equal(ev.a, 0);
    assert_int_equal(cub_timeline_next(t, 30000000, &ev), 1);
    assert_int_equal(ev.a, 1);
    assert_int_equal(ev.t_us, 26250000);
    assert_int_equal(cub_timeline_next(t, 30000000, &ev), 0); /* all delivered */
    cub_timeline_free(t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_lines_name_file_line_and_problem),
        cmocka_unit_test(test_events_come_in_time_order_when_due),
    };
    return cmocka_run_group_tests_name("timeline", tests, NULL, NULL);
}

/* Scripted buttons: the timeline parser (good input, each kind of bad line
 * named by file:line) and the delivery of due edges, in time order, into
 * the loop's queue. */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "buttons_script.h"

static cub_err parse(const char *text, cub_button_script **s, char *err, size_t n)
{
    return cub_button_script_parse(text, strlen(text), "timeline.txt", s, err, n);
}

/* Parsing must fail with "timeline.txt:<line>: ..." mentioning `what`. */
static void expect_bad(const char *text, int line, const char *what)
{
    cub_button_script *s = (cub_button_script *)1;
    char err[256], prefix[32];
    assert_int_equal(parse(text, &s, err, sizeof err), CUB_ERR_FORMAT);
    assert_null(s);
    snprintf(prefix, sizeof prefix, "timeline.txt:%d: ", line);
    printf("script: rejected: %s\n", err);
    assert_true(strncmp(err, prefix, strlen(prefix)) == 0);
    assert_non_null(strstr(err, what));
}

static void test_bad_lines_name_file_line_and_problem(void **state)
{
    expect_bad("1 start\nabc start\n", 2, "bad time \"abc\"");
    expect_bad("-1 start\n", 1, "bad time");
    expect_bad("1.1234567 start\n", 1, "at most 6 decimals");
    expect_bad("1.5x start\n", 1, "bad time");
    expect_bad("# c\n\n2 go\n", 3, "unknown button \"go\"");
    expect_bad("1 stop hold\n", 1, "unknown action \"hold\"");
    expect_bad("1\n", 1, "expected");
    expect_bad("1 start down extra\n", 1, "too many fields");
    expect_bad("2 start\n1 stop\n", 2, "before the previous entry");
    expect_bad("1 start down\n2 start down\n", 2, "already down");
    expect_bad("1 stop up\n", 1, "already up");
    /* A press's release at 1.1 s meets a down at 1.05 s: the press is the culprit. */
    expect_bad("1 start press\n1.05 start down\n", 2, "already down");
    char with_nul[] = "1 start\n2 st\0p\n";
    cub_button_script *s;
    char err[256];
    assert_int_equal(cub_button_script_parse(with_nul, sizeof with_nul - 1, "timeline.txt", &s,
                                             err, sizeof err),
                     CUB_ERR_FORMAT);
    assert_non_null(strstr(err, "timeline.txt:2: "));
    assert_non_null(strstr(err, "NUL"));
}

static void test_bad_arguments(void **state)
{
    cub_button_script *s;
    char err[64];
    assert_int_equal(cub_button_script_parse(NULL, 3, "x", &s, err, sizeof err), CUB_ERR_ARG);
    assert_int_equal(cub_button_script_parse("", 0, "x", NULL, err, sizeof err), CUB_ERR_ARG);
    assert_int_equal(cub_button_script_load("/nonexistent/timeline.txt", &s, err, sizeof err),
                     CUB_ERR_IO);
    assert_non_null(strstr(err, "/nonexistent/timeline.txt"));
}

static void test_good_file_gives_edges_in_time_order(void **state)
{
    const char *text = "# a session\r\n"
                       "\n"
                       "0.5 start          # same as press\r\n"
                       "  2   stop down\n"
                       "2.05 start press\n" /* its up (2.15) lands after stop's up */
                       "2.1  stop up\n"
                       "7 start";           /* no final newline */
    cub_button_script *s;
    char err[256];
    assert_int_equal(parse(text, &s, err, sizeof err), CUB_OK);
    assert_int_equal(cub_button_script_edges(s), 8);
    enum { DOWN = CUB_EV_BUTTON_DOWN, UP = CUB_EV_BUTTON_UP };
    enum { START = CUB_BUTTON_START, STOP = CUB_BUTTON_STOP };
    struct {
        int64_t t_us;
        int32_t type, a;
    } want[8] = {
        {500000, DOWN, START},  {600000, UP, START},  {2000000, DOWN, STOP},
        {2050000, DOWN, START}, {2100000, UP, STOP},  {2150000, UP, START},
        {7000000, DOWN, START}, {7100000, UP, START},
    };
    cub_event ev;
    for (int i = 0; i < 8; i++) {
        assert_false(cub_button_script_next(s, want[i].t_us - 1, &ev)); /* not due yet */
        assert_true(cub_button_script_next(s, want[i].t_us, &ev));
        assert_int_equal(ev.t_us, want[i].t_us);
        assert_int_equal(ev.type, want[i].type);
        assert_int_equal(ev.a, want[i].a);
    }
    assert_false(cub_button_script_next(s, INT64_MAX, &ev));
    cub_button_script_free(s);
}

static void test_empty_script_has_no_edges(void **state)
{
    cub_button_script *s;
    char err[64];
    assert_int_equal(parse("# nothing\n\n", &s, err, sizeof err), CUB_OK);
    assert_int_equal(cub_button_script_edges(s), 0);
    cub_button_script_free(s);
}

static void test_load_reads_a_file(void **state)
{
    char path[] = "/tmp/cub_script_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    const char *text = "1 start\n3 stop\n";
    assert_int_equal(write(fd, text, strlen(text)), (ssize_t)strlen(text));
    close(fd);
    cub_button_script *s;
    char err[256];
    assert_int_equal(cub_button_script_load(path, &s, err, sizeof err), CUB_OK);
    assert_int_equal(cub_button_script_edges(s), 4);
    cub_button_script_free(s);
    /* The file name is what errors cite. */
    FILE *f = fopen(path, "w");
    fputs("1 start\n1 jump\n", f);
    fclose(f);
    assert_int_equal(cub_button_script_load(path, &s, err, sizeof err), CUB_ERR_FORMAT);
    assert_true(strncmp(err, path, strlen(path)) == 0);
    assert_non_null(strstr(err, ":2: unknown button"));
    unlink(path);
}

/* The loop's queue sees exactly the due edges, in time order; a full queue
 * keeps the rest for the next poll. */
static void test_poll_posts_due_edges_in_order(void **state)
{
    cub_loop_desc desc = {.queue_capacity = 4};
    size_t mem_size = cub_loop_mem_size(&desc);
    void *mem = malloc(mem_size);
    cub_loop loop;
    assert_int_equal(cub_loop_init(&loop, &desc, mem, mem_size), CUB_OK);
    cub_button_script *s;
    char err[64];
    const char *text = "1 start\n1 stop\n2 start down\n2.5 start up\n2.5 stop\n3 start\n";
    assert_int_equal(parse(text, &s, err, sizeof err), CUB_OK);
    cub_event ev;
    cub_button_script_poll(s, &loop, 999999);
    assert_int_equal(cub_queue_count(&loop.queue), 0);

    cub_button_script_poll(s, &loop, 1100000); /* start down+up, stop down+up */
    int64_t want_t[4] = {1000000, 1000000, 1100000, 1100000};
    int32_t want_type[4] = {CUB_EV_BUTTON_DOWN, CUB_EV_BUTTON_DOWN, CUB_EV_BUTTON_UP,
                            CUB_EV_BUTTON_UP};
    int32_t want_a[4] = {CUB_BUTTON_START, CUB_BUTTON_STOP, CUB_BUTTON_START, CUB_BUTTON_STOP};
    for (int i = 0; i < 4; i++) {
        assert_int_equal(cub_queue_pop(&loop.queue, &ev), CUB_OK);
        assert_int_equal(ev.t_us, want_t[i]);
        assert_int_equal(ev.type, want_type[i]);
        assert_int_equal(ev.a, want_a[i]);
    }
    /* 6 edges due at once into a 4-slot queue: 4 now, 2 next time. */
    cub_button_script_poll(s, &loop, 10000000);
    assert_int_equal(cub_queue_count(&loop.queue), 4);
    int64_t prev = 0;
    for (int i = 0; i < 4; i++) {
        assert_int_equal(cub_queue_pop(&loop.queue, &ev), CUB_OK);
        assert_true(ev.t_us >= prev);
        prev = ev.t_us;
    }
    cub_button_script_poll(s, &loop, 10000000);
    assert_int_equal(cub_queue_pop(&loop.queue, &ev), CUB_OK);
    assert_int_equal(ev.t_us, 3000000);
    assert_int_equal(ev.type, CUB_EV_BUTTON_DOWN);
    assert_int_equal(cub_queue_pop(&loop.queue, &ev), CUB_OK);
    assert_int_equal(ev.t_us, 3100000);
    assert_int_equal(ev.type, CUB_EV_BUTTON_UP);
    assert_int_equal(ev.a, CUB_BUTTON_START);
    assert_int_equal(cub_queue_pop(&loop.queue, &ev), CUB_ERR_EMPTY);
    cub_button_script_free(s);
    free(mem);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_arguments),
        cmocka_unit_test(test_bad_lines_name_file_line_and_problem),
        cmocka_unit_test(test_good_file_gives_edges_in_time_order),
        cmocka_unit_test(test_empty_script_has_no_edges),
        cmocka_unit_test(test_load_reads_a_file),
        cmocka_unit_test(test_poll_posts_due_edges_in_order),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

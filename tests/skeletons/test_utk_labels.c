#define _DEFAULT_SOURCE /* mkstemp */
/* UTKinect's actionLabel.txt reader on small files written here: the real
 * file's "action: NaN NaN" is an action missing from that run (accepted, no
 * interval), while half a NaN, a reversed interval, an interval before any
 * run and a garbled run name are refused with the file and line. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "kinect_read.h"

static int read_text(const char *text, utk_interval *iv, int max, char *err, size_t size)
{
    char path[] = "/tmp/cub_utk_labels_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
    int n = kinect_read_utk_labels(path, iv, max, err, size);
    unlink(path);
    return n;
}

static void test_nan_nan_is_a_missing_action(void **state)
{
    (void)state;
    utk_interval iv[16];
    char err[600] = "";
    int n = read_text("s01_e01\nwalk: 252 390\ncarry: NaN NaN\nthrow: 1434 1488\n"
                      "s09_e02\nwalk: NaN NaN\nclapHands: 10 20\n",
                      iv, 16, err, sizeof err);
    if (n < 0) fail_msg("%s", err);
    assert_int_equal(n, 3);
    assert_string_equal(iv[0].run, "s01_e01");
    assert_string_equal(iv[1].action, "throw");
    assert_int_equal(iv[1].first, 1434);
    assert_int_equal(iv[1].last, 1488);
    assert_string_equal(iv[2].run, "s09_e02");
    assert_string_equal(iv[2].action, "clapHands");
    for (int i = 0; i < n; i++) {
        assert_string_not_equal(iv[i].action, "carry");
        assert_true(iv[i].first <= iv[i].last);
    }
}

static void expect_refused(const char *text, int line, const char *what)
{
    utk_interval iv[16];
    char err[600] = "", at[16];
    snprintf(at, sizeof at, ":%d: ", line);
    assert_int_equal(read_text(text, iv, 16, err, sizeof err), -1);
    printf("utk: refused: %s\n", err);
    assert_non_null(strstr(err, "/tmp/cub_utk_labels_"));
    assert_non_null(strstr(err, at));
    assert_non_null(strstr(err, what));
}

static void test_bad_lines_are_refused(void **state)
{
    (void)state;
    expect_refused("s01_e01\nwalk: NaN 390\n", 2, "NaN NaN");
    expect_refused("s01_e01\nwalk: 12 nan\n", 2, "NaN NaN");
    expect_refused("s01_e01\nwalk: 390 252\n", 2, "interval");
    expect_refused("walk: 1 2\ns01_e01\n", 1, "interval outside a run");
    expect_refused("carry: NaN NaN\n", 1, "interval outside a run");
    expect_refused("s01_e01\nsitDown: NaN\n", 2, "sSS_eEE");
    expect_refused("s01_e01\nsitDown: x y\n", 2, "sSS_eEE");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_nan_nan_is_a_missing_action),
        cmocka_unit_test(test_bad_lines_are_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

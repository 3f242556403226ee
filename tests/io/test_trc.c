/* TRC marker files (cub/trc.h): the real OpenSim files under
 * $CUB_DATA_DIR/mocap/opensim read with their markers, frames and values;
 * lost markers stay missing; each bad file is refused naming its line. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/trc.h"

typedef struct real_file {
    const char *name;
    int markers, frames;
    double rate;
    const char *marker0;
    float x0; /* marker 0's x in frame 1, mm, as the file writes it */
} real_file;

static const real_file reals[] = {
    {"arm26_elbow_flex.trc", 3, 121, 120, "r_acromion", -13.05452443f},
    {"rajagopal_walk.trc", 41, 238, 100, "R.Shoulder", -652.630f},
    {"subject01_walk1.trc", 41, 151, 60, "R.ASIS", 617.247620f},
    {"subject02_running.trc", 41, 600, 60, NULL, 809.009400f},
};

static void test_real_files(void **state)
{
    (void)state;
    const char *data = getenv("CUB_DATA_DIR");
    if (!data) skip();
    for (size_t i = 0; i < sizeof reals / sizeof reals[0]; i++) {
        char path[512], msg[600];
        snprintf(path, sizeof path, "%s/mocap/opensim/%s", data, reals[i].name);
        cub_trc t;
        cub_diag d = {0};
        cub_err e = cub_trc_load(path, &t, &d);
        if (e) fail_msg("%s", cub_diag_str(&d, msg, sizeof msg));
        int lost = 0;
        for (int k = 0; k < t.frames * t.markers; k++)
            lost += !t.present[k];
        printf("trc: %s: %d markers, %d frames at %.0f Hz, %d lost marker-frames\n", reals[i].name,
               t.markers, t.frames, t.rate, lost);
        assert_int_equal(t.markers, reals[i].markers);
        assert_int_equal(t.frames, reals[i].frames);
        assert_true(fabs(t.rate - reals[i].rate) < 1e-9);
        if (reals[i].marker0) assert_string_equal(t.names[0], reals[i].marker0);
        assert_true(t.present[0]);
        assert_true(fabsf(t.pos[0] - reals[i].x0) < 1e-3f);
        /* frame times step by 1 / rate */
        assert_true(fabs(t.time[t.frames - 1] - (t.frames - 1) / t.rate) < 1e-3);
        cub_trc_free(&t);
    }
}

#define HEAD(units, frames, markers)                                                       \
    "PathFileType\t4\t(X/Y/Z)\tt.trc\n"                                                      \
    "DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\tOrigDataRate\tOrigDataStartFrame\t" \
    "OrigNumFrames\n"                                                                        \
    "50\t50\t" frames "\t" markers "\t" units "\t50\t1\t" frames "\n"
#define NAMES2 "Frame#\tTime\tA\t\t\tB\t\t\n\t\tX1\tY1\tZ1\tX2\tY2\tZ2\n\n"

/* Metres become mm; a marker lost in frame 2 is missing, not at 0,0,0. */
static void test_metres_and_missing(void **state)
{
    (void)state;
    const char *s = HEAD("m", "2", "2") NAMES2 "1\t0\t1\t2\t3\t4\t5\t6\n"
                                               "2\t0.02\t\t\t\t0.5\t0.25\t-1\t\n";
    cub_trc t;
    cub_diag d = {0};
    assert_int_equal(cub_trc_parse(s, strlen(s), "t.trc", &t, &d), CUB_OK);
    assert_int_equal(t.markers, 2);
    assert_string_equal(t.names[1], "B");
    assert_true(t.present[0] && t.present[1] && !t.present[2] && t.present[3]);
    assert_true(fabsf(t.pos[2] - 3000.0f) < 1e-3f);
    assert_true(fabsf(t.pos[3 * 3 + 2] + 1000.0f) < 1e-3f);
    cub_trc_free(&t);
}

static void expect_error(const char *text, int line, const char *words)
{
    cub_trc t;
    cub_diag d = {0};
    char msg[600];
    cub_err e = cub_trc_parse(text, strlen(text), "t.trc", &t, &d);
    printf("trc: rejected: %s\n", cub_diag_str(&d, msg, sizeof msg));
    assert_int_equal(e, CUB_ERR_FORMAT);
    assert_null(t.pos);
    assert_string_equal(d.file, "t.trc");
    assert_int_equal(d.line, line);
    if (!strstr(d.msg, words)) fail_msg("message '%s' lacks '%s'", d.msg, words);
    cub_trc_free(&t);
}

static void test_bad_files(void **state)
{
    (void)state;
    expect_error("", 0, "empty");
    expect_error("DataRate\tNumFrames\n", 1, "PathFileType");
    expect_error(HEAD("mm", "1", "2") NAMES2 "1.5\t0\t1\t2\t3\t4\t5\t6\n", 7, "frame '1.5'");
    expect_error("PathFileType\t4\n", 1, "header ends");
    expect_error("PathFileType\t4\nDataRate\tNumFrames\tNumMarkers\n50\t1\t1\n", 3, "Units");
    expect_error(HEAD("in", "1", "2") NAMES2 "1\t0\t1\t2\t3\t4\t5\t6\n", 3, "units 'in'");
    expect_error(HEAD("mm", "1", "300") NAMES2 "1\t0\t1\t2\t3\t4\t5\t6\n", 3, "NumMarkers");
    expect_error(HEAD("mm", "1", "3") NAMES2 "1\t0\t1\t2\t3\t4\t5\t6\n", 4, "fewer marker names");
    expect_error(HEAD("mm", "1", "2") NAMES2 "1\t0\t1\t2\t3\t4\t5\n", 7, "short of cells");
    expect_error(HEAD("mm", "1", "2") NAMES2 "1\t0\t1\t2\t3\t4\t5\t6\t7\n", 7, "more cells");
    expect_error(HEAD("mm", "1", "2") NAMES2 "1\t0\t1\tnan\t3\t4\t5\t6\n", 7, "'nan' is not");
    expect_error(HEAD("mm", "1", "2") NAMES2 "1\t0\t1\t2\t3\t4\t1e999\t6\n", 7, "finite");
    expect_error(HEAD("mm", "1", "2") NAMES2 "1\t0\t1\t\t3\t4\t5\t6\n", 7, "part of x y z");
    expect_error(HEAD("mm", "2", "2") NAMES2 "1\t0\t1\t2\t3\t4\t5\t6\n", 7, "fewer than NumFrames");
    expect_error(HEAD("mm", "1", "2") NAMES2 "1\t0\t1\t2\t3\t4\t5\t6\n2\t0\t1\t2\t3\t4\t5\t6\n",
                 8, "more rows");
    expect_error(HEAD("mm", "900", "2") NAMES2 "1\t0\t1\t2\t3\t4\t5\t6\n", 3, "more than the file");
}

int main(void)
{
    if (!getenv("CUB_DATA_DIR")) printf("trc: CUB_DATA_DIR is not set: the real files skip\n");
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_real_files),
        cmocka_unit_test(test_metres_and_missing),
        cmocka_unit_test(test_bad_files),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

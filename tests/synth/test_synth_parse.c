/* The synth's text formats: truth.txt, sequence files and joint tracks. First what bad
 * input gets (an error naming the file and the line), then round trips.
 * No data needed. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/synth.h"

#define HEAD "# cub-synth truth v1: test\n"

/* A frame line with every joint at (j, 2j, 1000 + j), visible. */
static void frame_line(char *buf, size_t size, int frame, const char *vis_of_last)
{
    int n = snprintf(buf, size, "%d 1300000000.%06d %u", frame, frame * 33333,
                     1000000u + 2000000u * (unsigned)frame);
    for (int j = 0; j < CUB_KJ_COUNT; j++)
        n += snprintf(buf + n, size - (size_t)n, " %d %d %d %s", j, 2 * j, 1000 + j,
                      j + 1 == CUB_KJ_COUNT ? vis_of_last : "1");
    snprintf(buf + n, size - (size_t)n, "\n");
}

/* A refusal of a file named file: at line, saying needle. */
static void expect_refusal(cub_err err, const cub_diag *d, const char *what, const char *file,
                           int line, const char *needle)
{
    char shown[600];
    assert_int_equal(err, CUB_ERR_FORMAT);
    cub_diag_str(d, shown, sizeof(shown));
    printf("%s: rejected as expected: %s\n", what, shown);
    assert_string_equal(d->file, file);
    assert_int_equal(d->line, line);
    assert_non_null(strstr(d->msg, needle));
}

static void expect_bad_truth(const char *text, int line, const char *needle)
{
    cub_synth_truth t;
    cub_diag d;
    cub_err err = cub_synth_truth_parse(text, strlen(text), "bad.txt", &t, &d);
    expect_refusal(err, &d, "synth truth", "bad.txt", line, needle);
    assert_null(t.frames);
}

static void test_truth_rejects_malformed_files(void **state)
{
    (void)state;
    char f0[4096], f1[4096], text[10000];
    frame_line(f0, sizeof(f0), 0, "1");
    frame_line(f1, sizeof(f1), 1, "1");
    expect_bad_truth("", 1, "not a truth file");
    expect_bad_truth("# something else\ngravity 0 -1000 0\n", 1, "not a truth file");
    expect_bad_truth(HEAD, 1, "no 'gravity'");
    expect_bad_truth(HEAD "gravity 0 -1000\n", 2, "gravity");
    expect_bad_truth(HEAD "gravity 0 x 0\n", 2, "bad gravity");
    expect_bad_truth(HEAD "gravity 0 0 0\n", 2, "zero");
    expect_bad_truth(HEAD "gravity 0 -1000 0\n0 1.0 5 1 2\n", 3, "expected 83 fields");
    snprintf(text, sizeof(text), HEAD "gravity 0 -1000 0\n%s%s", f1, f0);
    expect_bad_truth(text, 4, "does not follow");
    frame_line(f1, sizeof(f1), 1, "2");
    snprintf(text, sizeof(text), HEAD "gravity 0 -1000 0\n%s# note\n%s", f0, f1);
    expect_bad_truth(text, 5, "visibility of foot_r");
    frame_line(f1, sizeof(f1), 1, "1");
    char *nan = strstr(f1, " 1001 ");
    memcpy(nan, " nan  ", 6);
    snprintf(text, sizeof(text), HEAD "gravity 0 -1000 0\n%s%s", f0, f1);
    expect_bad_truth(text, 4, "bad z of spine");
    /* a truncated last line */
    snprintf(text, sizeof(text), HEAD "gravity 0 -1000 0\n%s%.100s", f0, f0);
    expect_bad_truth(text, 4, "expected 83 fields");
    expect_bad_truth(HEAD "gravity 0 -1000 0\n-1 1.0 5 1\n", 3, "expected 83");
    /* a NUL byte inside line 3 */
    cub_synth_truth t;
    cub_diag d;
    static const char nul[] = HEAD "gravity 0 -1000 0\n0 1\0 2\n";
    assert_int_equal(cub_synth_truth_parse(nul, sizeof(nul) - 1, "bad.txt", &t, &d),
                     CUB_ERR_FORMAT);
    assert_int_equal(d.line, 3);
    assert_non_null(strstr(d.msg, "NUL"));
}

static void test_truth_reads_frames_and_comments(void **state)
{
    (void)state;
    char f0[4096], f1[4096], text[10000];
    frame_line(f0, sizeof(f0), 0, "1");
    frame_line(f1, sizeof(f1), 3, "0");
    snprintf(text, sizeof(text), HEAD "gravity 0 -996.2 87.2\n%s\n# comment\n%s", f0, f1);
    cub_synth_truth t;
    cub_diag d;
    assert_int_equal(cub_synth_truth_parse(text, strlen(text), "ok.txt", &t, &d), CUB_OK);
    assert_int_equal(t.frame_count, 2);
    assert_true(t.gravity[2] > 87.1f && t.gravity[2] < 87.3f);
    assert_int_equal(t.frames[1].frame, 3);
    assert_int_equal(t.frames[1].ts, 7000000u);
    assert_true(t.frames[1].t_s > 1300000000.09 && t.frames[1].t_s < 1300000000.11);
    assert_true(t.frames[1].joint_mm[CUB_KJ_FOOT_R][2] == 1019.0f);
    assert_int_equal(t.frames[1].visible[CUB_KJ_FOOT_R], 0);
    assert_int_equal(t.frames[1].visible[CUB_KJ_HEAD], 1);
    cub_synth_truth_free(&t);
    cub_synth_truth_free(&t); /* twice is harmless */
}

static void expect_bad_sequence(const char *text, int line, const char *needle)
{
    cub_synth_segment *s;
    int n;
    cub_diag d;
    char shown[600];
    assert_int_equal(cub_synth_sequence_parse(text, strlen(text), "seq.txt", &s, &n, &d),
                     CUB_ERR_FORMAT);
    printf("synth sequence: rejected as expected: %s\n", cub_diag_str(&d, shown, sizeof(shown)));
    assert_int_equal(d.line, line);
    assert_non_null(strstr(d.msg, needle));
    assert_null(s);
    assert_int_equal(n, 0);
}

static void test_sequence_rejects_malformed_lines(void **state)
{
    (void)state;
    expect_bad_sequence("", 0, "no segments");
    expect_bad_sequence("# only a comment\n", 1, "no segments");
    expect_bad_sequence("13_29 0\n", 1, "expected 'clip from_s to_s");
    expect_bad_sequence("13_29 0 2\n13_29 x 2\n", 2, "bad from_s");
    expect_bad_sequence("13_29 3 2\n", 1, "bad to_s");
    expect_bad_sequence("13_29 0 2 mirrored\n", 1, "expected 'mirror'");
    expect_bad_sequence("13_29 0 2 mirror extra\n", 1, "expected 'clip");
    expect_bad_sequence("13_29 -1 2\n", 1, "bad from_s");
    cub_synth_segment *seg;
    int n;
    cub_diag d;
    static const char nul[] = "13_29 0 2\n\0x 0 2\n";
    assert_int_equal(cub_synth_sequence_parse(nul, sizeof(nul) - 1, "seq.txt", &seg, &n, &d),
                     CUB_ERR_FORMAT);
    assert_int_equal(d.line, 2);
    assert_non_null(strstr(d.msg, "NUL"));
}

static void test_sequence_reads_segments(void **state)
{
    (void)state;
    const char *text = "# the song\n13_29 0 4.5\n\n141_16 1 end mirror\r\n  05_06\t2 3";
    cub_synth_segment *s;
    int n;
    cub_diag d;
    assert_int_equal(cub_synth_sequence_parse(text, strlen(text), "seq.txt", &s, &n, &d), CUB_OK);
    assert_int_equal(n, 3);
    assert_string_equal(s[0].clip, "13_29");
    assert_true(s[0].to_s == 4.5 && !s[0].mirror);
    assert_true(s[1].from_s == 1 && s[1].to_s == 0 && s[1].mirror);
    assert_string_equal(s[2].clip, "05_06");
    assert_true(s[2].from_s == 2 && s[2].to_s == 3);
    free(s);
}

#define JT_HEAD "cub-jtrack 1\nfps 30\nunit_mm 0.5\nframes 3\n"

/* A frame line of 63 residuals: the first n given, the rest `fill`. */
static const char *jt_line(char *buf, const char *first, char fill)
{
    size_t n = strlen(first);
    memcpy(buf, first, n);
    int k = 0;
    for (const char *c = first; *c; c++)
        k += *c == '(' || (*c >= '@' && *c <= '~');
    for (; k < CUB_SYNTH_JTRACK_POINTS * 3; k++)
        buf[n++] = fill;
    buf[n++] = '\n';
    buf[n] = 0;
    return buf;
}

static void expect_bad_jtrack(const char *text, int line, const char *needle)
{
    cub_synth_jtrack t;
    cub_diag d;
    cub_err err = cub_synth_jtrack_parse(text, strlen(text), "bad.jtrack", &t, &d);
    expect_refusal(err, &d, "joint track", "bad.jtrack", line, needle);
    assert_null(t.points_mm);
    assert_int_equal(t.frame_count, 0);
}

static void test_jtrack_rejects_malformed_files(void **state)
{
    (void)state;
    char a[400], b[400], c[400], text[2000];
    jt_line(a, "(2000)", '_');
    jt_line(b, "`", '_');
    expect_bad_jtrack("", 0, "header ends early");
    expect_bad_jtrack("cub-jtrack 2\n", 1, "not a number in [1, 1]");
    expect_bad_jtrack("fps 30\n", 1, "expected 'cub-jtrack VALUE'");
    expect_bad_jtrack("cub-jtrack 1\nfps 0\n", 2, "fps");
    expect_bad_jtrack("cub-jtrack 1\nfps 30\nunit_mm x\n", 3, "unit_mm 'x'");
    expect_bad_jtrack("cub-jtrack 1\nfps 30\nunit_mm 1\nframes 2.5\n", 4, "not whole");
    snprintf(text, sizeof(text), JT_HEAD "%s%s", a, b);
    expect_bad_jtrack(text, 0, "2 frame lines, the header says 3");
    snprintf(text, sizeof(text), JT_HEAD "%s%s%s%s", a, b, b, b);
    expect_bad_jtrack(text, 8, "more frame lines");
    snprintf(text, sizeof(text), JT_HEAD "%s%s%s", a, jt_line(c, "` ", '_'), b);
    expect_bad_jtrack(text, 6, "value 2 of 63");
    snprintf(text, sizeof(text), JT_HEAD "%s%s%s", a, jt_line(c, "(12", '_'), b);
    expect_bad_jtrack(text, 6, "value 1 of 63");
    snprintf(text, sizeof(text), JT_HEAD "%s%.62s\n%s", a, b, b);
    expect_bad_jtrack(text, 6, "value 63 of 63");
    snprintf(text, sizeof(text), JT_HEAD "%s%.63s_\n%s", a, b, b);
    expect_bad_jtrack(text, 6, "more than 63 values");
    snprintf(text, sizeof(text), JT_HEAD "%s%s%s", jt_line(c, "(999999999)", '_'), a, b);
    expect_bad_jtrack(text, 5, "beyond");
}

/* Decoded: frame 0 as written, frame 1 its residual on frame 0, frame 2
 * the constant-velocity guess plus its residual. */
static void test_jtrack_decodes_and_drives_a_render(void **state)
{
    (void)state;
    char a[400], b[400], c[400], text[2000];
    snprintf(text, sizeof(text), "# a comment\n" JT_HEAD "%s%s%s", jt_line(a, "(2000)\\", '_'),
             jt_line(b, "`^", '_'), jt_line(c, "(40)", '_'));
    cub_synth_jtrack t;
    cub_diag d;
    assert_int_equal(cub_synth_jtrack_parse(text, strlen(text), "ok.jtrack", &t, &d), CUB_OK);
    assert_int_equal(t.frame_count, 3);
    assert_true(t.fps == 30 && t.unit_mm == 0.5f);
    const float *f0 = t.points_mm, *f1 = f0 + 63, *f2 = f1 + 63;
    assert_true(f0[0] == 1000.0f && f0[1] == -1.5f && f0[2] == 0.0f);
    assert_true(f1[0] == 1000.5f && f1[1] == -2.0f && f1[2] == 0.0f);
    assert_true(f2[0] == 1021.0f && f2[1] == -2.5f && f2[2] == 0.0f);
    /* The scene plays it: 3 frames, the hips where frame 1 has them. */
    cub_synth_desc desc = {.track = &t, .clean = 1};
    cub_synth *s;
    assert_int_equal(cub_synth_open(&desc, NULL, 0, &s, &d), CUB_OK);
    assert_int_equal(cub_synth_frame_count(s), 3);
    static uint16_t raw[640 * 480];
    cub_synth_truth_frame truth;
    assert_int_equal(cub_synth_render(s, 1, raw, &truth, NULL, NULL), CUB_OK);
    assert_true(fabsf(truth.joint_mm[CUB_KJ_HIP_CENTRE][0] - 1000.5f) < 1e-3f);
    assert_true(fabsf(truth.joint_mm[CUB_KJ_HIP_CENTRE][1] - (-2.0f - 800.0f)) < 1e-3f);
    assert_true(fabsf(truth.joint_mm[CUB_KJ_HIP_CENTRE][2] - 2200.0f) < 1e-3f);
    /* Written back, it is the same text (the comment aside; -3 was written
     * as its character '\\'). */
    const char *path = "test_synth_parse.jtrack"; /* in the test's folder */
    assert_int_equal(cub_synth_write_jtrack(s, path, 0.5f, NULL, &d), CUB_OK);
    cub_synth_close(s);
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    char back[2000] = {0};
    size_t n = fread(back, 1, sizeof(back) - 1, f);
    fclose(f);
    remove(path);
    assert_int_equal(n, strlen(text) - strlen("# a comment\n"));
    assert_string_equal(back, text + strlen("# a comment\n"));
    cub_synth_jtrack_free(&t);
}

static void test_raw_mapping_follows_the_formula(void **state)
{
    (void)state;
    assert_int_equal(cub_synth_mm_to_raw(499), CUB_KINECT_NO_READING);
    assert_int_equal(cub_synth_mm_to_raw(4001), CUB_KINECT_NO_READING);
    assert_int_equal(cub_synth_raw_to_mm(2047), 0.0);
    /* the ends of the range map to the first and last levels inside it */
    assert_true(cub_synth_raw_to_mm(cub_synth_mm_to_raw(500)) >= 500);
    assert_true(cub_synth_raw_to_mm((uint16_t)(cub_synth_mm_to_raw(500) - 1)) < 500);
    assert_true(cub_synth_raw_to_mm(cub_synth_mm_to_raw(4000)) <= 4000);
    assert_true(cub_synth_raw_to_mm((uint16_t)(cub_synth_mm_to_raw(4000) + 1)) > 4000);
    for (double mm = 501; mm <= 3994; mm += 7.3) {
        uint16_t r = cub_synth_mm_to_raw(mm);
        assert_true(r < 2047);
        double back = cub_synth_raw_to_mm(r);
        /* within half a quantisation step of the true depth */
        double step =
            cub_synth_raw_to_mm((uint16_t)(r + 1)) - cub_synth_raw_to_mm((uint16_t)(r - 1));
        assert_true(fabs(back - mm) <= step / 4 * 1.1);
        /* the firmware's table agrees with the formula to a millimetre */
        assert_true(abs((int)cub_track_raw_to_mm_int(r) - (int)lround(back)) <= 1);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_truth_rejects_malformed_files),
        cmocka_unit_test(test_truth_reads_frames_and_comments),
        cmocka_unit_test(test_sequence_rejects_malformed_lines),
        cmocka_unit_test(test_sequence_reads_segments),
        cmocka_unit_test(test_jtrack_rejects_malformed_files),
        cmocka_unit_test(test_jtrack_decodes_and_drives_a_render),
        cmocka_unit_test(test_raw_mapping_follows_the_formula),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

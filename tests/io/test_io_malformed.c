/* Bad input: a table of malformed BVH and ASF/AMC texts, each refused with
 * CUB_ERR_FORMAT and a message naming the right line. First the small valid
 * files they are cut from, to show what a good one gives. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/io.h"

/* Lines numbered for the table below. */
static const char k_bvh[] = "HIERARCHY\n"                                   /* 1 */
                            "ROOT Hips\n"                                   /* 2 */
                            "{\n"                                           /* 3 */
                            "  OFFSET 0 0 0\n"                              /* 4 */
                            "  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
                            "  JOINT Leg\n"                                 /* 6 */
                            "  {\n"                                         /* 7 */
                            "    OFFSET 0 -10 0\n"                          /* 8 */
                            "    CHANNELS 3 Zrotation Xrotation Yrotation\n" /* 9 */
                            "    End Site\n"                                /* 10 */
                            "    {\n"                                       /* 11 */
                            "      OFFSET 0 -10 0\n"                        /* 12 */
                            "    }\n"                                       /* 13 */
                            "  }\n"                                         /* 14 */
                            "}\n"                                           /* 15 */
                            "MOTION\n"                                      /* 16 */
                            "Frames: 2\n"                                   /* 17 */
                            "Frame Time: 0.033333\n"                        /* 18 */
                            "0 20 0 0 0 0 90 0 0\n"                         /* 19 */
                            "1 20 0 0 0 0 0 0 0\n";                         /* 20 */

static const char k_asf[] = ":version 1.10\n"           /* 1 */
                            ":units\n"                  /* 2 */
                            "  length 0.45\n"           /* 3 */
                            "  angle deg\n"             /* 4 */
                            ":root\n"                   /* 5 */
                            "  order TX TY TZ RX RY RZ\n" /* 6 */
                            "  axis XYZ\n"              /* 7 */
                            "  position 0 0 0\n"        /* 8 */
                            "  orientation 0 0 0\n"     /* 9 */
                            ":bonedata\n"               /* 10 */
                            "  begin\n"                 /* 11 */
                            "    id 1\n"                /* 12 */
                            "    name lfemur\n"         /* 13 */
                            "    direction 0 -1 0\n"    /* 14 */
                            "    length 7\n"            /* 15 */
                            "    axis 0 0 20 XYZ\n"     /* 16 */
                            "    dof rx ry rz\n"        /* 17 */
                            "    limits (-160.0 20.0)\n" /* 18 */
                            "           (-70.0 70.0)\n" /* 19 */
                            "           (-60.0 70.0)\n" /* 20 */
                            "  end\n"                   /* 21 */
                            ":hierarchy\n"              /* 22 */
                            "  begin\n"                 /* 23 */
                            "    root lfemur\n"         /* 24 */
                            "  end\n";                  /* 25 */

static const char k_amc[] = "#!OML:ASF test\n"           /* 1 */
                            ":FULLY-SPECIFIED\n"         /* 2 */
                            ":DEGREES\n"                 /* 3 */
                            "1\n"                        /* 4 */
                            "root 0 16 0 0 0 0\n"        /* 5 */
                            "lfemur 0 0 0\n"             /* 6 */
                            "2\n"                        /* 7 */
                            "root 1 16 0 0 0 0\n"        /* 8 */
                            "lfemur 90 0 0\n";           /* 9 */

/* Replace the first occurrence of `from` in base by `to`. */
static char *edit(const char *base, const char *from, const char *to)
{
    const char *at = strstr(base, from);
    assert_non_null(at);
    size_t n = strlen(base) - strlen(from) + strlen(to) + 1;
    char *out = malloc(n);
    assert_non_null(out);
    snprintf(out, n, "%.*s%s%s", (int)(at - base), base, to, at + strlen(from));
    return out;
}

static void test_small_bvh_reads_and_saves(void **state)
{
    (void)state;
    cub_io_motion m, back;
    cub_diag d;
    cub_io_desc cm = {.unit_mm = 10};
    char path[1100], msg[600];
    const char *build = getenv("CUB_BUILD_DIR");
    assert_int_equal(cub_io_parse_bvh(k_bvh, strlen(k_bvh), "small.bvh", &cm, &m, &d), CUB_OK);
    assert_int_equal(m.skel.joint_count, 3);
    assert_int_equal(m.skel.joints[2].is_end_site, 1);
    assert_string_equal(m.skel.joints[2].name, "Leg_end");
    assert_int_equal(m.clip.frame_count, 2);
    assert_int_equal(m.clip.frame_ns, 33333000);
    assert_string_equal(m.channels[0].rot_order, "ZXY");
    assert_string_equal(m.channels[0].pos_order, "XYZ");
    /* Frame 1: hips at 200 mm, the leg turned 90 degrees about Z points
     * its 100 mm bone along +X. */
    cub_pose p;
    cub_vec3 w[3];
    assert_int_equal(cub_motion_clip_get_frame(&m.clip, 0, &p), CUB_OK);
    assert_int_equal(cub_motion_forward(&m.skel, &p, w, NULL), CUB_OK);
    assert_true(fabs(w[2].x / 65536.0 - 100.0) < 0.01);
    assert_true(fabs(w[2].y / 65536.0 - 100.0) < 0.01);
    snprintf(path, sizeof(path), "%s/io_small_%ld.bvh", build ? build : "/tmp", (long)rand());
    if (cub_io_save_bvh(path, &m, &d))
        fail_msg("%s", cub_diag_str(&d, msg, sizeof(msg)));
    assert_int_equal(cub_io_load_bvh(path, &cm, &back, &d), CUB_OK);
    assert_int_equal(back.skel.joint_count, 3);
    assert_int_equal(back.clip.root_mm[1].x, m.clip.root_mm[1].x);
    remove(path);
    cub_io_motion_free(&m);
    cub_io_motion_free(&back);
}

static void test_small_asf_amc_reads(void **state)
{
    (void)state;
    cub_io_motion m;
    cub_diag d;
    char msg[600];
    if (cub_io_parse_asf_amc(k_asf, strlen(k_asf), k_amc, strlen(k_amc), "small", NULL, &m, &d))
        fail_msg("%s", cub_diag_str(&d, msg, sizeof(msg)));
    assert_int_equal(m.skel.joint_count, 3); /* root, lfemur, lfemur_end */
    assert_int_equal(m.clip.frame_count, 2);
    assert_true(fabs(m.unit_mm - 25.4 / 0.45) < 1e-9);
    /* Frame 2 bends the femur 90 degrees about its own x axis (the ASF
     * axis turns the frame 20 degrees about Z, x stays horizontal): the
     * knee swings from below the hip to the front of it (+Z). */
    cub_pose p;
    cub_vec3 w[3];
    assert_int_equal(cub_motion_clip_get_frame(&m.clip, 1, &p), CUB_OK);
    assert_int_equal(cub_motion_forward(&m.skel, &p, w, NULL), CUB_OK);
    double len = 7 * m.unit_mm, root_y = 16 * m.unit_mm;
    assert_true(fabs(w[2].y / 65536.0 - root_y) < 0.35 * len);
    assert_true(fabs(w[2].z / 65536.0) > 0.9 * len);
    cub_io_motion_free(&m);
}

typedef struct bad_case {
    const char *label;
    char *text;
    size_t len;
    int line;
    const char *msg;
} bad_case;

static void expect_bvh_error(const bad_case *c)
{
    cub_io_motion m;
    cub_diag d;
    char full[600];
    cub_io_desc cm = {.unit_mm = 10};
    cub_err err = cub_io_parse_bvh(c->text, c->len, "bad.bvh", &cm, &m, &d);
    printf("io: bad bvh %-20s -> %s\n", c->label, cub_diag_str(&d, full, sizeof(full)));
    assert_int_equal(err, CUB_ERR_FORMAT);
    assert_string_equal(d.file, "bad.bvh");
    assert_int_equal(d.line, c->line);
    if (!strstr(d.msg, c->msg))
        fail_msg("%s: message \"%s\" lacks \"%s\"", c->label, d.msg, c->msg);
}

static char *deep_bvh(int joints)
{
    size_t cap = 64 + (size_t)joints * 80, o = 0;
    char *s = malloc(cap);
    assert_non_null(s);
    o += (size_t)snprintf(s + o, cap - o, "HIERARCHY\nROOT J0\n{\nOFFSET 0 0 0\n");
    for (int k = 1; k < joints; k++)
        o += (size_t)snprintf(s + o, cap - o, "CHANNELS 3 Zrotation Xrotation Yrotation\nJOINT J%d\n{\nOFFSET 0 1 0\n", k);
    return s;
}

static void test_bad_bvh_gets_line_and_reason(void **state)
{
    (void)state;
    static const char garbage[] = "\x7f" "ELF\x02\x01\x01\0\0\0\xff\xfe{}}\n\x01\x02";
    bad_case cases[] = {
        {"empty", strdup(""), 0, 1, "empty file"},
        {"garbage", NULL, sizeof(garbage) - 1, 1, "expected 'HIERARCHY'"},
        {"missing {", edit(k_bvh, "{\n  OFFSET 0 0 0", "  OFFSET 0 0 0"), 0, 3,
         "expected '{' after ROOT name"},
        {"bad number", edit(k_bvh, "OFFSET 0 -10 0", "OFFSET 0 -1x0 0"), 0, 8, "bad number '-1x0'"},
        {"unknown channel", edit(k_bvh, "3 Zrotation", "3 Wrotation"), 0, 9,
         "unknown channel 'Wrotation'"},
        {"channel count", edit(k_bvh, "CHANNELS 3", "CHANNELS 9"), 0, 9, "CHANNELS count 9"},
        {"duplicate name", edit(k_bvh, "JOINT Leg", "JOINT Hips"), 0, 6,
         "joint name 'Hips' is used twice"},
        {"missing }", edit(k_bvh, "  }\n}\nMOTION", "  }\nMOTION"), 0, 15,
         "unexpected 'MOTION' in joint 'Hips' (missing '}')"},
        {"no MOTION", edit(k_bvh, "MOTION", "MOTON"), 0, 16, "expected 'MOTION'"},
        {"negative frames", edit(k_bvh, "Frames: 2", "Frames: -3"), 0, 17,
         "Frames: count is negative"},
        {"zero frames", edit(k_bvh, "Frames: 2", "Frames: 0"), 0, 17, "Frames: count is zero"},
        {"huge frames", edit(k_bvh, "Frames: 2", "Frames: 99999999"), 0, 17, "cannot fit"},
        {"overflow frames", edit(k_bvh, "Frames: 2", "Frames: 99999999999999999999"), 0, 17,
         "bad integer"},
        {"frame time", edit(k_bvh, "0.033333", "0"), 0, 18, "Frame Time 0 s"},
        {"short frame", edit(k_bvh, "1 20 0 0 0 0 0 0 0", "1 20 0 0 0 0 0 0"), 0, 20,
         "frame 2 has 8 values, expected 9"},
        {"nan", edit(k_bvh, "0 20 0 0 0 0 90", "0 20 nan 0 0 0 90"), 0, 19,
         "bad number 'nan' for frame 1 value 3"},
        {"truncated", edit(k_bvh, "0 0 0 0 90 0 0\n1 20 0 0 0 0 0 0 0\n", "0"), 0, 17,
         "Frames: 2 frames of 9 values cannot fit in the 7 bytes"},
        {"missing frame",
         edit(k_bvh, "0 20 0 0 0 0 90 0 0\n1 20 0 0 0 0 0 0 0\n",
              "0.0000 20.0000 0.0000 0.0000 0.0000 0.0000 90.0000 0.0000 0.0000\n"),
         0, 20, "file ends after 1 frames, Frames: says 2"},
        {"extra frame", edit(k_bvh, "0 0 0 0 0 0 0\n", "0 0 0 0 0 0 0\n1 2 3\n"), 0, 21,
         "more frame data than Frames: 2"},
        {"end site channels", edit(k_bvh, "      OFFSET 0 -10 0\n", "      OFFSET 0 -10 0\n CHANNELS 0\n"),
         0, 13, "End Site cannot have CHANNELS"},
        {"out of range", edit(k_bvh, "1 20 0", "1 9999 0"), 0, 20, "beyond the +-32 m"},
        {"long name", edit(k_bvh, "JOINT Leg", "JOINT LegLegLegLegLegLegLegLegLegLegLeg"), 0, 6,
         "longer than 31 characters"},
        {"too many joints", deep_bvh(130), 0, 2 + 4 * 128, "more than 128 joints"},
    };
    cases[1].text = malloc(sizeof(garbage));
    memcpy(cases[1].text, garbage, sizeof(garbage));
    for (size_t i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
        if (cases[i].len == 0)
            cases[i].len = strlen(cases[i].text);
        expect_bvh_error(&cases[i]);
        free(cases[i].text);
    }
}

typedef struct bad_pair {
    const char *label;
    char *asf, *amc;
    const char *file; /* "small.asf" or "small.amc" */
    int line;
    const char *msg;
} bad_pair;

static void test_bad_asf_amc_gets_line_and_reason(void **state)
{
    (void)state;
    bad_pair cases[] = {
        {"empty asf", strdup(""), strdup(k_amc), "small.asf", 1, "empty ASF file"},
        {"bad direction", edit(k_asf, "direction 0 -1 0", "direction 0 -1 zero"), strdup(k_amc),
         "small.asf", 14, "bad number 'zero'"},
        {"unknown dof", edit(k_asf, "dof rx ry rz", "dof rx rw rz"), strdup(k_amc), "small.asf",
         17, "unknown dof 'rw'"},
        {"no end", edit(k_asf, "  end\n:hierarchy", ":hierarchy"), strdup(k_amc), "small.asf",
         21, "unknown bone field ':hierarchy'"},
        {"hierarchy name", edit(k_asf, "root lfemur", "root lfemr"), strdup(k_amc), "small.asf",
         24, "unknown bone 'lfemr' in :hierarchy"},
        {"no hierarchy", edit(k_asf, ":hierarchy\n  begin\n    root lfemur\n  end\n", ""),
         strdup(k_amc), "small.asf", 22, "no :hierarchy section"},
        {"value count", strdup(k_asf), edit(k_amc, "lfemur 90 0 0", "lfemur 90 0"), "small.amc",
         9, "frame 2: bone 'lfemur' has 2 values, expected 3"},
        {"unknown bone", strdup(k_asf), edit(k_amc, "lfemur 0 0 0", "lfoot 0 0 0"), "small.amc",
         6, "unknown bone 'lfoot'"},
        {"frame order", strdup(k_asf), edit(k_amc, "2\n", "3\n"), "small.amc", 7,
         "frame number 3 follows 1"},
        {"frame number max", strdup(k_asf), edit(k_amc, "1\n", "9223372036854775807\n"),
         "small.amc", 7, "frame number 2 follows 9223372036854775807"},
        {"no frames", strdup(k_asf), strdup(":DEGREES\n"), "small.amc", 2, "no frames"},
        {"bad value", strdup(k_asf), edit(k_amc, "root 1 16", "root 1 1e999"), "small.amc", 8,
         "bad number '1e999'"},
    };
    for (size_t i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
        bad_pair *c = &cases[i];
        cub_io_motion m;
        cub_diag d;
        char full[600];
        cub_err err = cub_io_parse_asf_amc(c->asf, strlen(c->asf), c->amc, strlen(c->amc), "small",
                                           NULL, &m, &d);
        printf("io: bad asf/amc %-14s -> %s\n", c->label, cub_diag_str(&d, full, sizeof(full)));
        assert_int_equal(err, CUB_ERR_FORMAT);
        assert_string_equal(d.file, c->file);
        assert_int_equal(d.line, c->line);
        if (!strstr(d.msg, c->msg))
            fail_msg("%s: message \"%s\" lacks \"%s\"", c->label, d.msg, c->msg);
        free(c->asf);
        free(c->amc);
    }
}

static void test_missing_file_is_an_io_error(void **state)
{
    (void)state;
    cub_io_motion m;
    cub_diag d;
    char *text = NULL, full[600];
    size_t len = 0;
    assert_int_equal(cub_io_load_bvh("/nonexistent/x.bvh", NULL, &m, &d), CUB_ERR_IO);
    assert_string_equal(d.file, "/nonexistent/x.bvh");
    assert_int_equal(d.line, 0);
    assert_non_null(strstr(cub_diag_str(&d, full, sizeof(full)), "/nonexistent/x.bvh: cannot open"));
    cub_text_src src = {"/nonexistent/y", NULL, 0};
    assert_int_equal(cub_text_read(&src, &text, &len, &d), CUB_ERR_IO);
    assert_null(text);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_small_bvh_reads_and_saves),
        cmocka_unit_test(test_small_asf_amc_reads),
        cmocka_unit_test(test_bad_bvh_gets_line_and_reason),
        cmocka_unit_test(test_bad_asf_amc_gets_line_and_reason),
        cmocka_unit_test(test_missing_file_is_an_io_error),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

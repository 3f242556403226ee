/* The character file: each validation error names its line, then the real
 * bear loads with its skeleton, features, body and standing COG height. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/character.h"

/* A small valid character; the bad-input cases edit one line of it. */
static const char *const GOOD[] = {
    "<character name=\"toy\" version=\"1\">",                                      /* 1 */
    "  <skeleton>",                                                                /* 2 */
    "    <joint name=\"Hips\" parent=\"\" offset=\"0 300 0\"/>",                   /* 3 */
    "    <joint name=\"Spine\" parent=\"Hips\" offset=\"0 100 0\"/>",              /* 4 */
    "    <joint name=\"Neck\" parent=\"Spine\" offset=\"0 100 0\"/>",              /* 5 */
    "    <joint name=\"Head\" parent=\"Neck\" offset=\"0 50 0\"/>",                /* 6 */
    "    <joint name=\"Head_end\" parent=\"Head\" offset=\"0 200 0\" end=\"1\"/>", /* 7 */
    "    <joint name=\"LArm\" parent=\"Neck\" offset=\"100 0 0\"/>",               /* 8 */
    "    <joint name=\"LFore\" parent=\"LArm\" offset=\"150 0 0\"/>",              /* 9 */
    "    <joint name=\"LHand\" parent=\"LFore\" offset=\"120 0 0\"/>",             /* 10 */
    "    <joint name=\"RArm\" parent=\"Neck\" offset=\"-100 0 0\"/>",              /* 11 */
    "    <joint name=\"RFore\" parent=\"RArm\" offset=\"-150 0 0\"/>",             /* 12 */
    "    <joint name=\"RHand\" parent=\"RFore\" offset=\"-120 0 0\"/>",            /* 13 */
    "    <joint name=\"LUp\" parent=\"Hips\" offset=\"80 -20 0\"/>",               /* 14 */
    "    <joint name=\"LLeg\" parent=\"LUp\" offset=\"0 -140 0\"/>",               /* 15 */
    "    <joint name=\"LFoot\" parent=\"LLeg\" offset=\"0 -140 0\"/>",             /* 16 */
    "    <joint name=\"RUp\" parent=\"Hips\" offset=\"-80 -20 0\"/>",              /* 17 */
    "    <joint name=\"RLeg\" parent=\"RUp\" offset=\"0 -140 0\"/>",               /* 18 */
    "    <joint name=\"RFoot\" parent=\"RLeg\" offset=\"0 -140 0\"/>",             /* 19 */
    "  </skeleton>",                                                               /* 20 */
    "  <features hip_centre=\"Hips\" spine=\"Spine\" shoulder_centre=\"Neck\" head=\"Head\"", /* 21
                                                                                               */
    "            left_shoulder=\"LArm\" left_elbow=\"LFore\" left_wrist=\"LHand\"",    /* 22 */
    "            right_shoulder=\"RArm\" right_elbow=\"RFore\" right_wrist=\"RHand\"", /* 23 */
    "            left_hip=\"LUp\" left_knee=\"LLeg\" left_ankle=\"LFoot\"",            /* 24 */
    "            right_hip=\"RUp\" right_knee=\"RLeg\" right_ankle=\"RFoot\"/>",       /* 25 */
    "  <body>",                                                                        /* 26 */
    "    <part joint=\"Spine\" shape=\"ellipsoid\" centre=\"0 20 0\" radii=\"150 160 140\" "
    "colour=\"#9a6434\"/>", /* 27 */
    "    <part joint=\"LArm\" shape=\"capsule\" radius=\"50\" end_radius=\"40\" "
    "colour=\"#E3C08D\"/>", /* 28 */
    "  </body>",            /* 29 */
    "</character>",         /* 30 */
};
#define GOOD_LINES ((int)(sizeof(GOOD) / sizeof(GOOD[0])))

/* GOOD with line `line` (1-based) replaced by `with` (NULL: unchanged). */
static char *good_with(int line, const char *with)
{
    size_t cap = 8192, n = 0;
    char *buf = malloc(cap);
    assert_non_null(buf);
    for (int i = 0; i < GOOD_LINES; i++)
        n += (size_t)snprintf(buf + n, cap - n, "%s\n", (i + 1 == line && with) ? with : GOOD[i]);
    assert_true(n < cap);
    return buf;
}

static void expect_error(int line, const char *with, const char *words)
{
    char *text = good_with(line, with);
    cub_character *ch = malloc(sizeof(*ch));
    cub_diag d = {0};
    char msg[600];
    cub_err err = cub_character_parse(text, strlen(text), "toy.xml", ch, &d);
    cub_diag_str(&d, msg, sizeof(msg));
    printf("character: rejected: %s\n", msg);
    assert_int_equal(err, CUB_ERR_FORMAT);
    assert_string_equal(d.file, "toy.xml");
    assert_int_equal(d.line, line);
    if (!strstr(d.msg, words)) fail_msg("message '%s' lacks '%s'", d.msg, words);
    free(ch);
    free(text);
}

static void test_the_template_is_valid(void **state)
{
    (void)state;
    char *text = good_with(0, NULL);
    cub_character *ch = malloc(sizeof(*ch));
    cub_diag d = {0};
    cub_err err = cub_character_parse(text, strlen(text), "toy.xml", ch, &d);
    if (err) fail_msg("%s:%d: %s", d.file, d.line, d.msg);
    assert_int_equal(ch->skel.joint_count, 17);
    assert_int_equal(ch->part_count, 2);
    assert_true(ch->skel.joints[4].is_end_site);
    assert_int_equal(ch->parts[1].shape, CUB_PART_CAPSULE);
    assert_true(ch->parts[1].rgb[0] > 0.89f && ch->parts[1].rgb[0] < 0.891f); /* E3 = 227 */
    assert_true(ch->parts[1].end_radius_mm == 40.0f);
    for (int j = 0; j < ch->skel.joint_count; j++)
        assert_int_equal(ch->optional[j], 0);
    free(ch);
    free(text);
}

/* optional="1": a joint only some clips move (the winged bear's wings). */
static void test_optional_joint(void **state)
{
    (void)state;
    char *text = good_with(13, "    <joint name=\"RHand\" parent=\"RFore\" offset=\"-120 0 0\" "
                               "optional=\"1\"/>");
    cub_character *ch = malloc(sizeof(*ch));
    cub_diag d = {0};
    cub_err err = cub_character_parse(text, strlen(text), "toy.xml", ch, &d);
    if (err) fail_msg("%s:%d: %s", d.file, d.line, d.msg);
    int j = cub_motion_skeleton_find(&ch->skel, "RHand");
    assert_int_equal(ch->optional[j], 1);
    assert_int_equal(ch->optional[j - 1], 0);
    free(ch);
    free(text);
}

static void test_skeleton_errors(void **state)
{
    (void)state;
    expect_error(9, "    <joint name=\"LFore\" parent=\"LArmm\" offset=\"150 0 0\"/>",
                 "joint 'LFore': parent 'LArmm' is not defined above it");
    expect_error(8, "    <joint name=\"LArm\" parent=\"LFore\" offset=\"100 0 0\"/>",
                 "parents must come first");
    expect_error(9, "    <joint name=\"LArm\" parent=\"Neck\" offset=\"150 0 0\"/>",
                 "defined twice (first on line 8)");
    expect_error(9, "    <joint name=\"LFore\" parent=\"\" offset=\"150 0 0\"/>",
                 "only the first joint is the root");
    expect_error(3, "    <joint name=\"Hips\" parent=\"Spine\" offset=\"0 300 0\"/>",
                 "needs parent=\"\"");
    expect_error(9, "    <joint name=\"LFore\" parent=\"LArm\" offset=\"150 0\"/>",
                 "is not 3 numbers");
    expect_error(9, "    <joint name=\"LFore\" parent=\"LArm\" offset=\"150 x 0\"/>",
                 "offset=\"150 x 0\" is not 3 numbers");
    expect_error(9, "    <joint name=\"LFore\" parent=\"LArm\" offset=\"150 0 1e9\"/>", "beyond");
    expect_error(9, "    <joint name=\"LFore\" parent=\"LArm\"/>", "missing offset");
    expect_error(9, "    <joint name=\"LFore\" offset=\"1 2 3\"/>", "missing parent");
    expect_error(9, "    <joint parent=\"LArm\" offset=\"1 2 3\"/>", "without a name");
    expect_error(9, "    <joint name=\"LFore\" parent=\"LArm\" offset=\"1 2 3\" end=\"yes\"/>",
                 "end=\"yes\" must be");
    expect_error(9, "    <joint name=\"LFore\" parent=\"LArm\" offset=\"1 2 3\" optional=\"2\"/>",
                 "optional=\"2\" must be");
    expect_error(9, "    <joint name=\"LFore\" parent=\"LArm\" ofset=\"1 2 3\"/>",
                 "unknown attribute 'ofset'");
    expect_error(9, "    <bone name=\"LFore\"/>", "unknown element <bone> in <skeleton>");
    expect_error(8, "    <joint name=\"LArm\" parent=\"Head_end\" offset=\"100 0 0\"/>",
                 "is an end site");
    expect_error(9,
                 "    <joint name=\"LFore_with_a_much_too_long_name_x\" parent=\"LArm\" "
                 "offset=\"1 2 3\"/>",
                 "longer than 31");
}

static void test_features_errors(void **state)
{
    (void)state;
    expect_error(21,
                 "  <features hip_centre=\"Hips\" spine=\"Spine\" shoulder_centre=\"Neck\" "
                 "head=\"Haed\"",
                 "<features>: head 'Haed' is not a joint");
    /* A missing attribute is reported where the element starts. */
    expect_error(22,
                 "            left_shoulder=\"LArm\" left_elbow=\"LFore\" "
                 "left_wrist=\"\"",
                 "missing left_wrist");
    expect_error(24,
                 "            left_hip=\"LUp\" left_knee=\"LLeg\" left_ankle=\"LFoot\" "
                 "left_toe=\"LFoot\"",
                 "unknown attribute 'left_toe'");
    /* spine is optional */
    char *text = good_with(21, "  <features hip_centre=\"Hips\" shoulder_centre=\"Neck\" "
                               "head=\"Head\"");
    cub_character *ch = malloc(sizeof(*ch));
    cub_diag d = {0};
    assert_int_equal(cub_character_parse(text, strlen(text), "toy.xml", ch, &d), CUB_OK);
    assert_int_equal(ch->body.spine, -1);
    free(ch);
    free(text);
}

static void test_body_errors(void **state)
{
    (void)state;
    const char *ell = "    <part joint=\"Spine\" shape=\"ellipsoid\" centre=\"0 20 0\" ";
    char line[300];
    expect_error(27,
                 "    <part joint=\"Spien\" shape=\"ellipsoid\" radii=\"1 1 1\" "
                 "colour=\"#000000\"/>",
                 "part on unknown joint 'Spien'");
    snprintf(line, sizeof(line), "%sradii=\"150 0 140\" colour=\"#9a6434\"/>", ell);
    expect_error(27, line, "radii must be positive, got 0");
    snprintf(line, sizeof(line), "%sradii=\"150 -3 140\" colour=\"#9a6434\"/>", ell);
    expect_error(27, line, "radii must be positive, got -3");
    snprintf(line, sizeof(line), "%sradii=\"1 1 1\" colour=\"#zzz\"/>", ell);
    expect_error(27, line, "bad colour '#zzz'");
    snprintf(line, sizeof(line), "%sradii=\"1 1 1\" colour=\"#12345g\"/>", ell);
    expect_error(27, line, "bad colour");
    snprintf(line, sizeof(line), "%sradii=\"1 1 1\"/>", ell);
    expect_error(27, line, "missing colour");
    snprintf(line, sizeof(line), "%sradii=\"1 1 1\" radius=\"3\" colour=\"#000000\"/>", ell);
    expect_error(27, line, "not radius");
    expect_error(27, "    <part joint=\"Spine\" shape=\"cube\" colour=\"#000000\"/>",
                 "unknown shape 'cube'");
    expect_error(27, "    <part joint=\"Spine\" colour=\"#000000\"/>", "missing shape");
    expect_error(28,
                 "    <part joint=\"LArm\" shape=\"capsule\" radius=\"-5\" colour=\"#000000\"/>",
                 "radius must be positive, got -5");
    expect_error(28,
                 "    <part joint=\"LArm\" shape=\"capsule\" radius=\"5\" end_radius=\"0\" "
                 "colour=\"#000000\"/>",
                 "end_radius must be positive");
    expect_error(28,
                 "    <part joint=\"Head_end\" shape=\"capsule\" radius=\"5\" "
                 "colour=\"#000000\"/>",
                 "this joint has none");
    expect_error(28,
                 "    <part joint=\"LArm\" shape=\"capsule\" radius=\"5\" raduis=\"4\" "
                 "colour=\"#000000\"/>",
                 "unknown attribute 'raduis'");
    expect_error(28, "    <shape joint=\"LArm\"/>", "unknown element <shape> in <body>");
}

static void test_document_errors(void **state)
{
    (void)state;
    expect_error(1, "<character name=\"toy\" version=\"2\">", "unsupported version");
    expect_error(1, "<character version=\"1\">", "needs a name");
    expect_error(20, "  </skeleton><skeleton/>", "a second <skeleton> (the first is on line 2)");
    expect_error(29, "  </body><hat/>", "unknown element <hat> in <character>");
    expect_error(9, "    <joint name=\"LFore\" parent=\"LArm\" offset=\"150 0 0\">", "XML");
    /* No body at all. */
    char *text = good_with(0, NULL);
    char *body = strstr(text, "  <body>");
    strcpy(body, "</character>\n");
    cub_character *ch = malloc(sizeof(*ch));
    cub_diag d = {0};
    assert_int_equal(cub_character_parse(text, strlen(text), "toy.xml", ch, &d), CUB_ERR_FORMAT);
    assert_int_equal(d.line, 1);
    assert_non_null(strstr(d.msg, "has no <body>"));
    const char *other = "<?xml version=\"1.0\"?>\n<characters name=\"toy\"/>\n";
    assert_int_equal(cub_character_parse(other, strlen(other), "o.xml", ch, &d), CUB_ERR_FORMAT);
    assert_int_equal(d.line, 2);
    assert_non_null(strstr(d.msg, "expected <character>, found <characters>"));
    assert_int_equal(cub_character_load("/nonexistent/bear.xml", ch, &d), CUB_ERR_IO);
    assert_int_equal(cub_character_parse(NULL, 5, "x", ch, &d), CUB_ERR_ARG);
    free(ch);
    free(text);
}

static void test_the_bear_loads(void **state)
{
    (void)state;
    const char *src = getenv("CUB_SOURCE_DIR");
    if (!src) skip();
    char path[512];
    snprintf(path, sizeof(path), "%s/assets/bear/bear.xml", src);
    cub_character *bear = malloc(sizeof(*bear));
    cub_diag d = {0};
    cub_err err = cub_character_load(path, bear, &d);
    if (err) fail_msg("%s:%d: %s", d.file, d.line, d.msg);
    assert_string_equal(bear->name, "bear");
    assert_int_equal(bear->skel.joint_count, 24);
    assert_int_equal(bear->part_count, 24);
    assert_int_equal(bear->skel.joints[0].parent, -1);
    assert_int_equal(bear->body.head, cub_motion_skeleton_find(&bear->skel, "Head"));
    assert_int_equal(bear->body.wrist[1], cub_motion_skeleton_find(&bear->skel, "RightHand"));
    assert_int_equal(bear->body.ankle[0], cub_motion_skeleton_find(&bear->skel, "LeftFoot"));

    /* Height: the rest pose with the root at its offset stands on y = 0. */
    static cub_pose rest;
    static cub_vec3 world[CUB_MOTION_MAX_JOINTS];
    cub_motion_pose_rest(&bear->skel, &rest);
    rest.root_mm = bear->skel.joints[0].offset_mm;
    assert_int_equal(cub_motion_forward(&bear->skel, &rest, world, NULL), CUB_OK);
    double lo = 1e9, hi = -1e9;
    for (int i = 0; i < bear->skel.joint_count; i++) {
        double y = world[i].y / 65536.0;
        lo = y < lo ? y : lo;
        hi = y > hi ? y : hi;
    }
    double cog = bear->body.stand_cog_mm / 65536.0;
    printf("character: bear joints=%d parts=%d height_mm=%.1f floor_mm=%.1f stand_cog_mm=%.1f\n",
           bear->skel.joint_count, bear->part_count, hi - lo, lo, cog);
    assert_true(lo > -0.01 && lo < 0.01);
    assert_true(hi - lo > 900 && hi - lo < 1000);
    assert_true(cog > 100 && cog < hi);
    assert_int_equal(bear->body.floor_y_mm, 0);
    free(bear);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_skeleton_errors),       cmocka_unit_test(test_features_errors),
        cmocka_unit_test(test_body_errors),           cmocka_unit_test(test_document_errors),
        cmocka_unit_test(test_the_template_is_valid), cmocka_unit_test(test_the_bear_loads),
        cmocka_unit_test(test_optional_joint),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

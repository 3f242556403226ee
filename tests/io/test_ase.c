/* ASE import and export (cub/ase.h): real clips go BVH -> ASE -> clip with
 * every joint's world position within 0.01 mm of the BVH's, every frame; a
 * hand-made file checks the seed's conventions by hand (relative rotation
 * samples, the TM path for offsets, rest rotations, joint translations);
 * hand-made malformed files are refused at the right line. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/ase.h"

#define ROUND_TRIP_MM 0.01

static const char *build_dir(void)
{
    const char *d = getenv("CUB_BUILD_DIR");
    return d ? d : ".";
}

/* Largest world position difference (mm) of any joint in any frame. */
static double max_world_error(const cub_clip *a, const cub_clip *b)
{
    static cub_pose pa, pb;
    static cub_vec3 wa[CUB_MOTION_MAX_JOINTS], wb[CUB_MOTION_MAX_JOINTS];
    double worst = 0;
    assert_int_equal(a->frame_count, b->frame_count);
    for (int f = 0; f < a->frame_count; f++) {
        assert_int_equal(cub_motion_clip_get_frame(a, f, &pa), CUB_OK);
        assert_int_equal(cub_motion_clip_get_frame(b, f, &pb), CUB_OK);
        cub_motion_forward(a->skel, &pa, wa, NULL);
        cub_motion_forward(b->skel, &pb, wb, NULL);
        for (int j = 0; j < a->skel->joint_count; j++) {
            double dx = (wa[j].x - wb[j].x) / 65536.0, dy = (wa[j].y - wb[j].y) / 65536.0,
                   dz = (wa[j].z - wb[j].z) / 65536.0;
            double e = sqrt(dx * dx + dy * dy + dz * dz);
            worst = e > worst ? e : worst;
        }
    }
    return worst;
}

static void round_trip(const char *path)
{
    static cub_io_motion src, back;
    cub_diag d = {0};
    char out[512];
    if (cub_io_load_bvh(path, NULL, &src, &d)) fail_msg("%s:%d: %s", d.file, d.line, d.msg);
    snprintf(out, sizeof(out), "%s/test_ase_rt.ase", build_dir());
    assert_int_equal(cub_ase_save(out, &src, &d), CUB_OK);
    cub_io_desc mm = {1.0};
    if (cub_ase_load(out, &mm, &back, &d)) fail_msg("%s:%d: %s", d.file, d.line, d.msg);
    assert_int_equal(back.skel.joint_count, src.skel.joint_count);
    for (int j = 0; j < src.skel.joint_count; j++) {
        assert_string_equal(back.skel.joints[j].name, src.skel.joints[j].name);
        assert_int_equal(back.skel.joints[j].parent, src.skel.joints[j].parent);
        assert_int_equal(back.skel.joints[j].is_end_site, src.skel.joints[j].is_end_site);
    }
    int dt = (int)back.clip.frame_ns - (int)src.clip.frame_ns;
    assert_true(dt >= -1 && dt <= 1);
    double e = max_world_error(&src.clip, &back.clip);
    printf("ase: %s: %d joints, %d frames, max joint world position error %.5f mm\n", path,
           src.skel.joint_count, src.clip.frame_count, e);
    assert_true(e <= ROUND_TRIP_MM);
    remove(out);
    cub_io_motion_free(&src);
    cub_io_motion_free(&back);
}

static void test_round_trip_real_clips(void **state)
{
    (void)state;
    const char *src = getenv("CUB_SOURCE_DIR"), *data = getenv("CUB_DATA_DIR");
    char path[512];
    assert_non_null(src);
    snprintf(path, sizeof(path), "%s/assets/clips/hello.bvh", src);
    round_trip(path);
    const char *real[] = {"mocap/cmu/daz43/08_01.bvh", "mocap/animdraw/cmu1/jumping_jacks.bvh",
                          "mocap/bandai/data/dataset-1_byebye_angry_001.bvh"};
    for (size_t i = 0; data && i < sizeof(real) / sizeof(real[0]); i++) {
        snprintf(path, sizeof(path), "%s/%s", data, real[i]);
        FILE *f = fopen(path, "rb");
        if (!f) {
            printf("ase: %s is absent; skipped\n", path);
            continue;
        }
        fclose(f);
        round_trip(path);
    }
}

/* A chain root -> arm -> hand (an end site), 3 frames at 30 fps. The arm's
 * rest: 10 units along x from the root, its rest frame turned 90 degrees
 * about z (TM_ROW only), the root's by TM_QUATERNION (identity). The
 * root's rotation samples: +90 about z, then +90 more relative to frame 1,
 * then 0 (stays at 180). The hand has no tracks: its offset comes from the
 * TM path, (0, 5, 0) in the world rest = (5, 0, 0) in the arm's frame. */
static const char hand_made[] =
    "*3DSMAX_ASCIIEXPORT 200\n"
    "*SCENE {\n *SCENE_FIRSTFRAME 0\n *SCENE_LASTFRAME 2\n *SCENE_FRAMESPEED 30\n"
    " *SCENE_TICKSPERFRAME 160\n *SCENE_BACKGROUND_STATIC 0 0 0\n}\n"
    "*MATERIAL_LIST {\n *MATERIAL_COUNT 0\n}\n"
    "*HELPEROBJECT {\n *NODE_NAME \"root node\"\n *HELPER_CLASS \"Bone\"\n"
    " *NODE_TM {\n  *TM_POS 0 0 0\n  *TM_QUATERNION 0 0 0 1\n }\n"
    " *TM_ANIMATION {\n  *CONTROL_POS_TRACK {\n   *CONTROL_POS_SAMPLE 0 1 2 3\n"
    "   *CONTROL_POS_SAMPLE 160 1 2 3\n   *CONTROL_POS_SAMPLE 320 1 2 4\n  }\n"
    "  *CONTROL_ROT_TRACK {\n   *CONTROL_ROT_SAMPLE 0 0 0 1 1.5707963267948966\n"
    "   *CONTROL_ROT_SAMPLE 160 0 0 1 1.5707963267948966\n"
    "   *CONTROL_ROT_SAMPLE 320 0 0 0 0\n  }\n }\n}\n"
    "*HELPEROBJECT {\n *NODE_NAME \"arm\"\n *NODE_PARENT \"root node\"\n"
    " *NODE_TM {\n  *TM_ROW0 0 1 0\n  *TM_ROW1 -1 0 0\n  *TM_ROW2 0 0 1\n  *TM_POS 10 0 0\n }\n}\n"
    "*HELPEROBJECT {\n *NODE_NAME \"hand\"\n *NODE_PARENT \"arm\"\n *HELPER_CLASS \"Dummy\"\n"
    " *NODE_TM {\n  *TM_POS 10 5 0\n  *TM_QUATERNION 0 0 0.7071067811865476 0.7071067811865476\n"
    " }\n}\n";

static void expect_near(cub_vec3 v, double x, double y, double z)
{
    double e = fabs(v.x / 65536.0 - x) + fabs(v.y / 65536.0 - y) + fabs(v.z / 65536.0 - z);
    if (e > 1e-3)
        fail_msg("(%.4f %.4f %.4f) is not (%g %g %g)", v.x / 65536.0, v.y / 65536.0,
                 v.z / 65536.0, x, y, z);
}

static void test_hand_made_file(void **state)
{
    (void)state;
    static cub_io_motion m;
    static cub_pose p;
    cub_vec3 w[CUB_MOTION_MAX_JOINTS];
    cub_diag d = {0};
    cub_io_desc mm = {1.0};
    if (cub_ase_parse(hand_made, strlen(hand_made), "hand.ase", &mm, &m, &d))
        fail_msg("%s:%d: %s", d.file, d.line, d.msg);
    assert_int_equal(m.skel.joint_count, 3);
    assert_int_equal(m.clip.frame_count, 3);
    assert_int_equal(m.clip.frame_ns, 33333333);
    assert_true(m.skel.joints[2].is_end_site);
    expect_near(m.skel.joints[1].offset_mm, 10, 0, 0);
    expect_near(m.skel.joints[2].offset_mm, 5, 0, 0);
    /* frame 0: root +90 about z at (1 2 3); the arm keeps its rest turn. */
    cub_motion_clip_get_frame(&m.clip, 0, &p);
    cub_motion_forward(&m.skel, &p, w, NULL);
    expect_near(w[0], 1, 2, 3);
    expect_near(w[1], 1, 12, 3);
    expect_near(w[2], -4, 12, 3);
    /* frame 1: root at 180 (the second sample is relative to the first). */
    cub_motion_clip_get_frame(&m.clip, 1, &p);
    cub_motion_forward(&m.skel, &p, w, NULL);
    expect_near(w[1], -9, 2, 3);
    expect_near(w[2], -9, -3, 3);
    /* frame 2: the identity sample keeps 180; the root moved up. */
    cub_motion_clip_get_frame(&m.clip, 2, &p);
    cub_motion_forward(&m.skel, &p, w, NULL);
    expect_near(w[2], -9, -3, 4);
    cub_io_motion_free(&m);
}

typedef struct bad_case {
    const char *text;
    int line;
    const char *words;
} bad_case;

#define SCENE "*3DSMAX_ASCIIEXPORT 200\n*SCENE {\n*SCENE_LASTFRAME 1\n*SCENE_FRAMESPEED 30\n}\n"
#define ROOT_OPEN "*HELPEROBJECT {\n*NODE_NAME \"r\"\n*NODE_TM {\n*TM_POS 0 0 0\n}\n"

static const bad_case bad_cases[] = {
    {"", 1, "no *3DSMAX_ASCIIEXPORT"},
    {"*SCENE {\n}\n", 1, "no *3DSMAX_ASCIIEXPORT"},
    {"*3DSMAX_ASCIIEXPORT 200\n" ROOT_OPEN "}\n", 2, "before the *SCENE"},
    {"*3DSMAX_ASCIIEXPORT 200\n*SCENE {\n*SCENE_LASTFRAME 1\n}\n", 2, "*SCENE needs"},
    {"*3DSMAX_ASCIIEXPORT 200\n*SCENE {\n*SCENE_LASTFRAME x\n*SCENE_FRAMESPEED 30\n}\n", 3,
     "bad number"},
    {"*3DSMAX_ASCIIEXPORT 200\n*SCENE {\n*SCENE_LASTFRAME 1\n*SCENE_FRAMESPEED 0\n}\n", 4,
     "not in 0.5..10000"},
    {SCENE, 6, "no *HELPEROBJECT"},
    {SCENE "*HELPEROBJECT {\n*NODE_TM {\n*TM_POS 0 0 0\n}\n}\n", 6, "no *NODE_NAME"},
    {SCENE "*HELPEROBJECT {\n*NODE_NAME r\n}\n", 7, "expected a quoted name"},
    {SCENE "*HELPEROBJECT {\n*NODE_NAME \"r\n}\n", 7, "closing quote"},
    {SCENE "*HELPEROBJECT {\n*NODE_NAME \"r\"\n}\n", 6, "no *NODE_TM"},
    {SCENE ROOT_OPEN, 6, "not closed"},
    {SCENE ROOT_OPEN "}\n*HELPEROBJECT {\n*NODE_NAME \"a\"\n*NODE_PARENT \"zz\"\n"
     "*NODE_TM {\n*TM_POS 0 0 0\n}\n}\n",
     12, "parent 'zz' is not a node before it"},
    {SCENE ROOT_OPEN "}\n" ROOT_OPEN "}\n", 12, "a second node named 'r'"},
    {SCENE ROOT_OPEN "}\n*HELPEROBJECT {\n*NODE_NAME \"b\"\n*NODE_TM {\n*TM_POS 0 0 0\n}\n}\n",
     12, "only the first node is the root"},
    {SCENE ROOT_OPEN "*TM_ANIMATION {\n*CONTROL_ROT_TRACK {\n*CONTROL_ROT_SAMPLE 0 0 0 1 0.5\n}\n}\n}\n",
     12, "the track has 1 samples; the scene has 2 frames"},
    {SCENE ROOT_OPEN "*TM_ANIMATION {\n*CONTROL_ROT_TRACK {\n*CONTROL_ROT_SAMPLE 0 0 0 1 0.5\n"
     "*CONTROL_ROT_SAMPLE 100 0 0 1 0.5\n}\n}\n}\n",
     14, "sample 1 is at tick 100; frame 1 is at tick 160"},
    {SCENE ROOT_OPEN "*TM_ANIMATION {\n*CONTROL_ROT_TRACK {\n*CONTROL_ROT_SAMPLE 0 0 0 2 0.5\n}\n}\n}\n",
     13, "is not a unit vector"},
    {SCENE ROOT_OPEN "*TM_ANIMATION {\n*CONTROL_POS_TRACK {\n*CONTROL_POS_SAMPLE 0 1 2\n}\n}\n}\n",
     13, "needs 4 numbers, found 3"},
    {SCENE ROOT_OPEN "*TM_ANIMATION {\n*CONTROL_ROT_TRACK {\n*CONTROL_TCB_ROT_KEY 0 0 0 1 0.5\n}\n}\n}\n",
     13, "sampled tracks"},
    {SCENE ROOT_OPEN "*TM_ANIMATION {\n*CONTROL_POS_TRACK {\n*CONTROL_POS_SAMPLE 0 1 2 nan\n"
     "*CONTROL_POS_SAMPLE 160 1 2 3\n}\n}\n}\n",
     13, "bad number"},
    {SCENE ROOT_OPEN "*TM_ANIMATION {\n*CONTROL_POS_TRACK {\n*CONTROL_POS_SAMPLE 0 1 2 1e9\n"
     "*CONTROL_POS_SAMPLE 160 1 2 3\n}\n}\n}\n",
     12, "beyond"},
    {SCENE "*HELPEROBJECT {\n*NODE_NAME \"r\"\n*NODE_TM {\n*TM_QUATERNION 0 0 0 3\n}\n}\n", 9,
     "has length 3"},
    /* a second scene would resize the frames after the tracks were read */
    {SCENE ROOT_OPEN "*TM_ANIMATION {\n*CONTROL_ROT_TRACK {\n*CONTROL_ROT_SAMPLE 0 0 0 1 0.5\n"
     "*CONTROL_ROT_SAMPLE 160 0 0 1 0.5\n}\n}\n}\n*SCENE {\n*SCENE_LASTFRAME 5\n"
     "*SCENE_FRAMESPEED 30\n}\n",
     18, "a second *SCENE block (the first is at line 2)"},
    {SCENE "stray\n", 6, "expected a *KEYWORD"},
    {SCENE "*HELPEROBJECT\n", 6, "expected '{'"},
};

static void test_malformed_files(void **state)
{
    (void)state;
    char msg[600];
    for (size_t i = 0; i < sizeof(bad_cases) / sizeof(bad_cases[0]); i++) {
        const bad_case *c = &bad_cases[i];
        static cub_io_motion m;
        cub_diag d = {0};
        size_t n = strlen(c->text);
        char *copy = malloc(n ? n : 1); /* exactly n bytes: ASan sees an overread */
        memcpy(copy, c->text, n);
        cub_err err = cub_ase_parse(copy, n, "bad.ase", NULL, &m, &d);
        free(copy);
        printf("ase: case %zu: %s\n", i, cub_diag_str(&d, msg, sizeof(msg)));
        assert_int_equal(err, CUB_ERR_FORMAT);
        assert_string_equal(d.file, "bad.ase");
        if (d.line != c->line || !strstr(d.msg, c->words))
            fail_msg("case %zu: got line %d '%s', want line %d '%s'", i, d.line, d.msg, c->line,
                     c->words);
        assert_int_equal(m.clip.frame_count, 0);
    }
    static cub_io_motion m;
    cub_diag d = {0};
    assert_int_equal(cub_ase_load("/nonexistent/x.ase", NULL, &m, &d), CUB_ERR_IO);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hand_made_file),
        cmocka_unit_test(test_malformed_files),
        cmocka_unit_test(test_round_trip_real_clips),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* The winged bear in the box (app/cubdance/wings.c, issue 22): the wings
 * show only around bird_flying, unfold and fold over WINGS_OPEN_S, flap as
 * the child clip says once open, and leave the bear's joints as given. On
 * the shipped assets (assets/bear/bear_winged.xml, bird_flying.wings.bvh). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/pack.h"
#include "wings.h"

#define TICK_US 33333

static cub_library g_lib;
static cub_wings g_w;
static float g_xyz[3 * CUB_MOTION_MAX_JOINTS], g_rot[4 * CUB_MOTION_MAX_JOINTS];
static char g_bear[1024];

static int setup(void **state)
{
    (void)state;
    char pack[1024];
    const char *src = getenv("CUB_SOURCE_DIR");
    snprintf(pack, sizeof pack, "%s/assets/clips/bear.cubclips", src ? src : ".");
    snprintf(g_bear, sizeof g_bear, "%s/assets/bear/bear.xml", src ? src : ".");
    if (cub_pack_read(pack, &g_lib, NULL)) return -1;
    /* the bear at rest, every joint unturned: what the wings hang on */
    for (int j = 0; j < g_lib.skel.joint_count; j++) {
        g_xyz[3 * j + 0] = 10.0f * j, g_xyz[3 * j + 1] = 500, g_xyz[3 * j + 2] = 0;
        g_rot[4 * j + 3] = 1;
    }
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    cub_wings_close(&g_w);
    cub_library_free(&g_lib);
    return 0;
}

static int open_wings(void)
{
    char err[256] = "";
    int clip = cub_library_find(&g_lib, "bird_flying");
    assert_true(clip >= 0);
    if (g_w.loaded) cub_wings_close(&g_w);
    assert_int_equal(cub_wings_open(&g_w, g_bear, "bird_flying", &g_lib.skel, clip, err,
                                    sizeof err), 0);
    assert_true(g_w.loaded);
    return clip;
}

/* Ticks of clip from t_us, n of them; the last tick's result. */
static int ticks(int clip, int64_t *t_us, int n)
{
    int shown = 0;
    for (int i = 0; i < n; i++, *t_us += TICK_US)
        shown = cub_wings_pose(&g_w, clip, (int64_t)i << 16, *t_us, g_xyz, g_rot);
    return shown;
}

static void test_wings_show_only_around_bird_flying(void **state)
{
    (void)state;
    int bird = open_wings(), other = bird == 0 ? 1 : 0;
    int64_t t = 1000000;
    assert_int_equal(ticks(other, &t, 30), 0); /* another clip: the bear as it is */
    assert_int_equal(ticks(bird, &t, 2), 1);    /* unfolding from the first frame after */
    assert_true(g_w.open > 0 && g_w.open < 0.2f);
    assert_int_equal(ticks(bird, &t, 12), 1);
    assert_true(g_w.open == 1.0f); /* open within 0.4 s */
    assert_int_equal(g_w.skel.joint_count, g_lib.skel.joint_count + g_w.extra);
    assert_int_equal(ticks(other, &t, 6), 1); /* folding, still shown */
    assert_true(g_w.open < 1.0f && g_w.open > 0);
    assert_int_equal(ticks(other, &t, 8), 0); /* folded away */
}

/* The wings belong to the move: while the coach is on bird_flying's move
 * they stay out through another clip (a correction's head shake), beating
 * on with the clock; they fold once the move is another. */
static void test_wings_stay_through_a_correction_of_the_move(void **state)
{
    (void)state;
    int bird = open_wings(), other = bird == 0 ? 1 : 0;
    int64_t t = 1000000;
    cub_wings_move(&g_w, bird);
    assert_int_equal(ticks(bird, &t, 20), 1);
    assert_true(g_w.open == 1.0f);
    double frame = g_w.frame;
    assert_int_equal(ticks(other, &t, 30), 1); /* the correcting clip: still open */
    assert_true(g_w.open == 1.0f);
    assert_true(fabs(g_w.frame - (frame + 30)) < 0.01); /* 30 ticks of 1/30 s beat on */
    cub_wings_move(&g_w, other);
    assert_int_equal(ticks(other, &t, 6), 1); /* the move is another: folding */
    assert_true(g_w.open < 1.0f && g_w.open > 0);
    assert_int_equal(ticks(other, &t, 8), 0);
    cub_wings_move(&g_w, -1);
}

/* Open, the wings turn as the child clip's; the bear's joints are copied. */
static void test_open_wings_flap_as_the_child_clip(void **state)
{
    (void)state;
    int bird = open_wings();
    int64_t t = 1000000;
    ticks(bird, &t, 20);
    int n = g_lib.skel.joint_count, f = 19;
    assert_memory_equal(g_w.xyz, g_xyz, 3 * (size_t)n * sizeof(float));
    static cub_pose pose;
    cub_motion_sample(&g_w.motion.clip, (int64_t)f * 1000000 / 30, CUB_MOTION_LOOP, &pose);
    for (int e = 0; e < g_w.extra; e++) {
        int j = n + e, p = g_w.skel.joints[j].parent;
        if (p >= n) continue; /* the wing roots hang on unturned bear joints */
        cub_quat q = pose.rot[g_w.src[e]];
        const float one = (float)CUB_QUAT_ONE, *r = g_w.rot + 4 * j;
        float dot = r[0] * q.x / one + r[1] * q.y / one + r[2] * q.z / one + r[3] * q.w / one;
        assert_true(fabsf(dot) > 0.9999f);
    }
}

static void test_no_wings_file_means_no_wings(void **state)
{
    (void)state;
    char err[256] = "";
    cub_wings w;
    assert_int_equal(cub_wings_open(&w, "/nonexistent/bear.xml", "bird_flying", &g_lib.skel, 0,
                                    err, sizeof err), 0);
    assert_false(w.loaded);
    assert_int_equal(cub_wings_pose(&w, 0, 0, 1000, g_xyz, g_rot), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_wings_show_only_around_bird_flying),
        cmocka_unit_test(test_wings_stay_through_a_correction_of_the_move),
        cmocka_unit_test(test_open_wings_flap_as_the_child_clip),
        cmocka_unit_test(test_no_wings_file_means_no_wings),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}

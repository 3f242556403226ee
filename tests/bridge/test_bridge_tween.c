/* The seed's tween clip (cub/bridge.h, "the tween clip") built from the
 * shipped library's bridge frames: its keys are bridge frames, shown
 * exactly; every bridge frame is within the cover distance of a key; the
 * loop (its wrap included) never moves a joint faster than its speed
 * bound; adding it keeps every library clip and plan as it was; and the
 * planner routes through it where no direct switch serves. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "cub/coachlib.h"

static cub_coachlib g_plain, g_tw;

static int setup(void **state)
{
    const char *src = getenv("CUB_SOURCE_DIR");
    char assets[1024], lib[1200], buf[600];
    snprintf(assets, sizeof assets, "%s/assets", src ? src : ".");
    snprintf(lib, sizeof lib, "%s/clips/bear.cubclips", assets);
    *state = NULL;
    if (access(lib, R_OK) != 0) return 0; /* the tests skip */
    cub_diag d = {0};
    if (cub_coachlib_load_assets(assets, &g_plain, &d) ||
        cub_coachlib_load_assets(assets, &g_tw, &d) || cub_coachlib_add_tween(&g_tw, NULL, &d)) {
        fprintf(stderr, "tween: %s\n", cub_diag_str(&d, buf, sizeof buf));
        return -1;
    }
    *state = &g_tw;
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    cub_coachlib_free(&g_plain);
    cub_coachlib_free(&g_tw);
    return 0;
}

#define NEED_LIBRARY(state)                                                                        \
    do {                                                                                           \
        if (!*(state)) skip();                                                                     \
    } while (0)

static void test_tween_refuses_bad_calls(void **state)
{
    NEED_LIBRARY(state);
    cub_bridge_tween tw;
    size_t ws = cub_bridge_tween_work_size(&g_plain.table);
    void *work = malloc(ws);
    assert_int_equal(cub_bridge_tween_plan(NULL, NULL, &tw, work, ws), CUB_ERR_ARG);
    assert_int_equal(cub_bridge_tween_plan(&g_plain.table, NULL, &tw, work, ws - 64),
                     CUB_ERR_NOMEM);
    /* a table that has a tween already */
    assert_int_equal(cub_bridge_tween_plan(&g_tw.table, NULL, &tw, work, ws), CUB_ERR_ARG);
    assert_int_equal(cub_coachlib_add_tween(&g_tw, NULL, NULL), CUB_ERR_ARG);
    /* the tween's clip is no bridge-frame-only clip of two passes elsewhere */
    assert_int_equal(cub_bridge_table_set_tween(&g_tw.table, 0, 10), CUB_ERR_ARG);
    free(work);
}

static void test_tween_keys_are_bridge_frames_shown_exactly(void **state)
{
    NEED_LIBRARY(state);
    const cub_bridge_tween *tw = &g_tw.tween;
    static cub_pose key, shown;
    assert_true(tw->key_count > 1);
    assert_int_equal(g_tw.tween_clip.frame_count, tw->frame_count);
    assert_int_equal(g_tw.table.tween_clip, g_tw.lib.clip_count);
    assert_int_equal(g_tw.table.clips[g_tw.tween_index].clip.frame_count, 2 * tw->frame_count);
    for (int k = 0; k < tw->key_count; k++) {
        assert_true(cub_bridge_is_bridge(&g_plain.table, tw->key_clip[k], tw->key_frame[k]));
        cub_motion_clip_get_frame(&g_tw.lib.clips[tw->key_clip[k]].clip, tw->key_frame[k], &key);
        cub_motion_clip_get_frame(&g_tw.tween_clip, tw->key_at[k], &shown);
        assert_int_equal(shown.root_mm.y, key.root_mm.y);
        assert_int_equal(shown.root_mm.x, 0);
        assert_memory_equal(shown.rot, key.rot, sizeof(cub_quat) * (size_t)key.joint_count);
    }
}

static void test_every_bridge_frame_is_near_a_key(void **state)
{
    NEED_LIBRARY(state);
    const cub_bridge_table *t = &g_plain.table;
    const cub_bridge_tween *tw = &g_tw.tween;
    cub_q16 cover = t->desc.fuzzy.threshold / 2, worst = 0;
    for (int c = 0; c < t->desc.clip_count; c++)
        for (int i = 0; i < t->clips[c].bridge_count; i++) {
            int f = t->bridges[t->clips[c].first_bridge + i];
            cub_q16 best = CUB_Q16_MAX;
            for (int k = 0; k < tw->key_count; k++) {
                const cub_fuzzy_frame *kf =
                    &t->fuzzy[t->clips[tw->key_clip[k]].first_frame + tw->key_frame[k]];
                cub_q16 d =
                    cub_fuzzy_distance(&t->fuzzy[t->clips[c].first_frame + f], kf, &t->desc.fuzzy);
                if (d < best) best = d;
            }
            assert_true(best < cover);
            if (best > worst) worst = best;
        }
    /* FNV-1a of the clip's rotations and roots: the same on every CPU
     * (compare the x86-64 and aarch64 runs' lines). */
    const cub_clip *clip = &g_tw.tween_clip;
    uint64_t h = 1469598103934665603ull;
    const unsigned char *bytes[2] = {(const unsigned char *)clip->rot,
                                     (const unsigned char *)clip->root_mm};
    size_t sizes[2] = {sizeof(cub_quat) * (size_t)clip->frame_count *
                           (size_t)g_tw.lib.skel.joint_count,
                       sizeof(cub_vec3) * (size_t)clip->frame_count};
    for (int b = 0; b < 2; b++)
        for (size_t i = 0; i < sizes[b]; i++)
            h = (h ^ bytes[b][i]) * 1099511628211ull;
    printf("tween: %d keys, %d frames a loop; every bridge frame within d=%.3f of a key; "
           "frames' fnv1a %016llx\n",
           tw->key_count, tw->frame_count, worst / 65536.0, (unsigned long long)h);
}

/* The largest joint move between two poses, Q16 mm. */
static int64_t fastest_move(const cub_skeleton *sk, const cub_pose *a, const cub_pose *b)
{
    static cub_vec3 wa[CUB_MOTION_MAX_JOINTS], wb[CUB_MOTION_MAX_JOINTS];
    cub_motion_forward(sk, a, wa, NULL);
    cub_motion_forward(sk, b, wb, NULL);
    int64_t worst = 0;
    for (int j = 0; j < sk->joint_count; j++) {
        int64_t d = cub_fx_vec3_length(cub_fx_vec3_sub(wa[j], wb[j]));
        if (d > worst) worst = d;
    }
    return worst;
}

static void test_loop_stays_within_its_speed(void **state)
{
    NEED_LIBRARY(state);
    static cub_pose a, b;
    const cub_clip *clip = &g_tw.tween_clip;
    int64_t worst = 0;
    for (int f = 0; f < clip->frame_count; f++) {
        cub_motion_clip_get_frame(clip, f, &a);
        cub_motion_clip_get_frame(clip, (f + 1) % clip->frame_count, &b);
        int64_t m = fastest_move(&g_tw.lib.skel, &a, &b);
        if (m > worst) worst = m;
    }
    printf("tween: fastest joint %.1f mm/frame (bound %d)\n", worst / 65536.0,
           CUB_BRIDGE_TWEEN_SPEED_MM >> 16);
    /* The leg lengths come from an upper bound of the path (a leg at the
     * longest allowed length is cut short of it): what must hold is the
     * motion's speed, up to rounding (1 mm). */
    assert_true(worst <= CUB_BRIDGE_TWEEN_SPEED_MM + CUB_Q16_ONE);
}

static void test_adding_the_tween_keeps_the_library_plans(void **state)
{
    NEED_LIBRARY(state);
    size_t ws = cub_bridge_plan_work_size(&g_tw.table);
    void *work = malloc(ws);
    int n = g_plain.lib.clip_count, routes = 0;
    for (int a = 0; a < n; a++)
        for (int b = 0; b < n; b++) {
            cub_bridge_query q = {
                .from_clip = a, .pos_q16 = 7 << 16, .from_loops = 1, .to_clip = b};
            cub_bridge_plan p0, p1, p2;
            cub_err e0 = cub_bridge_plan_switch(&g_plain.table, &q, &p0, work, ws);
            cub_err e1 = cub_bridge_plan_switch(&g_tw.table, &q, &p1, work, ws);
            assert_int_equal(e0, e1);
            assert_memory_equal(&p0, &p1, sizeof p0); /* chains never pass the tween */
            q.via_tween = 1;
            cub_err e2 = cub_bridge_plan_switch(&g_tw.table, &q, &p2, work, ws);
            if (e0 || p0.step[0].via == CUB_BRIDGE_DIRECT) {
                if (!e0) assert_memory_equal(&p0, &p2, sizeof p0); /* direct: the same */
                continue;
            }
            if (e2) continue;
            routes++;
            const int tc = g_tw.table.tween_clip, pass = g_tw.table.tween_pass;
            assert_int_equal(p2.step_count, 2);
            assert_int_equal(p2.step[0].from_clip, a);
            assert_int_equal(p2.step[0].to_clip, tc);
            assert_true(p2.step[0].to_frame < pass);
            assert_int_equal(p2.step[1].from_clip, tc);
            assert_int_equal(p2.step[1].to_clip, b);
            assert_true(p2.step[1].from_frame > p2.step[0].to_frame);
            assert_true(p2.step[1].from_frame - p2.step[0].to_frame <= pass);
            assert_true(cub_bridge_is_bridge(&g_tw.table, b, p2.step[1].to_frame));
            assert_true(p2.step[0].d < g_tw.table.desc.fuzzy.threshold);
            assert_true(p2.step[1].d < g_tw.table.desc.fuzzy.threshold);
        }
    printf("tween: %d chains replaced by routes through the tween\n", routes);
    assert_true(routes > 0);
    free(work);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_tween_refuses_bad_calls),
        cmocka_unit_test(test_tween_keys_are_bridge_frames_shown_exactly),
        cmocka_unit_test(test_every_bridge_frame_is_near_a_key),
        cmocka_unit_test(test_loop_stays_within_its_speed),
        cmocka_unit_test(test_adding_the_tween_keeps_the_library_plans),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}

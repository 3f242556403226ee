/* Joins without sliding feet (cub/join.h). First what bad input gets, then
 * Kovar's distance (zero for a turned and moved copy, the closed form
 * against a brute-force search over θ), contacts and support masks, and a
 * join of two synthetic standing clips: the foot that stays planted does
 * not move, the other steps; the shipped library's pairs last. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/join.h"
#include "cub/pack.h"

#define PI 3.14159265358979323846

/* ---- a small body ----------------------------------------------------------- */

static cub_skeleton skel;

static int add(const char *name, const char *parent, double x, double y, double z)
{
    int idx = -1;
    int p = parent ? cub_motion_skeleton_find(&skel, parent) : -1;
    cub_vec3 off = cub_dv3_to_fx(cub_dv3_make(x, y, z));
    assert_int_equal(cub_motion_skeleton_add(&skel, name, p, off, &idx), CUB_OK);
    return idx;
}

static void make_body(void)
{
    cub_motion_skeleton_reset(&skel);
    add("Hips", NULL, 0, 0, 0);
    add("Spine", "Hips", 0, 150, 0);
    add("Head", "Spine", 0, 150, 30);
    for (int s = 0; s < 2; s++) {
        const char *side = s ? "Right" : "Left";
        double x = s ? -1 : 1;
        char n[6][32];
        snprintf(n[0], 32, "%sArm", side), snprintf(n[1], 32, "%sHand", side);
        snprintf(n[2], 32, "%sUpLeg", side), snprintf(n[3], 32, "%sLeg", side);
        snprintf(n[4], 32, "%sFoot", side), snprintf(n[5], 32, "%sToe_end", side);
        add(n[0], "Spine", 150 * x, 100, 0);
        add(n[1], n[0], 0, -200, 20);
        add(n[2], "Hips", 90 * x, 0, 0);
        add(n[3], n[2], 0, -220, 0);
        add(n[4], n[3], 0, -220, 0);
        add(n[5], n[4], 0, -40, 80);
    }
}

/* A standing clip: knees bent, the right thigh out by abduct_deg, hips at
 * height hips_mm, frames of it. */
static void *stand_clip(cub_clip *clip, int frames, double abduct_deg)
{
    size_t size = cub_motion_clip_mem_size(skel.joint_count, frames, 0);
    void *mem = malloc(size);
    assert_non_null(mem);
    assert_int_equal(cub_motion_clip_init(clip, &skel, frames, 33333333, 0, mem, size), CUB_OK);
    cub_dv3 xaxis = cub_dv3_make(1, 0, 0), zaxis = cub_dv3_make(0, 0, 1);
    for (int f = 0; f < frames; f++) {
        clip->root_mm[f] = cub_dv3_to_fx(cub_dv3_make(0, 430, 0));
        cub_quat *r = clip->rot + (size_t)f * skel.joint_count;
        for (int s = 0; s < 2; s++) {
            const char *side = s ? "Right" : "Left";
            char up[32], leg[32], foot[32];
            snprintf(up, 32, "%sUpLeg", side), snprintf(leg, 32, "%sLeg", side);
            snprintf(foot, 32, "%sFoot", side);
            cub_dq bend = cub_dq_axis_angle(xaxis, -20 * PI / 180);
            if (s) bend = cub_dq_mul(cub_dq_axis_angle(zaxis, -abduct_deg * PI / 180), bend);
            r[cub_motion_skeleton_find(&skel, up)] = cub_dq_to_fx(bend);
            r[cub_motion_skeleton_find(&skel, leg)] =
                cub_dq_to_fx(cub_dq_axis_angle(xaxis, 40 * PI / 180));
            r[cub_motion_skeleton_find(&skel, foot)] =
                cub_dq_to_fx(cub_dq_axis_angle(xaxis, -20 * PI / 180));
        }
    }
    return mem;
}

static cub_dv3 world_joint(const cub_clip *clip, int f, int j)
{
    static cub_pose pose;
    cub_vec3 w[CUB_MOTION_MAX_JOINTS];
    assert_int_equal(cub_motion_clip_get_frame(clip, f, &pose), CUB_OK);
    assert_int_equal(cub_motion_forward(clip->skel, &pose, w, NULL), CUB_OK);
    return cub_dv3_from_fx(w[j]);
}

/* ---- bad input ----------------------------------------------------------- */

static void test_body_without_legs_is_refused_by_name(void **state)
{
    (void)state;
    cub_motion_skeleton_reset(&skel);
    add("Hips", NULL, 0, 0, 0);
    add("LeftUpLeg", "Hips", 90, 0, 0);
    cub_join_body body;
    cub_diag d = {0};
    char msg[300];
    assert_int_equal(cub_join_body_find(&skel, &body, &d), CUB_ERR_FORMAT);
    cub_diag_str(&d, msg, sizeof msg);
    printf("join: legless skeleton -> %s\n", msg);
    assert_non_null(strstr(msg, "no joint LeftLeg"));
}

static void test_db_refuses_another_skeleton_and_short_clips(void **state)
{
    (void)state;
    make_body();
    cub_join_db db;
    assert_int_equal(cub_join_db_init(&db, &skel, NULL, NULL), CUB_OK);
    cub_clip shortc;
    void *mem = stand_clip(&shortc, 4, 0); /* fewer than two 5-frame windows */
    assert_int_equal(cub_join_db_add(&db, "short", &shortc, NULL), CUB_ERR_ARG);
    static cub_skeleton other;
    other = skel;
    snprintf(other.joints[1].name, CUB_MOTION_NAME_LEN, "Torso");
    cub_clip longc;
    void *mem2 = stand_clip(&longc, 20, 0);
    longc.skel = &other;
    assert_int_equal(cub_join_db_add(&db, "other", &longc, NULL), CUB_ERR_ARG);
    assert_int_equal(db.count, 0);
    cub_join_db_free(&db);
    free(mem), free(mem2);
}

/* ---- Kovar's distance ---------------------------------------------------- */

static void cloud(cub_dv3 *p, int n, unsigned seed)
{
    for (int i = 0; i < n; i++) {
        seed = seed * 1103515245u + 12345u;
        double x = (double)(seed >> 8 & 0xFFFF) / 65536.0 * 800 - 400;
        seed = seed * 1103515245u + 12345u;
        double y = (double)(seed >> 8 & 0xFFFF) / 65536.0 * 1000;
        seed = seed * 1103515245u + 12345u;
        double z = (double)(seed >> 8 & 0xFFFF) / 65536.0 * 600 - 300;
        p[i] = cub_dv3_make(x, y, z);
    }
}

static void test_kovar_is_zero_for_a_turned_moved_copy(void **state)
{
    (void)state;
    enum { N = 60 };
    cub_dv3 p[N], q[N];
    cloud(q, N, 7);
    double angles[] = {0.3, -2.5, 3.0, 1.5707};
    for (int k = 0; k < 4; k++) {
        cub_join_align t = {angles[k], 350, -120, 0};
        for (int i = 0; i < N; i++)
            p[i] = cub_join_apply(&t, q[i]);
        cub_join_align got = cub_join_kovar(p, q, NULL, N);
        assert_true(got.d_mm2 < 1e-12);
        assert_true(fabs(remainder(got.theta_rad - angles[k], 2 * PI)) < 1e-9);
        assert_true(fabs(got.x0_mm - 350) < 1e-6 && fabs(got.z0_mm + 120) < 1e-6);
    }
}

/* Brute force: every θ on a 0.01° grid, the translation that brings the
 * weighted means together for it (the optimum for a fixed θ). */
static double brute_force(const cub_dv3 *p, const cub_dv3 *q, const double *w, int n, double *theta)
{
    double best = INFINITY;
    for (int k = 0; k < 36000; k++) {
        cub_join_align t = {(k / 100.0 - 180) * PI / 180, 0, 0, 0};
        double ws = 0, dx = 0, dz = 0;
        for (int i = 0; i < n; i++) {
            cub_dv3 r = cub_join_apply(&t, q[i]);
            double wi = w ? w[i] : 1;
            ws += wi, dx += wi * (p[i].x - r.x), dz += wi * (p[i].z - r.z);
        }
        t.x0_mm = dx / ws, t.z0_mm = dz / ws;
        double c = cub_join_kovar_cost(p, q, w, n, &t);
        if (c < best) best = c, *theta = t.theta_rad;
    }
    return best;
}

static void test_kovar_closed_form_matches_brute_force(void **state)
{
    (void)state;
    enum { N = 40 };
    cub_dv3 p[N], q[N];
    double w[N];
    for (int trial = 0; trial < 4; trial++) {
        cloud(p, N, 11u + (unsigned)trial);
        cloud(q, N, 101u + (unsigned)trial); /* unrelated clouds: a real minimum, not zero */
        for (int i = 0; i < N; i++)
            w[i] = 0.2 + (i % 5);
        const double *ws = trial % 2 ? w : NULL;
        cub_join_align t = cub_join_kovar(p, q, ws, N);
        double theta = 0, brute = brute_force(p, q, ws, N, &theta);
        printf("join: kovar closed form D=%.3f theta=%.4f, brute force D=%.3f theta=%.4f\n",
               t.d_mm2, t.theta_rad, brute, theta);
        assert_true(t.d_mm2 <= brute + 1e-6);
        assert_true(t.d_mm2 >= brute - 1e-3 * brute); /* the grid is within 0.005 deg */
        assert_true(fabs(remainder(t.theta_rad - theta, 2 * PI)) < 0.001);
    }
}

/* ---- contacts and supports ---------------------------------------------- */

static void test_contacts_are_low_slow_runs(void **state)
{
    (void)state;
    enum { F = 20 };
    cub_dv3 p[F];
    for (int f = 0; f < F; f++)
        p[f] = cub_dv3_make(0, 100, 0);
    for (int f = 2; f < 8; f++) /* planted */
        p[f] = cub_dv3_make(5, 10, 0);
    for (int f = 10; f < 12; f++) /* low for 2 frames only: passing */
        p[f] = cub_dv3_make(5, 10, 0);
    for (int f = 14; f < 20; f++) /* low but sliding fast (30 mm a frame = 900 mm/s) */
        p[f] = cub_dv3_make(30.0 * f, 5, 0);
    unsigned char ct[F];
    cub_join_track t = {p, 1, 1.0, F, 1.0 / 30};
    cub_join_contacts(&t, NULL, 0, ct);
    for (int f = 0; f < F; f++)
        assert_int_equal(ct[f], f >= 3 && f <= 6); /* the run's ends move in and out */
    assert_true(fabs(cub_join_track_lowest(&t) - 5) < 1e-12);
}

static void test_support_names_read_as_the_seed(void **state)
{
    (void)state;
    char b[64];
    assert_string_equal(cub_join_support_name(0, b, sizeof b), "air");
    assert_string_equal(cub_join_support_name(1u << CUB_JOIN_LFOOT | 1u << CUB_JOIN_RFOOT, b, 64),
                        "LF+RF");
    assert_string_equal(
        cub_join_support_name(1u << CUB_JOIN_HIP | 1u << CUB_JOIN_LFOOT | 1u << CUB_JOIN_RFOOT, b,
                              64),
        "HIP+LF+RF");
    assert_string_equal(cub_join_support_name(1u << CUB_JOIN_LHAND | 1u << CUB_JOIN_RKNEE, b, 64),
                        "LH+RK");
    assert_string_equal(cub_join_support_name(0x7F, b, 6), "HIP+L"); /* cut, terminated */
}

static void test_standing_clip_stands_on_two_feet(void **state)
{
    (void)state;
    make_body();
    cub_join_db db;
    cub_clip a;
    void *mem = stand_clip(&a, 30, 0);
    assert_int_equal(cub_join_db_init(&db, &skel, NULL, NULL), CUB_OK);
    assert_int_equal(cub_join_db_add(&db, "a", &a, NULL), CUB_OK);
    for (int f = 0; f < 30; f++)
        assert_int_equal(db.clips[0].support[f], 1u << CUB_JOIN_LFOOT | 1u << CUB_JOIN_RFOOT);
    cub_join_segment seg[4];
    assert_int_equal(cub_join_segments(&db, 0, 3, seg, 4), 1);
    assert_int_equal(seg[0].last, 29);
    cub_join_db_free(&db);
    free(mem);
}

/* ---- a join -------------------------------------------------------------- */

static void test_planted_foot_does_not_move_across_a_join(void **state)
{
    (void)state;
    make_body();
    cub_clip a, b;
    void *ma = stand_clip(&a, 30, 0), *mb = stand_clip(&b, 30, 25); /* B: right foot wide */
    cub_join_db db;
    int ia, ib;
    assert_int_equal(cub_join_db_init(&db, &skel, NULL, NULL), CUB_OK);
    assert_int_equal(cub_join_db_add(&db, "a", &a, &ia), CUB_OK);
    assert_int_equal(cub_join_db_add(&db, "b", &b, &ib), CUB_OK);
    cub_join_pick pick;
    cub_join_direct(&db, ia, ib, &pick);
    cub_join_result feet, direct;
    assert_int_equal(cub_join_build(&db, ia, ib, &pick, 1, &feet), CUB_OK);
    assert_int_equal(cub_join_build(&db, ia, ib, &pick, 0, &direct), CUB_OK);

    /* The right foot has farther to go: it steps first, the left stays. */
    int lank = cub_motion_skeleton_find(&skel, "LeftFoot");
    int rank = cub_motion_skeleton_find(&skel, "RightFoot");
    cub_dv3 planted = world_joint(&a, 29, lank);
    int w0 = feet.win_first[0], n = feet.win_frames[0];
    double left_moved = 0, direct_moved = 0, right_top = 0;
    for (int k = 0; 2 * (k + 1) < n + 1; k++) { /* the seam's first half */
        cub_dv3 l = world_joint(&feet.clip, w0 + k, lank);
        left_moved = fmax(left_moved, cub_dv3_len(cub_dv3_sub(l, planted)));
        right_top = fmax(right_top, world_joint(&feet.clip, w0 + k, rank).y);
        cub_dv3 d = world_joint(&direct.clip, direct.win_first[0] + k, lank);
        direct_moved = fmax(direct_moved, cub_dv3_len(cub_dv3_sub(d, planted)));
    }
    printf("join: planted foot moved %.3f mm with the legs one at a time, %.1f mm blended; "
           "the stepping foot rose to %.0f mm (rest %.0f)\n",
           left_moved, direct_moved, right_top, planted.y);
    assert_true(left_moved < 0.5);
    assert_true(direct_moved > 3);
    assert_true(right_top > planted.y + 40); /* a step, not a slide */

    /* After the seam both feet stand where B (moved onto A) has them. */
    cub_dv3 lb = cub_join_apply(&pick.direct, world_joint(&b, n, lank));
    cub_dv3 lo = world_joint(&feet.clip, w0 + n, lank);
    assert_true(cub_dv3_len(cub_dv3_sub(lb, lo)) < 1.0);

    cub_join_figures ff = cub_join_measure(&db, &feet), fd = cub_join_measure(&db, &direct);
    printf("join: slide %.2f cm (feet) vs %.2f cm (blended)\n", ff.slide_cm, fd.slide_cm);
    assert_true(ff.slide_cm < fd.slide_cm);
    assert_true(fd.slide_cm > 1);
    cub_join_result_free(&feet), cub_join_result_free(&direct);
    cub_join_db_free(&db);
    free(ma), free(mb);
}

/* ---- the shipped library ------------------------------------------------------ */

static void test_library_search_beats_direct_distance(void **state)
{
    (void)state;
    char path[512];
    snprintf(path, sizeof path, "%s/assets/clips/bear.cubclips", getenv("CUB_SOURCE_DIR"));
    static cub_library lib;
    cub_diag d = {0};
    assert_int_equal(cub_pack_read(path, &lib, &d), CUB_OK);
    cub_join_db db;
    assert_int_equal(cub_join_db_init(&db, &lib.skel, NULL, &d), CUB_OK);
    for (int i = 0; i < lib.clip_count; i++)
        assert_int_equal(cub_join_db_add(&db, lib.clips[i].name, &lib.clips[i].clip, NULL), CUB_OK);
    int a = cub_library_find(&lib, "jump"), b = cub_library_find(&lib, "squat");
    cub_join_pick pick;
    assert_int_equal(cub_join_search(&db, a, b, &pick), CUB_OK);
    printf("join: jump -> squat: direct D=%.0f mm2, through %s@%d-%d D=%.0f + %.0f mm2\n",
           pick.direct.d_mm2, db.clips[pick.clip].name, pick.first, pick.last, pick.in.d_mm2,
           pick.out.d_mm2);
    assert_true(pick.in.d_mm2 < pick.direct.d_mm2 && pick.out.d_mm2 < pick.direct.d_mm2);
    assert_true(pick.last - pick.first + 1 >= db.cfg.min_frames);
    cub_join_result r;
    assert_int_equal(cub_join_build(&db, a, b, &pick, 1, &r), CUB_OK);
    int na = lib.clips[a].clip.frame_count, nb = lib.clips[b].clip.frame_count;
    assert_int_equal(r.clip.frame_count,
                     na + (pick.last - pick.first + 1) + nb - r.win_frames[0] - r.win_frames[1]);
    cub_join_result_free(&r);
    cub_join_db_free(&db);
    cub_library_free(&lib);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_body_without_legs_is_refused_by_name),
        cmocka_unit_test(test_db_refuses_another_skeleton_and_short_clips),
        cmocka_unit_test(test_kovar_is_zero_for_a_turned_moved_copy),
        cmocka_unit_test(test_kovar_closed_form_matches_brute_force),
        cmocka_unit_test(test_contacts_are_low_slow_runs),
        cmocka_unit_test(test_support_names_read_as_the_seed),
        cmocka_unit_test(test_standing_clip_stands_on_two_feet),
        cmocka_unit_test(test_planted_foot_does_not_move_across_a_join),
        cmocka_unit_test(test_library_search_beats_direct_distance),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

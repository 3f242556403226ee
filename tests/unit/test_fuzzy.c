/* test_fuzzy — seed 000's fuzzy pose features and the distance d: bad input
 * first, then every membership function at the seed's breakpoints, the
 * geometry of each feature on hand-built poses, then properties (mirror
 * twins, d symmetric / zero on itself / within [0, 1]) and agreement with
 * the double reference tests/support/fuzzy_ref.c on random poses and on
 * every frame of the CMU BVH files in $CUB_DATA_DIR/mocap/cmu.
 * Under qemu (aarch64) or with CUB_QUICK set the sweeps are lighter. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/fuzzy.h"
#include "fuzzy_ref.h"
#include "fuzzy_pose.h"

#define Q16(x) ((cub_q16)lround((x)*65536.0))
#define MU(x) ((uint16_t)lround((x)*32768.0))

/* ---- bad input ---------------------------------------------------------- */

static void test_features_reject_bad_input(void **state)
{
    (void)state;
    cub_fuzzy_body body = fz_kinect_body(0, 900);
    cub_vec3 w[CUB_KJ_COUNT];
    cub_fuzzy_frame out;
    fz_template(w);
    assert_int_equal(cub_fuzzy_features(&body, w, CUB_KJ_COUNT, &out), CUB_OK);
    assert_int_equal(cub_fuzzy_features(NULL, w, CUB_KJ_COUNT, &out), CUB_ERR_ARG);
    assert_int_equal(cub_fuzzy_features(&body, NULL, CUB_KJ_COUNT, &out), CUB_ERR_ARG);
    assert_int_equal(cub_fuzzy_features(&body, w, CUB_KJ_COUNT, NULL), CUB_ERR_ARG);
    assert_int_equal(cub_fuzzy_features(&body, w, 0, &out), CUB_ERR_ARG);
    assert_int_equal(cub_fuzzy_features(&body, w, -3, &out), CUB_ERR_ARG);
    /* Every required joint: missing (-1), and one past the end. */
    int16_t *required[] = {&body.hip_centre,  &body.shoulder_centre, &body.shoulder[0],
                           &body.shoulder[1], &body.elbow[0],        &body.elbow[1],
                           &body.wrist[0],    &body.wrist[1],        &body.hip[0],
                           &body.hip[1],      &body.knee[0],         &body.knee[1],
                           &body.ankle[0],    &body.ankle[1]};
    for (size_t i = 0; i < sizeof required / sizeof required[0]; i++) {
        int16_t keep = *required[i];
        *required[i] = -1;
        assert_int_equal(cub_fuzzy_features(&body, w, CUB_KJ_COUNT, &out), CUB_ERR_ARG);
        assert_int_equal(cub_fuzzy_cog_height_mm(&body, w, CUB_KJ_COUNT), 0);
        *required[i] = CUB_KJ_COUNT;
        assert_int_equal(cub_fuzzy_features(&body, w, CUB_KJ_COUNT, &out), CUB_ERR_ARG);
        *required[i] = keep;
    }
    /* Spine and head may be absent, but not out of range. */
    body.spine = -1;
    body.head = -1;
    assert_int_equal(cub_fuzzy_features(&body, w, CUB_KJ_COUNT, &out), CUB_OK);
    body.spine = CUB_KJ_COUNT;
    assert_int_equal(cub_fuzzy_features(&body, w, CUB_KJ_COUNT, &out), CUB_ERR_ARG);
    body.spine = -1;
    body.head = -2;
    assert_int_equal(cub_fuzzy_features(&body, w, CUB_KJ_COUNT, &out), CUB_ERR_ARG);
    body.head = 3;
    body.stand_cog_mm = 0;
    assert_int_equal(cub_fuzzy_features(&body, w, CUB_KJ_COUNT, &out), CUB_ERR_ARG);
    body.stand_cog_mm = -Q16(900);
    assert_int_equal(cub_fuzzy_features(&body, w, CUB_KJ_COUNT, &out), CUB_ERR_ARG);
    /* A failed call leaves a zeroed frame, never garbage. */
    for (int k = 0; k < CUB_FUZZY_FEATURE_COUNT; k++)
        assert_int_equal(out.input[k], 0);
    assert_int_equal(cub_fuzzy_cog_height_mm(NULL, w, CUB_KJ_COUNT), 0);
    assert_int_equal(cub_fuzzy_cog_height_mm(&body, NULL, CUB_KJ_COUNT), 0);
}

static void test_names_and_sets_reject_bad_input(void **state)
{
    (void)state;
    uint16_t mu[CUB_FUZZY_MAX_SETS] = {1, 2, 3, 4};
    cub_fuzzy_membership((cub_fuzzy_feature)CUB_FUZZY_FEATURE_COUNT, 0, mu);
    for (int s = 0; s < CUB_FUZZY_MAX_SETS; s++)
        assert_int_equal(mu[s], 0);
    cub_fuzzy_membership(CUB_FUZZY_RH, 0, NULL); /* no crash */
    assert_int_equal(cub_fuzzy_set_count((cub_fuzzy_feature)-1), 0);
    assert_int_equal(cub_fuzzy_set_count((cub_fuzzy_feature)CUB_FUZZY_FEATURE_COUNT), 0);
    assert_string_equal(cub_fuzzy_feature_name((cub_fuzzy_feature)99), "?");
    assert_string_equal(cub_fuzzy_set_name(CUB_FUZZY_RH, 3), "?");
    assert_string_equal(cub_fuzzy_set_name(CUB_FUZZY_RH, -1), "?");
    assert_int_equal(cub_fuzzy_crisp_class(NULL), 0);
    cub_fuzzy_frame f = {0};
    assert_int_equal(cub_fuzzy_distance(NULL, &f, NULL), CUB_Q16_ONE);
    assert_int_equal(cub_fuzzy_distance(&f, NULL, NULL), CUB_Q16_ONE);
}

/* ---- membership functions at the seed's breakpoints --------------------- */

typedef struct mu_case {
    cub_fuzzy_feature f;
    double x;
    double mu[CUB_FUZZY_MAX_SETS];
} mu_case;

/* SEEDS.md § 000 step 2; the values follow from the printed formulas. */
static const mu_case cases[] = {
    /* RH: down, mid, up */
    {CUB_FUZZY_RH, -10, {1, 0, 0}},
    {CUB_FUZZY_RH, 0, {1, 0, 0}},
    {CUB_FUZZY_RH, 20, {1, 0, 0}},
    {CUB_FUZZY_RH, 55, {0.5, 0.5, 0}},
    {CUB_FUZZY_RH, 90, {0, 1, 0}},
    {CUB_FUZZY_RH, 135, {0, 0.5, 0.5}},
    {CUB_FUZZY_RH, 180, {0, 0, 1}},
    {CUB_FUZZY_RH, 200, {0, 0, 1}},
    /* RHE: false, true */
    {CUB_FUZZY_RHE, 0, {1, 0}},
    {CUB_FUZZY_RHE, 20, {70 / 90.0, 0}},
    {CUB_FUZZY_RHE, 45, {0.5, 25 / 70.0}},
    {CUB_FUZZY_RHE, 55, {35 / 90.0, 0.5}},
    {CUB_FUZZY_RHE, 90, {0, 1}},
    {CUB_FUZZY_RHE, 180, {0, 1}},
    /* Posture: lie, sit, stand, jump */
    {CUB_FUZZY_POSTURE, -5, {1, 0, 0, 0}},
    {CUB_FUZZY_POSTURE, 0, {1, 0, 0, 0}},
    {CUB_FUZZY_POSTURE, 20, {0.5, 0.5, 0, 0}},
    {CUB_FUZZY_POSTURE, 40, {0, 1, 0, 0}},
    {CUB_FUZZY_POSTURE, 60, {0, 0.5, 0.5, 0}},
    {CUB_FUZZY_POSTURE, 80, {0, 0, 1, 0}},
    {CUB_FUZZY_POSTURE, 100, {0, 0, 0.5, 0.5}},
    {CUB_FUZZY_POSTURE, 120, {0, 0, 0, 1}},
    {CUB_FUZZY_POSTURE, 150, {0, 0, 0, 1}},
    /* Trunk: true, false */
    {CUB_FUZZY_TRUNK, 90, {1, 0}},
    {CUB_FUZZY_TRUNK, 110, {1, 0}},
    {CUB_FUZZY_TRUNK, 125, {55 / 70.0, 0}},
    {CUB_FUZZY_TRUNK, 145, {0.5, 20 / 55.0}},
    {CUB_FUZZY_TRUNK, 180, {0, 1}},
    /* RF: inward, outward */
    {CUB_FUZZY_RF, -20, {1, 0}},
    {CUB_FUZZY_RF, 0, {1, 0}},
    {CUB_FUZZY_RF, 20, {0.5, 0.5}},
    {CUB_FUZZY_RF, 40, {0, 1}},
    {CUB_FUZZY_RF, 60, {0, 1}},
    /* RFK: true, false */
    {CUB_FUZZY_RFK, 60, {1, 0}},
    {CUB_FUZZY_RFK, 90, {1, 0}},
    {CUB_FUZZY_RFK, 100, {80 / 90.0, 0}},
    {CUB_FUZZY_RFK, 135, {0.5, 35 / 80.0}},
    {CUB_FUZZY_RFK, 140, {40 / 90.0, 0.5}},
    {CUB_FUZZY_RFK, 180, {0, 1}},
};

static void test_membership_at_seed_breakpoints(void **state)
{
    (void)state;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const mu_case *c = &cases[i];
        uint16_t mu[CUB_FUZZY_MAX_SETS];
        cub_fuzzy_membership(c->f, Q16(c->x), mu);
        for (int s = 0; s < CUB_FUZZY_MAX_SETS; s++) {
            /* Breakpoints and halves are exact; other fractions round. */
            if (mu[s] != MU(c->mu[s]))
                fail_msg("%s(%g) set %s: got %u, want %u", cub_fuzzy_feature_name(c->f), c->x,
                         cub_fuzzy_set_name(c->f, s), mu[s], MU(c->mu[s]));
        }
    }
}

static void test_set_names_follow_the_seed(void **state)
{
    (void)state;
    assert_int_equal(cub_fuzzy_set_count(CUB_FUZZY_RH), 3);
    assert_int_equal(cub_fuzzy_set_count(CUB_FUZZY_POSTURE), 4);
    assert_int_equal(cub_fuzzy_set_count(CUB_FUZZY_LFK), 2);
    assert_string_equal(cub_fuzzy_feature_name(CUB_FUZZY_POSTURE), "Posture");
    assert_string_equal(cub_fuzzy_set_name(CUB_FUZZY_POSTURE, 2), "stand");
    assert_string_equal(cub_fuzzy_set_name(CUB_FUZZY_TRUNK, 0), "true");
    assert_string_equal(cub_fuzzy_set_name(CUB_FUZZY_LF, 1), "outward");
    assert_string_equal(cub_fuzzy_set_name(CUB_FUZZY_LH, 2), "up");
}

/* The left features use the right ones' functions, at every input. */
static void test_left_sets_mirror_right(void **state)
{
    (void)state;
    const cub_fuzzy_feature pair[][2] = {{CUB_FUZZY_RH, CUB_FUZZY_LH},
                                         {CUB_FUZZY_RHE, CUB_FUZZY_LHE},
                                         {CUB_FUZZY_RF, CUB_FUZZY_LF},
                                         {CUB_FUZZY_RFK, CUB_FUZZY_LFK}};
    for (int p = 0; p < 4; p++) {
        assert_int_equal(cub_fuzzy_set_count(pair[p][0]), cub_fuzzy_set_count(pair[p][1]));
        for (cub_q16 x = Q16(-30); x <= Q16(210); x += 997) {
            uint16_t r[CUB_FUZZY_MAX_SETS], l[CUB_FUZZY_MAX_SETS];
            cub_fuzzy_membership(pair[p][0], x, r);
            cub_fuzzy_membership(pair[p][1], x, l);
            assert_memory_equal(r, l, sizeof r);
        }
    }
}

/* ---- the geometry of each feature --------------------------------------- */

static double in_deg(const cub_fuzzy_frame *f, cub_fuzzy_feature k)
{
    return f->input[k] / 65536.0;
}

static void features_of(cub_vec3 *w, cub_fuzzy_frame *f)
{
    cub_fuzzy_body body = fz_kinect_body(0, 0);
    cub_vec3 rest[CUB_KJ_COUNT];
    fz_template(rest);
    body.stand_cog_mm = cub_fuzzy_cog_height_mm(&body, rest, CUB_KJ_COUNT);
    assert_true(body.stand_cog_mm > Q16(800) && body.stand_cog_mm < Q16(1100));
    assert_int_equal(cub_fuzzy_features(&body, w, CUB_KJ_COUNT, f), CUB_OK);
}

#define NEAR_DEG(f, k, want) assert_true(fabs(in_deg(f, k) - (want)) < 0.02)

static void test_standing_template_reads_standing(void **state)
{
    (void)state;
    cub_vec3 w[CUB_KJ_COUNT];
    cub_fuzzy_frame f;
    fz_template(w);
    features_of(w, &f);
    NEAR_DEG(&f, CUB_FUZZY_POSTURE, 80);
    NEAR_DEG(&f, CUB_FUZZY_TRUNK, 180);
    NEAR_DEG(&f, CUB_FUZZY_RF, 0);
    NEAR_DEG(&f, CUB_FUZZY_LFK, 180);
    /* Crisp: arms down, elbows not bent, stand, trunk not bent, legs in,
     * knees straight. */
    uint32_t want = (0u << 0) | (0u << 2) | (0u << 4) | (0u << 6) | (2u << 8) | (1u << 10) |
                    (0u << 12) | (1u << 14) | (0u << 16) | (1u << 18);
    assert_int_equal(cub_fuzzy_crisp_class(&f), want);
}

static void test_each_feature_measures_its_angle(void **state)
{
    (void)state;
    cub_vec3 w[CUB_KJ_COUNT];
    cub_fuzzy_frame f;
    fz_template(w);
    /* Right arm straight out sideways, then forearm straight up: RH 90,
     * RHE 90. Left arm straight up: LH 180, LHE 0. */
    w[CUB_KJ_ELBOW_R] = fz_add(w[CUB_KJ_SHOULDER_R], -300, 0, 0); /* right is -x */
    w[CUB_KJ_WRIST_R] = fz_add(w[CUB_KJ_ELBOW_R], 0, 250, 0);
    w[CUB_KJ_ELBOW_L] = fz_add(w[CUB_KJ_SHOULDER_L], 0, 300, 0);
    w[CUB_KJ_WRIST_L] = fz_add(w[CUB_KJ_ELBOW_L], 0, 250, 0);
    /* Right leg stepped out 30 degrees in the frontal plane; left knee
     * bent to 90 with the shank pointing back. */
    w[CUB_KJ_KNEE_R] = fz_add(w[CUB_KJ_HIP_R], -430 * sin(M_PI / 6), -430 * cos(M_PI / 6), 0);
    w[CUB_KJ_ANKLE_R] = fz_add(w[CUB_KJ_KNEE_R], -440 * sin(M_PI / 6), -440 * cos(M_PI / 6), 0);
    w[CUB_KJ_ANKLE_L] = fz_add(w[CUB_KJ_KNEE_L], 0, 0, -440);
    features_of(w, &f);
    NEAR_DEG(&f, CUB_FUZZY_RH, 90);
    NEAR_DEG(&f, CUB_FUZZY_RHE, 90);
    NEAR_DEG(&f, CUB_FUZZY_LH, 180);
    NEAR_DEG(&f, CUB_FUZZY_LHE, 0);
    NEAR_DEG(&f, CUB_FUZZY_RF, 30);
    NEAR_DEG(&f, CUB_FUZZY_RFK, 180);
    NEAR_DEG(&f, CUB_FUZZY_LF, 0);
    NEAR_DEG(&f, CUB_FUZZY_LFK, 90);
    assert_int_equal(f.mu[CUB_FUZZY_RH][1], CUB_FUZZY_ONE);
    assert_int_equal(f.mu[CUB_FUZZY_LH][2], CUB_FUZZY_ONE);
    assert_int_equal(f.mu[CUB_FUZZY_LFK][0], CUB_FUZZY_ONE);

    /* A forward kick is not a side step: the thigh forward reads ~0. */
    fz_template(w);
    w[CUB_KJ_KNEE_R] = fz_add(w[CUB_KJ_HIP_R], 0, 0, 430);
    features_of(w, &f);
    NEAR_DEG(&f, CUB_FUZZY_RF, 0);
    /* A crossed leg reads negative (inward). */
    w[CUB_KJ_KNEE_R] = fz_add(w[CUB_KJ_HIP_R], 430 * sin(M_PI / 9), -430 * cos(M_PI / 9), 0);
    features_of(w, &f);
    NEAR_DEG(&f, CUB_FUZZY_RF, -20);
    assert_int_equal(f.mu[CUB_FUZZY_RF][0], CUB_FUZZY_ONE);

    /* Bent over at the hips: the upper body rotated 90 degrees forward. */
    fz_template(w);
    fz_bend_forward(w, 90);
    for (int side = 0; side < 2; side++) { /* arms hang straight down */
        int sh = side ? CUB_KJ_SHOULDER_R : CUB_KJ_SHOULDER_L;
        w[sh + 1] = fz_add(w[sh], 0, -290, 0);
        w[sh + 2] = fz_add(w[sh + 1], 0, -250, 0);
    }
    features_of(w, &f);
    NEAR_DEG(&f, CUB_FUZZY_TRUNK, 90);
    assert_int_equal(f.mu[CUB_FUZZY_TRUNK][0], CUB_FUZZY_ONE);
    /* The arms hang straight down: 90 from the (now horizontal) trunk. */
    NEAR_DEG(&f, CUB_FUZZY_RH, 90);
}

static void test_posture_follows_cog_height(void **state)
{
    (void)state;
    cub_vec3 w[CUB_KJ_COUNT];
    cub_fuzzy_frame f;
    fz_template(w);
    cub_fuzzy_body body = fz_kinect_body(0, 0);
    cub_q16 stand = cub_fuzzy_cog_height_mm(&body, w, CUB_KJ_COUNT);
    /* Lift everything by half the CoG height: x = 120, jump. */
    for (int j = 0; j < CUB_KJ_COUNT; j++)
        w[j].y += stand / 2;
    features_of(w, &f);
    NEAR_DEG(&f, CUB_FUZZY_POSTURE, 120);
    assert_int_equal(f.mu[CUB_FUZZY_POSTURE][3], CUB_FUZZY_ONE);
    /* Seated on a chair: reads sit more than stand. */
    fz_template(w);
    fz_sit(w);
    features_of(w, &f);
    printf("fuzzy: seated template posture x=%.1f trunk=%.1f knee=%.1f\n",
           in_deg(&f, CUB_FUZZY_POSTURE), in_deg(&f, CUB_FUZZY_TRUNK), in_deg(&f, CUB_FUZZY_RFK));
    assert_true(f.mu[CUB_FUZZY_POSTURE][1] > f.mu[CUB_FUZZY_POSTURE][2]);
    assert_true(f.mu[CUB_FUZZY_TRUNK][0] > f.mu[CUB_FUZZY_TRUNK][1]);
    assert_true(f.mu[CUB_FUZZY_RFK][0] > f.mu[CUB_FUZZY_RFK][1]);
    /* Lying on the floor. */
    fz_template(w);
    for (int j = 0; j < CUB_KJ_COUNT; j++) {
        cub_q16 y = w[j].y;
        w[j].y = Q16(10) + w[j].z / 8;
        w[j].z = y;
    }
    features_of(w, &f);
    assert_int_equal(cub_fuzzy_crisp_class(&f) >> (2 * CUB_FUZZY_POSTURE) & 3, 0); /* lie */
}

/* ---- properties ---------------------------------------------------------- */

static int quick(void)
{
#if defined(__aarch64__)
    return 1; /* cross build: the tests run under qemu, 10-30x slower */
#else
    return getenv("CUB_QUICK") != NULL;
#endif
}

/* The template with every joint moved by up to ±r mm. */
static void random_pose(uint64_t *rng, double r, cub_vec3 *w)
{
    fz_template(w);
    for (int j = 0; j < CUB_KJ_COUNT; j++)
        w[j] = fz_add(w[j], fz_uniform(rng, -r, r), fz_uniform(rng, -r, r), fz_uniform(rng, -r, r));
}

/* Mirror x and swap the sides: the right features of one are the left
 * features of the other. */
static void test_mirrored_pose_swaps_sides(void **state)
{
    (void)state;
    const int pairs[][2] = {{CUB_KJ_SHOULDER_L, CUB_KJ_SHOULDER_R}, {CUB_KJ_ELBOW_L, CUB_KJ_ELBOW_R},
                            {CUB_KJ_WRIST_L, CUB_KJ_WRIST_R},       {CUB_KJ_HAND_L, CUB_KJ_HAND_R},
                            {CUB_KJ_HIP_L, CUB_KJ_HIP_R},           {CUB_KJ_KNEE_L, CUB_KJ_KNEE_R},
                            {CUB_KJ_ANKLE_L, CUB_KJ_ANKLE_R},       {CUB_KJ_FOOT_L, CUB_KJ_FOOT_R}};
    const int twin[CUB_FUZZY_FEATURE_COUNT] = {
        CUB_FUZZY_LH,    CUB_FUZZY_LHE, CUB_FUZZY_RH,  CUB_FUZZY_RHE, CUB_FUZZY_POSTURE,
        CUB_FUZZY_TRUNK, CUB_FUZZY_LF,  CUB_FUZZY_LFK, CUB_FUZZY_RF,  CUB_FUZZY_RFK};
    cub_fuzzy_body body = fz_kinect_body(0, 950);
    uint64_t rng = 7;
    double max_err = 0;
    for (int i = 0; i < 500; i++) {
        cub_vec3 w[CUB_KJ_COUNT], m[CUB_KJ_COUNT];
        cub_fuzzy_frame a, b;
        random_pose(&rng, 300, w);
        for (int j = 0; j < CUB_KJ_COUNT; j++)
            m[j] = (cub_vec3){-w[j].x, w[j].y, w[j].z};
        for (int p = 0; p < 8; p++) {
            cub_vec3 t = m[pairs[p][0]];
            m[pairs[p][0]] = m[pairs[p][1]];
            m[pairs[p][1]] = t;
        }
        assert_int_equal(cub_fuzzy_features(&body, w, CUB_KJ_COUNT, &a), CUB_OK);
        assert_int_equal(cub_fuzzy_features(&body, m, CUB_KJ_COUNT, &b), CUB_OK);
        for (int k = 0; k < CUB_FUZZY_FEATURE_COUNT; k++) {
            double e = fabs((a.input[k] - b.input[twin[k]]) / 65536.0);
            if (e > max_err) max_err = e;
            for (int s = 0; s < CUB_FUZZY_MAX_SETS; s++)
                assert_true(abs(a.mu[k][s] - b.mu[twin[k]][s]) <= 2);
        }
    }
    printf("fuzzy: mirrored pose max |right - left twin| = %.2g deg over 500 poses\n", max_err);
    assert_true(max_err < 1e-3);
}

static void test_config_defaults(void **state)
{
    (void)state;
    cub_fuzzy_config zero = {0}, c = cub_fuzzy_config_defaults(&zero);
    cub_fuzzy_config n = cub_fuzzy_config_defaults(NULL);
    assert_memory_equal(&c, &n, sizeof c);
    int64_t sum = 0;
    for (int k = 0; k < CUB_FUZZY_FEATURE_COUNT; k++)
        sum += c.weight[k];
    assert_int_equal(sum, CUB_Q16_ONE);
    assert_int_equal(c.threshold, 26214); /* 0.4 */
    /* Arms = Posture > Trunk > legs. */
    assert_int_equal(c.weight[CUB_FUZZY_RH], c.weight[CUB_FUZZY_POSTURE]);
    assert_int_equal(c.weight[CUB_FUZZY_LHE], c.weight[CUB_FUZZY_RHE]);
    assert_true(c.weight[CUB_FUZZY_RH] > c.weight[CUB_FUZZY_TRUNK]);
    assert_true(c.weight[CUB_FUZZY_TRUNK] > c.weight[CUB_FUZZY_RF]);
    assert_int_equal(c.weight[CUB_FUZZY_RF], c.weight[CUB_FUZZY_LFK]);
    /* Own weights are normalised; negative ones count as 0. */
    cub_fuzzy_config own = {.threshold = Q16(0.25)};
    for (int k = 0; k < CUB_FUZZY_FEATURE_COUNT; k++)
        own.weight[k] = Q16(5);
    own.weight[CUB_FUZZY_LFK] = -Q16(5);
    c = cub_fuzzy_config_defaults(&own);
    sum = 0;
    for (int k = 0; k < CUB_FUZZY_FEATURE_COUNT; k++)
        sum += c.weight[k];
    assert_int_equal(sum, CUB_Q16_ONE);
    assert_int_equal(c.weight[CUB_FUZZY_LFK], 0);
    assert_true(abs(c.weight[CUB_FUZZY_RH] - CUB_Q16_ONE / 9) <= 1);
    assert_int_equal(c.threshold, Q16(0.25));
}

static void test_crisp_class_ties_to_lower(void **state)
{
    (void)state;
    cub_fuzzy_frame f = {0};
    assert_int_equal(cub_fuzzy_crisp_class(&f), 0);
    f.mu[CUB_FUZZY_RH][0] = f.mu[CUB_FUZZY_RH][1] = 16384;
    f.mu[CUB_FUZZY_POSTURE][1] = f.mu[CUB_FUZZY_POSTURE][2] = f.mu[CUB_FUZZY_POSTURE][3] = 9000;
    f.mu[CUB_FUZZY_LFK][1] = 1;
    f.mu[CUB_FUZZY_LH][2] = CUB_FUZZY_ONE;
    uint32_t want =
        (2u << (2 * CUB_FUZZY_LH)) | (1u << (2 * CUB_FUZZY_POSTURE)) | (1u << (2 * CUB_FUZZY_LFK));
    assert_int_equal(cub_fuzzy_crisp_class(&f), want);
}

static void frame_from_inputs(const double *x, cub_fuzzy_frame *f)
{
    for (int k = 0; k < CUB_FUZZY_FEATURE_COUNT; k++) {
        f->input[k] = Q16(x[k]);
        cub_fuzzy_membership((cub_fuzzy_feature)k, f->input[k], f->mu[k]);
    }
}

static void test_distance_properties(void **state)
{
    (void)state;
    /* Every feature at the opposite end: each term is 2/2, d = 1. */
    const double low[] = {0, 0, 0, 0, 0, 90, 0, 90, 0, 90};
    const double high[] = {180, 180, 180, 180, 80, 180, 40, 180, 40, 180};
    cub_fuzzy_frame a, b;
    frame_from_inputs(low, &a);
    frame_from_inputs(high, &b);
    assert_int_equal(cub_fuzzy_distance(&a, &b, NULL), CUB_Q16_ONE);
    assert_int_equal(cub_fuzzy_distance(&a, &a, NULL), 0);
    /* Only Posture differs (lie vs stand): d = sqrt(S_posture) = sqrt(3/21). */
    double x[CUB_FUZZY_FEATURE_COUNT];
    memcpy(x, low, sizeof x);
    x[CUB_FUZZY_POSTURE] = 80;
    frame_from_inputs(x, &b);
    assert_true(fabs(cub_fuzzy_distance(&a, &b, NULL) / 65536.0 - sqrt(3.0 / 21)) < 2e-5);
    /* Random frames: d(a,a) = 0, symmetric, within [0, 1]. */
    uint64_t rng = 99;
    int n = quick() ? 20000 : 200000;
    cub_q16 dmax = 0;
    for (int i = 0; i < n; i++) {
        for (int k = 0; k < CUB_FUZZY_FEATURE_COUNT; k++)
            x[k] = fz_uniform(&rng, -20, 200);
        frame_from_inputs(x, &a);
        for (int k = 0; k < CUB_FUZZY_FEATURE_COUNT; k++)
            x[k] = fz_uniform(&rng, -20, 200);
        frame_from_inputs(x, &b);
        cub_q16 d = cub_fuzzy_distance(&a, &b, NULL);
        assert_int_equal(d, cub_fuzzy_distance(&b, &a, NULL));
        assert_int_equal(cub_fuzzy_distance(&a, &a, NULL), 0);
        assert_true(d >= 0 && d <= CUB_Q16_ONE);
        if (d > dmax) dmax = d;
    }
    printf("fuzzy: d symmetric, d(a,a)=0, max d=%.4f over %d random frame pairs\n", dmax / 65536.0,
           n);
}

/* Random poses, near-human (template ±350 mm) and wild (anywhere in a 2 m
 * box), against the double reference. */
static void test_fixed_matches_float_on_random_poses(void **state)
{
    (void)state;
    uint64_t rng = 2024;
    int n = quick() ? 4000 : 100000;
    double max_mu = 0, max_d = 0, max_in = 0;
    int same_class = 0;
    cub_fuzzy_frame prev = {0};
    cub_fuzzy_ref_frame prev_ref = {0};
    for (int i = 0; i < n; i++) {
        cub_vec3 w[CUB_KJ_COUNT];
        double xyz[3 * CUB_KJ_COUNT];
        random_pose(&rng, i % 2 ? 350 : 1000, w);
        cub_fuzzy_body body =
            fz_kinect_body(fz_uniform(&rng, -100, 100), fz_uniform(&rng, 500, 1100));
        cub_fuzzy_ref_body rb = fz_ref_body(&body);
        cub_fuzzy_frame f;
        cub_fuzzy_ref_frame r;
        fz_to_double(w, CUB_KJ_COUNT, xyz);
        assert_int_equal(cub_fuzzy_features(&body, w, CUB_KJ_COUNT, &f), CUB_OK);
        assert_int_equal(cub_fuzzy_ref_features(&rb, xyz, CUB_KJ_COUNT, &r), 0);
        for (int k = 0; k < CUB_FUZZY_FEATURE_COUNT; k++)
            max_in = fmax(max_in, fabs(f.input[k] / 65536.0 - r.input[k]));
        max_mu = fmax(max_mu, fz_max_mu_err(&f, &r));
        same_class += cub_fuzzy_crisp_class(&f) == cub_fuzzy_ref_crisp_class(&r);
        if (i > 0) {
            double d = cub_fuzzy_distance(&f, &prev, NULL) / 65536.0;
            max_d = fmax(max_d, fabs(d - cub_fuzzy_ref_distance(&r, &prev_ref, NULL)));
            assert_true(d >= 0 && d <= 1);
        }
        prev = f;
        prev_ref = r;
    }
    printf("fuzzy: fixed vs float max_mu_err=%.2e max_d_err=%.2e max_input_err=%.2e "
           "crisp_agree=%.4f over %d random poses\n",
           max_mu, max_d, max_in, (double)same_class / n, n);
    assert_true(max_mu < 1e-3);
    assert_true(max_d < 1e-3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_features_reject_bad_input),
        cmocka_unit_test(test_names_and_sets_reject_bad_input),
        cmocka_unit_test(test_membership_at_seed_breakpoints),
        cmocka_unit_test(test_set_names_follow_the_seed),
        cmocka_unit_test(test_left_sets_mirror_right),
        cmocka_unit_test(test_standing_template_reads_standing),
        cmocka_unit_test(test_each_feature_measures_its_angle),
        cmocka_unit_test(test_posture_follows_cog_height),
        cmocka_unit_test(test_mirrored_pose_swaps_sides),
        cmocka_unit_test(test_config_defaults),
        cmocka_unit_test(test_crisp_class_ties_to_lower),
        cmocka_unit_test(test_distance_properties),
        cmocka_unit_test(test_fixed_matches_float_on_random_poses),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* Shared by the evolve tests: small hand-made skeletons (a horned
 * four-legged walker, a swimmer with a tail), deterministic motions, and a
 * fixture crossing the two. Static: each test file gets its own copy. */
#ifndef CUB_TEST_EVOLVE_FIXTURE_H
#define CUB_TEST_EVOLVE_FIXTURE_H

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/evolve.h"

/* ---- small skeletons and motions ------------------------------------------ */

typedef struct bone {
    const char *name, *parent;
    double x, y, z; /* rest offset, mm */
} bone;

static void build(cub_skeleton *s, const bone *b, int n)
{
    cub_motion_skeleton_reset(s);
    for (int i = 0; i < n; i++) {
        int p = b[i].parent ? cub_motion_skeleton_find(s, b[i].parent) : -1;
        int at;
        assert_int_equal(
            cub_motion_skeleton_add(s, b[i].name, p,
                                    cub_dv3_to_fx(cub_dv3_make(b[i].x, b[i].y, b[i].z)), &at),
            CUB_OK);
    }
}

/* A four-legged horned walker: 9 joints. */
static const bone horse[] = {
    {"Hips", NULL, 0, 900, 0},
    {"Spine", "Hips", 0, 100, 200},
    {"Neck", "Spine", 0, 100, 200},
    {"Head", "Neck", 0, 100, 100},
    {"Horn", "Head", 0, 80, 60},
    {"LeftUpLeg", "Hips", 100, -400, 0},
    {"LeftLeg", "LeftUpLeg", 0, -400, 0},
    {"RightUpLeg", "Hips", -100, -400, 0},
    {"RightLeg", "RightUpLeg", 0, -400, 0},
};
/* A fish-like swimmer: a collar where the horse has a neck, a tail. */
static const bone fish[] = {
    {"Hips", NULL, 0, 500, 0},     {"Spine", "Hips", 0, 0, 200}, {"Collar", "Spine", 0, 0, 150},
    {"Head", "Collar", 0, 0, 100}, {"Tail", "Hips", 0, 0, -200}, {"Tail1", "Tail", 0, 0, -200},
};
#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

static uint32_t rng = 12345;
static double noise(void) /* -1..1, deterministic */
{
    rng = rng * 1664525u + 1013904223u;
    return (rng >> 8) / (double)(1u << 24) * 2 - 1;
}

/* A motion of s: every joint turns by a random amount each frame, except
 * still (held at one fixed, non-rest rotation). The root walks along +z. */
static void animate(const cub_skeleton *s, int frames, int still, cub_evolve_motion *m)
{
    assert_int_equal(cub_evolve_motion_alloc(s, frames, 30, m), CUB_OK);
    for (int f = 0; f < frames; f++) {
        m->root_mm[f] = cub_dv3_make(0, s->joints[0].offset_mm.y / 65536.0, 10.0 * f);
        for (int j = 0; j < s->joint_count; j++) {
            cub_dv3 axis =
                cub_dv3_norm(cub_dv3_make(noise(), noise(), noise()), cub_dv3_make(1, 0, 0));
            double a = j == still ? 0.3 : 0.6 * noise();
            *cub_evolve_rot(m, f, j) =
                cub_dq_axis_angle(j == still ? cub_dv3_make(1, 0, 0) : axis, a);
        }
    }
}

static int joint(const cub_skeleton *s, const char *name)
{
    int j = cub_motion_skeleton_find(s, name);
    assert_true(j >= 0);
    return j;
}

/* ---- the two crossed -------------------------------------------------------- */

typedef struct pair_fixture {
    cub_skeleton a, b;
    cub_evolve_corr c;
    cub_evolve_meta m;
    cub_evolve_motion p1, p2;
    cub_evolve_mutation mut;
    cub_evolve_pop pop;
} pair_fixture;

static pair_fixture fx;

static void cross(int still_in_a, int frames1, int frames2)
{
    cub_evolve_motion_free(&fx.p1);
    cub_evolve_motion_free(&fx.p2);
    memset(&fx, 0, sizeof fx);
    build(&fx.a, horse, COUNT(horse));
    build(&fx.b, fish, COUNT(fish));
    assert_int_equal(cub_evolve_correspond(&fx.a, &fx.b, NULL, &fx.c, NULL), CUB_OK);
    assert_int_equal(cub_evolve_crossover(&fx.a, &fx.b, &fx.c, &fx.m, NULL), CUB_OK);
    animate(&fx.a, frames1, still_in_a, &fx.p1);
    animate(&fx.b, frames2, -1, &fx.p2);
}

static void free_fixture(void)
{
    cub_evolve_motion_free(&fx.p1);
    cub_evolve_motion_free(&fx.p2);
}

#endif

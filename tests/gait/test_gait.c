/* test_gait — seed 003's firmware (cub/gait.h) on hand-made ground: the
 * terrain's heights, the footstep planner (a blocked foothold forces a
 * backtrack; the first feasible step is taken; a dead end stops the walk)
 * the swing path (it clears a log) and the leg IK's limits. The phase analysis on a captured
 * walk is test_gait_walk. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <string.h>
#include <stdio.h>
#include <math.h>
#include <stdlib.h>

#include "cub/gait.h"

#define MM(n) CUB_Q16_INT(n)
#define Q(num, den) ((cub_q16)(((int64_t)(num) * CUB_Q16_ONE + (den) / 2) / (den)))

static cub_gait_box box(int x0, int y0, int z0, int x1, int y1, int z1)
{
    return (cub_gait_box){{MM(x0), MM(y0), MM(z0)}, {MM(x1), MM(y1), MM(z1)}};
}

static void test_terrain_heights(void **state)
{
    (void)state;
    cub_gait_terrain t;
    cub_gait_terrain_flat(&t, MM(12));
    assert_int_equal(cub_gait_height(&t, MM(-900), MM(4000)), MM(12));
    assert_true(cub_gait_terrain_is_flat(&t));

    cub_gait_terrain_slope(&t, MM(10), Q(1, 10), Q(-1, 5)); /* 10 % up x, 20 % down z */
    /* 1/10 is not exact in Q16.16: within 0.01 mm over a metre. */
    assert_in_range(cub_gait_height(&t, MM(1000), 0), MM(110) - 655, MM(110) + 655);
    assert_in_range(cub_gait_height(&t, 0, MM(500)) + MM(1000), MM(910) - 655, MM(910) + 655);
    assert_false(cub_gait_terrain_is_flat(&t));

    static cub_q16 hf[9 * 7];
    assert_int_equal(cub_gait_terrain_rolling(&t, hf, 1, 7, MM(250), MM(80), MM(2000)),
                     CUB_ERR_ARG);
    assert_int_equal(cub_gait_terrain_rolling(&t, hf, 9, 7, MM(250), MM(80), MM(2000)), CUB_OK);
    /* x = 500 is a quarter wave: sin 1, cos(0) 1 at z = 0; the crest. */
    assert_in_range(cub_gait_height(&t, MM(500), 0), MM(80) - 20, MM(80) + 20);
    /* Between samples: bilinear, so the midpoint of two samples is their mean. */
    cub_q16 mid = cub_gait_height(&t, MM(125), MM(250));
    assert_in_range(mid, (hf[9 + 0] + hf[9 + 1]) / 2 - 2, (hf[9 + 0] + hf[9 + 1]) / 2 + 2);
    /* Off the grid the edge holds. */
    assert_int_equal(cub_gait_height(&t, MM(-5000), MM(-5000)), hf[0]);
    assert_int_equal(cub_gait_height(&t, MM(9000), MM(9000)), hf[9 * 7 - 1]);
}

static void test_obstacles_raise_the_ground(void **state)
{
    (void)state;
    cub_gait_terrain t;
    cub_gait_terrain_flat(&t, 0);
    assert_int_equal(cub_gait_terrain_add(&t, box(0, 0, 0, 0, 10, 10)), CUB_ERR_ARG);
    /* A log across the path (x), 15 cm high; a stone. */
    assert_int_equal(cub_gait_terrain_add(&t, box(-1000, 0, 300, 1000, 150, 450)), CUB_OK);
    assert_int_equal(cub_gait_terrain_add(&t, box(200, 0, 900, 350, 90, 1050)), CUB_OK);
    assert_int_equal(cub_gait_height(&t, 0, MM(350)), MM(150));
    assert_int_equal(cub_gait_height(&t, MM(250), MM(1000)), MM(90));
    assert_int_equal(cub_gait_height(&t, 0, MM(1000)), 0);
    assert_int_equal(cub_gait_ground_height(&t, 0, MM(350)), 0);
    for (int i = 2; i < CUB_GAIT_MAX_OBSTACLES; i++)
        assert_int_equal(cub_gait_terrain_add(&t, box(0, 0, 0, 1, 1, 1)), CUB_OK);
    assert_int_equal(cub_gait_terrain_add(&t, box(0, 0, 0, 1, 1, 1)), CUB_ERR_FULL);
}

/* A walk along +z from the left foot at the origin: stride 60 cm, feet
 * 15 cm apart, foot base 25 cm. */
static cub_gait_plan_params walk_params(void)
{
    return (cub_gait_plan_params){.stride_mm = MM(600), .width_mm = MM(150), .foot_mm = MM(250)};
}

static const cub_gait_start start = {{0, 0, 0}, 1, 0, CUB_Q16_ONE, {MM(-150), 0, MM(-600)}};

static void test_plan_on_flat_ground(void **state)
{
    (void)state;
    cub_gait_terrain t;
    cub_gait_terrain_flat(&t, 0);
    cub_gait_plan_params p = walk_params();
    cub_gait_plan plan;
    assert_int_equal(cub_gait_plan_steps(&t, &p, &start, &plan), CUB_OK);
    assert_int_equal(plan.count, 4); /* flat: 4 steps ahead */
    assert_int_equal(plan.tested, 4);
    assert_int_equal(plan.backtracks, 0);
    for (int i = 0; i < plan.count; i++) {
        assert_int_equal(plan.steps[i].try_index, 0);
        assert_int_equal(plan.steps[i].left, i % 2); /* right first */
        assert_int_equal(plan.steps[i].foot_mm.z, MM(600 * (i + 1)));
        assert_int_equal(plan.steps[i].foot_mm.x, i % 2 ? 0 : MM(-150));
    }
    p.stride_mm = 0;
    assert_int_equal(cub_gait_plan_steps(&t, &p, &start, &plan), CUB_ERR_ARG);
}

/* Step 0 at the nominal 60 cm puts both of step 1's tries (60 and 45 cm
 * on) across the edge of a raised slab at z = 125 cm: step 1 fails, the
 * planner backs up to step 0's next try (45 cm), and from there step 1's
 * first try still straddles the edge, its second (45 cm) is clear. */
static void test_blocked_foothold_forces_a_backtrack(void **state)
{
    (void)state;
    cub_gait_terrain t;
    cub_gait_terrain_flat(&t, 0);
    assert_int_equal(cub_gait_terrain_add(&t, box(-1000, 0, 1250, 1000, 100, 2000)), CUB_OK);
    cub_gait_plan_params p = walk_params();
    p.steps = 2;
    p.tries = 2;
    p.factors[0] = CUB_Q16_ONE;
    p.factors[1] = Q(3, 4);
    cub_gait_plan plan;
    assert_int_equal(cub_gait_plan_steps(&t, &p, &start, &plan), CUB_OK);
    assert_int_equal(plan.count, 2);
    assert_int_equal(plan.backtracks, 1);
    assert_int_equal(plan.tested, 6);
    assert_int_equal(plan.steps[0].try_index, 1);
    assert_int_equal(plan.steps[0].foot_mm.z, MM(450));
    assert_int_equal(plan.steps[1].try_index, 1);
    assert_int_equal(plan.steps[1].foot_mm.z, MM(900));
    /* Each foothold taken is feasible; the rejected one is not. */
    assert_true(cub_gait_foothold_ok(&t, &p, 0, 0, MM(900), 0, CUB_Q16_ONE));
    assert_false(cub_gait_foothold_ok(&t, &p, 0, 0, MM(1050), 0, CUB_Q16_ONE));
}

/* A stone slab 72 cm on: the nominal step straddles its edge, the 0.75
 * stride is clear: the first feasible in the tried order is taken, 0.75.
 * On the slab's top, a foothold whose heel (a quarter foot behind the
 * ankle) hangs over the edge is refused; one further on is not. */
/* A stone (16 cm across, 7 cm high) 1 m on: a foot base (heel a quarter
 * foot behind the ankle to the toe, a fifth of the foot either side) that
 * ends within 20 mm of it, ahead or beside, is refused; one 20 mm clear
 * is not (a foot lands on an obstacle's top or clear of it). */
static void test_foothold_beside_a_stone_is_refused(void **state)
{
    (void)state;
    cub_gait_terrain t;
    cub_gait_terrain_flat(&t, 0);
    assert_int_equal(cub_gait_terrain_add(&t, box(-80, 0, 1000, 80, 70, 1160)), CUB_OK);
    cub_gait_plan_params p = walk_params();
    assert_false(cub_gait_foothold_ok(&t, &p, 0, 0, MM(740), 0, CUB_Q16_ONE)); /* toe 10 mm short */
    assert_true(cub_gait_foothold_ok(&t, &p, 0, 0, MM(725), 0, CUB_Q16_ONE));  /* toe 25 mm short */
    assert_false(cub_gait_foothold_ok(&t, &p, 0, MM(140), MM(1000), 0, CUB_Q16_ONE)); /* edge 10 mm off */
    assert_true(cub_gait_foothold_ok(&t, &p, 0, MM(180), MM(1000), 0, CUB_Q16_ONE));  /* 50 mm off */
    assert_false(cub_gait_foothold_ok(&t, &p, 0, 0, MM(1210), 0, CUB_Q16_ONE)); /* heel 12.5 mm past */
    p.obstacle_gap_mm = -1; /* the test off: only the base's tilt counts */
    assert_true(cub_gait_foothold_ok(&t, &p, 0, 0, MM(740), 0, CUB_Q16_ONE));
}

static void test_first_feasible_step_is_taken(void **state)
{
    (void)state;
    cub_gait_terrain t;
    cub_gait_terrain_flat(&t, 0);
    assert_int_equal(cub_gait_terrain_add(&t, box(-1000, 0, 720, 1000, 100, 1100)), CUB_OK);
    cub_gait_plan_params p = walk_params();
    p.steps = 1;
    cub_gait_plan plan;
    assert_int_equal(cub_gait_plan_steps(&t, &p, &start, &plan), CUB_OK);
    assert_int_equal(plan.steps[0].try_index, 1);
    assert_int_equal(plan.steps[0].foot_mm.z, MM(450));
    assert_int_equal(plan.tested, 2);
    assert_false(cub_gait_foothold_ok(&t, &p, 0, 0, MM(750), 0, CUB_Q16_ONE));
    assert_true(cub_gait_foothold_ok(&t, &p, 0, 0, MM(790), 0, CUB_Q16_ONE));
    /* Rough ground (an obstacle) plans 3 ahead by default. */
    p.steps = 0;
    assert_int_equal(cub_gait_plan_steps(&t, &p, &start, &plan), CUB_OK);
    assert_int_equal(plan.count, 3);
}

/* A wall too high to step on: every try fails back to step 0: the walk
 * stops (count 0). */
static void test_dead_end_stops_the_walk(void **state)
{
    (void)state;
    cub_gait_terrain t;
    cub_gait_terrain_flat(&t, 0);
    assert_int_equal(cub_gait_terrain_add(&t, box(-1000, 0, 400, 1000, 900, 3000)), CUB_OK);
    cub_gait_plan_params p = walk_params();
    p.steps = 3;
    cub_gait_plan plan;
    assert_int_equal(cub_gait_plan_steps(&t, &p, &start, &plan), CUB_ERR_EMPTY);
    assert_int_equal(plan.count, 0);
    assert_int_equal(plan.tested, 5);
}

static void test_bezier_ends_and_line(void **state)
{
    (void)state;
    cub_vec3 p[5];
    for (int k = 0; k < 5; k++)
        p[k] = (cub_vec3){MM(100 * k), MM(40), MM(-30 * k)};
    cub_vec3 a = cub_gait_bezier4(p, 0), b = cub_gait_bezier4(p, CUB_Q16_ONE);
    assert_int_equal(a.x, p[0].x);
    assert_int_equal(b.z, p[4].z);
    /* Evenly spaced control points on a line: B(t) runs along it linearly. */
    cub_vec3 m = cub_gait_bezier4(p, Q(3, 10));
    assert_in_range(m.x, MM(120) - 3277, MM(120) + 3277); /* within 0.05 mm */
    assert_in_range(m.y, MM(40) - 3277, MM(40) + 3277);
}

/* The swing sampled densely (4000 points; the firmware tests the ground
 * at 64 samples, the obstacles exactly), the
 * ankle and the toe 250 mm ahead of it: the lowest gap to the ground
 * anywhere (returned) and over z0..z1 mm (*over), in mm. */
static double swing_gaps(const cub_gait_swing *sw, const cub_gait_terrain *t, int z0, int z1,
                         double *over)
{
    double lowest = 1e9;
    *over = 1e9;
    for (int i = 0; i <= 4000; i++) {
        cub_vec3 q = cub_gait_bezier4(sw->p, (cub_q16)(((int64_t)i << 16) / 4000));
        for (int toe = 0; toe <= 1; toe++) {
            cub_q16 z = toe ? cub_fx_add(q.z, MM(250)) : q.z;
            double gap = (q.y - cub_gait_height(t, q.x, z)) / 65536.0;
            lowest = fmin(lowest, gap);
            if (z >= MM(z0) && z <= MM(z1)) *over = fmin(*over, gap);
        }
    }
    return lowest;
}

/* The swing found the least raise that clears: allowed one raise fewer,
 * the path from `from` to `to` does not clear. */
static void assert_one_raise_fewer_fails(const cub_gait_terrain *t, const cub_gait_swing_params *sp,
                                         cub_vec3 from, cub_vec3 to, int raises)
{
    cub_gait_swing_params fewer = *sp;
    fewer.max_raises = raises - 1;
    cub_gait_swing sw;
    assert_int_equal(cub_gait_swing_path(t, &fewer, from, to, &sw), CUB_ERR_RANGE);
    assert_false(sw.clear);
}

/* A log 15 cm high and 10 cm deep midway through a 60 cm step: the path
 * rises over it; checked densely here,
 * it never enters the ground and is >= 2 cm above the log, toe included. */
static void test_swing_clears_a_log(void **state)
{
    (void)state;
    cub_gait_terrain t;
    cub_gait_terrain_flat(&t, 0);
    assert_int_equal(cub_gait_terrain_add(&t, box(-1000, 0, 250, 1000, 150, 350)), CUB_OK);
    cub_gait_swing_params sp = {.foot_mm = MM(250)};
    cub_vec3 from = {0, 0, MM(-200)}, to = {0, 0, MM(600)};
    cub_gait_swing sw;
    assert_int_equal(cub_gait_swing_path(&t, &sp, from, to, &sw), CUB_OK);
    assert_true(sw.clear);
    assert_true(sw.raises > 0);
    double min_over_log;
    assert_true(swing_gaps(&sw, &t, 250, 350, &min_over_log) >= -0.01);
    assert_true(min_over_log >= 19.5);
    assert_one_raise_fewer_fails(&t, &sp, from, to, sw.raises);
}

/* A stone just behind the landing foothold (its far face 85 mm before
 * the ankle comes down: the heel, a quarter foot behind, 22.5 mm clear,
 * as the planner allows): the clearance that ramps to 0 at the footholds
 * let the ankle pass over it low; over an obstacle the full 20 mm
 * holds, ramp or not (checked at 4000 points, ankle and toe). */
static void test_swing_clears_a_stone_by_the_foothold(void **state)
{
    (void)state;
    cub_gait_terrain t;
    cub_gait_terrain_flat(&t, 0);
    assert_int_equal(cub_gait_terrain_add(&t, box(-80, 0, 355, 80, 70, 515)), CUB_OK);
    cub_gait_swing_params sp = {.foot_mm = MM(250)};
    cub_vec3 from = {0, 0, MM(-200)}, to = {0, 0, MM(600)};
    cub_gait_swing sw;
    assert_int_equal(cub_gait_swing_path(&t, &sp, from, to, &sw), CUB_OK);
    double min_over;
    swing_gaps(&sw, &t, 355, 515, &min_over);
    printf("gait: a stone by the foothold cleared by %.1f mm after %d raises\n", min_over, sw.raises);
    assert_true(min_over >= 19.5);
}

/* A plank on edge across the way, 12 mm thick and 80 mm high, under a
 * 1.5 m swing: the 64 samples of the old stepped test fell 23 mm apart
 * (ankle at z 398 and 422 mm, toe 250 mm ahead at 391 and 414 mm) and
 * missed it, so the path stayed 30 mm up and went through it. The raise
 * solved against each obstacle's edges clears it by >= 2 cm, checked at
 * 4000 points, ankle and toe; and it is the least raise that does: one
 * raise fewer does not clear. */
static void test_swing_clears_a_plank_between_samples(void **state)
{
    (void)state;
    cub_gait_terrain t;
    cub_gait_terrain_flat(&t, 0);
    assert_int_equal(cub_gait_terrain_add(&t, box(-1000, 0, 400, 1000, 80, 412)), CUB_OK);
    cub_gait_swing_params sp = {.foot_mm = MM(250)};
    cub_vec3 from = {0, 0, 0}, to = {0, 0, MM(1500)};
    cub_gait_swing sw;
    assert_int_equal(cub_gait_swing_path(&t, &sp, from, to, &sw), CUB_OK);
    double over_plank;
    assert_true(swing_gaps(&sw, &t, 400, 412, &over_plank) >= -0.01);
    printf("gait: a 12 mm plank cleared by %.1f mm after %d raises\n", over_plank, sw.raises);
    assert_true(over_plank >= 19.99);
    assert_one_raise_fewer_fails(&t, &sp, from, to, sw.raises);
}

/* The two tests below: flat ground with a log 15 cm high and 10 cm deep
 * across the way 875 mm on, a 25 cm foot's swing of at most 40 raises, a
 * plan of 3 steps (without the swing test: p->swing is left to them). */
static void log_setup(cub_gait_terrain *t, cub_gait_swing_params *sp, cub_gait_plan_params *p)
{
    cub_gait_terrain_flat(t, 0);
    assert_int_equal(cub_gait_terrain_add(t, box(-1000, 0, 875, 1000, 150, 975)), CUB_OK);
    *sp = (cub_gait_swing_params){.foot_mm = MM(250), .max_raises = 40};
    *p = walk_params();
    p->steps = 3;
}

/* A log 15 cm high and 10 cm deep across the way 875 mm on: the nominal
 * step 0 (60 cm) is a feasible foothold, its toe 25 mm short of the log,
 * but from there the same foot's swing over the log (step 2) cannot
 * clear within 40 raises (its toe meets the log at the swing's start).
 * With the swing in the feasibility test that foothold is refused: the
 * planner backs up and takes another step 0, and every swing of the plan
 * clears the log by >= 2 cm (checked at 4000 points, ankle and toe). */
static void test_foothold_too_near_an_obstacle_is_refused(void **state)
{
    (void)state;
    cub_gait_terrain t;
    cub_gait_swing_params sp;
    cub_gait_plan_params p;
    /* The obstacles are tested exactly (the 64 samples of the stepped
     * test let the toe dip to 11.9 mm at the log's near edge). */
    log_setup(&t, &sp, &p);
    cub_gait_plan plan;
    assert_int_equal(cub_gait_plan_steps(&t, &p, &start, &plan), CUB_OK);
    assert_int_equal(plan.steps[0].foot_mm.z, MM(600)); /* footholds alone: the nominal step */
    cub_gait_swing sw;
    assert_int_equal(cub_gait_swing_path(&t, &sp, plan.steps[0].foot_mm, plan.steps[2].foot_mm, &sw),
                     CUB_ERR_RANGE);
    p.swing = &sp;
    assert_int_equal(cub_gait_plan_steps(&t, &p, &start, &plan), CUB_OK);
    assert_int_equal(plan.count, 3);
    assert_true(plan.backtracks > 0);
    assert_true(plan.steps[0].foot_mm.z != MM(600));
    for (int i = 0; i < 3; i++) {
        cub_vec3 from = i >= 2 ? plan.steps[i - 2].foot_mm : i ? start.foot_mm : start.swing_from_mm;
        assert_int_equal(cub_gait_swing_path(&t, &sp, from, plan.steps[i].foot_mm, &sw), CUB_OK);
        double over_log; /* 1e9 for a swing that does not pass over the log */
        assert_true(swing_gaps(&sw, &t, 875, 975, &over_log) >= -0.01);
        printf("gait: step %d to %.0f mm (try %d), %d raises, over the log %.1f mm\n", i,
               plan.steps[i].foot_mm.z / 65536.0, plan.steps[i].try_index, sw.raises,
               over_log < 1e8 ? over_log : -1.0);
        assert_true(over_log >= 19.5);
    }
}

/* The planner run a foothold test at a time (as the walker spreads it
 * over frames) makes the plan of one call, byte for byte, the swing to
 * step 0 too; a copy of it taken midway (the walker's struct is copied)
 * finishes the same. Each run tests one foothold: as many runs as tests.
 * The log of the test above forces backtracks; a dead end (no swing
 * over it clears) ends the same. */
static void planner_run_a_test_at_a_time(void **state)
{
    (void)state;
    cub_gait_terrain t;
    cub_gait_swing_params sp;
    cub_gait_plan_params p;
    log_setup(&t, &sp, &p);
    p.swing = &sp;
    for (int dead = 0; dead < 2; dead++) {
        if (dead) sp.max_raises = 2; /* no swing over the log clears: a dead end */
        cub_gait_plan whole;
        cub_err e = cub_gait_plan_steps(&t, &p, &start, &whole);
        assert_int_equal(e, dead ? CUB_ERR_EMPTY : CUB_OK);
        assert_true(dead || whole.backtracks > 0);
        cub_gait_planner pl, copy;
        assert_int_equal(cub_gait_planner_begin(&pl, &p, &start), CUB_OK);
        int runs = 1;
        while (!cub_gait_planner_run(&pl, &t, 1)) {
            if (runs == 3) {
                copy = pl;
                memset(&pl, 0xa5, sizeof pl);
                pl = copy;
            }
            runs++;
        }
        assert_int_equal(pl.err, e);
        assert_int_equal(runs, whole.tested);
        assert_memory_equal(&pl.plan, &whole, sizeof whole);
        assert_int_equal(pl.plan.swung, !dead);
        printf("gait: planner a test per run: %d runs, %d backtracks, %s\n", runs,
               whole.backtracks, dead ? "dead end" : "planned");
    }
    assert_int_equal(cub_gait_planner_begin(NULL, &p, &start), CUB_ERR_ARG);
    p.stride_mm = 0;
    cub_gait_planner pl;
    assert_int_equal(cub_gait_planner_begin(&pl, &p, &start), CUB_ERR_ARG);
}

#define DEG(d) ((cub_q16)(((int64_t)(d) * CUB_Q16_PI + 90) / 180))

/* A right leg: hip 90 cm up, thigh 45 cm, shin 43 cm, the knee bending
 * toward +z. */
static const cub_gait_leg leg = {{0, MM(900), 0}, MM(450), MM(430), {0, MM(500), MM(500)}};

static double dist(cub_vec3 a, cub_vec3 b)
{
    return cub_fx_vec3_length(cub_fx_vec3_sub(a, b)) / 65536.0;
}

/* Thigh and knee: a target beyond reach (or at the straight knee's) is
 * pulled in and the knee stays at <= 175 degrees; one by the hip keeps it
 * >= 25 degrees; one in range is met exactly and uncorrected. */
static void test_leg_ik_keeps_the_knee_in_range(void **state)
{
    (void)state;
    cub_gait_leg_pose pose;
    cub_vec3 far = {0, 0, 0}, toe_far = {0, 0, MM(140)};
    assert_int_equal(cub_gait_leg_solve(&leg, NULL, far, toe_far, &pose), CUB_OK);
    assert_true(pose.corrected & CUB_GAIT_LEG_REACH);
    assert_true(pose.knee_rad <= DEG(175) + 100);
    assert_true(pose.knee_rad >= DEG(170));
    cub_vec3 straight = {0, MM(21), 0}, toe_s = {0, MM(21), MM(140)}; /* 879 mm: 178 degrees */
    assert_int_equal(cub_gait_leg_solve(&leg, NULL, straight, toe_s, &pose), CUB_OK);
    assert_true(pose.knee_rad <= DEG(175) + 100);
    cub_vec3 near = {0, MM(850), MM(100)}, toe_n = {0, MM(850), MM(240)};
    assert_int_equal(cub_gait_leg_solve(&leg, NULL, near, toe_n, &pose), CUB_OK);
    assert_true(pose.knee_rad >= DEG(25) - 100);
    cub_vec3 ok = {0, MM(150), MM(150)}, toe_ok = {0, MM(120), MM(285)};
    assert_int_equal(cub_gait_leg_solve(&leg, NULL, ok, toe_ok, &pose), CUB_OK);
    assert_int_equal(pose.corrected, 0);
    assert_true(dist(pose.ankle_mm, ok) < 0.1);
    assert_true(dist(pose.toe_mm, toe_ok) < 0.1);
    assert_true(fabs(dist(pose.knee_mm, leg.hip_mm) - 450) < 0.1);
    assert_true(fabs(dist(pose.knee_mm, pose.ankle_mm) - 430) < 0.1);
    assert_true(pose.knee_mm.z > 0); /* toward the pole */
}

/* The ankle: a foot pointed down the shin, or back up it, is turned to
 * the nearest end of its range (35..150 degrees by default, or the
 * caller's), keeping its length. */
static void test_leg_ik_keeps_the_ankle_in_range(void **state)
{
    (void)state;
    cub_gait_leg_pose pose;
    cub_vec3 ankle = {0, MM(150), MM(150)};
    cub_vec3 down = {0, MM(10), MM(150)}, up = {0, MM(290), MM(150)};
    assert_int_equal(cub_gait_leg_solve(&leg, NULL, ankle, down, &pose), CUB_OK);
    assert_true(pose.corrected & CUB_GAIT_LEG_ANKLE);
    assert_in_range(pose.ankle_rad, DEG(35) - 200, DEG(35) + 200);
    assert_true(fabs(dist(pose.toe_mm, pose.ankle_mm) - 140) < 0.2);
    assert_int_equal(cub_gait_leg_solve(&leg, NULL, ankle, up, &pose), CUB_OK);
    assert_in_range(pose.ankle_rad, DEG(150) - 200, DEG(150) + 200);
    cub_gait_leg_limits lim = {0, 0, DEG(70), DEG(110)};
    cub_vec3 flat = {0, MM(150), MM(290)};
    assert_int_equal(cub_gait_leg_solve(&leg, &lim, ankle, flat, &pose), CUB_OK);
    assert_true(pose.ankle_rad >= DEG(70) - 200 && pose.ankle_rad <= DEG(110) + 200);
}

/* The pelvis lowers so both feet reach: a left ankle target 90 cm under
 * its hip needs the hips ~21 mm lower (reach 878.9 mm at 175 degrees);
 * lowered by that the leg reaches it uncorrected, by 5 mm less it does not. */
static void test_pelvis_lowers_so_both_feet_reach(void **state)
{
    (void)state;
    cub_gait_leg legs[2] = {leg, leg};
    legs[0].hip_mm.x = MM(100);
    legs[1].hip_mm.x = MM(-100);
    legs[0].pole_mm.x = MM(100);
    legs[1].pole_mm.x = MM(-100);
    cub_vec3 targets[2] = {{MM(100), 0, 0}, {MM(-100), MM(100), 0}};
    cub_q16 drop = cub_gait_pelvis_drop(legs, NULL, targets);
    assert_in_range(drop, MM(20), MM(22));
    cub_gait_leg_pose pose;
    cub_gait_leg low = legs[0];
    low.hip_mm.y -= drop + MM(1);
    low.pole_mm.y -= drop + MM(1);
    cub_vec3 toe = {MM(100), 0, MM(140)};
    assert_int_equal(cub_gait_leg_solve(&low, NULL, targets[0], toe, &pose), CUB_OK);
    assert_false(pose.corrected & CUB_GAIT_LEG_REACH);
    low = legs[0];
    low.hip_mm.y -= drop - MM(5);
    assert_int_equal(cub_gait_leg_solve(&low, NULL, targets[0], toe, &pose), CUB_OK);
    assert_true(pose.corrected & CUB_GAIT_LEG_REACH);
    /* Both within reach already: no drop. */
    targets[0].y = MM(100);
    assert_int_equal(cub_gait_pelvis_drop(legs, NULL, targets), 0);
}

/* ---- phase analysis: flickers ------------------------------------------------ */

#define PH_FRAMES 240

/* A made walk at 120 fps: both points down until 100, the ankle rising
 * (lift) until 130 while the toe stays, both up and moving on (off) until
 * 180, then both down again. The toe flickers twice at the lift's end
 * (up 30 mm at 120 and at 122: two up runs with one down frame between,
 * the train CMU 07_01's toe makes). */
static void flicker_walk(cub_vec3 *ankle, cub_vec3 *toe)
{
    for (int f = 0; f < PH_FRAMES; f++) {
        int swing = f >= 131 && f < 180, lift = f >= 100 && f <= 130;
        int x = f < 131 ? 0 : (f < 180 ? 20 * (f - 130) : 20 * 49);
        int ay = swing ? 200 : (lift ? 80 + 2 * (f - 100) : 80);
        int ty = swing ? 100 : (f == 120 || f == 122 ? 50 : 20);
        ankle[f] = (cub_vec3){MM(x), MM(ay), 0};
        toe[f] = (cub_vec3){MM(x + 130), MM(ty), 0};
    }
}

/* The contact debounce merges the train: one foot-off, after the lift. */
static void test_flicker_train_is_one_foot_off(void **state)
{
    (void)state;
    static cub_vec3 ankle[PH_FRAMES], toe[PH_FRAMES];
    static uint8_t ph[PH_FRAMES];
    flicker_walk(ankle, toe);
    cub_gait_foot foot;
    assert_int_equal(cub_gait_analyse(ankle, toe, PH_FRAMES, NULL, ph, &foot), CUB_OK);
    int offs = 0;
    for (int f = 1; f < PH_FRAMES; f++)
        offs += ph[f] == CUB_GAIT_OFF && ph[f - 1] != CUB_GAIT_OFF;
    assert_int_equal(offs, 1);
    for (int f = 100; f < 129; f++) /* 129-130: the made swing's jump already moves them */
        assert_int_not_equal(ph[f], CUB_GAIT_OFF);
    assert_int_equal(ph[125], CUB_GAIT_LIFT);
    assert_int_equal(ph[140], CUB_GAIT_OFF);
}

/* The key configuration's rule: a quarter of the height difference,
 * either way, capped at a 200 mm step. */
static void test_key_pelvis_by_height_difference(void **state)
{
    (void)state;
    assert_int_equal(cub_gait_key_pelvis(0), 0);
    assert_int_equal(cub_gait_key_pelvis(MM(100)), -MM(25));
    assert_int_equal(cub_gait_key_pelvis(-MM(100)), -MM(25));
    assert_int_equal(cub_gait_key_pelvis(MM(400)), -MM(50));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_terrain_heights),
        cmocka_unit_test(test_obstacles_raise_the_ground),
        cmocka_unit_test(test_plan_on_flat_ground),
        cmocka_unit_test(test_blocked_foothold_forces_a_backtrack),
        cmocka_unit_test(planner_run_a_test_at_a_time),
        cmocka_unit_test(test_first_feasible_step_is_taken),
        cmocka_unit_test(test_foothold_beside_a_stone_is_refused),
        cmocka_unit_test(test_swing_clears_a_stone_by_the_foothold),
        cmocka_unit_test(test_dead_end_stops_the_walk),
        cmocka_unit_test(test_bezier_ends_and_line),
        cmocka_unit_test(test_swing_clears_a_log),
        cmocka_unit_test(test_swing_clears_a_plank_between_samples),
        cmocka_unit_test(test_foothold_too_near_an_obstacle_is_refused),
        cmocka_unit_test(test_leg_ik_keeps_the_knee_in_range),
        cmocka_unit_test(test_leg_ik_keeps_the_ankle_in_range),
        cmocka_unit_test(test_pelvis_lowers_so_both_feet_reach),
        cmocka_unit_test(test_flicker_train_is_one_foot_off),
        cmocka_unit_test(test_key_pelvis_by_height_difference),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* The tracker's resolvers (firmware/track/trk_resolve.c), each on a small
 * synthetic pose: a flat-layered body painted straight onto the tracker's
 * 160x120 grid (each part a capsule in the image's plane at one depth),
 * the geodesic paths from the torso run by the tracker's own trk_extrema,
 * the body's frame set by hand (upright, facing the camera, 1200 mm tall,
 * 2 m away, the floor 800 mm below the camera). Each test looks its
 * resolver up by name in the table and checks what it corrects, and that
 * it leaves a pose without its case alone: it fails when the resolver is
 * removed from the table or no longer does its job. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "trk_body.h"

#define ST 1200    /* stature, mm */
#define Z 2000     /* the body's depth */
#define FLOOR -800 /* the floor's height (y) */

#include "tracker_fixture.h"

/* An empty grid with a floor (up = +y). */
static void new_scene(void)
{
    memset(t->z, 0, sizeof t->z);
    memset(t->x, 0, sizeof t->x);
    memset(t->y, 0, sizeof t->y);
    memset(t->mask, 0, sizeof t->mask);
    t->up = (cub_vec3){0, CUB_Q16_ONE, 0};
    t->have_floor = true;
    t->floor_h_mm = FLOOR;
    t->have_prev = false;
    memset(t->reach_mm, 0, sizeof t->reach_mm);
}

/* A capsule from (ax, ay) to (bx, by) of radius r in the image's plane
 * at depth z: the player's cells it covers, nearer parts in front. */
static void paint(int32_t ax, int32_t ay, int32_t bx, int32_t by, int32_t r, int32_t z)
{
    int32_t dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
    for (int32_t i = 0; i < TRK_CELLS; i++) {
        if (t->z[i] && t->z[i] <= z) continue;
        int32_t gx = i % TRK_GW, gy = i / TRK_GW;
        int32_t x = (gx * TRK_CELL_PX + 2 - CUB_KINECT_CX) * z / CUB_KINECT_FOCAL_PX;
        int32_t y = (CUB_KINECT_CY - gy * TRK_CELL_PX - 2) * z / CUB_KINECT_FOCAL_PX;
        /* the nearest point of the segment, at u/1024 along it */
        int32_t u = 0;
        if (l2 > 0)
            u = (int32_t)cub_fx_clamp(
                (int32_t)(((int64_t)(x - ax) * dx + (int64_t)(y - ay) * dy) * 1024 / l2), 0, 1024);
        int32_t ex = x - ax - dx * u / 1024, ey = y - ay - dy * u / 1024;
        if (ex * ex + ey * ey >= r * r) continue;
        t->z[i] = (int16_t)z, t->x[i] = x, t->y[i] = y, t->mask[i] = 1;
    }
}

/* Head, torso and two legs apart, standing on the floor. */
static void paint_body(void)
{
    paint(0, 330, 0, 330, 90, Z);
    paint(0, 200, 0, -150, 140, Z);
    paint(-50, -150, -60, -755, 45, Z);
    paint(50, -150, 60, -755, 45, Z);
}

/* The right arm held out level: its hand is a plain extremity. */
static void paint_right_arm_out(void)
{
    paint(140, 150, 520, 150, 35, Z);
}

/* The player's cell nearest (x, y, z) (z 0: any depth, nearest in x, y). */
static int32_t cell_near(int32_t x, int32_t y, int32_t z)
{
    int32_t best = -1;
    int64_t best_d = INT64_MAX;
    for (int32_t i = 0; i < TRK_CELLS; i++) {
        if (!t->mask[i] || (z && t->z[i] != z)) continue;
        int64_t dx = t->x[i] - x, dy = t->y[i] - y, d = dx * dx + dy * dy;
        if (d < best_d) best_d = d, best = i;
    }
    assert_true(best >= 0);
    return best;
}

/* The body's frame of paint_body, and the paths from its root. */
static trk_frame frame_of_body(void)
{
    trk_frame f = {
        .t = t,
        .root = cell_near(0, 20, Z),
        .st = ST,
        .head = 0,
        .head_c = {0, 330, Z},
        .sc = {0, 160, Z},
        .sj = {0, 170, Z},
        .hc = {0, 160 - ST * P_HIPC / 1000, Z},
        .axis = {0, CUB_Q16_ONE, 0},
        .lat = {CUB_Q16_ONE, 0, 0},
        .lft = {-CUB_Q16_ONE, 0, 0}, /* the player's left at smaller x (TRK_LEFT_SIGN) */
        .down = {0, CUB_Q16_ONE, 0},
        .arm_root = {{-150, 160, Z}, {150, 160, Z}},
        .fit_root = {{-150, 170, Z}, {150, 170, Z}},
        .joint_half = 120,
        .reach_mm = ST * (P_UPPER_ARM + P_FOREARM + P_HAND_REACH) / 1000,
        .on_floor = true,
    };
    int32_t ext[TRK_MAX_EXTREMA];
    trk_extrema(t, f.root, 150, ext, TRK_MAX_EXTREMA);
    return f;
}

/* paint_body with the right arm held out, its frame and paths. */
static trk_frame body_right_arm_out(void)
{
    new_scene();
    paint_body();
    paint_right_arm_out();
    return frame_of_body();
}

static limb_pick no_pick(void)
{
    return (limb_pick){.hand = {-1, -1}, .foot = {-1, -1}, .elbow = {-1, -1}, .hang = {-1, -1}};
}

/* The resolver of that name in the table (a test fails if it is gone). */
static trk_resolver resolver(const char *name)
{
    int32_t n;
    const trk_resolver_entry *r = trk_resolvers(&n);
    for (int32_t k = 0; k < n; k++)
        if (!strcmp(r[k].name, name)) return r[k].run;
    fail_msg("no resolver %s in the table", name);
    return NULL;
}

/* The table: every resolver, in the order and at the stage it runs. */
static void test_table_order(void **st)
{
    (void)st;
    static const struct {
        const char *name;
        trk_stage stage;
    } want[] = {
        {"bow", TRK_AT_FRAME},
        {"raised_foot_is_hand", TRK_AT_CLASSIFIED},
        {"knee_is_no_hand", TRK_AT_FEET},
        {"surface_reach", TRK_AT_COSTED},
        {"path_from_across", TRK_AT_COSTED},
        {"shoulder_bump", TRK_AT_COSTED},
        {"bow_shoulder_top", TRK_AT_COSTED},
        {"skull_bump", TRK_AT_COSTED},
        {"legs_together", TRK_AT_NAMED},
        {"hand_before_torso", TRK_AT_NAMED},
        {"fist_beyond_elbow", TRK_AT_NAMED},
        {"hanging_arm", TRK_AT_NAMED},
    };
    int32_t n;
    const trk_resolver_entry *r = trk_resolvers(&n);
    assert_int_equal(n, sizeof want / sizeof *want);
    for (int32_t k = 0; k < n; k++) {
        assert_string_equal(r[k].name, want[k].name);
        assert_int_equal(r[k].stage, want[k].stage);
        assert_non_null(r[k].run);
    }
}

/* bow: the head's centre 120 mm before the torso's surface is a body
 * bent toward the camera; level with it, or no head, is not. */
static void test_bow(void **st)
{
    (void)st;
    new_scene();
    paint_body();
    trk_frame f = frame_of_body();
    limb_pick lp = no_pick();
    f.head_c.z = Z - 120;
    assert_true(resolver("bow")(&f, &lp));
    assert_true(lp.bent);
    f.head_c.z = Z + 40;
    assert_false(resolver("bow")(&f, &lp));
    assert_false(lp.bent);
    f.head_c.z = Z - 120, f.head = -1;
    assert_false(resolver("bow")(&f, &lp));
}

/* raised_foot_is_hand: an extremity classed a leg's but within an arm's
 * reach of the left shoulder and 900 mm above the floor (a hand hanging
 * against the hip joins the torso low) is an arm's; the foot on the floor
 * stays a leg's; without a floor nothing is reclassed. */
static void test_raised_foot_is_hand(void **st)
{
    (void)st;
    new_scene();
    paint_body();
    paint(-150, 150, -380, 100, 35, Z);
    trk_frame f = frame_of_body();
    limb_pick lp = no_pick();
    lp.cand[0] = cell_near(-400, 100, Z), lp.cand[1] = cell_near(-60, -800, Z), lp.ncand = 2;
    lp.limb[0] = lp.limb[1] = TRK_LEG;
    t->have_floor = false;
    assert_false(resolver("raised_foot_is_hand")(&f, &lp));
    assert_int_equal(lp.limb[0], TRK_LEG);
    t->have_floor = true;
    assert_true(resolver("raised_foot_is_hand")(&f, &lp));
    assert_int_equal(lp.limb[0], TRK_ARM);
    assert_int_equal(lp.limb[1], TRK_LEG);
}

/* knee_is_no_hand: the left leg raised aside with its knee bent; the
 * knee's outer tip, a candidate hand, lies by the foot's path and its
 * knee: no hand. The right hand held out stays a candidate. */
static void test_knee_is_no_hand(void **st)
{
    (void)st;
    new_scene();
    paint(0, 330, 0, 330, 90, Z);
    paint(0, 200, 0, -150, 140, Z);
    paint(-50, -150, -300, -330, 50, Z);
    paint(-300, -330, -300, -755, 45, Z);
    paint(50, -150, 60, -755, 45, Z);
    paint_right_arm_out();
    trk_frame f = frame_of_body();
    limb_pick lp = no_pick();
    lp.foot[0] = cell_near(-300, -800, Z), lp.foot[1] = cell_near(60, -800, Z);
    lp.cand[0] = cell_near(-340, -340, Z), lp.cand[1] = cell_near(560, 150, Z), lp.ncand = 2;
    lp.limb[0] = lp.limb[1] = TRK_ARM;
    assert_true(resolver("knee_is_no_hand")(&f, &lp));
    assert_int_equal(lp.limb[0], TRK_NEITHER);
    assert_int_equal(lp.limb[1], TRK_ARM);
    /* with no foot named there is no leg to be on */
    lp = no_pick();
    lp.cand[0] = cell_near(-340, -340, Z), lp.ncand = 1, lp.limb[0] = TRK_ARM;
    assert_false(resolver("knee_is_no_hand")(&f, &lp));
    assert_int_equal(lp.limb[0], TRK_ARM);
}

/* The hands' naming with these candidate cells, each costing 0 on both
 * sides, far from both shoulders along the surface and leaving the torso
 * on its own side; the last one out of the right arm's reach. */
static void naming_of(limb_pick *lp, const int32_t *cells, int32_t n)
{
    lp->nm.n = n;
    for (int side = 0; side < 2; side++) {
        for (int32_t k = 0; k < n; k++) {
            lp->nm.cell[k] = cells[k];
            lp->nm.cost[side][k] = 0;
            lp->nm.gs[side][k] = lp->nm.go[side][k] = 400;
            lp->nm.le[side][k] = 100;
        }
        lp->nm.cost[side][n] = -ST / 10;
    }
    lp->nm.cost[1][n - 1] = INT32_MAX;
}

/* The first candidate paid cost on both sides, the second nothing. */
static void expect_first_paid(const limb_pick *lp, int32_t cost)
{
    assert_int_equal(lp->nm.cost[0][0], cost);
    assert_int_equal(lp->nm.cost[1][0], cost);
    assert_int_equal(lp->nm.cost[0][1], 0);
}

/* surface_reach: a candidate 1000 mm along the surface from its
 * shoulder (more than 1.5 times the 480 mm reach) is out of that arm's
 * reach, though near in a straight line; a fist 300 mm nearer the camera
 * than the shoulder (an arm pointing at it) is held to the straight line
 * only; a candidate within reach stays. */
static void test_surface_reach(void **st)
{
    (void)st;
    trk_frame f = body_right_arm_out();
    paint(-200, 60, -200, 60, 40, Z - 300);
    limb_pick lp = no_pick();
    const int32_t cells[3] = {cell_near(-80, -300, Z), cell_near(-200, 60, Z - 300),
                              cell_near(560, 150, Z)};
    naming_of(&lp, cells, 3);
    assert_false(resolver("surface_reach")(&f, &lp));
    lp.nm.gs[0][0] = lp.nm.gs[0][1] = 1000;
    assert_true(resolver("surface_reach")(&f, &lp));
    assert_int_equal(lp.nm.cost[0][0], INT32_MAX);
    assert_int_equal(lp.nm.cost[0][1], 0);
    assert_int_equal(lp.nm.cost[1][0], 0);
}

/* path_from_across: a candidate whose path leaves the torso 100 mm on
 * the other shoulder's side pays 400 per mille of stature for that side;
 * one leaving on its own side, or out of reach, pays nothing. */
static void test_path_from_across(void **st)
{
    (void)st;
    trk_frame f = body_right_arm_out();
    limb_pick lp = no_pick();
    const int32_t cells[2] = {cell_near(-80, 0, Z), cell_near(560, 150, Z)};
    naming_of(&lp, cells, 2);
    assert_false(resolver("path_from_across")(&f, &lp));
    lp.nm.le[0][0] = -100, lp.nm.le[1][1] = -100;
    assert_true(resolver("path_from_across")(&f, &lp));
    assert_int_equal(lp.nm.cost[0][0], ST * 400 / 1000);
    assert_int_equal(lp.nm.cost[1][0], 0);
    assert_int_equal(lp.nm.cost[0][1], 0);
    assert_int_equal(lp.nm.cost[1][1], INT32_MAX);
}

/* shoulder_bump: a candidate 100 mm along the surface from either
 * shoulder is a bump on it: 800 per mille of stature, on both sides. */
static void test_shoulder_bump(void **st)
{
    (void)st;
    new_scene();
    paint_body();
    trk_frame f = frame_of_body();
    limb_pick lp = no_pick();
    const int32_t cells[3] = {cell_near(-140, 190, Z), cell_near(0, -600, Z),
                              cell_near(60, -600, Z)};
    naming_of(&lp, cells, 3);
    assert_false(resolver("shoulder_bump")(&f, &lp));
    lp.nm.gs[0][0] = 100, lp.nm.go[1][0] = 100;
    assert_true(resolver("shoulder_bump")(&f, &lp));
    expect_first_paid(&lp, ST * 800 / 1000);
}

/* bow_shoulder_top: on a bow (the head 120 mm before the torso), a
 * candidate above the shoulder centre, over a shoulder and behind the
 * head's centre is the shoulder's top, far along the surface though it
 * is: it pays the bump's cost. Upright, or before the head (a hand at the
 * mouth), or already paid as a bump, it does not. */
static void test_bow_shoulder_top(void **st)
{
    (void)st;
    new_scene();
    paint_body();
    paint(-90, 230, -90, 230, 30, Z - 200);
    trk_frame f = frame_of_body();
    f.head_c.z = Z - 120;
    limb_pick lp = no_pick();
    const int32_t cells[3] = {cell_near(-130, 200, Z), cell_near(-90, 230, Z - 200),
                              cell_near(0, -600, Z)};
    naming_of(&lp, cells, 3);
    assert_false(resolver("bow_shoulder_top")(&f, &lp));
    assert_true(resolver("bow")(&f, &lp));
    assert_true(resolver("bow_shoulder_top")(&f, &lp));
    expect_first_paid(&lp, ST * 800 / 1000);
    assert_int_equal(lp.nm.cost[0][2], 0);
    naming_of(&lp, cells, 3);
    lp.nm.gs[0][0] = lp.nm.go[1][0] = 100; /* the left shoulder's distance, seen from each side */
    resolver("bow_shoulder_top")(&f, &lp);
    expect_first_paid(&lp, 0);
}

/* skull_bump: a candidate 60 mm from the head's centre is the skull's
 * side (or a bowed head's chin): 400 per mille of stature; away from the
 * head, or with no head, nothing. */
static void test_skull_bump(void **st)
{
    (void)st;
    trk_frame f = body_right_arm_out();
    limb_pick lp = no_pick();
    const int32_t cells[3] = {cell_near(60, 330, Z), cell_near(560, 150, Z), cell_near(0, -600, Z)};
    naming_of(&lp, cells, 3);
    f.head = -1;
    assert_false(resolver("skull_bump")(&f, &lp));
    f.head = 0;
    assert_true(resolver("skull_bump")(&f, &lp));
    expect_first_paid(&lp, ST * 400 / 1000);
}

/* legs_together: legs held together end in one extremity, named the
 * right foot; the left foot is the lowest cell on the left of the hips,
 * on the floor. Not standing on the floor, nothing is added. */
static void test_legs_together(void **st)
{
    (void)st;
    new_scene();
    paint(0, 330, 0, 330, 90, Z);
    paint(0, 200, 0, -150, 140, Z);
    paint(0, -150, 0, -720, 80, Z);
    trk_frame f = frame_of_body();
    limb_pick lp = no_pick();
    lp.foot[1] = cell_near(40, -800, Z);
    f.on_floor = false;
    assert_false(resolver("legs_together")(&f, &lp));
    assert_int_equal(lp.foot[0], -1);
    f.on_floor = true;
    assert_true(resolver("legs_together")(&f, &lp));
    int32_t c = lp.foot[0];
    assert_true(c >= 0);
    assert_true(t->x[c] < 0);
    assert_true(t->y[c] < -740);
    assert_int_equal(lp.foot[1], cell_near(40, -800, Z));
}

/* hand_before_torso: a left fist held 250 mm before the chest is no
 * extremity; with no left hand named, the fist is found. The right hand
 * out to the side is not on the torso and is kept; without the fist the
 * left side keeps no hand. */
static void test_hand_before_torso(void **st)
{
    (void)st;
    for (int fist = 0; fist < 2; fist++) {
        new_scene();
        paint_body();
        paint_right_arm_out();
        if (fist) paint(-80, 0, -80, 0, 50, Z - 250);
        trk_frame f = frame_of_body();
        limb_pick lp = no_pick();
        int32_t right = cell_near(560, 150, Z);
        lp.hand[1] = right;
        assert_int_equal(resolver("hand_before_torso")(&f, &lp), fist);
        assert_int_equal(lp.hand[1], right);
        if (!fist) {
            assert_int_equal(lp.hand[0], -1);
            continue;
        }
        assert_true(lp.hand[0] >= 0);
        assert_int_equal(t->z[lp.hand[0]], Z - 250);
    }
}

/* fist_beyond_elbow: the left forearm points at the camera; the arm's
 * path ends at the elbow (named the hand), the fist lies 200 mm nearer
 * the camera and farther from the shoulder: it becomes the hand, the
 * elbow is remembered. The right hand, with nothing beyond it, stays. */
static void test_fist_beyond_elbow(void **st)
{
    (void)st;
    new_scene();
    paint_body();
    paint(-150, 150, -300, 0, 35, Z);
    paint(-330, -30, -330, -30, 45, Z - 200);
    paint_right_arm_out();
    trk_frame f = frame_of_body();
    limb_pick lp = no_pick();
    int32_t elbow = cell_near(-300, 0, Z), right = cell_near(560, 150, Z);
    lp.hand[0] = elbow, lp.hand[1] = right;
    assert_true(resolver("fist_beyond_elbow")(&f, &lp));
    assert_int_equal(lp.elbow[0], elbow);
    assert_true(lp.hand[0] >= 0);
    assert_int_equal(t->z[lp.hand[0]], Z - 200);
    assert_int_equal(lp.hand[1], right);
    assert_int_equal(lp.elbow[1], -1);
}

/* fist_beyond_elbow, a guard: the left upper arm hangs forward, the
 * forearm stands upright before the chest and the fist is by the chin
 * (no extremity: the elbow ends the arm's path; at about the elbow's
 * depth and distance from the shoulder): the fist is the top of the cells
 * above the elbow. On a bowed body it is not looked for. */
static void test_guard_fist(void **st)
{
    (void)st;
    for (int bent = 0; bent < 2; bent++) {
        new_scene();
        paint_body();
        paint(-150, 150, -150, -10, 35, Z - 100);
        paint(-150, 20, -110, 185, 30, Z - 170);
        paint(-110, 185, -110, 185, 40, Z - 180);
        trk_frame f = frame_of_body();
        limb_pick lp = no_pick();
        lp.bent = bent;
        int32_t elbow = cell_near(-150, -30, Z - 100);
        lp.hand[0] = elbow;
        bool changed = resolver("fist_beyond_elbow")(&f, &lp);
        if (bent) {
            assert_false(changed);
            assert_int_equal(lp.hand[0], elbow);
            continue;
        }
        assert_true(changed);
        assert_int_equal(lp.elbow[0], elbow);
        assert_int_equal(t->z[lp.hand[0]], Z - 180);
        assert_true(t->y[lp.hand[0]] > 185);
    }
}

/* hanging_arm: the left arm hangs against the flank, no extremity and
 * not before the torso: its tip is the lowest of its cells within reach
 * beside the hips. A side with a hand is not looked at. */
static void test_hanging_arm(void **st)
{
    (void)st;
    new_scene();
    paint_body();
    paint(-175, 120, -185, -300, 35, Z);
    paint_right_arm_out();
    trk_frame f = frame_of_body();
    limb_pick lp = no_pick();
    lp.hand[1] = cell_near(560, 150, Z);
    assert_true(resolver("hanging_arm")(&f, &lp));
    int32_t c = lp.hang[0];
    assert_true(c >= 0);
    assert_true(t->x[c] < -145);
    assert_true(t->y[c] < -200);
    assert_int_equal(lp.hang[1], -1);
    lp.hand[0] = cell_near(-185, -300, Z);
    assert_false(resolver("hanging_arm")(&f, &lp));
    assert_int_equal(lp.hang[0], -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_table_order),         cmocka_unit_test(test_bow),
        cmocka_unit_test(test_raised_foot_is_hand), cmocka_unit_test(test_knee_is_no_hand),
        cmocka_unit_test(test_surface_reach),       cmocka_unit_test(test_path_from_across),
        cmocka_unit_test(test_shoulder_bump),       cmocka_unit_test(test_bow_shoulder_top),
        cmocka_unit_test(test_skull_bump),          cmocka_unit_test(test_legs_together),
        cmocka_unit_test(test_hand_before_torso),   cmocka_unit_test(test_fist_beyond_elbow),
        cmocka_unit_test(test_guard_fist),          cmocka_unit_test(test_hanging_arm),
    };
    return cmocka_run_group_tests(tests, tracker_fixture_open, tracker_fixture_close);
}

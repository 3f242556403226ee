/* test_motion_ik — the two-bone analytic IK (cub/motion.h): bad input,
 * a reachable target reached, an unreachable one clamped on its ray, the
 * elbow bent toward the pole, the fold and stretch limits, and the same on
 * a skeleton (an arm like the bear's) through forward kinematics. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <stdlib.h>

#include "cub/motion.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define Q16(x) ((cub_q16)lround((x) * 65536.0))
#define MM(x, y, z) ((cub_vec3){Q16(x), Q16(y), Q16(z)})

static cub_skeleton skel;
static cub_pose pose;

static double dist(cub_vec3 a, cub_vec3 b)
{
    double dx = (a.x - b.x) / 65536.0, dy = (a.y - b.y) / 65536.0, dz = (a.z - b.z) / 65536.0;
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* Inner angle at the middle joint, degrees. */
static double inner_deg(cub_vec3 root, const cub_ik_solution *s)
{
    double a = dist(root, s->mid_mm), b = dist(s->mid_mm, s->end_mm), c = dist(root, s->end_mm);
    return acos((a * a + b * b - c * c) / (2 * a * b)) * 180.0 / M_PI;
}

static void test_bad_input(void **state)
{
    (void)state;
    cub_ik_solution s;
    cub_vec3 o = MM(0, 0, 0);
    assert_int_equal(cub_motion_ik_solve(o, 0, Q16(100), o, o, NULL, &s), CUB_ERR_ARG);
    assert_int_equal(cub_motion_ik_solve(o, Q16(100), -1, o, o, NULL, &s), CUB_ERR_ARG);
    assert_int_equal(cub_motion_ik_solve(o, Q16(100), Q16(100), o, o, NULL, NULL), CUB_ERR_ARG);
}

static void test_reachable_target_is_reached(void **state)
{
    (void)state;
    cub_vec3 root = MM(10, 500, -20), target = MM(-90, 380, 150), pole = MM(-200, 200, -50);
    cub_ik_solution s;
    assert_int_equal(cub_motion_ik_solve(root, Q16(150), Q16(135), target, pole, NULL, &s), CUB_OK);
    assert_int_equal(s.clamped, 0);
    assert_true(dist(s.end_mm, target) < 0.01);
    assert_true(fabs(dist(root, s.mid_mm) - 150) < 0.01);
    assert_true(fabs(dist(s.mid_mm, s.end_mm) - 135) < 0.01);
}

static void test_out_of_reach_clamps_on_the_ray(void **state)
{
    (void)state;
    cub_vec3 root = MM(0, 0, 0), target = MM(0, 0, 1000), pole = MM(0, -100, 0);
    cub_ik_solution s;
    assert_int_equal(cub_motion_ik_solve(root, Q16(150), Q16(135), target, pole, NULL, &s), CUB_OK);
    assert_int_equal(s.clamped, 1);
    /* 175 degrees: sqrt(150^2 + 135^2 - 2 150 135 cos 175) = 284.74 mm */
    assert_true(fabs(s.end_mm.z / 65536.0 - 284.74) < 0.05);
    assert_true(abs(s.end_mm.x) <= 2 && abs(s.end_mm.y) <= 2);
    assert_true(fabs(inner_deg(root, &s) - 175) < 0.1);
}

static void test_elbow_bends_toward_the_pole(void **state)
{
    (void)state;
    cub_vec3 root = MM(0, 0, 0), target = MM(200, 0, 0);
    cub_ik_solution down, back;
    cub_motion_ik_solve(root, Q16(150), Q16(135), target, MM(100, -300, 0), NULL, &down);
    cub_motion_ik_solve(root, Q16(150), Q16(135), target, MM(100, 0, -300), NULL, &back);
    assert_true(down.mid_mm.y < -Q16(50) && abs(down.mid_mm.z) <= 2);
    assert_true(back.mid_mm.z < -Q16(50) && abs(back.mid_mm.y) <= 2);
    /* A pole on the reach line itself still bends the chain somewhere. */
    cub_ik_solution on_line;
    cub_motion_ik_solve(root, Q16(150), Q16(135), target, MM(400, 0, 0), NULL, &on_line);
    assert_true(dist(on_line.end_mm, target) < 0.01);
    assert_true(fabs(dist(root, on_line.mid_mm) - 150) < 0.01);
}

static void test_fold_limit_holds(void **state)
{
    (void)state;
    cub_vec3 root = MM(0, 0, 0);
    cub_ik_limits lim = {Q16(60 * M_PI / 180), Q16(150 * M_PI / 180)};
    cub_ik_solution s;
    cub_motion_ik_solve(root, Q16(150), Q16(135), MM(5, 0, 0), MM(0, -100, 0), &lim, &s);
    assert_int_equal(s.clamped, 1);
    assert_true(fabs(inner_deg(root, &s) - 60) < 0.2);
    cub_motion_ik_solve(root, Q16(150), Q16(135), MM(0, 0, 400), MM(0, -100, 0), &lim, &s);
    assert_true(fabs(inner_deg(root, &s) - 150) < 0.2);
    /* A target at the root itself: no direction, still a valid fold. */
    cub_motion_ik_solve(root, Q16(150), Q16(135), root, MM(0, -100, 0), &lim, &s);
    assert_true(fabs(inner_deg(root, &s) - 60) < 0.2);
}

static void test_quat_between(void **state)
{
    (void)state;
    cub_vec3 from = MM(-1, 0, 0), to = MM(0, -3, 4);
    cub_vec3 got = cub_fx_quat_rotate(cub_motion_quat_between(from, to), MM(-100, 0, 0));
    assert_true(dist(got, MM(0, -60, 80)) < 0.01);
    got = cub_fx_quat_rotate(cub_motion_quat_between(from, MM(1, 0, 0)), MM(-100, 0, 0));
    assert_true(dist(got, MM(100, 0, 0)) < 0.01);
}

/* A right arm like the bear's: chest, shoulder, arm, forearm, hand. */
static void build_arm(void)
{
    cub_motion_skeleton_reset(&skel);
    int i;
    cub_motion_skeleton_add(&skel, "Chest", -1, MM(0, 525, 0), &i);
    cub_motion_skeleton_add(&skel, "RightShoulder", 0, MM(-45, 55, 0), &i);
    cub_motion_skeleton_add(&skel, "RightArm", 1, MM(-80, 0, 0), &i);
    cub_motion_skeleton_add(&skel, "RightForeArm", 2, MM(-150, 0, 0), &i);
    cub_motion_skeleton_add(&skel, "RightHand", 3, MM(-135, 0, 0), &i);
    cub_motion_skeleton_add(&skel, "RightHand_end", 4, MM(-60, 0, 0), &i);
    cub_motion_pose_rest(&skel, &pose);
}

static void test_apply_on_a_skeleton(void **state)
{
    (void)state;
    build_arm();
    cub_vec3 world[8];
    cub_vec3 target = MM(-180, 420, 160), pole = MM(-300, 300, -100);
    assert_int_equal(cub_motion_ik_apply(&skel, &pose, 4, target, pole, NULL, NULL), CUB_ERR_RANGE);
    /* a turned chest: the solve works in world space */
    pose.root_mm = MM(0, 525, 0); /* FK puts the root at root_mm */
    pose.rot[0] = cub_fx_quat_from_axis_angle(MM(0, 1, 0), Q16(0.3));
    cub_ik_solution s;
    assert_int_equal(cub_motion_ik_apply(&skel, &pose, 2, target, pole, NULL, &s), CUB_OK);
    cub_motion_forward(&skel, &pose, world, NULL);
    assert_true(dist(world[4], target) < 0.5);
    assert_true(dist(world[3], s.mid_mm) < 0.5);
    assert_true(world[3].y < world[2].y); /* the elbow hangs below the shoulder */
    /* solving again from the solved pose moves nothing */
    cub_vec3 again[8];
    cub_motion_ik_apply(&skel, &pose, 2, target, pole, NULL, NULL);
    cub_motion_forward(&skel, &pose, again, NULL);
    assert_true(dist(again[3], world[3]) < 0.01 && dist(again[5], world[5]) < 0.01);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_reachable_target_is_reached),
        cmocka_unit_test(test_out_of_reach_clamps_on_the_ray),
        cmocka_unit_test(test_elbow_bends_toward_the_pole),
        cmocka_unit_test(test_fold_limit_holds),
        cmocka_unit_test(test_quat_between),
        cmocka_unit_test(test_apply_on_a_skeleton),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

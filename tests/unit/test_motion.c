/* test_motion — skeletons, forward kinematics, clips and sampling: bad input
 * first, then behaviour, then FK against a double reference and a
 * determinism hash that must be the same on x86-64 and aarch64. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/motion.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define Q16(x) ((cub_q16)lround((x)*65536.0))
#define MM(x, y, z) ((cub_vec3){Q16(x), Q16(y), Q16(z)})

static double to_d(cub_q16 v)
{
    return v / 65536.0;
}

/* Shared by the tests; static so the big structs stay off the stack. */
static cub_skeleton skel;
static cub_pose pose, pose2, pose3;
static cub_vec3 world[CUB_MOTION_MAX_JOINTS];
static uint8_t clip_mem[1 << 20];

/* A fixed integer pseudo-random stream (splitmix64): the same scene on
 * every CPU, with no floating point involved. */
static uint64_t rng_state;
static uint64_t rng_next(void)
{
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}
/* Uniform integer in [lo, hi]. */
static int32_t rng_int(int32_t lo, int32_t hi)
{
    return lo + (int32_t)(rng_next() % (uint64_t)((int64_t)hi - lo + 1));
}

static cub_quat random_rot(void)
{
    cub_vec3 axis = {rng_int(-65536, 65536), rng_int(-65536, 65536), rng_int(-65536, 65536)};
    return cub_fx_quat_from_axis_angle(axis, rng_int(-CUB_Q16_PI, CUB_Q16_PI));
}

/* A random tree: each joint hangs off any earlier one, bones 20..400 mm. */
static void random_skeleton(int n)
{
    cub_motion_skeleton_reset(&skel);
    for (int i = 0; i < n; i++) {
        char name[16];
        snprintf(name, sizeof name, "j%d", i);
        cub_vec3 off = {rng_int(-Q16(400), Q16(400)), rng_int(-Q16(400), Q16(400)),
                        rng_int(-Q16(400), Q16(400))};
        int idx;
        assert_int_equal(
            cub_motion_skeleton_add(&skel, name, i == 0 ? -1 : rng_int(0, i - 1), off, &idx),
            CUB_OK);
    }
}

static void random_pose(cub_pose *p)
{
    cub_motion_pose_rest(&skel, p);
    p->root_mm = (cub_vec3){rng_int(-Q16(2000), Q16(2000)), rng_int(0, Q16(1000)),
                            rng_int(-Q16(3000), Q16(3000))};
    for (int i = 0; i < skel.joint_count; i++)
        p->rot[i] = random_rot();
}

static int poses_equal(const cub_pose *a, const cub_pose *b)
{
    int n = a->joint_count;
    return n == b->joint_count && a->has_trans == b->has_trans &&
           memcmp(&a->root_mm, &b->root_mm, sizeof a->root_mm) == 0 &&
           memcmp(a->rot, b->rot, (size_t)n * sizeof a->rot[0]) == 0 &&
           (!a->has_trans ||
            memcmp(a->trans_mm, b->trans_mm, (size_t)n * sizeof a->trans_mm[0]) == 0);
}

/* ---- bad input ------------------------------------------------------------ */

static void test_skeleton_add_rejects_bad_input(void **state)
{
    int idx = 77;
    cub_motion_skeleton_reset(&skel);
    assert_int_equal(cub_motion_skeleton_add(NULL, "a", -1, MM(0, 0, 0), &idx), CUB_ERR_ARG);
    assert_int_equal(cub_motion_skeleton_add(&skel, NULL, -1, MM(0, 0, 0), &idx), CUB_ERR_ARG);
    assert_int_equal(cub_motion_skeleton_add(&skel, "", -1, MM(0, 0, 0), &idx), CUB_ERR_ARG);
    assert_int_equal(
        cub_motion_skeleton_add(&skel, "0123456789abcdef0123456789abcdef", -1, MM(0, 0, 0), &idx),
        CUB_ERR_ARG); /* 32 characters: no room for the NUL */
    assert_int_equal(cub_motion_skeleton_add(&skel, "root", 0, MM(0, 0, 0), &idx), CUB_ERR_ARG);
    assert_int_equal(idx, 77);
    assert_int_equal(skel.joint_count, 0);
    assert_int_equal(
        cub_motion_skeleton_add(&skel, "0123456789abcdef0123456789abcde", -1, MM(0, 0, 0), &idx),
        CUB_OK); /* 31 characters fit */
    assert_int_equal(cub_motion_skeleton_add(&skel, "second_root", -1, MM(0, 0, 0), &idx),
                     CUB_ERR_ARG);
    assert_int_equal(cub_motion_skeleton_add(&skel, "self", 1, MM(0, 0, 0), &idx), CUB_ERR_ARG);
    assert_int_equal(cub_motion_skeleton_add(&skel, "far", 9, MM(0, 0, 0), &idx), CUB_ERR_ARG);
    assert_int_equal(skel.joint_count, 1);
    skel.joints[0].is_end_site = 1;
    assert_int_equal(cub_motion_skeleton_add(&skel, "under_end", 0, MM(0, 0, 0), &idx),
                     CUB_ERR_ARG);
    skel.joints[0].is_end_site = 0;
    assert_int_equal(cub_motion_skeleton_add(&skel, "0123456789abcdef0123456789abcde", 0,
                                             MM(0, 0, 0), &idx),
                     CUB_ERR_ARG); /* names are unique */
    for (int i = 1; i < CUB_MOTION_MAX_JOINTS; i++) {
        char name[8];
        snprintf(name, sizeof name, "j%d", i);
        assert_int_equal(cub_motion_skeleton_add(&skel, name, i - 1, MM(0, 1, 0), NULL), CUB_OK);
    }
    assert_int_equal(cub_motion_skeleton_add(&skel, "one_too_many", 0, MM(0, 0, 0), &idx),
                     CUB_ERR_FULL);
    assert_int_equal(cub_motion_skeleton_validate(&skel), CUB_OK);
}

static void test_skeleton_validate_finds_broken_invariants(void **state)
{
    assert_int_equal(cub_motion_skeleton_validate(NULL), CUB_ERR_ARG);
    cub_motion_skeleton_reset(&skel);
    assert_int_equal(cub_motion_skeleton_validate(&skel), CUB_ERR_FORMAT); /* no root */
    assert_int_equal(cub_motion_skeleton_add(&skel, "root", -1, MM(0, 0, 0), NULL), CUB_OK);
    assert_int_equal(cub_motion_skeleton_add(&skel, "a", 0, MM(0, 10, 0), NULL), CUB_OK);
    assert_int_equal(cub_motion_skeleton_add(&skel, "b", 1, MM(0, 10, 0), NULL), CUB_OK);
    assert_int_equal(cub_motion_skeleton_validate(&skel), CUB_OK);
    skel.joints[1].parent = 2; /* child before parent */
    assert_int_equal(cub_motion_skeleton_validate(&skel), CUB_ERR_FORMAT);
    assert_int_equal(cub_motion_forward(&skel, &pose, world, NULL), CUB_ERR_ARG); /* pose not set */
    cub_motion_pose_rest(&skel, &pose);
    assert_int_equal(cub_motion_forward(&skel, &pose, world, NULL), CUB_ERR_FORMAT);
    skel.joints[1].parent = -1; /* a second root */
    assert_int_equal(cub_motion_skeleton_validate(&skel), CUB_ERR_FORMAT);
    assert_int_equal(cub_motion_forward(&skel, &pose, world, NULL), CUB_ERR_FORMAT);
    skel.joints[1].parent = 0;
    memset(skel.joints[2].name, 'x', CUB_MOTION_NAME_LEN); /* unterminated name */
    assert_int_equal(cub_motion_skeleton_validate(&skel), CUB_ERR_FORMAT);
    strcpy(skel.joints[2].name, "b");
    skel.joints[1].is_end_site = 1; /* an end site with a child */
    assert_int_equal(cub_motion_skeleton_validate(&skel), CUB_ERR_FORMAT);
    skel.joints[1].is_end_site = 0;
    skel.joint_count = CUB_MOTION_MAX_JOINTS + 1;
    assert_int_equal(cub_motion_skeleton_validate(&skel), CUB_ERR_FORMAT);
    assert_int_equal(cub_motion_forward(&skel, &pose, world, NULL), CUB_ERR_ARG);
    skel.joint_count = 3;
    assert_int_equal(cub_motion_skeleton_find(&skel, "b"), 2);
    assert_int_equal(cub_motion_skeleton_find(&skel, "nope"), -1);
    assert_int_equal(cub_motion_skeleton_find(NULL, "b"), -1);
    assert_int_equal(cub_motion_skeleton_find(&skel, NULL), -1);
}

static void test_forward_rejects_null_and_mismatch(void **state)
{
    rng_state = 1;
    random_skeleton(5);
    cub_motion_pose_rest(&skel, &pose);
    assert_int_equal(cub_motion_forward(NULL, &pose, world, NULL), CUB_ERR_ARG);
    assert_int_equal(cub_motion_forward(&skel, NULL, world, NULL), CUB_ERR_ARG);
    assert_int_equal(cub_motion_forward(&skel, &pose, NULL, NULL), CUB_ERR_ARG);
    pose.joint_count = 4;
    assert_int_equal(cub_motion_forward(&skel, &pose, world, NULL), CUB_ERR_ARG);
    pose.joint_count = 5;
    assert_int_equal(cub_motion_forward(&skel, &pose, world, NULL), CUB_OK);
    cub_motion_pose_rest(&skel, &pose2);
    pose2.joint_count = 6;
    assert_int_equal(cub_motion_pose_blend(&pose, &pose2, 0, &pose3), CUB_ERR_ARG);
    pose2.joint_count = 5;
    pose2.has_trans = 1;
    assert_int_equal(cub_motion_pose_blend(&pose, &pose2, 0, &pose3), CUB_ERR_ARG);
    assert_int_equal(cub_motion_pose_blend(NULL, &pose2, 0, &pose3), CUB_ERR_ARG);
}

static void test_clip_rejects_bad_input(void **state)
{
    rng_state = 2;
    random_skeleton(4);
    cub_clip clip;
    assert_int_equal(cub_motion_clip_mem_size(0, 10, 0), 0);
    assert_int_equal(cub_motion_clip_mem_size(CUB_MOTION_MAX_JOINTS + 1, 10, 0), 0);
    assert_int_equal(cub_motion_clip_mem_size(4, 0, 0), 0);
    size_t need = cub_motion_clip_mem_size(4, 10, 1);
    assert_true(need >= 10 * (12 + 4 * (16 + 12)));
    assert_int_equal(cub_motion_clip_init(&clip, &skel, 10, 1000000, 1, clip_mem, need - 1),
                     CUB_ERR_NOMEM);
    assert_int_equal(cub_motion_clip_init(NULL, &skel, 10, 1000000, 1, clip_mem, need),
                     CUB_ERR_ARG);
    assert_int_equal(cub_motion_clip_init(&clip, NULL, 10, 1000000, 1, clip_mem, need),
                     CUB_ERR_ARG);
    assert_int_equal(cub_motion_clip_init(&clip, &skel, 10, 1000000, 1, NULL, need), CUB_ERR_ARG);
    assert_int_equal(cub_motion_clip_init(&clip, &skel, 0, 1000000, 1, clip_mem, need),
                     CUB_ERR_ARG);
    assert_int_equal(cub_motion_clip_init(&clip, &skel, 10, 0, 1, clip_mem, need), CUB_ERR_ARG);
    /* Any alignment of the buffer works: the clip aligns inside it. */
    assert_int_equal(cub_motion_clip_init(&clip, &skel, 10, 1000000, 1, clip_mem + 3, need),
                     CUB_OK);
    assert_int_equal((uintptr_t)clip.rot % 8, 0);
    assert_int_equal(cub_motion_clip_get_frame(&clip, -1, &pose), CUB_ERR_RANGE);
    assert_int_equal(cub_motion_clip_get_frame(&clip, 10, &pose), CUB_ERR_RANGE);
    assert_int_equal(cub_motion_clip_get_frame(NULL, 0, &pose), CUB_ERR_ARG);
    assert_int_equal(cub_motion_clip_get_frame(&clip, 0, NULL), CUB_ERR_ARG);
    assert_int_equal(cub_motion_clip_get_frame(&clip, 9, &pose), CUB_OK);
    assert_int_equal(cub_motion_clip_set_frame(&clip, 10, &pose), CUB_ERR_RANGE);
    pose.joint_count = 3;
    assert_int_equal(cub_motion_clip_set_frame(&clip, 0, &pose), CUB_ERR_ARG);
    assert_int_equal(cub_motion_sample(NULL, 0, CUB_MOTION_CLAMP, &pose), CUB_ERR_ARG);
    assert_int_equal(cub_motion_sample(&clip, 0, CUB_MOTION_CLAMP, NULL), CUB_ERR_ARG);
    assert_int_equal(cub_motion_sample(&clip, 0, (cub_motion_wrap)7, &pose), CUB_ERR_ARG);
    /* A clip without translations refuses a pose that has them. */
    assert_int_equal(cub_motion_clip_init(&clip, &skel, 10, 1000000, 0, clip_mem, need), CUB_OK);
    assert_null(clip.trans_mm);
    cub_motion_pose_rest(&skel, &pose);
    pose.has_trans = 1;
    assert_int_equal(cub_motion_clip_set_frame(&clip, 0, &pose), CUB_ERR_ARG);
    /* A skeleton that breaks its invariants cannot carry a clip. */
    skel.joints[2].parent = 3;
    assert_int_equal(cub_motion_clip_init(&clip, &skel, 10, 1000000, 0, clip_mem, need),
                     CUB_ERR_FORMAT);
}

/* ---- behaviour: forward kinematics ---------------------------------------- */

static void assert_near_mm(cub_vec3 got, double x, double y, double z, double tol)
{
    double e = fmax(fabs(to_d(got.x) - x), fmax(fabs(to_d(got.y) - y), fabs(to_d(got.z) - z)));
    if (e > tol)
        fail_msg("(%f %f %f) vs (%f %f %f)", to_d(got.x), to_d(got.y), to_d(got.z), x, y, z);
}

static void test_forward_three_joint_chain_by_hand(void **state)
{
    cub_motion_skeleton_reset(&skel);
    /* The root's offset is ignored: it stands at root_mm. */
    assert_int_equal(cub_motion_skeleton_add(&skel, "hips", -1, MM(7, 7, 7), NULL), CUB_OK);
    assert_int_equal(cub_motion_skeleton_add(&skel, "spine", 0, MM(0, 100, 0), NULL), CUB_OK);
    assert_int_equal(cub_motion_skeleton_add(&skel, "head", 1, MM(0, 50, 0), NULL), CUB_OK);
    cub_motion_pose_rest(&skel, &pose);
    cub_quat world_rot[3];
    assert_int_equal(cub_motion_forward(&skel, &pose, world, world_rot), CUB_OK);
    assert_near_mm(world[0], 0, 0, 0, 0);
    assert_near_mm(world[1], 0, 100, 0, 0);
    assert_near_mm(world[2], 0, 150, 0, 0);

    /* Root at (100, 0, 0) turned 90 degrees about z, spine another 90. */
    const cub_vec3 z = {0, 0, CUB_Q16_ONE};
    pose.root_mm = MM(100, 0, 0);
    pose.rot[0] = cub_fx_quat_from_axis_angle(z, CUB_Q16_HALF_PI);
    pose.rot[1] = cub_fx_quat_from_axis_angle(z, CUB_Q16_HALF_PI);
    assert_int_equal(cub_motion_forward(&skel, &pose, world, world_rot), CUB_OK);
    /* Rz90 (0,100,0) = (-100,0,0); Rz180 (0,50,0) = (0,-50,0). The Q16.16
     * pi/2 is 4.6e-6 rad long: 0.7 um at 150 mm, hence the tolerance. */
    assert_near_mm(world[0], 100, 0, 0, 0);
    assert_near_mm(world[1], 0, 0, 0, 2e-3);
    assert_near_mm(world[2], 0, -50, 0, 2e-3);
    assert_int_equal(cub_fx_quat_angle(world_rot[2]), CUB_Q16_PI);
    /* Without world_rot the positions are the same. */
    cub_vec3 again[3];
    assert_int_equal(cub_motion_forward(&skel, &pose, again, NULL), CUB_OK);
    assert_memory_equal(again, world, sizeof again);

    /* Animated translations replace the offsets (the root's is ignored). */
    pose.has_trans = 1;
    pose.trans_mm[0] = MM(1000, 1000, 1000);
    pose.trans_mm[1] = MM(0, 200, 0);
    pose.trans_mm[2] = MM(0, 0, 30);
    assert_int_equal(cub_motion_forward(&skel, &pose, world, NULL), CUB_OK);
    assert_near_mm(world[0], 100, 0, 0, 0);
    assert_near_mm(world[1], -100, 0, 0, 2e-3);
    assert_near_mm(world[2], -100, 0, 30, 2e-3);
}

typedef struct dq {
    double w, x, y, z;
} dq;

static dq dq_mul(dq a, dq b)
{
    return (dq){a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z,
                a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
                a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
                a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}

static dq dq_of(cub_quat q)
{
    dq d = {q.w, q.x, q.y, q.z};
    double n = sqrt(d.w * d.w + d.x * d.x + d.y * d.y + d.z * d.z);
    return (dq){d.w / n, d.x / n, d.y / n, d.z / n};
}

/* The same FK in doubles, from the same fixed-point inputs. */
static void reference_forward(const cub_pose *p, double (*out)[3])
{
    dq rot[CUB_MOTION_MAX_JOINTS];
    out[0][0] = to_d(p->root_mm.x), out[0][1] = to_d(p->root_mm.y), out[0][2] = to_d(p->root_mm.z);
    rot[0] = dq_of(p->rot[0]);
    for (int i = 1; i < skel.joint_count; i++) {
        int par = skel.joints[i].parent;
        cub_vec3 o = skel.joints[i].offset_mm;
        dq r = rot[par];
        dq v = dq_mul(dq_mul(r, (dq){0, to_d(o.x), to_d(o.y), to_d(o.z)}),
                      (dq){r.w, -r.x, -r.y, -r.z});
        out[i][0] = out[par][0] + v.x, out[i][1] = out[par][1] + v.y, out[i][2] = out[par][2] + v.z;
        rot[i] = dq_mul(rot[par], dq_of(p->rot[i]));
    }
}

static void test_forward_matches_double_reference(void **state)
{
    double max_err = 0, ref[CUB_MOTION_MAX_JOINTS][3];
    const int poses = 500;
    rng_state = 30;
    random_skeleton(30);
    for (int k = 0; k < poses; k++) {
        random_pose(&pose);
        assert_int_equal(cub_motion_forward(&skel, &pose, world, NULL), CUB_OK);
        reference_forward(&pose, ref);
        for (int i = 0; i < skel.joint_count; i++) {
            double e =
                fmax(fabs(to_d(world[i].x) - ref[i][0]),
                     fmax(fabs(to_d(world[i].y) - ref[i][1]), fabs(to_d(world[i].z) - ref[i][2])));
            if (e > max_err) max_err = e;
        }
    }
    printf("motion: fk max_abs_err=%.1e mm vs double, 30-joint random tree, bones <= 693 mm, "
           "%d random poses\n",
           max_err, poses);
    assert_true(max_err < 0.01);
}

/* ---- behaviour: clips, sampling, blending ---------------------------------- */

/* A clip of random frames on a random skeleton. */
static void random_clip(cub_clip *clip, int joints, int frames, uint32_t frame_ns, int with_trans)
{
    random_skeleton(joints);
    size_t need = cub_motion_clip_mem_size(joints, frames, with_trans);
    assert_true(need > 0 && need <= sizeof clip_mem);
    assert_int_equal(
        cub_motion_clip_init(clip, &skel, frames, frame_ns, with_trans, clip_mem, need), CUB_OK);
    for (int f = 0; f < frames; f++) {
        random_pose(&pose);
        if (with_trans) {
            pose.has_trans = 1;
            for (int i = 0; i < joints; i++)
                pose.trans_mm[i] =
                    (cub_vec3){rng_int(-Q16(300), Q16(300)), rng_int(-Q16(300), Q16(300)),
                               rng_int(-Q16(300), Q16(300))};
        }
        assert_int_equal(cub_motion_clip_set_frame(clip, f, &pose), CUB_OK);
    }
}

static void test_clip_starts_at_rest_and_round_trips(void **state)
{
    rng_state = 3;
    random_skeleton(6);
    cub_clip clip;
    size_t need = cub_motion_clip_mem_size(6, 4, 0);
    assert_int_equal(cub_motion_clip_init(&clip, &skel, 4, 8333333, 0, clip_mem, need), CUB_OK);
    cub_motion_pose_rest(&skel, &pose2);
    assert_int_equal(cub_motion_clip_get_frame(&clip, 3, &pose), CUB_OK);
    assert_true(poses_equal(&pose, &pose2));
    random_pose(&pose2);
    assert_int_equal(cub_motion_clip_set_frame(&clip, 2, &pose2), CUB_OK);
    assert_int_equal(cub_motion_clip_get_frame(&clip, 2, &pose), CUB_OK);
    assert_true(poses_equal(&pose, &pose2));
    /* 3 periods of 8333333 ns = 24999.999 us, rounded up. */
    assert_int_equal(cub_motion_clip_duration_us(&clip), 25000);
}

static void test_sample_on_frames_returns_frames(void **state)
{
    cub_clip clip;
    rng_state = 4;
    random_clip(&clip, 12, 8, 10000000, 1); /* 100 fps: frames on whole us */
    for (int f = 0; f < 8; f++) {
        assert_int_equal(cub_motion_clip_get_frame(&clip, f, &pose2), CUB_OK);
        assert_int_equal(cub_motion_sample(&clip, f * 10000LL, CUB_MOTION_CLAMP, &pose), CUB_OK);
        assert_true(poses_equal(&pose, &pose2));
        assert_int_equal(cub_motion_sample(&clip, f * 10000LL, CUB_MOTION_LOOP, &pose), CUB_OK);
        assert_true(poses_equal(&pose, &pose2));
    }
    /* At 120 fps frames fall between whole microseconds; the nearest
     * microsecond lands within 1/8333 of a frame of them. */
    rng_state = 5;
    random_clip(&clip, 12, 8, 8333333, 0);
    assert_int_equal(cub_motion_clip_get_frame(&clip, 5, &pose2), CUB_OK);
    assert_int_equal(cub_motion_sample(&clip, 41667, CUB_MOTION_CLAMP, &pose), CUB_OK);
    for (int i = 0; i < 12; i++) {
        cub_quat d = cub_fx_quat_mul(cub_fx_quat_conj(pose.rot[i]), pose2.rot[i]);
        assert_true(cub_fx_quat_angle(d) <= Q16(1e-3));
    }
}

static void test_sample_halfway_lies_between(void **state)
{
    cub_clip clip;
    rng_state = 6;
    random_clip(&clip, 10, 3, 10000000, 1);
    assert_int_equal(cub_motion_clip_get_frame(&clip, 1, &pose2), CUB_OK);
    assert_int_equal(cub_motion_clip_get_frame(&clip, 2, &pose3), CUB_OK);
    assert_int_equal(cub_motion_sample(&clip, 15000, CUB_MOTION_CLAMP, &pose), CUB_OK);
    assert_int_equal(pose.root_mm.x, cub_fx_lerp(pose2.root_mm.x, pose3.root_mm.x, CUB_Q16_HALF));
    for (int i = 0; i < 10; i++) {
        /* Halfway by nlerp is the geodesic midpoint: equal angles to both
         * ends, summing to the whole. */
        cub_q16 whole =
            cub_fx_quat_angle(cub_fx_quat_mul(cub_fx_quat_conj(pose2.rot[i]), pose3.rot[i]));
        cub_q16 to_a =
            cub_fx_quat_angle(cub_fx_quat_mul(cub_fx_quat_conj(pose2.rot[i]), pose.rot[i]));
        cub_q16 to_b =
            cub_fx_quat_angle(cub_fx_quat_mul(cub_fx_quat_conj(pose.rot[i]), pose3.rot[i]));
        assert_true(abs(to_a - to_b) <= 4);
        assert_true(abs(to_a + to_b - whole) <= 4);
        cub_vec3 tm = pose.trans_mm[i], ta = pose2.trans_mm[i], tb = pose3.trans_mm[i];
        assert_true((tm.y >= ta.y && tm.y <= tb.y) || (tm.y <= ta.y && tm.y >= tb.y));
    }
}

static void test_sample_loop_wraps_and_clamp_holds(void **state)
{
    cub_clip clip;
    rng_state = 7;
    random_clip(&clip, 8, 5, 8333333, 0);
    const int64_t loop_us = 41667; /* 5 periods = 41666.665 us */
    cub_pose *first = &pose2, *last = &pose3;
    assert_int_equal(cub_motion_clip_get_frame(&clip, 0, first), CUB_OK);
    assert_int_equal(cub_motion_clip_get_frame(&clip, 4, last), CUB_OK);
    /* CLAMP: before the start the first frame, from the end on the last. */
    const int64_t before[] = {-1, -1000000, INT64_MIN};
    for (int k = 0; k < 3; k++) {
        assert_int_equal(cub_motion_sample(&clip, before[k], CUB_MOTION_CLAMP, &pose), CUB_OK);
        assert_true(poses_equal(&pose, first));
    }
    const int64_t after[] = {cub_motion_clip_duration_us(&clip), 10000000, 3600000000LL * 5,
                             INT64_MAX};
    for (int k = 0; k < 4; k++) {
        assert_int_equal(cub_motion_sample(&clip, after[k], CUB_MOTION_CLAMP, &pose), CUB_OK);
        assert_true(poses_equal(&pose, last));
    }
    /* LOOP: between the last frame and the loop's end it blends back to
     * the first; whole loops later (hours, or negative) give the same
     * pose bit for bit, since the loop is 5 * 8333333 ns = 41666665 ns. */
    static cub_pose ref;
    const int64_t t = 38000; /* between frame 4 (33333 us) and the loop end */
    assert_int_equal(cub_motion_sample(&clip, t, CUB_MOTION_LOOP, &ref), CUB_OK);
    assert_false(poses_equal(&ref, last));
    /* 38000 us = 38000000 ns, 4666668 ns past frame 4 (at 33333332 ns). */
    const cub_q16 frac = (cub_q16)((4666668LL << 16) / 8333333);
    assert_int_equal(ref.root_mm.x, cub_fx_lerp(last->root_mm.x, first->root_mm.x, frac));
    const int64_t loops_us_x1000 = 41666665; /* one loop in ns = 1000 x us */
    for (int64_t n = -3; n <= 3; n++) {
        /* n * 1000 loops = n * 41666665 us exactly. */
        assert_int_equal(cub_motion_sample(&clip, t + n * loops_us_x1000, CUB_MOTION_LOOP, &pose),
                         CUB_OK);
        assert_true(poses_equal(&pose, &ref));
    }
    /* Five hours on (432 x 1000 loops = 18000 s): still the same pose. */
    assert_int_equal(cub_motion_sample(&clip, t + 432LL * loops_us_x1000, CUB_MOTION_LOOP, &pose),
                     CUB_OK);
    assert_true(poses_equal(&pose, &ref));
    assert_int_equal(cub_motion_sample(&clip, loop_us - 1, CUB_MOTION_LOOP, &pose), CUB_OK);
    assert_false(poses_equal(&pose, first));
    assert_int_equal(cub_motion_sample(&clip, INT64_MAX, CUB_MOTION_LOOP, &pose), CUB_OK);
    assert_int_equal(cub_motion_sample(&clip, INT64_MIN, CUB_MOTION_LOOP, &pose), CUB_OK);
    /* A one-frame clip is that frame at any time, in either mode. */
    rng_state = 8;
    random_clip(&clip, 4, 1, 8333333, 0);
    assert_int_equal(cub_motion_clip_get_frame(&clip, 0, first), CUB_OK);
    assert_int_equal(cub_motion_clip_duration_us(&clip), 0);
    const int64_t any[] = {-5, 0, 4000, 8333, 123456789, INT64_MAX, INT64_MIN};
    for (int k = 0; k < 7; k++) {
        assert_int_equal(cub_motion_sample(&clip, any[k], CUB_MOTION_LOOP, &pose), CUB_OK);
        assert_true(poses_equal(&pose, first));
        assert_int_equal(cub_motion_sample(&clip, any[k], CUB_MOTION_CLAMP, &pose), CUB_OK);
        assert_true(poses_equal(&pose, first));
    }
}

static void test_blend_endpoints_and_aliasing(void **state)
{
    rng_state = 9;
    random_skeleton(20);
    random_pose(&pose2);
    random_pose(&pose3);
    assert_int_equal(cub_motion_pose_blend(&pose2, &pose3, 0, &pose), CUB_OK);
    assert_true(poses_equal(&pose, &pose2));
    assert_int_equal(cub_motion_pose_blend(&pose2, &pose3, CUB_Q16_ONE, &pose), CUB_OK);
    assert_true(poses_equal(&pose, &pose3));
    assert_int_equal(cub_motion_pose_blend(&pose2, &pose3, -5, &pose), CUB_OK); /* clamped */
    assert_true(poses_equal(&pose, &pose2));
    assert_int_equal(cub_motion_pose_blend(&pose2, &pose3, CUB_Q16_HALF, &pose), CUB_OK);
    static cub_pose alias;
    alias = pose2;
    assert_int_equal(cub_motion_pose_blend(&alias, &pose3, CUB_Q16_HALF, &alias), CUB_OK);
    assert_true(poses_equal(&alias, &pose));
}

static void test_world_to_float(void **state)
{
    const cub_vec3 w[2] = {MM(1.5, -2.25, 1000), {CUB_Q16_MAX, CUB_Q16_MIN, 1}};
    float f[6];
    cub_motion_world_to_float(w, 2, f);
    assert_true(f[0] == 1.5f && f[1] == -2.25f && f[2] == 1000.0f);
    assert_true(f[4] == -32768.0f && f[5] == 1.0f / 65536.0f);
    cub_motion_world_to_float(NULL, 2, f); /* ignored, no crash */
}

/* ---- determinism across CPUs ---------------------------------------------- */

static uint64_t fnv1a_i32(uint64_t h, int32_t v)
{
    uint32_t u = (uint32_t)v;
    for (int b = 0; b < 4; b++) { /* little-endian bytes, whatever the CPU */
        h ^= (u >> (8 * b)) & 0xffu;
        h *= 0x100000001b3u;
    }
    return h;
}

/* The constant was printed by the x86-64 host build and by the aarch64
 * build under qemu-aarch64, which printed the same value; both must keep
 * matching it (any change to fx or motion rounding changes it: then re-run
 * both and update it only if they agree). */
#define SCENE_HASH 0x82c5bc58e44ee6bfull

static void test_fk_is_bit_identical_across_cpus(void **state)
{
    cub_clip clip;
    rng_state = 2024; /* a fixed scene: 60 joints, 40 frames at 120 fps */
    random_clip(&clip, 60, 40, 8333333, 1);
    uint64_t h = 0xcbf29ce484222325u;
    for (int k = 0; k < 400; k++) {
        int64_t t_us = (int64_t)k * 1237 - 20000;
        assert_int_equal(
            cub_motion_sample(&clip, t_us, k % 2 ? CUB_MOTION_LOOP : CUB_MOTION_CLAMP, &pose),
            CUB_OK);
        if (k % 5 == 0) {
            random_pose(&pose2);
            pose2.has_trans = 1;
            for (int i = 0; i < 60; i++)
                pose2.trans_mm[i] = pose.trans_mm[i];
            assert_int_equal(cub_motion_pose_blend(&pose, &pose2, (cub_q16)(k * 163), &pose),
                             CUB_OK);
        }
        assert_int_equal(cub_motion_forward(&skel, &pose, world, NULL), CUB_OK);
        for (int i = 0; i < 60; i++) {
            h = fnv1a_i32(h, world[i].x);
            h = fnv1a_i32(h, world[i].y);
            h = fnv1a_i32(h, world[i].z);
        }
    }
    printf("motion: scene hash fnv1a=0x%016llx (400 samples x 60 joints FK)\n",
           (unsigned long long)h);
    assert_int_equal(h, SCENE_HASH);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_skeleton_add_rejects_bad_input),
        cmocka_unit_test(test_skeleton_validate_finds_broken_invariants),
        cmocka_unit_test(test_forward_rejects_null_and_mismatch),
        cmocka_unit_test(test_clip_rejects_bad_input),
        cmocka_unit_test(test_forward_three_joint_chain_by_hand),
        cmocka_unit_test(test_forward_matches_double_reference),
        cmocka_unit_test(test_clip_starts_at_rest_and_round_trips),
        cmocka_unit_test(test_sample_on_frames_returns_frames),
        cmocka_unit_test(test_sample_halfway_lies_between),
        cmocka_unit_test(test_sample_loop_wraps_and_clamp_holds),
        cmocka_unit_test(test_blend_endpoints_and_aliasing),
        cmocka_unit_test(test_world_to_float),
        cmocka_unit_test(test_fk_is_bit_identical_across_cpus),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

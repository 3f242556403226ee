/* gait — leg IK with limits (SEEDS.md § 003, "Leg IK"; the formula is
 * missing from the seed, the method is ours): cub/motion.h's two-bone
 * solve for hip, knee and ankle, the knee's range enforced there; the
 * foot then turned in the plane of shin and foot into the ankle's range.
 * Q16.16 mm and radians. */
#include "cub/gait.h"

#define DEG(d) ((cub_q16)(((int64_t)(d) * CUB_Q16_PI + 90) / 180))

typedef struct leg_range {
    cub_q16 knee_min, knee_max, ankle_min, ankle_max;
} leg_range;

/* ours: a knee folds to 25 degrees and straightens short of 180 (a
 * straight knee flips its bend); the ankle's 35..150 spans a walk's
 * dorsi- and plantar flexion with room. The angle is to the toe joint,
 * wherever the skeleton puts it: CMU's "toe" is the ball of the foot,
 * below the ankle, so its neutral angle is ~60 degrees, not 90 (02_01
 * walks within 41..74). */
static leg_range range(const cub_gait_leg_limits *lim)
{
    leg_range r = {DEG(25), DEG(175), DEG(35), DEG(150)};
    if (lim && (lim->knee_min_rad || lim->knee_max_rad)) {
        r.knee_min = lim->knee_min_rad;
        r.knee_max = lim->knee_max_rad;
    }
    if (lim && (lim->ankle_min_rad || lim->ankle_max_rad)) {
        r.ankle_min = lim->ankle_min_rad;
        r.ankle_max = lim->ankle_max_rad;
    }
    return r;
}

cub_q16 cub_gait_ankle_angle(cub_vec3 knee_mm, cub_vec3 ankle_mm, cub_vec3 toe_mm)
{
    return cub_fx_vec3_angle(cub_fx_vec3_sub(ankle_mm, knee_mm), cub_fx_vec3_sub(toe_mm, ankle_mm));
}

/* v scaled to length len (a zero v stays zero). */
static cub_vec3 with_length(cub_vec3 v, cub_q16 len)
{
    cub_q16 l = cub_fx_vec3_length(v);
    if (l == 0) return v;
    return (cub_vec3){(cub_q16)((int64_t)v.x * len / l), (cub_q16)((int64_t)v.y * len / l),
                      (cub_q16)((int64_t)v.z * len / l)};
}

/* The foot at angle a from the shin, in the plane of shin and foot: unit
 * s along the shin, unit p across it toward the foot. */
static cub_vec3 turn_foot(cub_vec3 shin, cub_vec3 foot, cub_q16 a, cub_q16 len)
{
    cub_vec3 s = with_length(shin, CUB_Q16_ONE);
    cub_vec3 f = with_length(foot, CUB_Q16_ONE);
    cub_vec3 p = cub_fx_vec3_sub(f, cub_fx_vec3_scale(s, cub_fx_vec3_dot(f, s)));
    if (cub_fx_vec3_length(p) < 64) /* foot along the shin: any side; take +x of it */
        p = cub_fx_vec3_cross(s, (cub_vec3){0, 0, CUB_Q16_ONE});
    p = with_length(p, CUB_Q16_ONE);
    cub_vec3 dir =
        cub_fx_vec3_add(cub_fx_vec3_scale(s, cub_fx_cos(a)), cub_fx_vec3_scale(p, cub_fx_sin(a)));
    return with_length(dir, len);
}

cub_err cub_gait_leg_solve(const cub_gait_leg *leg, const cub_gait_leg_limits *lim,
                           cub_vec3 ankle_target, cub_vec3 toe_target, cub_gait_leg_pose *out)
{
    if (!leg || !out) return CUB_ERR_ARG;
    cub_q16 foot_len = cub_fx_vec3_length(cub_fx_vec3_sub(toe_target, ankle_target));
    if (foot_len <= 0) return CUB_ERR_ARG;
    leg_range r = range(lim);
    cub_ik_limits kl = {r.knee_min, r.knee_max};
    cub_ik_solution sol;
    cub_err e = cub_motion_ik_solve(leg->hip_mm, leg->thigh_mm, leg->shin_mm, ankle_target,
                                    leg->pole_mm, &kl, &sol);
    if (e) return e;
    *out = (cub_gait_leg_pose){.knee_mm = sol.mid_mm, .ankle_mm = sol.end_mm};
    out->corrected = sol.clamped ? CUB_GAIT_LEG_REACH : 0;
    out->knee_rad = cub_fx_vec3_angle(cub_fx_vec3_sub(leg->hip_mm, sol.mid_mm),
                                      cub_fx_vec3_sub(sol.end_mm, sol.mid_mm));
    /* The foot keeps its direction from the target ankle, moved with it. */
    cub_vec3 shin = cub_fx_vec3_sub(sol.end_mm, sol.mid_mm);
    cub_vec3 foot = cub_fx_vec3_sub(toe_target, ankle_target);
    cub_q16 a = cub_fx_vec3_angle(shin, foot);
    cub_q16 bounded = cub_fx_clamp(a, r.ankle_min, r.ankle_max);
    if (bounded != a) {
        foot = turn_foot(shin, foot, bounded, foot_len);
        out->corrected |= CUB_GAIT_LEG_ANKLE;
    }
    out->toe_mm = cub_fx_vec3_add(sol.end_mm, foot);
    out->ankle_rad = cub_gait_ankle_angle(sol.mid_mm, sol.end_mm, out->toe_mm);
    return CUB_OK;
}

/* The reach of a leg with its knee opened to at most knee_max (law of
 * cosines), squared, in 64 bits of Q16.16 squared. */
static int64_t reach2(const cub_gait_leg *leg, cub_q16 knee_max)
{
    int64_t a = leg->thigh_mm, b = leg->shin_mm;
    int64_t c = cub_fx_cos(knee_max);
    return a * a + b * b - ((2 * a * b) >> 16) * c;
}

static cub_q16 leg_drop(const cub_gait_leg *leg, cub_q16 knee_max, cub_vec3 target)
{
    cub_vec3 d = cub_fx_vec3_sub(leg->hip_mm, target);
    int64_t h2 = (int64_t)d.x * d.x + (int64_t)d.z * d.z;
    int64_t r2 = reach2(leg, knee_max);
    if (h2 >= r2) return 0; /* too far ahead to reach by lowering: the planner's to fix */
    cub_q16 v_max = (cub_q16)cub_fx_isqrt64((uint64_t)(r2 - h2));
    return d.y > v_max ? d.y - v_max : 0;
}

cub_q16 cub_gait_pelvis_drop(const cub_gait_leg legs[2], const cub_gait_leg_limits *lim,
                             const cub_vec3 ankle_targets[2])
{
    cub_q16 knee_max = range(lim).knee_max;
    cub_q16 a = leg_drop(&legs[0], knee_max, ankle_targets[0]);
    cub_q16 b = leg_drop(&legs[1], knee_max, ankle_targets[1]);
    return a > b ? a : b;
}

/* ---- the leg of a skeleton's pose ---------------------------------------- */

static cub_q16 bone(const cub_skeleton *sk, const cub_pose *pose, int j)
{
    return cub_fx_vec3_length(pose->has_trans ? pose->trans_mm[j] : sk->joints[j].offset_mm);
}

static cub_vec3 joint_at(const cub_skeleton *sk, const cub_pose *pose, int j, cub_quat *rot)
{
    cub_vec3 at = {0};
    cub_quat r;
    cub_motion_joint_world(sk, pose, j, &at, rot ? rot : &r);
    return at;
}

static bool leg_chain_ok(const cub_skeleton *sk, int ankle)
{
    if (!sk || ankle <= 0 || ankle >= sk->joint_count) return false;
    int knee = sk->joints[ankle].parent;
    return knee > 0 && sk->joints[knee].parent >= 0;
}

/* Where the knee's pole lies from the knee: along the knee's own bend
 * (its offset from the hip-ankle line), so the solved leg keeps the
 * pose's bend plane (02_01 flat: the knees 3-5 mm aside with the pole a
 * hand ahead of the knee, the old rule), plus a fifth of a hand ahead so
 * a straight leg still has a plane [ours]. */
static cub_vec3 pole_dir(cub_vec3 hip, cub_vec3 knee, cub_vec3 ankle, cub_vec3 ahead)
{
    cub_vec3 axis = with_length(cub_fx_vec3_sub(ankle, hip), CUB_Q16_ONE);
    cub_vec3 r = cub_fx_vec3_sub(knee, hip);
    cub_vec3 bend = cub_fx_vec3_sub(r, cub_fx_vec3_scale(axis, cub_fx_vec3_dot(r, axis)));
    return cub_fx_vec3_add(cub_fx_vec3_scale(bend, CUB_Q16_INT(8)),
                           cub_fx_vec3_scale(ahead, CUB_Q16_INT(20)));
}

cub_err cub_gait_pose_leg(const cub_skeleton *sk, const cub_pose *pose, int ankle, cub_vec3 ahead,
                          cub_gait_leg *leg)
{
    if (!pose || !leg || !leg_chain_ok(sk, ankle)) return CUB_ERR_ARG;
    int knee = sk->joints[ankle].parent, hip = sk->joints[knee].parent;
    cub_vec3 h = joint_at(sk, pose, hip, NULL), k = joint_at(sk, pose, knee, NULL);
    cub_vec3 pole = cub_fx_vec3_add(k, pole_dir(h, k, joint_at(sk, pose, ankle, NULL), ahead));
    *leg = (cub_gait_leg){h, bone(sk, pose, knee), bone(sk, pose, ankle), pole};
    return CUB_OK;
}

/* Turn the ankle joint so the toe joint points at toe_mm (world). */
static void aim_foot(const cub_skeleton *sk, cub_pose *pose, int ankle, int toe, cub_vec3 toe_mm)
{
    cub_quat parent_rot;
    joint_at(sk, pose, sk->joints[ankle].parent, &parent_rot);
    cub_vec3 aw = joint_at(sk, pose, ankle, NULL), tw = joint_at(sk, pose, toe, NULL);
    cub_quat turn = cub_motion_quat_between(cub_fx_vec3_sub(tw, aw), cub_fx_vec3_sub(toe_mm, aw));
    cub_quat local =
        cub_fx_quat_mul(cub_fx_quat_conj(parent_rot), cub_fx_quat_mul(turn, parent_rot));
    pose->rot[ankle] = cub_fx_quat_normalize(cub_fx_quat_mul(local, pose->rot[ankle]));
}

cub_err cub_gait_leg_apply(const cub_skeleton *sk, cub_pose *pose, const cub_gait_leg_target *t,
                           const cub_gait_leg_limits *lim, cub_gait_leg_pose *out)
{
    if (!t || !out || t->toe <= 0 || !sk || t->toe >= sk->joint_count) return CUB_ERR_ARG;
    cub_gait_leg leg;
    cub_err e = cub_gait_pose_leg(sk, pose, t->ankle, t->ahead, &leg);
    if (!e) e = cub_gait_leg_solve(&leg, lim, t->ankle_mm, t->toe_mm, out);
    if (e) return e;
    leg_range r = range(lim);
    cub_ik_limits kl = {r.knee_min, r.knee_max};
    int hip = sk->joints[sk->joints[t->ankle].parent].parent;
    e = cub_motion_ik_apply(sk, pose, hip, t->ankle_mm, leg.pole_mm, &kl, NULL);
    if (e) return e;
    aim_foot(sk, pose, t->ankle, t->toe, out->toe_mm);
    return CUB_OK;
}

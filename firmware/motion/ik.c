/* motion — two-bone analytic IK (cub/motion.h). The law of cosines places
 * the middle joint; the pole point picks the plane it bends in (the
 * closed-form two-bone case of IKAN, Tolani, Goswami and Badler, which
 * seed 001 names for the arms). Integer only: lengths and dot products in
 * 64 bits, so the same target gives the same pose on every CPU. */
#include "cub/motion.h"

#define DEFAULT_MIN_RAD 22877  /* 20 degrees */
#define DEFAULT_MAX_RAD 200277 /* 175 degrees */

static int64_t dot64(cub_vec3 a, cub_vec3 b) /* Q32 */
{
    return (int64_t)a.x * b.x + (int64_t)a.y * b.y + (int64_t)a.z * b.z;
}

static cub_q16 len64(cub_vec3 a)
{
    return (cub_q16)cub_fx_isqrt64((uint64_t)dot64(a, a));
}

/* a scaled to length len (Q16 mm); a zero vector stays zero. */
static cub_vec3 with_length(cub_vec3 a, cub_q16 len)
{
    int64_t l = len64(a);
    if (l == 0) return a;
    return (cub_vec3){(cub_q16)((int64_t)a.x * len / l), (cub_q16)((int64_t)a.y * len / l),
                      (cub_q16)((int64_t)a.z * len / l)};
}

/* A unit vector perpendicular to a (a nonzero). */
static cub_vec3 any_perpendicular(cub_vec3 a)
{
    cub_vec3 axis = cub_fx_abs(a.x) < cub_fx_abs(a.y) ? (cub_vec3){CUB_Q16_ONE, 0, 0}
                                                      : (cub_vec3){0, CUB_Q16_ONE, 0};
    cub_vec3 ua = with_length(a, CUB_Q16_ONE);
    return with_length(cub_fx_vec3_cross(ua, axis), CUB_Q16_ONE);
}

cub_quat cub_motion_quat_between(cub_vec3 from, cub_vec3 to)
{
    cub_vec3 a = with_length(from, CUB_Q16_ONE), b = with_length(to, CUB_Q16_ONE);
    if (len64(a) == 0 || len64(b) == 0) return cub_fx_quat_identity();
    /* q = (1 + a.b, a x b) normalised: half the angle, no trigonometry.
     * Components in Q29 (a quarter of Q2.30's range) so 1 + a.b <= 2 fits. */
    int64_t w = ((int64_t)1 << 29) + (dot64(a, b) >> 3);
    if (w < (1 << 12)) { /* nearly opposite: the cross product is noise */
        cub_vec3 p = any_perpendicular(a);
        return cub_fx_quat_normalize((cub_quat){0, p.x, p.y, p.z});
    }
    int64_t cx = (int64_t)a.y * b.z - (int64_t)a.z * b.y,
            cy = (int64_t)a.z * b.x - (int64_t)a.x * b.z,
            cz = (int64_t)a.x * b.y - (int64_t)a.y * b.x;
    return cub_fx_quat_normalize(
        (cub_quat){(int32_t)w, (int32_t)(cx >> 3), (int32_t)(cy >> 3), (int32_t)(cz >> 3)});
}

/* The reach for inner angle theta: sqrt(a^2 + b^2 - 2ab cos theta). */
static cub_q16 reach_at(cub_q16 a, cub_q16 b, cub_q16 theta)
{
    int64_t ab = (int64_t)a * b; /* Q32 */
    int64_t r2 = (int64_t)a * a + (int64_t)b * b - 2 * ((ab >> 16) * cub_fx_cos(theta));
    return (cub_q16)cub_fx_isqrt64((uint64_t)(r2 > 0 ? r2 : 0));
}

cub_err cub_motion_ik_solve(cub_vec3 root_mm, cub_q16 upper_mm, cub_q16 lower_mm,
                            cub_vec3 target_mm, cub_vec3 pole_mm, const cub_ik_limits *limits,
                            cub_ik_solution *out)
{
    if (upper_mm <= 0 || lower_mm <= 0 || !out) return CUB_ERR_ARG;
    cub_ik_limits lim = limits && (limits->min_rad || limits->max_rad)
                            ? *limits
                            : (cub_ik_limits){DEFAULT_MIN_RAD, DEFAULT_MAX_RAD};
    cub_q16 lo = reach_at(upper_mm, lower_mm, lim.min_rad),
            hi = reach_at(upper_mm, lower_mm, lim.max_rad);
    cub_vec3 d = cub_fx_vec3_sub(target_mm, root_mm), pole = cub_fx_vec3_sub(pole_mm, root_mm);
    cub_q16 dist = len64(d);
    if (dist == 0) d = len64(pole) ? pole : (cub_vec3){0, -CUB_Q16_ONE, 0};
    cub_q16 reach = cub_fx_clamp(dist, lo, hi);
    out->clamped = reach != dist;
    cub_vec3 dir = with_length(d, CUB_Q16_ONE);
    out->end_mm = cub_fx_vec3_add(root_mm, with_length(d, reach));
    /* Along the reach: x = (a^2 - b^2 + r^2) / 2r; off it: h = sqrt(a^2 - x^2). */
    int64_t a2 = (int64_t)upper_mm * upper_mm, b2 = (int64_t)lower_mm * lower_mm,
            r2 = (int64_t)reach * reach;
    int64_t x = reach > 0 ? (a2 - b2 + r2) / (2 * (int64_t)reach) : 0; /* Q16 */
    int64_t h2 = a2 - x * x;
    cub_q16 h = (cub_q16)cub_fx_isqrt64((uint64_t)(h2 > 0 ? h2 : 0));
    /* The pole's part perpendicular to the reach says which way to bend. */
    int64_t along = dot64(pole, dir) >> 16;
    cub_vec3 side = cub_fx_vec3_sub(pole, cub_fx_vec3_scale(dir, (cub_q16)along));
    if (len64(side) < CUB_Q16_ONE) side = any_perpendicular(dir);
    cub_vec3 mid = cub_fx_vec3_add(cub_fx_vec3_scale(dir, (cub_q16)x), with_length(side, h));
    out->mid_mm = cub_fx_vec3_add(root_mm, mid);
    return CUB_OK;
}

static int first_child(const cub_skeleton *skel, int joint)
{
    for (int j = joint + 1; j < skel->joint_count; j++)
        if (skel->joints[j].parent == joint) return j;
    return -1;
}

/* Turn joint j (world rotation *world, parent's world rotation parent_w)
 * so its bone toward child offset off points from at along want; returns
 * the new world rotation. */
static cub_quat aim(cub_pose *pose, int j, cub_quat parent_w, cub_quat world, cub_vec3 off,
                    cub_vec3 want)
{
    cub_quat turn = cub_motion_quat_between(cub_fx_quat_rotate(world, off), want);
    cub_quat w = cub_fx_quat_normalize(cub_fx_quat_mul(turn, world));
    pose->rot[j] = cub_fx_quat_normalize(cub_fx_quat_mul(cub_fx_quat_conj(parent_w), w));
    return w;
}

cub_err cub_motion_ik_apply(const cub_skeleton *skel, cub_pose *pose, int upper, cub_vec3 target_mm,
                            cub_vec3 pole_mm, const cub_ik_limits *limits, cub_ik_solution *out)
{
    if (!skel || !pose || pose->joint_count != skel->joint_count) return CUB_ERR_ARG;
    if (upper <= 0 || upper >= skel->joint_count) return CUB_ERR_RANGE;
    int mid = first_child(skel, upper), end = mid > 0 ? first_child(skel, mid) : -1;
    if (end < 0) return CUB_ERR_RANGE;
    /* Only the chain's ancestors: the rest of the skeleton is no concern. */
    int parent = skel->joints[upper].parent;
    cub_vec3 parent_pos, root;
    cub_quat parent_w;
    cub_err e = cub_motion_joint_world(skel, pose, parent, &parent_pos, &parent_w);
    if (e) return e;
    cub_vec3 local = pose->has_trans ? pose->trans_mm[upper] : skel->joints[upper].offset_mm;
    root = cub_fx_vec3_add(parent_pos, cub_fx_quat_rotate(parent_w, local));
    cub_quat upper_now = cub_fx_quat_mul(parent_w, pose->rot[upper]);
    cub_vec3 off_mid = skel->joints[mid].offset_mm, off_end = skel->joints[end].offset_mm;
    cub_ik_solution s;
    e = cub_motion_ik_solve(root, len64(off_mid), len64(off_end), target_mm, pole_mm, limits, &s);
    if (e) return e;
    cub_quat upper_w =
        aim(pose, upper, parent_w, upper_now, off_mid, cub_fx_vec3_sub(s.mid_mm, root));
    cub_quat mid_w = cub_fx_quat_mul(upper_w, pose->rot[mid]);
    aim(pose, mid, upper_w, mid_w, off_end, cub_fx_vec3_sub(s.end_mm, s.mid_mm));
    if (out) *out = s;
    return CUB_OK;
}

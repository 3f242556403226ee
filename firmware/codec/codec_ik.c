/* The seed's IK correction: CCD on an effector's parent and grandparent. */
#include "cub/codec.h"

/* Close enough: a tenth of a millimetre. */
#define CCD_TOLERANCE_Q16 ((cub_q16)6554)
/* Vectors are shifted down this much before the 64-bit cross product, which
 * only gives the axis's direction. */
#define CROSS_PRESHIFT 4

/* CA x CB as a Q16.16 vector of the right direction (its length is free:
 * cub_fx_quat_from_axis_angle renormalises). */
static cub_vec3 cross_dir(cub_vec3 a, cub_vec3 b)
{
    int64_t ax = a.x >> CROSS_PRESHIFT, ay = a.y >> CROSS_PRESHIFT, az = a.z >> CROSS_PRESHIFT;
    int64_t bx = b.x >> CROSS_PRESHIFT, by = b.y >> CROSS_PRESHIFT, bz = b.z >> CROSS_PRESHIFT;
    int64_t c[3] = {ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx};
    int64_t big = 0;
    for (int i = 0; i < 3; i++) {
        int64_t m = c[i] < 0 ? -c[i] : c[i];
        if (m > big) big = m;
    }
    int shift = 0;
    while ((big >> shift) >= ((int64_t)1 << 30))
        shift++;
    return (cub_vec3){(cub_q16)(c[0] >> shift), (cub_q16)(c[1] >> shift), (cub_q16)(c[2] >> shift)};
}

/* One CCD step on joint j: returns 1 if the effector is already on target. */
static int ccd_joint(const cub_skeleton *skel, cub_pose *pose, int j, int effector,
                     cub_vec3 target)
{
    cub_vec3 world[CUB_MOTION_MAX_JOINTS];
    cub_quat wrot[CUB_MOTION_MAX_JOINTS];
    if (cub_motion_forward(skel, pose, world, wrot)) return 1;
    cub_vec3 ca = cub_fx_vec3_sub(world[effector], world[j]);
    cub_vec3 cb = cub_fx_vec3_sub(target, world[j]);
    if (cub_fx_vec3_length(cub_fx_vec3_sub(target, world[effector])) <= CCD_TOLERANCE_Q16) return 1;
    cub_q16 angle = cub_fx_vec3_angle(ca, cb);
    cub_vec3 axis = cross_dir(ca, cb);
    if (angle == 0 || (axis.x == 0 && axis.y == 0 && axis.z == 0)) return 0;
    /* Q_c <- Quat . Q_c in world terms; back to the joint's local rotation
     * through its parent's world rotation. */
    cub_quat turn = cub_fx_quat_from_axis_angle(axis, angle);
    cub_quat w_new = cub_fx_quat_mul(turn, wrot[j]);
    int p = skel->joints[j].parent;
    cub_quat local = p < 0 ? w_new : cub_fx_quat_mul(cub_fx_quat_conj(wrot[p]), w_new);
    pose->rot[j] = cub_fx_quat_normalize(local);
    return 0;
}

cub_err cub_codec_ccd(const cub_skeleton *skel, cub_pose *pose, int effector, cub_vec3 target_mm)
{
    if (!skel || !pose || effector < 0 || effector >= skel->joint_count) return CUB_ERR_ARG;
    int p = skel->joints[effector].parent;
    int g = p < 0 ? -1 : skel->joints[p].parent;
    if (g < 0) return CUB_ERR_ARG;
    const int chain[2] = {g, p}; /* root to tip: the seed's order */
    for (int it = 0; it < CUB_CODEC_IK_ITERATIONS; it++)
        for (int k = 0; k < 2; k++)
            if (ccd_joint(skel, pose, chain[k], effector, target_mm)) return CUB_OK;
    return CUB_OK;
}

/* name ends in suffix, ignoring ASCII case */
static int ends_with_ci(const char *name, const char *suffix)
{
    size_t n = 0, s = 0;
    while (name[n])
        n++;
    while (suffix[s])
        s++;
    if (n < s) return 0;
    for (size_t i = 0; i < s; i++) {
        char c = name[n - s + i];
        if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
        if (c != suffix[i]) return 0;
    }
    return 1;
}

int cub_codec_pick_effectors(const cub_skeleton *skel, int *out, int max)
{
    int count = 0;
    for (int j = 0; skel && j < skel->joint_count && count < max; j++) {
        const cub_joint *jt = &skel->joints[j];
        int p = jt->parent;
        /* a grandparent that is the root would turn the whole body */
        if (p < 0 || skel->joints[p].parent <= 0 || jt->is_end_site) continue;
        if (ends_with_ci(jt->name, "foot") || ends_with_ci(jt->name, "ankle") ||
            ends_with_ci(jt->name, "hand"))
            out[count++] = j;
    }
    return count;
}

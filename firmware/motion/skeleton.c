/* motion: skeletons, the rest pose and forward kinematics. */
#include <string.h>

#include "cub/motion.h"

void cub_motion_skeleton_reset(cub_skeleton *skel)
{
    if (skel) memset(skel, 0, sizeof *skel);
}

/* Length of a name if it is non-empty and fits with its NUL, else 0. */
static size_t name_len(const char *name)
{
    if (!name) return 0;
    const char *end = memchr(name, '\0', CUB_MOTION_NAME_LEN);
    return end ? (size_t)(end - name) : 0;
}

cub_err cub_motion_skeleton_add(cub_skeleton *skel, const char *name, int parent,
                                cub_vec3 offset_mm, int *out_index)
{
    if (!skel || skel->joint_count < 0 || skel->joint_count > CUB_MOTION_MAX_JOINTS)
        return CUB_ERR_ARG;
    size_t len = name_len(name);
    if (len == 0) return CUB_ERR_ARG;
    int n = skel->joint_count;
    if (n == CUB_MOTION_MAX_JOINTS) return CUB_ERR_FULL;
    /* The first joint is the one root; every later one hangs off an
     * earlier joint, which keeps parents before children. */
    if (n == 0 ? parent != -1 : (parent < 0 || parent >= n)) return CUB_ERR_ARG;
    if (n > 0 && skel->joints[parent].is_end_site) return CUB_ERR_ARG;
    /* Names are how joints are found (mapping tables, features): unique. */
    if (cub_motion_skeleton_find(skel, name) >= 0) return CUB_ERR_ARG;
    cub_joint *j = &skel->joints[n];
    memset(j, 0, sizeof *j);
    memcpy(j->name, name, len + 1);
    j->parent = (int16_t)parent;
    j->offset_mm = offset_mm;
    skel->joint_count = n + 1;
    if (out_index) *out_index = n;
    return CUB_OK;
}

int cub_motion_skeleton_find(const cub_skeleton *skel, const char *name)
{
    if (!skel || !name) return -1;
    for (int i = 0; i < skel->joint_count && i < CUB_MOTION_MAX_JOINTS; i++)
        if (strncmp(skel->joints[i].name, name, CUB_MOTION_NAME_LEN) == 0) return i;
    return -1;
}

cub_err cub_motion_skeleton_validate(const cub_skeleton *skel)
{
    if (!skel) return CUB_ERR_ARG;
    if (skel->joint_count < 1 || skel->joint_count > CUB_MOTION_MAX_JOINTS) return CUB_ERR_FORMAT;
    for (int i = 0; i < skel->joint_count; i++) {
        const cub_joint *j = &skel->joints[i];
        if (name_len(j->name) == 0) return CUB_ERR_FORMAT;
        if (i == 0 ? j->parent != -1 : (j->parent < 0 || j->parent >= i)) return CUB_ERR_FORMAT;
        if (i > 0 && skel->joints[j->parent].is_end_site) return CUB_ERR_FORMAT;
    }
    return CUB_OK;
}

void cub_motion_pose_rest(const cub_skeleton *skel, cub_pose *out)
{
    if (!out) return;
    int n = skel ? skel->joint_count : 0;
    if (n < 0 || n > CUB_MOTION_MAX_JOINTS) n = 0;
    out->joint_count = n;
    out->root_mm = (cub_vec3){0, 0, 0};
    out->has_trans = 0;
    for (int i = 0; i < n; i++) {
        out->rot[i] = cub_fx_quat_identity();
        /* Unused while has_trans is 0, but kept meaningful: switching
         * has_trans on leaves the rest pose unchanged. */
        out->trans_mm[i] = skel->joints[i].offset_mm;
    }
}

cub_err cub_motion_forward(const cub_skeleton *skel, const cub_pose *pose, cub_vec3 *world_mm,
                           cub_quat *world_rot)
{
    if (!skel || !pose || !world_mm) return CUB_ERR_ARG;
    int n = skel->joint_count;
    if (n < 1 || n > CUB_MOTION_MAX_JOINTS || pose->joint_count != n) return CUB_ERR_ARG;
    if (skel->joints[0].parent != -1) return CUB_ERR_FORMAT;
    cub_quat scratch[CUB_MOTION_MAX_JOINTS];
    cub_quat *rot = world_rot ? world_rot : scratch;
    /* The root sits at root_mm; its offset is ignored (BVH practice: the
     * root's position channels replace its OFFSET). */
    world_mm[0] = pose->root_mm;
    rot[0] = pose->rot[0];
    for (int i = 1; i < n; i++) {
        int p = skel->joints[i].parent;
        if (p < 0 || p >= i) return CUB_ERR_FORMAT;
        cub_vec3 local = pose->has_trans ? pose->trans_mm[i] : skel->joints[i].offset_mm;
        world_mm[i] = cub_fx_vec3_add(world_mm[p], cub_fx_quat_rotate(rot[p], local));
        rot[i] = cub_fx_quat_mul(rot[p], pose->rot[i]);
    }
    return CUB_OK;
}

cub_err cub_motion_joint_world(const cub_skeleton *skel, const cub_pose *pose, int joint,
                               cub_vec3 *world_mm, cub_quat *world_rot)
{
    if (!skel || !pose || !world_mm || !world_rot || pose->joint_count != skel->joint_count)
        return CUB_ERR_ARG;
    if (joint < 0 || joint >= skel->joint_count) return CUB_ERR_RANGE;
    int chain[CUB_MOTION_MAX_JOINTS], len = 0;
    for (int j = joint; j > 0; j = skel->joints[j].parent) {
        if (skel->joints[j].parent < 0 || skel->joints[j].parent >= j) return CUB_ERR_FORMAT;
        chain[len++] = j;
    }
    /* The same operations in the same order as cub_motion_forward, so the
     * result is bit-identical to its entry for this joint. */
    cub_vec3 pos = pose->root_mm;
    cub_quat rot = pose->rot[0];
    while (len-- > 0) {
        int i = chain[len];
        cub_vec3 local = pose->has_trans ? pose->trans_mm[i] : skel->joints[i].offset_mm;
        pos = cub_fx_vec3_add(pos, cub_fx_quat_rotate(rot, local));
        rot = cub_fx_quat_mul(rot, pose->rot[i]);
    }
    *world_mm = pos, *world_rot = rot;
    return CUB_OK;
}

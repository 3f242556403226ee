/* groove — a song's plan (notes, segments, keys, handles, turns) and the
 * bear's pose at any time of it: waist, head, both arms by the two-bone IK
 * of cub/motion.h, the legs left at rest so the feet stay planted. */
#include "groove_internal.h"

cub_err cub_groove_plan_build(const cub_groove_song *song, const cub_groove_pick *pick,
                              const cub_groove_params *p, int window, cub_groove_store *mem,
                              cub_groove_plan *out, int *seg_count, cub_groove_cost *cost)
{
    if (!song || !pick || !p || !mem || !out) return CUB_ERR_ARG;
    int n = 0, k = 0;
    cub_err e = cub_groove_notes(song, pick, mem->notes, mem->cap, &n);
    if (!e)
        e = cub_groove_segment_notes(p, mem->notes, n, window, mem->work, mem->segs, mem->cap, &k,
                                     cost);
    if (!e) e = cub_groove_keys(p, mem->notes, n, mem->segs, k, mem->keys);
    if (!e) cub_groove_keys_pace(p, mem->notes, n, mem->keys);
    if (!e) e = cub_groove_handles_make(p, mem->notes, n, mem->keys, mem->handles);
    if (e) return e;
    cub_groove_stretch_limit(p, mem->notes, n, mem->keys, mem->handles);
    *out = (cub_groove_plan){
        *p,         mem->notes, n, mem->keys, mem->handles,
        mem->waist, mem->head,  0, 0,         cub_groove_tick_us(song, song->end_tick)};
    groove_song_turns(song, mem->notes, n, out->end_us, p->swing_deg, mem->waist, mem->cap,
                      &out->waist_count);
    groove_song_turns(song, mem->notes, n, out->end_us, p->nod_deg, mem->head, mem->cap,
                      &out->head_count);
    if (seg_count) *seg_count = k;
    return CUB_OK;
}

/* An arm as the bear has it: the joint, its child next, the child's next. */
static bool chain(const cub_skeleton *skel, int upper)
{
    return upper > 0 && upper + 2 < skel->joint_count && skel->joints[upper + 1].parent == upper &&
           skel->joints[upper + 2].parent == upper + 1;
}

cub_err cub_groove_rig_bind(const cub_skeleton *skel, cub_groove_rig *out)
{
    if (!skel || !out) return CUB_ERR_ARG;
    *out = (cub_groove_rig){skel,
                            cub_motion_skeleton_find(skel, "Spine"),
                            cub_motion_skeleton_find(skel, "Chest"),
                            cub_motion_skeleton_find(skel, "Head"),
                            cub_motion_skeleton_find(skel, "RightArm"),
                            cub_motion_skeleton_find(skel, "LeftArm"),
                            (cub_q16)(CUB_Q16_ONE * 2 / 5)};
    bool ok = out->spine > 0 && out->chest > 0 && out->head > 0 && chain(skel, out->right_arm) &&
              chain(skel, out->left_arm);
    return ok ? CUB_OK : CUB_ERR_FORMAT;
}

/* Homes and poles in the Chest's frame (the bear's: y up, facing +z, its
 * left +x; shoulders at x = +-125, y = 55): the wrists rest low in front
 * of the shoulders, the elbows point down, out and a little back. Ours. */
#define MM(x, y, z) ((cub_vec3){CUB_Q16_INT(x), CUB_Q16_INT(y), CUB_Q16_INT(z)})

static cub_q16 rad(cub_q16 deg)
{
    return (cub_q16)((int64_t)deg * CUB_Q16_PI / CUB_Q16_INT(180));
}

static cub_vec3 in_chest(cub_vec3 chest, cub_quat rot, cub_vec3 local)
{
    return cub_fx_vec3_add(chest, cub_fx_quat_rotate(rot, local));
}

/* The arm hanging with the forearm forward: the IK turns the bones the
 * least from here, and no target in front of the bear lies opposite a
 * bone's direction (from the T pose, a forearm reaching across the body
 * would, and its twist would flip from one frame to the next). */
static void ready(const cub_skeleton *skel, cub_pose *pose, int upper)
{
    int mid = upper + 1, end = upper + 2; /* the bear's chain: arm, forearm, hand */
    cub_quat arm = cub_motion_quat_between(skel->joints[mid].offset_mm, MM(0, -1, 0));
    cub_vec3 fore = cub_fx_quat_rotate(arm, skel->joints[end].offset_mm);
    cub_quat fore_w = cub_fx_quat_mul(cub_motion_quat_between(fore, MM(0, 0, 1)), arm);
    pose->rot[upper] = arm;
    pose->rot[mid] = cub_fx_quat_normalize(cub_fx_quat_mul(cub_fx_quat_conj(arm), fore_w));
}

/* side -1: the right arm (key x sweeps it inward), +1: the left. */
static cub_err arm(const cub_groove_rig *rig, cub_pose *pose, int side, cub_groove_key at,
                   cub_vec3 chest, cub_quat chest_rot)
{
    cub_vec3 home = MM(side * 210, -40, 160), pole = MM(side * 330, -200, -100);
    cub_vec3 local = {cub_fx_add(home.x, cub_fx_mul(at.x_mm, rig->scale)),
                      cub_fx_add(home.y, cub_fx_mul(at.y_mm, rig->scale)), home.z};
    int upper = side < 0 ? rig->right_arm : rig->left_arm;
    ready(rig->skel, pose, upper);
    /* the elbow opens to 160 degrees at most: nearer straight, a small
     * move of the wrist swings the elbow fast */
    const cub_ik_limits lim = {22877, 167552};
    return cub_motion_ik_apply(rig->skel, pose, upper, in_chest(chest, chest_rot, local),
                               in_chest(chest, chest_rot, pole), &lim, NULL);
}

cub_err cub_groove_pose_at(const cub_groove_plan *plan, const cub_groove_rig *rig, int64_t t_us,
                           cub_pose *out)
{
    if (!plan || !rig || !out || plan->n < 1) return CUB_ERR_ARG;
    t_us = cub_groove_clock(plan, t_us);
    const cub_skeleton *skel = rig->skel;
    cub_motion_pose_rest(skel, out);
    out->root_mm = skel->joints[0].offset_mm;
    cub_q16 waist = cub_groove_turn_at(plan->waist, plan->waist_count, t_us),
            nod = cub_groove_turn_at(plan->head, plan->head_count, t_us);
    out->rot[rig->spine] = cub_fx_quat_from_axis_angle(MM(0, 1, 0), rad(waist));
    out->rot[rig->head] = cub_fx_quat_from_axis_angle(MM(1, 0, 0), rad(nod));
    cub_vec3 chest;
    cub_quat chest_rot;
    cub_err e = cub_motion_joint_world(skel, out, rig->chest, &chest, &chest_rot);
    cub_groove_key right = cub_groove_wrist_at(plan, t_us);
    if (!e) e = arm(rig, out, -1, right, chest, chest_rot);
    cub_groove_key left = cub_groove_left_at(plan, t_us);
    if (!e) e = arm(rig, out, 1, left, chest, chest_rot);
    return e;
}

cub_err cub_groove_clip_fill(const cub_groove_plan *plan, const cub_groove_rig *rig, int64_t t0_us,
                             cub_clip *clip)
{
    if (!clip || clip->skel != rig->skel) return CUB_ERR_ARG;
    cub_pose pose;
    for (int f = 0; f < clip->frame_count; f++) {
        int64_t t = t0_us + (int64_t)f * clip->frame_ns / 1000;
        cub_err e = cub_groove_pose_at(plan, rig, t, &pose);
        if (!e) e = cub_motion_clip_set_frame(clip, f, &pose);
        if (e) return e;
    }
    return CUB_OK;
}

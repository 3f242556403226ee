/* The transfer: source world bone directions and rotations onto the
 * target, frame by frame at the output rate (see cub/retarget.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "rt_ctx.h"

static const char *or_default(const char *s, const char *d)
{
    return s && *s ? s : d;
}

static cub_err find_key(rt_ctx *c, const char *name, int *out)
{
    *out = cub_motion_skeleton_find(c->tgt, name);
    if (*out < 0)
        return cub_diag_fail(c->diag, CUB_ERR_ARG, c->name, 0, "target has no joint \"%s\"", name);
    if (c->link_of[*out] < 0)
        return cub_diag_fail(c->diag, CUB_ERR_FORMAT, c->map->file, 0,
                       "key joint \"%s\" is not linked to a source joint", name);
    return CUB_OK;
}

static cub_err setup_links(rt_ctx *c)
{
    for (int j = 0; j < c->tj; j++)
        c->link_of[j] = c->aim_of[j] = -1;
    for (int l = 0; l < c->links; l++) {
        int t = c->map->link[l].target;
        if (t < 0 || t >= c->tj)
            return cub_diag_fail(c->diag, CUB_ERR_ARG, c->map->file, c->map->link[l].line,
                           "link not bound to this target");
        c->link_of[t] = l;
    }
    for (int l = 0; l < c->links; l++) {
        const cub_retarget_link *lk = &c->map->link[l];
        for (int ch = lk->target + 1; ch < c->tj && lk->policy != CUB_RETARGET_ROT; ch++)
            if (c->tgt->joints[ch].parent == lk->target && c->link_of[ch] >= 0) {
                c->aim_of[lk->target] = ch;
                break;
            }
        if (lk->policy == CUB_RETARGET_AIM && c->aim_of[lk->target] < 0)
            return cub_diag_fail(c->diag, CUB_ERR_FORMAT, c->map->file, lk->line,
                           "\"%s\" is marked aim but no child of it is linked", lk->target_name);
    }
    const cub_retarget_joints *k = &c->d.joints;
    static const char *side[2][3] = {{"LeftUpLeg", "LeftLeg", "LeftFoot"},
                                     {"RightUpLeg", "RightLeg", "RightFoot"}};
    cub_err err = find_key(c, or_default(k->hips, "Hips"), &c->hips);
    if (!err)
        err = find_key(c, or_default(k->head, "Head"), &c->head);
    for (int s = 0; s < 2 && !err; s++) {
        err = find_key(c, or_default(k->up_leg[s], side[s][0]), &c->up_leg[s]);
        if (!err)
            err = find_key(c, or_default(k->leg[s], side[s][1]), &c->leg[s]);
        if (!err)
            err = find_key(c, or_default(k->foot[s], side[s][2]), &c->foot[s]);
    }
    return err;
}

static cub_err alloc_work(rt_ctx *c)
{
    size_t fl = (size_t)c->frames * (size_t)c->links, ft = (size_t)c->frames * (size_t)c->tj;
    c->lpos = malloc(fl * sizeof(cub_dv3));
    c->lrot = malloc(fl * sizeof(cub_dq));
    c->root = malloc((size_t)c->frames * sizeof(cub_dv3));
    c->local = malloc(ft * sizeof(cub_dq));
    c->contact[0] = calloc((size_t)c->frames, 1);
    c->contact[1] = calloc((size_t)c->frames, 1);
    c->s_rot = malloc((size_t)c->sj * sizeof(cub_dq));
    c->s_wrot = malloc((size_t)c->sj * sizeof(cub_dq));
    c->s_trans = malloc((size_t)c->sj * sizeof(cub_dv3));
    c->s_wpos = malloc((size_t)c->sj * sizeof(cub_dv3));
    if (!c->lpos || !c->lrot || !c->root || !c->local || !c->contact[0] || !c->contact[1] ||
        !c->s_rot || !c->s_wrot || !c->s_trans || !c->s_wpos)
        return cub_diag_fail(c->diag, CUB_ERR_NOMEM, c->name, 0, "out of memory for %d frames",
                       c->frames);
    return CUB_OK;
}

static void free_work(rt_ctx *c)
{
    free(c->lpos), free(c->lrot), free(c->root), free(c->local);
    free(c->contact[0]), free(c->contact[1]);
    free(c->s_rot), free(c->s_wrot), free(c->s_trans), free(c->s_wpos);
}

static double src_time(const rt_ctx *c, int f)
{
    return c->d.start_s + f * c->dt_s * c->d.speed;
}

/* Sample every output frame's link data (target axes, mirrored), then turn
 * the whole clip so that the hips face +z on average. */
static void sample_links(rt_ctx *c)
{
    double fx = 0, fz = 0;
    for (int f = 0; f < c->frames; f++) {
        cub_dv3 *pos = c->lpos + (size_t)f * c->links;
        cub_dq *rot = c->lrot + (size_t)f * c->links;
        rt_source_links_at(c, src_time(c, f), pos, rot);
        if (c->d.mirror)
            rt_mirror_links(c, pos, rot);
        cub_dv3 fw = cub_dq_rotate(rot[c->link_of[c->hips]], cub_dv3_make(0, 0, 1));
        double n = hypot(fw.x, fw.z);
        if (n > 1e-6)
            fx += fw.x / n, fz += fw.z / n;
    }
    double turn = c->d.turn_deg * CUB_VEC_PI / 180.0;
    if (!c->d.keep_facing && hypot(fx, fz) > 1e-6)
        turn -= atan2(fx, fz);
    c->yaw = cub_dq_axis_angle(cub_dv3_make(0, 1, 0), turn);
    for (size_t i = 0; i < (size_t)c->frames * c->links; i++) {
        c->lpos[i] = cub_dq_rotate(c->yaw, c->lpos[i]);
        c->lrot[i] = cub_dq_norm(cub_dq_mul(c->yaw, c->lrot[i]));
    }
}

/* One frame: world rotations of the target, parents first, then locals. */
static void transfer_frame(rt_ctx *c, int f)
{
    const cub_dv3 *pos = c->lpos + (size_t)f * c->links;
    const cub_dq *rot = c->lrot + (size_t)f * c->links;
    cub_dq world[CUB_MOTION_MAX_JOINTS];
    cub_dq *local = c->local + (size_t)f * c->tj;
    for (int j = 0; j < c->tj; j++) {
        int p = c->tgt->joints[j].parent, l = c->link_of[j];
        cub_dq parent = p >= 0 ? world[p] : cub_dq_identity();
        if (l < 0) {
            world[j] = parent;
        } else if (c->aim_of[j] < 0) {
            world[j] = rot[l];
        } else {
            int ch = c->aim_of[j];
            cub_dq r1 = cub_dq_mul(rot[l], c->align_inv[j]);
            cub_dv3 rest_dir = cub_dv3_sub(c->tgt_rest_pos[ch], c->tgt_rest_pos[j]);
            cub_dv3 want = cub_dv3_sub(pos[c->link_of[ch]], pos[l]);
            world[j] = cub_dq_norm(cub_dq_mul(cub_dq_arc(cub_dq_rotate(r1, rest_dir), want), r1));
        }
        local[j] = cub_dq_norm(cub_dq_mul(cub_dq_conj(parent), world[j]));
    }
    c->root[f] = cub_dv3_scale(pos[c->link_of[c->hips]], c->k);
}

/* Keep each joint's quaternion in the hemisphere of the previous frame's. */
static void hemisphere(rt_ctx *c)
{
    for (int f = 1; f < c->frames; f++)
        for (int j = 0; j < c->tj; j++) {
            cub_dq *q = &c->local[(size_t)f * c->tj + j];
            if (cub_dq_dot(*q, c->local[(size_t)(f - 1) * c->tj + j]) < 0)
                *q = (cub_dq){-q->w, -q->x, -q->y, -q->z};
        }
}

static cub_err write_out(const rt_ctx *c, const cub_skeleton *target, cub_io_motion *out)
{
    memset(out, 0, sizeof(*out));
    out->skel = *target;
    out->unit_mm = 10.0; /* BVH in centimetres, what most viewers expect */
    uint32_t frame_ns = (uint32_t)llround(1e9 * c->dt_s);
    size_t size = cub_motion_clip_mem_size(c->tj, c->frames, 0);
    void *mem = malloc(size ? size : 1);
    if (!mem)
        return cub_diag_fail(c->diag, CUB_ERR_NOMEM, c->name, 0, "out of memory");
    cub_err err = cub_motion_clip_init(&out->clip, &out->skel, c->frames, frame_ns, 0, mem, size);
    if (err) {
        free(mem);
        return cub_diag_fail(c->diag, err, c->name, 0, "cannot lay out the clip: %s", cub_err_str(err));
    }
    out->frame_mem = mem;
    for (int f = 0; f < c->frames; f++) {
        out->clip.root_mm[f] = cub_dv3_to_fx(c->root[f]);
        for (int j = 0; j < c->tj; j++)
            out->clip.rot[(size_t)f * c->tj + j] = cub_dq_to_fx(c->local[(size_t)f * c->tj + j]);
    }
    for (int j = 0; j < c->tj; j++) {
        cub_io_channels *ch = &out->channels[j];
        if (target->joints[j].is_end_site)
            continue;
        ch->count = j == 0 ? 6 : 3;
        ch->has_pos = j == 0;
        memcpy(ch->rot_order, "ZXY", 4);
        memcpy(ch->pos_order, j == 0 ? "XYZ" : "", j == 0 ? 4 : 1);
    }
    return CUB_OK;
}

static cub_err check_args(rt_ctx *c, const cub_retarget_desc *desc)
{
    if (desc)
        c->d = *desc;
    c->name = or_default(c->d.name, "clip");
    if (c->d.fps <= 0)
        c->d.fps = 30;
    if (c->d.speed <= 0)
        c->d.speed = 1;
    if (c->d.contact_height_mm <= 0)
        c->d.contact_height_mm = 30;
    if (c->d.contact_speed_mm_s <= 0)
        c->d.contact_speed_mm_s = 180;
    if (!c->map->bound)
        return cub_diag_fail(c->diag, CUB_ERR_ARG, c->map->file, 0, "map not bound to the skeletons");
    if (!c->src->skel || c->src->frame_count < 1 || !c->src->frame_ns)
        return cub_diag_fail(c->diag, CUB_ERR_ARG, c->name, 0, "empty source clip");
    c->tj = c->tgt->joint_count;
    c->sj = c->src->skel->joint_count;
    c->links = c->map->link_count;
    c->dt_s = 1.0 / c->d.fps;
    c->src_dt_s = c->src->frame_ns * 1e-9;
    double dur = (c->src->frame_count - 1) * c->src_dt_s;
    double end = c->d.end_s > 0 ? c->d.end_s : dur;
    if (!isfinite(c->d.start_s) || !isfinite(end) || c->d.start_s < 0 ||
        end > dur + c->src_dt_s || end <= c->d.start_s)
        return cub_diag_fail(c->diag, CUB_ERR_RANGE, c->name, 0,
                       "time range %.3f..%.3f s is not inside the source (0..%.3f s)",
                       c->d.start_s, end, dur);
    c->frames = (int)floor((end - c->d.start_s) / (c->dt_s * c->d.speed) + 1e-9) + 1;
    return CUB_OK;
}

cub_err cub_retarget_clip(const cub_retarget_map *map, const cub_skeleton *target,
                          const cub_clip *src, const cub_retarget_desc *desc, cub_io_motion *out,
                          cub_retarget_report *report, cub_diag *diag)
{
    if (!map || !target || !src || !out)
        return cub_diag_fail(diag, CUB_ERR_ARG, "(retarget)", 0, "missing map, target, source or out");
    rt_ctx *c = calloc(1, sizeof(*c));
    if (!c)
        return cub_diag_fail(diag, CUB_ERR_NOMEM, "(retarget)", 0, "out of memory");
    c->map = map, c->tgt = target, c->src = src, c->diag = diag;
    cub_retarget_report rep;
    memset(&rep, 0, sizeof(rep));
    cub_err err = check_args(c, desc);
    if (!err)
        err = setup_links(c);
    if (!err)
        err = alloc_work(c);
    if (!err)
        err = rt_setup_frames(c);
    if (!err) {
        sample_links(c);
        for (int f = 0; f < c->frames; f++)
            transfer_frame(c, f);
        rt_feet(c, &rep);
        hemisphere(c);
        rep.leg_ratio = c->k;
        rep.frames = c->frames;
        rep.yaw_deg = 2 * atan2(c->yaw.y, c->yaw.w) * 180.0 / CUB_VEC_PI;
        err = write_out(c, target, out);
    }
    if (!err && report)
        *report = rep;
    free_work(c);
    free(c);
    return err;
}

cub_err cub_retarget_load_source(const char *path, const char *amc_path, cub_io_motion *out,
                                 cub_diag *diag)
{
    cub_io_desc d = {0};
    if (amc_path)
        return cub_io_load_asf_amc(path, amc_path, &d, out, diag);
    return cub_io_load_bvh(path, &d, out, diag);
}

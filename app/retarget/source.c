/* The source side of a retarget: sampling the source clip at any time
 * (slerp between its frames), the per-link data in target axes, mirroring,
 * and the frames of reference (Q0) and the leg ratio k. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "rt_ctx.h"

/* Source world pose at t_s (slerp/lerp between the two nearest frames). */
static void source_world_at(rt_ctx *c, double t_s)
{
    const cub_clip *s = c->src;
    double fi = t_s / c->src_dt_s;
    if (fi < 0)
        fi = 0;
    int i0 = (int)floor(fi);
    if (i0 > s->frame_count - 1)
        i0 = s->frame_count - 1;
    int i1 = i0 + 1 < s->frame_count ? i0 + 1 : i0;
    double a = fi - i0;
    if (a > 1)
        a = 1;
    cub_dv3 r0 = cub_dv3_from_fx(s->root_mm[i0]), r1 = cub_dv3_from_fx(s->root_mm[i1]);
    cub_dv3 root = cub_dv3_add(r0, cub_dv3_scale(cub_dv3_sub(r1, r0), a));
    for (int j = 0; j < c->sj; j++) {
        size_t k0 = (size_t)i0 * c->sj + j, k1 = (size_t)i1 * c->sj + j;
        cub_dq q0 = cub_dq_norm(cub_dq_from_fx(s->rot[k0]));
        cub_dq q1 = cub_dq_norm(cub_dq_from_fx(s->rot[k1]));
        c->s_rot[j] = cub_dq_slerp(q0, q1, a);
        if (s->trans_mm) {
            cub_dv3 t0 = cub_dv3_from_fx(s->trans_mm[k0]), t1 = cub_dv3_from_fx(s->trans_mm[k1]);
            c->s_trans[j] = cub_dv3_add(t0, cub_dv3_scale(cub_dv3_sub(t1, t0), a));
        }
    }
    rt_forward(s->skel, root, c->s_rot, s->trans_mm ? c->s_trans : NULL, c->s_wpos, c->s_wrot);
}

/* Per-link data from the source world pose in s_wpos / s_wrot, turned
 * into target axes by Q0 (rotations conjugated, so the rest stays I). */
static void links_from_world(const rt_ctx *c, cub_dv3 *pos, cub_dq *rot)
{
    cub_dq q0i = cub_dq_conj(c->q0);
    for (int l = 0; l < c->links; l++) {
        const cub_retarget_link *lk = &c->map->link[l];
        cub_dv3 p = {0, 0, 0};
        for (int s = 0; s < lk->source_count; s++)
            p = cub_dv3_add(p, cub_dv3_scale(c->s_wpos[lk->source[s].joint], lk->source[s].weight));
        pos[l] = cub_dq_rotate(c->q0, p);
        rot[l] = cub_dq_mul(cub_dq_mul(c->q0, c->s_wrot[lk->source[0].joint]), q0i);
    }
}

void rt_source_links_at(rt_ctx *c, double t_s, cub_dv3 *pos, cub_dq *rot)
{
    source_world_at(c, t_s);
    links_from_world(c, pos, rot);
}

void rt_source_links_rest(rt_ctx *c, cub_dv3 *pos, cub_dq *rot)
{
    for (int j = 0; j < c->sj; j++)
        c->s_rot[j] = cub_dq_identity();
    rt_forward(c->src->skel, cub_dv3_make(0, 0, 0), c->s_rot, NULL, c->s_wpos, c->s_wrot);
    links_from_world(c, pos, rot);
}

void rt_mirror_links(const rt_ctx *c, cub_dv3 *pos, cub_dq *rot)
{
    cub_dv3 p[CUB_MOTION_MAX_JOINTS];
    cub_dq q[CUB_MOTION_MAX_JOINTS];
    memcpy(p, pos, sizeof(*p) * (size_t)c->links);
    memcpy(q, rot, sizeof(*q) * (size_t)c->links);
    for (int l = 0; l < c->links; l++) {
        /* Reflection x -> -x: positions flip x; a rotation M R M keeps its
         * x component and flips y and z. */
        const cub_dv3 *a = &p[c->partner[l]];
        const cub_dq *b = &q[c->partner[l]];
        pos[l] = cub_dv3_make(-a->x, a->y, a->z);
        rot[l] = (cub_dq){b->w, b->x, -b->y, -b->z};
    }
}

/* Mirror partners by target names: LeftX <-> RightX. */
static void find_partners(rt_ctx *c)
{
    for (int l = 0; l < c->links; l++) {
        const char *n = c->map->link[l].target_name;
        char other[CUB_MOTION_NAME_LEN + 8] = "";
        c->partner[l] = l;
        if (!strncmp(n, "Left", 4))
            snprintf(other, sizeof(other), "Right%s", n + 4);
        else if (!strncmp(n, "Right", 5))
            snprintf(other, sizeof(other), "Left%s", n + 5);
        int tj = other[0] ? cub_motion_skeleton_find(c->tgt, other) : -1;
        if (tj >= 0 && c->link_of[tj] >= 0)
            c->partner[l] = c->link_of[tj];
    }
}

/* The coordinate axis (+-x, +-y, +-z) nearest to v: files are written with
 * axis-aligned conventions (y up or z up), and a rest spine leaning a
 * couple of degrees must not tilt the floor of the whole clip. */
static cub_dv3 nearest_axis(cub_dv3 v)
{
    double a[3] = {v.x, v.y, v.z};
    int k = 0;
    for (int i = 1; i < 3; i++)
        if (fabs(a[i]) > fabs(a[k]))
            k = i;
    double s = a[k] < 0 ? -1 : 1;
    return cub_dv3_make(k == 0 ? s : 0, k == 1 ? s : 0, k == 2 ? s : 0);
}

/* Target rest pose and which joints count as feet (feet + descendants). */
static void target_rest(rt_ctx *c)
{
    cub_dq rot[CUB_MOTION_MAX_JOINTS], wrot[CUB_MOTION_MAX_JOINTS];
    for (int j = 0; j < c->tj; j++)
        rot[j] = cub_dq_identity();
    rt_forward(c->tgt, cub_dv3_from_fx(c->tgt->joints[0].offset_mm), rot, NULL, c->tgt_rest_pos,
               wrot);
    for (int j = 0; j < c->tj; j++) {
        int p = c->tgt->joints[j].parent;
        c->is_foot[j] = j == c->foot[0] || j == c->foot[1] || (p >= 0 && c->is_foot[p]);
    }
}

/* Rest alignment A_j per aimed joint: source rest bone direction (target
 * axes, mirrored if asked) onto the target's rest bone direction. */
static void rest_alignment(rt_ctx *c, const cub_dv3 *rest_pos)
{
    for (int j = 0; j < c->tj; j++) {
        c->align_inv[j] = cub_dq_identity();
        int ch = c->aim_of[j];
        if (ch < 0)
            continue;
        cub_dv3 ds = cub_dv3_sub(rest_pos[c->link_of[ch]], rest_pos[c->link_of[j]]);
        cub_dv3 dt = cub_dv3_sub(c->tgt_rest_pos[ch], c->tgt_rest_pos[j]);
        c->align_inv[j] = cub_dq_conj(cub_dq_arc(ds, dt));
    }
}

cub_err rt_setup_frames(rt_ctx *c)
{
    cub_dv3 pos[CUB_MOTION_MAX_JOINTS];
    cub_dq rot[CUB_MOTION_MAX_JOINTS];
    find_partners(c);
    target_rest(c);
    c->q0 = cub_dq_identity();
    rt_source_links_rest(c, pos, rot);
    cub_dv3 up = cub_dv3_sub(pos[c->link_of[c->head]], pos[c->link_of[c->hips]]);
    cub_dv3 left = cub_dv3_sub(pos[c->link_of[c->up_leg[0]]], pos[c->link_of[c->up_leg[1]]]);
    if (cub_dv3_len(up) < 1e-6 || cub_dv3_len(left) < 1e-6 ||
        cub_dv3_len(cub_dv3_cross(up, left)) < 0.5 * cub_dv3_len(up) * cub_dv3_len(left))
        return cub_diag_fail(c->diag, CUB_ERR_FORMAT, c->name, 0,
                       "source rest pose has no clear up (hips->head) and left (hips)");
    cub_dv3 up_axis = nearest_axis(up), left_axis = nearest_axis(left);
    if (fabs(cub_dv3_dot(up_axis, left_axis)) > 0.5)
        return cub_diag_fail(c->diag, CUB_ERR_FORMAT, c->name, 0,
                       "source rest pose: up (hips->head) and left (hips) share an axis");
    c->q0 = cub_dq_frames(up_axis, left_axis, cub_dv3_make(0, 1, 0), cub_dv3_make(1, 0, 0));

    /* Leg ratio from the rest poses: hips above the lowest joint. */
    rt_source_links_rest(c, pos, rot);
    double src_low = 0;
    for (int j = 0; j < c->sj; j++) {
        double y = cub_dq_rotate(c->q0, c->s_wpos[j]).y;
        src_low = j == 0 || y < src_low ? y : src_low;
    }
    double src_h = pos[c->link_of[c->hips]].y - src_low;
    double tgt_low = c->tgt_rest_pos[0].y;
    for (int j = 0; j < c->tj; j++)
        if (c->tgt_rest_pos[j].y < tgt_low)
            tgt_low = c->tgt_rest_pos[j].y;
    double tgt_h = c->tgt_rest_pos[c->hips].y - tgt_low;
    if (src_h < 1 || tgt_h < 1)
        return cub_diag_fail(c->diag, CUB_ERR_FORMAT, c->name, 0,
                       "hip height too small (source %.1f mm, target %.1f mm)", src_h, tgt_h);
    c->k = tgt_h / src_h;

    if (c->d.mirror)
        rt_mirror_links(c, pos, rot);
    rest_alignment(c, pos);
    return CUB_OK;
}

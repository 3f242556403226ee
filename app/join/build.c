/* Building a join: A, then (C moved onto A's end,) then B moved onto what
 * precedes it, with a blend at each seam over frames the seam's distance
 * sets (seed 002, § 5.1: "插值的帧数由相似性的大小来决定"). The blend
 * overlaps the outgoing clip's last frames with the incoming clip's first
 * ones (Kovar 2002 § 3.3), the incoming weight easing from 0 to 1.
 * With feet on, the legs do not blend with the body: one leg goes over in
 * the first half of the seam while the other keeps the outgoing clip's
 * foot where it is, then the other in the second half (§ 5.1 (2): "先对一只
 * 脚插值，另外一只脚作为支撑"), each ankle put on its target by leg IK; a
 * foot that has to travel is lifted on the way (a step, not a slide). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "join_internal.h"

#define STEP_MM 20.0     /* a foot travelling farther than this steps (is lifted) */
#define LIFT_MIN_MM 50.0 /* a step clears the floor: above the contact height (30 mm) */
#define LIFT_MAX_MM 80.0 /* the step's highest lift (half its travel between the two) */

/* One pose in doubles; trans: each joint's local translation (its rest
 * offset for clips that animate none). */
typedef struct dpose {
    cub_dv3 root;
    cub_dq rot[CUB_MOTION_MAX_JOINTS];
    cub_dv3 trans[CUB_MOTION_MAX_JOINTS];
} dpose;

/* Frame f of clip moved by t (NULL: as it is). */
static void get_frame(const cub_clip *clip, int f, const cub_join_align *t, dpose *out)
{
    int nj = clip->skel->joint_count;
    out->root = cub_dv3_from_fx(clip->root_mm[f]);
    for (int j = 0; j < nj; j++) {
        out->rot[j] = cub_dq_norm(cub_dq_from_fx(clip->rot[(size_t)f * nj + j]));
        out->trans[j] = cub_dv3_from_fx(clip->trans_mm ? clip->trans_mm[(size_t)f * nj + j]
                                                       : clip->skel->joints[j].offset_mm);
    }
    if (t) {
        out->root = cub_join_apply(t, out->root);
        out->rot[0] = cub_dq_norm(cub_dq_mul(cub_join_align_rot(t), out->rot[0]));
    }
}

static void put_frame(cub_clip *clip, int f, const dpose *p)
{
    int nj = clip->skel->joint_count;
    clip->root_mm[f] = cub_dv3_to_fx(p->root);
    for (int j = 0; j < nj; j++) {
        clip->rot[(size_t)f * nj + j] = cub_dq_to_fx(p->rot[j]);
        if (clip->trans_mm) clip->trans_mm[(size_t)f * nj + j] = cub_dv3_to_fx(p->trans[j]);
    }
}

static void pose_world(const cub_skeleton *s, const dpose *p, cub_dv3 *pos, cub_dq *rot)
{
    static cub_pose fp;
    cub_vec3 w[CUB_MOTION_MAX_JOINTS];
    cub_quat r[CUB_MOTION_MAX_JOINTS];
    cub_motion_pose_rest(s, &fp);
    fp.root_mm = cub_dv3_to_fx(p->root);
    fp.has_trans = 1;
    for (int j = 0; j < s->joint_count; j++) {
        fp.rot[j] = cub_dq_to_fx(p->rot[j]);
        fp.trans_mm[j] = cub_dv3_to_fx(p->trans[j]);
    }
    cub_motion_forward(s, &fp, w, r);
    for (int j = 0; j < s->joint_count; j++) {
        pos[j] = cub_dv3_from_fx(w[j]);
        rot[j] = cub_dq_norm(cub_dq_from_fx(r[j]));
    }
}

static double smooth(double u)
{
    u = fmax(0, fmin(1, u));
    return u * u * (3 - 2 * u);
}

/* A seam: n frames, outgoing clip `from` moved by tf starting at frame f0,
 * incoming `to` moved by tt starting at t0; which feet each side plants. */
typedef struct seam {
    const cub_clip *from, *to;
    const cub_join_align *tf, *tt;
    int f0, t0, n;
    int first_leg;          /* the leg that goes over first; -1: blend the legs too */
    int from_clip, to_clip; /* their db indices */
    int cut;                /* no blend: from to the middle, then to (CUB_JOIN_CUT) */
} seam;

/* Leg `side` of the blended pose o onto its target at leg phase u (0..1):
 * a step - the lift follows sin(pi u), the ankle goes over (smoothstep)
 * only in the middle half, so the foot leaves the floor before it moves
 * and is set down where it arrives. */
static void place_leg(const cub_join_db *db, const dpose *p, const dpose *q, double u, int side,
                      dpose *o)
{
    static cub_dv3 pp[CUB_MOTION_MAX_JOINTS], qp[CUB_MOTION_MAX_JOINTS], op[CUB_MOTION_MAX_JOINTS];
    static cub_dq pr[CUB_MOTION_MAX_JOINTS], qr[CUB_MOTION_MAX_JOINTS], orr[CUB_MOTION_MAX_JOINTS];
    const cub_join_leg *leg = &db->body.leg[side];
    pose_world(db->skel, p, pp, pr);
    pose_world(db->skel, q, qp, qr);
    pose_world(db->skel, o, op, orr);
    cub_dv3 a = pp[leg->ankle], b = qp[leg->ankle];
    u = fmax(0, fmin(1, u));
    double w = smooth(2 * u - 0.5);
    cub_join_goal g;
    g.ankle = cub_dv3_lerp(a, b, w);
    double travel = hypot(b.x - a.x, b.z - a.z);
    if (travel > STEP_MM)
        g.ankle.y += fmax(LIFT_MIN_MM, fmin(travel / 2, LIFT_MAX_MM)) * sin(CUB_VEC_PI * u);
    g.foot = cub_dq_slerp(pr[leg->ankle], qr[leg->ankle], w);
    g.forward = cub_dq_rotate(orr[db->body.hips], cub_dv3_make(0, 0, 1));
    cub_join_leg_ik(db->skel, leg, op, orr, &g, o->rot);
}

/* A root that is not the pelvis (Bandai's sits on the floor, the body
 * walking away from it) makes a blend of its rotation swing the body
 * through an arc: move the blended pose so the pelvis goes straight. */
static void pelvis_on_path(const cub_join_db *db, const dpose *p, const dpose *q, double w,
                           dpose *o)
{
    static cub_dv3 pp[CUB_MOTION_MAX_JOINTS], qp[CUB_MOTION_MAX_JOINTS], op[CUB_MOTION_MAX_JOINTS];
    static cub_dq rr[CUB_MOTION_MAX_JOINTS];
    int h = db->body.hips;
    pose_world(db->skel, p, pp, rr);
    pose_world(db->skel, q, qp, rr);
    pose_world(db->skel, o, op, rr);
    o->root = cub_dv3_add(o->root, cub_dv3_sub(cub_dv3_lerp(pp[h], qp[h], w), op[h]));
}

/* Bit s: foot s stands at frame f of db clip c. */
static unsigned char feet_at(const cub_join_db *db, int c, int f)
{
    return (unsigned char)(db->clips[c].foot[0][f] | db->clips[c].foot[1][f] << 1);
}

static void blend_seam(const cub_join_db *db, const seam *s, cub_join_result *r, int o0)
{
    cub_clip *out = &r->clip;
    static dpose p, q, o;
    int nj = db->skel->joint_count;
    for (int k = 0; k < s->n; k++) {
        get_frame(s->from, s->f0 + k, s->tf, &p);
        get_frame(s->to, s->t0 + k, s->tt, &q);
        r->stance[o0 + k] =
            feet_at(db, s->from_clip, s->f0 + k) & feet_at(db, s->to_clip, s->t0 + k);
        if (s->cut) {
            put_frame(out, o0 + k, k < s->n / 2 ? &p : &q);
            if (k == s->n / 2) r->stance[o0 + k] = 0;
            continue;
        }
        double u = (k + 1.0) / (s->n + 1.0), w = smooth(u);
        o.root = cub_dv3_lerp(p.root, q.root, w);
        for (int j = 0; j < nj; j++) {
            o.rot[j] = cub_dq_slerp(p.rot[j], q.rot[j], w);
            o.trans[j] = cub_dv3_lerp(p.trans[j], q.trans[j], w);
        }
        if (db->body.hips != 0) pelvis_on_path(db, &p, &q, w, &o);
        if (s->first_leg >= 0)
            for (int i = 0; i < 2; i++) {
                int side = i ? 1 - s->first_leg : s->first_leg;
                place_leg(db, &p, &q, 2 * u - i, side, &o);
            }
        put_frame(out, o0 + k, &o);
    }
}

static void copy_run(const cub_join_db *db, int c, int f0, int n, const cub_join_align *t,
                     cub_join_result *r, int o0)
{
    static dpose p;
    for (int k = 0; k < n; k++) {
        get_frame(db->clips[c].clip, f0 + k, t, &p);
        put_frame(&r->clip, o0 + k, &p);
        r->stance[o0 + k] = feet_at(db, c, f0 + k);
    }
}

/* Blend frames for a seam of distance d_mm2, at most cap: the residual
 * spread at blend_mm_per_frame. With the legs one at a time each leg gets
 * that many frames, so the seam is twice as long. */
static int blend_frames(const cub_join_db *db, double d_mm2, int feet, int cap)
{
    int n = (int)ceil(sqrt(d_mm2) / db->cfg.blend_mm_per_frame);
    n = n < db->cfg.min_blend ? db->cfg.min_blend : n > db->cfg.max_blend ? db->cfg.max_blend : n;
    n *= feet ? 2 : 1;
    return n < cap ? n : cap;
}

/* Which leg goes over first: the one the outgoing clip does not stand on
 * (it is free); when both or neither, the one with farther to go. */
static int first_leg(const cub_join_db *db, const seam *s)
{
    const cub_join_clip *c = &db->clips[s->from_clip];
    int l = c->foot[0][s->f0], r = c->foot[1][s->f0];
    if (l != r) return l ? 1 : 0;
    static dpose p, q;
    static cub_dv3 pp[CUB_MOTION_MAX_JOINTS], qp[CUB_MOTION_MAX_JOINTS];
    static cub_dq rr[CUB_MOTION_MAX_JOINTS];
    get_frame(s->from, s->f0, s->tf, &p);
    get_frame(s->to, s->t0 + s->n - 1, s->tt, &q);
    pose_world(db->skel, &p, pp, rr);
    pose_world(db->skel, &q, qp, rr);
    double d[2];
    for (int i = 0; i < 2; i++) {
        int aj = db->body.leg[i].ankle;
        d[i] = hypot(pp[aj].x - qp[aj].x, pp[aj].z - qp[aj].z);
    }
    return d[1] > d[0];
}

static cub_err alloc_out(const cub_join_db *db, const cub_clip *a, int frames, cub_join_result *out)
{
    memset(out, 0, sizeof *out);
    int trans = 0; /* translations out when any clip animates them */
    for (int c = 0; c < db->count; c++)
        trans |= db->clips[c].clip->trans_mm != NULL;
    size_t size = cub_motion_clip_mem_size(db->skel->joint_count, frames, trans);
    out->mem = malloc(size);
    out->stance = calloc((size_t)frames, 1);
    if (!out->mem || !out->stance) return CUB_ERR_NOMEM;
    return cub_motion_clip_init(&out->clip, db->skel, frames, a->frame_ns, trans, out->mem, size);
}

static cub_err build_direct(const cub_join_db *db, int a, int b, const cub_join_pick *pick,
                            int feet, cub_join_result *out)
{
    const cub_clip *ca = db->clips[a].clip, *cb = db->clips[b].clip;
    int na = ca->frame_count, nb = cb->frame_count;
    int n = blend_frames(db, pick->direct.d_mm2, feet & 1, na < nb ? na : nb);
    cub_err e = alloc_out(db, ca, na + nb - n, out);
    if (e) return e;
    seam s = {ca, cb, NULL, &pick->direct, na - n, 0, n, -1, a, b, (feet & CUB_JOIN_CUT) != 0};
    if (feet == 1) s.first_leg = first_leg(db, &s);
    copy_run(db, a, 0, na - n, NULL, out, 0);
    blend_seam(db, &s, out, na - n);
    copy_run(db, b, n, nb - n, &pick->direct, out, na);
    out->windows = 1;
    out->win_first[0] = na - n, out->win_frames[0] = n;
    return CUB_OK;
}

static cub_err build_searched(const cub_join_db *db, int a, int b, const cub_join_pick *pick,
                              int feet, cub_join_result *out)
{
    const cub_clip *ca = db->clips[a].clip, *cb = db->clips[b].clip;
    const cub_clip *cc = db->clips[pick->clip].clip;
    int na = ca->frame_count, nb = cb->frame_count, nc = pick->last - pick->first + 1;
    int n1 = blend_frames(db, pick->in.d_mm2, feet & 1, na < nc / 2 ? na : nc / 2);
    int n2 = blend_frames(db, pick->out.d_mm2, feet & 1, nb < nc / 2 ? nb : nc / 2);
    cub_err e = alloc_out(db, ca, na + nc + nb - n1 - n2, out);
    if (e) return e;
    int cut = (feet & CUB_JOIN_CUT) != 0;
    seam s1 = {ca, cc, NULL, &pick->in, na - n1, pick->first, n1, -1, a, pick->clip, cut};
    seam s2 = {cc, cb, &pick->in, &pick->out, pick->last - n2 + 1, 0, n2, -1, pick->clip, b, cut};
    if (feet == 1) {
        s1.first_leg = first_leg(db, &s1);
        s2.first_leg = first_leg(db, &s2);
    }
    int o = 0;
    copy_run(db, a, 0, na - n1, NULL, out, o), o += na - n1;
    blend_seam(db, &s1, out, o);
    out->win_first[0] = o, out->win_frames[0] = n1, o += n1;
    copy_run(db, pick->clip, pick->first + n1, nc - n1 - n2, &pick->in, out, o);
    o += nc - n1 - n2;
    blend_seam(db, &s2, out, o);
    out->win_first[1] = o, out->win_frames[1] = n2, o += n2;
    copy_run(db, b, n2, nb - n2, &pick->out, out, o);
    out->windows = 2;
    return CUB_OK;
}

cub_err cub_join_build(const cub_join_db *db, int a, int b, const cub_join_pick *pick, int feet,
                       cub_join_result *out)
{
    if (!db || !pick || !out || a < 0 || b < 0 || a >= db->count || b >= db->count)
        return CUB_ERR_ARG;
    cub_err e = pick->clip >= 0 ? build_searched(db, a, b, pick, feet, out)
                                : build_direct(db, a, b, pick, feet, out);
    if (e) {
        cub_join_result_free(out);
        return e;
    }
    out->floor_mm = db->clips[a].floor_mm;
    return CUB_OK;
}

void cub_join_result_free(cub_join_result *r)
{
    if (!r) return;
    free(r->mem);
    free(r->stance);
    memset(r, 0, sizeof *r);
}

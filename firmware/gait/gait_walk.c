/* gait — the walker (SEEDS.md § 003, the method put together): one
 * captured walk cycle played over a terrain, one frame per call. At each
 * foot-off the planner places the next footholds from the other foot's;
 * the swinging ankle goes from its foothold to the new one (the clip's own
 * path on flat ground, the raised quartic Bézier elsewhere); a planted foot
 * stays on its foothold and follows the clip's roll over it, and the root
 * follows it (the capture's stance slide taken out of the body too); each
 * foot point keeps its captured height over the ground under it; the
 * pelvis rides the mean ground of the feet and drops so both feet reach;
 * the leg IK (with limits) then sets the hip, knee and ankle rotations.
 *
 * Clip coordinates are "unwrapped": frame f of loop k sits at the clip's
 * position plus k cycles of root travel, so a foot planted before the
 * cycle wraps keeps its place. Q16.16 mm, Q2.30 rotations, no allocation. */
#include <limits.h>
#include <string.h>

#include "cub/gait.h"

#define DEG(d) ((cub_q16)(((int64_t)(d) * CUB_Q16_PI + 90) / 180))
#define UP ((cub_vec3){0, CUB_Q16_ONE, 0})

static const cub_vec3 *track(const cub_gait_walker *w, int foot, int toe)
{
    return toe ? w->c->toe_mm[foot] : w->c->ankle_mm[foot];
}

static cub_vec3 flat_xz(cub_vec3 v)
{
    return (cub_vec3){v.x, 0, v.z};
}

/* A clip point of frame f, loop k, unwrapped (its height untouched). */
static cub_vec3 unwrap(const cub_gait_walker *w, cub_vec3 v, int k)
{
    return (cub_vec3){v.x + k * w->cycle_u.x, v.y, v.z + k * w->cycle_u.z};
}

/* The captured ankle's velocity at frame f (central difference inside
 * the clip), mm per frame, clip axes. */
static cub_vec3 ankle_velocity(const cub_gait_walker *w, int foot, int f)
{
    const cub_vec3 *a = w->c->ankle_mm[foot];
    int n = w->c->clip->frame_count;
    int lo = f > 0 ? f - 1 : f, hi = f + 1 < n ? f + 1 : f;
    if (hi == lo) return (cub_vec3){0};
    return cub_fx_vec3_scale(cub_fx_vec3_sub(a[hi], a[lo]), CUB_Q16_ONE / (hi - lo));
}

static cub_vec3 yaw_rotate(cub_q16 c, cub_q16 s, cub_vec3 v)
{
    /* about y: x' = c x + s z, z' = -s x + c z */
    return (cub_vec3){cub_fx_add(cub_fx_mul(c, v.x), cub_fx_mul(s, v.z)), v.y,
                      cub_fx_sub(cub_fx_mul(c, v.z), cub_fx_mul(s, v.x))};
}

/* World (x, z) of an unwrapped clip point; y is left to the caller. */
static cub_vec3 to_world(const cub_gait_walker *w, cub_vec3 u)
{
    cub_vec3 d = yaw_rotate(w->yaw_c, w->yaw_s, flat_xz(cub_fx_vec3_sub(u, w->ref_u)));
    return cub_fx_vec3_add(flat_xz(w->origin_mm), d);
}

static cub_vec3 unit_xz(cub_vec3 v)
{
    cub_q16 l = cub_fx_vec3_length(flat_xz(v));
    if (l == 0) return (cub_vec3){0, 0, CUB_Q16_ONE};
    return (cub_vec3){cub_fx_div(v.x, l), 0, cub_fx_div(v.z, l)};
}

static void emit(const cub_gait_walker *w, cub_gait_event e)
{
    if (w->p.on_event) w->p.on_event(w->p.ctx, &e);
}

static uint8_t phase_at(const cub_gait_walker *w, int foot, int f)
{
    return w->c->phase[foot][f];
}

/* ---- the cycle ------------------------------------------------------------- */

static int off_start(const cub_gait_walker *w, int foot, int from)
{
    int n = w->c->clip->frame_count;
    for (int f = from > 1 ? from : 1; f < n; f++)
        if (phase_at(w, foot, f) == CUB_GAIT_OFF && phase_at(w, foot, f - 1) != CUB_GAIT_OFF)
            return f;
    return -1;
}

/* The cycle: from a left foot-off with the right foot down to the next
 * left foot-off. */
static bool find_cycle(cub_gait_walker *w)
{
    for (int a = off_start(w, 0, 1); a > 0; a = off_start(w, 0, a + 1)) {
        if (phase_at(w, 1, a) == CUB_GAIT_OFF) continue;
        int b = off_start(w, 0, a + 1);
        if (b < 0) return false;
        w->a = a;
        w->b = b;
        return true;
    }
    return false;
}

/* Frame f advanced by one inside the cycle; *k counts the wraps. */
static int next_frame(const cub_gait_walker *w, int f, int *k)
{
    if (++f < w->b) return f;
    ++*k;
    return w->a;
}

/* ---- feet ------------------------------------------------------------------ */

/* A foot point (0 ankle, 1 toe) of frame f, loop k, unwrapped, with its
 * share of the cycle's mismatch (as close_cycle turns the joints): the
 * captured foot at the cycle's end is not where the next loop's first
 * frame puts it (08_01: 22 mm aside, the foot turned 16 degrees in the
 * wrap's frame). From +1/2 of the mismatch at the cycle's first frame to
 * -1/2 at its end, so the two meet [ours]. */
static cub_vec3 clip_point(const cub_gait_walker *w, int foot, int pt, int f, int k)
{
    const cub_vec3 *tr = track(w, foot, pt);
    cub_vec3 u = unwrap(w, tr[f], k);
    if ((w->p.without & CUB_GAIT_NO_CLOSE) || f < w->a || f >= w->b) return u;
    cub_vec3 miss = cub_fx_vec3_sub(tr[w->b], cub_fx_vec3_add(tr[w->a], w->cycle_u));
    cub_q16 s = (cub_q16)(((int64_t)(f - w->a) << 16) / (w->b - w->a)) - CUB_Q16_ONE / 2;
    return cub_fx_vec3_sub(u, cub_fx_vec3_scale(miss, s));
}


/* The clip's floor under a foot planted at frame p: its lowest point
 * (ankle or toe) over the contact that begins there in the clip
 * (strike's first frame may have the other point still high). */
static cub_q16 clip_floor(const cub_gait_walker *w, int foot, int p)
{
    cub_q16 lo = CUB_Q16_MAX;
    int n = w->c->clip->frame_count;
    if (w->p.without & CUB_GAIT_NO_FLOOR) /* the whole clip's lowest foot point */
        for (int f = 0; f < n; f++)
            for (int i = 0; i < 4; i++)
                if (track(w, i / 2, i % 2)[f].y < lo) lo = track(w, i / 2, i % 2)[f].y;
    if (lo < CUB_Q16_MAX) return lo;
    for (int f = p; f < n && (f == p || phase_at(w, foot, f) != CUB_GAIT_OFF); f++) {
        cub_q16 a = track(w, foot, 0)[f].y, t = track(w, foot, 1)[f].y;
        if (a < lo) lo = a;
        if (t < lo) lo = t;
    }
    return lo;
}

static cub_q16 foot_len(const cub_gait_walker *w, int foot)
{
    return w->c->foot[foot].length_mm;
}

/* Ground point (ankle, world) a clip point maps to, on the terrain. */
static cub_vec3 ground_of(const cub_gait_walker *w, cub_vec3 u)
{
    cub_vec3 g = to_world(w, u);
    g.y = cub_gait_height(w->t, g.x, g.z);
    return g;
}

/* A foot at rest before the cycle starts: planted where the clip last put it. */
static void plant_initial(cub_gait_walker *w, int foot)
{
    int p = w->a - 1;
    while (p > 0 && phase_at(w, foot, p - 1) != CUB_GAIT_OFF)
        p--;
    cub_gait_walk_foot *ft = &w->feet[foot];
    ft->plant_u = track(w, foot, 0)[p];
    ft->floor_u = clip_floor(w, foot, p);
    ft->hold_mm = ground_of(w, ft->plant_u);
    ft->yaw_c = w->yaw_c;
    ft->yaw_s = w->yaw_s;
    ft->last_phase = phase_at(w, foot, w->a - 1);
    ft->pin_u[0] = track(w, foot, 0)[w->a - 1];
    ft->pin_u[1] = track(w, foot, 1)[w->a - 1];
}

void cub_gait_sole_points(cub_vec3 ankle_mm, cub_vec3 toe_mm, cub_q16 foot_mm, cub_q16 ankle_h_mm,
                          cub_vec3 out[6])
{
    cub_vec3 heel0 = {ankle_mm.x, ankle_mm.y - ankle_h_mm, ankle_mm.z};
    cub_vec3 d = cub_fx_vec3_sub(toe_mm, heel0);
    cub_q16 l = cub_fx_vec3_length(d);
    d = l ? cub_fx_vec3_scale(d, cub_fx_div(CUB_Q16_ONE, l)) : (cub_vec3){0, 0, CUB_Q16_ONE};
    cub_vec3 side = unit_xz(cub_fx_vec3_cross(d, UP));
    cub_q16 w = foot_mm / 5;
    /* ours: the heel a quarter foot behind the ankle, the toe tip a third
     * ahead of the ball (CMU's "toe" joint) */
    out[0] = cub_fx_vec3_sub(heel0, cub_fx_vec3_scale(d, foot_mm / 4));
    out[1] = cub_fx_vec3_add(toe_mm, cub_fx_vec3_scale(d, foot_mm / 3));
    out[2] = cub_fx_vec3_add(out[0], cub_fx_vec3_scale(side, w));
    out[3] = cub_fx_vec3_sub(out[0], cub_fx_vec3_scale(side, w));
    out[4] = cub_fx_vec3_add(out[1], cub_fx_vec3_scale(side, w));
    out[5] = cub_fx_vec3_sub(out[1], cub_fx_vec3_scale(side, w));
}

/* The height a sole point at (x, z) must keep: the terrain's; a
 * swinging foot's also the swing's clearance over an obstacle higher
 * than both its footholds (the path was raised for it, but on a model
 * of the foot: a flat sole; the posed foot's toe corner passed 08_01's
 * log 16.9 mm up) [ours]. */
static cub_q16 sole_need(const cub_gait_walker *w, const cub_gait_walk_foot *ft, cub_vec3 pt)
{
    cub_q16 h = cub_gait_height(w->t, pt.x, pt.z);
    if (!ft->swinging || !ft->rough) return h;
    cub_q16 level = ft->hold_mm.y > ft->next_mm.y ? ft->hold_mm.y : ft->next_mm.y;
    if (h <= level || h <= cub_gait_ground_height(w->t, pt.x, pt.z)) return h;
    cub_q16 clear = w->p.swing.clearance_mm > 0 ? w->p.swing.clearance_mm : CUB_Q16_INT(20);
    return cub_fx_add(h, clear);
}

/* How far the sole dips below what it must keep (>= 0). */
static cub_q16 sole_dip(const cub_gait_walker *w, int foot, cub_vec3 ankle, cub_vec3 toe)
{
    cub_vec3 pts[6];
    cub_gait_sole_points(ankle, toe, foot_len(w, foot), w->c->foot[foot].ankle_lift_mm, pts);
    cub_q16 dip = 0;
    for (int i = 0; i < 6; i++) {
        cub_q16 d = cub_fx_sub(sole_need(w, &w->feet[foot], pts[i]), pts[i].y);
        if (d > dip) dip = d;
    }
    return dip;
}

/* ---- planning at foot-off --------------------------------------------------- */

/* The signed angle from the heading to the unit direction u. */
static cub_q16 angle_to(const cub_gait_walker *w, cub_vec3 u)
{
    cub_vec3 h = {w->dir_x, 0, w->dir_z};
    return cub_fx_atan2(cub_fx_vec3_cross(h, u).y, cub_fx_vec3_dot(h, u));
}

/* The yaw (yaw_rotate's c, s) taking the unit direction d to h. */
static void yaw_between(cub_vec3 d, cub_vec3 h, cub_q16 *c, cub_q16 *s)
{
    *c = cub_fx_add(cub_fx_mul(d.x, h.x), cub_fx_mul(d.z, h.z));
    *s = cub_fx_sub(cub_fx_mul(d.z, h.x), cub_fx_mul(d.x, h.z));
}

static cub_vec3 stride_shift(const cub_gait_walker *w);

/* Where the root is from where the clip's mapping puts it: held back by
 * the pinned feet (follow_pins) and shifted by the plan's stride changes
 * (stride_change); the target is measured from there. */
static cub_vec3 held_back(const cub_gait_walker *w)
{
    return cub_fx_vec3_add(w->follow_mm, stride_shift(w));
}

/* Turn the heading toward the target by at most max_turn; the mapping is
 * rebased at the root so the body does not jump. */
static void steer(cub_gait_walker *w, cub_vec3 root_u, cub_vec3 target)
{
    cub_vec3 root = to_world(w, root_u);
    cub_vec3 want = flat_xz(cub_fx_vec3_sub(target, cub_fx_vec3_add(root, held_back(w))));
    cub_q16 dist = cub_fx_vec3_length(want);
    /* Half a step: the last step lands at most that far from the target
     * (a whole step left the box's bear a step short of its place). */
    cub_q16 half_step = cub_fx_vec3_length(flat_xz(w->cycle_u)) / 4;
    w->arrived = dist <= half_step;
    if (w->arrived || dist == 0) return;
    cub_vec3 h = {w->dir_x, 0, w->dir_z};
    cub_q16 ang = angle_to(w, unit_xz(want));
    cub_q16 lim = w->p.max_turn_rad > 0 ? w->p.max_turn_rad : DEG(10);
    ang = cub_fx_clamp(ang, -lim, lim);
    if (ang == 0) return;
    cub_q16 c = cub_fx_cos(ang), s = cub_fx_sin(ang);
    cub_vec3 nh = unit_xz(yaw_rotate(c, s, h));
    w->dir_x = nh.x;
    w->dir_z = nh.z;
    cub_q16 yc = cub_fx_sub(cub_fx_mul(w->yaw_c, c), cub_fx_mul(w->yaw_s, s));
    cub_q16 ys = cub_fx_add(cub_fx_mul(w->yaw_s, c), cub_fx_mul(w->yaw_c, s));
    w->origin_mm = root;
    w->ref_u = root_u;
    w->yaw_c = yc;
    w->yaw_s = ys;
}

static cub_vec3 ahead(const cub_gait_walker *w);

static cub_vec3 clip_dir(const cub_gait_walker *w)
{
    return unit_xz(w->travel_u);
}

/* The root follows the plan's stride changes (a half or 1.25 stride by
 * an obstacle): the later footholds are planned from this one, so the
 * feet stay shifted by the change; the root moves by half of it over this
 * swing and the other half over the other foot's next one, as the mean
 * of the feet does. It stayed on the clip's line before: by the log a
 * half step left the body half a stride ahead of both feet (02_01's
 * pelvis lowered 280 mm) [ours]. */
static void stride_change(cub_gait_walker *w, int foot, cub_q16 along, cub_vec3 from, cub_vec3 hold)
{
    cub_vec3 d = ahead(w);
    cub_q16 got = cub_fx_vec3_dot(flat_xz(cub_fx_vec3_sub(hold, from)), d);
    cub_vec3 half = cub_fx_vec3_scale(d, cub_fx_sub(got, along) / 2);
    w->feet[foot].stride_shift_mm = cub_fx_vec3_add(w->stride_due_mm, half);
    w->stride_due_mm = half;
}

/* The planner's inputs from the other foot's foothold; the step's length
 * and width are the clip's own for this step (so flat ground gives back
 * the capture); its foot base reaches the sole box's toe tip (a third
 * past the toe); the swing to each foothold is tested with sp. */
static cub_err plan_begin(const cub_gait_walker *w, int foot, const cub_gait_swing_params *sp,
                          cub_gait_planner *pl, cub_q16 *along_out)
{
    const cub_gait_walk_foot *o = &w->feet[!foot];
    cub_vec3 d0 = clip_dir(w);
    cub_vec3 rel = flat_xz(cub_fx_vec3_sub(w->feet[foot].next_u, o->plant_u));
    cub_vec3 back = cub_fx_vec3_sub(w->feet[foot].follow_at_mm, o->follow_at_mm);
    cub_q16 along = cub_fx_add(cub_fx_vec3_dot(rel, d0), cub_fx_vec3_dot(back, ahead(w)));
    cub_q16 lateral = cub_fx_add(cub_fx_sub(cub_fx_mul(rel.x, d0.z), cub_fx_mul(rel.z, d0.x)),
                                 cub_fx_sub(cub_fx_mul(back.x, w->dir_z), cub_fx_mul(back.z, w->dir_x)));
    cub_gait_plan_params pp = {.steps = w->p.steps,
                               .stride_mm = along > CUB_Q16_ONE ? along : CUB_Q16_ONE,
                               .width_mm = cub_fx_abs(lateral),
                               .foot_mm = foot_len(w, foot) + foot_len(w, foot) / 3,
                               .swing = sp};
    /* The planner's "left" is a side label: left of the heading gets +width. */
    cub_gait_start st = {o->hold_mm, lateral < 0, w->dir_x, w->dir_z, w->feet[foot].hold_mm};
    *along_out = along;
    return cub_gait_planner_begin(pl, &pp, &st);
}

/* The plan made ahead is this foot-off's: the same foot, frame and
 * obstacles, and the same inputs (the planner is a function of them and
 * the terrain). */
static bool ahead_fits(const cub_gait_walker *w, int foot, const cub_gait_planner *now)
{
    const cub_gait_planner *a = &w->ahead;
    return w->ahead_on && w->ahead_foot == foot && w->ahead_frame == w->frame &&
           w->ahead_loops == w->loops && w->ahead_obstacles == w->t->obstacle_count &&
           a->has_swing == now->has_swing && !memcmp(&a->p, &now->p, sizeof a->p) &&
           !memcmp(&a->swing, &now->swing, sizeof a->swing) &&
           !memcmp(&a->start, &now->start, sizeof a->start);
}

/* The plan for this foot-off: the one made ahead when it fits (finished
 * here if it is not yet), else made whole now. */
static cub_err plan(cub_gait_walker *w, int foot, const cub_gait_swing_params *sp,
                    cub_vec3 *hold)
{
    cub_gait_planner now;
    cub_q16 along;
    cub_err e = plan_begin(w, foot, sp, &now, &along);
    if (e) return e;
    if (ahead_fits(w, foot, &now))
        w->ahead_taken++;
    else
        w->ahead = now;
    w->ahead_on = 0;
    cub_gait_planner_run(&w->ahead, w->t, INT_MAX);
    w->plan = w->ahead.plan;
    if (w->ahead.err) return w->ahead.err;
    *hold = w->plan.steps[0].foot_mm;
    stride_change(w, foot, along, w->feet[!foot].hold_mm, *hold);
    return CUB_OK;
}

static void report_plan(cub_gait_walker *w, int foot)
{
    for (int i = 0; i < w->plan.count; i++)
        emit(w, (cub_gait_event){CUB_GAIT_EV_PLANNED, !foot, w->steps, i, 0,
                                 w->plan.steps[i].foot_mm});
    if (w->plan.backtracks)
        emit(w, (cub_gait_event){CUB_GAIT_EV_BACKTRACKED, !foot, w->steps, 0, w->plan.backtracks,
                                 w->plan.steps[0].foot_mm});
}

static cub_vec3 planted(const cub_gait_walker *w, const cub_gait_walk_foot *ft, int pt, cub_vec3 u);
static cub_q16 path_u(const cub_gait_walk_foot *ft, cub_vec3 ankle);

/* Where the ankle leaves the ground on the path, and the path's height
 * there over its start (path_height fades it out). */
static void fade_from_off(const cub_gait_walker *w, cub_gait_walk_foot *ft)
{
    ft->path_u0 = ft->path_lift0 = 0;
    if (!ft->rough) return;
    ft->path_u0 = path_u(ft, planted(w, ft, 0, ft->key_u[0]));
    cub_q16 lift = cub_fx_sub(cub_gait_bezier4(ft->path.p, ft->path_u0).y, ft->path.p[0].y);
    ft->path_lift0 = lift > 0 ? lift : 0;
}

/* The first end step (has_end): the end's facing, square to the line
 * from the right end foothold to the left (the feet of a clip standing
 * side by side). The end feet land turned to it (their swings turn them,
 * foot_yaw), the body and the knees' pole ease to it over the end swings
 * (turned); the walk's own heading and path are left as steered [ours:
 * steering alone turns 10 degrees a step and left the box's bear 47
 * degrees off the dance; turning the heading itself moved the root's path
 * aside and the pelvis dropped 96 mm to reach both feet]. */
static void face_end(cub_gait_walker *w)
{
    cub_vec3 lr = cub_fx_vec3_sub(w->p.end_mm[0], w->p.end_mm[1]);
    if (lr.x == 0 && lr.z == 0) return;
    w->end_face = unit_xz((cub_vec3){-lr.z, 0, lr.x});
    yaw_between(clip_dir(w), w->end_face, &w->end_yaw_c, &w->end_yaw_s);
}

/* The yaw a foot lands with: the walk's, or an end step's the end's
 * facing (face_end). */
static void foot_yaw(const cub_gait_walker *w, const cub_gait_walk_foot *ft, cub_q16 *c, cub_q16 *s)
{
    bool face = ft->at_end && (w->end_face.x || w->end_face.z);
    *c = face ? w->end_yaw_c : w->yaw_c;
    *s = face ? w->end_yaw_s : w->yaw_s;
}

/* The walk's end (params.has_end): this foot's step lands on its end
 * foothold once the planned one comes within half a step of it along the
 * heading, or past it, or once the other foot stands on its own; the
 * plan's first step is logged there [ours: the seed's planner has no end]. */
static void end_step(cub_gait_walker *w, int foot, cub_vec3 *hold)
{
    cub_gait_walk_foot *ft = &w->feet[foot];
    ft->at_end = 0;
    ft->end_shift_mm = (cub_vec3){0};
    if (!w->p.has_end) return;
    cub_vec3 e = flat_xz(w->p.end_mm[foot]);
    cub_vec3 r = flat_xz(cub_fx_vec3_sub(*hold, e));
    cub_q16 along = cub_fx_add(cub_fx_mul(r.x, w->dir_x), cub_fx_mul(r.z, w->dir_z));
    cub_q16 half = cub_fx_vec3_length(flat_xz(w->cycle_u)) / 4;
    if (!w->feet[!foot].at_end && along < -half) return;
    ft->at_end = 1;
    if (!w->feet[!foot].at_end) face_end(w);
    /* the foothold is where the ankle strikes; it stands on the end once
     * flat (the captured ankle rolls on 20-35 mm by then) */
    cub_q16 yc, ys;
    foot_yaw(w, ft, &yc, &ys);
    e = cub_fx_vec3_sub(e, yaw_rotate(yc, ys, flat_xz(cub_fx_vec3_sub(ft->stand_u, ft->next_u))));
    e.y = cub_gait_height(w->t, e.x, e.z);
    ft->end_shift_mm = flat_xz(cub_fx_vec3_sub(e, *hold));
    *hold = w->plan.steps[0].foot_mm = e;
}

/* The planner refuses a foothold whose swing needs more raises than this
 * [ours]: 16_11's right foot, planted 20 mm before the log, then needed
 * 76 (an apex 0.8 m up) and its toe still touched the log's top. 70 with
 * the stepped test at 64 samples; its swing to a half step (62 raises
 * then) needs 72 tested exactly (its toe tip dipped between samples), so
 * 75 with the raise solved (70 and 80 put 16_11's foot into the log:
 * docs/gait.md; a tuning figure). */
#ifndef PLAN_MAX_RAISES
#define PLAN_MAX_RAISES 75
#endif

/* The swing to hold: the planner's own test of it (from this foot's
 * foothold, with sp) unless the end step moved the foothold. */
static cub_err swing_to(cub_gait_walker *w, int foot, const cub_gait_swing_params *sp,
                        cub_vec3 hold)
{
    cub_gait_walk_foot *ft = &w->feet[foot];
    if (w->plan.swung && !ft->at_end) {
        ft->path = w->plan.first_swing;
        return CUB_OK;
    }
    return cub_gait_swing_path(w->t, sp, ft->hold_mm, hold, &ft->path);
}

/* Plan the step and the swing to it. The planner tests the swing to each
 * foothold it plans (step 0's from this foot's foothold) within
 * PLAN_MAX_RAISES, so the way to the foothold taken is clear; BLOCKED
 * (CUB_ERR_EMPTY) when no plan is found. */
static cub_gait_swing_params swing_params(const cub_gait_walker *w, int foot)
{
    cub_gait_swing_params sp = w->p.swing;
    sp.foot_mm = foot_len(w, foot) + foot_len(w, foot) / 3; /* to the sole box's toe tip */
    sp.heel_mm = foot_len(w, foot) / 4;                      /* ... and its heel */
    for (int i = 0; i < 2; i++) /* its corners, and the sway */
        sp.side_mm[i] = foot_len(w, foot) / 5 + w->feet[foot].sway_mm[i];
    if (sp.max_raises <= 0) sp.max_raises = PLAN_MAX_RAISES;
    return sp;
}

static cub_err plan_swing(cub_gait_walker *w, int foot, cub_vec3 *hold)
{
    cub_gait_walk_foot *ft = &w->feet[foot];
    cub_gait_swing_params sp = swing_params(w, foot);
    ft->path = (cub_gait_swing){0};
    cub_err e = plan(w, foot, &sp, hold);
    if (!e) end_step(w, foot, hold);
    if (!e && ft->rough) e = swing_to(w, foot, &sp, *hold);
    if (e) {
        ft->path = (cub_gait_swing){0};
        return CUB_ERR_EMPTY;
    }
    fade_from_off(w, ft);
    report_plan(w, foot);
    return CUB_OK;
}

/* How far the captured ankle strays sideways from the line between its
 * places at foot-off and strike over the len frames of the swing from f,
 * each way ([0] toward (d.z, 0, -d.x), d along the line, as the swing
 * path's side_mm): the swing path is tested along that line, the foot
 * passes beside it (08_01's foot swung 40 mm outside its line, over a
 * stone's corner). */
static void swing_sway(cub_gait_walker *w, int foot, int f, int k, int len)
{
    cub_gait_walk_foot *ft = &w->feet[foot];
    cub_vec3 from = ft->key_u[0], d = unit_xz(cub_fx_vec3_sub(ft->next_u, from));
    ft->sway_mm[0] = ft->sway_mm[1] = 0;
    for (int i = 0; i < len; i++, f = next_frame(w, f, &k)) {
        cub_vec3 r = flat_xz(cub_fx_vec3_sub(clip_point(w, foot, 0, f, k), from));
        cub_q16 side = cub_fx_sub(cub_fx_mul(r.x, d.z), cub_fx_mul(r.z, d.x));
        if (side > ft->sway_mm[0]) ft->sway_mm[0] = side;
        if (-side > ft->sway_mm[1]) ft->sway_mm[1] = -side;
    }
}

/* The captured ankle where the foot struck at frame p (loop k) is next
 * flat on the ground: stance's first frame after it. */
static cub_vec3 stand_at(const cub_gait_walker *w, int foot, int p, int k)
{
    for (int i = 0; i < w->b - w->a && phase_at(w, foot, p) != CUB_GAIT_STANCE; i++)
        p = next_frame(w, p, &k);
    return clip_point(w, foot, 0, p, k);
}

/* Does the root follow the pinned feet (see follow_pins)? */
static bool follows(const cub_gait_walker *w)
{
    return !(w->p.without & (CUB_GAIT_NO_PIN | CUB_GAIT_NO_FOLLOW));
}

/* The clip's ankle move of a pinned foot from frame f0 (loop k0) to f1
 * (k1), turned as the foot was planted (world, horizontal). */
static cub_vec3 pinned_move(const cub_gait_walker *w, int foot, int f0, int k0, int f1, int k1)
{
    const cub_gait_walk_foot *ft = &w->feet[foot];
    cub_vec3 d = cub_fx_vec3_sub(clip_point(w, foot, 0, f1, k1), clip_point(w, foot, 0, f0, k0));
    return yaw_rotate(ft->yaw_c, ft->yaw_s, flat_xz(d));
}

/* How far the root will follow the other foot's pin (follow_pins) over
 * the len frames of a swing from frame f (the swinging foot is the only
 * one not pinned meanwhile): the step is shortened by it, so the foot
 * strikes where the capture puts it from the body. */
static cub_vec3 follow_until(const cub_gait_walker *w, int other, int f, int k, int len)
{
    cub_vec3 back = {0};
    if (!follows(w)) return back;
    int g = f, kg = k, pf = f > w->a ? f - 1 : w->b - 1, pk = f > w->a ? k : k - 1;
    for (int i = 0; i <= len; i++) {
        if (phase_at(w, other, g) == CUB_GAIT_STANCE && phase_at(w, other, pf) == CUB_GAIT_STANCE)
            back = cub_fx_vec3_sub(back, pinned_move(w, other, pf, pk, g, kg));
        pf = g, pk = kg;
        g = next_frame(w, g, &kg);
    }
    return back;
}

/* Foot-off at frame f, loop k, before the plan: turn, find where the clip
 * lands the foot and how its swing goes. False: arrived. */
static bool swing_setup(cub_gait_walker *w, int foot, int f, int k, cub_vec3 target)
{
    cub_gait_walk_foot *ft = &w->feet[foot];
    steer(w, unwrap(w, w->c->clip->root_mm[f], k), target);
    if (w->p.has_end) w->arrived = ft->at_end && w->feet[!foot].at_end; /* on the end footholds */
    if (w->arrived) return false;
    int p = f, kk = k, len = 0;
    ft->key_u[0] = ft->key_u[1] = clip_point(w, foot, 0, f, k);
    ft->key_v[0] = ft->key_v[1] = ankle_velocity(w, foot, f);
    ft->key_at[0] = ft->key_at[1] = 0;
    while (phase_at(w, foot, p) == CUB_GAIT_OFF && len < w->b - w->a) {
        cub_vec3 u = clip_point(w, foot, 0, p, kk);
        if (u.y > ft->key_u[1].y) {
            ft->key_u[1] = u;
            ft->key_v[1] = ankle_velocity(w, foot, p);
            ft->key_at[1] = len;
        }
        p = next_frame(w, p, &kk);
        len++;
    }
    ft->key_u[2] = clip_point(w, foot, 0, p, kk);
    ft->key_v[2] = ankle_velocity(w, foot, p);
    ft->key_at[2] = len;
    ft->next_u = clip_point(w, foot, 0, p, kk);
    ft->next_floor = clip_floor(w, foot, p);
    ft->stand_u = stand_at(w, foot, p, kk);
    ft->follow_at_mm = cub_fx_vec3_add(w->follow_mm, follow_until(w, !foot, f, k, len));
    swing_sway(w, foot, f, k, len);
    ft->swing_at = w->ticks;
    ft->swing_len = len > 0 ? len : 1;
    ft->rough = !cub_gait_terrain_is_flat(w->t);
    return true;
}

/* Foot-off at frame f, loop k: set up, plan, shape the swing. False: no
 * swing (arrived, or BLOCKED): the walker stops. */
static bool begin_swing(cub_gait_walker *w, int foot, int f, int k, cub_vec3 target)
{
    cub_gait_walk_foot *ft = &w->feet[foot];
    if (!swing_setup(w, foot, f, k, target)) return false;
    cub_vec3 hold;
    if (plan_swing(w, foot, &hold)) {
        /* [ours] a step with no foothold or no clear way is not taken */
        emit(w, (cub_gait_event){CUB_GAIT_EV_BLOCKED, !foot, w->steps, 0, 0, ground_of(w, ft->next_u)});
        w->blocked = 1;
        return false;
    }
    ft->swinging = 1;
    ft->next_mm = hold;
    ft->key_mm = (w->p.without & CUB_GAIT_NO_KEYS)
                     ? 0
                     : cub_gait_key_pelvis(cub_fx_sub(hold.y, w->feet[!foot].hold_mm.y));
    ft->step = w->steps;
    w->steps++;
    return true;
}

static void land(cub_gait_walker *w, int foot)
{
    cub_gait_walk_foot *ft = &w->feet[foot];
    ft->swinging = 0;
    ft->hold_mm = ft->next_mm;
    ft->plant_u = ft->next_u;
    ft->floor_u = ft->next_floor;
    foot_yaw(w, ft, &ft->yaw_c, &ft->yaw_s);
    ft->has_rest = 0; /* its rest is on this foothold, once it stands */
    ft->skate_u[0] = ft->skate_u[1] = (cub_vec3){0};
    w->key_mm = ft->key_mm;
    w->end_shift_mm = cub_fx_vec3_add(w->end_shift_mm, cub_fx_vec3_scale(ft->end_shift_mm, CUB_Q16_ONE / 2));
    w->stride_shift_mm = cub_fx_vec3_add(w->stride_shift_mm, ft->stride_shift_mm);
    ft->stride_shift_mm = (cub_vec3){0};
    ft->end_shift_mm = (cub_vec3){0};
    emit(w, (cub_gait_event){CUB_GAIT_EV_TAKEN, !foot, ft->step, 0, 0, ft->hold_mm});
}

/* ---- per frame targets --------------------------------------------------------- */

/* Progress through the swing, Q16.16 in [0, 1]. */
static cub_q16 swing_s(const cub_gait_walker *w, const cub_gait_walk_foot *ft)
{
    int64_t s = ((int64_t)(w->ticks - ft->swing_at) << 16) / ft->swing_len;
    return cub_fx_clamp((cub_q16)s, 0, CUB_Q16_ONE);
}

/* A planted point (0 ankle, 1 toe): on its foothold, moved as the clip
 * rolls it, less the clip's own slide in stance (a flat foot is pinned). */
static cub_vec3 planted(const cub_gait_walker *w, const cub_gait_walk_foot *ft, int pt, cub_vec3 u)
{
    bool pin = !(w->p.without & CUB_GAIT_NO_PIN);
    if (pin && ft->last_phase == CUB_GAIT_STANCE && !ft->swinging) u = ft->pin_u[pt];
    cub_vec3 rel = cub_fx_vec3_sub(u, ft->plant_u);
    if (pin) rel = cub_fx_vec3_sub(rel, ft->skate_u[pt]);
    cub_vec3 d = yaw_rotate(ft->yaw_c, ft->yaw_s, flat_xz(rel));
    return cub_fx_vec3_add(flat_xz(ft->hold_mm), d);
}

/* An end foot's landing yaw (yc, ys) eased in from its planted one by
 * the swing's progress s: its captured offset from the strike is turned
 * by as much as the foot has turned. Turned by the whole of the end's
 * facing from the foot-off, the offset (half a stride early on) swung the
 * foot aside and back in over the swing's last frames (22 mm in the
 * strike's frame, return's second walk in) [ours]. */
static void ease_landing_yaw(const cub_gait_walk_foot *ft, cub_q16 s, cub_q16 *yc, cub_q16 *ys)
{
    if (!ft->at_end || s >= CUB_Q16_ONE || (*yc == ft->yaw_c && *ys == ft->yaw_s)) return;
    cub_q16 dc = cub_fx_add(cub_fx_mul(*yc, ft->yaw_c), cub_fx_mul(*ys, ft->yaw_s));
    cub_q16 ds = cub_fx_sub(cub_fx_mul(*ys, ft->yaw_c), cub_fx_mul(*yc, ft->yaw_s));
    cub_q16 a = cub_fx_add(cub_fx_atan2(ft->yaw_s, ft->yaw_c), cub_fx_mul(cub_fx_atan2(ds, dc), s));
    *yc = cub_fx_cos(a);
    *ys = cub_fx_sin(a);
}

/* A swinging point: its planted places at both ends, blended by s. */
static cub_vec3 swinging(const cub_gait_walker *w, const cub_gait_walk_foot *ft, int pt,
                         cub_vec3 u, cub_q16 s)
{
    cub_vec3 from = planted(w, ft, pt, u);
    cub_q16 yc, ys;
    foot_yaw(w, ft, &yc, &ys);
    ease_landing_yaw(ft, s, &yc, &ys);
    cub_vec3 d = yaw_rotate(yc, ys, flat_xz(cub_fx_vec3_sub(u, ft->next_u)));
    cub_vec3 to = cub_fx_vec3_add(flat_xz(ft->next_mm), d);
    return cub_fx_vec3_lerp(from, to, s);
}

/* The swinging ankle's progress along the path's line P0P4, Q16.16 in
 * [0, 1] (the control points lie evenly on that line, so B(u) is over
 * its u-th part). */
static cub_q16 path_u(const cub_gait_walk_foot *ft, cub_vec3 ankle)
{
    cub_vec3 d = flat_xz(cub_fx_vec3_sub(ft->path.p[4], ft->path.p[0]));
    int64_t dd = ((int64_t)d.x * d.x + (int64_t)d.z * d.z) >> 16; /* Q16.16 mm^2 */
    if (dd == 0) return 0;
    cub_vec3 r = flat_xz(cub_fx_vec3_sub(ankle, ft->path.p[0]));
    int64_t along = (int64_t)r.x * d.x + (int64_t)r.z * d.z; /* Q32.32 */
    int64_t u = along <= 0 ? 0 : along / dd;
    return (cub_q16)(u > CUB_Q16_ONE ? CUB_Q16_ONE : u);
}

/* The raised path's height where the swinging ankle is now: the Bezier
 * at the ankle's progress u, not at the swing's time (the captured ankle
 * starts and ends slowly: the path at time s was ahead of the foot at the
 * start and behind it at the end; 08_01's toe slid over a stone, 0 mm).
 * The ankle leaves the ground already u0 along (it rolled forward over
 * the toe through the lift), where the path is up by lift0: that lift
 * fades out linearly by the foothold, so the foot does not jump up at
 * the foot-off [ours]. */
static cub_q16 path_height(const cub_gait_walk_foot *ft, cub_vec3 ankle)
{
    cub_q16 u = path_u(ft, ankle), y = cub_gait_bezier4(ft->path.p, u).y;
    if (ft->path_u0 >= CUB_Q16_ONE) return y;
    cub_q16 left = cub_fx_div(CUB_Q16_ONE - u, CUB_Q16_ONE - ft->path_u0);
    return cub_fx_sub(y, cub_fx_mul(ft->path_lift0, cub_fx_clamp(left, 0, CUB_Q16_ONE)));
}

/* The height a point keeps over the ground: the clip's over its floor
 * (never below it). On rough ground, in the swing, the ground is the
 * higher of the ground alone (no obstacles) and the raised path where
 * the ankle is (path_y): the path was raised until the sole box over it
 * cleared every obstacle; the obstacle's own top under the point came in
 * with a jump at its edge (the foot lifted by the stone's height in a
 * frame) and only touching clearance. (Adding only the point's resting
 * height to the Bézier, not its captured swing height, was tried: the
 * foot then grazed the log, 0 mm, and turned 20 degrees in a frame.) */
static cub_q16 point_y(const cub_gait_walker *w, const cub_gait_walk_foot *ft, cub_vec3 at,
                       cub_q16 clip_y, cub_q16 s, cub_q16 path_y)
{
    cub_q16 floor = ft->swinging ? cub_fx_lerp(ft->floor_u, ft->next_floor, s) : ft->floor_u;
    cub_q16 over = cub_fx_sub(clip_y, floor);
    if (over < 0) over = 0;
    cub_q16 ground;
    if (ft->swinging && ft->rough) {
        ground = cub_gait_ground_height(w->t, at.x, at.z);
        if (path_y > ground) ground = path_y;
    } else {
        ground = cub_gait_height(w->t, at.x, at.z);
    }
    return cub_fx_add(ground, over);
}

/* The ankle at swing key k (its place blended as any swinging point's). */
static cub_vec3 key_point(const cub_gait_walker *w, const cub_gait_walk_foot *ft, int k)
{
    cub_q16 s = (cub_q16)(((int64_t)ft->key_at[k] << 16) / ft->swing_len);
    cub_vec3 a = swinging(w, ft, 0, ft->key_u[k], s);
    a.y = point_y(w, ft, a, ft->key_u[k].y, s, 0);
    return a;
}

/* A key's tangent for the Bezier: its captured velocity turned to the
 * walk's heading, times a third of the span (frames). */
static cub_vec3 key_tangent(const cub_gait_walker *w, const cub_gait_walk_foot *ft, int k, int span)
{
    cub_q16 yc, ys;
    foot_yaw(w, ft, &yc, &ys);
    cub_vec3 v = yaw_rotate(yc, ys, ft->key_v[k]);
    return cub_fx_vec3_scale(v, CUB_Q16_INT(span) / 3);
}

static cub_vec3 bezier3(const cub_vec3 p[4], cub_q16 s)
{
    cub_vec3 a = cub_fx_vec3_lerp(p[0], p[1], s), b = cub_fx_vec3_lerp(p[1], p[2], s);
    cub_vec3 c = cub_fx_vec3_lerp(p[2], p[3], s);
    a = cub_fx_vec3_lerp(a, b, s);
    b = cub_fx_vec3_lerp(b, c, s);
    return cub_fx_vec3_lerp(a, b, s);
}

/* Flat ground: the swinging ankle between its places at the swing's key
 * frames (foot-off, the apex [ours: a swing has no key frame between off
 * and strike, and a straight off-strike line would drag the foot],
 * strike). The seed's rule is straight segments: they start and stop the
 * ankle at once at each key (the knee pops at foot-off) and cost 13 mm of
 * leg joint error on 02_01; so, by default, a cubic Bezier through the
 * same keys, its tangents the capture's velocity at each key (the seed's
 * "frames between keys are interpolated with Bezier curves") [ours]. */
static cub_vec3 flat_swing(const cub_gait_walker *w, const cub_gait_walk_foot *ft)
{
    int t = w->ticks - ft->swing_at;
    int k = t >= ft->key_at[1] ? 1 : 0;
    int span = ft->key_at[k + 1] - ft->key_at[k];
    cub_q16 s = span > 0 ? (cub_q16)(((int64_t)(t - ft->key_at[k]) << 16) / span) : 0;
    s = cub_fx_clamp(s, 0, CUB_Q16_ONE);
    cub_vec3 p[4] = {key_point(w, ft, k), {0}, {0}, key_point(w, ft, k + 1)};
    if (w->p.straight_swing) return cub_fx_vec3_lerp(p[0], p[3], s);
    p[1] = cub_fx_vec3_add(p[0], key_tangent(w, ft, k, span));
    p[2] = cub_fx_vec3_sub(p[3], key_tangent(w, ft, k + 1, span));
    return bezier3(p, s);
}

/* Both feet on their end footholds (has_end): the one standing since its
 * end step stays flat, as it stood, not rolled up onto its toe for a
 * foot-off the walk will not make (its heel rose 105 mm before the stop
 * and settled back, the knee turning over) [ours]. */
static bool stays_flat(const cub_gait_walker *w, const cub_gait_walk_foot *ft)
{
    return w->p.has_end && w->feet[0].at_end && w->feet[1].at_end && !ft->swinging &&
           ft->has_rest && ft->last_phase != CUB_GAIT_STANCE;
}

static void foot_targets(cub_gait_walker *w, int foot, int f, int k)
{
    cub_gait_walk_foot *ft = &w->feet[foot];
    cub_q16 s = ft->swinging ? swing_s(w, ft) : 0;
    cub_vec3 au = clip_point(w, foot, 0, f, k), tu = clip_point(w, foot, 1, f, k);
    cub_vec3 a = ft->swinging ? swinging(w, ft, 0, au, s) : planted(w, ft, 0, au);
    cub_vec3 t = ft->swinging ? swinging(w, ft, 1, tu, s) : planted(w, ft, 1, tu);
    cub_q16 py = ft->swinging && ft->rough ? path_height(ft, a) : 0;
    a.y = point_y(w, ft, a, au.y, s, py);
    t.y = point_y(w, ft, t, tu.y, s, py);
    if (ft->swinging && !ft->rough && (w->p.key_swing || w->p.straight_swing)) {
        cub_vec3 seg = flat_swing(w, ft);
        t = cub_fx_vec3_add(t, cub_fx_vec3_sub(seg, a)); /* the foot moves with its ankle */
        a = seg;
    }
    /* The toe at the skeleton's foot length along the aimed direction:
     * the pose's toe lands where the sole guard looks. */
    const cub_skeleton *sk = w->c->clip->skel;
    cub_q16 len = cub_fx_vec3_length(sk->joints[w->c->toe[foot]].offset_mm);
    cub_vec3 d = cub_fx_vec3_sub(t, a);
    cub_q16 dl = cub_fx_vec3_length(d);
    if (dl > 0 && len > 0) t = cub_fx_vec3_add(a, cub_fx_vec3_scale(d, cub_fx_div(len, dl)));
    /* The sole guard: the whole foot lifts until no sole point is below. */
    cub_q16 dip = sole_dip(w, foot, a, t);
    a.y += dip;
    t.y += dip;
    ft->ankle_mm = a;
    ft->toe_mm = t;
    /* an end foot rests as it first stood flat (its heel rises 10 mm over
     * the stance; the end's feet are flat) */
    bool first = !(ft->at_end && ft->has_rest);
    if (!ft->swinging && ft->last_phase == CUB_GAIT_STANCE && first) {
        ft->rest_mm[0] = a;
        ft->rest_mm[1] = t;
        ft->has_rest = 1;
    }
    if (stays_flat(w, ft)) {
        ft->ankle_mm = ft->rest_mm[0];
        ft->toe_mm = ft->rest_mm[1];
    }
}

/* The pelvis height: the clip's over the mean shift of the two feet's
 * ground from the clip's floor. */
static cub_q16 ground_shift(const cub_gait_walker *w, int foot)
{
    const cub_gait_walk_foot *ft = &w->feet[foot];
    cub_q16 from = cub_fx_sub(ft->hold_mm.y, ft->floor_u);
    if (!ft->swinging) return from;
    cub_q16 to = cub_fx_sub(ft->next_mm.y, ft->next_floor);
    return cub_fx_lerp(from, to, swing_s(w, ft));
}

cub_q16 cub_gait_key_pelvis(cub_q16 dh_mm)
{
    cub_q16 dh = cub_fx_clamp(cub_fx_abs(dh_mm), 0, CUB_Q16_INT(200));
    return -dh / 4;
}

/* The pelvis key offset this frame: from the last strike's key to the
 * swinging foot's strike key along a cubic Bezier in time whose inner
 * control points repeat the ends (3s^2 - 2s^3: the pelvis neither jumps
 * nor starts at speed at a key); held while both feet are down. */
static cub_q16 key_offset(const cub_gait_walker *w)
{
    for (int foot = 0; foot < 2; foot++) {
        const cub_gait_walk_foot *ft = &w->feet[foot];
        if (!ft->swinging) continue;
        cub_q16 s = swing_s(w, ft);
        cub_q16 e = cub_fx_mul(cub_fx_mul(s, s), CUB_Q16_INT(3) - 2 * s);
        return cub_fx_add(w->key_mm, cub_fx_mul(cub_fx_sub(ft->key_mm, w->key_mm), e));
    }
    return w->key_mm;
}

/* ---- the pose --------------------------------------------------------------------- */

/* The share of the cycle's mismatch a frame takes, Q16.16: from -1/2 at
 * the cycle's first frame to +1/2 at its end, linear [ours]. From 0 to 1
 * (the first way) the body turned by up to the whole mismatch: 13.4 mm of
 * mean joint error on 02_01 against 8.9 (docs/gait.md), but fewer leg
 * joint samples over the source's p99 (2.4 % against 4.5 %). Eased into
 * the cycle's first and last quarter: less error, as many over p99. */
static cub_q16 close_share(const cub_gait_walker *w, int f)
{
    cub_q16 s = (cub_q16)(((int64_t)(f - w->a) << 16) / (w->b - w->a));
    return s - CUB_Q16_ONE / 2;
}

/* The captured cycle does not close: frame b is not frame a. Each joint
 * is turned, and the root raised, by its share of the mismatch, so the
 * loop joins without a pop [ours]. */
static void close_cycle(cub_gait_walker *w, int f)
{
    if (w->p.without & CUB_GAIT_NO_CLOSE) return;
    const cub_clip *c = w->c->clip;
    int nj = c->skel->joint_count;
    cub_q16 s = close_share(w, f);
    if (s == 0) return;
    for (int j = 0; j < nj; j++) {
        cub_quat delta = cub_fx_quat_mul(cub_fx_quat_conj(c->rot[w->b * nj + j]), c->rot[w->a * nj + j]);
        if (s < 0) delta = cub_fx_quat_conj(delta);
        cub_quat part = cub_fx_quat_nlerp(cub_fx_quat_identity(), delta, cub_fx_abs(s));
        w->pose.rot[j] = cub_fx_quat_normalize(cub_fx_quat_mul(w->pose.rot[j], part));
    }
    w->pose.root_mm.y += cub_fx_mul(c->root_mm[w->a].y - c->root_mm[w->b].y, s);
}

/* The root follows the end steps' shifts (has_end): half of each, over
 * its swing, so the body stays over feet the end moved [ours]. */
static cub_vec3 end_shift(const cub_gait_walker *w)
{
    cub_vec3 s = w->end_shift_mm;
    for (int foot = 0; foot < 2; foot++) {
        const cub_gait_walk_foot *ft = &w->feet[foot];
        if (ft->swinging)
            s = cub_fx_vec3_add(s, cub_fx_vec3_scale(ft->end_shift_mm, swing_s(w, ft) / 2));
    }
    return s;
}

/* How far into the arrival (has_end), Q16.16 in [0, 1]: half for each
 * end foot, eased over its swing (smoothstep: no speed at either end of
 * it, none while both feet are down between the swings), all once both
 * stand on their end footholds. */
static cub_q16 end_weight(const cub_gait_walker *w)
{
    cub_q16 k = 0;
    for (int foot = 0; foot < 2 && w->p.has_end; foot++) {
        const cub_gait_walk_foot *ft = &w->feet[foot];
        if (!ft->at_end) continue;
        cub_q16 s = ft->swinging ? swing_s(w, ft) : CUB_Q16_ONE;
        k += cub_fx_mul(cub_fx_mul(s, s), CUB_Q16_INT(3) - 2 * s) / 2;
    }
    return k;
}

/* How far the body has turned from the heading toward the end's facing:
 * the whole angle between them times the end weight. */
static cub_q16 turned(const cub_gait_walker *w)
{
    if (!w->end_face.x && !w->end_face.z) return 0;
    return cub_fx_mul(angle_to(w, w->end_face), end_weight(w));
}

static bool arriving_in_pose(const cub_gait_walker *w)
{
    return w->p.end_pose && w->p.end_pose->joint_count == w->pose.joint_count;
}

/* A thigh or a shin (the joints the leg solve turns)? */
static bool solved_leg_joint(const cub_gait_walker *w, int j)
{
    const cub_skeleton *sk = w->c->clip->skel;
    for (int i = 0; i < 2; i++) {
        int knee = sk->joints[w->c->ankle[i]].parent;
        if (j == knee || j == sk->joints[knee].parent) return true;
    }
    return false;
}

/* The arrival: every joint's rotation but the thighs' and shins' eased
 * toward the end pose by the end weight, the root's place over the second
 * end swing only (the legs are solved after, onto the feet). Over the
 * first the other foot still stands a step back: the root drawn to the
 * end stretched that leg past its reach and the knee turned over (177
 * degrees in a frame). The solve sets the thigh and the shin but for
 * their twist, and the knee's bend plane follows the pose's: eased toward
 * the end pose's, they turned the striking knee out of its hinge (wake's
 * second walk in: 42.6 degrees in the first end strike's frame, 12.6 of
 * them the bend) [ours]. */
static void arrive(cub_gait_walker *w)
{
    const cub_pose *e = w->p.end_pose;
    cub_q16 k = end_weight(w);
    if (!arriving_in_pose(w) || k <= 0) return;
    for (int j = 0; j < e->joint_count; j++)
        if (!solved_leg_joint(w, j)) w->pose.rot[j] = cub_fx_quat_nlerp(w->pose.rot[j], e->rot[j], k);
    if (k > CUB_Q16_ONE / 2)
        w->pose.root_mm = cub_fx_vec3_lerp(w->pose.root_mm, e->root_mm, 2 * k - CUB_Q16_ONE);
}

/* The root's shift by the plan's stride changes (stride_change): the
 * landed ones, and the swinging foot's share so far. */
static cub_vec3 stride_shift(const cub_gait_walker *w)
{
    cub_vec3 s = w->stride_shift_mm;
    for (int foot = 0; foot < 2; foot++) {
        const cub_gait_walk_foot *ft = &w->feet[foot];
        if (ft->swinging) s = cub_fx_vec3_add(s, cub_fx_vec3_scale(ft->stride_shift_mm, swing_s(w, ft)));
    }
    return s;
}

static void place_root(cub_gait_walker *w, int f, int k)
{
    const cub_clip *c = w->c->clip;
    cub_motion_clip_get_frame(c, f, &w->pose);
    close_cycle(w, f);
    cub_vec3 ru = unwrap(w, c->root_mm[f], k);
    ru.y = w->pose.root_mm.y;
    cub_vec3 r = to_world(w, ru);
    r.y = ru.y + (ground_shift(w, 0) + ground_shift(w, 1)) / 2;
    cub_vec3 shift = cub_fx_vec3_add(end_shift(w), held_back(w));
    w->pose.root_mm = cub_fx_vec3_add(r, shift);
    /* the body's turn: an end pose's root brings its own (arrive) */
    cub_q16 ang = cub_fx_atan2(w->yaw_s, w->yaw_c);
    if (!arriving_in_pose(w)) ang = cub_fx_add(ang, turned(w));
    cub_quat yaw = cub_fx_quat_from_axis_angle(UP, ang);
    w->pose.rot[0] = cub_fx_quat_normalize(cub_fx_quat_mul(yaw, w->pose.rot[0]));
    arrive(w);
}

/* The knees' pole: the heading, turned as the body is (turned). */
static cub_vec3 ahead(const cub_gait_walker *w)
{
    cub_vec3 h = {w->dir_x, 0, w->dir_z};
    cub_q16 a = turned(w);
    return a ? unit_xz(yaw_rotate(cub_fx_cos(a), cub_fx_sin(a), h)) : h;
}

static cub_err solve_leg(cub_gait_walker *w, int foot)
{
    cub_gait_walk_foot *ft = &w->feet[foot];
    cub_gait_leg_target t = {w->c->ankle[foot], w->c->toe[foot], ft->ankle_mm, ft->toe_mm, ahead(w)};
    cub_err e = cub_gait_leg_apply(w->c->clip->skel, &w->pose, &t, &w->p.limits, &ft->leg);
    /* The limits may have turned the foot into the ground, or the leg fallen
     * short: once more, the whole foot raised by what still dips. */
    cub_q16 dip = e ? 0 : sole_dip(w, foot, ft->leg.ankle_mm, ft->leg.toe_mm);
    if (dip <= 0) return e;
    ft->ankle_mm.y += dip;
    ft->toe_mm.y += dip;
    t.ankle_mm = ft->ankle_mm;
    t.toe_mm = ft->toe_mm;
    return cub_gait_leg_apply(w->c->clip->skel, &w->pose, &t, &w->p.limits, &ft->leg);
}

#define DROP_KNEE_DEG 165        /* [ours] the drop keeps each knee this open at most */
#define DROP_RELEASE_MM_S 120    /* [ours] the pelvis rises back at most this fast */

/* How far the pelvis lowers: so both feet reach with each knee at most
 * DROP_KNEE_DEG open, not at its limit (near straight the knee's angle
 * swings ~3 degrees per mm of reach: a leg held at full stretch by the
 * pinned foot popped the knee, 02_01's leg joints 4.2 % over the
 * source's p99 on flat); and rising back at most DROP_RELEASE_MM_S (the
 * drop fell by up to 15 mm in a frame at foot-off). Lowering is at once:
 * the feet must reach [ours]. */
static cub_q16 pelvis_drop(const cub_gait_walker *w, const cub_gait_leg legs[2],
                           const cub_vec3 targets[2])
{
    cub_gait_leg_limits dl = w->p.limits;
    if (dl.knee_min_rad == 0 && dl.knee_max_rad == 0) dl.knee_min_rad = DEG(25);
    if (dl.knee_max_rad == 0 || dl.knee_max_rad > DEG(DROP_KNEE_DEG)) dl.knee_max_rad = DEG(DROP_KNEE_DEG);
    cub_q16 want = cub_gait_pelvis_drop(legs, &dl, targets);
    uint32_t ns = w->c->clip->frame_ns ? w->c->clip->frame_ns : 8333333u;
    cub_q16 step = (cub_q16)((int64_t)CUB_Q16_INT(DROP_RELEASE_MM_S) * ns / 1000000000);
    return want < w->drop_mm - step ? w->drop_mm - step : want;
}

static cub_err pose_frame(cub_gait_walker *w, int f, int k)
{
    place_root(w, f, k);
    cub_gait_leg legs[2];
    const cub_skeleton *sk = w->c->clip->skel;
    cub_gait_pose_leg(sk, &w->pose, w->c->ankle[0], ahead(w), &legs[0]);
    cub_gait_pose_leg(sk, &w->pose, w->c->ankle[1], ahead(w), &legs[1]);
    cub_vec3 targets[2] = {w->feet[0].ankle_mm, w->feet[1].ankle_mm};
    w->drop_mm = pelvis_drop(w, legs, targets);
    if (w->p.without & CUB_GAIT_NO_DROP) w->drop_mm = 0;
    /* The key lowers the pelvis past what the reach needs: before the
     * drop it was swallowed by it (at a strike across a step the longer
     * leg is at full stretch, and the drop already sets the pelvis). */
    w->pose.root_mm.y += key_offset(w) - w->drop_mm;
    cub_err e = solve_leg(w, 0);
    return e ? e : solve_leg(w, 1);
}

/* Stance pins the foot where it began; leaving stance adds the clip's
 * slide meanwhile to what the foot's later roll discounts. */
static void pin(cub_gait_walker *w, int foot, uint8_t ph, int f, int k)
{
    cub_gait_walk_foot *ft = &w->feet[foot];
    bool was = ft->last_phase == CUB_GAIT_STANCE, is = ph == CUB_GAIT_STANCE;
    for (int pt = 0; pt < 2; pt++) {
        cub_vec3 u = clip_point(w, foot, pt, f, k);
        if (is && !was) ft->pin_u[pt] = u;
        if (was && !is)
            ft->skate_u[pt] =
                cub_fx_vec3_add(ft->skate_u[pt], flat_xz(cub_fx_vec3_sub(u, ft->pin_u[pt])));
    }
}

/* The root follows the pinned feet: the pin takes the capture's stance
 * slide (22-48 mm a stance on 02_01) out of the foot only, and the body
 * then moved against its foot by it (8 mm of the 20 mm leg error on flat
 * with the captured swing). So the root moves back by the slide a pinned
 * foot loses (the mean of both when both are pinned), and the body moves
 * over the foot as the capture's does over its own [ours]. */
static void follow_pins(cub_gait_walker *w, int f, int k)
{
    cub_vec3 sum = {0};
    int n = 0;
    for (int foot = 0; foot < 2; foot++) {
        cub_gait_walk_foot *ft = &w->feet[foot];
        cub_vec3 was = ft->slid_mm;
        ft->slid_mm = (cub_vec3){0};
        if (ft->swinging || ft->last_phase != CUB_GAIT_STANCE) continue;
        ft->slid_mm = yaw_rotate(ft->yaw_c, ft->yaw_s,
                                 flat_xz(cub_fx_vec3_sub(clip_point(w, foot, 0, f, k), ft->pin_u[0])));
        sum = cub_fx_vec3_add(sum, cub_fx_vec3_sub(ft->slid_mm, was));
        n++;
    }
    if (n && follows(w)) w->follow_mm = cub_fx_vec3_sub(w->follow_mm, cub_fx_vec3_scale(sum, CUB_Q16_ONE / n));
}

/* The root's travel over a cycle less what it follows of the pinned
 * feet's slide (follow_pins): the walk's direction. With the root's
 * travel alone the bear walked off its heading by the slide's sideways
 * part (08_01: 16 mm a step) [ours]. */
static cub_vec3 travel(const cub_gait_walker *w)
{
    cub_vec3 t = w->cycle_u;
    if (!follows(w)) return t;
    for (int f = w->a + 1; f < w->b; f++)
        for (int foot = 0; foot < 2; foot++) {
            if (phase_at(w, foot, f) != CUB_GAIT_STANCE || phase_at(w, foot, f - 1) != CUB_GAIT_STANCE) continue;
            bool both = phase_at(w, !foot, f) == CUB_GAIT_STANCE && phase_at(w, !foot, f - 1) == CUB_GAIT_STANCE;
            cub_vec3 d = flat_xz(cub_fx_vec3_sub(track(w, foot, 0)[f], track(w, foot, 0)[f - 1]));
            t = cub_fx_vec3_sub(t, both ? cub_fx_vec3_scale(d, CUB_Q16_ONE / 2) : d);
        }
    return t;
}

/* ---- the public calls ------------------------------------------------------------ */

cub_err cub_gait_walker_init(cub_gait_walker *w, const cub_gait_walk_clip *c,
                             const cub_gait_terrain *t, const cub_gait_walk_params *p)
{
    if (!w || !c || !t || !p || !c->clip || !c->clip->skel) return CUB_ERR_ARG;
    for (int i = 0; i < 2; i++)
        if (!c->ankle_mm[i] || !c->toe_mm[i] || !c->phase[i] || c->foot[i].length_mm <= 0)
            return CUB_ERR_ARG;
    *w = (cub_gait_walker){.c = c, .t = t, .p = *p};
    if (!find_cycle(w)) return CUB_ERR_FORMAT;
    const cub_vec3 *root = c->clip->root_mm;
    w->cycle_u = flat_xz(cub_fx_vec3_sub(root[w->b], root[w->a]));
    w->travel_u = travel(w);
    cub_vec3 d0 = clip_dir(w);
    cub_vec3 h = (p->dir_x || p->dir_z) ? unit_xz((cub_vec3){p->dir_x, 0, p->dir_z}) : d0;
    w->dir_x = h.x;
    w->dir_z = h.z;
    yaw_between(d0, h, &w->yaw_c, &w->yaw_s);
    w->origin_mm = flat_xz(p->start_mm);
    w->ref_u = root[w->a];
    w->frame = w->a;
    plant_initial(w, 0);
    plant_initial(w, 1);
    return CUB_OK;
}

/* ---- stopping ---------------------------------------------------------------------- */

#define SETTLE_FRAMES 12 /* [ours] the lifting foot flattens over 0.1 s at 120 fps */

static cub_q16 root_to(const cub_gait_walker *w, cub_vec3 target)
{
    cub_vec3 root = to_world(w, unwrap(w, w->c->clip->root_mm[w->frame], w->loops));
    root = cub_fx_vec3_add(root, held_back(w));
    return cub_fx_vec3_length(flat_xz(cub_fx_vec3_sub(target, root)));
}

/* Walk on: the target is beyond half a step again (after BLOCKED, only once
 * the caller has moved it: the same target would block again). */
static bool want_on(const cub_gait_walker *w, cub_vec3 target)
{
    if (w->blocked && target.x == w->stop_target.x && target.z == w->stop_target.z) return false;
    if (w->p.has_end && w->feet[0].at_end && w->feet[1].at_end) return false;
    return root_to(w, target) > cub_fx_vec3_length(flat_xz(w->cycle_u)) / 4;
}

/* The held frame: the one before the foot-off that stopped the walk. */
static cub_err hold_still(cub_gait_walker *w, const cub_pose **out)
{
    int f = w->frame - 1, k = w->loops;
    if (f < w->a) f = w->b - 1, k--;
    foot_targets(w, 0, f, k);
    foot_targets(w, 1, f, k);
    cub_gait_walk_foot *ft = &w->feet[w->stop_foot];
    cub_q16 s = ft->has_rest ? (cub_q16)(((int64_t)w->settle << 16) / SETTLE_FRAMES) : 0;
    ft->ankle_mm = cub_fx_vec3_lerp(ft->ankle_mm, ft->rest_mm[0], s);
    ft->toe_mm = cub_fx_vec3_lerp(ft->toe_mm, ft->rest_mm[1], s);
    cub_err e = pose_frame(w, f, k);
    *out = &w->pose;
    return e;
}

static void stop(cub_gait_walker *w, int foot, cub_vec3 target)
{
    w->stopped = 1;
    w->stop_foot = foot;
    w->stop_target = target;
    w->settle = 0;
}

/* ---- planning ahead ------------------------------------------------------------ */

/* The next foot-off from frame f, loop k, of a foot not swinging: its
 * foot, frame and loop; false when none comes within a cycle. */
static bool next_off(const cub_gait_walker *w, int *foot, int *f, int *k)
{
    for (int n = 0; n < w->b - w->a; n++, *f = next_frame(w, *f, k))
        for (*foot = 0; *foot < 2; ++*foot)
            if (!w->feet[*foot].swinging && phase_at(w, *foot, *f) == CUB_GAIT_OFF) return true;
    return false;
}

/* The next foot-off's plan a foothold test per frame, from the frame
 * after the last foot-off on: its set-up (the other foot landed on its
 * planned foothold, the turn, the clip's swing) on a copy of the walker
 * as the foot-off will find it (nothing it reads changes before then but
 * the target; ahead_fits checks), the tests on the frames after. The
 * feet are both down for 1-3 frames only in 08_01, so the plan is made
 * over the other foot's swing (16_11 on the forest floor: up to 8 tests
 * of a swing at one foot-off, each about a frame's work) [ours]. */
static void plan_ahead(cub_gait_walker *w, cub_vec3 target)
{
    if ((w->p.without & CUB_GAIT_NO_AHEAD) || (w->feet[0].swinging && w->feet[1].swinging)) return;
    if (w->ahead_on) {
        cub_gait_planner_run(&w->ahead, w->t, 1);
        return;
    }
    int foot, f = w->frame, k = w->loops;
    if (!next_off(w, &foot, &f, &k)) return;
    cub_gait_walker then = *w;
    then.p.on_event = NULL; /* its landing is not news */
    if (then.feet[!foot].swinging) land(&then, !foot);
    if (!swing_setup(&then, foot, f, k, target)) return;
    cub_gait_swing_params sp = swing_params(&then, foot);
    cub_q16 along;
    if (plan_begin(&then, foot, &sp, &w->ahead, &along)) return;
    w->ahead_on = 1;
    w->ahead_foot = foot;
    w->ahead_frame = f;
    w->ahead_loops = k;
    w->ahead_obstacles = w->t->obstacle_count;
}

cub_err cub_gait_walker_step(cub_gait_walker *w, cub_vec3 target_mm, const cub_pose **out)
{
    if (!w || !out) return CUB_ERR_ARG;
    if (w->stopped) {
        bool on = want_on(w, target_mm);
        w->settle += on ? -1 : (w->settle < SETTLE_FRAMES);
        if (!on || w->settle > 0) return hold_still(w, out);
        w->stopped = w->blocked = w->settle = 0;
    }
    int f = w->frame, k = w->loops, steps = w->steps;
    for (int foot = 0; foot < 2; foot++) {
        uint8_t ph = phase_at(w, foot, f);
        cub_gait_walk_foot *ft = &w->feet[foot];
        if (ph == CUB_GAIT_OFF && !ft->swinging && !begin_swing(w, foot, f, k, target_mm)) {
            stop(w, foot, target_mm);
            return hold_still(w, out);
        }
        if (ph != CUB_GAIT_OFF && ft->swinging) land(w, foot);
        pin(w, foot, ph, f, k);
        ft->last_phase = ph;
    }
    follow_pins(w, f, k);
    foot_targets(w, 0, f, k);
    foot_targets(w, 1, f, k);
    cub_err e = pose_frame(w, f, k);
    w->frame = next_frame(w, f, &w->loops);
    w->ticks++;
    if (w->steps == steps) plan_ahead(w, target_mm); /* a foot-off frame has its plan's work */
    *out = &w->pose;
    return e;
}

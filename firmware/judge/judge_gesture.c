/* judge: claps and waves from the hands (cub/judge.h gives the rules).
 * Distances in whole millimetres (ample for hands), ratios of the
 * shoulder width in Q16.16. */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "cub/judge.h"
#include "judge_internal.h"

#define MIN_WIDTH_MM 150 /* a shoulder width below this is tracker noise */
/* A wave's swing, reversal to reversal, takes at least this long: no arm
 * waves 6 times a second (half a cycle 83 ms; people wave 1-4 times); a
 * hand that turns back sooner is the recoil of a hit or a racket's
 * follow-through (at 15 fps: one frame, 67 ms). */
#define WAVE_SWING_MIN_MS 80

/* ratio (Q16.16) of width_mm, in mm. */
static int32_t part_of(cub_q16 ratio, int32_t width_mm)
{
    return (int32_t)(((int64_t)ratio * width_mm) >> 16);
}

void judge_gestures_reset(cub_judge *j)
{
    j->clap.n = 0;
    j->clap.met = 0;
    memset(j->wave, 0, sizeof j->wave);
}

static void hand_at(const cub_track_skeleton *s, int32_t out[2][3])
{
    static const int hand[2] = {CUB_KJ_HAND_L, CUB_KJ_HAND_R};
    for (int h = 0; h < 2; h++) {
        out[h][0] = judge_mm(s->joint_mm[hand[h]].x);
        out[h][1] = judge_mm(s->joint_mm[hand[h]].y);
        out[h][2] = judge_mm(s->joint_mm[hand[h]].z);
    }
}

static void clap_push(clap_state *c, int64_t t_us, int32_t gap_mm, const cub_track_skeleton *s)
{
    c->t_us[c->head] = t_us;
    c->gap_mm[c->head] = gap_mm;
    hand_at(s, c->hand_mm[c->head]);
    c->head = (c->head + 1) % JUDGE_HIST;
    if (c->n < JUDGE_HIST) c->n++;
}

/* The widest hand gap of the frames since t_us, and when it was. */
static int32_t clap_widest_since(const clap_state *c, int64_t t_us, int *slot)
{
    int32_t widest = 0;
    *slot = -1;
    for (int i = 0; i < c->n; i++) {
        int k = (c->head - 1 - i + 2 * JUDGE_HIST) % JUDGE_HIST;
        if (c->t_us[k] < t_us) break;
        if (c->gap_mm[k] > widest) {
            widest = c->gap_mm[k];
            *slot = k;
        }
    }
    return widest;
}

/* Both hands did a share of the closing: each moved toward the other by
 * at least a quarter of their closing along the line between them at the
 * open gap. A clap brings both hands in; a punch across the body, or a
 * hand brought to a still one, moves one. */
static int clap_both_hands(const int32_t from[2][3], const int32_t now[2][3])
{
    int64_t toward_r = 0, toward_l = 0; /* displacements dotted with the L->R line */
    for (int a = 0; a < 3; a++) {
        int64_t line = (int64_t)from[1][a] - from[0][a];
        toward_r += ((int64_t)now[0][a] - from[0][a]) * line;
        toward_l -= ((int64_t)now[1][a] - from[1][a]) * line;
    }
    int64_t closing = toward_r + toward_l;
    return closing > 0 && 4 * toward_r >= closing && 4 * toward_l >= closing;
}

/* The hands closed side to side: the change of the vector between them,
 * from the open gap to the meet, lies within 45 degrees of the shoulders'
 * line (clap_side). Palms clap across the body's midline; a hand brought down onto
 * the other (grasping a ball to throw it) closes up and down or in depth. */
static int clap_sideways(const int32_t from[2][3], const int32_t now[2][3],
                         const cub_track_skeleton *s, cub_q16 cos2)
{
    const cub_vec3 *sl = &s->joint_mm[CUB_KJ_SHOULDER_L], *sr = &s->joint_mm[CUB_KJ_SHOULDER_R];
    /* in cm: the products below stay under 2^63 for anything within 40 m */
    int64_t line[3] = {(judge_mm(sr->x) - (int64_t)judge_mm(sl->x)) / 10,
                       (judge_mm(sr->y) - (int64_t)judge_mm(sl->y)) / 10,
                       (judge_mm(sr->z) - (int64_t)judge_mm(sl->z)) / 10};
    int64_t along = 0, d2 = 0, l2 = 0;
    for (int a = 0; a < 3; a++) {
        int64_t d = (((int64_t)from[1][a] - from[0][a]) - ((int64_t)now[1][a] - now[0][a])) / 10;
        along += d * line[a];
        d2 += d * d;
        l2 += line[a] * line[a];
    }
    if (l2 == 0) return 0;
    /* the closing's part along the line, squared, >= cos2 of all of it */
    return (along * along / l2) * CUB_Q16_ONE >= d2 * cos2;
}

/* The hands meet: the gap is under clap_meet of the width, or would have
 * been between two frames. At the closing speed of a clap the hands
 * travel up to a shoulder width between two Kinect frames (15 fps), so the
 * sampled gap nearest the contact can be up to half that frame's closing
 * above it: clap_slack of it (1/2) is allowed on top of clap_meet. (Off
 * until clap_sideways: near-meets of a boxing guard and a grasp then
 * passed it, docs/gestures_eval.md.) */
static int clap_meets(const clap_state *c, int32_t gap, int32_t meet_mm, cub_q16 slack)
{
    int32_t closing = 0;
    if (c->n > 0) closing = c->gap_mm[(c->head - 1 + JUDGE_HIST) % JUDGE_HIST] - gap;
    return gap < meet_mm + (closing > 0 ? part_of(slack, closing) : 0);
}

/* The hands came together like a clap: open by clap_open of the width
 * within clap_approach_ms, and closed from there at clap_speed widths a
 * second or faster on average (a clap, not hands brought together to hold
 * something). */
static int clap_approached(const cub_judge *j, int64_t t_us, const cub_track_skeleton *s,
                           int32_t gap, int32_t width_mm)
{
    const cub_judge_desc *d = &j->d;
    const clap_state *c = &j->clap;
    int k;
    int32_t widest = clap_widest_since(c, t_us - (int64_t)d->clap_approach_ms * 1000, &k);
    if (k < 0 || widest < part_of(d->clap_open, width_mm)) return 0;
    int32_t now[2][3];
    hand_at(s, now);
    /* closed mm / elapsed s >= speed mm/s, in integers: mm * 1e6 >= speed * us */
    return (int64_t)(widest - gap) * 1000000 >=
               (int64_t)part_of(d->clap_speed, width_mm) * (t_us - c->t_us[k]) &&
           clap_both_hands(c->hand_mm[k], now) &&
           clap_sideways(c->hand_mm[k], now, s, d->clap_side);
}

/* Hands in clapping position, from their height h (0 at hip-centre, 1 at
 * shoulder-centre height) and the forearms' slope (rise over forward
 * reach, summed over both forearms; the hands must be ahead of the
 * elbows), measured on UTKinect and MSR Action3D:
 * - h in [-1/8, 1.5] (a low clap dips below the hip-centre: UTKinect
 *   -0.05) and the midpoint not behind the shoulders;
 * - above shoulder-centre (h > 1), slope <= 1/2: a high clap reaches
 *   forward (MSR: 0.2..0.33 at h 1.1..1.3), a two-hand overhead wave
 *   points the forearms up (UTKinect: slope 0.66 and more, h 1.1 and up);
 * - slope >= -1/2, and >= -1/3 below h = 1/4: hands clasped at the belt
 *   (before a throw, when lowering the arms) hang the forearms (-0.37 and
 *   steeper at h ~0.05), while low claps keep them near level (-0.27 at
 *   h 0.03..0.12; -0.40 at h 0.3). */
static int clap_pose(const cub_track_skeleton *s, int32_t width_mm)
{
    const cub_vec3 *w = s->joint_mm;
    int64_t hip = judge_mm(w[CUB_KJ_HIP_CENTRE].y);
    int64_t h_mm = judge_mm(w[CUB_KJ_SHOULDER_CENTRE].y) - hip;
    int64_t rel = ((int64_t)judge_mm(w[CUB_KJ_HAND_L].y) + judge_mm(w[CUB_KJ_HAND_R].y)) / 2 - hip;
    int64_t mz = ((int64_t)judge_mm(w[CUB_KJ_HAND_L].z) + judge_mm(w[CUB_KJ_HAND_R].z)) / 2;
    int64_t dy = (int64_t)judge_mm(w[CUB_KJ_HAND_L].y) - judge_mm(w[CUB_KJ_ELBOW_L].y) +
                 judge_mm(w[CUB_KJ_HAND_R].y) - judge_mm(w[CUB_KJ_ELBOW_R].y);
    int64_t reach = (int64_t)judge_mm(w[CUB_KJ_ELBOW_L].z) - judge_mm(w[CUB_KJ_HAND_L].z) +
                    judge_mm(w[CUB_KJ_ELBOW_R].z) - judge_mm(w[CUB_KJ_HAND_R].z);
    if (h_mm <= 0 || 8 * rel < -h_mm || 2 * rel > 3 * h_mm || reach <= 0) return 0;
    if (mz > (int64_t)judge_mm(w[CUB_KJ_SHOULDER_CENTRE].z) + width_mm / 2) return 0;
    if (rel > h_mm && 2 * dy > reach) return 0;
    if (2 * dy < -reach) return 0;
    return 4 * rel >= h_mm || 3 * dy >= -reach;
}

static void clap_step(cub_judge *j, int64_t t_us, const cub_track_skeleton *s, int32_t width_mm,
                      cub_judge_out *out)
{
    clap_state *c = &j->clap;
    const cub_judge_desc *d = &j->d;
    int32_t gap = judge_dist_mm(s->joint_mm[CUB_KJ_HAND_L], s->joint_mm[CUB_KJ_HAND_R]);
    if (c->met) {
        if (gap < c->min_gap_mm) c->min_gap_mm = gap;
        if (gap - c->min_gap_mm >= part_of(d->clap_part, width_mm)) {
            c->met = 0;
            c->clapped = 1;
            c->last_clap_us = t_us;
            memset(j->wave, 0, sizeof j->wave); /* hands that met were no wave */
            cub_judge_event e = {
                .ev = {.t_us = t_us, .type = CUB_EV_CLAP},
                .kind = CUB_JUDGE_CLAP, .why = CUB_JUDGE_WHY_CLAP,
                .move = -1, .rep = -1, .feature = -1, .set = -1, .side = -1,
                .value = CUB_Q16_INT(c->min_gap_mm),
            };
            judge_emit(j, out, &e);
        } else if (t_us - c->met_us > (int64_t)d->clap_part_ms * 1000) {
            c->met = 0; /* hands held together: no clap */
        }
    } else if (clap_meets(c, gap, part_of(d->clap_meet, width_mm), d->clap_slack) &&
               (!c->clapped || t_us - c->last_clap_us >= (int64_t)d->clap_refractory_ms * 1000) &&
               clap_approached(j, t_us, s, gap, width_mm) && clap_pose(s, width_mm)) {
        c->met = 1;
        c->met_us = t_us;
        c->min_gap_mm = gap;
    }
    clap_push(c, t_us, gap, s);
}

static void wave_restart(wave_state *w, int64_t t_us, int32_t x, int32_t y)
{
    memset(w, 0, sizeof *w);
    w->active = 1;
    w->lo_mm = w->hi_mm = w->extreme_mm = w->from_mm = x;
    w->ylo_mm = w->yhi_mm = y;
    w->last_us = t_us;
}

/* The swing was sideways: a wave swings the hand about the elbow (or the
 * shoulder) across the body's front, so its path spans no more up and
 * down than across; drawing a circle, throwing or serving move it up and
 * down more. */
static int wave_sideways(const wave_state *w)
{
    int32_t across = w->extreme_mm - w->from_mm;
    if (across < 0) across = -across;
    return w->yhi_mm - w->ylo_mm <= across;
}

/* A swing ended at a reversal: it counts when it was sideways, otherwise
 * it restarts the count. */
static void wave_swing_done(wave_state *w, int64_t t_us, int32_t x, int32_t y)
{
    int swung = t_us - w->last_us >= (int64_t)WAVE_SWING_MIN_MS * 1000;
    if (swung) { /* a turn, sideways or not, for wave_paired */
        w->turn_us = t_us;
        w->turn_dir = w->dir;
        w->swing_from_mm = w->from_mm;
    }
    if (swung && wave_sideways(w)) {
        w->reversals++;
    } else {
        w->reversals = 0;
    }
    w->from_mm = w->extreme_mm;
    w->extreme_mm = x;
    w->ylo_mm = w->yhi_mm = y;
    w->last_us = t_us;
}

/* Direction changes of the hand's x with hysteresis `swing`; y the hand's
 * height for wave_sideways. */
static void wave_track(wave_state *w, int64_t t_us, int32_t x, int32_t y, int32_t swing)
{
    if (y < w->ylo_mm) w->ylo_mm = y;
    if (y > w->yhi_mm) w->yhi_mm = y;
    if (w->dir == 0) {
        if (x < w->lo_mm) w->lo_mm = x;
        if (x > w->hi_mm) w->hi_mm = x;
        if (x - w->lo_mm >= swing || w->hi_mm - x >= swing) {
            w->dir = x - w->lo_mm >= swing ? 1 : -1;
            w->from_mm = w->dir > 0 ? w->lo_mm : w->hi_mm;
            w->extreme_mm = x;
            w->last_us = t_us;
        }
        return;
    }
    if ((x - w->extreme_mm) * w->dir > 0) {
        w->extreme_mm = x;
    } else if ((w->extreme_mm - x) * w->dir >= swing) {
        w->dir = -w->dir;
        wave_swing_done(w, t_us, x, y);
    }
}

/* Both arms swept overhead together, each turning back within
 * wave_pair_ms of the other, the other hand still up: a two-hand wave,
 * seen at its first reversal (one arc out and over the head and back is
 * a two-hand wave). The turns need not be sideways (wave_sideways is for
 * one hand's loops): arms swept up from the sides rise as they go out.
 * In mirror (the hands turn apart), no one-armed movement (a throw, a
 * serve, a loop) does it. In step (both turn the same way) the hands
 * must also be at least a shoulder width apart: hands that hold one
 * thing (a club, a ball) move in step as well, but together; and a golf
 * swing's lower hand drops below its shoulder (the other hand up). */
static int wave_paired(const cub_judge *j, int side, int64_t t_us, int32_t gap_mm,
                       int32_t width_mm)
{
    const wave_state *w = &j->wave[side], *o = &j->wave[!side];
    if (!(w->turn_us == t_us && o->active && !o->fired && !o->dipped &&
          o->turn_us > 0 && t_us - o->turn_us <= (int64_t)j->d.wave_pair_ms * 1000))
        return 0;
    return o->turn_dir == -w->turn_dir || gap_mm >= width_mm;
}

/* One sweep of one raised arm, seen as it ends: a wave made of a single
 * arc (MSR's high arm wave of some people: out, over the head across the
 * body and back out). The swing that ended at the last turn was sideways
 * (counted), began outside the shoulder and crossed the body's midline;
 * the hand is now back outside its shoulder, and all this time in front
 * of it. A throw or a serve sweeps the arm over the head alike, but it
 * draws the hand back behind the shoulder first (the wind-up); a wave is
 * made facing whom one waves to. x, mid: the hand's and the shoulder
 * centre's x from the shoulder; out: +1 when the arm's outside is +x. */
static void wave_sweep_turned(wave_state *w, int64_t t_us, int32_t mid, int out)
{
    if (w->turn_us != t_us) return;
    w->crossed = w->reversals > 0 && out * w->swing_from_mm >= 0 &&
                 out * (w->from_mm - mid) < 0;
}

static int wave_swept(const wave_state *w, int32_t x, int out)
{
    return w->crossed && !w->behind && w->dir == out && out * x >= 0;
}

static void wave_step(cub_judge *j, int64_t t_us, const cub_track_skeleton *s, int side,
                      int32_t width_mm, cub_judge_out *out)
{
    static const int hand[2] = {CUB_KJ_HAND_L, CUB_KJ_HAND_R};
    static const int elbow[2] = {CUB_KJ_ELBOW_L, CUB_KJ_ELBOW_R};
    static const int shoulder[2] = {CUB_KJ_SHOULDER_L, CUB_KJ_SHOULDER_R};
    wave_state *w = &j->wave[side];
    const cub_vec3 *p = s->joint_mm;
    int raised = p[hand[side]].y > p[elbow[side]].y && p[hand[side]].y > p[shoulder[side]].y &&
                 s->confidence[hand[side]] > 0;
    int32_t x = judge_mm(p[hand[side]].x) - judge_mm(p[shoulder[side]].x);
    int32_t y = judge_mm(p[hand[side]].y) - judge_mm(p[shoulder[side]].y);
    if (!raised) {
        w->dipped = 1;
        return;
    }
    if (!w->active || t_us - w->last_us > (int64_t)j->d.wave_gap_ms * 1000) {
        wave_restart(w, t_us, x, y);
    } else if (w->dipped) {
        /* a wave swings with the hand up; a hand that came back up from
         * below went round a loop (drawing a circle, a throw): its swings
         * start afresh, in the same episode (no second event) */
        int fired = w->fired;
        wave_restart(w, t_us, x, y);
        w->fired = fired;
    }
    /* the side of the body this arm is on, from the skeleton itself (the
     * detectors are mirror-blind: the image may be mirrored) */
    int outward = p[shoulder[side]].x >= p[CUB_KJ_SHOULDER_CENTRE].x ? 1 : -1;
    if (judge_mm(p[hand[side]].z) > judge_mm(p[shoulder[side]].z)) w->behind = 1;
    wave_track(w, t_us, x, y, part_of(j->d.wave_swing, width_mm));
    wave_sweep_turned(w, t_us, judge_mm(p[CUB_KJ_SHOULDER_CENTRE].x) - judge_mm(p[shoulder[side]].x),
                      outward);
    int32_t gap = judge_dist_mm(p[CUB_KJ_HAND_L], p[CUB_KJ_HAND_R]);
    int both = !w->fired && wave_paired(j, side, t_us, gap, width_mm);
    if (w->fired ||
        (w->reversals < j->d.wave_reversals && !both && !wave_swept(w, x, outward)))
        return;
    w->fired = 1;
    if (both) j->wave[!side].fired = 1; /* one event for the two hands */
    cub_judge_event e = {
        .ev = {.t_us = t_us, .type = CUB_EV_NONE},
        .kind = CUB_JUDGE_WAVE, .why = CUB_JUDGE_WHY_WAVE,
        .move = -1, .rep = -1, .feature = -1, .set = -1, .side = side,
        .value = CUB_Q16_INT(w->reversals),
    };
    judge_emit(j, out, &e);
}

/* The shoulder width the ratios read, followed at 1/16 per frame: the
 * Kinect's shoulders collapse for a few frames when the arms cross over
 * the head, and such frames (under 0.6 of the width) are left out. */
static int32_t shoulder_width(cub_judge *j, const cub_track_skeleton *s)
{
    int32_t w = judge_dist_mm(s->joint_mm[CUB_KJ_SHOULDER_L], s->joint_mm[CUB_KJ_SHOULDER_R]);
    if (w < MIN_WIDTH_MM) w = MIN_WIDTH_MM;
    if (j->width_mm == 0)
        j->width_mm = w;
    else if ((int64_t)w * 10 >= (int64_t)j->width_mm * 6)
        j->width_mm += (w - j->width_mm) / 16;
    return j->width_mm;
}

void judge_gestures(cub_judge *j, int64_t t_us, const cub_track_skeleton *s, cub_judge_out *out)
{
    int32_t width = shoulder_width(j, s);
    if (s->confidence[CUB_KJ_HAND_L] > 0 && s->confidence[CUB_KJ_HAND_R] > 0)
        clap_step(j, t_us, s, width, out);
    else
        j->clap.met = 0;
    for (int side = 0; side < 2; side++)
        wave_step(j, t_us, s, side, width, out);
}

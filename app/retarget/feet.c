/* Feet: floor placement, foot contacts found in the source, and the
 * analytic two-bone leg IK that pins the target's ankle during a contact.
 * A human foot in contact is rarely flat in the data (heel strike, toe
 * off, the marker set's own pitch), and the bear's foot is a stiff paw:
 * so during a contact the bear's foot is put flat on the floor (its
 * heading kept) with the ankle at its rest height, and the floor is where
 * those flat contacts stand - not the lowest point a swinging toe reaches. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cub/join.h"
#include "rt_ctx.h"

#define BLEND_FRAMES 4       /* IK eases in/out over this many frames */

void rt_target_world(const rt_ctx *c, int f, cub_dv3 *pos, cub_dq *rot)
{
    rt_forward(c->tgt, c->root[f], c->local + (size_t)f * c->tj, NULL, pos, rot);
}

/* Lowest foot joint over the clip. */
static double lowest_foot(const rt_ctx *c)
{
    cub_dv3 pos[CUB_MOTION_MAX_JOINTS];
    cub_dq rot[CUB_MOTION_MAX_JOINTS];
    double low = INFINITY;
    for (int f = 0; f < c->frames; f++) {
        rt_target_world(c, f, pos, rot);
        for (int j = 0; j < c->tj; j++)
            if (c->is_foot[j] && pos[j].y < low)
                low = pos[j].y;
    }
    return low;
}

static void shift_root(rt_ctx *c, cub_dv3 by)
{
    for (int f = 0; f < c->frames; f++)
        c->root[f] = cub_dv3_add(c->root[f], by);
}

/* Contacts of one foot from the source ankle (scaled): low and slow, runs
 * of at least 3 frames (the rule cub_join_contacts shares). */
static void find_contacts(rt_ctx *c, int side)
{
    int l = c->link_of[c->foot[side]];
    cub_join_track t = {c->lpos + l, (size_t)c->links, c->k, c->frames, c->dt_s};
    cub_join_contact_cfg cfg = {c->d.contact_height_mm, c->d.contact_speed_mm_s, 0};
    cub_join_contacts(&t, &cfg, cub_join_track_lowest(&t), c->contact[side]);
}

/* Move the leg of `side` in frame f so its ankle reaches target; the knee
 * stays in its current bend plane (forward when straight) and the foot
 * turns to the world rotation foot_w. */
static void leg_ik(rt_ctx *c, int f, int side, cub_dv3 target, cub_dq foot_w)
{
    cub_dv3 pos[CUB_MOTION_MAX_JOINTS];
    cub_dq rot[CUB_MOTION_MAX_JOINTS];
    rt_target_world(c, f, pos, rot);
    cub_join_leg leg = {c->up_leg[side], c->leg[side], c->foot[side]};
    cub_join_goal goal = {target, foot_w, cub_dq_rotate(rot[c->hips], cub_dv3_make(0, 0, 1))};
    cub_join_leg_ik(c->tgt, &leg, pos, rot, &goal, c->local + (size_t)f * c->tj);
}

/* The foot's world rotation in frame f. */
static cub_dq foot_rot_at(const rt_ctx *c, int f, int side)
{
    cub_dv3 pos[CUB_MOTION_MAX_JOINTS];
    cub_dq rot[CUB_MOTION_MAX_JOINTS];
    rt_target_world(c, f, pos, rot);
    return rot[c->foot[side]];
}

/* The foot flat on the floor: only the heading of rot is kept (the rest
 * foot is flat, toe along +z). A foot pointing straight down or up has no
 * heading of its own; the hips give it. */
static cub_dq flat_foot(const rt_ctx *c, int f, cub_dq rot)
{
    cub_dv3 fw = cub_dq_rotate(rot, cub_dv3_make(0, 0, 1));
    if (hypot(fw.x, fw.z) < 0.1) {
        cub_dv3 pos[CUB_MOTION_MAX_JOINTS];
        cub_dq wr[CUB_MOTION_MAX_JOINTS];
        rt_target_world(c, f, pos, wr);
        fw = cub_dq_rotate(wr[c->hips], cub_dv3_make(0, 0, 1));
    }
    return cub_dq_axis_angle(cub_dv3_make(0, 1, 0), atan2(fw.x, fw.z));
}

/* Height of the ankle above the floor when the foot stands flat. */
static double rest_ankle_mm(const rt_ctx *c, int side)
{
    double low = INFINITY;
    for (int j = 0; j < c->tj; j++)
        if (c->is_foot[j])
            low = fmin(low, c->tgt_rest_pos[j].y);
    return c->tgt_rest_pos[c->foot[side]].y - low;
}

static cub_dv3 ankle_at(const rt_ctx *c, int f, int side)
{
    cub_dv3 pos[CUB_MOTION_MAX_JOINTS];
    cub_dq rot[CUB_MOTION_MAX_JOINTS];
    rt_target_world(c, f, pos, rot);
    return pos[c->foot[side]];
}

/* Where each contact run of `side` is pinned: the mean ground position of
 * the ankle over the run, at the rest ankle height, the foot flat with its
 * mean heading. Stored per contact frame in pin[] and flat[]. */
static void find_pins(const rt_ctx *c, int side, cub_dv3 *pin, cub_dq *flat)
{
    const unsigned char *ct = c->contact[side];
    for (int f = 0; f < c->frames;) {
        if (!ct[f]) {
            f++;
            continue;
        }
        int e = f;
        cub_dv3 p = {0, 0, 0}, fw = {0, 0, 0};
        for (; e < c->frames && ct[e]; e++) {
            p = cub_dv3_add(p, ankle_at(c, e, side));
            cub_dq fl = flat_foot(c, e, foot_rot_at(c, e, side));
            fw = cub_dv3_add(fw, cub_dq_rotate(fl, cub_dv3_make(0, 0, 1)));
        }
        p = cub_dv3_scale(p, 1.0 / (e - f));
        p.y = rest_ankle_mm(c, side);
        for (int g = f; g < e; g++)
            pin[g] = p, flat[g] = cub_dq_axis_angle(cub_dv3_make(0, 1, 0), atan2(fw.x, fw.z));
        f = e;
    }
}

/* A pinned foot the leg cannot reach would slide with the hips (the body
 * sways over a planted foot): lower the root just enough, per frame, that
 * every pinned ankle is within REACH of its leg's length. The drop is
 * smoothed by a max filter then a box filter of the same width, so it is
 * never less than what a frame needs. */
#define REACH 0.995
static void drop_for_reach(rt_ctx *c, cub_dv3 *const pin[2], double *need, double *tmp)
{
    cub_dv3 pos[CUB_MOTION_MAX_JOINTS];
    cub_dq rot[CUB_MOTION_MAX_JOINTS];
    for (int f = 0; f < c->frames; f++) {
        need[f] = 0;
        rt_target_world(c, f, pos, rot);
        for (int s = 0; s < 2; s++) {
            if (!c->contact[s][f])
                continue;
            double l = REACH * (c->tgt_rest_pos[c->leg[s]].y - c->tgt_rest_pos[c->up_leg[s]].y +
                                c->tgt_rest_pos[c->foot[s]].y - c->tgt_rest_pos[c->leg[s]].y);
            l = fabs(l);
            cub_dv3 h = cub_dv3_sub(pos[c->up_leg[s]], pin[s][f]);
            double flat2 = h.x * h.x + h.z * h.z;
            double v = l * l > flat2 ? sqrt(l * l - flat2) : 0;
            need[f] = fmax(need[f], h.y - v);
        }
    }
    for (int pass = 0; pass < 2; pass++) {
        for (int f = 0; f < c->frames; f++) {
            double m = pass ? 0 : need[f];
            int n = 0;
            for (int g = f - BLEND_FRAMES; g <= f + BLEND_FRAMES; g++)
                if (g >= 0 && g < c->frames)
                    m = pass ? m + need[g] : fmax(m, need[g]), n++;
            tmp[f] = pass ? m / n : m;
        }
        memcpy(need, tmp, sizeof(double) * (size_t)c->frames);
    }
    for (int f = 0; f < c->frames; f++)
        c->root[f].y -= need[f];
}

/* Pin each contact run, easing the IK in and out over BLEND_FRAMES outside
 * the run (never into another contact). */
static void pin_foot(rt_ctx *c, int side, const cub_dv3 *pin, const cub_dq *flat)
{
    const unsigned char *ct = c->contact[side];
    for (int f = 0; f < c->frames;) {
        if (!ct[f]) {
            f++;
            continue;
        }
        int e = f;
        while (e < c->frames && ct[e])
            e++;
        for (int g = f - BLEND_FRAMES; g < e + BLEND_FRAMES; g++) {
            if (g < 0 || g >= c->frames || (g < f || g >= e ? ct[g] : 0))
                continue;
            int dist = g < f ? f - g : g >= e ? g - e + 1 : 0;
            int k = g < f ? f : g >= e ? e - 1 : g; /* the run's pin */
            double w = 1.0 - (double)dist / (BLEND_FRAMES + 1);
            cub_dv3 free_a = ankle_at(c, g, side);
            cub_dq foot_w = cub_dq_slerp(foot_rot_at(c, g, side), flat[k], w);
            leg_ik(c, g, side, cub_dv3_add(free_a, cub_dv3_scale(cub_dv3_sub(pin[k], free_a), w)),
                   foot_w);
        }
        f = e;
    }
}

static void measure(const rt_ctx *c, cub_retarget_report *rep)
{
    double slide_sum = 0, ankle_sum = 0;
    int slide_n = 0, ankle_n = 0;
    rep->min_foot_mm = lowest_foot(c);
    for (int s = 0; s < 2; s++)
        for (int f = 0; f < c->frames; f++) {
            if (!c->contact[s][f])
                continue;
            rep->contact_frames[s]++;
            cub_dv3 a = ankle_at(c, f, s);
            ankle_sum += a.y, ankle_n++;
            if (f > 0 && c->contact[s][f - 1]) {
                double d = cub_dv3_len(cub_dv3_sub(a, ankle_at(c, f - 1, s)));
                slide_sum += d, slide_n++;
                rep->slide_max_mm = fmax(rep->slide_max_mm, d);
            }
        }
    rep->slide_mean_mm = slide_n ? slide_sum / slide_n : 0;
    rep->contact_ankle_mm = ankle_n ? ankle_sum / ankle_n : 0;
    for (int f = 1; f < c->frames; f++)
        for (int j = 0; j < c->tj; j++) {
            double a = cub_dq_angle_between(c->local[(size_t)f * c->tj + j],
                                          c->local[(size_t)(f - 1) * c->tj + j]);
            rep->max_ang_deg = fmax(rep->max_ang_deg, a * 180.0 / CUB_VEC_PI);
        }
}

/* Lowest point of one foot (its joints) in frame f. */
static double foot_low_at(const rt_ctx *c, int f, int side)
{
    cub_dv3 pos[CUB_MOTION_MAX_JOINTS];
    cub_dq rot[CUB_MOTION_MAX_JOINTS];
    rt_target_world(c, f, pos, rot);
    double low = INFINITY;
    for (int j = 0; j < c->tj; j++) {
        int a = j; /* is j the foot or below it? */
        while (a >= 0 && a != c->foot[side])
            a = c->tgt->joints[a].parent;
        if (a >= 0)
            low = fmin(low, pos[j].y);
    }
    return low;
}

/* Out of contact a swinging foot may dip below the floor the contacts
 * stand on (a pointed toe): lift its ankle just out of the floor, the foot
 * keeping its rotation. The lift is continuous since the dip is. */
static void lift_swing_feet(rt_ctx *c)
{
    for (int s = 0; s < 2; s++)
        for (int f = 0; f < c->frames; f++) {
            double low = foot_low_at(c, f, s);
            if (c->contact[s][f] || low >= 0)
                continue;
            cub_dv3 a = ankle_at(c, f, s);
            a.y -= low;
            leg_ik(c, f, s, a, foot_rot_at(c, f, s));
        }
}

/* Shift the root so that the ankles in contact stand, on average, at the
 * rest ankle height: pinning then moves the legs as little as it can. */
static void floor_on_contacts(rt_ctx *c, double *dy)
{
    double sum = 0;
    int n = 0;
    for (int s = 0; s < 2; s++)
        for (int f = 0; f < c->frames; f++)
            if (c->contact[s][f])
                sum += ankle_at(c, f, s).y - rest_ankle_mm(c, s), n++;
    if (n) {
        shift_root(c, cub_dv3_make(0, -sum / n, 0));
        *dy -= sum / n;
    }
}

void rt_feet(rt_ctx *c, cub_retarget_report *rep)
{
    /* Centre the clip on its mean ground position, feet on the floor. */
    cub_dv3 mean = {0, 0, 0};
    for (int f = 0; f < c->frames; f++)
        mean = cub_dv3_add(mean, c->root[f]);
    mean = cub_dv3_scale(mean, 1.0 / c->frames);
    shift_root(c, cub_dv3_make(-mean.x, 0, -mean.z));
    double low = lowest_foot(c);
    shift_root(c, cub_dv3_make(0, -low, 0));
    double dy = -low;
    int contacts = 0;
    if (!c->d.no_contacts)
        for (int s = 0; s < 2; s++) {
            find_contacts(c, s);
            for (int f = 0; f < c->frames; f++)
                contacts += c->contact[s][f];
        }
    cub_dv3 *pin[2] = {calloc((size_t)c->frames, sizeof(cub_dv3)),
                     calloc((size_t)c->frames, sizeof(cub_dv3))};
    cub_dq *flat[2] = {calloc((size_t)c->frames, sizeof(cub_dq)),
                     calloc((size_t)c->frames, sizeof(cub_dq))};
    double *need = calloc((size_t)c->frames * 2, sizeof(double));
    if (contacts && pin[0] && pin[1] && flat[0] && flat[1] && need) {
        floor_on_contacts(c, &dy);
        for (int s = 0; s < 2; s++)
            find_pins(c, s, pin[s], flat[s]);
        drop_for_reach(c, pin, need, need + c->frames);
        for (int s = 0; s < 2; s++)
            pin_foot(c, s, pin[s], flat[s]);
        lift_swing_feet(c);
    }
    free(pin[0]), free(pin[1]), free(flat[0]), free(flat[1]), free(need);
    rep->offset_mm[0] = -mean.x, rep->offset_mm[1] = dy, rep->offset_mm[2] = -mean.z;
    measure(c, rep);
}

/* The joints' confidence from the evidence the tracker has per joint
 * (docs/tracker_eval.md, "the confidence", has the figures and how the
 * numbers were chosen, on the dev folds only). The fit writes what it
 * knows of a joint's source (0: guessed, a quarter: an arm hanging by the thigh,
 * more: found on an extremity's path or on the torso); this step keeps a
 * joint CUB_TRACK_CONFIDENT only when the depth backs it:
 *   - the player is whole in view (status OK), on the same track as last
 *     frame;
 *   - the fit found the joint (not guessed, not hung);
 *   - the cell the joint projects to is the player's, its surface from
 *     100 mm before the joint (a part's radius and more) to 25 mm behind
 *     it (not hidden by a nearer part, not off the silhouette), and
 *     enough of the 5x5 cells around agree;
 *   - the body faces the camera: the shoulders' and hips' depths differ
 *     little (side-on the far limbs hide, and which side is which
 *     becomes a guess); and, for the joints named left or right, it was
 *     not side-on in the last 2 s: a child seen side-on may have turned
 *     on to show its back, which in depth looks like its front while the
 *     image's sides name its limbs the wrong way round;
 *   - the joint moved little in the last 100 ms (from the newest kept
 *     frame 90-300 ms old: the last at 10 fps, the third last at 30; a
 *     frame's jitter is not motion): a fast limb is where the fit swaps
 *     or lags.
 * Limits per group: the head, shoulders and legs are placed well when
 * seen; the torso's middle and hips lie inside the body by proportion,
 * and the arms are where the fit errs most, so theirs are strict. A joint
 * found but not backed so gets a quarter: seen, not confident. */
#include "trk_body.h"

enum {
    CONF_SEEN = CUB_Q16_ONE / 4, /* found, not confident */
    CONF_FRONT_MM = 25,          /* the joint may lie this far before its cell's surface... */
    CONF_BEHIND_MM = 100,        /* ...and this far behind it (the part's radius and more) */
    CONF_NEAR_MM = 100,          /* a neighbour cell agrees within this of the joint's surface */
    CONF_NEAR_R = 40,            /* the surface expected this far before the joint */
    CONF_SIDE_ON_MM = 100,       /* the depth asymmetry of a body side-on */
};
#define CONF_TURN_US 2000000 /* after side-on, left and right stay unsure this long */
#define CONF_SPAN_MIN_US 90000 /* the motion is measured against a frame this old... */
#define CONF_SPAN_MAX_US 300000 /* ...to this (none: no motion known, not confident) */

/* Per group (legs and head, torso, arms): the most asymmetry in depth
 * (mm), the most motion per 100 ms (mm) and the fewest agreeing cells of
 * 25. */
typedef struct conf_limits {
    int32_t face_mm, move_mm, cells;
} conf_limits;
static const conf_limits conf_group[3] = {{30, 60, 20}, {20, 20, 25}, {20, 20, 10}};

static int conf_group_of(int j)
{
    switch (j) {
    case CUB_KJ_SPINE:
    case CUB_KJ_HIP_CENTRE:
    case CUB_KJ_HIP_L:
    case CUB_KJ_HIP_R:
        return 1;
    case CUB_KJ_ELBOW_L:
    case CUB_KJ_WRIST_L:
    case CUB_KJ_HAND_L:
    case CUB_KJ_ELBOW_R:
    case CUB_KJ_WRIST_R:
    case CUB_KJ_HAND_R:
        return 2;
    default:
        return 0;
    }
}

/* How many of the 5x5 cells around p's cell are the player's at p's
 * surface; -1 when p's own cell is not (or p is off the image). */
static int32_t depth_support(const cub_tracker *t, trk_p3 p)
{
    int32_t gx, gy;
    if (p.z <= 0) return -1;
    grid_of(p, &gx, &gy);
    if (!on_grid(gx, gy)) return -1;
    int32_t i = gy * TRK_GW + gx, dz = p.z - t->z[i];
    if (!t->mask[i] || dz < -CONF_FRONT_MM || dz > CONF_BEHIND_MM) return -1;
    int32_t n = 0;
    for (int32_t dy = -2; dy <= 2; dy++)
        for (int32_t dx = -2; dx <= 2; dx++) {
            int32_t c = (gy + dy) * TRK_GW + gx + dx;
            n += on_grid(gx + dx, gy + dy) && t->mask[c] &&
                 trk_abs(p.z - t->z[c] - CONF_NEAR_R) <= CONF_NEAR_MM;
        }
    return n;
}

/* A joint named left or right (not on the body's middle line). */
static bool conf_sided(int j)
{
    return j != CUB_KJ_HEAD && j != CUB_KJ_SHOULDER_CENTRE && j != CUB_KJ_SPINE &&
           j != CUB_KJ_HIP_CENTRE;
}

/* The newest kept frame of this player 90-300 ms before t_us, or -1. */
static int32_t past_frame(const cub_tracker *t, int64_t t_us, int32_t id)
{
    int32_t best = -1;
    for (int32_t k = 0; k < TRK_PAST; k++) {
        int64_t age = t_us - t->past[k].t_us;
        if (!t->past[k].used || t->past[k].id != id || age < CONF_SPAN_MIN_US ||
            age > CONF_SPAN_MAX_US)
            continue;
        if (best < 0 || t->past[k].t_us > t->past[best].t_us) best = k;
    }
    return best;
}

static void keep_frame(cub_tracker *t, int64_t t_us, const cub_track_skeleton *s)
{
    int32_t k = t->past_next;
    for (int j = 0; j < CUB_KJ_COUNT; j++) t->past[k].j[j] = got(s, j);
    t->past[k].t_us = t_us, t->past[k].id = s->player_id, t->past[k].used = true;
    t->past_next = (k + 1) % TRK_PAST;
}

void trk_confidence(cub_tracker *t, int64_t t_us, cub_track_skeleton *s)
{
    trk_p3 sl = got(s, CUB_KJ_SHOULDER_L), sr = got(s, CUB_KJ_SHOULDER_R);
    trk_p3 hl = got(s, CUB_KJ_HIP_L), hr = got(s, CUB_KJ_HIP_R);
    int32_t face = trk_abs(sl.z - sr.z) + trk_abs(hl.z - hr.z);
    if (face >= CONF_SIDE_ON_MM)
        t->side_on_us = t_us, t->side_on_id = s->player_id, t->side_on_seen = true;
    bool turned = t->side_on_seen && t->side_on_id == s->player_id &&
                  t_us - t->side_on_us <= CONF_TURN_US;
    int32_t past = past_frame(t, t_us, s->player_id);
    bool go_on = s->status == CUB_TRACK_OK && t->have_prev && t->lost_frames == 0 &&
                 t->prev.player_id == s->player_id && past >= 0;
    int64_t span = past >= 0 ? t_us - t->past[past].t_us : 0;
    for (int j = 0; j < CUB_KJ_COUNT; j++) {
        if (s->confidence[j] == 0) continue;
        const conf_limits *l = &conf_group[conf_group_of(j)];
        trk_p3 p = got(s, j);
        bool sure = go_on && s->confidence[j] >= CUB_Q16_ONE / 2 && face < l->face_mm &&
                    !(turned && conf_sided(j)) &&
                    (int64_t)dist3(t->past[past].j[j], p) * 100000 < (int64_t)l->move_mm * span &&
                    depth_support(t, p) >= l->cells;
        s->confidence[j] = sure ? CUB_Q16_ONE : CONF_SEEN;
    }
    keep_frame(t, t_us, s);
}

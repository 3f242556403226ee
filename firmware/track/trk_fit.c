/* From extremities to twenty joints: label the extremities (head, hands,
 * feet), measure the player's stature, then place the joints along the
 * geodesic paths and the torso axis with body proportions (in 1/1000 of
 * stature: the synthetic child's skeleton of cub/synth.h, measured on its
 * truth for CMU clip 13_29, the tuning clip). */
#include "trk_internal.h"

/* Which side of the image the player's left lands on: -1 as the Kinect
 * mirrors its images (cub/synth.h): a player facing the camera shows the
 * left hand at smaller camera x. */
#define TRK_LEFT_SIGN (-1)

/* proportions, per mille of stature */
enum {
    P_HEAD_DOWN = 85,      /* head top to head centre along the face */
    P_NECK_DOWN = 200,     /* head top to shoulder centre */
    P_WIDEN = 150,         /* head top to where the silhouette widens (neck base) */
    P_BELOW_NECK = 40,     /* neck base to shoulder centre */
    P_SPINE = 95,         /* shoulder centre to spine */
    P_HIPC = 165,          /* shoulder centre to hip centre */
    P_SHOULDER_HALF = 100, /* half the shoulder width */
    P_SHOULDER_DROP = -20,
    P_SHOULDER_RUN = 50, /* where the shoulders' width is measured */
    R_ARM_EDGE = 15,     /* shoulder joint to the deltoid's outer surface */
    P_HIP_HALF = 56,
    P_HIP_DROP = 70,
    P_UPPER_ARM = 190,
    P_FOREARM = 130,
    P_HAND_REACH = 80, /* the hand's surface around the fingertip */
    P_WRIST_IN = 75,
    P_THIGH = 267,
    P_SHIN = 285,
    P_ANKLE_UP = 80,
    P_FOOT_UP = 40,
    R_HEAD = 55, /* surface to joint: the part's radius */
    R_TORSO = 60,
    R_LIMB = 25,
};

static int32_t pm(int32_t stature, int32_t per_mille) { return stature * per_mille / 1000; }

/* A part's radius: proportional, but a grown-up's chest is not deeper than
 * what the joint conventions put inside the surface. */
static int32_t radius(int32_t stature, int32_t per_mille)
{
    int32_t r = pm(stature, per_mille);
    return r > 75 ? 75 : r;
}

static trk_p3 cell_p(const cub_tracker *t, int32_t i) { return (trk_p3){t->x[i], t->y[i], t->z[i]}; }

static int32_t dist3(trk_p3 a, trk_p3 b) { return trk_len(a.x - b.x, a.y - b.y, a.z - b.z); }

static trk_p3 add_s(trk_p3 a, cub_vec3 dir_q16, int32_t mm)
{
    return (trk_p3){a.x + (int32_t)(((int64_t)dir_q16.x * mm) >> 16), a.y + (int32_t)(((int64_t)dir_q16.y * mm) >> 16),
                    a.z + (int32_t)(((int64_t)dir_q16.z * mm) >> 16)};
}

/* Surface point to the part's axis: back along the camera's ray. */
static trk_p3 inside(trk_p3 p, int32_t r_mm) { return (trk_p3){p.x, p.y, p.z + r_mm}; }

static cub_vec3 unit(int32_t x, int32_t y, int32_t z)
{
    int32_t l = trk_len(x, y, z);
    if (l == 0) return (cub_vec3){0, CUB_Q16_ONE, 0};
    return (cub_vec3){(int32_t)((int64_t)x * 65536 / l), (int32_t)((int64_t)y * 65536 / l), (int32_t)((int64_t)z * 65536 / l)};
}

/* The cell on the path from tip toward the root where the straight-line
 * distance from the tip first reaches mm (the root if never). */
static int32_t path_at(const cub_tracker *t, int32_t tip, int32_t mm)
{
    trk_p3 p0 = cell_p(t, tip);
    int32_t i = tip;
    while (t->parent0[i] >= 0 && dist3(p0, cell_p(t, i)) < mm) i = t->parent0[i];
    return i;
}

/* The middle joint of a limb (elbow, knee): the path cell whose distances to
 * both end joints best match the two bone lengths. */
static int32_t path_middle(const cub_tracker *t, int32_t tip, trk_p3 a, int32_t la, trk_p3 b, int32_t lb)
{
    int32_t best = tip, best_err = INT32_MAX;
    for (int32_t i = tip, steps = 0; i >= 0 && steps < 400; i = t->parent0[i], steps++) {
        trk_p3 p = cell_p(t, i);
        int32_t e = trk_abs(dist3(p, a) - la) + trk_abs(dist3(p, b) - lb);
        if (e < best_err) best_err = e, best = i;
    }
    return best;
}

/* Stature from the head top: the floor when the feet are on it, else the
 * drop from the head top to where the silhouette widens into shoulders. */
static int32_t measure_stature(const cub_tracker *t, int32_t head, bool on_floor, int32_t *neck_drop_mm)
{
    trk_p3 top = cell_p(t, head);
    *neck_drop_mm = 0;
    int32_t gx = head % TRK_GW, wmax = 0;
    bool frozen = false;
    for (int32_t gy = head / TRK_GW; gy < TRK_GH; gy++) {
        int32_t i = gy * TRK_GW + gx;
        if (!t->mask[i]) continue;
        int32_t a = gx, b = gx;
        while (a > 0 && t->mask[i - (gx - a) - 1]) a--;
        while (b < TRK_GW - 1 && t->mask[i + (b - gx) + 1]) b++;
        int32_t w = (b - a + 1) * TRK_CELL_PX * t->z[i] / CUB_TRACK_FOCAL_PX;
        int32_t drop = top.y - t->y[i];
        if (wmax > 0 && drop > 100 && w * 10 > wmax * 19) {
            *neck_drop_mm = drop;
            break;
        }
        /* the head's width: the widest row until the neck narrows it */
        if (w * 10 < wmax * 9) frozen = true;
        if (!frozen && w > wmax) wmax = w;
        gx = (a + b) / 2;
    }
    if (on_floor) return trk_along(top.x, top.y, top.z, t->up) - t->floor_h_mm;
    return *neck_drop_mm * 1000 / P_WIDEN;
}

/* Half the width of the silhouette's run through p's row (mm), 0 if p
 * is off the player. At the shoulders the run always ends in the deltoids,
 * whatever the arms do, so it measures the shoulders of this body. */
static int32_t run_half_mm(const cub_tracker *t, trk_p3 p)
{
    if (p.z <= 0) return 0;
    int32_t gx = (CUB_TRACK_CX + p.x * CUB_TRACK_FOCAL_PX / p.z) / TRK_CELL_PX;
    int32_t gy = (CUB_TRACK_CY - p.y * CUB_TRACK_FOCAL_PX / p.z) / TRK_CELL_PX;
    if (gx < 0 || gy < 0 || gx >= TRK_GW || gy >= TRK_GH) return 0;
    int32_t row = gy * TRK_GW;
    if (!t->mask[row + gx]) return 0;
    int32_t a = gx, b = gx;
    while (a > 0 && t->mask[row + a - 1]) a--;
    while (b < TRK_GW - 1 && t->mask[row + b + 1]) b++;
    return (t->x[row + b] - t->x[row + a]) / 2;
}

static void put(cub_track_skeleton *s, int j, trk_p3 p, cub_q16 conf)
{
    s->joint_mm[j] = (cub_vec3){p.x * 65536, p.y * 65536, p.z * 65536};
    s->confidence[j] = conf;
}

static trk_p3 got(const cub_track_skeleton *s, int j)
{
    return (trk_p3){s->joint_mm[j].x >> 16, s->joint_mm[j].y >> 16, s->joint_mm[j].z >> 16};
}

typedef struct limb_pick {
    int32_t hand[2], foot[2]; /* extremum cell per side (0 = left), -1 none */
    int32_t head;
} limb_pick;

/* Percent of a disk of rho_mm around cell c (in the image plane) that the
 * player's surface fills at about c's depth: a head is round and fills its
 * disk, a raised forearm or hand crosses it as a strip. */
static int32_t disk_fill_pct(const cub_tracker *t, int32_t c, int32_t rho_mm)
{
    int32_t z0 = t->z[c], rc = rho_mm * CUB_TRACK_FOCAL_PX / ((z0 ? z0 : 1) * TRK_CELL_PX);
    if (rc < 1) rc = 1;
    if (rc > 12) rc = 12;
    int32_t gx0 = c % TRK_GW, gy0 = c / TRK_GW, in = 0, all = 0;
    for (int32_t dy = -rc; dy <= rc; dy++)
        for (int32_t dx = -rc; dx <= rc; dx++) {
            if (dx * dx + dy * dy > rc * rc) continue;
            all++;
            int32_t gx = gx0 + dx, gy = gy0 + dy;
            if (gx < 0 || gy < 0 || gx >= TRK_GW || gy >= TRK_GH) continue;
            int32_t i = gy * TRK_GW + gx;
            if (t->mask[i] && trk_abs(t->z[i] - z0) < 2 * rho_mm) in++;
        }
    return in * 100 / all;
}

/* The head: above the root, central, not a hand held in front; the nearer
 * to last frame's head the better. */
static int32_t pick_head(const cub_tracker *t, int32_t root, const int32_t *ext, int32_t n, int32_t st0,
                         bool *is_round)
{
    *is_round = false;
    int32_t min_geo_mm = pm(st0, 220);
    trk_p3 r = cell_p(t, root);
    int32_t best = -1, best_cost = INT32_MAX;
    for (int32_t k = 0; k < n; k++) {
        trk_p3 p = cell_p(t, ext[k]);
        int32_t dh = p.y - r.y; /* image-up: the head is found before the up vector matters */
        if (trk_along(p.x - r.x, p.y - r.y, p.z - r.z, t->up) < 100 && dh < 100) continue;
        /* a head sticks out of the torso by its neck and itself; a shallow
         * bump (a shoulder between arms held down) is no head */
        if (t->dist0[ext[k]] < min_geo_mm) continue;
        /* central, not in front of the torso, far out along the surface
         * (a head stands out by neck and skull, a shoulder bump does not),
         * and round (a raised hand beside the head is a strip) */
        int32_t cost = 2 * trk_abs(p.x - r.x) + 2 * (r.z - p.z > 100 ? r.z - p.z - 100 : 0) - t->dist0[ext[k]];
        /* (an arm held out level fills a far, coarse disk too, but it
         * reaches out more than up) */
        bool round = disk_fill_pct(t, path_at(t, ext[k], pm(st0, P_HEAD_DOWN)), pm(st0, 60)) >= 75 &&
                     trk_abs(p.x - r.x) < dh;
        if (!round) cost += 600;
        /* last frame's head helps, but a wrong one must not hold on */
        if (t->have_prev && t->lost_frames == 0) {
            int32_t d = dist3(p, got(&t->prev, CUB_TJ_HEAD));
            cost += d < 300 ? d : 300;
        }
        if (cost < best_cost) best_cost = cost, best = k, *is_round = round;
    }
    return best;
}

/* Where a limb joins the torso: the cell on the tip's path to the root
 * that is base_mm of surface from the root. An arm's path enters through
 * the shoulder, a leg's through the hip, whatever the limb's pose (a leg
 * kicked up to the side is still a leg). */
static int32_t path_base(const cub_tracker *t, int32_t tip, int32_t base_mm)
{
    int32_t i = tip;
    for (int32_t steps = 0; t->parent0[i] >= 0 && t->dist0[i] > base_mm && steps < 800; steps++) i = t->parent0[i];
    return i;
}

static void pick_limbs(const cub_tracker *t, int32_t root, const int32_t *ext, int32_t n, int32_t stature,
                       trk_p3 sc, trk_p3 hc, cub_vec3 axis, cub_vec3 lat, limb_pick *lp)
{
    int32_t hands[TRK_MAX_EXTREMA], feet[TRK_MAX_EXTREMA], nh = 0, nf = 0;
    int32_t hb[TRK_MAX_EXTREMA], fb[TRK_MAX_EXTREMA];
    trk_p3 r = cell_p(t, root);
    for (int32_t k = 0; k < n; k++) {
        if (k == lp->head) continue;
        trk_p3 p = cell_p(t, ext[k]);
        int32_t b = path_base(t, ext[k], pm(stature, 200));
        trk_p3 bp = cell_p(t, b);
        /* the attachment above or below the root; the tip's height decides
         * only when the attachment is level with the root */
        int32_t bh = trk_along(bp.x - r.x, bp.y - r.y, bp.z - r.z, axis);
        int32_t dh = trk_along(p.x - hc.x, p.y - hc.y, p.z - hc.z, axis);
        /* a hand hanging against the hip joins the torso low too, by a
         * short cut: a leg raised high is also far along the surface */
        bool leg = dh < -pm(stature, 250) || (bh < -pm(stature, 40) && t->dist0[ext[k]] > pm(stature, 550));
        if (leg) fb[nf] = b, feet[nf++] = ext[k];
        else hb[nh] = b, hands[nh++] = ext[k];
    }
    int32_t *lists[2] = {hands, feet}, *bases[2] = {hb, fb}, counts[2] = {nh, nf}, *dst[2] = {lp->hand, lp->foot};
    trk_p3 centre[2] = {sc, hc};
    for (int g = 0; g < 2; g++) {
        dst[g][0] = dst[g][1] = -1;
        /* the two farthest along the surface (extrema come farthest first);
         * the side from where the limb joins the torso (a hand crossing
         * the body keeps its name), then from the tip */
        int32_t m = counts[g] < 2 ? counts[g] : 2;
        int32_t s[2] = {0, 0};
        for (int32_t k = 0; k < m; k++) {
            trk_p3 p = cell_p(t, lists[g][k]), b = cell_p(t, bases[g][k]);
            trk_p3 c = centre[g];
            s[k] = TRK_LEFT_SIGN * (0 * trk_along(b.x - c.x, b.y - c.y, b.z - c.z, lat) +
                                    trk_along(p.x - c.x, p.y - c.y, p.z - c.z, lat));
        }
        if (m == 2) {
            int left = s[0] > s[1] ? 0 : 1;
            dst[g][0] = lists[g][left], dst[g][1] = lists[g][1 - left];
        } else if (m == 1) {
            dst[g][s[0] > 0 ? 0 : 1] = lists[g][0];
        }
    }
}

/* Legs held together make one extremity for two feet: a leg whose tip
 * hangs well above the floor (or that has none) while the body stands on
 * it takes the lowest cell on its side of the hips, away from the other
 * foot, when that cell touches the floor. */
static void feet_on_floor(const cub_tracker *t, trk_p3 hc, cub_vec3 lat, int32_t st, limb_pick *lp)
{
    if (!t->have_floor) return;
    for (int side = 0; side < 2; side++) {
        int32_t tip = lp->foot[side], other = lp->foot[1 - side];
        if (tip >= 0 && trk_along(t->x[tip], t->y[tip], t->z[tip], t->up) - t->floor_h_mm < pm(st, 150)) continue;
        int32_t best = -1, best_h = INT32_MAX;
        for (int32_t i = 0; i < TRK_CELLS; i++) {
            if (!t->mask[i] || t->dist0[i] == TRK_INF) continue;
            int32_t l = TRK_LEFT_SIGN * trk_along(t->x[i] - hc.x, t->y[i] - hc.y, t->z[i] - hc.z, lat);
            if ((side == 0) != (l > 0) || trk_abs(l) > pm(st, 200)) continue;
            int32_t h = trk_along(t->x[i], t->y[i], t->z[i], t->up);
            if (h >= best_h) continue;
            if (other >= 0 && dist3(cell_p(t, i), cell_p(t, other)) < pm(st, 150)) continue;
            best_h = h, best = i;
        }
        if (best >= 0 && best_h - t->floor_h_mm < pm(st, 100)) lp->foot[side] = best;
    }
}

/* The horizontal line across the torso (the shoulders' direction), from
 * the spread of the torso's surface in x and z. */
static cub_vec3 torso_lateral(const cub_tracker *t, int32_t root, int32_t radius_mm)
{
    int64_t n = 0, sx = 0, sz = 0, sxx = 0, sxz = 0, szz = 0;
    for (int32_t i = 0; i < TRK_CELLS; i++) {
        if (!t->mask[i] || t->dist0[i] > radius_mm) continue;
        int32_t dx = t->x[i] - t->x[root], dz = t->z[i] - t->z[root];
        n++, sx += dx, sz += dz, sxx += (int64_t)dx * dx, sxz += (int64_t)dx * dz, szz += (int64_t)dz * dz;
    }
    if (n < 8) return (cub_vec3){CUB_Q16_ONE, 0, 0};
    int64_t cxx = sxx - sx * sx / n, cxz = sxz - sx * sz / n, czz = szz - sz * sz / n;
    while (cxx > INT32_MAX / 4 || czz > INT32_MAX / 4 || cxz > INT32_MAX / 4 || cxz < -INT32_MAX / 4)
        cxx /= 2, cxz /= 2, czz /= 2;
    cub_q16 a = cub_fx_atan2((cub_q16)(2 * cxz), (cub_q16)(cxx - czz)) / 2;
    cub_vec3 l = {cub_fx_cos(a), 0, cub_fx_sin(a)};
    return l.x < 0 ? (cub_vec3){-l.x, 0, -l.z} : l;
}

/* The hand: the mean of the surface near the fingertip extremity that is
 * as far along the body as it (the palm, not the wrist behind it). */
static trk_p3 hand_centre(const cub_tracker *t, int32_t tip, int32_t reach_mm)
{
    trk_p3 p0 = cell_p(t, tip);
    int32_t rc = reach_mm * CUB_TRACK_FOCAL_PX / (p0.z * TRK_CELL_PX) + 1, gx0 = tip % TRK_GW, gy0 = tip / TRK_GW;
    int64_t sx = 0, sy = 0, sz = 0, n = 0;
    for (int32_t gy = gy0 - rc; gy <= gy0 + rc; gy++)
        for (int32_t gx = gx0 - rc; gx <= gx0 + rc; gx++) {
            if (gx < 0 || gy < 0 || gx >= TRK_GW || gy >= TRK_GH) continue;
            int32_t i = gy * TRK_GW + gx;
            if (!t->mask[i] || t->dist0[i] == TRK_INF || t->dist0[i] < t->dist0[tip] - reach_mm * 3 / 2) continue;
            if (dist3(cell_p(t, i), p0) > reach_mm) continue;
            sx += t->x[i], sy += t->y[i], sz += t->z[i], n++;
        }
    if (!n) return p0;
    return (trk_p3){(int32_t)(sx / n), (int32_t)(sy / n), (int32_t)(sz / n)};
}

/* The limb's stretched length, learnt: it rises quickly to the longest
 * span seen (a straight limb) and sinks slowly, within 25 % of the
 * proportions. Bone lengths scaled to it put the middle joint right on a
 * straight limb, where lengths that do not add up make the fit drift. */
static int32_t learn_reach(cub_tracker *t, int k, int32_t span_mm, int32_t nominal_mm)
{
    int32_t cur = t->reach_mm[k] ? t->reach_mm[k] : nominal_mm * 9 / 10;
    if (span_mm > cur) cur += (span_mm - cur) / 3;
    else cur -= cur / 200;
    if (cur > nominal_mm * 5 / 4) cur = nominal_mm * 5 / 4;
    if (cur < nominal_mm * 3 / 4) cur = nominal_mm * 3 / 4;
    t->reach_mm[k] = cur;
    return cur;
}

static void fit_arm(cub_tracker *t, cub_track_skeleton *s, int side, int32_t tip, int32_t st)
{
    int js = side ? CUB_TJ_SHOULDER_R : CUB_TJ_SHOULDER_L;
    trk_p3 sh = got(s, js);
    int32_t r = radius(st, R_LIMB);
    trk_p3 hand = inside(hand_centre(t, tip, pm(st, P_HAND_REACH)), r);
    trk_p3 wrist = inside(cell_p(t, path_at(t, tip, pm(st, P_WRIST_IN))), r);
    int32_t lu = pm(st, P_UPPER_ARM), lf = pm(st, P_FOREARM);
    int32_t reach = learn_reach(t, side, dist3(sh, wrist), lu + lf);
    lu = reach * lu / (lu + lf), lf = reach - lu;
    trk_p3 elbow = inside(cell_p(t, path_middle(t, tip, sh, lu, wrist, lf)), r);
    put(s, js + 1, elbow, CUB_Q16_ONE * 3 / 4);
    put(s, js + 2, wrist, CUB_Q16_ONE);
    put(s, js + 3, hand, CUB_Q16_ONE);
}

static void fit_leg(cub_tracker *t, cub_track_skeleton *s, int side, int32_t tip, int32_t st)
{
    int jh = side ? CUB_TJ_HIP_R : CUB_TJ_HIP_L;
    trk_p3 hip = got(s, jh);
    int32_t r = radius(st, R_LIMB);
    trk_p3 foot = inside(cell_p(t, path_at(t, tip, pm(st, P_FOOT_UP))), r);
    trk_p3 ankle = inside(cell_p(t, path_at(t, tip, pm(st, P_ANKLE_UP))), r);
    int32_t lt = pm(st, P_THIGH), ls = pm(st, P_SHIN);
    int32_t reach = learn_reach(t, 2 + side, dist3(hip, ankle), lt + ls);
    lt = reach * lt / (lt + ls), ls = reach - lt;
    trk_p3 knee = inside(cell_p(t, path_middle(t, tip, hip, lt, ankle, ls)), r);
    put(s, jh + 1, knee, CUB_Q16_ONE * 3 / 4);
    put(s, jh + 2, ankle, CUB_Q16_ONE);
    put(s, jh + 3, foot, CUB_Q16_ONE);
}

/* A limb without an extremity: where it was last frame relative to its
 * root joint, or hanging straight down. Confidence 0. */
static void guess_chain(const cub_tracker *t, cub_track_skeleton *s, int j0, cub_vec3 axis, int32_t st, bool leg)
{
    trk_p3 base = got(s, j0);
    for (int k = 1; k <= 3; k++) {
        trk_p3 p;
        if (t->have_prev && t->lost_frames < 15) {
            trk_p3 pb = got(&t->prev, j0), pj = got(&t->prev, j0 + k);
            p = (trk_p3){base.x + pj.x - pb.x, base.y + pj.y - pb.y, base.z + pj.z - pb.z};
        } else {
            static const int32_t arm[4] = {0, 190, 320, 365}, leg_[4] = {0, 267, 552, 560};
            p = add_s(base, axis, -pm(st, leg ? leg_[k] : arm[k]));
        }
        put(s, j0 + k, p, 0);
    }
}

/* The top of the body's column straight above the root: where the head
 * is when it is not an extremity (hands up beside it join it to the arms).
 * Climbs while the surface continues; parts nearer than the torso (an arm
 * across it) are climbed past, not taken for the head. */
static int32_t column_top(const cub_tracker *t, int32_t root, int32_t max_rise_mm)
{
    int32_t best = -1, gx = root % TRK_GW, z0 = t->z[root];
    for (int32_t c = gx - 1; c <= gx + 1; c++) {
        if (c < 0 || c >= TRK_GW) continue;
        int32_t top = -1;
        for (int32_t i = (root / TRK_GW) * TRK_GW + c; i >= 0 && t->mask[i]; i -= TRK_GW) {
            if (t->y[i] - t->y[root] > max_rise_mm || t->z[i] > z0 + 150) break;
            if (t->z[i] >= z0 - 150) top = i;
        }
        if (top >= 0 && (best < 0 || t->y[top] > t->y[best])) best = top;
    }
    return best;
}

void trk_fit_skeleton(cub_tracker *t, int32_t root, int32_t *ext, int32_t next, cub_track_skeleton *s)
{
    int32_t st0 = t->stature_mm ? t->stature_mm : 1200;
    bool round;
    limb_pick lp = {.head = pick_head(t, root, ext, next, st0, &round)};
    if (lp.head < 0 || (!round && trk_abs(t->x[ext[lp.head]] - t->x[root]) > pm(st0, 90))) {
        /* no round, central extremity: the head is the column's top (a
         * head leaning aside is round, hands up beside it are not) */
        int32_t top = column_top(t, root, pm(st0, 450));
        if (top >= 0) {
            lp.head = -1;
            for (int32_t k = 0; k < next; k++)
                if (dist3(cell_p(t, ext[k]), cell_p(t, top)) < pm(st0, 100)) lp.head = k;
            if (lp.head < 0) {
                /* in place of the nearest extremity when the list is full */
                if (next == TRK_MAX_EXTREMA) next--;
                ext[next] = top;
                lp.head = next++;
            }
        }
    }
    int32_t head = lp.head >= 0 ? ext[lp.head] : root;
    int32_t hmin = INT32_MAX;
    for (int32_t i = 0; i < TRK_CELLS; i++)
        if (t->mask[i]) {
            int32_t h = trk_along(t->x[i], t->y[i], t->z[i], t->up);
            if (h < hmin) hmin = h;
        }
    bool on_floor = t->have_floor && hmin - t->floor_h_mm < 120;
    int32_t neck = 0;
    int32_t st = lp.head >= 0 ? measure_stature(t, head, on_floor, &neck) : 0;
    /* a neck base far from where the body's proportions put it is an arm
     * or a leaning head widening the silhouette, not the shoulders */
    if (neck >= pm(st0, 100) && neck <= pm(st0, 250)) {
        int32_t cur = t->neck_drop_mm; /* arms beside the head fool one frame */
        if (cur && neck > cur + cur / 8) neck = cur + cur / 8;
        if (cur && neck < cur - cur / 8) neck = cur - cur / 8;
        t->neck_drop_mm = cur ? cur + (neck - cur) / 4 : neck;
    }
    t->head_cell = lp.head >= 0 ? head : -1;
    t->stature_seen_mm = st;
    if (st >= 700 && st <= 2100) {
        /* a body does not change size: once known, one odd measurement
         * (a raised hand beside the head) moves it by 10 % at most */
        int32_t cur = t->stature_mm;
        if (cur && st > cur + cur / 10) st = cur + cur / 10;
        if (cur && st < cur - cur / 10) st = cur - cur / 10;
        t->stature_mm = cur ? cur + (st - cur) / 4 : st;
    }
    if (!t->stature_mm) t->stature_mm = 1200;
    st = t->stature_mm;

    trk_p3 hd = inside(cell_p(t, path_at(t, head, pm(st, P_HEAD_DOWN))), radius(st, R_HEAD));
    /* the shoulder centre just below the neck base, where one was seen */
    int32_t sc_drop = t->neck_drop_mm ? t->neck_drop_mm + pm(st, P_BELOW_NECK) : pm(st, P_NECK_DOWN);
    trk_p3 sc = inside(cell_p(t, path_at(t, head, sc_drop)), radius(st, R_TORSO));
    trk_p3 rt = inside(cell_p(t, root), radius(st, R_TORSO));
    cub_vec3 axis = dist3(sc, rt) > 60 ? unit(sc.x - rt.x, sc.y - rt.y, sc.z - rt.z) : t->up;
    if (lp.head < 0) axis = t->up;
    cub_vec3 lat = torso_lateral(t, root, pm(st, 150));
    cub_vec3 lft = {lat.x * TRK_LEFT_SIGN, lat.y * TRK_LEFT_SIGN, lat.z * TRK_LEFT_SIGN};
    trk_p3 hc = add_s(sc, axis, -pm(st, P_HIPC));
    put(s, CUB_TJ_HEAD, hd, lp.head >= 0 ? CUB_Q16_ONE : 0);
    put(s, CUB_TJ_SHOULDER_CENTRE, sc, CUB_Q16_ONE * 3 / 4);
    put(s, CUB_TJ_SPINE, add_s(sc, axis, -pm(st, P_SPINE)), CUB_Q16_ONE / 2);
    put(s, CUB_TJ_HIP_CENTRE, hc, CUB_Q16_ONE / 2);
    trk_p3 sd = add_s(sc, axis, -pm(st, P_SHOULDER_DROP)), hp = add_s(hc, axis, -pm(st, P_HIP_DROP));
    int32_t half = run_half_mm(t, add_s(sc, axis, -pm(st, P_SHOULDER_RUN))) - pm(st, R_ARM_EDGE);
    if (half < pm(st, 75)) half = pm(st, P_SHOULDER_HALF);
    if (half > pm(st, 140)) half = pm(st, 140);
    put(s, CUB_TJ_SHOULDER_L, add_s(sd, lft, half), CUB_Q16_ONE / 2);
    put(s, CUB_TJ_SHOULDER_R, add_s(sd, lft, -half), CUB_Q16_ONE / 2);
    put(s, CUB_TJ_HIP_L, add_s(hp, lft, pm(st, P_HIP_HALF)), CUB_Q16_ONE / 2);
    put(s, CUB_TJ_HIP_R, add_s(hp, lft, -pm(st, P_HIP_HALF)), CUB_Q16_ONE / 2);

    pick_limbs(t, root, ext, next, st, sc, hc, axis, lat, &lp);
    if (on_floor) feet_on_floor(t, hc, lat, st, &lp);
    for (int side = 0; side < 2; side++) {
        int js = side ? CUB_TJ_SHOULDER_R : CUB_TJ_SHOULDER_L, jh = side ? CUB_TJ_HIP_R : CUB_TJ_HIP_L;
        if (lp.hand[side] >= 0) fit_arm(t, s, side, lp.hand[side], st);
        else guess_chain(t, s, js, axis, st, false);
        if (lp.foot[side] >= 0) fit_leg(t, s, side, lp.foot[side], st);
        else guess_chain(t, s, jh, axis, st, true);
    }
}

/* Light smoothing that does not lag: small moves (sensor jitter) are
 * averaged, large ones (a child's real motion) pass straight through. */
void trk_smooth(cub_tracker *t, cub_track_skeleton *s)
{
    if (!t->have_prev || t->lost_frames > 0 || t->prev.player_id != s->player_id) return;
    for (int j = 0; j < CUB_TJ_COUNT; j++) {
        trk_p3 a = got(&t->prev, j), b = got(s, j);
        int32_t d = dist3(a, b), w; /* weight of the new value, /4 */
        w = d < 15 ? 1 : d < 40 ? 2 : d < 80 ? 3 : 4;
        trk_p3 m = {a.x + (b.x - a.x) * w / 4, a.y + (b.y - a.y) * w / 4, a.z + (b.z - a.z) * w / 4};
        put(s, j, m, s->confidence[j]);
    }
}

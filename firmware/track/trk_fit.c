/* From extremities to twenty joints: label the extremities (hands, feet;
 * the head and stature come from trk_head.c), then place the joints along
 * the geodesic paths and the torso axis with body proportions
 * (trk_body.h). */
#include "trk_body.h"

/* hands close in side keep last frame's names, per mille of stature */
enum {
    SWAP_NEAR = 100,  /* apart across the body by less than */
    SWAP_MARGIN = 50, /* the other naming nearer last frame's by more than */
};

/* a hand before the torso, per mille of stature */
enum {
    HF_FRONT = 70,  /* nearer the camera than the torso's surface by */
    HF_MIN = 150,   /* at least this far from the shoulder */
    HF_CROSS = 50,  /* how far across the body's middle */
    HF_OTHER = 100, /* away from the other hand */
    HF_ABOVE = 0,   /* an extremity on the torso: below the shoulders by */
    HF_WIDE = 200,  /* and within this of the middle */
    HF_CELLS = 4,   /* cells before the torso, fewer is noise */
};

static cub_vec3 unit(int32_t x, int32_t y, int32_t z)
{
    int32_t l = trk_len(x, y, z);
    if (l == 0) return (cub_vec3){0, CUB_Q16_ONE, 0};
    return (cub_vec3){(int32_t)((int64_t)x * 65536 / l), (int32_t)((int64_t)y * 65536 / l), (int32_t)((int64_t)z * 65536 / l)};
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

typedef struct limb_pick {
    int32_t hand[2], foot[2]; /* extremum cell per side (0 = left), -1 none */
    int32_t head;
} limb_pick;

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
            /* hands close in side (crossed, or one before the other): the
             * naming nearer last frame's hands, so they do not swap */
            if (g == 0 && trk_abs(s[0] - s[1]) < pm(stature, SWAP_NEAR) && t->have_prev && t->lost_frames == 0) {
                trk_p3 pl = got(&t->prev, CUB_TJ_HAND_L), pr = got(&t->prev, CUB_TJ_HAND_R);
                trk_p3 a = cell_p(t, lists[g][left]), b = cell_p(t, lists[g][1 - left]);
                if (dist3(a, pr) + dist3(b, pl) + pm(stature, SWAP_MARGIN) < dist3(a, pl) + dist3(b, pr)) left = 1 - left;
            }
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

/* An extremity on the torso's surface (not before it): a shoulder bump or
 * the elbow of an arm whose hand lies before the chest. */
static bool on_torso(const cub_tracker *t, int32_t root, int32_t i, trk_p3 sc, trk_p3 hc, cub_vec3 axis, cub_vec3 lft,
                     int32_t st)
{
    if (t->z[i] <= t->z[root] - pm(st, HF_FRONT)) return false;
    trk_p3 p = cell_p(t, i);
    int32_t up_sc = trk_along(p.x - sc.x, p.y - sc.y, p.z - sc.z, axis);
    int32_t up_hc = trk_along(p.x - hc.x, p.y - hc.y, p.z - hc.z, axis);
    int32_t l = trk_along(p.x - sc.x, p.y - sc.y, p.z - sc.z, lft);
    /* below the hips it is a leg's, not an arm's */
    return up_sc <= pm(st, HF_ABOVE) && (up_hc < 0 || trk_abs(l) <= pm(st, HF_WIDE));
}

/* A hand held before the torso is no extremity (its path ends in the
 * chest), but the forearm and hand stand out in depth: among the cells
 * clearly nearer the camera than the torso's surface, on the shoulder's
 * side and within the arm's reach, the farthest from the shoulder. */
static int32_t hand_in_front(const cub_tracker *t, int32_t root, trk_p3 sh, trk_p3 sc, trk_p3 hc, cub_vec3 axis,
                             cub_vec3 lft, int side, int32_t st, int32_t other)
{
    int32_t zf = t->z[root] - pm(st, HF_FRONT), reach = pm(st, P_UPPER_ARM + P_FOREARM + P_HAND_REACH);
    int32_t best = -1, best_d = pm(st, HF_MIN), nfront = 0, sgn = side ? -1 : 1;
    for (int32_t i = 0; i < TRK_CELLS; i++) {
        if (!t->mask[i] || t->dist0[i] == TRK_INF || t->z[i] > zf) continue;
        trk_p3 p = cell_p(t, i);
        /* between the hips and a little above the shoulders */
        int32_t up_sc = trk_along(p.x - sc.x, p.y - sc.y, p.z - sc.z, axis);
        int32_t up_hc = trk_along(p.x - hc.x, p.y - hc.y, p.z - hc.z, axis);
        if (up_sc > pm(st, 60) || up_hc < -pm(st, 60)) continue;
        if (sgn * trk_along(p.x - sc.x, p.y - sc.y, p.z - sc.z, lft) < -pm(st, HF_CROSS)) continue;
        int32_t d = dist3(p, sh);
        if (d > reach) continue;
        if (other >= 0 && dist3(p, cell_p(t, other)) < pm(st, HF_OTHER)) continue;
        nfront++;
        if (d > best_d) best_d = d, best = i;
    }
    return nfront >= HF_CELLS ? best : -1;
}

void trk_fit_skeleton(cub_tracker *t, int32_t root, int32_t *ext, int32_t next, cub_track_skeleton *s)
{
    bool on_floor;
    limb_pick lp = {.head = trk_fit_head(t, root, ext, &next, &on_floor)};
    int32_t head = lp.head >= 0 ? ext[lp.head] : root, st = t->stature_mm;
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
        int32_t h = lp.hand[side];
        if (h >= 0 && !on_torso(t, root, h, sc, hc, axis, lft, st)) continue;
        int32_t f = hand_in_front(t, root, got(s, side ? CUB_TJ_SHOULDER_R : CUB_TJ_SHOULDER_L), sc, hc, axis, lft,
                                  side, st, lp.hand[1 - side]);
        if (f >= 0) lp.hand[side] = f;
    }
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

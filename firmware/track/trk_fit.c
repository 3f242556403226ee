/* From extremities to twenty joints: label the extremities (hands, feet;
 * the head and stature come from trk_head.c), then place the joints along
 * the geodesic paths and the torso axis with body proportions
 * (trk_body.h). */
#include "trk_body.h"

/* legs and feet: a leg's extremity within the arms' reach (percent) and
 * this far above the floor is a hand; legs held together put the second
 * foot at least this far from the first (per mille of stature) */
enum {
    ARM_SLACK = 100,
    FOOT_ABOVE = 200,
    FOOT_APART = 60,
};
/* the elbow: how far around the path's cell it is looked for (per mille of
 * stature), the weight (quarters) of lying out to the arm's side, the
 * upper arm's length it fits (per mille of its share of the learnt
 * reach: the source skeletons' upper arms are ~30 mm shorter than that
 * share, their forearms not); a folded arm (wrist within EL_FOLDED per mille of the reach from
 * the shoulder) is looked for farther, with a weight (quarters) of lying
 * high */
enum {
    EL_SEARCH = 100,
    EL_W_OUT = 4,
    EL_UPPER = 900,
    EL_FOLDED = 350,
    EL_SEARCH_FOLDED = 220,
    EL_W_UP = 2,
};
/* smoothing: moves within 100 ms (mm) up to which a new position counts
 * a quarter, a half, three quarters */
enum {
    SM_JITTER = 20,
    SM_SLOW = 60,
    SM_FAST = 200,
};
/* the knee: the foot's path runs down the leg's inner side (the shortest
 * way from the crotch) and meets the thigh's length early, so its cell
 * lies inward of the joint and above it; the joint is moved out, away
 * from the other hip, and down the leg toward the ankle (mm; the truth's
 * knees sit so on every source) */
enum {
    KNEE_OUT = 25,
    KNEE_DOWN = 20,
};
/* the shoulder joints' learnt half width: its largest move per frame (mm) */
enum {
    LS_STEP = 8,
};
/* the torso's joints: how far (mm) one is moved in depth onto the surface
 * at most, and the quarters of the torso axis's tilt in depth kept going
 * down it */
enum {
    SURF_NEAR = 200,
    SH_NEAR = 60, /* a shoulder's surface no nearer than expected by more (a hand held before it) */
    AXIS_Z = 1,
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
 * is off the player. Just below the shoulders the run ends in the deltoids
 * or the arms hanging from them (the arms' roots); at the shoulder joints'
 * height, in the shoulders' round tops (the joints). */
static int32_t run_half_mm(const cub_tracker *t, trk_p3 p)
{
    if (p.z <= 0) return 0;
    int32_t gx, gy;
    grid_of(p, &gx, &gy);
    if (!on_grid(gx, gy)) return 0;
    int32_t row = gy * TRK_GW;
    if (!t->mask[row + gx]) return 0;
    int32_t a = gx, b = gx;
    while (a > 0 && t->mask[row + a - 1]) a--;
    while (b < TRK_GW - 1 && t->mask[row + b + 1]) b++;
    return (t->x[row + b] - t->x[row + a]) / 2;
}

/* p moved in depth to the player's surface where it projects (the
 * farthest of the cells around: a hand before the belly is not the belly)
 * plus r_mm: a torso axis tilted by the chest standing out before the neck
 * misplaces in depth what lies far along it (the hips). p when no cell is
 * near its depth. */
static trk_p3 onto_surface_within(const cub_tracker *t, trk_p3 p, int32_t r_mm, int32_t near_mm)
{
    if (p.z <= 0) return p;
    int32_t gx0, gy0, zmax = 0;
    grid_of(p, &gx0, &gy0);
    for (int32_t gy = gy0 - 1; gy <= gy0 + 1; gy++)
        for (int32_t gx = gx0 - 1; gx <= gx0 + 1; gx++) {
            if (!on_grid(gx, gy)) continue;
            int32_t i = gy * TRK_GW + gx;
            int32_t dz = t->z[i] + r_mm - p.z;
            if (t->mask[i] && dz < SURF_NEAR && dz > -near_mm && t->z[i] > zmax) zmax = t->z[i];
        }
    return zmax ? (trk_p3){p.x, p.y, zmax + r_mm} : p;
}

static trk_p3 onto_surface(const cub_tracker *t, trk_p3 p, int32_t r_mm)
{
    return onto_surface_within(t, p, r_mm, SURF_NEAR);
}

/* A shoulder: a hand or forearm held before it is no shoulder surface. */
static trk_p3 onto_shoulder(const cub_tracker *t, trk_p3 p, int32_t r_mm)
{
    return onto_surface_within(t, p, r_mm, SH_NEAR);
}

/* Legs and arms among the extremities (all but the head): a leg joins the
 * torso below the root or ends low, unless it ends within an arm's reach
 * well above the floor; then the feet and the hands. */
static void pick_limbs(const cub_tracker *t, int32_t root, const int32_t *ext, int32_t n, int32_t stature,
                       trk_p3 sc, trk_p3 hc, cub_vec3 axis, cub_vec3 lat, limb_pick *lp)
{
    int32_t hands[TRK_MAX_EXTREMA], feet[TRK_MAX_EXTREMA], nh = 0, nf = 0;
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
        /* a foot is out of the arms' reach, or on the floor */
        if (leg && lp->reach_mm > 0) {
            /* each arm's reach as learnt (bodies differ), not shorter than
             * the proportions' */
            bool in_reach = false;
            for (int side = 0; side < 2; side++) {
                int32_t arm = t->reach_mm[side] + pm(stature, P_HAND_REACH);
                if (arm < lp->reach_mm) arm = lp->reach_mm;
                if (dist3(p, lp->shoulder[side]) < arm) in_reach = true;
            }
            int32_t above = trk_along(p.x, p.y, p.z, t->up) - t->floor_h_mm;
            if (in_reach && t->have_floor && above > pm(stature, FOOT_ABOVE)) leg = false;
        }
        if (leg) feet[nf++] = ext[k];
        else hands[nh++] = ext[k];
    }
    /* the feet: the two farthest along the surface (extrema come farthest
     * first), each on its side of the hips */
    lp->foot[0] = lp->foot[1] = -1;
    int32_t m = nf < 2 ? nf : 2, s[2] = {0, 0};
    for (int32_t k = 0; k < m; k++) {
        trk_p3 p = cell_p(t, feet[k]);
        s[k] = TRK_LEFT_SIGN * trk_along(p.x - hc.x, p.y - hc.y, p.z - hc.z, lat);
    }
    if (m == 2) {
        int left = s[0] > s[1] ? 0 : 1;
        lp->foot[0] = feet[left], lp->foot[1] = feet[1 - left];
    } else if (m == 1) {
        lp->foot[s[0] > 0 ? 0 : 1] = feet[0];
    }
    /* a knee raised aside stands out like a hand within reach, but the
     * foot's path runs through it: it is no hand */
    int32_t kept = 0;
    for (int32_t k = 0; k < nh; k++)
        if (!trk_on_leg(t, hands[k], lp, stature)) hands[kept++] = hands[k];
    cub_vec3 lft = {lat.x * TRK_LEFT_SIGN, lat.y * TRK_LEFT_SIGN, lat.z * TRK_LEFT_SIGN};
    trk_pick_hands(t, hands, kept, lp, sc, lft, stature);
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
            if (other >= 0 && dist3(cell_p(t, i), cell_p(t, other)) < pm(st, FOOT_APART)) continue;
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
    int32_t rc = reach_mm * CUB_KINECT_FOCAL_PX / (p0.z * TRK_CELL_PX) + 1, gx0 = tip % TRK_GW, gy0 = tip / TRK_GW;
    int64_t sx = 0, sy = 0, sz = 0, n = 0;
    for (int32_t gy = gy0 - rc; gy <= gy0 + rc; gy++)
        for (int32_t gx = gx0 - rc; gx <= gx0 + rc; gx++) {
            if (!on_grid(gx, gy)) continue;
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

/* The shoulder joints' half width, learnt per player from this frame's
 * measurement m (mm): it moves toward m by at most LS_STEP a frame, a
 * running median, so a forearm raised beside the shoulder or an arm held
 * out level (the run goes on along it) for a few frames does not move it;
 * measurements outside the proportions' range are ignored. */
static int32_t learn_shoulders(cub_tracker *t, int32_t m, int32_t st)
{
    int32_t cur = t->shoulder_half_mm;
    bool ok = m >= pm(st, P_SHOULDER_MIN) && m <= pm(st, P_SHOULDER_MAX);
    if (!cur) cur = ok ? m : pm(st, P_SHOULDER_HALF);
    else if (ok) cur += m > cur + LS_STEP ? LS_STEP : m < cur - LS_STEP ? -LS_STEP : (m - cur) / 2;
    t->shoulder_half_mm = cur;
    return cur;
}

/* The elbow near the path's middle cell mid: the
 * player's cell around it that best fits both bone lengths from a (the
 * shoulder) and b (the wrist), out to the arm's side rather than toward
 * the body's middle: an arm against the torso lets the path cut across
 * the touching surfaces, which pulls the path's cell inward. other: the
 * other shoulder (the outward direction is away from it, level);
 * search_mm: how far around mid; w_up: the weight (quarters) of lying
 * above the shoulder. (Knees
 * keep the path's cell: legs together make the search find the other
 * leg.) */
static trk_p3 middle_near(const cub_tracker *t, int32_t mid, trk_p3 a, int32_t la, trk_p3 b, int32_t lb, trk_p3 other,
                          int32_t r, int32_t search_mm, int32_t w_up)
{
    trk_p3 m = cell_p(t, mid), c = {(a.x + other.x) / 2, (a.y + other.y) / 2, (a.z + other.z) / 2};
    int32_t ox = a.x - other.x, oz = a.z - other.z, ol = trk_len(ox, 0, oz);
    if (ol == 0 || m.z <= 0) return inside(m, r);
    int32_t rc = search_mm * CUB_KINECT_FOCAL_PX / (m.z * TRK_CELL_PX) + 1, gx0 = mid % TRK_GW, gy0 = mid / TRK_GW;
    int32_t best = mid, best_e = INT32_MAX, step = 1 + rc / 10; /* a near body: every few cells will do */
    for (int32_t gy = gy0 - rc; gy <= gy0 + rc; gy += step)
        for (int32_t gx = gx0 - rc; gx <= gx0 + rc; gx += step) {
            if (!on_grid(gx, gy)) continue;
            int32_t i = gy * TRK_GW + gx;
            if (!t->mask[i]) continue;
            trk_p3 p = inside(cell_p(t, i), r);
            int32_t out = (int32_t)(((int64_t)(p.x - c.x) * ox + (int64_t)(p.z - c.z) * oz) / ol);
            int32_t up = trk_along(p.x - a.x, p.y - a.y, p.z - a.z, t->up);
            int32_t e = trk_abs(dist3(p, a) - la) + trk_abs(dist3(p, b) - lb) - EL_W_OUT * out / 4 + w_up * up / 4;
            if (e < best_e) best_e = e, best = i;
        }
    return inside(cell_p(t, best), r);
}

/* The arm from its fingertip cell tip; el: the extremity that was an
 * elbow taken for the hand (trk_hand_beyond), -1 none. */
static void fit_arm(cub_tracker *t, cub_track_skeleton *s, int side, int32_t tip, int32_t el, int32_t st)
{
    int js = side ? CUB_KJ_SHOULDER_R : CUB_KJ_SHOULDER_L;
    trk_p3 sh = got(s, js);
    int32_t r = radius(st, R_LIMB);
    trk_p3 hand = inside(hand_centre(t, tip, pm(st, P_HAND_REACH)), r);
    trk_p3 wrist = inside(cell_p(t, path_at(t, tip, pm(st, P_WRIST_IN))), r);
    if (el >= 0) {
        /* the wrist on the forearm's straight line from the fist to the
         * elbow (not on the fist's path, which runs into the chest) */
        trk_p3 pe = cell_p(t, el), pt = cell_p(t, tip);
        int32_t l = dist3(pe, pt), w = pm(st, P_WRIST_IN);
        if (l > w)
            wrist = inside((trk_p3){pt.x + (pe.x - pt.x) * w / l, pt.y + (pe.y - pt.y) * w / l,
                                    pt.z + (pe.z - pt.z) * w / l},
                           r);
    }
    int32_t lu = pm(st, P_UPPER_ARM), lf = pm(st, P_FOREARM);
    int32_t reach = learn_reach(t, side, dist3(sh, wrist), lu + lf);
    lu = reach * lu / (lu + lf), lf = reach - lu;
    trk_p3 other = got(s, side ? CUB_KJ_SHOULDER_L : CUB_KJ_SHOULDER_R);
    /* a folded arm: the elbow fitting both lengths lies on a wide circle
     * that the path need not cross (a forearm raised before the chest),
     * and mostly hangs below */
    bool folded = dist3(sh, wrist) * 1000 < reach * EL_FOLDED;
    int32_t search = pm(st, folded ? EL_SEARCH_FOLDED : EL_SEARCH), w_up = folded ? EL_W_UP : 0;
    trk_p3 elbow = middle_near(t, path_middle(t, tip, sh, lu, wrist, lf), sh, lu * EL_UPPER / 1000, wrist, lf, other, r,
                               search, w_up);
    put(s, js + 1, elbow, CUB_Q16_ONE * 3 / 4);
    put(s, js + 2, wrist, CUB_Q16_ONE);
    put(s, js + 3, hand, CUB_Q16_ONE);
}

static void fit_leg(cub_tracker *t, cub_track_skeleton *s, int side, int32_t tip, int32_t st)
{
    int jh = side ? CUB_KJ_HIP_R : CUB_KJ_HIP_L;
    trk_p3 hip = got(s, jh);
    int32_t r = radius(st, R_LIMB);
    trk_p3 foot = inside(cell_p(t, path_at(t, tip, pm(st, P_FOOT_UP))), r);
    trk_p3 ankle = inside(cell_p(t, path_at(t, tip, pm(st, P_ANKLE_UP))), r);
    int32_t lt = pm(st, P_THIGH), ls = pm(st, P_SHIN);
    int32_t reach = learn_reach(t, 2 + side, dist3(hip, ankle), lt + ls);
    lt = reach * lt / (lt + ls), ls = reach - lt;
    trk_p3 knee = inside(cell_p(t, path_middle(t, tip, hip, lt, ankle, ls)), r);
    trk_p3 oh = got(s, side ? CUB_KJ_HIP_L : CUB_KJ_HIP_R);
    knee = add_s(knee, unit(hip.x - oh.x, 0, hip.z - oh.z), KNEE_OUT);
    knee = add_s(knee, unit(ankle.x - hip.x, ankle.y - hip.y, ankle.z - hip.z), KNEE_DOWN);
    put(s, jh + 1, knee, CUB_Q16_ONE * 3 / 4);
    put(s, jh + 2, ankle, CUB_Q16_ONE);
    put(s, jh + 3, foot, CUB_Q16_ONE);
}

/* a limb without an extremity */
enum {
    GUESS_BEHIND = 120, /* mm: a joint this far in front of the surface it projects to is still hidden */
};

/* Point p (a joint inside a limb) agrees with the depth: the cell it
 * projects to is the player's and not behind it (a limb is seen there or
 * hidden by a nearer part); off the image it may be. */
static bool seen_or_hidden(const cub_tracker *t, trk_p3 p)
{
    if (p.z <= 0) return false;
    int32_t gx, gy;
    grid_of(p, &gx, &gy);
    if (!on_grid(gx, gy)) return true;
    int32_t i = gy * TRK_GW + gx;
    return t->mask[i] && t->z[i] <= p.z + GUESS_BEHIND;
}

/* how many of a chain's three joints (1..3) agree with the depth */
static int32_t chain_agrees(const cub_tracker *t, const trk_p3 chain[4])
{
    int32_t n = 0;
    for (int k = 1; k <= 3; k++) n += seen_or_hidden(t, chain[k]);
    return n;
}

/* A limb without an extremity: where it was last frame relative to its
 * root joint, or hanging straight down along the torso. A leg keeps last
 * frame's pose; an arm takes whichever has more of its joints agreeing
 * with the depth. Confidence 0. */
static void guess_chain(const cub_tracker *t, cub_track_skeleton *s, int j0, cub_vec3 axis, int32_t st, bool leg)
{
    static const int32_t arm[4] = {0, 190, 320, 365}, leg_[4] = {0, 267, 552, 560};
    trk_p3 base = got(s, j0), hang[4], kept[4];
    for (int k = 1; k <= 3; k++) hang[k] = add_s(base, axis, -pm(st, leg ? leg_[k] : arm[k]));
    const trk_p3 *chain = hang;
    if (t->have_prev && t->lost_frames < 15) {
        trk_p3 pb = got(&t->prev, j0);
        for (int k = 1; k <= 3; k++) {
            trk_p3 pj = got(&t->prev, j0 + k);
            kept[k] = (trk_p3){base.x + pj.x - pb.x, base.y + pj.y - pb.y, base.z + pj.z - pb.z};
        }
        if (leg || chain_agrees(t, kept) > chain_agrees(t, hang)) chain = kept;
    }
    for (int k = 1; k <= 3; k++) put(s, j0 + k, chain[k], 0);
}

/* The arm's stretched length (shoulder to wrist) as learnt, the
 * proportions' before it is. */
static int32_t arm_reach_mm(const cub_tracker *t, int side, int32_t st)
{
    return t->reach_mm[side] ? t->reach_mm[side] : pm(st, P_UPPER_ARM + P_FOREARM);
}

/* an arm hanging against the thigh or the flank (no extremity: its hand
 * is reached across the touching surfaces, a short cut), per mille of
 * stature */
enum {
    HANG_OUT = 90,   /* out from the torso's axis by (the hip's side: 106; a hanging arm lies beside it) */
    HANG_DROP = 250, /* the tip at least this far below the shoulder */
    HANG_CELLS = 6,  /* such cells at least (fewer are the hip's bulge or noise) */
};

/* The hanging hand's tip on this side: among the player's cells out to
 * the arm's side of the torso's axis beyond the hip, within the arm's
 * reach below its shoulder and off the legs, the farthest from the
 * shoulder (the silhouette's arm beside the thigh ends in the hand); -1
 * when too few cells stand out there. */
static int32_t hang_tip(const cub_tracker *t, const limb_pick *lp, trk_p3 sc, cub_vec3 axis, cub_vec3 lft, int side,
                        int32_t st)
{
    trk_p3 sh = lp->shoulder[side];
    int32_t sgn = side ? -1 : 1, tilt = trk_along(axis.x, axis.y, axis.z, lft);
    int32_t reach = arm_reach_mm(t, side, st) + pm(st, P_HAND_REACH);
    int32_t best = -1, best_d = 0, n = 0;
    for (int32_t i = 0; i < TRK_CELLS; i++) {
        if (!t->mask[i] || t->dist0[i] == TRK_INF) continue;
        trk_p3 p = cell_p(t, i);
        int32_t up = trk_along(p.x - sc.x, p.y - sc.y, p.z - sc.z, axis);
        /* out from the axis (a leaning torso's axis slants sideways) */
        int32_t l = sgn * (trk_along(p.x - sc.x, p.y - sc.y, p.z - sc.z, lft) - (int32_t)(((int64_t)tilt * up) >> 16));
        if (l < pm(st, HANG_OUT) || up > -pm(st, HANG_DROP)) continue;
        int32_t d = dist3(p, sh);
        if (d > reach) continue;
        n++;
        if (d > best_d && !trk_on_leg(t, i, lp, st)) best_d = d, best = i;
    }
    return n >= HANG_CELLS ? best : -1;
}

/* A straight arm hanging from the shoulder joint j0 to the tip cell: the
 * hand, wrist and elbow on the line between them (inside the limb). */
static void hang_arm(const cub_tracker *t, cub_track_skeleton *s, int j0, int32_t tip, int side, int32_t st)
{
    int32_t r = radius(st, R_LIMB);
    trk_p3 sh = got(s, j0), tp = inside(cell_p(t, tip), r);
    int32_t l = dist3(sh, tp);
    if (l <= 0) return;
    int32_t reach = arm_reach_mm(t, side, st);
    int32_t lu = reach * P_UPPER_ARM / (P_UPPER_ARM + P_FOREARM);
    /* along the line: the upper arm's share of the reach, then the wrist
     * and the palm's middle back from the fingertip */
    int32_t a[4] = {0, lu < l ? lu : l, l - pm(st, P_WRIST_IN), l - pm(st, P_HAND_REACH / 2)};
    for (int k = 1; k <= 3; k++) {
        int32_t ak = a[k] > 0 ? a[k] : 0;
        put(s, j0 + k, (trk_p3){sh.x + (tp.x - sh.x) * ak / l, sh.y + (tp.y - sh.y) * ak / l, sh.z + (tp.z - sh.z) * ak / l},
            CUB_Q16_ONE / 4);
    }
}

void trk_fit_skeleton(cub_tracker *t, int32_t root, int32_t *ext, int32_t next, cub_track_skeleton *s)
{
    bool on_floor;
    limb_pick lp = {.head = trk_fit_head(t, root, ext, &next, &on_floor), .elbow = {-1, -1}};
    int32_t head = lp.head >= 0 ? ext[lp.head] : root, st = t->stature_mm;
    trk_p3 hd = inside(cell_p(t, path_at(t, head, pm(st, P_HEAD_DOWN))), radius(st, R_HEAD));
    /* the torso hangs from just below the neck base, where one was seen
     * (the silhouette's shoulders: a long neck, a long torso); the
     * shoulder centre joint, and the shoulder joints level with it, sit
     * close to a fixed share of stature below the head top on every
     * source, which the neck base measured on a silhouette (100-250 per
     * mille, and a first reading taken on a bent body lasts) may only
     * nudge */
    int32_t sc_drop = t->neck_drop_mm ? t->neck_drop_mm + pm(st, P_BELOW_NECK) : pm(st, P_NECK_DOWN);
    trk_p3 sc = inside(cell_p(t, path_at(t, head, sc_drop)), radius(st, R_TORSO));
    int32_t sj_drop = cub_fx_clamp(sc_drop, pm(st, P_NECK_DOWN_MIN), pm(st, P_NECK_DOWN_MAX)); /* mm */
    trk_p3 sj = inside(cell_p(t, path_at(t, head, sj_drop)), radius(st, R_TORSO));
    trk_p3 rt = inside(cell_p(t, root), radius(st, R_TORSO));
    cub_vec3 axis = dist3(sc, rt) > 60 ? unit(sc.x - rt.x, sc.y - rt.y, sc.z - rt.z) : t->up;
    if (lp.head < 0) axis = t->up;
    cub_vec3 lat = torso_lateral(t, root, pm(st, 150));
    cub_vec3 lft = {lat.x * TRK_LEFT_SIGN, lat.y * TRK_LEFT_SIGN, lat.z * TRK_LEFT_SIGN};
    /* down the torso in the image's plane: the axis's tilt in depth is
     * mostly the chest standing out before the neck (depth comes from the
     * surface below) */
    cub_vec3 down = unit(axis.x, axis.y, axis.z * AXIS_Z / 4);
    trk_p3 hc = add_s(sc, axis, -pm(st, P_HIPC));
    put(s, CUB_KJ_HEAD, hd, lp.head >= 0 ? CUB_Q16_ONE : 0);
    put(s, CUB_KJ_SHOULDER_CENTRE, sj, CUB_Q16_ONE * 3 / 4);
    put(s, CUB_KJ_SPINE, onto_surface(t, add_s(sc, down, -pm(st, P_SPINE)), radius(st, R_TORSO)), CUB_Q16_ONE / 2);
    put(s, CUB_KJ_HIP_CENTRE, onto_surface(t, add_s(sc, down, -pm(st, P_HIPC_JOINT)), radius(st, R_TORSO)),
        CUB_Q16_ONE / 2);
    trk_p3 hp = add_s(sc, down, -pm(st, P_HIPC + P_HIP_DROP));
    int32_t half = run_half_mm(t, add_s(sc, axis, -pm(st, P_ARM_ROOT_RUN))) - pm(st, R_ARM_ROOT_EDGE);
    if (half < pm(st, P_ARM_ROOT_MIN)) half = pm(st, P_SHOULDER_HALF);
    if (half > pm(st, P_SHOULDER_MAX)) half = pm(st, P_SHOULDER_MAX);
    int32_t jrun = run_half_mm(t, add_s(sj, axis, -pm(st, P_SHOULDER_RUN)));
    int32_t jhalf = learn_shoulders(t, jrun - pm(st, R_SHOULDER_EDGE), st);
    /* the arms hang from the shoulders deep in the body (where they
     * widen the silhouette below the shoulders); the joints the skeletons
     * name shoulders sit nearer the front, and as far in from the
     * silhouette's edge at their own height as the shoulder's round top is
     * thick, whatever the source: CMU's wide, Bandai's close to the neck
     * (the chest is as wide for both, and below the shoulders it or an arm
     * held out hides where the joint is) */
    trk_p3 shl = onto_shoulder(t, add_s(sc, lft, half), radius(st, R_SHOULDER));
    trk_p3 shr = onto_shoulder(t, add_s(sc, lft, -half), radius(st, R_SHOULDER));
    put(s, CUB_KJ_SHOULDER_L, shl, CUB_Q16_ONE / 2);
    put(s, CUB_KJ_SHOULDER_R, shr, CUB_Q16_ONE / 2);
    put(s, CUB_KJ_HIP_L, onto_surface(t, add_s(hp, lft, pm(st, P_HIP_HALF)), radius(st, R_HIP)), CUB_Q16_ONE / 2);
    put(s, CUB_KJ_HIP_R, onto_surface(t, add_s(hp, lft, -pm(st, P_HIP_HALF)), radius(st, R_HIP)), CUB_Q16_ONE / 2);

    lp.shoulder[0] = got(s, CUB_KJ_SHOULDER_L), lp.shoulder[1] = got(s, CUB_KJ_SHOULDER_R), lp.head_c = hd;
    lp.reach_mm = pm(st, P_UPPER_ARM + P_FOREARM + P_HAND_REACH) * ARM_SLACK / 100;
    lp.bent = trk_bent(t, root, &lp, st);
    trk_from_shoulders(t, &lp);
    pick_limbs(t, root, ext, next, st, sc, hc, axis, lat, &lp);
    if (on_floor) feet_on_floor(t, hc, lat, st, &lp);
    for (int side = 0; side < 2; side++) {
        int32_t h = lp.hand[side];
        if (h >= 0 && !trk_on_torso(t, root, h, sc, hc, axis, lft, st)) continue;
        int32_t f = trk_hand_in_front(t, root, &lp, sc, hc, axis, lft, side, st);
        if (f >= 0) lp.hand[side] = f;
    }
    /* a forearm pointing at the camera or raised before the chest leaves
     * its elbow as the arm's extremity: the fist lies beyond it */
    for (int side = 0; side < 2; side++) {
        if (lp.hand[side] < 0) continue;
        int32_t f = trk_hand_beyond(t, &lp, sc, hc, axis, lft, side, st);
        if (f >= 0) lp.elbow[side] = lp.hand[side], lp.hand[side] = f;
    }
    /* the elbows hang from the arms' roots level with the shoulder joints
     * (sj, its drop held to the proportions' range), not with the
     * neck-based centre: a bent or leaning body measures its neck base
     * low, and a root 80 mm down the flank fits the elbow onto the torso;
     * the hands were named from the roots above */
    put(s, CUB_KJ_SHOULDER_L, onto_shoulder(t, add_s(sj, lft, half), radius(st, R_SHOULDER)), CUB_Q16_ONE / 2);
    put(s, CUB_KJ_SHOULDER_R, onto_shoulder(t, add_s(sj, lft, -half), radius(st, R_SHOULDER)), CUB_Q16_ONE / 2);
    for (int side = 0; side < 2; side++) {
        int jh = side ? CUB_KJ_HIP_R : CUB_KJ_HIP_L;
        if (lp.hand[side] >= 0) fit_arm(t, s, side, lp.hand[side], lp.elbow[side], st);
        if (lp.foot[side] >= 0) fit_leg(t, s, side, lp.foot[side], st);
        else guess_chain(t, s, jh, axis, st, true);
    }
    int32_t front = radius(st, R_SHOULDER) - pm(st, R_SHOULDER_JOINT);
    /* the output's shoulder joints (the arms were fitted from their roots above) */
    trk_p3 jl = onto_shoulder(t, add_s(sj, lft, jhalf), radius(st, R_SHOULDER));
    trk_p3 jr = onto_shoulder(t, add_s(sj, lft, -jhalf), radius(st, R_SHOULDER));
    put(s, CUB_KJ_SHOULDER_L, (trk_p3){jl.x, jl.y, jl.z - front}, CUB_Q16_ONE / 2);
    put(s, CUB_KJ_SHOULDER_R, (trk_p3){jr.x, jr.y, jr.z - front}, CUB_Q16_ONE / 2);
    /* an arm without a hand: hanging beside the thigh when the silhouette
     * shows it there, else last frame's pose about the output's shoulder
     * or down the torso */
    for (int side = 0; side < 2; side++) {
        if (lp.hand[side] >= 0) continue;
        int j0 = side ? CUB_KJ_SHOULDER_R : CUB_KJ_SHOULDER_L;
        int32_t h = hang_tip(t, &lp, sc, axis, lft, side, st);
        if (h >= 0) hang_arm(t, s, j0, h, side, st);
        else guess_chain(t, s, j0, axis, st, false);
    }
}

/* Light smoothing that does not lag: small moves (sensor jitter) are
 * averaged, large ones (a child's real motion) pass straight through. The
 * limits are per 100 ms and scale with the time since the last frame
 * (33 ms, the Kinect's rate, when unknown): a move that big within that
 * time is motion at any frame rate. A wrong pick for one frame (hands
 * swapped, an elbow taken for a hand) jumps further than the limbs move,
 * and a quarter of it is kept out. */
void trk_smooth(cub_tracker *t, cub_track_skeleton *s)
{
    if (!t->have_prev || t->lost_frames > 0 || t->prev.player_id != s->player_id) return;
    int32_t dt = t->dt_us;
    int32_t l1 = SM_JITTER * dt / 100000, l2 = SM_SLOW * dt / 100000, l3 = SM_FAST * dt / 100000;
    for (int j = 0; j < CUB_KJ_COUNT; j++) {
        trk_p3 a = got(&t->prev, j), b = got(s, j);
        int32_t d = dist3(a, b), w; /* weight of the new value, /4 */
        w = d < l1 ? 1 : d < l2 ? 2 : d < l3 ? 3 : 4;
        trk_p3 m = {a.x + (b.x - a.x) * w / 4, a.y + (b.y - a.y) * w / 4, a.z + (b.z - a.z) * w / 4};
        put(s, j, m, s->confidence[j]);
    }
}

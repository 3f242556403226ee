/* From extremities to twenty joints (the pipeline's steps 7-10, see
 * tracker.c): the body's frame once per frame, the limbs' pick (the
 * hands and feet among the extremities, corrected by the resolvers of
 * trk_resolve.c), then the joints placed along the geodesic paths and the
 * torso axis with body proportions (trk_body.h). */
#include "trk_body.h"

/* an extremity this far from a shoulder (per mille of the arm's reach
 * with the hand) is no hand */
enum {
    ARM_SLACK = 1000,
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

/* The body's frame (trk_body.h): the head and stature first
 * (trk_head.c), then the torso from the head down, the direction across
 * it, and the arms' roots. */
static void body_frame(cub_tracker *t, int32_t root, int32_t *ext, int32_t *next, trk_frame *f)
{
    f->t = t, f->root = root;
    f->head = trk_fit_head(t, root, ext, next, &f->on_floor);
    int32_t head = f->head >= 0 ? ext[f->head] : root, st = t->stature_mm;
    f->st = st;
    f->head_c = inside(cell_p(t, path_at(t, head, pm(st, P_HEAD_DOWN))), radius(st, R_HEAD));
    /* the torso hangs from just below the neck base, where one was seen
     * (the silhouette's shoulders: a long neck, a long torso); the
     * shoulder centre joint, and the shoulder joints level with it, sit
     * close to a fixed share of stature below the head top on every
     * source, which the neck base measured on a silhouette (100-250 per
     * mille, and a first reading taken on a bent body lasts) may only
     * nudge */
    int32_t sc_drop = t->neck_drop_mm ? t->neck_drop_mm + pm(st, P_BELOW_NECK) : pm(st, P_NECK_DOWN);
    f->sc = inside(cell_p(t, path_at(t, head, sc_drop)), radius(st, R_TORSO));
    int32_t sj_drop = cub_fx_clamp(sc_drop, pm(st, P_NECK_DOWN_MIN), pm(st, P_NECK_DOWN_MAX)); /* mm */
    f->sj = inside(cell_p(t, path_at(t, head, sj_drop)), radius(st, R_TORSO));
    trk_p3 sc = f->sc, sj = f->sj, rt = inside(cell_p(t, root), radius(st, R_TORSO));
    f->axis = dist3(sc, rt) > 60 ? unit(sc.x - rt.x, sc.y - rt.y, sc.z - rt.z) : t->up;
    if (f->head < 0) f->axis = t->up;
    f->lat = torso_lateral(t, root, pm(st, 150));
    f->lft = (cub_vec3){f->lat.x * TRK_LEFT_SIGN, f->lat.y * TRK_LEFT_SIGN, f->lat.z * TRK_LEFT_SIGN};
    /* down the torso in the image's plane: the axis's tilt in depth is
     * mostly the chest standing out before the neck (depth comes from the
     * surface below) */
    f->down = unit(f->axis.x, f->axis.y, f->axis.z * AXIS_Z / 4);
    f->hc = add_s(sc, f->axis, -pm(st, P_HIPC));
    /* the arms hang from the shoulders deep in the body (where they
     * widen the silhouette below the shoulders); the joints the skeletons
     * name shoulders sit nearer the front, and as far in from the
     * silhouette's edge at their own height as the shoulder's round top is
     * thick, whatever the source: CMU's wide, Bandai's close to the neck
     * (the chest is as wide for both, and below the shoulders it or an arm
     * held out hides where the joint is) */
    int32_t half = run_half_mm(t, add_s(sc, f->axis, -pm(st, P_ARM_ROOT_RUN))) - pm(st, R_ARM_ROOT_EDGE);
    if (half < pm(st, P_ARM_ROOT_MIN)) half = pm(st, P_SHOULDER_HALF);
    if (half > pm(st, P_SHOULDER_MAX)) half = pm(st, P_SHOULDER_MAX);
    int32_t jrun = run_half_mm(t, add_s(sj, f->axis, -pm(st, P_SHOULDER_RUN)));
    f->joint_half = learn_shoulders(t, jrun - pm(st, R_SHOULDER_EDGE), st);
    /* the hands are named from the arms' roots level with the neck-based
     * centre; the elbows hang from roots level with the shoulder joints
     * (sj, its drop held to the proportions' range): a bent or leaning
     * body measures its neck base low, and a root 80 mm down the flank
     * fits the elbow onto the torso */
    for (int side = 0; side < 2; side++) {
        int32_t h = side ? -half : half;
        f->arm_root[side] = onto_shoulder(t, add_s(sc, f->lft, h), radius(st, R_SHOULDER));
        f->fit_root[side] = onto_shoulder(t, add_s(sj, f->lft, h), radius(st, R_SHOULDER));
    }
    f->reach_mm = pm(st, P_UPPER_ARM + P_FOREARM + P_HAND_REACH) * ARM_SLACK / 1000;
}

/* The torso's joints: spine and hip centre down the torso in the
 * image's plane, taking their depth from the surface there (the axis
 * tilts in depth as the chest stands out); the hips too. */
static void fit_torso(const trk_frame *f, cub_track_skeleton *s)
{
    const cub_tracker *t = f->t;
    int32_t st = f->st;
    trk_p3 sc = f->sc, hp = add_s(sc, f->down, -pm(st, P_HIPC + P_HIP_DROP));
    put(s, CUB_KJ_HEAD, f->head_c, f->head >= 0 ? CUB_Q16_ONE : 0);
    put(s, CUB_KJ_SHOULDER_CENTRE, f->sj, CUB_Q16_ONE * 3 / 4);
    put(s, CUB_KJ_SPINE, onto_surface(t, add_s(sc, f->down, -pm(st, P_SPINE)), radius(st, R_TORSO)), CUB_Q16_ONE / 2);
    put(s, CUB_KJ_HIP_CENTRE, onto_surface(t, add_s(sc, f->down, -pm(st, P_HIPC_JOINT)), radius(st, R_TORSO)),
        CUB_Q16_ONE / 2);
    put(s, CUB_KJ_HIP_L, onto_surface(t, add_s(hp, f->lft, pm(st, P_HIP_HALF)), radius(st, R_HIP)), CUB_Q16_ONE / 2);
    put(s, CUB_KJ_HIP_R, onto_surface(t, add_s(hp, f->lft, -pm(st, P_HIP_HALF)), radius(st, R_HIP)), CUB_Q16_ONE / 2);
}

/* The output's shoulder joints, written once: the learnt width about
 * the shoulder centre joint, R_SHOULDER_JOINT inside the surface (the
 * arms were fitted from their roots, f->fit_root). */
static void fit_shoulders(const trk_frame *f, cub_track_skeleton *s)
{
    int32_t st = f->st, front = radius(st, R_SHOULDER) - pm(st, R_SHOULDER_JOINT);
    for (int side = 0; side < 2; side++) {
        int32_t h = side ? -f->joint_half : f->joint_half;
        trk_p3 j = onto_shoulder(f->t, add_s(f->sj, f->lft, h), radius(st, R_SHOULDER));
        put(s, side ? CUB_KJ_SHOULDER_R : CUB_KJ_SHOULDER_L, (trk_p3){j.x, j.y, j.z - front}, CUB_Q16_ONE / 2);
    }
}

/* Legs and arms among the extremities (all but the head): a leg joins the
 * torso below the root or ends low (a hand hanging against the hip joins
 * the torso low too, by a short cut: a leg raised high is also far along
 * the surface). The resolvers of TRK_AT_CLASSIFIED may class it again. */
static void classify_limbs(const trk_frame *f, const int32_t *ext, int32_t n, limb_pick *lp)
{
    const cub_tracker *t = f->t;
    int32_t st = f->st;
    trk_p3 r = cell_p(t, f->root), hc = f->hc;
    lp->ncand = 0;
    for (int32_t k = 0; k < n; k++) {
        if (k == f->head) continue;
        trk_p3 p = cell_p(t, ext[k]);
        trk_p3 bp = cell_p(t, path_base(t, ext[k], pm(st, 200)));
        /* the attachment above or below the root; the tip's height decides
         * only when the attachment is level with the root */
        int32_t bh = trk_along(bp.x - r.x, bp.y - r.y, bp.z - r.z, f->axis);
        int32_t dh = trk_along(p.x - hc.x, p.y - hc.y, p.z - hc.z, f->axis);
        bool leg = dh < -pm(st, 250) || (bh < -pm(st, 40) && t->dist0[ext[k]] > pm(st, 550));
        lp->limb[lp->ncand] = leg ? TRK_LEG : TRK_ARM;
        lp->cand[lp->ncand++] = ext[k];
    }
}

/* The feet: the two legs farthest along the surface (extrema come
 * farthest first), each on its side of the hips. */
static void name_feet(const trk_frame *f, limb_pick *lp)
{
    int32_t feet[2], nf = 0, s[2] = {0, 0};
    for (int32_t k = 0; k < lp->ncand && nf < 2; k++)
        if (lp->limb[k] == TRK_LEG) feet[nf++] = lp->cand[k];
    lp->foot[0] = lp->foot[1] = -1;
    for (int32_t k = 0; k < nf; k++) {
        trk_p3 p = cell_p(f->t, feet[k]), hc = f->hc;
        s[k] = TRK_LEFT_SIGN * trk_along(p.x - hc.x, p.y - hc.y, p.z - hc.z, f->lat);
    }
    if (nf == 2) {
        int left = s[0] > s[1] ? 0 : 1;
        lp->foot[0] = feet[left], lp->foot[1] = feet[1 - left];
    } else if (nf == 1) {
        lp->foot[s[0] > 0 ? 0 : 1] = feet[0];
    }
}

/* What the elbow's search fits: both bone lengths from a (the shoulder,
 * la) and b (the wrist, lb); other: the other shoulder (the outward
 * direction is away from it, level); r: the limb's radius; search_mm: how
 * far around the path's cell; w_up: the weight (quarters) of lying above
 * the shoulder. */
typedef struct elbow_fit {
    trk_p3 a, b, other;
    int32_t la, lb, r, search_mm, w_up;
} elbow_fit;

/* The elbow near the path's middle cell mid: the player's cell around it
 * that best fits both bone lengths, out to the arm's side rather than
 * toward the body's middle: an arm against the torso lets the path cut
 * across the touching surfaces, which pulls the path's cell inward.
 * (Knees keep the path's cell: legs together make the search find the
 * other leg.) */
static trk_p3 middle_near(const cub_tracker *t, int32_t mid, const elbow_fit *ef)
{
    trk_p3 a = ef->a, b = ef->b, other = ef->other;
    int32_t la = ef->la, lb = ef->lb, r = ef->r, search_mm = ef->search_mm, w_up = ef->w_up;
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

/* The arm from its fingertip cell tip, hanging from its root level with
 * the shoulder joints (f->fit_root); el: the extremity that was an elbow
 * taken for the hand (trk_hand_beyond), -1 none. */
static void fit_arm(cub_tracker *t, const trk_frame *f, cub_track_skeleton *s, int side, int32_t tip, int32_t el)
{
    int js = side ? CUB_KJ_SHOULDER_R : CUB_KJ_SHOULDER_L;
    int32_t st = f->st;
    trk_p3 sh = f->fit_root[side];
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
    trk_p3 other = f->fit_root[1 - side];
    /* a folded arm: the elbow fitting both lengths lies on a wide circle
     * that the path need not cross (a forearm raised before the chest),
     * and mostly hangs below */
    bool folded = dist3(sh, wrist) * 1000 < reach * EL_FOLDED;
    int32_t search = pm(st, folded ? EL_SEARCH_FOLDED : EL_SEARCH), w_up = folded ? EL_W_UP : 0;
    elbow_fit ef = {.a = sh, .b = wrist, .other = other, .la = lu * EL_UPPER / 1000, .lb = lf, .r = r,
                    .search_mm = search, .w_up = w_up};
    trk_p3 elbow = middle_near(t, path_middle(t, tip, sh, lu, wrist, lf), &ef);
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
static void guess_chain(const trk_frame *f, cub_track_skeleton *s, int j0, bool leg)
{
    const cub_tracker *t = f->t;
    cub_vec3 axis = f->axis;
    int32_t st = f->st;
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

/* A straight arm hanging from the output's shoulder joint to the tip
 * cell (the resolver hanging_arm's): the hand, wrist and elbow on the line
 * between them (inside the limb). */
static void hang_arm(const trk_frame *f, cub_track_skeleton *s, int side, int32_t tip)
{
    const cub_tracker *t = f->t;
    int32_t st = f->st;
    int j0 = side ? CUB_KJ_SHOULDER_R : CUB_KJ_SHOULDER_L;
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

/* The pipeline's steps 7-10 (tracker.c): the body's frame, the limbs'
 * pick with the resolvers at each stage, then the joints. */
void trk_fit_skeleton(cub_tracker *t, int32_t root, int32_t *ext, int32_t next, cub_track_skeleton *s)
{
    trk_frame f;
    body_frame(t, root, ext, &next, &f);
    fit_torso(&f, s);
    limb_pick lp = {.elbow = {-1, -1}, .hang = {-1, -1}};
    trk_from_shoulders(t, &f);
    trk_resolve(&f, &lp, TRK_AT_FRAME);
    classify_limbs(&f, ext, next, &lp);
    trk_resolve(&f, &lp, TRK_AT_CLASSIFIED);
    name_feet(&f, &lp);
    trk_resolve(&f, &lp, TRK_AT_FEET);
    trk_cost_hands(&f, &lp);
    trk_resolve(&f, &lp, TRK_AT_COSTED);
    trk_choose_hands(&lp);
    trk_resolve(&f, &lp, TRK_AT_NAMED);
    for (int side = 0; side < 2; side++) {
        int jh = side ? CUB_KJ_HIP_R : CUB_KJ_HIP_L;
        if (lp.hand[side] >= 0) fit_arm(t, &f, s, side, lp.hand[side], lp.elbow[side]);
        if (lp.foot[side] >= 0) fit_leg(t, s, side, lp.foot[side], f.st);
        else guess_chain(&f, s, jh, true);
    }
    fit_shoulders(&f, s);
    /* an arm without a hand: hanging beside the thigh when the silhouette
     * shows it there, else last frame's pose about the output's shoulder
     * or down the torso */
    for (int side = 0; side < 2; side++) {
        if (lp.hand[side] >= 0) continue;
        if (lp.hang[side] >= 0) hang_arm(&f, s, side, lp.hang[side]);
        else guess_chain(&f, s, side ? CUB_KJ_SHOULDER_R : CUB_KJ_SHOULDER_L, false);
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

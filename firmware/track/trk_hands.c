/* Naming the hands: which extremity is which hand (a cost per candidate
 * and side, both hands chosen at once), and a hand held before the torso,
 * which is no extremity. */
#include "trk_body.h"

/* naming the hands: limits (per mille of stature, or of the arm's reach:
 * shoulder to fingertip) and the cost's weights (quarters); the naming's
 * special cases (the reach along the surface, a bump on a shoulder or the
 * skull, a path from across the body) are trk_resolve.c's */
enum {
    HC_REACH = 1300,   /* per mille of the reach: no farther from its shoulder, straight */
    HC_W_GOWN = 4,     /* along the surface, nearer its own shoulder than the other */
    HC_W_FAR = 1,      /* far along the arm from its shoulder */
    HC_W_SIDE = 0,     /* on its own side of the body (0: a sword's grip crosses the hands) */
    HC_W_LONG = 4,     /* standing out far from the root... */
    HC_LONG = 600,     /* ...up to this */
    HC_W_PREV = 3,     /* near last frame's hand... */
    HC_PREV_CAP = 300, /* ...counted up to this */
    HC_NONE = -100,    /* the cost of seeing no hand on a side */
    HC_W_ENTRY = 6,    /* the side the arm's path leaves the torso... */
    HC_ENTRY = 180,    /* ...this far from the root along the surface */
};

/* a hand before the torso, per mille of stature */
enum {
    HF_FRONT = 40,  /* nearer the camera than the torso's surface by */
    HF_MIN = 150,   /* at least this far from the shoulder */
    HF_CROSS = 50,  /* how far across the body's middle */
    HF_OTHER = 50,  /* away from the other hand (fists side by side) */
    HF_HEAD = 130,  /* and from the head's centre (a chin leaning forward stands out too) */
    HF_ABOVE = 0,   /* an extremity on the torso: below the shoulders by */
    HF_WIDE = 200,  /* and within this of the middle */
    HF_LEGS = 130,  /* below the hips: within this of the middle */
    HF_CELLS = 4,   /* cells before the torso, fewer is noise */
    HF_UP = 60,     /* looked for up to this far above the shoulders */
    HF_BOW = 70,    /* the head's centre this much nearer the camera than the root's surface: a body bent toward it */
    HF_FOOT_PATH = 80,    /* a cell this near a foot's path is the leg's (a knee raised aside or before the hip) */
    HF_JOIN_BACK = 100,  /* or its own path, this far back from it... */
    HF_JOIN_NEAR = 40,   /* ...runs this near a foot's path... */
    HF_JOIN_FROM = 200,  /* ...this far from the root (beyond the hip)... */
    HF_JOIN_BEHIND = 80, /* ...along the foot path's cells from this nearer the root than it on */
    HF_KNEE = 120,       /* or it lies this near a named leg's knee (a bent knee's tip stands out of its path) */
};

/* an elbow taken for the hand, per mille of stature: the fist beyond it */
enum {
    HB_NEAR = 210,  /* within a forearm and hand of the extremity */
    HB_DZ = 40,     /* nearer the camera than it by */
    HB_MORE = 20,   /* farther from the shoulder than it by */
    HB_BELOW = 60,  /* no lower below the pelvis' middle (a thigh) */
    HB_CELLS = 14,  /* such cells, at least (a few are a fold of the sleeve or chest)... */
    HB_CELLS_MM = 2100, /* ...up to this depth; farther, fewer (a fist's cells fall with the square of its distance) */
    HB_ACROSS = 16, /* the fist no nearer the other shoulder than the extremity by (across the middle) */
};

/* a guard's fist by the chin above its elbow, per mille of stature */
enum {
    HG_ELBOW = 250, /* the extremity no farther from its shoulder (an elbow: a straight arm's hand is farther) */
    HG_UP = 120,    /* the fist at least this far above it (the forearm upright)... */
    HG_DZ = 80,     /* ...at its depth within this (the forearm before the chest, not the chest behind) */
    HG_LESS = 40,   /* ...no nearer the shoulder than it by more (the upper arm runs up to the shoulder) */
    HG_CELLS = 6,   /* such cells, at least */
};

/* The head's centre well before the root's surface: a bow (its chest and
 * shoulders stand out before the belly, the hands hang below). */
bool trk_bent(const trk_frame *f)
{
    return f->head >= 0 && f->head_c.z < f->t->z[f->root] - pm(f->st, HF_BOW);
}

/* Distances along the surface from the shoulder joint sh (the player's
 * cell nearest it) into dist, TRK_INF where unreachable. */
static void from_shoulder(cub_tracker *t, trk_p3 sh, int32_t *dist)
{
    for (int32_t b = 0; b < TRK_BLOCKS; b++) dist[b] = TRK_INF;
    if (sh.z <= 0) return;
    int32_t gx0 = (CUB_KINECT_CX + sh.x * CUB_KINECT_FOCAL_PX / sh.z) / TRK_CELL_PX;
    int32_t gy0 = (CUB_KINECT_CY - sh.y * CUB_KINECT_FOCAL_PX / sh.z) / TRK_CELL_PX;
    int32_t best = -1, best_d = INT32_MAX;
    for (int32_t gy = gy0 - 4; gy <= gy0 + 4; gy++)
        for (int32_t gx = gx0 - 4; gx <= gx0 + 4; gx++) {
            if (!on_grid(gx, gy)) continue;
            int32_t i = gy * TRK_GW + gx;
            if (!t->mask[i] || t->dist0[i] == TRK_INF) continue;
            int32_t d = dist3(cell_p(t, i), sh);
            if (d < best_d) best_d = d, best = i;
        }
    if (best >= 0) trk_geodesic_coarse(t, dist, best);
}

void trk_from_shoulders(cub_tracker *t, const trk_frame *f)
{
    trk_coarse_edges(t);
    from_shoulder(t, f->arm_root[0], t->dist_sh[0]);
    from_shoulder(t, f->arm_root[1], t->dist_sh[1]);
}

/* The cost of naming candidate k side's hand (mm-like units; lower is
 * better), INT32_MAX when out of that arm's reach: a hand is nearer its own
 * shoulder than the other, near where it was, and at the end of a long
 * path (a bump on the torso is not); what it needs for the naming's
 * special cases (the resolvers of TRK_AT_COSTED) goes into lp->nm too. */
static int32_t hand_cost(const trk_frame *f, limb_pick *lp, int32_t k, int side)
{
    const cub_tracker *t = f->t;
    int32_t c = lp->nm.cell[k];
    trk_p3 p = cell_p(t, c), sc = f->sc;
    cub_vec3 lft = f->lft;
    int32_t st = f->st;
    int32_t d = dist3(p, f->arm_root[side]), d_other = dist3(p, f->arm_root[1 - side]);
    if (d > f->reach_mm * HC_REACH / 1000) return INT32_MAX;
    /* along the surface from each shoulder; a part cut off by the
     * projector's shadow (a hand before the body) has the straight line */
    int32_t gs = trk_coarse_at(t, t->dist_sh[side], c), go = trk_coarse_at(t, t->dist_sh[1 - side], c);
    if (gs == TRK_INF) gs = d;
    if (go == TRK_INF) go = d_other;
    int32_t sgn = side ? -1 : 1, l = sgn * trk_along(p.x - sc.x, p.y - sc.y, p.z - sc.z, lft);
    int32_t g = t->dist0[c] < pm(st, HC_LONG) ? t->dist0[c] : pm(st, HC_LONG);
    int32_t cost = -HC_W_SIDE * l / 4 - HC_W_LONG * g / 4;
    /* the side where the path from the root (depth steps cost extra on
     * it, so it follows the arm) leaves the torso: arms crossed before
     * the body keep their own shoulder */
    int32_t e = c;
    for (int32_t steps = 0; t->parent0[e] >= 0 && t->dist0[e] > pm(st, HC_ENTRY) && steps < 800; steps++)
        e = t->parent0[e];
    int32_t le = sgn * trk_along(t->x[e] - sc.x, t->y[e] - sc.y, t->z[e] - sc.z, lft);
    cost -= HC_W_ENTRY * le / 4;
    /* nearer its own shoulder than the other; the arm's length from it */
    cost += HC_W_GOWN * (gs - go) / 4 - HC_W_FAR * (gs < f->reach_mm ? gs : f->reach_mm) / 4;
    if (t->have_prev && t->lost_frames == 0) {
        int32_t dp = dist3(p, got(&t->prev, side ? CUB_KJ_HAND_R : CUB_KJ_HAND_L));
        cost += HC_W_PREV * (dp < pm(st, HC_PREV_CAP) ? dp : pm(st, HC_PREV_CAP)) / 4;
    }
    lp->nm.gs[side][k] = gs, lp->nm.go[side][k] = go, lp->nm.le[side][k] = le;
    return cost;
}

void trk_cost_hands(const trk_frame *f, limb_pick *lp)
{
    hand_naming *nm = &lp->nm;
    nm->n = 0;
    for (int32_t k = 0; k < lp->ncand; k++)
        if (lp->limb[k] == TRK_ARM) nm->cell[nm->n++] = lp->cand[k];
    for (int side = 0; side < 2; side++) {
        for (int32_t k = 0; k < nm->n; k++) nm->cost[side][k] = hand_cost(f, lp, k, side);
        nm->cost[side][nm->n] = pm(f->st, HC_NONE); /* no hand seen on this side */
    }
}

/* Both hands at once: the pair of candidates (or none for a side) with the
 * least summed cost. */
void trk_choose_hands(limb_pick *lp)
{
    const hand_naming *nm = &lp->nm;
    int32_t nh = nm->n;
    int64_t best = INT64_MAX;
    lp->hand[0] = lp->hand[1] = -1;
    for (int32_t a = 0; a <= nh; a++)
        for (int32_t b = 0; b <= nh; b++) {
            if (a == b && a < nh) continue;
            if (nm->cost[0][a] == INT32_MAX || nm->cost[1][b] == INT32_MAX) continue;
            int64_t c = (int64_t)nm->cost[0][a] + nm->cost[1][b];
            if (c < best) best = c, lp->hand[0] = a < nh ? nm->cell[a] : -1, lp->hand[1] = b < nh ? nm->cell[b] : -1;
        }
}

/* The torso's surface depth at p's height (mm): the root's, or, for a
 * body bent toward the camera, farther up the axis the nearer (a bow
 * brings the chest and shoulders before the belly; they are no hand
 * before the torso). */
static int32_t torso_z(const cub_tracker *t, int32_t root, trk_p3 p, cub_vec3 axis)
{
    if (axis.z >= 0) return t->z[root];
    int32_t u = trk_along(p.x - t->x[root], p.y - t->y[root], p.z - t->z[root], axis);
    return u > 0 ? t->z[root] + (int32_t)(((int64_t)u * axis.z) >> 16) : t->z[root];
}

/* An extremity on the torso's surface (not before it): a shoulder bump or
 * the elbow of an arm whose hand lies before the chest. */
bool trk_on_torso(const trk_frame *f, int32_t i)
{
    const cub_tracker *t = f->t;
    trk_p3 sc = f->sc, hc = f->hc;
    cub_vec3 axis = f->axis, lft = f->lft;
    int32_t st = f->st;
    if (t->z[i] <= t->z[f->root] - pm(st, HF_FRONT)) return false;
    trk_p3 p = cell_p(t, i);
    int32_t up_sc = trk_along(p.x - sc.x, p.y - sc.y, p.z - sc.z, axis);
    int32_t up_hc = trk_along(p.x - hc.x, p.y - hc.y, p.z - hc.z, axis);
    int32_t l = trk_along(p.x - sc.x, p.y - sc.y, p.z - sc.z, lft);
    /* below the hips, within the legs' width, it is a leg's, not an arm's;
     * a hand hanging beside the thigh is out to the side */
    return up_sc <= pm(st, HF_ABOVE) && trk_abs(l) <= pm(st, up_hc < 0 ? HF_LEGS : HF_WIDE);
}

/* Point p lies within near_mm of a named foot's path, at least from_mm
 * along the surface from the root. */
static bool near_foot_path(const cub_tracker *t, trk_p3 p, const limb_pick *lp, int32_t from_mm,
                           int32_t near_mm)
{
    for (int side = 0; side < 2; side++) {
        int32_t f = lp->foot[side];
        if (f < 0 || t->dist0[f] <= from_mm) continue;
        for (int32_t i = f, n = 0; i >= 0 && n < TRK_PATH_STEPS && t->dist0[i] >= from_mm;
             i = t->parent0[i], n++)
            if (dist3(p, cell_p(t, i)) < near_mm) return true;
    }
    return false;
}

/* Cell c lies near a named leg's knee: the foot's path cell a shin's
 * length from the foot's tip in a straight line (the path runs round a
 * bent knee's inner side, and its outer tip, raised aside or toward the
 * camera, stands a thigh's thickness off the path: HF_FOOT_PATH misses
 * it, and a wider path distance everywhere takes hands beside the thigh). */
static bool near_knee(const cub_tracker *t, const limb_pick *lp, int32_t c, int32_t st)
{
    trk_p3 p = cell_p(t, c);
    for (int side = 0; side < 2; side++) {
        int32_t f = lp->foot[side];
        if (f < 0) continue;
        int32_t k = path_at(t, f, pm(st, P_SHIN));
        if (t->parent0[k] >= 0 && dist3(p, cell_p(t, k)) < pm(st, HF_KNEE)) return true;
    }
    return false;
}

/* Cell c lies on a leg: near a named foot's path, or its own path from
 * the root runs along one away from the hips (the foot's path follows the
 * raised thigh's underside, the knee's tip sticks out above it, farther
 * than HF_FOOT_PATH). A real hand's path runs along the arm. */
static bool on_foot_path(const cub_tracker *t, const limb_pick *lp, int32_t c, int32_t st)
{
    int32_t near_mm = pm(st, HF_FOOT_PATH);
    if (near_foot_path(t, cell_p(t, c), lp, t->dist0[c] - near_mm, near_mm)) return true;
    int32_t m = path_base(t, c, t->dist0[c] - pm(st, HF_JOIN_BACK));
    if (t->dist0[m] <= pm(st, HF_JOIN_FROM)) return false;
    return near_foot_path(t, cell_p(t, m), lp, t->dist0[m] - pm(st, HF_JOIN_BEHIND),
                          pm(st, HF_JOIN_NEAR));
}

bool trk_on_leg(const trk_frame *f, const limb_pick *lp, int32_t c)
{
    return on_foot_path(f->t, lp, c, f->st) || near_knee(f->t, lp, c, f->st);
}

/* A hand held before the torso is no extremity (its path ends in the
 * chest), but the forearm and hand stand out in depth: among the cells
 * clearly nearer the camera than the torso's surface, on the shoulder's
 * side and within the arm's reach, the farthest along the surface from
 * the root. */
int32_t trk_hand_in_front(const trk_frame *f, const limb_pick *lp, int side)
{
    const cub_tracker *t = f->t;
    trk_p3 sc = f->sc, hc = f->hc, sh = f->arm_root[side];
    cub_vec3 axis = f->axis, lft = f->lft;
    int32_t root = f->root, st = f->st;
    int32_t other = lp->hand[1 - side];
    int32_t zf = t->z[root] - pm(st, HF_FRONT), reach = pm(st, P_UPPER_ARM + P_FOREARM + P_HAND_REACH);
    int32_t best = -1, best_s = INT32_MIN, nfront = 0, sgn = side ? -1 : 1;
    for (int32_t i = 0; i < TRK_CELLS; i++) {
        if (!t->mask[i] || t->dist0[i] == TRK_INF || t->z[i] > zf) continue;
        trk_p3 p = cell_p(t, i);
        if (lp->bent && p.z > torso_z(t, root, p, axis) - pm(st, HF_FRONT)) continue;
        /* between the hips and a little above the shoulders */
        int32_t up_sc = trk_along(p.x - sc.x, p.y - sc.y, p.z - sc.z, axis);
        int32_t up_hc = trk_along(p.x - hc.x, p.y - hc.y, p.z - hc.z, axis);
        if (up_sc > pm(st, HF_UP) || up_hc < -pm(st, 60)) continue;
        if (sgn * trk_along(p.x - sc.x, p.y - sc.y, p.z - sc.z, lft) < -pm(st, HF_CROSS)) continue;
        int32_t d = dist3(p, sh);
        if (d > reach) continue;
        if (other >= 0 && dist3(p, cell_p(t, other)) < pm(st, HF_OTHER)) continue;
        /* a face leaning forward is no fist before it */
        if (f->head >= 0 && dist3(p, f->head_c) < pm(st, HF_HEAD)) continue;
        nfront++;
        /* the fist ends the forearm's path: a guard's elbow hangs as far
         * from the shoulder as its fist, but is nearer the root along the
         * surface (depth steps cost extra there) */
        if (d <= pm(st, HF_MIN) || t->dist0[i] <= best_s) continue;
        /* a knee raised before the hip stands out in depth too */
        if (!on_foot_path(t, lp, i, st)) best_s = t->dist0[i], best = i;
    }
    return nfront >= HF_CELLS ? best : -1;
}

/* A guard's fist by the chin: the forearm stands upright above the
 * elbow, which ends the arm's path (the fist touches the face, so it is
 * no extremity, and is neither nearer the camera nor farther from the
 * shoulder than the elbow). The fist is the top of the cells above the
 * elbow at its depth, about as far from the shoulder as it (the upper
 * arm's cells run up to the shoulder), off the face; -1 when too few. */
static int32_t fist_above(const trk_frame *f, const limb_pick *lp, int side)
{
    const cub_tracker *t = f->t;
    int32_t e = lp->hand[side], st = f->st;
    trk_p3 pe = cell_p(t, e), sh = f->arm_root[side];
    int32_t other = lp->hand[1 - side], lim = pm(st, HB_NEAR), de = dist3(pe, sh);
    int32_t rc = lim * CUB_KINECT_FOCAL_PX / (pe.z * TRK_CELL_PX) + 1, gx0 = e % TRK_GW, gy0 = e / TRK_GW;
    int32_t best = -1, best_up = INT32_MIN, n = 0;
    for (int32_t gy = gy0 - rc; gy <= gy0; gy++)
        for (int32_t gx = gx0 - rc; gx <= gx0 + rc; gx++) {
            if (!on_grid(gx, gy)) continue;
            int32_t i = gy * TRK_GW + gx;
            if (!t->mask[i] || t->dist0[i] == TRK_INF || trk_abs(t->z[i] - pe.z) > pm(st, HG_DZ)) continue;
            trk_p3 p = cell_p(t, i);
            int32_t up = trk_along(p.x - pe.x, p.y - pe.y, p.z - pe.z, t->up);
            if (up < pm(st, HG_UP) || dist3(p, pe) > lim || dist3(p, sh) < de - pm(st, HG_LESS)) continue;
            if (other >= 0 && dist3(p, cell_p(t, other)) < pm(st, HF_OTHER)) continue;
            if (f->head >= 0 && dist3(p, f->head_c) < pm(st, HF_HEAD)) continue;
            n++;
            if (up > best_up) best_up = up, best = i;
        }
    return n >= HG_CELLS ? best : -1;
}

/* An elbow taken for the hand: a forearm pointing at the camera (or held
 * before the chest) foreshortens into depth steps, the fist is reached
 * across them from the chest and the elbow ends the arm's path. Then the
 * fist lies within a forearm of the extremity, nearer the camera and
 * farther from the shoulder: the nearest such cell, off the face and the
 * other hand. -1 when none, or when that cell lies across the body (past
 * its middle and nearer the other shoulder than the extremity: the other
 * arm's fist before a real hand, the belly of a side bend); a fist at the
 * back of the room shows fewer cells. A guard's fist by the chin is
 * neither nearer nor farther: it is looked for above the elbow first. */
int32_t trk_hand_beyond(const trk_frame *f, const limb_pick *lp, int side)
{
    const cub_tracker *t = f->t;
    trk_p3 sc = f->sc, hc = f->hc;
    cub_vec3 axis = f->axis, lft = f->lft;
    int32_t e = lp->hand[side], other = lp->hand[1 - side], st = f->st;
    trk_p3 pe = cell_p(t, e), sh = f->arm_root[side], so = f->arm_root[1 - side];
    if (pe.z <= 0) return -1;
    int32_t deo = dist3(pe, so) - pm(st, HB_ACROSS);
    int32_t de = dist3(pe, sh), lim = pm(st, HB_NEAR), reach = pm(st, P_UPPER_ARM + P_FOREARM + P_HAND_REACH);
    int32_t rc = lim * CUB_KINECT_FOCAL_PX / (pe.z * TRK_CELL_PX) + 1, gx0 = e % TRK_GW, gy0 = e / TRK_GW;
    int32_t best = -1, best_z = INT32_MAX, n = 0;
    if (!lp->bent && de <= pm(st, HG_ELBOW) && trk_along(pe.x - sh.x, pe.y - sh.y, pe.z - sh.z, t->up) < 0) {
        int32_t fist = fist_above(f, lp, side);
        if (fist >= 0) return fist;
    }
    for (int32_t gy = gy0 - rc; gy <= gy0 + rc; gy++)
        for (int32_t gx = gx0 - rc; gx <= gx0 + rc; gx++) {
            if (!on_grid(gx, gy)) continue;
            int32_t i = gy * TRK_GW + gx;
            if (!t->mask[i] || t->dist0[i] == TRK_INF || t->z[i] > pe.z - pm(st, HB_DZ)) continue;
            trk_p3 p = cell_p(t, i);
            int32_t ds = dist3(p, sh);
            if (dist3(p, pe) > lim || ds < de + pm(st, HB_MORE) || ds > reach) continue;
            if (trk_along(p.x - hc.x, p.y - hc.y, p.z - hc.z, axis) < -pm(st, HB_BELOW)) continue;
            if (other >= 0 && dist3(p, cell_p(t, other)) < pm(st, HF_OTHER)) continue;
            if (f->head >= 0 && dist3(p, f->head_c) < pm(st, HF_HEAD)) continue;
            n++;
            /* the nearest the camera, not the farthest from the shoulder:
             * a fist pointing at the camera is the forearm's nearest part,
             * and the chest's front can be farther from the shoulder */
            if (t->z[i] < best_z) best_z = t->z[i], best = i;
        }
    /* a fist lies out along its own arm, not back across the body */
    if (n < HB_CELLS && (pe.z <= HB_CELLS_MM || n * pe.z / HB_CELLS_MM * pe.z < HB_CELLS * HB_CELLS_MM)) return -1;
    trk_p3 pb = cell_p(t, best);
    int32_t l = (side ? -1 : 1) * trk_along(pb.x - sc.x, pb.y - sc.y, pb.z - sc.z, lft);
    /* hands clasped before the belly in a bow lie a little nearer the
     * other shoulder, but on their own side */
    if (dist3(pb, so) < deo && l < 0) return -1;
    return best;
}

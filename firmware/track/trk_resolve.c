/* The resolvers: the special poses the general rules (a leg joins the
 * torso low, the hands' naming cost) get wrong, each a function of one
 * signature (trk_resolver, trk_body.h) that reads the body's frame and
 * corrects the limbs' pick, run in the order of the table below at the
 * stage its entry names. Each has a unit test on a small synthetic pose
 * (tests/track/test_trk_resolvers.c) and its history, with the figures it
 * was kept on, in docs/tracker.md (the section its comment names). */
#include "trk_body.h"

/* per mille of stature */
enum {
    FOOT_ABOVE = 200, /* a leg's tip within an arm's reach and this far above the floor is a hand */
    FOOT_LIFTED = 150, /* legs together: a foot this far above the floor stands on nothing */
    FOOT_BESIDE = 200, /* its cell within this of the hips' middle across the body */
    FOOT_APART = 60,   /* and at least this far from the other foot */
    FOOT_FLOOR = 100,  /* and touching the floor within this */
};

/* the hands' naming's special cases: limits (per mille of stature unless
 * said) and what a candidate found so pays (all but a veto) */
enum {
    HC_GEO = 1500, /* per mille of the arm's reach: no farther along the surface */
    HC_FORE = 220, /* nearer the camera than its shoulder by this: the arm points at it */
    HC_NEAR = 120, /* this near a shoulder: a bump on it (on a bow, across the line of sight) */
    HC_NEAR_COST = 800,
    HC_HEAD = 130, /* this near the head's centre: a bump on the skull */
    HC_HEAD_COST = 400,
    HC_ACROSS = 80,       /* its path leaving the torso this far on the other shoulder's side */
    HC_ACROSS_COST = 400, /* ...is the other arm's */
};

/* an arm hanging against the thigh or the flank (no extremity: its hand
 * is reached across the touching surfaces, a short cut), per mille of
 * stature */
enum {
    HANG_OUT = 90, /* out from the torso's axis by (the hip's side: 106; the arm lies beside it) */
    HANG_DROP = 250, /* the tip at least this far below the shoulder */
    HANG_CELLS = 6,  /* such cells at least (fewer are the hip's bulge or noise) */
};

/* A bow: the head's centre well before the root's surface. Its chest and
 * shoulders stand out before the belly; the later resolvers and the
 * naming read lp->bent (docs/tracker.md section 12). */
static bool bow(const trk_frame *f, limb_pick *lp)
{
    lp->bent = trk_bent(f);
    return lp->bent;
}

/* A foot raised within an arm's reach, well above the floor, is a hand:
 * a leg's class came from where its path joins the torso, and a hand
 * hanging against the hip joins it low too (section 11). Each arm's
 * reach as learnt (bodies differ), not shorter than the proportions'. */
static bool raised_foot_is_hand(const trk_frame *f, limb_pick *lp)
{
    const cub_tracker *t = f->t;
    int32_t st = f->st;
    bool changed = false;
    if (f->reach_mm <= 0 || !t->have_floor) return false;
    for (int32_t k = 0; k < lp->ncand; k++) {
        if (lp->limb[k] != TRK_LEG) continue;
        trk_p3 p = cell_p(t, lp->cand[k]);
        bool in_reach = false;
        for (int side = 0; side < 2; side++) {
            int32_t arm = t->reach_mm[side] + pm(st, P_HAND_REACH);
            if (arm < f->reach_mm) arm = f->reach_mm;
            if (dist3(p, f->arm_root[side]) < arm) in_reach = true;
        }
        int32_t above = trk_along(p.x, p.y, p.z, t->up) - t->floor_h_mm;
        if (in_reach && above > pm(st, FOOT_ABOVE)) lp->limb[k] = TRK_ARM, changed = true;
    }
    return changed;
}

/* A knee is no hand: a knee raised aside stands out like a hand within
 * reach, but the named foot's path runs through it, and a bent knee's tip
 * stands a thigh's thickness off that path, near the knee (section 11). */
static bool knee_is_no_hand(const trk_frame *f, limb_pick *lp)
{
    bool changed = false;
    for (int32_t k = 0; k < lp->ncand; k++)
        if (lp->limb[k] == TRK_ARM && trk_on_leg(f, lp, lp->cand[k]))
            lp->limb[k] = TRK_NEITHER, changed = true;
    return changed;
}

/* An arm is no longer than its reach along the surface either: a knee or
 * a hip bulge within reach in a straight line is not reached along the
 * arm (its path runs down the torso), and is no hand. But an arm pointing
 * at the camera is foreshortened into depth steps that the surface runs
 * round: there the straight line counts (section 8, round 7). */
static bool surface_reach(const trk_frame *f, limb_pick *lp)
{
    bool changed = false;
    int32_t lim = f->reach_mm * HC_GEO / 1000;
    for (int side = 0; side < 2; side++)
        for (int32_t k = 0; k < lp->nm.n; k++) {
            if (lp->nm.cost[side][k] == INT32_MAX) continue;
            trk_p3 p = cell_p(f->t, lp->nm.cell[k]), sh = f->arm_root[side];
            bool fore = p.z < sh.z - pm(f->st, HC_FORE);
            if ((fore ? dist3(p, sh) : lp->nm.gs[side][k]) <= lim) continue;
            lp->nm.cost[side][k] = INT32_MAX;
            changed = true;
        }
    return changed;
}

/* Adds cost to every candidate (each side) that pred holds for, within
 * that arm's reach; true when any. */
typedef bool (*cand_pred)(const trk_frame *f, const limb_pick *lp, int32_t k, int side);
static bool penalise(const trk_frame *f, limb_pick *lp, cand_pred pred, int32_t cost)
{
    bool changed = false;
    for (int side = 0; side < 2; side++)
        for (int32_t k = 0; k < lp->nm.n; k++) {
            if (lp->nm.cost[side][k] == INT32_MAX || !pred(f, lp, k, side)) continue;
            lp->nm.cost[side][k] += cost;
            changed = true;
        }
    return changed;
}

static bool near_a_shoulder(const trk_frame *f, const limb_pick *lp, int32_t k, int side)
{
    int32_t near = pm(f->st, HC_NEAR);
    return lp->nm.gs[side][k] < near || lp->nm.go[side][k] < near;
}

/* A bump on a shoulder is no hand: a candidate near either shoulder
 * along the surface (section 8). */
static bool shoulder_bump(const trk_frame *f, limb_pick *lp)
{
    return penalise(f, lp, near_a_shoulder, pm(f->st, HC_NEAR_COST));
}

/* A bowed body's shoulder top: a body bent toward the camera shows its
 * shoulders' tops as extremities far from the root, round the bent
 * torso's depth from the arm's root (the surface test misses them), while
 * the hands hang below, hidden or beside the thighs. Such a top lies above
 * the shoulder centre, over a shoulder across the camera's line of sight,
 * and behind the bowed head's centre (a hand called to the mouth stands
 * before it). */
static bool bowed_top(const trk_frame *f, const limb_pick *lp, int32_t k, int side)
{
    trk_p3 p = cell_p(f->t, lp->nm.cell[k]), sc = f->sc;
    if (near_a_shoulder(f, lp, k, side)) return false; /* paid as a bump already */
    if (!lp->bent || p.z <= f->head_c.z ||
        trk_along(p.x - sc.x, p.y - sc.y, p.z - sc.z, f->t->up) <= 0)
        return false;
    for (int s = 0; s < 2; s++)
        if (trk_len(p.x - f->arm_root[s].x, p.y - f->arm_root[s].y, 0) < pm(f->st, HC_NEAR))
            return true;
    return false;
}

/* On a bow, a shoulder's top named a hand pays the shoulder bump's cost;
 * the hanging or before-the-torso resolvers then place the arm (section
 * 12). */
static bool bow_shoulder_top(const trk_frame *f, limb_pick *lp)
{
    return penalise(f, lp, bowed_top, pm(f->st, HC_NEAR_COST));
}

static bool on_the_skull(const trk_frame *f, const limb_pick *lp, int32_t k, int side)
{
    (void)side;
    return f->head >= 0 && dist3(cell_p(f->t, lp->nm.cell[k]), f->head_c) < pm(f->st, HC_HEAD);
}

/* On the head's surface: the skull's side or a bowed head's chin, not a
 * hand (a palm's centre keeps off the head's) (section 8). */
static bool skull_bump(const trk_frame *f, limb_pick *lp)
{
    return penalise(f, lp, on_the_skull, pm(f->st, HC_HEAD_COST));
}

static bool from_across(const trk_frame *f, const limb_pick *lp, int32_t k, int side)
{
    return lp->nm.le[side][k] < -pm(f->st, HC_ACROSS);
}

/* A path from across the body: the naming weighs the side where a
 * candidate's path from the root leaves the torso, but well across the
 * axis that weight is outbid by the surface from the shoulders (a forearm
 * across the body ends nearer the other one): such a candidate is the
 * other arm's (section 8). */
static bool path_from_across(const trk_frame *f, limb_pick *lp)
{
    return penalise(f, lp, from_across, pm(f->st, HC_ACROSS_COST));
}

/* Legs held together make one extremity for two feet: a leg whose tip
 * hangs well above the floor (or that has none) while the body stands on
 * it takes the lowest cell on its side of the hips, away from the other
 * foot, when that cell touches the floor. */
static bool legs_together(const trk_frame *f, limb_pick *lp)
{
    const cub_tracker *t = f->t;
    int32_t st = f->st;
    trk_p3 hc = f->hc;
    bool changed = false;
    if (!f->on_floor || !t->have_floor) return false;
    for (int side = 0; side < 2; side++) {
        int32_t tip = lp->foot[side], other = lp->foot[1 - side];
        if (tip >= 0 &&
            trk_along(t->x[tip], t->y[tip], t->z[tip], t->up) - t->floor_h_mm < pm(st, FOOT_LIFTED))
            continue;
        int32_t best = -1, best_h = INT32_MAX;
        for (int32_t i = 0; i < TRK_CELLS; i++) {
            if (!t->mask[i] || t->dist0[i] == TRK_INF) continue;
            int32_t l =
                TRK_LEFT_SIGN * trk_along(t->x[i] - hc.x, t->y[i] - hc.y, t->z[i] - hc.z, f->lat);
            if ((side == 0) != (l > 0) || trk_abs(l) > pm(st, FOOT_BESIDE)) continue;
            int32_t h = trk_along(t->x[i], t->y[i], t->z[i], t->up);
            if (h >= best_h) continue;
            if (other >= 0 && dist3(cell_p(t, i), cell_p(t, other)) < pm(st, FOOT_APART)) continue;
            best_h = h, best = i;
        }
        if (best >= 0 && best_h - t->floor_h_mm < pm(st, FOOT_FLOOR))
            lp->foot[side] = best, changed = true;
    }
    return changed;
}

/* A hand held before the torso is no extremity (its path ends in the
 * chest): when a side has no hand, or its "hand" lies on the torso's
 * surface (a shoulder bump, the elbow of that arm), the hand is the cell
 * standing out before the torso on that side (trk_hand_in_front: off the
 * face, the other hand and a knee; on a bow, before the tilted torso)
 * (section 9). */
static bool hand_before_torso(const trk_frame *f, limb_pick *lp)
{
    bool changed = false;
    for (int side = 0; side < 2; side++) {
        int32_t h = lp->hand[side];
        if (h >= 0 && !trk_on_torso(f, h)) continue;
        int32_t c = trk_hand_in_front(f, lp, side);
        if (c >= 0) lp->hand[side] = c, changed = true;
    }
    return changed;
}

/* An elbow taken for the hand: a forearm pointing at the camera or
 * raised before the chest leaves its elbow as the arm's extremity; the
 * fist lies beyond it, nearer the camera, or, for a guard's fist by the
 * chin, above it (trk_hand_beyond) (section 10). */
static bool fist_beyond_elbow(const trk_frame *f, limb_pick *lp)
{
    bool changed = false;
    for (int side = 0; side < 2; side++) {
        if (lp->hand[side] < 0) continue;
        int32_t c = trk_hand_beyond(f, lp, side);
        if (c >= 0) lp->elbow[side] = lp->hand[side], lp->hand[side] = c, changed = true;
    }
    return changed;
}

/* The hanging hand's tip on this side: among the player's cells out to
 * the arm's side of the torso's axis beyond the hip, within the arm's
 * reach below its shoulder and off the legs, the farthest from the
 * shoulder (the silhouette's arm beside the thigh ends in the hand); -1
 * when too few cells stand out there. */
static int32_t hang_tip(const trk_frame *f, const limb_pick *lp, int side)
{
    const cub_tracker *t = f->t;
    trk_p3 sh = f->arm_root[side], sc = f->sc;
    cub_vec3 axis = f->axis, lft = f->lft;
    int32_t st = f->st, sgn = side ? -1 : 1, tilt = trk_along(axis.x, axis.y, axis.z, lft);
    int32_t reach = arm_reach_mm(t, side, st) + pm(st, P_HAND_REACH);
    int32_t best = -1, best_d = 0, n = 0;
    for (int32_t i = 0; i < TRK_CELLS; i++) {
        if (!t->mask[i] || t->dist0[i] == TRK_INF) continue;
        trk_p3 p = cell_p(t, i);
        int32_t up = trk_along(p.x - sc.x, p.y - sc.y, p.z - sc.z, axis);
        /* out from the axis (a leaning torso's axis slants sideways) */
        int32_t l = sgn * (trk_along(p.x - sc.x, p.y - sc.y, p.z - sc.z, lft) -
                           (int32_t)(((int64_t)tilt * up) >> 16));
        if (l < pm(st, HANG_OUT) || up > -pm(st, HANG_DROP)) continue;
        int32_t d = dist3(p, sh);
        if (d > reach) continue;
        n++;
        if (d > best_d && !trk_on_leg(f, lp, i)) best_d = d, best = i;
    }
    return n >= HANG_CELLS ? best : -1;
}

/* An arm hanging against the thigh has no extremity (its hand is reached
 * from the thigh, a short cut) and is not before the torso: an arm still
 * without a hand looks for itself beside the hips in the silhouette; the
 * fit then hangs it straight from the shoulder to that tip (section 9). */
static bool hanging_arm(const trk_frame *f, limb_pick *lp)
{
    bool changed = false;
    for (int side = 0; side < 2; side++) {
        lp->hang[side] = lp->hand[side] < 0 ? hang_tip(f, lp, side) : -1;
        changed |= lp->hang[side] >= 0;
    }
    return changed;
}

/* In the order they run; each function above says more, and the section
 * of docs/tracker.md its comment names has the figures it was kept on. */
static const trk_resolver_entry resolvers[] = {
    /* a bow: the chest before the belly, the shoulders' tops as extremities */
    {"bow", TRK_AT_FRAME, bow},
    /* a "leg" ending within an arm's reach high above the floor: a hand */
    {"raised_foot_is_hand", TRK_AT_CLASSIFIED, raised_foot_is_hand},
    /* a knee raised aside or bent toward the camera looks like a hand */
    {"knee_is_no_hand", TRK_AT_FEET, knee_is_no_hand},
    /* out of reach along the surface (a knee, a hip), unless the arm points at the camera */
    {"surface_reach", TRK_AT_COSTED, surface_reach},
    /* a forearm across the body: its path leaves the torso on the other side */
    {"path_from_across", TRK_AT_COSTED, path_from_across},
    /* a bump on a shoulder stands out like a short arm */
    {"shoulder_bump", TRK_AT_COSTED, shoulder_bump},
    /* on a bow, the shoulders' tops are far along the surface, no hands */
    {"bow_shoulder_top", TRK_AT_COSTED, bow_shoulder_top},
    /* the skull's side or a bowed head's chin is no hand */
    {"skull_bump", TRK_AT_COSTED, skull_bump},
    /* legs together: one extremity for two feet */
    {"legs_together", TRK_AT_NAMED, legs_together},
    /* a hand held before the torso: no extremity, but it stands out in depth */
    {"hand_before_torso", TRK_AT_NAMED, hand_before_torso},
    /* a forearm pointing at the camera, or a guard: the elbow ends the arm's path */
    {"fist_beyond_elbow", TRK_AT_NAMED, fist_beyond_elbow},
    /* an arm hanging against the thigh: no extremity, beside the hips */
    {"hanging_arm", TRK_AT_NAMED, hanging_arm},
};

const trk_resolver_entry *trk_resolvers(int32_t *n)
{
    *n = (int32_t)(sizeof resolvers / sizeof *resolvers);
    return resolvers;
}

void trk_resolve(const trk_frame *f, limb_pick *lp, trk_stage stage)
{
    for (size_t k = 0; k < sizeof resolvers / sizeof *resolvers; k++)
        if (resolvers[k].stage == stage) resolvers[k].run(f, lp);
}

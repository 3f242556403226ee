/* The head and the player's size: which extremity is the head (or the
 * top of the body's column when none is), the stature and the neck base,
 * both smoothed over frames as a body does not change size. */
#include "trk_body.h"

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
        int32_t w = (b - a + 1) * TRK_CELL_PX * t->z[i] / CUB_KINECT_FOCAL_PX;
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

/* per mille of stature, or quarters for weights */
enum {
    HEAD_WIDE = 180,    /* no head is wider than this */
    HEAD_W_X = 4,       /* weight of lying aside of the root */
    HEAD_W_UP = 4,      /* weight of standing high above it */
    HEAD_ABOVE = 1120,  /* no head top this high above the floor, standing */
    HEAD_COLUMN = 1040, /* the head top below a hand raised above it */
    HEAD_CLIMB = 200,   /* no farther from the head's middle to its top along the surface */
    HEAD_SKULL_DZ = 50, /* the skull's surface, in depth about the face's */
    HEAD_ARM_OUT = 110, /* a hand's path leads out to its elbow by more than */
};
/* the stature learnt: one frame's measurement moves it by at most a tenth
 * up, a twentieth down (before the quarter taken) */
enum {
    ST_RISE = 10,
    ST_SINK = 20,
};

/* Where a head's middle would be below the extremity tip: mm lower in the
 * image, in the middle of the silhouette's run on that row (the path from
 * the tip may run down the skull's side, and the top curves away in
 * depth); the tip itself when that row is off the player. */
static int32_t below_middle(const cub_tracker *t, int32_t tip, int32_t mm, int32_t max_wide_mm)
{
    int32_t z = t->z[tip] > 0 ? t->z[tip] : 1, gx = tip % TRK_GW;
    int32_t gy = tip / TRK_GW + mm * CUB_KINECT_FOCAL_PX / (z * TRK_CELL_PX);
    if (gy >= TRK_GH) return tip;
    int32_t row = gy * TRK_GW;
    if (!t->mask[row + gx]) return tip;
    int32_t a = gx, b = gx;
    while (a > 0 && t->mask[row + a - 1]) a--;
    while (b < TRK_GW - 1 && t->mask[row + b + 1]) b++;
    /* wider than a head: the skull merges with a forearm or a shoulder
     * there, and the run's middle says nothing */
    if (t->x[row + b] - t->x[row + a] > max_wide_mm) return path_at(t, tip, mm);
    return row + (a + b) / 2;
}

/* Percent of a disk of rho_mm around cell c (in the image plane) that the
 * player's surface fills at about c's depth: a head is round and fills its
 * disk, a raised forearm or hand crosses it as a strip. */
static int32_t disk_fill_pct(const cub_tracker *t, int32_t c, int32_t rho_mm)
{
    int32_t z0 = t->z[c], rc = rho_mm * CUB_KINECT_FOCAL_PX / ((z0 ? z0 : 1) * TRK_CELL_PX);
    if (rc < 1) rc = 1;
    if (rc > 12) rc = 12;
    int32_t gx0 = c % TRK_GW, gy0 = c / TRK_GW, in = 0, all = 0;
    for (int32_t dy = -rc; dy <= rc; dy++)
        for (int32_t dx = -rc; dx <= rc; dx++) {
            if (dx * dx + dy * dy > rc * rc) continue;
            all++;
            int32_t gx = gx0 + dx, gy = gy0 + dy;
            if (!on_grid(gx, gy)) continue;
            int32_t i = gy * TRK_GW + gx;
            if (t->mask[i] && trk_abs(t->z[i] - z0) < 2 * rho_mm) in++;
        }
    return in * 100 / all;
}

/* The top of the skull under a hand laid on the head: up the column from
 * the head's middle while the surface stays at the face's depth (the hand
 * on top lies deeper or nearer). */
static int32_t skull_top(const cub_tracker *t, int32_t middle, int32_t depth_mm)
{
    int32_t top = middle, z0 = t->z[middle];
    for (int32_t i = middle - TRK_GW; i >= 0 && t->mask[i] && trk_abs(t->z[i] - z0) < depth_mm; i -= TRK_GW)
        top = i;
    return top;
}

/* How far aside (in x) of the tip its path from the root runs within its
 * first len_mm: a hand laid on the head is reached from its elbow, out to
 * the side; a head from the neck, below it. */
static int32_t path_aside_mm(const cub_tracker *t, int32_t tip, int32_t len_mm)
{
    int32_t out = 0, end = t->dist0[tip] - len_mm;
    for (int32_t i = tip, steps = 0; i >= 0 && t->dist0[i] > end && steps < 400; i = t->parent0[i], steps++)
        if (trk_abs(t->x[i] - t->x[tip]) > out) out = trk_abs(t->x[i] - t->x[tip]);
    return out;
}

/* A head candidate's cost (lower is better) and roundness. */
static int32_t head_cost(const cub_tracker *t, trk_p3 r, int32_t c, int32_t middle, int32_t st0, bool *round)
{
    trk_p3 p = cell_p(t, c);
    int32_t dh = p.y - r.y; /* image-up: the head is found before the up vector matters */
    /* central, not in front of the torso, far out along the surface
     * (a head stands out by neck and skull, a shoulder bump does not),
     * and round (a raised hand beside the head is a strip) */
    /* and high: a bump on a shoulder stands lower than a head leaning
     * aside, which lies as far aside of the root as that shoulder */
    int32_t cost = HEAD_W_X * trk_abs(p.x - r.x) / 4 - HEAD_W_UP * dh / 4 +
                   2 * (r.z - p.z > 100 ? r.z - p.z - 100 : 0) - t->dist0[c];
    /* (an arm held out level fills a far, coarse disk too, but it
     * reaches out more than up) */
    *round = disk_fill_pct(t, middle, pm(st0, 60)) >= 75 && trk_abs(p.x - r.x) < dh;
    if (!*round) cost += 600;
    /* last frame's head helps, but a wrong one must not hold on */
    if (t->have_prev && t->lost_frames == 0) {
        int32_t d = dist3(p, got(&t->prev, CUB_KJ_HEAD));
        cost += d < 300 ? d : 300;
    }
    return cost;
}

/* The head: above the root, central, not a hand held in front; the nearer
 * to last frame's head the better. Returns the head's cell: an extremity,
 * or the skull's top under a hand laid on the head (no extremity: the hand
 * covers it). */
static int32_t pick_head(const cub_tracker *t, int32_t root, const int32_t *ext, int32_t n, int32_t st0,
                         bool *is_round)
{
    *is_round = false;
    int32_t min_geo_mm = pm(st0, 220);
    trk_p3 r = cell_p(t, root);
    int32_t best = -1, best_cost = INT32_MAX;
    for (int32_t k = 0; k < n; k++) {
        trk_p3 p = cell_p(t, ext[k]);
        if (trk_along(p.x - r.x, p.y - r.y, p.z - r.z, t->up) < 100 && p.y - r.y < 100) continue;
        /* a head sticks out of the torso by its neck and itself; a shallow
         * bump (a shoulder between arms held down) is no head */
        if (t->dist0[ext[k]] < min_geo_mm) continue;
        int32_t c = ext[k];
        int32_t middle = below_middle(t, c, pm(st0, P_HEAD_DOWN), pm(st0, HEAD_WIDE));
        /* the neck leads straight up into the skull; a hand laid on top of
         * the head is reached round by its arm, far along the surface from
         * the skull below it: the head is that skull */
        if (t->dist0[middle] != TRK_INF && t->dist0[c] - t->dist0[middle] > pm(st0, HEAD_CLIMB) &&
            path_aside_mm(t, c, pm(st0, HEAD_CLIMB)) > pm(st0, HEAD_ARM_OUT)) {
            int32_t top = skull_top(t, middle, pm(st0, HEAD_SKULL_DZ));
            /* (under the hand, not up a forearm raised before the face) */
            if (t->y[top] < t->y[c]) {
                c = top;
                middle = below_middle(t, c, pm(st0, P_HEAD_DOWN), pm(st0, HEAD_WIDE));
            }
        }
        bool round;
        int32_t cost = head_cost(t, r, c, middle, st0, &round);
        if (cost < best_cost) best_cost = cost, best = c, *is_round = round;
    }
    return best;
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

/* The index in ext of the head's cell: the (last) extremity that is that
 * cell or lies within near_mm of it, else the cell added to the list, in
 * place of the nearest extremity when the list is full. */
static int32_t as_extremity(const cub_tracker *t, int32_t *ext, int32_t *n, int32_t cell, int32_t near_mm)
{
    int32_t found = -1;
    for (int32_t k = 0; k < *n; k++)
        if (ext[k] == cell || dist3(cell_p(t, ext[k]), cell_p(t, cell)) < near_mm) found = k;
    if (found >= 0) return found;
    if (*n == TRK_MAX_EXTREMA) (*n)--;
    ext[*n] = cell;
    return (*n)++;
}

int32_t trk_fit_head(cub_tracker *t, int32_t root, int32_t *ext, int32_t *next, bool *on_floor_out)
{
    int32_t st0 = t->stature_mm ? t->stature_mm : 1200;
    bool round;
    int32_t n = *next;
    int32_t hmin = INT32_MAX;
    for (int32_t i = 0; i < TRK_CELLS; i++)
        if (t->mask[i]) {
            int32_t h = trk_along(t->x[i], t->y[i], t->z[i], t->up);
            if (h < hmin) hmin = h;
        }
    bool on_floor = t->have_floor && hmin - t->floor_h_mm < 120;
    int32_t head_c = pick_head(t, root, ext, n, st0, &round);
    /* (the skull under a hand laid on the head is no extremity yet) */
    int32_t head_k = head_c >= 0 ? as_extremity(t, ext, &n, head_c, 0) : -1;
    /* standing, no head top is far above the stature learnt: that is a
     * hand raised right above the head (a fist is round too) */
    int32_t rise = pm(st0, 450);
    if (head_k >= 0 && on_floor && t->stature_mm) {
        int32_t top = trk_along(t->x[ext[head_k]], t->y[ext[head_k]], t->z[ext[head_k]], t->up) - t->floor_h_mm;
        int32_t hr = trk_along(t->x[root], t->y[root], t->z[root], t->up) - t->floor_h_mm;
        if (top > pm(st0, HEAD_ABOVE)) round = false, rise = pm(st0, HEAD_COLUMN) - hr;
    }
    if (head_k < 0 || (!round && trk_abs(t->x[ext[head_k]] - t->x[root]) > pm(st0, 90)) || rise < pm(st0, 450)) {
        /* no round, central extremity: the head is the column's top (a
         * head leaning aside is round, hands up beside it are not) */
        int32_t top = column_top(t, root, rise);
        if (top >= 0) head_k = as_extremity(t, ext, &n, top, pm(st0, 100));
    }
    int32_t head = head_k >= 0 ? ext[head_k] : root;
    int32_t neck = 0;
    int32_t st = head_k >= 0 ? measure_stature(t, head, on_floor, &neck) : 0;
    /* a neck base far from where the body's proportions put it is an arm
     * or a leaning head widening the silhouette, not the shoulders */
    if (neck >= pm(st0, 100) && neck <= pm(st0, 250)) {
        int32_t cur = t->neck_drop_mm; /* arms beside the head fool one frame */
        if (cur && neck > cur + cur / 8) neck = cur + cur / 8;
        if (cur && neck < cur - cur / 8) neck = cur - cur / 8;
        t->neck_drop_mm = cur ? cur + (neck - cur) / 4 : neck;
    }
    t->head_cell = head_k >= 0 ? head : -1;
    t->stature_seen_mm = st;
    if (st >= 700 && st <= 2100) {
        /* a body does not change size: once known, one odd measurement
         * (a raised hand beside the head) moves it by 10 % at most; a
         * body bending or crouching lowers its head top for many frames
         * (a dancer bent double for a second), but does not shrink: down,
         * half that */
        int32_t cur = t->stature_mm;
        if (cur && st > cur + cur / ST_RISE) st = cur + cur / ST_RISE;
        if (cur && st < cur - cur / ST_SINK) st = cur - cur / ST_SINK;
        t->stature_mm = cur ? cur + (st - cur) / 4 : st;
    }
    if (!t->stature_mm) t->stature_mm = 1200;
    *next = n;
    *on_floor_out = on_floor;
    return head_k;
}

/* The tracker's first stages on the 160x120 grid: depth per cell, the
 * floor, connected blobs, and which blob is the player. */
#include "depth_table.h"
#include "trk_internal.h"
#include "trk_body.h"

int32_t trk_len(int32_t dx, int32_t dy, int32_t dz)
{
    uint64_t s = (uint64_t)((int64_t)dx * dx) + (uint64_t)((int64_t)dy * dy) + (uint64_t)((int64_t)dz * dz);
    return (int32_t)cub_fx_isqrt64(s);
}

/* A cell's depth: the nearest valid of four samples inside it. Nearest,
 * not mean, so thin limbs in front of a farther surface keep their depth
 * instead of blending into a phantom in between. */
void trk_grid_fill(cub_tracker *t, const uint16_t *raw)
{
    static const uint8_t off[4][2] = {{1, 1}, {3, 3}, {1, 3}, {3, 1}};
    for (int32_t gy = 0; gy < TRK_GH; gy++) {
        for (int32_t gx = 0; gx < TRK_GW; gx++) {
            int32_t best = 0;
            for (int k = 0; k < 4; k++) {
                int32_t u = gx * TRK_CELL_PX + off[k][0], v = gy * TRK_CELL_PX + off[k][1];
                int32_t mm = trk_raw_mm(raw[v * CUB_KINECT_WIDTH + u]);
                if (mm >= t->min_mm && mm <= t->max_mm && (best == 0 || mm < best)) best = mm;
            }
            int32_t i = gy * TRK_GW + gx;
            t->z[i] = (int16_t)best;
            t->x[i] = (gx * TRK_CELL_PX + 2 - CUB_KINECT_CX) * best / CUB_KINECT_FOCAL_PX;
            t->y[i] = (CUB_KINECT_CY - gy * TRK_CELL_PX - 2) * best / CUB_KINECT_FOCAL_PX;
        }
    }
}

/* Height histogram peak along up: the floor is the lowest height that many
 * cells in the lower image share. Returns the count, *h_mm the height. */
#define FLOOR_BIN_MM 25
#define FLOOR_BINS 200 /* heights -4000 .. +1000 mm */
#define FLOOR_MIN_CELLS 200
/* The lower image's readings the floor is looked for in (every other cell,
 * about), into low_x/y/z; their count. */
static int32_t gather_low(cub_tracker *t)
{
    int32_t n = 0;
    for (int32_t i = TRK_CELLS / 2; i < TRK_CELLS && n < TRK_LOW_CELLS; i += 1 + (i & 1)) {
        if (!t->z[i]) continue;
        t->low_x[n] = (int16_t)t->x[i], t->low_y[n] = (int16_t)t->y[i], t->low_z[n] = t->z[i];
        n++;
    }
    return n;
}

static int32_t low_along(const cub_tracker *t, int32_t k, cub_vec3 up)
{
    return trk_along(t->low_x[k], t->low_y[k], t->low_z[k], up);
}

/* Over the n cells gather_low took. */
static int32_t floor_peak(const cub_tracker *t, int32_t n, cub_vec3 up, int32_t *h_mm)
{
    int32_t hist[FLOOR_BINS], total = n;
    memset(hist, 0, sizeof hist);
    for (int32_t k = 0; k < n; k++) {
        int32_t b = (low_along(t, k, up) + 4000) / FLOOR_BIN_MM;
        if (b >= 0 && b < FLOOR_BINS) hist[b]++;
    }
    for (int32_t b = 0; b + 1 < FLOOR_BINS; b++) {
        int32_t c = hist[b] + hist[b + 1];
        /* dense: a real floor holds a good share of the lower image */
        if (c < FLOOR_MIN_CELLS / 2 || c * 8 < total) continue;
        int32_t best = hist[b + 1] > hist[b] ? b + 1 : b;
        *h_mm = best * FLOOR_BIN_MM - 4000 + FLOOR_BIN_MM / 2;
        /* and a floor recedes: its cells span depth, unlike the cut-off
         * bottom of a body standing close */
        int32_t zmin = INT32_MAX, zmax = 0;
        for (int32_t k = 0; k < n; k++) {
            int32_t h = low_along(t, k, up), z = t->low_z[k];
            if (h < *h_mm - FLOOR_BIN_MM || h > *h_mm + FLOOR_BIN_MM) continue;
            if (z < zmin) zmin = z;
            if (z > zmax) zmax = z;
        }
        if (zmax - zmin < 700) return 0;
        /* continuously: no depth gaps (two bodies' cut-off bottoms are not a floor) */
        uint64_t slices = 0;
        for (int32_t k = 0; k < n; k++) {
            int32_t h = low_along(t, k, up), z = t->low_z[k];
            if (h >= *h_mm - FLOOR_BIN_MM && h <= *h_mm + FLOOR_BIN_MM && (z - zmin) / 100 < 64)
                slices |= (uint64_t)1 << ((z - zmin) / 100);
        }
        int32_t span = (zmax - zmin) / 100 + 1, filled = 0;
        for (int32_t k = 0; k < span && k < 64; k++) filled += (int32_t)((slices >> k) & 1);
        if (filled * 10 < (span < 64 ? span : 64) * 7) return 0;
        return c + (best + 1 < FLOOR_BINS ? hist[best + 1] : 0);
    }
    return 0;
}

static cub_vec3 unit_q16(cub_vec3 v)
{
    int64_t l = cub_fx_isqrt64((uint64_t)((int64_t)v.x * v.x + (int64_t)v.y * v.y + (int64_t)v.z * v.z));
    if (l == 0) return (cub_vec3){0, CUB_Q16_ONE, 0};
    return (cub_vec3){(int32_t)((int64_t)v.x * 65536 / l), (int32_t)((int64_t)v.y * 65536 / l),
                      (int32_t)((int64_t)v.z * 65536 / l)};
}

/* With gravity, up is known and only the floor's height is searched. Without
 * it the camera's pitch is searched too (roll assumed small), every 8th
 * frame: the pitch whose histogram has the densest low layer wins. */
void trk_floor_update(cub_tracker *t, const cub_vec3 *gravity_mm)
{
    int32_t h = 0;
    if (gravity_mm && (gravity_mm->x || gravity_mm->y || gravity_mm->z)) {
        /* scale down so the squares fit in 64 bits whatever the length */
        cub_vec3 g = *gravity_mm;
        while (trk_abs(g.x) > (1 << 24) || trk_abs(g.y) > (1 << 24) || trk_abs(g.z) > (1 << 24))
            g.x /= 2, g.y /= 2, g.z /= 2;
        t->up = unit_q16((cub_vec3){-g.x, -g.y, -g.z});
        t->have_floor = floor_peak(t, gather_low(t), t->up, &h) >= FLOOR_MIN_CELLS;
        if (t->have_floor) t->floor_h_mm = h;
        return;
    }
    if (t->have_floor && (t->frame_no & 7) && t->lost_frames == 0) return;
    int32_t best = 0, best_h = 0, best_p = TRK_PITCHES / 2, n = gather_low(t);
    for (int32_t p = 0; p < TRK_PITCHES; p++) {
        int32_t c = floor_peak(t, n, t->pitch_up[p], &h);
        if (c > best) best = c, best_h = h, best_p = p;
    }
    if (best >= FLOOR_MIN_CELLS) {
        t->up = t->pitch_up[best_p];
        t->floor_h_mm = best_h;
        t->have_floor = true;
    } else if (!t->have_floor) {
        t->up = t->pitch_up[TRK_PITCHES / 2];
    }
}

/* Floor cells (and anything under it) go; feet keep what is 40 mm up. */
void trk_floor_remove(cub_tracker *t)
{
    if (!t->have_floor) return;
    int32_t cut = t->floor_h_mm + 40;
    for (int32_t i = 0; i < TRK_CELLS; i++)
        if (t->z[i] && trk_along(t->x[i], t->y[i], t->z[i], t->up) < cut) t->z[i] = 0;
}

/* Neighbours belong together when their depths differ by less than this:
 * the disparity step (and a slanted surface's step) grows with depth. */
static int32_t joins_mm(int32_t z) { return 40 + z / 20; }

static void comp_add(cub_tracker *t, trk_comp *c, int32_t i)
{
    int32_t gx = i % TRK_GW, gy = i / TRK_GW, z = t->z[i];
    int32_t h = trk_along(t->x[i], t->y[i], z, t->up);
    c->n++;
    c->sx += t->x[i], c->sy += t->y[i], c->sz += z;
    c->area_mm2 += (int64_t)z * z * (TRK_CELL_PX * TRK_CELL_PX) / (CUB_KINECT_FOCAL_PX * CUB_KINECT_FOCAL_PX);
    if (h < c->hmin) c->hmin = h;
    if (h > c->hmax) c->hmax = h;
    if (t->x[i] < c->xmin) c->xmin = t->x[i];
    if (t->x[i] > c->xmax) c->xmax = t->x[i];
    if (gx < c->gx0) c->gx0 = gx;
    if (gx > c->gx1) c->gx1 = gx;
    if (gy < c->gy0) c->gy0 = gy;
    if (gy > c->gy1) c->gy1 = gy;
    if (gx == 0 || gy == 0 || gx == TRK_GW - 1 || gy == TRK_GH - 1) c->border++;
}

static trk_comp comp_empty(void)
{
    return (trk_comp){.hmin = INT32_MAX, .hmax = INT32_MIN, .xmin = INT32_MAX, .xmax = INT32_MIN,
                      .gx0 = TRK_GW, .gx1 = -1, .gy0 = TRK_GH, .gy1 = -1};
}

/* Cell i's 4-neighbours on the grid, -1 past its edges. */
static void neighbours4(int32_t i, int32_t nb[4])
{
    int32_t gx = i % TRK_GW, gy = i / TRK_GW;
    nb[0] = gx > 0 ? i - 1 : -1;
    nb[1] = gx < TRK_GW - 1 ? i + 1 : -1;
    nb[2] = gy > 0 ? i - TRK_GW : -1;
    nb[3] = gy < TRK_GH - 1 ? i + TRK_GW : -1;
}

/* Every blob's cells whose 4 neighbours are all in it. */
static void count_interior(cub_tracker *t)
{
    for (int32_t k = 0; k < t->ncomps; k++) t->comps[k].interior = 0;
    for (int32_t gy = 1; gy < TRK_GH - 1; gy++)
        for (int32_t i = gy * TRK_GW + 1; i < gy * TRK_GW + TRK_GW - 1; i++) {
            int16_t l = t->label[i];
            if (l >= 0 && t->label[i - 1] == l && t->label[i + 1] == l && t->label[i - TRK_GW] == l &&
                t->label[i + TRK_GW] == l)
                t->comps[l].interior++;
        }
}

/* Flood fill with 4-neighbours; blobs past TRK_MAX_COMPS stay unlabelled. */
void trk_components(cub_tracker *t)
{
    for (int32_t i = 0; i < TRK_CELLS; i++) t->label[i] = -1;
    t->ncomps = 0;
    for (int32_t s = 0; s < TRK_CELLS && t->ncomps < TRK_MAX_COMPS; s++) {
        if (!t->z[s] || t->label[s] >= 0) continue;
        int16_t id = (int16_t)t->ncomps++;
        trk_comp *c = &t->comps[id];
        *c = comp_empty();
        int32_t top = 0;
        t->stack[top++] = s;
        t->label[s] = id;
        while (top) {
            int32_t i = t->stack[--top];
            comp_add(t, c, i);
            int32_t j = joins_mm(t->z[i]), nb[4];
            neighbours4(i, nb);
            for (int k = 0; k < 4; k++) {
                int32_t n = nb[k];
                if (n < 0 || !t->z[n] || t->label[n] >= 0) continue;
                if (trk_abs(t->z[n] - t->z[i]) > j) continue;
                t->label[n] = id;
                t->stack[top++] = n;
            }
        }
    }
    count_interior(t);
}

/* A person-like blob: big enough, solid (noise makes sparse, stringy
 * blobs), upright extent of a body (or the upper part of one), not as wide
 * as a wall. */
static bool person_like(const trk_comp *c)
{
    return c->n >= 40 && c->interior * 10 >= c->n * 4 && c->area_mm2 >= 40000 && c->hmax - c->hmin >= 350 && c->hmax - c->hmin <= 2300 &&
           c->xmax - c->xmin <= 2200;
}

static trk_p3 comp_centre(const trk_comp *c)
{
    return (trk_p3){(int32_t)(c->sx / c->n), (int32_t)(c->sy / c->n), (int32_t)(c->sz / c->n)};
}

static bool was_someone_else(const cub_tracker *t, int32_t k);

/* A forearm held across the whole width of a (turned) torso cuts the
 * body in two blobs by depth: a smaller blob at about the player's depth
 * that touches it or a part merged in front of it, within the player's
 * columns (give or take half its width), is the rest of the body; not a
 * blob that was someone else last frame (the adult just behind the child,
 * split from it this frame by split_merged: taken back as the child's,
 * the next frame had nobody else to split, and the adult's top and torso
 * drew the track away). */
#define CUT_OFF_DZ_MM 300
static void merge_cut_off(cub_tracker *t, int32_t pid, int32_t pz, const uint8_t *front)
{
    uint8_t touch[TRK_MAX_COMPS] = {0};
    const trk_comp *p = &t->comps[pid];
    int32_t pw = p->gx1 - p->gx0 + 1;
    for (int32_t gy = 1; gy < TRK_GH - 1; gy++)
        for (int32_t i = gy * TRK_GW + 1; i < gy * TRK_GW + TRK_GW - 1; i++) {
            int16_t l = t->label[i];
            if (l < 0 || (l != pid && !front[l])) continue;
            const int32_t nb[4] = {i - 1, i + 1, i - TRK_GW, i + TRK_GW};
            for (int k = 0; k < 4; k++)
                if (t->label[nb[k]] >= 0) touch[t->label[nb[k]]] = 1;
        }
    for (int32_t k = 0; k < t->ncomps; k++) {
        const trk_comp *c = &t->comps[k];
        if (k == pid || front[k] || !touch[k] || c->n < 3) continue;
        if (trk_abs((int32_t)(c->sz / c->n) - pz) > CUT_OFF_DZ_MM || c->n > p->n) continue;
        if (was_someone_else(t, k)) continue;
        /* within the player's columns: not furniture beside it */
        if (c->gx0 < p->gx0 - pw / 2 || c->gx1 > p->gx1 + pw / 2) continue;
        for (int32_t i = 0; i < TRK_CELLS; i++)
            if (t->label[i] == k) t->mask[i] = 1;
    }
}

/* A piece next to someone who stands before the player (its box within
 * 2 cells of that person's), at that person's depth, is that person's:
 * a crosser's arm reaching past the child, the crosser's body cut by its
 * own arm, not the child's hand. */
#define ID_FRONT_MM 350   /* a blob this much nearer than the player (or its prediction) is someone in front */
#define OTHERS_PART_DZ 300 /* a piece this near in depth to someone in front is theirs */
static bool part_of_someone_in_front(const cub_tracker *t, int32_t pid, int32_t pz, const trk_comp *c)
{
    int32_t cz = (int32_t)(c->sz / c->n);
    for (int32_t k = 0; k < t->ncomps; k++) {
        const trk_comp *o = &t->comps[k];
        if (k == pid || o == c || !person_like(o)) continue;
        int32_t oz = (int32_t)(o->sz / o->n);
        if (oz >= pz - ID_FRONT_MM || trk_abs(cz - oz) > OTHERS_PART_DZ) continue;
        if (c->gx1 < o->gx0 - 2 || c->gx0 > o->gx1 + 2 || c->gy1 < o->gy0 - 2 || c->gy0 > o->gy1 + 2) continue;
        return true;
    }
    return false;
}

/* A piece belongs to the body it joins with the smaller depth step: blob
 * k touches (4-neighbours in the image) someone else (a person-like blob
 * not the player's pid, or a piece of someone in front) with a step of
 * at most JOIN_OTHER_MM and smaller than any step to pid. A limb is
 * continuous in depth with its own body and only overlaps the others':
 * the arm a crosser swings back toward the hidden child (270 mm behind
 * the crosser's chest, 420 mm before the child) is the crosser's, not a
 * hand before the child's chest. */
#define JOIN_OTHER_MM 250
static bool joins_someone_else(const cub_tracker *t, int32_t pid, int32_t pz, int32_t k)
{
    int32_t step[TRK_MAX_COMPS];
    for (int32_t l = 0; l < t->ncomps; l++) step[l] = INT32_MAX;
    for (int32_t gy = 1; gy < TRK_GH - 1; gy++)
        for (int32_t i = gy * TRK_GW + 1; i < gy * TRK_GW + TRK_GW - 1; i++) {
            if (t->label[i] != k) continue;
            const int32_t nb[4] = {i - 1, i + 1, i - TRK_GW, i + TRK_GW};
            for (int n = 0; n < 4; n++) {
                int16_t l = t->label[nb[n]];
                int32_t d = trk_abs(t->z[i] - t->z[nb[n]]);
                if (l >= 0 && l != k && d < step[l]) step[l] = d;
            }
        }
    int32_t mine = pid >= 0 ? step[pid] : INT32_MAX;
    for (int32_t l = 0; l < t->ncomps; l++)
        if (l != pid && step[l] <= JOIN_OTHER_MM && step[l] < mine &&
            (person_like(&t->comps[l]) || part_of_someone_in_front(t, pid, pz, &t->comps[l])))
            return true;
    return false;
}

/* How far before the player's blob its own hand may be: an arm's length
 * (shoulder to fingertip, of the stature learnt) and the body's half
 * depth; 900 mm before a stature is known. A piece farther before it is
 * not the player's: the hand of someone crossing close before the hidden
 * child (830 mm before it) was merged as the child's and drew its torso
 * to the crosser. */
#define FRONT_MAX_MM 900
#define FRONT_BODY_MM 100
static int32_t front_reach_mm(const cub_tracker *t)
{
    int32_t r = pm(t->stature_mm, P_UPPER_ARM + P_FOREARM + P_HAND_REACH) + FRONT_BODY_MM;
    return t->stature_mm > 0 && r < FRONT_MAX_MM ? r : FRONT_MAX_MM;
}

/* Small blobs in front of the player and overlapping it in the image are
 * its own hands and forearms (a hand before the chest is a depth jump),
 * unless they are someone else's who stands in front. */
static void merge_front_parts(cub_tracker *t, int32_t pid)
{
    const trk_comp *p = &t->comps[pid];
    int32_t pz = (int32_t)(p->sz / p->n);
    trk_p3 pc = comp_centre(p);
    uint8_t front[TRK_MAX_COMPS] = {0};
    for (int32_t k = 0; k < t->ncomps; k++) {
        const trk_comp *c = &t->comps[k];
        if (k == pid || c->n < 3 || c->area_mm2 > 80000) continue;
        if (c->gx1 < p->gx0 - 2 || c->gx0 > p->gx1 + 2 || c->gy1 < p->gy0 - 2 || c->gy0 > p->gy1 + 2) continue;
        trk_p3 cc = comp_centre(c);
        if (cc.z > pz + 100 || cc.z < pz - front_reach_mm(t) || trk_abs(cc.x - pc.x) > 1000) continue;
        if (part_of_someone_in_front(t, pid, pz, c) || joins_someone_else(t, pid, pz, k)) continue;
        front[k] = 1;
        for (int32_t i = 0; i < TRK_CELLS; i++)
            if (t->label[i] == k) t->mask[i] = 1;
    }
    merge_cut_off(t, pid, pz, front);
}

/* A blob holding both last frame's player and last frame's other person
 * (a sibling's hand touching the child's, a parent beside it at the same
 * depth) is two bodies joined: each cell goes to the side whose last
 * frame's cells it is fewer 4-neighbour steps from, and the other side
 * becomes a blob of its own. Else the joined blob, its centre near the
 * player's, is taken whole and the adult's limbs become the child's. */
#define SPLIT_MIN_CELLS 20 /* cells of each side last frame before a blob is split */
/* Blob id's sums and bounds again from its cells (interior apart). */
static void refill_comp(cub_tracker *t, int16_t id)
{
    trk_comp *c = &t->comps[id];
    *c = comp_empty();
    for (int32_t i = 0; i < TRK_CELLS; i++)
        if (t->label[i] == id) comp_add(t, c, i);
}

/* Multi-source breadth-first fill within blob k and its depth joins from
 * the cells of k whose side (t->mask) the caller set. */
static void grow_sides(cub_tracker *t, int16_t k)
{
    int32_t head = 0, tail = 0;
    for (int32_t i = 0; i < TRK_CELLS; i++)
        if (t->label[i] == k && t->mask[i]) t->stack[tail++] = i;
    while (head < tail) {
        int32_t i = t->stack[head++];
        int32_t j = joins_mm(t->z[i]), nb[4];
        neighbours4(i, nb);
        for (int n = 0; n < 4; n++) {
            int32_t c = nb[n];
            if (c < 0 || t->label[c] != k || t->mask[c] || trk_abs(t->z[c] - t->z[i]) > j) continue;
            t->mask[c] = t->mask[i];
            t->stack[tail++] = c;
        }
    }
}

/* Blob k's cells of side 2 (t->mask) become a blob of their own. */
static void split_off(cub_tracker *t, int16_t k)
{
    int16_t id = (int16_t)t->ncomps++;
    for (int32_t i = 0; i < TRK_CELLS; i++)
        if (t->label[i] == k && t->mask[i] == 2) t->label[i] = id;
    refill_comp(t, k);
    refill_comp(t, id);
    count_interior(t);
}

#define ID_MAX_SPEED 2500 /* mm/s: a child's run; faster is a wrong centre, not motion */
static int32_t per_s(int32_t v, int32_t us) { return (int32_t)((int64_t)v * us / 1000000); }

/* Where a body at p moving at vel (mm/s) is us later. */
static trk_p3 moved_on(trk_p3 p, trk_p3 vel, int32_t us)
{
    return (trk_p3){p.x + per_s(vel.x, us), p.y + per_s(vel.y, us), p.z + per_s(vel.z, us)};
}

/* How a body at p moving at vel moves on the grid this frame: cells
 * across (gx, gy) and depth (dz, mm). */
typedef struct trk_shift {
    int32_t gx, gy, dz;
} trk_shift;
static trk_shift shift_of(const cub_tracker *t, trk_p3 p, trk_p3 vel)
{
    trk_p3 q = moved_on(p, vel, t->dt_us);
    if (p.z <= 0 || q.z <= 0) return (trk_shift){0, 0, 0};
    int32_t gx0, gy0, gx1, gy1;
    grid_of(p, &gx0, &gy0);
    grid_of(q, &gx1, &gy1);
    return (trk_shift){gx1 - gx0, gy1 - gy0, q.z - p.z};
}

/* Last frame's cell that moved by s onto cell i was `who` (of blob
 * `label` unless -1), and lands on cell i's surface: its depth moved on
 * is not SEED_DZ_MM before cell i's (the adult 300 mm behind the child is
 * not the child's arm that moved away from before it), nor, moved at
 * all, SEED_DZ_MM behind it (nor the child's chest the adult's motion
 * carried its cells onto). A cell now nearer than last frame, unmoved,
 * may be the same body (a hand come forward). */
#define SEED_DZ_MM 150
static bool came_from(const cub_tracker *t, int32_t i, trk_shift s, uint8_t who, int16_t label)
{
    int32_t gx = i % TRK_GW - s.gx, gy = i / TRK_GW - s.gy;
    if (!on_grid(gx, gy)) return false;
    int32_t j = gy * TRK_GW + gx;
    if (t->who_prev[j] != who || (label >= 0 && t->label_prev[j] != label)) return false;
    int32_t dz = t->z[i] - t->z_prev[j] - s.dz;
    return dz <= SEED_DZ_MM && ((!s.gx && !s.gy) || dz >= -SEED_DZ_MM);
}

/* Cell i's side when a blob holds two people: the player's if last
 * frame's player cells, moved on by the player's motion, cover it; the
 * other's if the other person nearest the player (moved on by its motion)
 * or anybody else (where they stood) covers it; neither if both or none.
 * A crosser at the child's depth moves 10 cells a frame: where it stood
 * last frame is the child's now, where it went is not. */
static uint8_t side_of(const cub_tracker *t, int32_t i, trk_shift sp, trk_shift so)
{
    static const trk_shift still = {0, 0, 0};
    bool mine = came_from(t, i, sp, TRK_WHO_PLAYER, -1);
    bool other = t->other_label >= 0 && came_from(t, i, so, TRK_WHO_OTHER, t->other_label);
    if (!other && came_from(t, i, still, TRK_WHO_OTHER, -1)) other = t->label_prev[i] != t->other_label;
    return mine && !other ? TRK_WHO_PLAYER : other && !mine ? TRK_WHO_OTHER : 0;
}

/* A blob with SPLIT_MIN_CELLS of the player's predicted cells and
 * SPLIT_MIN_PIECE of another person's is parted between them. The
 * other's side may be a mere piece: the adult's hand and forearm behind
 * the moving child, at its arm's depth, joined the child's blob. */
#define SPLIT_MIN_PIECE 8
static void split_merged(cub_tracker *t)
{
    trk_shift sp = shift_of(t, t->centre, t->vel), so = shift_of(t, t->other_c, t->other_vel);
    int32_t mine[TRK_MAX_COMPS] = {0}, other[TRK_MAX_COMPS] = {0};
    for (int32_t i = 0; i < TRK_CELLS; i++) {
        int16_t l = t->label[i];
        t->mask[i] = l < 0 ? 0 : side_of(t, i, sp, so);
        if (t->mask[i] == TRK_WHO_PLAYER) mine[l]++;
        if (t->mask[i] == TRK_WHO_OTHER) other[l]++;
    }
    int32_t n = t->ncomps;
    for (int16_t k = 0; k < n && t->ncomps < TRK_MAX_COMPS; k++) {
        if (mine[k] < SPLIT_MIN_CELLS || other[k] < SPLIT_MIN_PIECE) continue;
        grow_sides(t, k);
        split_off(t, k); /* side 2: TRK_WHO_OTHER */
        t->parted = true;
    }
    memset(t->mask, 0, sizeof t->mask);
}

/* The two person-like blobs of last frame with most cells in blob k
 * (SPLIT_MIN_CELLS or more each: two people who touch this frame), false
 * if fewer. */
static bool two_people(const cub_tracker *t, int32_t k, int16_t *a, int16_t *b)
{
    int32_t count[TRK_MAX_COMPS] = {0};
    for (int32_t i = 0; i < TRK_CELLS; i++)
        if (t->label[i] == k && t->label_prev[i] >= 0) count[t->label_prev[i]]++;
    *a = *b = -1;
    for (int16_t l = 0; l < TRK_MAX_COMPS; l++) {
        if (count[l] < SPLIT_MIN_CELLS) continue;
        if (*a < 0 || count[l] > count[*a]) *b = *a, *a = l;
        else if (*b < 0 || count[l] > count[*b]) *b = l;
    }
    return *b >= 0;
}

/* Blob k holding two people of last frame is split between them (each
 * cell to the one whose last frame's cells are fewer steps away). */
static void split_two_people(cub_tracker *t, int16_t k)
{
    int16_t a, b;
    if (t->ncomps >= TRK_MAX_COMPS || !two_people(t, k, &a, &b)) return;
    for (int32_t i = 0; i < TRK_CELLS; i++)
        t->mask[i] = t->label[i] != k ? 0 : t->label_prev[i] == a ? 1 : t->label_prev[i] == b ? 2 : 0;
    grow_sides(t, k);
    split_off(t, k);
}

/* Another person stands beside the player, its centre apart along the
 * floor; the player's own upper body cut off by depth (a forearm across
 * the waist) is a person-like blob too, but right above its legs. */
#define SPLIT_APART_MM 250
static bool apart(const cub_tracker *t, const trk_comp *c)
{
    trk_p3 cc = comp_centre(c);
    int32_t dx = cc.x - t->centre.x, dy = cc.y - t->centre.y, dz = cc.z - t->centre.z;
    int64_t h = trk_along(dx, dy, dz, t->up);
    int64_t d2 = (int64_t)dx * dx + (int64_t)dy * dy + (int64_t)dz * dz - h * h;
    return d2 > (int64_t)SPLIT_APART_MM * SPLIT_APART_MM;
}

/* A velocity (mm/s) smoothed with the move from `from` to `to` in u us,
 * along the floor only (people walk on it), capped at ID_MAX_SPEED. */
static trk_p3 floor_velocity(const cub_tracker *t, trk_p3 vel, trk_p3 from, trk_p3 to, int32_t u)
{
    trk_p3 v = {(int32_t)((int64_t)(to.x - from.x) * 1000000 / u), (int32_t)((int64_t)(to.y - from.y) * 1000000 / u),
                (int32_t)((int64_t)(to.z - from.z) * 1000000 / u)};
    int32_t h = trk_along(v.x, v.y, v.z, t->up);
    v = (trk_p3){v.x - (int32_t)(((int64_t)t->up.x * h) >> 16), v.y - (int32_t)(((int64_t)t->up.y * h) >> 16),
                 v.z - (int32_t)(((int64_t)t->up.z * h) >> 16)};
    int32_t s = trk_len(v.x, v.y, v.z);
    if (s > ID_MAX_SPEED) v.x = v.x * ID_MAX_SPEED / s, v.y = v.y * ID_MAX_SPEED / s, v.z = v.z * ID_MAX_SPEED / s;
    return (trk_p3){(vel.x + v.x) / 2, (vel.y + v.y) / 2, (vel.z + v.z) / 2};
}

/* The person-like blob nearest p, not mostly the player's cells; -1 none. */
static int32_t nearest_other(const cub_tracker *t, const bool *person, trk_p3 p, int32_t *d_mm)
{
    int32_t mine[TRK_MAX_COMPS] = {0}, best = -1;
    for (int32_t i = 0; i < TRK_CELLS; i++)
        if (t->mask[i] && t->label[i] >= 0) mine[t->label[i]]++;
    *d_mm = INT32_MAX;
    for (int32_t k = 0; k < t->ncomps; k++) {
        if (!person[k] || mine[k] * 2 > t->comps[k].n) continue;
        int32_t d = dist3(comp_centre(&t->comps[k]), p);
        if (d < *d_mm) *d_mm = d, best = k;
    }
    return best;
}

/* The other person nearest the player, followed for split_merged: last
 * frame's other where its motion brings it (within OTHER_GATE_MM), else
 * whoever stands nearest the player (motion unknown: none). Parted from
 * the player, its centre is where the parting put it (at 1.5 m/s a
 * crosser's speed measured so drove its predicted cells over the child):
 * then only its side away from the player is its own, and that side's
 * move is its motion (an adult who walked in and stopped behind the
 * child stops there too). */
#define OTHER_GATE_MM 600
#define OTHER_JUMP_MM 60 /* the far edge's move this much beyond the motion's */
static void other_motion(cub_tracker *t, const bool *person)
{
    trk_p3 pred = moved_on(t->other_c, t->other_vel, t->dt_us);
    int32_t d, k = t->other_label >= 0 ? nearest_other(t, person, pred, &d) : -1;
    bool followed = k >= 0 && d <= OTHER_GATE_MM;
    if (!followed) k = t->tracked ? nearest_other(t, person, t->centre, &d) : -1;
    t->other_label = (int16_t)k;
    if (k < 0) return;
    const trk_comp *o = &t->comps[k];
    trk_p3 c = comp_centre(o);
    int8_t side = c.x > t->centre.x ? 1 : -1;
    int32_t edge = side > 0 ? o->xmax : o->xmin;
    /* an edge that jumps (another piece, an arm flung out) is not a move */
    bool jump = t->parted && trk_abs(edge - t->other_edge) > trk_abs(per_s(t->other_vel.x, t->dt_us)) + OTHER_JUMP_MM;
    if (!followed || (t->parted && (side != t->other_side || jump))) {
        t->other_vel = followed ? t->other_vel : (trk_p3){0, 0, 0};
        t->other_c = followed ? pred : c;
    } else {
        if (t->parted) c = (trk_p3){t->other_c.x + edge - t->other_edge, c.y, c.z};
        t->other_vel = floor_velocity(t, t->other_vel, t->other_c, c, t->dt_us > 0 ? t->dt_us : 1);
        t->other_c = c;
    }
    t->other_edge = edge, t->other_side = side;
}

/* What each cell was this frame (and its depth), for the next frame's
 * split_merged and was_someone_else, and the background's learning. */
static void remember_who(cub_tracker *t)
{
    uint8_t who[TRK_MAX_COMPS];
    bool person[TRK_MAX_COMPS];
    for (int32_t k = 0; k < t->ncomps; k++) {
        person[k] = person_like(&t->comps[k]);
        who[k] = !person[k] ? 0 : !t->tracked || apart(t, &t->comps[k]) ? TRK_WHO_OTHER : TRK_WHO_NEAR;
    }
    trk_bg_mark_people(t, person);
    other_motion(t, person);
    for (int32_t i = 0; i < TRK_CELLS; i++) {
        int16_t l = t->label[i];
        t->who_prev[i] = t->mask[i] ? TRK_WHO_PLAYER : l >= 0 ? who[l] : 0;
        t->label_prev[i] = (int16_t)(l >= 0 && person[l] ? l : -1);
        t->z_prev[i] = t->z[i];
    }
}

/* Blob k is someone else who was in view last frame: many of its cells
 * were another person-like blob's at about the same depth, few were the
 * player's. The track's gate does not make it the player: the child who
 * merges for a moment with the sofa behind it does not become the adult
 * standing 400 mm away, the crosser joined to the hidden child's pieces
 * stays the crosser. The other person followed counts where its motion
 * brought its cells; the player's cells count only on the same surface
 * (the adult seen where the child's arm was is not the child). */
#define WAS_OTHER_DZ 150
#define WAS_OTHER_SHARE 10 /* or ten times more of its cells the other's than the player's */
static bool was_someone_else(const cub_tracker *t, int32_t k)
{
    trk_shift so = shift_of(t, t->other_c, t->other_vel);
    bool moved = t->other_label >= 0 && (so.gx || so.gy);
    int32_t mine = 0, other = 0;
    for (int32_t i = 0; i < TRK_CELLS; i++) {
        if (t->label[i] != k) continue;
        bool same_surface = trk_abs(t->z[i] - t->z_prev[i]) <= WAS_OTHER_DZ;
        if (t->who_prev[i] == TRK_WHO_PLAYER) mine += same_surface;
        else if ((t->who_prev[i] && same_surface) || (moved && came_from(t, i, so, TRK_WHO_OTHER, t->other_label)))
            other++;
    }
    return other >= SPLIT_MIN_CELLS && (mine < SPLIT_MIN_CELLS || mine * WAS_OTHER_SHARE < other);
}

/* A person new to the box: the nearest, near the image's centre (lower is
 * better). */
static int64_t newcomer_score(trk_p3 cc) { return cc.z + 2 * trk_abs(cc.x); }

/* Cell i is new this frame: nothing stood there last frame (or only
 * something well behind it), and no person-like blob's cell of last frame
 * lies within NEW_CLEAR cells (the edge a moving person sweeps is not a
 * newcomer). */
#define NEW_CLEAR 2      /* cells: a walking person's edge moves less per frame */
#define NEW_BEHIND_MM 300 /* last frame's reading this far behind: something came in front */
#define NEWCOMER_CELLS 100 /* new cells of a blob before it counts someone just come in */
static bool new_cell(const cub_tracker *t, int32_t i)
{
    if (t->z_prev[i] && t->z_prev[i] - t->z[i] < NEW_BEHIND_MM) return false;
    int32_t gx = i % TRK_GW, gy = i / TRK_GW;
    for (int32_t y = gy - NEW_CLEAR; y <= gy + NEW_CLEAR; y++)
        for (int32_t x = gx - NEW_CLEAR; x <= gx + NEW_CLEAR; x++)
            if (on_grid(x, y) && t->label_prev[y * TRK_GW + x] >= 0) return false;
    return true;
}

/* START, the child stepping in beside someone the box saw before (a
 * sibling, the sofa it stood at): one blob by depth with them. Split
 * between last frame's people and the cells new this frame, so the child
 * who just came is a blob of its own and the newcomer's choice can take
 * it, not the one who was there. */
static void split_newcomer(cub_tracker *t, int16_t k)
{
    int32_t old = 0, fresh = 0;
    for (int32_t i = 0; i < TRK_CELLS; i++) {
        t->mask[i] = 0;
        if (t->label[i] != k) continue;
        if (t->label_prev[i] >= 0) t->mask[i] = 1, old++;
        else if (new_cell(t, i)) t->mask[i] = 2, fresh++;
    }
    if (old < SPLIT_MIN_CELLS || fresh < NEWCOMER_CELLS || t->ncomps >= TRK_MAX_COMPS) return;
    grow_sides(t, k);
    split_off(t, k);
}

/* A limb does not go on onto a surface a depth step behind it where that
 * surface joins someone else. The player's blob, cut wherever
 * 4-neighbours differ by more than LIMB_STEP_MM (joins_mm's step is
 * 160-190 mm at 2.4-3 m), falls in pieces, the largest its body. A piece
 * of at most 1/LIMB_PIECE_SHARE of the body's cells (a forearm, a hand:
 * not a body cut in two by its own forearm, merge_cut_off's), behind the
 * body where it comes nearest it in depth (before it: a hand before the
 * chest) or touching only other pieces, that joins another person-like
 * blob (a step of at most LIMB_STEP_MM) with a smaller step than any it
 * has to the body is that person's. The adult's forearm raised
 * behind the moving child's shoulder, 120-140 mm behind it and continuous
 * with the adult, stayed the child's frame after frame (its cells were
 * the player's last frame, so split_merged seeded them so) and took the
 * child's right hand. Along the child's own arm, even one reaching back,
 * neighbouring cells differ by a few tens of mm. Not the other way (the
 * others' pieces to the player): the adult's hands at the child's depth
 * then came to the child as often as the child's arm came back
 * (docs/tracker_eval.md). */
#define LIMB_STEP_MM 100
#define LIMB_PIECE_SHARE 4

/* Blob pid's pieces: each cell's piece id in t->dist0 (-1 elsewhere; a
 * scratch here, the geodesics fill it later), each piece's cells one run
 * of t->stack[0..returned); *body: the largest piece's id, *body_n its
 * cells. */
static int32_t cut_pieces(cub_tracker *t, int32_t pid, int32_t *body, int32_t *body_n)
{
    int32_t tail = 0, id = 0;
    *body = -1, *body_n = 0;
    for (int32_t i = 0; i < TRK_CELLS; i++) t->dist0[i] = -1;
    for (int32_t s = 0; s < TRK_CELLS; s++) {
        if (t->label[s] != pid || t->dist0[s] >= 0) continue;
        int32_t head = tail;
        t->stack[tail++] = s, t->dist0[s] = id;
        for (int32_t q = head; q < tail; q++) {
            int32_t i = t->stack[q], nb[4];
            neighbours4(i, nb);
            for (int k = 0; k < 4; k++) {
                int32_t n = nb[k];
                if (n < 0 || t->label[n] != pid || t->dist0[n] >= 0 || trk_abs(t->z[n] - t->z[i]) > LIMB_STEP_MM)
                    continue;
                t->dist0[n] = id, t->stack[tail++] = n;
            }
        }
        if (tail - head > *body_n) *body_n = tail - head, *body = id;
        id++;
    }
    return tail;
}

/* The person-like blob other than pid that the piece t->stack[from..to)
 * joins (a step of at most LIMB_STEP_MM) with a smaller step than any it
 * has to the body piece, the piece behind the body at the smallest of
 * those (or touching only other pieces); -1 none. */
static int32_t piece_owner(const cub_tracker *t, int32_t pid, int32_t body, int32_t from, int32_t to)
{
    int32_t to_body = INT32_MAX, to_other = INT32_MAX, owner = -1;
    bool behind = false;
    for (int32_t q = from; q < to; q++) {
        int32_t i = t->stack[q], nb[4];
        neighbours4(i, nb);
        for (int k = 0; k < 4; k++) {
            int32_t n = nb[k], l = n < 0 ? -1 : t->label[n];
            if (l < 0) continue;
            int32_t d = trk_abs(t->z[n] - t->z[i]);
            if (l == pid && t->dist0[n] == body && d < to_body) to_body = d, behind = t->z[i] > t->z[n];
            if (l != pid && d < to_other && person_like(&t->comps[l])) to_other = d, owner = l;
        }
    }
    return (behind || to_body == INT32_MAX) && to_other <= LIMB_STEP_MM && to_other < to_body ? owner : -1;
}

void trk_give_back_pieces(cub_tracker *t, int32_t pid)
{
    int32_t body, body_n, end = cut_pieces(t, pid, &body, &body_n);
    bool gained[TRK_MAX_COMPS] = {0}, any = false;
    for (int32_t from = 0, to; from < end; from = to) {
        int32_t id = t->dist0[t->stack[from]];
        for (to = from + 1; to < end && t->dist0[t->stack[to]] == id;) to++;
        if (id == body || (to - from) * LIMB_PIECE_SHARE > body_n) continue;
        int32_t owner = piece_owner(t, pid, body, from, to);
        if (owner < 0) continue;
        for (int32_t q = from; q < to; q++) t->label[t->stack[q]] = (int16_t)owner;
        gained[owner] = any = true;
    }
    if (!any) return;
    refill_comp(t, (int16_t)pid);
    for (int32_t k = 0; k < t->ncomps; k++)
        if (gained[k]) refill_comp(t, (int16_t)k);
    count_interior(t);
}

/* The newcomer a box that just started would take, -1 none; a blob of
 * two people who touch (the child beside the adult it stood apart from
 * last frame) is split between them first, and at START a blob of
 * someone seen before and someone new. */
static int32_t first_choice(cub_tracker *t)
{
    int32_t best = -1;
    for (int pass = 0; pass < 2; pass++) {
        int64_t best_score = INT64_MAX;
        best = -1;
        for (int32_t k = 0; k < t->ncomps; k++) {
            if (!person_like(&t->comps[k])) continue;
            int64_t score = newcomer_score(comp_centre(&t->comps[k]));
            if (score < best_score) best_score = score, best = k;
        }
        if (best < 0 || pass == 1) break;
        int32_t n = t->ncomps;
        split_two_people(t, (int16_t)best);
        if (t->ncomps == n && t->start_afresh) split_newcomer(t, (int16_t)best);
        if (t->ncomps == n) break;
    }
    return best;
}

/* The player's identity is its track in the room: the centre where it was
 * last seen, moving on at its velocity. A blob is the player only near
 * that prediction (the gate widens while the player is unseen), and never
 * a blob well in front of it: someone crossing before the player hides it
 * but stands nearer the camera than the player can have moved. While the
 * track is alive (unseen for less than ID_HOLD_US) nobody else becomes the
 * player; the player hidden but for pieces (an arm, the legs beside the
 * one in front) is those pieces at its depth. */
#define ID_HOLD_US 2000000 /* a hidden player keeps its track this long: an occlusion of 1.5 s and the
                            * frames either side of it that show too little of the player */
#define ID_GATE_MM 450     /* a blob's centre this near the prediction may be the player (a child moves 250 mm in 0.1 s) */
#define ID_GATE_GROW 600   /* and this much farther per second unseen (mm/s) */
#define ID_PART_DZ_MM 400  /* a piece of a hidden player: within this depth of the prediction */
#define ID_PART_CELLS 12   /* and no smaller */
#define ID_FAR 1000000     /* score offset: a blob that is not the tracked player */

static int32_t unseen_us(const cub_tracker *t)
{
    int64_t d = t->prev_t_us - t->seen_us;
    return d < 0 ? 0 : d > ID_HOLD_US ? ID_HOLD_US + 1 : (int32_t)d;
}

static trk_p3 predicted(const cub_tracker *t)
{
    return moved_on(t->centre, t->vel, unseen_us(t));
}

/* Blob centre cc's distance from the prediction, -1 outside the gate or in front. */
static int32_t track_gap(const cub_tracker *t, trk_p3 pred, trk_p3 cc)
{
    /* the front does not widen: a hidden player is behind whoever hides it */
    int32_t grow = per_s(ID_GATE_GROW, unseen_us(t));
    if (cc.z < pred.z - ID_FRONT_MM) return -1;
    int32_t d = trk_len(cc.x - pred.x, cc.y - pred.y, cc.z - pred.z);
    return d <= ID_GATE_MM + grow ? d : -1;
}

/* A person-like blob's score: the tracked player's gap, else ID_FAR and
 * more (a newcomer); below 0 a newcomer who takes over at once (see below). */
static int64_t person_score(const cub_tracker *t, trk_p3 pred, trk_p3 cc)
{
    if (!t->tracked) return ID_FAR + newcomer_score(cc);
    int32_t d = track_gap(t, pred, cc);
    /* a player never yet nearer than the play range's far end (someone at
     * the back of the room when the box started) gives way to another
     * person who comes into it: the child walking in */
    if (!t->in_play && d < 0 && cc.z <= TRK_FAR_MM) return -ID_FAR + newcomer_score(cc);
    return d >= 0 ? d : ID_FAR + newcomer_score(cc);
}

/* Blob k is the player merged with someone taller who stood beside or
 * before it last frame (a parent crossing close before the child, touching
 * it): its top stands ID_TALLER_MM above the player's highest of late
 * (raised hands included) and SPLIT_MIN_CELLS of its cells were another
 * person's last frame. Alone, a child who jumps with its arms up is never
 * this (no cells of anybody else). */
#define ID_TALLER_MM 200
#define ID_TOP_FALL 150 /* mm/s: the player's highest point is forgotten this fast */
static bool merged_with_taller(const cub_tracker *t, int32_t k)
{
    if (t->comps[k].hmax <= t->top_mm + ID_TALLER_MM) return false;
    int32_t other = 0;
    for (int32_t i = 0; i < TRK_CELLS; i++) {
        uint8_t w = t->label[i] == k ? t->who_prev[i] : 0;
        other += w == TRK_WHO_OTHER || w == TRK_WHO_NEAR;
    }
    return other >= SPLIT_MIN_CELLS;
}

/* The player's highest point: this frame's blob's top, or the one of late
 * falling at ID_TOP_FALL. */
static void update_top(cub_tracker *t, int32_t blob, bool same, int32_t dt_us)
{
    int32_t top = t->comps[blob].hmax, kept = t->top_mm - per_s(ID_TOP_FALL, dt_us);
    t->top_mm = same && kept > top ? kept : top;
}

/* Someone stands before the player's columns of last sighting: the
 * player may be hidden but for pieces. */
static bool someone_in_front(const cub_tracker *t, trk_p3 pred)
{
    for (int32_t k = 0; k < t->ncomps; k++) {
        const trk_comp *c = &t->comps[k];
        if (!person_like(c) || c->gx1 < t->seen_gx0 || c->gx0 > t->seen_gx1) continue;
        if ((int32_t)(c->sz / c->n) < pred.z - ID_FRONT_MM) return true;
    }
    return false;
}

/* The hidden player's largest piece near the prediction, -1 none. */
static int32_t player_part(const cub_tracker *t, trk_p3 pred)
{
    int32_t best = -1;
    for (int32_t k = 0; k < t->ncomps; k++) {
        const trk_comp *c = &t->comps[k];
        if (c->n < ID_PART_CELLS || (best >= 0 && c->n <= t->comps[best].n)) continue;
        trk_p3 cc = comp_centre(c);
        if (trk_abs(cc.z - pred.z) > ID_PART_DZ_MM || track_gap(t, pred, cc) < 0) continue;
        if (part_of_someone_in_front(t, -1, pred.z, c))
            continue; /* the hider's own arm */
        best = k;
    }
    return best;
}

/* The blob holding last frame's torso (the skeleton's hip centre, spine
 * and shoulder centre) moved on at the track's velocity: the cells within
 * TORSO_WIN cells of where it projects, within TORSO_DZ of its depth, by
 * blob; the blob with most, -1 none. When the player's blob splits (two
 * children who stood touching part), the piece where the body was is the
 * player, not the piece nearer the blob's old centre (the other child
 * and the furniture pulled that centre their way). */
#define TORSO_WIN 4
#define TORSO_DZ 300
static int32_t torso_blob(const cub_tracker *t)
{
    static const int part[3] = {CUB_KJ_HIP_CENTRE, CUB_KJ_SPINE, CUB_KJ_SHOULDER_CENTRE};
    if (!t->have_prev || t->prev.status == CUB_TRACK_NO_PLAYER) return -1;
    trk_p3 p = {0, 0, 0};
    for (int k = 0; k < 3; k++)
        p.x += (t->prev.joint_mm[part[k]].x >> 16) / 3, p.y += (t->prev.joint_mm[part[k]].y >> 16) / 3,
            p.z += (t->prev.joint_mm[part[k]].z >> 16) / 3;
    p = moved_on(p, t->vel, unseen_us(t));
    if (p.z <= 0) return -1;
    int32_t gx0, gy0, count[TRK_MAX_COMPS] = {0}, best = -1;
    grid_of(p, &gx0, &gy0);
    for (int32_t gy = gy0 - TORSO_WIN; gy <= gy0 + TORSO_WIN; gy++)
        for (int32_t gx = gx0 - TORSO_WIN; gx <= gx0 + TORSO_WIN; gx++) {
            if (!on_grid(gx, gy)) continue;
            int32_t i = gy * TRK_GW + gx, l = t->label[i];
            if (l < 0 || trk_abs(t->z[i] - p.z) > TORSO_DZ) continue;
            if (++count[l] > (best >= 0 ? count[best] : 0)) best = l;
        }
    return best;
}

/* The player's blob this frame; *same: the tracked player (else a
 * newcomer), *hidden: someone stands before it. */
static int32_t choose_blob(cub_tracker *t, bool *same, bool *hidden)
{
    *hidden = t->tracked && someone_in_front(t, predicted(t));
    trk_p3 pred = predicted(t);
    int32_t best = -1;
    int64_t best_score = INT64_MAX;
    bool someone_else[TRK_MAX_COMPS] = {0};
    for (int32_t k = 0; k < t->ncomps; k++) {
        if (!person_like(&t->comps[k])) continue;
        int64_t score = person_score(t, pred, comp_centre(&t->comps[k]));
        /* not while the player waits to be chosen afresh (the room just
         * known, START): the blobs then are not the frame before's */
        bool afresh = t->room_known == 1 || t->start_afresh;
        if (t->tracked && !afresh && score >= 0 && score < ID_FAR &&
            (was_someone_else(t, k) || merged_with_taller(t, k)))
            someone_else[k] = true, score = ID_FAR + newcomer_score(comp_centre(&t->comps[k]));
        if (score < best_score) best_score = score, best = k;
    }
    *same = t->tracked && best >= 0 && best_score >= 0 && best_score < ID_FAR;
    if (*same) {
        /* two people about as near the prediction (within half the gate
         * of each other): the one where the torso was */
        int32_t tb = torso_blob(t);
        int32_t gap = tb >= 0 && tb != best && person_like(&t->comps[tb]) && !someone_else[tb]
                          ? track_gap(t, pred, comp_centre(&t->comps[tb]))
                          : -1;
        if (gap >= 0 && gap - best_score <= ID_GATE_MM / 2) best = tb;
    }
    if (*same || !t->tracked || best_score < 0) return best;
    /* the track is alive: its pieces, or nobody, but no one else */
    int32_t part = *hidden ? player_part(t, pred) : -1;
    *same = part >= 0;
    return part >= 0 || unseen_us(t) <= ID_HOLD_US ? part : best;
}

/* The track follows the blob seen: its centre, and the velocity along the
 * floor from the last sighting (people walk on it). A player with someone
 * in front shows pieces whose centre is not the body's: the centre goes
 * half-way to them from the prediction (a mere piece: across the image
 * only), the velocity and columns stay. Parted from someone this frame
 * or the last, the blob's centre is where the parting put it: the
 * velocity stays too (split_merged moves the player's cells by it; one
 * measured so drove a hidden child's prediction into the crosser). */
static void track_update(cub_tracker *t, int32_t blob, bool same, bool hidden)
{
    trk_p3 c = comp_centre(&t->comps[blob]), pred = predicted(t);
    int32_t u = unseen_us(t);
    if (!same) {
        t->vel = (trk_p3){0, 0, 0};
    } else if (hidden) {
        /* a piece (not a whole body) says little of the body's depth: a
         * hand reaching forward would pull the track toward whoever hides
         * the player, frame after frame */
        int32_t z = person_like(&t->comps[blob]) ? (c.z + pred.z) / 2 : pred.z;
        c = (trk_p3){(c.x + pred.x) / 2, (c.y + pred.y) / 2, z};
    } else if (u > 0 && u <= 200000 && !t->parted && !t->parted_before) {
        t->vel = floor_velocity(t, t->vel, t->centre, c, u);
    }
    t->centre = c;
    t->seen_us = t->prev_t_us;
    if (!hidden) t->seen_gx0 = t->comps[blob].gx0, t->seen_gx1 = t->comps[blob].gx1;
}

/* START (cub_track_choose_afresh): the nearest, most central person,
 * whoever the track followed before; the choice waits for a frame with
 * someone person-like. */
static int32_t start_choice(cub_tracker *t, int32_t best, bool *same)
{
    int32_t fresh = first_choice(t);
    if (fresh < 0) return best;
    t->start_afresh = false;
    if (fresh != best) *same = false;
    return fresh;
}

cub_err cub_track_choose_afresh(cub_tracker *t)
{
    if (!t) return CUB_ERR_ARG;
    t->start_afresh = true;
    return CUB_OK;
}

int32_t trk_pick_player(cub_tracker *t)
{
    if (t->tracked && unseen_us(t) > ID_HOLD_US && t->lost_frames > 0) t->tracked = false;
    t->parted_before = t->parted, t->parted = false;
    if (t->tracked) split_merged(t);
    bool same, hidden;
    int32_t best = choose_blob(t, &same, &hidden);
    if (trk_bg_room_new(t) && same && person_like(&t->comps[best])) {
        /* the room has just become known: a child merged with the sofa
         * behind it is seen only now, so the player is chosen afresh as
         * when the box starts (in attract mode this happens before START) */
        int32_t fresh = first_choice(t);
        if (fresh >= 0 && fresh != best) best = fresh, same = false;
        t->room_known = 2;
    }
    if (t->start_afresh) best = start_choice(t, best, &same);
    if (best >= 0) trk_give_back_pieces(t, best);
    memset(t->mask, 0, sizeof t->mask);
    if (best < 0) {
        remember_who(t); /* the others, still */
        return -1;
    }
    if (!same) {
        t->player_id = ++t->next_id;
        memset(t->reach_mm, 0, sizeof t->reach_mm); /* another body */
        t->shoulder_half_mm = 0;
        t->stature_mm = t->neck_drop_mm = 0;
    }
    t->tracked = true;
    update_top(t, best, same, unseen_us(t));
    track_update(t, best, same, hidden);
    t->in_play = (same && t->in_play) || t->centre.z <= TRK_FAR_MM;
    for (int32_t i = 0; i < TRK_CELLS; i++)
        if (t->label[i] == best) t->mask[i] = 1;
    merge_front_parts(t, best);
    remember_who(t);
    return best;
}

/* Geodesic distances over the player's surface: the torso root, shortest
 * paths (Dijkstra on the 8-connected grid, edge = 3D step length) and the
 * extremities (head, hands, feet) as the farthest points, one at a time. */
#include "trk_internal.h"

/* A depth step between neighbours this large (mm) is an edge: a limb
 * lying before the torso. */
#define ROOT_EDGE_MM 60

static bool depth_edge(const cub_tracker *t, int32_t i, int32_t j)
{
    return trk_abs(t->z[i] - t->z[j]) > ROOT_EDGE_MM;
}

/* The root is the cell deepest inside the silhouette (chamfer 3-4
 * distance): the torso is the body's thickest part at any pose. Depth
 * steps count as the silhouette's edge: a forearm held across the chest
 * lies over the silhouette's middle, and a root on it puts every path
 * behind a depth jump. */
int32_t trk_root_cell(cub_tracker *t)
{
    int32_t *d = t->distx;
    for (int32_t i = 0; i < TRK_CELLS; i++) {
        d[i] = t->mask[i] ? 1 << 20 : 0;
        if (!d[i]) continue;
        int32_t gx = i % TRK_GW, gy = i / TRK_GW;
        if ((gx > 0 && t->mask[i - 1] && depth_edge(t, i, i - 1)) ||
            (gx < TRK_GW - 1 && t->mask[i + 1] && depth_edge(t, i, i + 1)) ||
            (gy > 0 && t->mask[i - TRK_GW] && depth_edge(t, i, i - TRK_GW)) ||
            (gy < TRK_GH - 1 && t->mask[i + TRK_GW] && depth_edge(t, i, i + TRK_GW)))
            d[i] = 3;
    }
    for (int32_t gy = 0; gy < TRK_GH; gy++)
        for (int32_t gx = 0; gx < TRK_GW; gx++) {
            int32_t i = gy * TRK_GW + gx;
            if (!d[i]) continue;
            int32_t m = d[i];
            if (gx == 0 || gy == 0) m = 3;
            if (gx > 0 && d[i - 1] + 3 < m) m = d[i - 1] + 3;
            if (gy > 0 && d[i - TRK_GW] + 3 < m) m = d[i - TRK_GW] + 3;
            if (gy > 0 && gx > 0 && d[i - TRK_GW - 1] + 4 < m) m = d[i - TRK_GW - 1] + 4;
            if (gy > 0 && gx < TRK_GW - 1 && d[i - TRK_GW + 1] + 4 < m) m = d[i - TRK_GW + 1] + 4;
            d[i] = m;
        }
    int32_t best = -1, best_d = 0;
    for (int32_t gy = TRK_GH - 1; gy >= 0; gy--)
        for (int32_t gx = TRK_GW - 1; gx >= 0; gx--) {
            int32_t i = gy * TRK_GW + gx;
            if (!d[i]) continue;
            int32_t m = d[i];
            if (gx == TRK_GW - 1 || gy == TRK_GH - 1) m = 3;
            if (gx < TRK_GW - 1 && d[i + 1] + 3 < m) m = d[i + 1] + 3;
            if (gy < TRK_GH - 1 && d[i + TRK_GW] + 3 < m) m = d[i + TRK_GW] + 3;
            if (gy < TRK_GH - 1 && gx < TRK_GW - 1 && d[i + TRK_GW + 1] + 4 < m) m = d[i + TRK_GW + 1] + 4;
            if (gy < TRK_GH - 1 && gx > 0 && d[i + TRK_GW - 1] + 4 < m) m = d[i + TRK_GW - 1] + 4;
            d[i] = m;
            /* silhouette thickness in mm, so near and far parts compare */
            int32_t thick = m * t->z[i];
            if (thick > best_d) best_d = thick, best = i;
        }
    return best;
}

/* |v| within about 8 %, no square root: a + 11/32 b + 1/4 c, a >= b >= c.
 * By min and max, not swaps: no branch to mispredict in the geodesics'
 * inner loop. */
static inline int32_t max2(int32_t a, int32_t b) { return a > b ? a : b; }
static inline int32_t min2(int32_t a, int32_t b) { return a < b ? a : b; }

static int32_t approx_len(int32_t dx, int32_t dy, int32_t dz)
{
    int32_t p = trk_abs(dx), q = trk_abs(dy), r = trk_abs(dz);
    int32_t a = max2(max2(p, q), r), c = min2(min2(p, q), r), b = p + q + r - a - c;
    return a + ((11 * b) >> 5) + (c >> 2);
}

#define TRK_JUMP_MM 40
#define TRK_JUMP_COST 4

/* A 4-ary heap of (distance << 32 | cell): shallower than a binary one,
 * so a pop reads fewer levels. The keys are unique (a cell is pushed again
 * only at a strictly smaller distance), so any exact heap pops them in the
 * same order: the shape of the heap never changes the output. */
#define HEAP_ARITY 4

static void heap_push(cub_tracker *t, int32_t *n, uint32_t key, int32_t cell)
{
    if (*n >= TRK_HEAP_CAP) return;
    uint64_t v = ((uint64_t)key << 32) | (uint32_t)cell;
    int32_t i = (*n)++;
    while (i > 0) {
        int32_t p = (i - 1) / HEAP_ARITY;
        if (t->heap[p] <= v) break;
        t->heap[i] = t->heap[p];
        i = p;
    }
    t->heap[i] = v;
}

/* The smallest of i's children, -1 when it has none. */
static int32_t heap_min_child(const uint64_t *h, int32_t i, int32_t n)
{
    int32_t c = HEAP_ARITY * i + 1, end = c + HEAP_ARITY < n ? c + HEAP_ARITY : n;
    if (c >= n) return -1;
    int32_t m = c;
    for (c++; c < end; c++)
        if (h[c] < h[m]) m = c;
    return m;
}

static uint64_t heap_pop(cub_tracker *t, int32_t *n)
{
    uint64_t top = t->heap[0], last = t->heap[--(*n)];
    int32_t i = 0;
    for (;;) {
        int32_t c = heap_min_child(t->heap, i, *n);
        if (c < 0 || t->heap[c] >= last) break;
        t->heap[i] = t->heap[c];
        i = c;
    }
    if (*n > 0) t->heap[i] = last;
    return top;
}

/* The step between two of the player's neighbouring cells i and j: its 3D
 * length, and a depth jump between them is mostly an edge (a hand or
 * forearm lying before the chest), not surface: crossing it costs extra,
 * so the hand stays far along its own arm. At most about 44 000 (depths
 * 500-8191 mm: a step under 13 300 mm, a jump under 30 700), so it fits
 * in 16 bits below TRK_EDGE_NONE. */
static int32_t step_cost(const cub_tracker *t, int32_t i, int32_t j)
{
    int32_t dz = trk_abs(t->z[j] - t->z[i]);
    int32_t w = approx_len(t->x[j] - t->x[i], t->y[j] - t->y[i], t->z[j] - t->z[i]);
    if (dz > TRK_JUMP_MM) w += TRK_JUMP_COST * (dz - TRK_JUMP_MM);
    return w;
}

/* A grid the searches run on: per node its four forward edges' lengths
 * (TRK_EDGE_NONE: no edge), w[k][i] node i's (a row of none lies before
 * node 0, so w[k][i - off[k]], the edge from the node behind, needs no
 * bounds check), and the forward offsets (right, down, down right, down
 * left). Each step is symmetric: computed once a frame instead of in
 * every search from both ends. */
typedef struct edge_grid {
    const uint16_t *w[4];
    int32_t off[4];
} edge_grid;

static edge_grid fine_grid(const cub_tracker *t)
{
    return (edge_grid){{&t->edge_w[0][TRK_EDGE_PAD], &t->edge_w[1][TRK_EDGE_PAD], &t->edge_w[2][TRK_EDGE_PAD],
                        &t->edge_w[3][TRK_EDGE_PAD]},
                       {1, TRK_GW, TRK_GW + 1, TRK_GW - 1}};
}

static edge_grid coarse_grid(const cub_tracker *t)
{
    return (edge_grid){{&t->coarse_w[0][TRK_COARSE_PAD], &t->coarse_w[1][TRK_COARSE_PAD],
                        &t->coarse_w[2][TRK_COARSE_PAD], &t->coarse_w[3][TRK_COARSE_PAD]},
                       {1, TRK_BW, TRK_BW + 1, TRK_BW - 1}};
}

static const int8_t fwd_dx[4] = {1, 0, 1, -1}, fwd_dy[4] = {0, 1, 1, 1};

/* Every edge of the mask's 8-connected grid, for the many searches over
 * it (the root's, the bridges', one per extremity). */
static void edges_fill(cub_tracker *t)
{
    memset(t->edge_w, 0xFF, sizeof t->edge_w);
    for (int32_t i = 0; i < TRK_CELLS; i++) {
        if (!t->mask[i]) continue;
        int32_t gx = i % TRK_GW, gy = i / TRK_GW;
        for (int k = 0; k < 4; k++) {
            int32_t j = (gy + fwd_dy[k]) * TRK_GW + gx + fwd_dx[k];
            if (on_grid(gx + fwd_dx[k], gy + fwd_dy[k]) && t->mask[j])
                t->edge_w[k][TRK_EDGE_PAD + i] = (uint16_t)step_cost(t, i, j);
        }
    }
}

/* j reached from i at distance nd: lowered when it improves. */
static inline void relax(cub_tracker *t, int32_t *dist, int32_t *parent, int32_t *n, int32_t i, int32_t j,
                         int32_t nd)
{
    if (nd >= dist[j]) return;
    dist[j] = nd;
    if (parent) parent[j] = i;
    heap_push(t, n, (uint32_t)nd, j);
}

/* Dijkstra over grid g from whatever the heap holds, lowering dist where
 * it improves (so repeated runs give the distance to the nearest source). */
static void run_heap(cub_tracker *t, const edge_grid *g, int32_t *dist, int32_t *parent, int32_t n)
{
    while (n > 0) {
        uint64_t v = heap_pop(t, &n);
        int32_t i = (int32_t)(uint32_t)v, d = (int32_t)(v >> 32);
        if (d > dist[i]) continue;
        for (int k = 0; k < 4; k++) {
            int32_t w = g->w[k][i], o = g->off[k];
            if (w != TRK_EDGE_NONE) relax(t, dist, parent, &n, i, i + o, d + w);
            w = g->w[k][i - o];
            if (w != TRK_EDGE_NONE) relax(t, dist, parent, &n, i, i - o, d + w);
        }
    }
}

static void geodesic(cub_tracker *t, int32_t *dist, int32_t *parent, int32_t src)
{
    int32_t n = 0;
    dist[src] = 0;
    if (parent) parent[src] = -1;
    heap_push(t, &n, 0, src);
    edge_grid g = fine_grid(t);
    run_heap(t, &g, dist, parent, n);
}

/* The coarse surface: 2x2 blocks of cells. Any two cells of a block touch,
 * so two blocks join when a cell on one's border touches one on the
 * other's; a block stands at its first player cell. */
static int32_t block_rep(const cub_tracker *t, int32_t bx, int32_t by)
{
    int32_t i = 2 * by * TRK_GW + 2 * bx;
    if (t->mask[i]) return i;
    if (t->mask[i + 1]) return i + 1;
    if (t->mask[i + TRK_GW]) return i + TRK_GW;
    if (t->mask[i + TRK_GW + 1]) return i + TRK_GW + 1;
    return -1;
}

static bool blocks_join(const cub_tracker *t, int32_t bx, int32_t by, int32_t dx, int32_t dy)
{
    const uint8_t *m = t->mask;
    int32_t x = 2 * bx, y = 2 * by; /* block A's top left cell */
    if (dy == 0) {
        int32_t ca = dx > 0 ? x + 1 : x, cb = dx > 0 ? x + 2 : x - 1; /* the facing columns */
        return (m[y * TRK_GW + ca] || m[(y + 1) * TRK_GW + ca]) && (m[y * TRK_GW + cb] || m[(y + 1) * TRK_GW + cb]);
    }
    if (dx == 0) {
        int32_t ra = dy > 0 ? y + 1 : y, rb = dy > 0 ? y + 2 : y - 1;
        return (m[ra * TRK_GW + x] || m[ra * TRK_GW + x + 1]) && (m[rb * TRK_GW + x] || m[rb * TRK_GW + x + 1]);
    }
    /* diagonal: only the two facing corners touch */
    int32_t ax = dx > 0 ? x + 1 : x, ay = dy > 0 ? y + 1 : y;
    return m[ay * TRK_GW + ax] && m[(ay + dy) * TRK_GW + ax + dx];
}

/* The coarse grid's edges: two blocks joined (blocks_join), from one's
 * first player cell to the other's. */
void trk_coarse_edges(cub_tracker *t)
{
    memset(t->coarse_w, 0xFF, sizeof t->coarse_w);
    for (int32_t b = 0; b < TRK_BLOCKS; b++) {
        int32_t bx = b % TRK_BW, by = b / TRK_BW, i = block_rep(t, bx, by);
        if (i < 0) continue;
        for (int k = 0; k < 4; k++) {
            int32_t nx = bx + fwd_dx[k], ny = by + fwd_dy[k];
            if (nx < 0 || nx >= TRK_BW || ny >= TRK_BH) continue;
            int32_t j = block_rep(t, nx, ny);
            if (j < 0 || !blocks_join(t, bx, by, fwd_dx[k], fwd_dy[k])) continue;
            t->coarse_w[k][TRK_COARSE_PAD + b] =
                (uint16_t)approx_len(t->x[j] - t->x[i], t->y[j] - t->y[i], t->z[j] - t->z[i]);
        }
    }
}

void trk_geodesic_coarse(cub_tracker *t, int32_t *dist_b, int32_t src)
{
    for (int32_t b = 0; b < TRK_BLOCKS; b++) dist_b[b] = TRK_INF;
    int32_t sb = (src / TRK_GW / 2) * TRK_BW + (src % TRK_GW) / 2, n = 0;
    int32_t sr = block_rep(t, sb % TRK_BW, sb / TRK_BW);
    if (sr < 0) return;
    dist_b[sb] = approx_len(t->x[sr] - t->x[src], t->y[sr] - t->y[src], t->z[sr] - t->z[src]);
    heap_push(t, &n, (uint32_t)dist_b[sb], sb);
    edge_grid g = coarse_grid(t);
    run_heap(t, &g, dist_b, NULL, n);
}

int32_t trk_coarse_at(const cub_tracker *t, const int32_t *dist_b, int32_t cell)
{
    int32_t gx = cell % TRK_GW, gy = cell / TRK_GW, b = (gy / 2) * TRK_BW + gx / 2;
    int32_t r = block_rep(t, gx / 2, gy / 2);
    if (r < 0 || dist_b[b] == TRK_INF) return TRK_INF;
    return dist_b[b] + approx_len(t->x[cell] - t->x[r], t->y[cell] - t->y[r], t->z[cell] - t->z[r]);
}

/* Parts merged in front of the body (a hand before the chest or face) may
 * be cut off from it by a thin band of no reading (the projector's
 * shadow): bridge gaps of up to two cells with their 3D length. */
#define BRIDGE_CELLS 2
static void bridge_gaps(cub_tracker *t, int32_t *dist, int32_t *parent)
{
    int32_t n = 0;
    for (int32_t i = 0; i < TRK_CELLS; i++) {
        if (!t->mask[i] || dist[i] != TRK_INF) continue;
        int32_t gx = i % TRK_GW, gy = i / TRK_GW, best = TRK_INF, from = -1;
        for (int32_t dy = -BRIDGE_CELLS; dy <= BRIDGE_CELLS; dy++)
            for (int32_t dx = -BRIDGE_CELLS; dx <= BRIDGE_CELLS; dx++) {
                int32_t nx = gx + dx, ny = gy + dy;
                if (!on_grid(nx, ny)) continue;
                int32_t j = ny * TRK_GW + nx;
                if (!t->mask[j] || dist[j] == TRK_INF) continue;
                int32_t d = dist[j] + approx_len(t->x[j] - t->x[i], t->y[j] - t->y[i], t->z[j] - t->z[i]);
                if (d < best) best = d, from = j;
            }
        if (from < 0) continue;
        dist[i] = best, parent[i] = from;
        heap_push(t, &n, (uint32_t)best, i);
    }
    edge_grid g = fine_grid(t);
    run_heap(t, &g, dist, parent, n);
}

/* The rows and columns the player's cells span (x0, x1, y0, y1), so the
 * searches for the farthest cell read only them (in the same order). */
static void mask_box(const cub_tracker *t, int32_t box[4])
{
    box[0] = TRK_GW, box[1] = -1, box[2] = TRK_GH, box[3] = -1;
    for (int32_t i = 0; i < TRK_CELLS; i++) {
        if (!t->mask[i]) continue;
        int32_t gx = i % TRK_GW, gy = i / TRK_GW;
        if (gx < box[0]) box[0] = gx;
        if (gx > box[1]) box[1] = gx;
        if (gy < box[2]) box[2] = gy;
        box[3] = gy;
    }
}

/* The player's cell farthest along distx beyond best_d (the first in
 * row-major order on a tie), -1 none. */
static int32_t farthest(const cub_tracker *t, const int32_t box[4], int32_t best_d)
{
    int32_t best = -1;
    for (int32_t gy = box[2]; gy <= box[3]; gy++)
        for (int32_t i = gy * TRK_GW + box[0]; i <= gy * TRK_GW + box[1]; i++)
            if (t->mask[i] && t->distx[i] != TRK_INF && t->distx[i] > best_d) best_d = t->distx[i], best = i;
    return best;
}

/* Up to max_out extremities, farthest first, each at least min_mm of
 * surface away from the root and from every extremity found before. */
int32_t trk_extrema(cub_tracker *t, int32_t root, int32_t min_mm, int32_t *out, int32_t max_out)
{
    for (int32_t i = 0; i < TRK_CELLS; i++) t->dist0[i] = TRK_INF;
    edges_fill(t);
    geodesic(t, t->dist0, t->parent0, root);
    bridge_gaps(t, t->dist0, t->parent0);
    bridge_gaps(t, t->dist0, t->parent0);
    memcpy(t->distx, t->dist0, sizeof t->distx);
    int32_t n = 0, box[4];
    mask_box(t, box);
    while (n < max_out) {
        int32_t best = farthest(t, box, min_mm);
        if (best < 0) break;
        out[n++] = best;
        /* the distances to the last extremity are never read */
        if (n < max_out) geodesic(t, t->distx, NULL, best);
    }
    return n;
}

/* Growing the forest: per tree its own pixels, then depth-first splits of
 * the highest information gain among random probe pairs and thresholds.
 * Nodes are numbered in the order they are made, so a node's children
 * always come after it (the asset's rule). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cub/forest_train.h"
#include "cub/kinect.h"

#define NPIX (CUB_KINECT_WIDTH * CUB_KINECT_HEIGHT)
#define NC CUB_PART_COUNT

typedef struct sample {
    int32_t frame, x, y, label;
} sample;

typedef struct grower {
    const cub_ft_set *set;
    const cub_ft_params *p;
    uint64_t rng;
    sample *s;
    int32_t *val;
    cub_forest_node *nodes;
    uint32_t nn, node_cap;
    uint16_t *leaves; /* NC per leaf */
    uint32_t nl, leaf_cap;
    int failed;
} grower;

static uint64_t next(uint64_t *s) /* splitmix64 */
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static int32_t uniform(uint64_t *s, int32_t lo, int32_t hi) /* [lo, hi] */
{
    return lo + (int32_t)(next(s) % (uint64_t)(hi - lo + 1));
}

static double entropy(const long *h, long n)
{
    double e = 0;
    for (int c = 0; c < NC && n > 0; c++)
        if (h[c]) e -= (double)h[c] / n * log2((double)h[c] / n);
    return e;
}

static int32_t feature_of(const grower *g, const sample *s, const cub_forest_node *n)
{
    const cub_ft_frame *fr = &g->set->frames[s->frame];
    cub_forest_image im = {fr->mm, CUB_KINECT_WIDTH, CUB_KINECT_HEIGHT};
    return cub_forest_feature(&im, s->x, s->y, n);
}

static uint32_t make_leaf(grower *g, const long *h, long n)
{
    if (g->nl == g->leaf_cap) {
        g->leaf_cap = g->leaf_cap ? 2 * g->leaf_cap : 256;
        uint16_t *l = realloc(g->leaves, (size_t)g->leaf_cap * NC * sizeof(uint16_t));
        if (!l) return g->failed = 1, CUB_FOREST_LEAF_BIT;
        g->leaves = l;
    }
    for (int c = 0; c < NC; c++)
        g->leaves[(size_t)g->nl * NC + c] = (uint16_t)(n ? h[c] * 65535 / n : 0);
    return CUB_FOREST_LEAF_BIT | g->nl++;
}

static cub_forest_node random_node(grower *g)
{
    int32_t r = g->p->max_offset;
    cub_forest_node n = {{uniform(&g->rng, -r, r), uniform(&g->rng, -r, r)}, {0, 0}, 0, 0, 0};
    if (next(&g->rng) & 1) { /* half the pairs compare two probes, half a probe with p */
        n.v[0] = uniform(&g->rng, -r, r);
        n.v[1] = uniform(&g->rng, -r, r);
    }
    return n;
}

/* Information gain of splitting val[0..n) at threshold t. */
static double gain_at(const grower *g, const sample *s, long n, int32_t t, double e_all)
{
    long hl[NC] = {0}, hr[NC] = {0}, nl = 0;
    for (long i = 0; i < n; i++) {
        if (g->val[i] < t) hl[s[i].label]++, nl++;
        else hr[s[i].label]++;
    }
    if (nl == 0 || nl == n) return -1;
    return e_all - ((double)nl * entropy(hl, nl) + (double)(n - nl) * entropy(hr, n - nl)) / n;
}

/* The best split of s[0..n); *best_gain < 0 when none splits. */
static cub_forest_node best_split(grower *g, sample *s, long n, double e_all, double *best_gain)
{
    cub_forest_node best = {{0, 0}, {0, 0}, 0, 0, 0};
    *best_gain = -1;
    for (int f = 0; f < g->p->features; f++) {
        cub_forest_node cand = random_node(g);
        for (long i = 0; i < n; i++)
            g->val[i] = feature_of(g, &s[i], &cand);
        for (int t = 0; t < g->p->thresholds; t++) {
            cand.threshold_mm = g->val[next(&g->rng) % (uint64_t)n] + 1;
            double gain = gain_at(g, s, n, cand.threshold_mm, e_all);
            if (gain > *best_gain) *best_gain = gain, best = cand;
        }
    }
    return best;
}

/* Samples going left first; returns how many. */
static long partition(grower *g, sample *s, long n, const cub_forest_node *node)
{
    long m = 0;
    for (long i = 0; i < n; i++)
        if (feature_of(g, &s[i], node) < node->threshold_mm) {
            sample t = s[m];
            s[m++] = s[i];
            s[i] = t;
        }
    return m;
}

static uint32_t grow_node(grower *g, sample *s, long n, int depth)
{
    long h[NC] = {0};
    for (long i = 0; i < n; i++)
        h[s[i].label]++;
    double e = entropy(h, n), gain = -1;
    cub_forest_node node = {{0, 0}, {0, 0}, 0, 0, 0};
    if (depth < g->p->depth && n >= g->p->min_samples && e > 0) node = best_split(g, s, n, e, &gain);
    if (gain <= 0 || g->failed) return make_leaf(g, h, n);
    if (g->nn == g->node_cap) {
        g->node_cap = g->node_cap ? 2 * g->node_cap : 256;
        cub_forest_node *b = realloc(g->nodes, (size_t)g->node_cap * sizeof(*b));
        if (!b) return g->failed = 1, make_leaf(g, h, n);
        g->nodes = b;
    }
    uint32_t me = g->nn++;
    long m = partition(g, s, n, &node);
    node.left = grow_node(g, s, m, depth + 1);
    node.right = grow_node(g, s + m, n - m, depth + 1);
    g->nodes[me] = node;
    return me;
}

/* The tree's own pixels: pixels_per_frame body pixels of every frame. */
static long draw_samples(grower *g)
{
    long n = 0;
    static int32_t body[NPIX];
    for (int k = 0; k < g->set->n; k++) {
        const cub_ft_frame *fr = &g->set->frames[k];
        int nb = 0;
        for (int i = 0; i < NPIX; i++)
            if (fr->mm[i] && fr->part[i]) body[nb++] = i;
        for (int j = 0; j < g->p->pixels_per_frame && nb; j++) {
            int i = body[next(&g->rng) % (uint64_t)nb];
            g->s[n++] = (sample){k, i % CUB_KINECT_WIDTH, i / CUB_KINECT_WIDTH, fr->part[i]};
        }
    }
    return n;
}

static void put32(uint8_t *b, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        b[i] = (uint8_t)(v >> (8 * i));
}

static uint8_t *write_asset(const grower *g, const uint32_t *roots, int trees, size_t *len)
{
    *len = CUB_FOREST_HEADER_BYTES + 4 * (size_t)trees + (size_t)g->nn * CUB_FOREST_NODE_BYTES +
           (size_t)g->nl * NC * 2;
    uint8_t *b = calloc(1, *len), *p = b;
    if (!b) return NULL;
    memcpy(p, "CUBFRST1", 8);
    p[8] = CUB_FOREST_VERSION, p[10] = NC, p[12] = (uint8_t)trees;
    put32(p + 16, g->nn);
    put32(p + 20, g->nl);
    p += CUB_FOREST_HEADER_BYTES;
    for (int t = 0; t < trees; t++, p += 4)
        put32(p, roots[t]);
    for (uint32_t i = 0; i < g->nn; i++, p += CUB_FOREST_NODE_BYTES) {
        const cub_forest_node *n = &g->nodes[i];
        uint32_t w[7] = {(uint32_t)n->u[0], (uint32_t)n->u[1],        (uint32_t)n->v[0], (uint32_t)n->v[1],
                         (uint32_t)n->threshold_mm, n->left, n->right};
        for (int k = 0; k < 7; k++)
            put32(p + 4 * k, w[k]);
    }
    for (size_t i = 0; i < (size_t)g->nl * NC; i++, p += 2)
        p[0] = (uint8_t)g->leaves[i], p[1] = (uint8_t)(g->leaves[i] >> 8);
    return b;
}

cub_err cub_ft_train(const cub_ft_set *set, const cub_ft_params *p, uint8_t **asset, size_t *len)
{
    if (!set || !p || !asset || !len || set->n < 1 || p->trees < 1 ||
        p->trees > CUB_FOREST_MAX_TREES || p->pixels_per_frame < 1 || p->features < 1 ||
        p->thresholds < 1 || p->max_offset < 1 || p->max_offset > CUB_FOREST_MAX_OFFSET)
        return CUB_ERR_ARG;
    grower g = {.set = set, .p = p, .rng = p->seed};
    size_t most = (size_t)set->n * (size_t)p->pixels_per_frame;
    g.s = malloc(most * sizeof(sample));
    g.val = malloc(most * sizeof(int32_t));
    uint32_t roots[CUB_FOREST_MAX_TREES];
    g.failed = !g.s || !g.val;
    for (int t = 0; t < p->trees && !g.failed; t++) {
        long n = draw_samples(&g);
        roots[t] = grow_node(&g, g.s, n, 0);
    }
    *asset = g.failed ? NULL : write_asset(&g, roots, p->trees, len);
    free(g.s);
    free(g.val);
    free(g.nodes);
    free(g.leaves);
    return *asset ? CUB_OK : CUB_ERR_NOMEM;
}

/* The forest's loader (every byte checked before a view is handed out)
 * and its evaluation (integers only). Layout: cub/forest.h. */
#include <string.h>

#include "cub/forest.h"

static uint32_t rd_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static uint16_t rd_u16(const uint8_t *p)
{
    return (uint16_t)(p[0] | p[1] << 8);
}

static cub_err refuse(cub_forest_problem *why, const char *what, size_t offset)
{
    if (why) {
        why->what = what;
        why->offset = offset;
    }
    return CUB_ERR_FORMAT;
}

/* A child reference made at byte offset `at` of node `from` (or a root
 * when from < 0) must name a later node or an existing leaf. */
static const char *bad_ref(const cub_forest *f, uint32_t ref, int64_t from)
{
    if (ref & CUB_FOREST_LEAF_BIT)
        return (ref & ~CUB_FOREST_LEAF_BIT) < f->leaf_count ? NULL : "leaf index out of range";
    if (ref >= f->node_count) return "node index out of range";
    return (int64_t)ref > from ? NULL : "a child must come after its node (a cycle)";
}

static int offset_ok(int32_t v)
{
    return v >= -CUB_FOREST_MAX_OFFSET && v <= CUB_FOREST_MAX_OFFSET;
}

static cub_err check_nodes(const cub_forest *f, cub_forest_problem *why)
{
    for (int t = 0; t < f->trees; t++) {
        const char *bad = bad_ref(f, rd_u32(f->roots + 4 * t), -1);
        if (bad) return refuse(why, bad, CUB_FOREST_HEADER_BYTES + 4 * (size_t)t);
    }
    size_t base = CUB_FOREST_HEADER_BYTES + 4 * (size_t)f->trees;
    for (uint32_t i = 0; i < f->node_count; i++) {
        cub_forest_node n = cub_forest_node_at(f, i);
        size_t at = base + (size_t)i * CUB_FOREST_NODE_BYTES;
        if (!offset_ok(n.u[0]) || !offset_ok(n.u[1]) || !offset_ok(n.v[0]) || !offset_ok(n.v[1]))
            return refuse(why, "probe offset beyond 2^24 pixel·mm", at);
        const char *bad = bad_ref(f, n.left, i);
        if (!bad) bad = bad_ref(f, n.right, i);
        if (bad) return refuse(why, bad, at + 20);
    }
    return CUB_OK;
}

cub_err cub_forest_open(const void *data, size_t len, cub_forest *f, cub_forest_problem *why)
{
    if (!data || !f) return CUB_ERR_ARG;
    const uint8_t *b = data;
    memset(f, 0, sizeof(*f));
    if (len < CUB_FOREST_HEADER_BYTES) return refuse(why, "shorter than the header", len);
    if (memcmp(b, "CUBFRST1", 8) != 0) return refuse(why, "not a forest (magic)", 0);
    if (rd_u16(b + 8) != CUB_FOREST_VERSION) return refuse(why, "unknown version", 8);
    f->classes = rd_u16(b + 10);
    f->trees = rd_u16(b + 12);
    if (f->classes < 1 || f->classes > CUB_FOREST_MAX_CLASSES)
        return refuse(why, "classes not in 1..64", 10);
    if (f->trees < 1 || f->trees > CUB_FOREST_MAX_TREES) return refuse(why, "trees not in 1..64", 12);
    if (rd_u16(b + 14) != 0) return refuse(why, "reserved field not 0", 14);
    f->node_count = rd_u32(b + 16);
    f->leaf_count = rd_u32(b + 20);
    if (f->node_count >= CUB_FOREST_LEAF_BIT || f->leaf_count >= CUB_FOREST_LEAF_BIT)
        return refuse(why, "too many nodes or leaves", 16);
    /* 64-bit sizes: no count can wrap the sum */
    uint64_t need = CUB_FOREST_HEADER_BYTES + 4ull * (uint64_t)f->trees +
                    (uint64_t)f->node_count * CUB_FOREST_NODE_BYTES +
                    (uint64_t)f->leaf_count * (uint64_t)f->classes * 2;
    if (need > len) return refuse(why, "truncated: the counts need more bytes", len);
    if (need < len) return refuse(why, "bytes after the last leaf", (size_t)need);
    f->roots = b + CUB_FOREST_HEADER_BYTES;
    f->nodes = f->roots + 4 * f->trees;
    f->leaves = f->nodes + (size_t)f->node_count * CUB_FOREST_NODE_BYTES;
    cub_err err = check_nodes(f, why);
    if (err) memset(f, 0, sizeof(*f));
    return err;
}

cub_forest_node cub_forest_node_at(const cub_forest *f, uint32_t i)
{
    const uint8_t *p = f->nodes + (size_t)i * CUB_FOREST_NODE_BYTES;
    cub_forest_node n;
    n.u[0] = (int32_t)rd_u32(p);
    n.u[1] = (int32_t)rd_u32(p + 4);
    n.v[0] = (int32_t)rd_u32(p + 8);
    n.v[1] = (int32_t)rd_u32(p + 12);
    n.threshold_mm = (int32_t)rd_u32(p + 16);
    n.left = rd_u32(p + 20);
    n.right = rd_u32(p + 24);
    return n;
}

/* Division by a pixel's depth d without dividing (Granlund & Montgomery,
 * PLDI 1994): for |n| < 2^25 and 0 < d < 2^13, with m = ceil(2^38 / d),
 * trunc(n / d) = sign(n) * (|n| m >> 38) exactly (m d - 2^38 < 2^13, so
 * the error |n| (m d - 2^38) / 2^38 stays below 1 / d). A descent divides
 * four offsets a node by the same d: one division a pixel instead. Depths
 * from 8192 mm (beyond the Kinect's table) divide. */
#define RECIP_SHIFT 38
typedef struct recip {
    int32_t d;
    uint64_t m; /* 0: divide */
} recip;

static recip recip_of(int32_t d)
{
    recip r = {d, 0};
    if (d > 0 && d < (1 << 13)) r.m = (((uint64_t)1 << RECIP_SHIFT) + (uint64_t)d - 1) / (uint64_t)d;
    return r;
}

static int64_t div_by(int32_t n, recip r)
{
    if (!r.m) return n / r.d;
    uint64_t a = n < 0 ? (uint64_t)(-(int64_t)n) : (uint64_t)n;
    int64_t q = (int64_t)((a * r.m) >> RECIP_SHIFT);
    return n < 0 ? -q : q;
}

static int32_t probe_r(const cub_forest_image *im, int x, int y, recip r, const int32_t off[2])
{
    int64_t px = x + div_by(off[0], r), py = y + div_by(off[1], r);
    if (px < 0 || py < 0 || px >= im->w || py >= im->h) return CUB_FOREST_FAR_MM;
    uint16_t d = im->mm[py * im->w + px];
    return d ? d : CUB_FOREST_FAR_MM;
}

int32_t cub_forest_probe(const cub_forest_image *im, int x, int y, int32_t d_mm,
                         const int32_t off[2])
{
    return probe_r(im, x, y, recip_of(d_mm), off);
}

static int32_t feature_r(const cub_forest_image *im, int x, int y, recip r, const cub_forest_node *n)
{
    return probe_r(im, x, y, r, n->u) - probe_r(im, x, y, r, n->v);
}

int32_t cub_forest_feature(const cub_forest_image *im, int x, int y, const cub_forest_node *n)
{
    int32_t d = im->mm[y * im->w + x];
    if (!d) return 0; /* both probes would read far */
    return feature_r(im, x, y, recip_of(d), n);
}

/* The leaf tree t reaches from p, whose depth's reciprocal is r (p has a
 * reading; without one every feature is 0). */
static uint32_t descend_r(const cub_forest *f, int t, const cub_forest_image *im, int x, int y,
                          const recip *r)
{
    uint32_t ref = rd_u32(f->roots + 4 * t);
    while (!(ref & CUB_FOREST_LEAF_BIT)) {
        cub_forest_node n = cub_forest_node_at(f, ref);
        int32_t v = r ? feature_r(im, x, y, *r, &n) : 0;
        ref = v < n.threshold_mm ? n.left : n.right;
    }
    return ref & ~CUB_FOREST_LEAF_BIT;
}

uint32_t cub_forest_descend(const cub_forest *f, int t, const cub_forest_image *im, int x, int y)
{
    int32_t d = im->mm[y * im->w + x];
    recip r = recip_of(d);
    return descend_r(f, t, im, x, y, d ? &r : NULL);
}

int cub_forest_classify(const cub_forest *f, const cub_forest_image *im, int x, int y,
                        uint32_t *score)
{
    for (int c = 0; c < f->classes; c++)
        score[c] = 0;
    int32_t d = im->mm[y * im->w + x];
    recip r = recip_of(d); /* once for every tree */
    for (int t = 0; t < f->trees; t++) {
        const uint8_t *leaf = f->leaves + (size_t)descend_r(f, t, im, x, y, d ? &r : NULL) * 2 * f->classes;
        for (int c = 0; c < f->classes; c++)
            score[c] += rd_u16(leaf + 2 * c);
    }
    int best = 0;
    for (int c = 1; c < f->classes; c++)
        if (score[c] > score[best]) best = c;
    return best;
}

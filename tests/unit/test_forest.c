/* firmware/forest: a hand-made two-tree forest on a hand-made depth image:
 * the probes scale with depth and truncate towards zero, off-image and
 * no-reading probes read far, the trees' leaves add up, and the loader
 * refuses every broken asset with the offset of the fault. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/forest.h"

#define IW 320
#define IH 240
#define ROOTS 24
#define NODE0 (ROOTS + 8)

static void wr16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)v, p[1] = (uint8_t)(v >> 8);
}

static void wr32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        p[i] = (uint8_t)(v >> (8 * i));
}

/* Tree 0: one split, d(p + (100000, 0) / d) - d(p) < 500 mm -> leaf 0
 * (class 1 likely), else leaf 1 (class 2). Tree 1: leaf 2 alone (class 0
 * a little). 3 classes. */
static size_t make_forest(uint8_t *b)
{
    memset(b, 0, 200);
    memcpy(b, "CUBFRST1", 8);
    wr16(b + 8, 1), wr16(b + 10, 3), wr16(b + 12, 2);
    wr32(b + 16, 1), wr32(b + 20, 3);
    wr32(b + ROOTS, 0), wr32(b + ROOTS + 4, CUB_FOREST_LEAF_BIT | 2);
    uint8_t *n = b + NODE0;
    wr32(n, 100000), wr32(n + 16, 500);
    wr32(n + 20, CUB_FOREST_LEAF_BIT | 0), wr32(n + 24, CUB_FOREST_LEAF_BIT | 1);
    uint16_t leaves[3][3] = {{1000, 60000, 4535}, {1000, 4535, 60000}, {30000, 0, 0}};
    uint8_t *l = n + CUB_FOREST_NODE_BYTES;
    for (int i = 0; i < 9; i++)
        wr16(l + 2 * i, leaves[i / 3][i % 3]);
    return (size_t)(l + 18 - b);
}

/* make_forest's bytes, opened (static: the view outlives the call). */
static cub_forest made_forest(void)
{
    static uint8_t b[200];
    size_t len = make_forest(b);
    cub_forest f;
    cub_forest_problem why = {0};
    assert_int_equal(cub_forest_open(b, len, &f, &why), CUB_OK);
    return f;
}

/* A box of depth mm over columns [x0, x1), rows 50..149; no reading elsewhere. */
static cub_forest_image box_image(uint16_t *mm, uint16_t depth, int x0, int x1)
{
    memset(mm, 0, IW * IH * sizeof(*mm));
    for (int y = 50; y < 150; y++)
        for (int x = x0; x < x1; x++)
            mm[y * IW + x] = depth;
    cub_forest_image im = {mm, IW, IH};
    return im;
}

static void probes_scale_with_depth(void **state)
{
    (void)state;
    static uint16_t mm[IW * IH];
    cub_forest_image im = box_image(mm, 1000, 50, 200);
    mm[100 * IW + 98] = 777;
    int32_t off[2] = {-1999, 0}; /* -1.999 px: truncated to -1 */
    assert_int_equal(cub_forest_probe(&im, 99, 100, 1000, off), 777);
    int32_t right[2] = {100000, 0};
    assert_int_equal(cub_forest_probe(&im, 60, 100, 1000, right), 1000);  /* x 160 */
    assert_int_equal(cub_forest_probe(&im, 60, 100, 500, right), 10000);   /* x 260: none */
    assert_int_equal(cub_forest_probe(&im, 300, 100, 1000, right), 10000); /* off image */
    int32_t up[2] = {0, -200000};
    assert_int_equal(cub_forest_probe(&im, 60, 100, 1000, up), CUB_FOREST_FAR_MM);
}

static void trees_add_up(void **state)
{
    (void)state;
    static uint16_t mm[IW * IH];
    cub_forest f = made_forest();
    uint32_t score[3];
    cub_forest_image near = box_image(mm, 1000, 50, 200);
    /* probe 100 px right: on the box from x 60, off it from x 150 */
    assert_int_equal(cub_forest_classify(&f, &near, 60, 100, score), 1);
    assert_int_equal(score[0], 31000);
    assert_int_equal(score[1], 60000);
    assert_int_equal(cub_forest_classify(&f, &near, 150, 100, score), 2);
    /* twice as far, the probe reaches 50 px: x 140 still on the box */
    cub_forest_image far = box_image(mm, 2000, 50, 200);
    assert_int_equal(cub_forest_classify(&f, &far, 140, 100, score), 1);
    assert_int_equal(cub_forest_classify(&f, &far, 150, 100, score), 2);
    /* no reading at p: f = 0 */
    assert_int_equal(cub_forest_classify(&f, &far, 10, 10, score), 1);
}

typedef struct fault {
    size_t at;     /* byte to overwrite (SIZE_MAX: change the length) */
    uint32_t val;  /* a u32 there, or the length change */
    int wide;      /* 4: u32, 2: u16, 1: byte */
    const char *what;
    size_t offset; /* SIZE_MAX: the length */
} fault;

static void loader_refuses_broken_assets(void **state)
{
    (void)state;
    static uint8_t good[200], b[200];
    size_t len = make_forest(good);
    const fault faults[] = {
        {0, 'X', 1, "not a forest (magic)", 0},
        {8, 2, 2, "unknown version", 8},
        {10, 0, 2, "classes not in 1..64", 10},
        {12, 65, 2, "trees not in 1..64", 12},
        {14, 1, 2, "reserved field not 0", 14},
        {16, 2, 4, "truncated: the counts need more bytes", SIZE_MAX},
        {16, 0x80000000u, 4, "too many nodes or leaves", 16},
        {ROOTS, 5, 4, "node index out of range", ROOTS},
        {ROOTS + 4, CUB_FOREST_LEAF_BIT | 3, 4, "leaf index out of range", ROOTS + 4},
        {NODE0 + 20, 0, 4, "a child must come after its node (a cycle)", NODE0 + 20},
        {NODE0 + 24, 7, 4, "node index out of range", NODE0 + 20},
        {NODE0 + 8, (1u << 24) + 1, 4, "probe offset beyond 2^24 pixel·mm", NODE0},
        {NODE0 + 4, (uint32_t)-(1 << 24) - 1, 4, "probe offset beyond 2^24 pixel·mm", NODE0},
    };
    for (size_t k = 0; k < sizeof(faults) / sizeof(faults[0]); k++) {
        const fault *q = &faults[k];
        memcpy(b, good, sizeof(b));
        if (q->wide == 4) wr32(b + q->at, q->val);
        if (q->wide == 2) wr16(b + q->at, (uint16_t)q->val);
        if (q->wide == 1) b[q->at] = (uint8_t)q->val;
        cub_forest f;
        cub_forest_problem why = {0};
        assert_int_equal(cub_forest_open(b, len, &f, &why), CUB_ERR_FORMAT);
        assert_string_equal(why.what, q->what);
        assert_int_equal(why.offset, q->offset == SIZE_MAX ? len : q->offset);
    }
    cub_forest f;
    cub_forest_problem why = {0};
    assert_int_equal(cub_forest_open(good, len + 1, &f, &why), CUB_ERR_FORMAT);
    assert_string_equal(why.what, "bytes after the last leaf");
    assert_int_equal(why.offset, len);
    for (size_t n = 0; n < len; n++) /* every prefix */
        assert_int_equal(cub_forest_open(good, n, &f, &why), CUB_ERR_FORMAT);
    assert_int_equal(cub_forest_open(NULL, len, &f, &why), CUB_ERR_ARG);
}

/* ---- part proposals ---- */

#define LW 640
#define LH 480
#define MAXPTS 20000

static int32_t pts_mm[MAXPTS][3];
static uint16_t pts_prob[MAXPTS * 3];
static uint8_t lab_img[LW * LH];
static uint16_t lmm[LW * LH];

/* The proposal lies within 4 mm (x, y) of pixel (u, v) at z. */
static int at_pixel(const cub_forest_proposal *pr, int u, int v, int32_t z)
{
    int32_t c[3];
    cub_forest_point_at(u, v, z, c);
    return pr->found && abs(pr->mm[0] - c[0]) <= 4 && abs(pr->mm[1] - c[1]) <= 4;
}

/* A disc of `label` (prob q) of radius r px around (cu, cv) at depth z
 * painted into a label image and a depth image. */
static void disc(uint8_t *label, uint16_t *mm, int cu, int cv, int r, int lab, uint16_t z)
{
    for (int v = cv - r; v <= cv + r; v++)
        for (int u = cu - r; u <= cu + r; u++)
            if ((u - cu) * (u - cu) + (v - cv) * (v - cv) <= r * r)
                label[v * LW + u] = (uint8_t)lab, mm[v * LW + u] = z;
}

/* The points of a label image: every stride-th labelled pixel, its label's
 * probability q, the rest shared by class 0 (3 classes). */
static cub_forest_points label_points(const uint8_t *label, const uint16_t *mm, int stride,
                                      uint16_t q)
{
    cub_forest_points p = {pts_mm, pts_prob, 0, MAXPTS, 3, stride, NULL};
    for (int v = 0; v < LH; v += stride)
        for (int u = 0; u < LW; u += stride) {
            if (!label[v * LW + u] || p.n == MAXPTS) continue;
            uint16_t *pr = pts_prob + 3 * p.n;
            pr[0] = (uint16_t)(65535 - q), pr[1] = pr[2] = 0;
            pr[label[v * LW + u]] = q;
            cub_forest_point_at(u, v, mm[v * LW + u], pts_mm[p.n++]);
        }
    return p;
}

static void points_are_the_camera_model(void **state)
{
    (void)state;
    int32_t m[3];
    cub_forest_point_at(320 + 58, 240 - 29, 2000, m); /* 58 px at 2 m: 200 mm */
    assert_int_equal(m[0], 200);
    assert_int_equal(m[1], 100);
    assert_int_equal(m[2], 2000);
    cub_forest_point_at(320 - 1, 240, 579, m); /* truncated towards zero */
    assert_int_equal(m[0], 0);
}

/* Two discs of one part: the larger surface wins, the proposal sits at its
 * centre pushed back, its share and area say how much voted for it. */
static void the_largest_mode_wins_pushed_back(void **state)
{
    (void)state;
    memset(lab_img, 0, sizeof(lab_img)), memset(lmm, 0, sizeof(lmm));
    disc(lab_img, lmm, 200, 200, 30, 1, 2000);
    disc(lab_img, lmm, 450, 300, 12, 1, 2000);
    disc(lab_img, lmm, 320, 100, 15, 2, 1500);
    cub_forest_points p = label_points(lab_img, lmm, 2, 65535);
    cub_forest_shift sh = {150, 6554, 40};
    cub_forest_proposal pr;
    cub_forest_propose(&p, 1, &sh, &pr);
    assert_true(at_pixel(&pr, 200, 200, 2000));
    assert_int_equal(pr.mm[2], 2000 + 40);
    /* a 30 px disc at 2 m is about pi (30 * 2000 / 580)^2 = 33600 mm^2 */
    assert_in_range(pr.area_mm2, 31000, 36000);
    /* the small disc holds (12/30)^2 of the big one's weight: the mode 900/1044 */
    assert_in_range(pr.share, CUB_Q16_ONE * 80 / 100, CUB_Q16_ONE * 90 / 100);
    /* the other part, at its own disc */
    cub_forest_propose(&p, 2, &sh, &pr);
    assert_true(at_pixel(&pr, 320, 100, 1500));
    /* below the probability floor, nothing is proposed */
    cub_forest_points weak = label_points(lab_img, lmm, 2, 5000);
    cub_forest_propose(&weak, 1, &sh, &pr);
    assert_int_equal(pr.found, 0);
    sh.min_prob = 0;
    cub_forest_propose(&weak, 1, &sh, &pr);
    assert_int_equal(pr.found, 1);
}

/* The part's points listed once (part_pts, the box's speed) give the same
 * proposal to the last bit as visiting every point. */
static void listing_a_parts_points_changes_nothing(void **state)
{
    (void)state;
    static int32_t list[MAXPTS];
    memset(lab_img, 0, sizeof(lab_img)), memset(lmm, 0, sizeof(lmm));
    disc(lab_img, lmm, 200, 200, 30, 1, 2000);
    disc(lab_img, lmm, 450, 300, 12, 1, 2300);
    disc(lab_img, lmm, 320, 100, 15, 2, 1500);
    cub_forest_points p = label_points(lab_img, lmm, 2, 40000);
    for (int part = 0; part < 3; part++) {
        cub_forest_shift sh = {120, 9175, 30};
        cub_forest_proposal every, listed;
        p.part_pts = NULL;
        cub_forest_propose(&p, part, &sh, &every);
        p.part_pts = list;
        cub_forest_propose(&p, part, &sh, &listed);
        assert_memory_equal(&every, &listed, sizeof(every));
    }
}

/* A pixel far away covers more of the body than one near: fewer pixels
 * far win when their surface is larger (z^2 weighting), as the body's
 * real size decides, not its pixel count. */
static void depth_squared_weighs_the_surface(void **state)
{
    (void)state;
    memset(lab_img, 0, sizeof(lab_img)), memset(lmm, 0, sizeof(lmm));
    disc(lab_img, lmm, 150, 240, 20, 1, 1500); /* more pixels, 1.5 m */
    disc(lab_img, lmm, 450, 240, 17, 1, 2500); /* fewer pixels, 2.5 m: more surface */
    cub_forest_points p = label_points(lab_img, lmm, 1, 65535);
    cub_forest_shift sh = {200, 0, 0};
    cub_forest_proposal pr;
    cub_forest_propose(&p, 1, &sh, &pr);
    assert_true(at_pixel(&pr, 450, 240, 2500) && abs(pr.mm[2] - 2500) <= 4);
}

/* gather: every stride-th pixel with a reading, the trees' mean. */
static void gather_keeps_the_trees_mean(void **state)
{
    (void)state;
    static uint16_t mm[IW * IH];
    cub_forest f = made_forest();
    cub_forest_image im = box_image(mm, 1000, 50, 200);
    cub_forest_points p = {pts_mm, pts_prob, 0, MAXPTS, 3, 0, NULL};
    assert_int_equal(cub_forest_gather(&f, &im, 5, &p), 30 * 20);
    assert_int_equal(p.stride, 5);
    /* the first point: (50, 50), probe at x 150 on the box: leaf 0 + leaf 2 */
    assert_int_equal(pts_prob[0], 31000 / 2);
    assert_int_equal(pts_prob[1], 60000 / 2);
    p.capacity = 7;
    assert_int_equal(cub_forest_gather(&f, &im, 5, &p), 7);
    p.classes = 2;
    assert_int_equal(cub_forest_gather(&f, &im, 5, &p), 0);
}

/* A probe's offset divided by the depth: C's truncating division for
 * every depth the Kinect reads and offsets up to the loader's 2^24 (the
 * evaluator multiplies by a reciprocal instead: it must not differ). */
static void probes_divide_as_c_does(void **state)
{
    (void)state;
    static uint16_t mm[IW * IH];
    const int32_t offs[] = {0, 1, -1, 7, -7, 999, -1000, 65535, -65536, 1234567, -7654321,
                            (1 << 24) - 1, -(1 << 24) + 1, 1 << 24, -(1 << 24)};
    cub_forest_image im = {mm, IW, IH};
    for (int32_t d = 1; d < 20000; d += 1 + d / 64) {
        for (int i = 0; i < IW * IH; i++)
            mm[i] = (uint16_t)(1 + i % 4000);
        for (size_t k = 0; k < sizeof(offs) / sizeof(offs[0]); k++) {
            int32_t off[2] = {offs[k], -offs[k]}, q0 = offs[k] / d, q1 = -offs[k] / d;
            int x = IW / 2, y = IH / 2;
            int64_t px = x + q0, py = y + q1;
            int32_t want = px < 0 || py < 0 || px >= IW || py >= IH ? CUB_FOREST_FAR_MM
                                                                     : mm[py * IW + px];
            assert_int_equal(cub_forest_probe(&im, x, y, d, off), want);
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(probes_scale_with_depth),
        cmocka_unit_test(probes_divide_as_c_does),
        cmocka_unit_test(trees_add_up),
        cmocka_unit_test(loader_refuses_broken_assets),
        cmocka_unit_test(points_are_the_camera_model),
        cmocka_unit_test(the_largest_mode_wins_pushed_back),
        cmocka_unit_test(listing_a_parts_points_changes_nothing),
        cmocka_unit_test(depth_squared_weighs_the_surface),
        cmocka_unit_test(gather_keeps_the_trees_mean),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

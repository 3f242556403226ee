/* firmware/forest: a hand-made two-tree forest on a hand-made depth image:
 * the probes scale with depth and truncate towards zero, off-image and
 * no-reading probes read far, the trees' leaves add up, and the loader
 * refuses every broken asset with the offset of the fault. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
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
    static uint8_t b[200];
    static uint16_t mm[IW * IH];
    size_t len = make_forest(b);
    cub_forest f;
    cub_forest_problem why = {0};
    assert_int_equal(cub_forest_open(b, len, &f, &why), CUB_OK);
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(probes_scale_with_depth),
        cmocka_unit_test(trees_add_up),
        cmocka_unit_test(loader_refuses_broken_assets),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

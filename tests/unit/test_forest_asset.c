/* The committed body-part forest (assets/forest/body.forest, made by
 * scripts/make_forest.sh; its bytes are checked against their recorded
 * SHA-256 by the ctest forest_asset_hash): it opens through the firmware's
 * loader, has the trained shape (16 classes: 15 parts and none; 3 trees),
 * every leaf is a distribution (the trainer's floor(count * 65535 / n)
 * sums to 65535 less at most one per class), and every pixel of a depth
 * image descends to a class. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/forest.h"

#define IW 640
#define IH 480
#define CLASSES 16

static uint8_t *bytes;
static size_t len;
static cub_forest forest;

static int read_asset(void **state)
{
    (void)state;
    const char *src = getenv("CUB_SOURCE_DIR");
    char path[512];
    snprintf(path, sizeof(path), "%s/assets/forest/body.forest", src ? src : ".");
    FILE *fp = fopen(path, "rb");
    if (!fp) return fprintf(stderr, "test_forest_asset: cannot open %s\n", path), -1;
    fseek(fp, 0, SEEK_END);
    len = (size_t)ftell(fp);
    rewind(fp);
    bytes = malloc(len);
    size_t got = bytes ? fread(bytes, 1, len, fp) : 0;
    fclose(fp);
    return got == len ? 0 : -1;
}

static int free_asset(void **state)
{
    (void)state;
    free(bytes);
    return 0;
}

static void opens_with_the_trained_shape(void **state)
{
    (void)state;
    cub_forest_problem why = {0};
    assert_int_equal(cub_forest_open(bytes, len, &forest, &why), CUB_OK);
    assert_int_equal(forest.classes, CLASSES);
    assert_int_equal(forest.trees, 3);
    printf("forest asset: %zu bytes, %d trees, %u nodes, %u leaves\n", len, forest.trees,
           forest.node_count, forest.leaf_count);
    assert_true(forest.node_count > 1000); /* trained, not a stub */
}

static void every_leaf_is_a_distribution(void **state)
{
    (void)state;
    for (uint32_t i = 0; i < forest.leaf_count; i++) {
        uint32_t sum = 0;
        for (int c = 0; c < CLASSES; c++) {
            const uint8_t *p = forest.leaves + 2 * ((size_t)i * CLASSES + (size_t)c);
            sum += (uint32_t)p[0] | (uint32_t)p[1] << 8;
        }
        if (sum > 65535 || sum < 65535 - (CLASSES - 1))
            fail_msg("leaf %u sums to %u", i, sum);
    }
}

/* A child-sized blob (head disc over a torso box, 2 m away): every pixel,
 * body or not, ends in a leaf and gets a class; the disc on top is a head
 * (the forest names 91-97 % of head pixels right on held-out folds). */
static void every_pixel_gets_a_class(void **state)
{
    (void)state;
    static uint16_t mm[IW * IH];
    for (int y = 0; y < IH; y++)
        for (int x = 0; x < IW; x++) {
            int head = (x - 320) * (x - 320) + (y - 120) * (y - 120) < 30 * 30;
            int torso = x >= 280 && x < 360 && y >= 150 && y < 330;
            mm[y * IW + x] = (uint16_t)(head || torso ? 2000 + (x & 7) : 0);
        }
    cub_forest_image im = {mm, IW, IH};
    uint32_t score[CLASSES];
    for (int y = 0; y < IH; y += 3)
        for (int x = 0; x < IW; x += 3) {
            int c = cub_forest_classify(&forest, &im, x, y, score);
            assert_in_range(c, 0, CLASSES - 1);
        }
    assert_int_equal(cub_forest_classify(&forest, &im, 320, 110, score), 1 /* head */);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(opens_with_the_trained_shape),
        cmocka_unit_test(every_leaf_is_a_distribution),
        cmocka_unit_test(every_pixel_gets_a_class),
    };
    return cmocka_run_group_tests(tests, read_asset, free_asset);
}

/* PNG I/O (app/io/png.c): what bad input gets, then exact round trips. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <cmocka.h>

#include "cub/png.h"

static void out_path(char *buf, size_t size, const char *name)
{
    snprintf(buf, size, "%s/%s", CUB_GOLDEN_OUT_DIR, name);
}

static void test_png_rejects_bad_arguments(void **state)
{
    uint8_t px[4] = {0};
    uint8_t *img = NULL;
    int w = 0, h = 0;
    char path[1024];
    out_path(path, sizeof path, "never.png");
    assert_int_equal(cub_png_write(NULL, px, 1, 1), CUB_ERR_ARG);
    assert_int_equal(cub_png_write(path, NULL, 1, 1), CUB_ERR_ARG);
    assert_int_equal(cub_png_write(path, px, 0, 1), CUB_ERR_ARG);
    assert_int_equal(cub_png_read(NULL, &img, &w, &h), CUB_ERR_ARG);
    assert_int_equal(cub_png_read(path, NULL, &w, &h), CUB_ERR_ARG);
}

static void test_png_missing_file_is_io_error(void **state)
{
    uint8_t *img = (uint8_t *)1;
    int w = 7, h = 7;
    char path[1024];
    out_path(path, sizeof path, "does_not_exist.png");
    remove(path);
    assert_int_equal(cub_png_read(path, &img, &w, &h), CUB_ERR_IO);
    assert_null(img);
    assert_int_equal(w, 0);
}

static void test_png_garbage_and_truncated_are_format_errors(void **state)
{
    char path[1024];
    out_path(path, sizeof path, "garbage.png");
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fputs("this is not a PNG file at all", f);
    fclose(f);
    uint8_t *img = NULL;
    int w = 0, h = 0;
    assert_int_equal(cub_png_read(path, &img, &w, &h), CUB_ERR_FORMAT);
    assert_null(img);

    /* A real PNG cut in half: the header reads, the pixels do not. */
    uint8_t rgba[16 * 16 * 4];
    for (size_t i = 0; i < sizeof rgba; i++)
        rgba[i] = (uint8_t)(i * 37u);
    out_path(path, sizeof path, "truncated.png");
    assert_int_equal(cub_png_write(path, rgba, 16, 16), CUB_OK);
    static uint8_t bytes[1 << 16];
    f = fopen(path, "rb");
    assert_non_null(f);
    size_t len = fread(bytes, 1, sizeof bytes, f);
    fclose(f);
    assert_true(len > 60 && len < sizeof bytes);
    f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(bytes, 1, len / 2, f), len / 2);
    fclose(f);
    assert_int_not_equal(cub_png_read(path, &img, &w, &h), CUB_OK);
    assert_null(img);
}

static void test_png_round_trip_is_exact(void **state)
{
    enum { PW = 37, PH = 23 }; /* odd sizes: no row padding assumptions */
    static uint8_t rgba[PW * PH * 4];
    for (int y = 0; y < PH; y++)
        for (int x = 0; x < PW; x++) {
            uint8_t *p = rgba + 4 * (y * PW + x);
            p[0] = (uint8_t)(x * 7);
            p[1] = (uint8_t)(y * 11);
            p[2] = (uint8_t)(x * y);
            p[3] = (uint8_t)(255 - x);
        }
    char path[1024];
    out_path(path, sizeof path, "round_trip.png");
    assert_int_equal(cub_png_write(path, rgba, PW, PH), CUB_OK);
    uint8_t *back = NULL;
    int w = 0, h = 0;
    assert_int_equal(cub_png_read(path, &back, &w, &h), CUB_OK);
    assert_int_equal(w, PW);
    assert_int_equal(h, PH);
    assert_memory_equal(back, rgba, sizeof rgba);
    free(back);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_png_rejects_bad_arguments),
        cmocka_unit_test(test_png_missing_file_is_io_error),
        cmocka_unit_test(test_png_garbage_and_truncated_are_format_errors),
        cmocka_unit_test(test_png_round_trip_is_exact),
    };
    return cmocka_run_group_tests_name("png", tests, NULL, NULL);
}

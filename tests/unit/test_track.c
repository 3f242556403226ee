/* track: the depth units (raw 11-bit disparity -> millimetres). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include <cmocka.h>

#include "cub/track.h"

static double formula_mm(int raw) { return 123.6 * tan(raw / 2842.5 + 1.1863); }

static void test_no_reading_and_out_of_range_give_zero(void **s)
{
    assert_int_equal(cub_track_raw_to_mm(2047), 0);
    assert_int_equal(cub_track_raw_to_mm(2048), 0);
    assert_int_equal(cub_track_raw_to_mm(65535), 0);
    assert_int_equal(cub_track_raw_to_mm_int(2047), 0);
    /* Past the tangent's pole the formula goes negative: no reading. */
    assert_int_equal(cub_track_raw_to_mm(1500), 0);
}

static void test_table_matches_the_data_readme_formula(void **s)
{
    double worst = 0;
    int valid = 0, worst_raw = 0;
    for (int raw = 0; raw < 2047; raw++) {
        cub_q16 q = cub_track_raw_to_mm(raw);
        double want = formula_mm(raw);
        if (want <= 0 || want > 8191) {
            assert_int_equal(q, 0);
            continue;
        }
        valid++;
        double err = fabs(q / 65536.0 - want);
        if (err > worst) worst = err, worst_raw = raw;
        /* Whole mm from the 1/8 mm table: two roundings, 0.5 + 1/16 at worst. */
        assert_true(fabs(cub_track_raw_to_mm_int(raw) - want) <= 0.5625 + 1e-9);
    }
    printf("track: raw->mm max_abs_err=%.4f mm (raw %d) over %d valid raw values\n", worst,
           worst_raw, valid);
    assert_true(worst <= 0.0625 + 1e-9); /* half a Q13.3 step */
    assert_true(valid > 1000);
}

static void test_depth_grows_with_raw(void **s)
{
    for (int raw = 1; raw < 2047; raw++) {
        cub_q16 a = cub_track_raw_to_mm(raw - 1), b = cub_track_raw_to_mm(raw);
        if (a && b) assert_true(b > a);
    }
    /* The Kinect's useful range, 0.5 m to 4 m, is inside the table. */
    int seen_half = 0, seen_four = 0;
    for (int raw = 0; raw < 2047; raw++) {
        uint16_t mm = cub_track_raw_to_mm_int(raw);
        seen_half |= mm >= 495 && mm <= 505;
        seen_four |= mm >= 3950 && mm <= 4050;
    }
    assert_true(seen_half && seen_four);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_no_reading_and_out_of_range_give_zero),
        cmocka_unit_test(test_table_matches_the_data_readme_formula),
        cmocka_unit_test(test_depth_grows_with_raw),
    };
    return cmocka_run_group_tests_name("track", tests, NULL, NULL);
}

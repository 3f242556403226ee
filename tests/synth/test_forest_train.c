/* The body-part forest's trainer on real renders (skipped without
 * $CUB_DATA_DIR), kept tiny for CI: two shallow trees on 66 turning frames
 * of four shippable sources beat naming every pixel the commonest part on
 * the fifth source, left out; the same seed gives the same bytes; the
 * asset opens in the firmware; Bandai and the dog never
 * train. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "cub/forest_train.h"
#include "synth_data.h"

static const char *data_dir(void)
{
    return synth_data_dir("14_14");
}

static void load(cub_ft_set *set, const char *fold, int frames, uint64_t seed)
{
    cub_ft_render r = {data_dir(), frames, 30, seed}; /* a frame a second */
    cub_diag diag;
    for (const char *const *c = cub_ft_fold(fold); *c; c++)
        assert_int_equal(cub_ft_add_clip(set, &r, *c, &diag), CUB_OK);
}

static void beats_chance_on_an_unseen_source(void **state)
{
    (void)state;
    if (!data_dir()) skip();
    cub_ft_set train = {0}, test = {0};
    const char *train_folds[] = {"cmu13", "cmu14", "cmu_dance_sport", "animdraw"};
    for (int i = 0; i < 4; i++)
        load(&train, train_folds[i], 3, 1); /* 22 clips x 3 frames, turning */
    load(&test, "cmu_walks", 2, 1);        /* the source left out: 5 clips x 2 */
    cub_ft_params p = {.trees = 2, .depth = 10, .features = 30, .thresholds = 8,
                       .pixels_per_frame = 150, .min_samples = 10, .max_offset = 120000,
                       .seed = 1};
    uint8_t *a = NULL, *b = NULL;
    size_t na, nb;
    assert_int_equal(cub_ft_train(&train, &p, &a, &na), CUB_OK);
    assert_int_equal(cub_ft_train(&train, &p, &b, &nb), CUB_OK);
    assert_int_equal(na, nb);
    assert_memory_equal(a, b, na);
    cub_forest f;
    cub_forest_problem why = {0};
    assert_int_equal(cub_forest_open(a, na, &f, &why), CUB_OK);
    assert_int_equal(f.classes, CUB_PART_COUNT);
    cub_ft_score s = {0};
    cub_ft_score_set(&f, &test, 5, &s);
    long n = 0, right = 0, most = 0;
    for (int k = 1; k < CUB_PART_COUNT; k++) {
        n += s.n[k], right += s.right[k];
        if (s.n[k] > most) most = s.n[k];
    }
    printf("forest smoke: %ld held-out pixels, %.1f %% right, commonest part %.1f %%\n", n,
           100.0 * right / n, 100.0 * most / n);
    assert_true(n > 1000);
    assert_true(right > most + most / 3); /* a third more than chance */
    free(a), free(b);
    cub_ft_set_free(&train);
    cub_ft_set_free(&test);
}

static void only_shippable_motion_trains(void **state)
{
    (void)state;
    assert_true(cub_ft_shippable("13_29"));
    assert_true(cub_ft_shippable("jesse_dance@5"));
    assert_false(cub_ft_shippable("dataset-1_bow_childish_001"));
    assert_false(cub_ft_shippable("/x/mocap/bandai/walk.bvh"));
    assert_false(cub_ft_shippable("/x/mocap/dog/D1_001.bvh"));
    for (int i = 0; cub_ft_fold_name(i); i++)
        for (const char *const *c = cub_ft_fold(cub_ft_fold_name(i)); *c; c++)
            assert_true(cub_ft_shippable(*c));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(only_shippable_motion_trains),
        cmocka_unit_test(beats_chance_on_an_unseen_source),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

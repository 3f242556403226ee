/* The player's blob and someone else's (firmware/track/trk_grid.c,
 * trk_give_back_pieces) on a scene painted straight onto the tracker's
 * 160x120 grid: the child facing the camera at 2.4 m with its right arm
 * reaching back, its hand 160 mm behind its chest; an adult 500 mm behind
 * the child, whose left forearm rises from the adult's body to end just
 * beside the child's hand, forearm_gap_mm behind it. The two are one blob
 * by depth through hand and forearm; the test labels the blobs as
 * split_merged left them in the end to end songs (the adult's body its
 * own blob, its forearm the child's: those cells were the player's last
 * frame), then checks what the rule gives back and what it keeps. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "trk_internal.h"

#include "tracker_fixture.h"

#define CHILD_MM 2400
#define ADULT_MM 2900
#define HAND_MM (CHILD_MM + 160)
#define ARM_GY0 50 /* the child's arm: rows ARM_GY0..ARM_GY0+3 */
#define ARM_GX0 90 /* from its shoulder's column */
#define HAND_GX 109 /* to its hand's last */

static int32_t forearm_gap_mm = 120;

static void cell(int32_t gx, int32_t gy, int32_t z)
{
    int32_t i = gy * TRK_GW + gx;
    t->z[i] = (int16_t)z;
    t->x[i] = (gx * TRK_CELL_PX + 2 - CUB_KINECT_CX) * z / CUB_KINECT_FOCAL_PX;
    t->y[i] = (CUB_KINECT_CY - gy * TRK_CELL_PX - 2) * z / CUB_KINECT_FOCAL_PX;
}

/* Cell (gx, gy) is the adult's forearm: the four columns right of the
 * child's hand, from the hand's rows up to the adult's shoulder (row 20),
 * its depth running back from forearm_gap_mm behind the hand to the
 * adult's body. */
static bool on_forearm(int32_t gx, int32_t gy)
{
    return gx > HAND_GX && gx <= HAND_GX + 4 && gy >= 20 && gy <= ARM_GY0 + 3;
}

static int32_t forearm_mm(int32_t gy)
{
    int32_t tip = HAND_MM + forearm_gap_mm;
    return ADULT_MM + (tip - ADULT_MM) * (gy - 20) / (ARM_GY0 + 3 - 20);
}

/* The scene; with_adult false: the child alone. */
static void paint_scene(bool with_adult)
{
    memset(t->z, 0, sizeof t->z);
    t->up = (cub_vec3){0, CUB_Q16_ONE, 0};
    for (int32_t gy = 10; gy < 110 && with_adult; gy++)
        for (int32_t gx = HAND_GX - 4; gx < HAND_GX + 30; gx++) cell(gx, gy, ADULT_MM);
    for (int32_t gy = 25; gy < 110; gy++)
        for (int32_t gx = 70; gx < ARM_GX0; gx++) cell(gx, gy, CHILD_MM);
    for (int32_t gy = ARM_GY0; gy < ARM_GY0 + 4; gy++)
        for (int32_t gx = ARM_GX0; gx <= HAND_GX; gx++)
            cell(gx, gy, CHILD_MM + (HAND_MM - CHILD_MM) * (gx - ARM_GX0) / (HAND_GX - ARM_GX0));
    for (int32_t gy = 0; gy < TRK_GH && with_adult; gy++)
        for (int32_t gx = 0; gx < TRK_GW; gx++)
            if (on_forearm(gx, gy)) cell(gx, gy, forearm_mm(gy));
}

/* The adult's blob as trk_components measures it alone, then the whole
 * scene as one blob (the player's, 0) but for the adult's body (blob 1):
 * as split_merged parted them. The player's blob's index. */
static int32_t as_split_left_it(void)
{
    paint_scene(true);
    for (int32_t gy = 0; gy < TRK_GH; gy++)
        for (int32_t gx = 0; gx < TRK_GW; gx++)
            if (t->z[gy * TRK_GW + gx] < ADULT_MM) t->z[gy * TRK_GW + gx] = 0;
    trk_components(t);
    assert_int_equal(t->ncomps, 1);
    trk_comp adult = t->comps[0];
    paint_scene(true);
    trk_components(t);
    assert_int_equal(t->ncomps, 1); /* joined through hand and forearm */
    for (int32_t i = 0; i < TRK_CELLS; i++)
        if (t->z[i] == ADULT_MM) t->label[i] = 1;
    t->comps[1] = adult, t->ncomps = 2;
    return 0;
}

/* Cells of the forearm (or of the child's arm) labelled l. */
static int32_t forearm_cells(int16_t l)
{
    int32_t n = 0;
    for (int32_t gy = 0; gy < TRK_GH; gy++)
        for (int32_t gx = 0; gx < TRK_GW; gx++) n += on_forearm(gx, gy) && t->label[gy * TRK_GW + gx] == l;
    return n;
}

static int32_t arm_cells(int16_t l)
{
    int32_t n = 0;
    for (int32_t gy = ARM_GY0; gy < ARM_GY0 + 4; gy++)
        for (int32_t gx = ARM_GX0; gx <= HAND_GX; gx++) n += t->label[gy * TRK_GW + gx] == l;
    return n;
}

static int32_t labelled(int16_t l)
{
    int32_t n = 0;
    for (int32_t i = 0; i < TRK_CELLS; i++) n += t->label[i] == l;
    return n;
}

/* The forearm 120-160 mm behind the child's hand (the end to end songs'
 * 120-140 at the child's shoulder) goes to the adult, every cell of it;
 * the child's arm reaching back, hand included, stays the child's. */
static void test_the_adults_forearm_behind_the_hand_is_the_adults(void **st)
{
    (void)st;
    static const int32_t gap[] = {120, 140, 160};
    for (size_t k = 0; k < sizeof gap / sizeof gap[0]; k++) {
        forearm_gap_mm = gap[k];
        int32_t pid = as_split_left_it();
        int32_t glued = forearm_cells(0), all = glued + forearm_cells(1);
        assert_true(glued > 100);
        trk_give_back_pieces(t, pid);
        printf("pieces: forearm %d mm behind the hand: %d of the %d cells glued to the child given to the adult, "
               "the child's arm %d of 80 cells kept\n",
               gap[k], forearm_cells(1) - (all - glued), glued, arm_cells(0));
        assert_int_equal(forearm_cells(1), all);
        assert_int_equal(arm_cells(0), 80);
        assert_int_equal(t->comps[pid].n, labelled(0)); /* the blobs measured again */
        assert_int_equal(t->comps[1].n, labelled(1));
    }
}

/* A forearm continuous in depth with the child's hand (60 mm behind it:
 * no step between them) is not cut from it: the rule needs a step. */
static void test_a_surface_continuous_with_the_hand_stays(void **st)
{
    (void)st;
    forearm_gap_mm = 60;
    int32_t pid = as_split_left_it();
    int32_t forearm = forearm_cells(0);
    trk_give_back_pieces(t, pid);
    assert_int_equal(forearm_cells(0), forearm);
    assert_int_equal(arm_cells(0), 80);
}

/* The child alone, its arm reaching back 160 mm: nothing to give back. */
static void test_the_child_alone_keeps_its_arm(void **st)
{
    (void)st;
    paint_scene(false);
    trk_components(t);
    assert_int_equal(t->ncomps, 1);
    int32_t n = t->comps[0].n;
    trk_give_back_pieces(t, 0);
    assert_int_equal(t->comps[0].n, n);
    assert_int_equal(arm_cells(0), 80);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_the_adults_forearm_behind_the_hand_is_the_adults),
        cmocka_unit_test(test_a_surface_continuous_with_the_hand_stays),
        cmocka_unit_test(test_the_child_alone_keeps_its_arm),
    };
    return cmocka_run_group_tests(tests, tracker_fixture_open, tracker_fixture_close);
}

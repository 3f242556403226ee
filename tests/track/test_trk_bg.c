/* The tracker's background model (firmware/track/trk_bg.c) on scenes
 * painted straight onto the tracker's 160x120 grid at 10 frames a second:
 * a still object becomes background, a moving child does not, a still
 * player is not absorbed, a bumped camera forgets the room, frames with
 * no time between them learn nothing. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "trk_internal.h"

#define FRAME_US 100000

#include "tracker_fixture.h"

/* A wall at wall_mm everywhere, a box of cells gx0..gx1 x gy0..gy1 before
 * it at box_mm (0: none); no blobs, nobody's cells. */
static void paint(int32_t wall_mm, int32_t gx0, int32_t gx1, int32_t gy0, int32_t gy1, int32_t box_mm)
{
    for (int32_t gy = 0; gy < TRK_GH; gy++)
        for (int32_t gx = 0; gx < TRK_GW; gx++) {
            bool in = box_mm && gx >= gx0 && gx <= gx1 && gy >= gy0 && gy <= gy1;
            t->z[gy * TRK_GW + gx] = (int16_t)(in ? box_mm : wall_mm);
        }
    memset(t->mask, 0, sizeof t->mask);
    for (int32_t i = 0; i < TRK_CELLS; i++) t->label[i] = -1;
    t->ncomps = 0;
}

/* Cells of the box left after the background went. */
static int32_t left_of_box(int32_t gx0, int32_t gx1, int32_t gy0, int32_t gy1)
{
    int32_t n = 0;
    for (int32_t gy = gy0; gy <= gy1; gy++)
        for (int32_t gx = gx0; gx <= gx1; gx++) n += t->z[gy * TRK_GW + gx] != 0;
    return n;
}

static int32_t left_anywhere(void)
{
    int32_t n = 0;
    for (int32_t i = 0; i < TRK_CELLS; i++) n += t->z[i] != 0;
    return n;
}

/* One frame: paint, learn, then mark the box as the player's (player) and
 * remove the background; the box's cells left. */
static int32_t frame(int32_t gx0, int32_t box_mm, bool player)
{
    paint(3500, gx0, gx0 + 9, 40, 90, box_mm);
    trk_bg_learn(t, FRAME_US);
    if (player) {
        for (int32_t gy = 40; gy <= 90; gy++)
            for (int32_t gx = gx0; gx <= gx0 + 9; gx++) t->mask[gy * TRK_GW + gx] = 1;
        bool person[1] = {false};
        trk_bg_mark_people(t, person);
    }
    trk_bg_remove(t);
    return left_of_box(gx0, gx0 + 9, 40, 90);
}

/* A box (a chair) and the wall behind it stay: after a second both are
 * the room's, and nothing is left of the view. Before, all of it stays. */
static void test_still_object_becomes_background(void **st)
{
    (void)st;
    for (int k = 0; k < 5; k++) assert_int_equal(frame(70, 2500, false), 10 * 51);
    assert_int_equal(left_anywhere(), TRK_CELLS);
    for (int k = 0; k < 10; k++) frame(70, 2500, false);
    assert_int_equal(frame(70, 2500, false), 0);
    assert_int_equal(left_anywhere(), 0);
    assert_int_equal(t->bg_resets, 0); /* no bump seen */
}

/* A child-sized box that moves two cells a frame, back and forth, for 5 s:
 * never background, whole every frame once the wall is known. */
static void test_moving_child_is_not_background(void **st)
{
    (void)st;
    for (int k = 0; k < 50; k++) {
        int32_t gx0 = 40 + 2 * (k % 20 < 10 ? k % 20 : 20 - k % 20);
        assert_int_equal(frame(gx0, 2500, false), 10 * 51);
    }
    /* and the wall beside its path is background */
    int32_t outside = left_anywhere() - left_of_box(40, 69, 0, TRK_GH - 1);
    assert_int_equal(outside, 0);
}

/* The player standing still for 10 s is not absorbed; the same box not
 * marked as anybody's is, within a second and a half. */
static void test_still_player_is_not_absorbed(void **st)
{
    (void)st;
    for (int k = 0; k < 100; k++) assert_int_equal(frame(70, 2500, true), 10 * 51);
    assert_int_equal(left_anywhere(), 10 * 51);
    tracker_fixture_open(NULL);
    for (int k = 0; k < 15; k++) frame(70, 2500, false);
    assert_int_equal(frame(70, 2500, false), 0);
}

/* Nor for 40 s, longer than a moving blob that is not the player is
 * held (30 s): the player is never the room. */
static void test_player_is_never_absorbed(void **st)
{
    (void)st;
    for (int k = 0; k < 400; k++) frame(70, 2500, true);
    assert_int_equal(frame(70, 2500, true), 10 * 51);
}

/* A parent who sat on the sofa for 2 s and got up: the sofa's depth comes
 * back as background within a second of it showing again. */
static void test_revealed_background_returns(void **st)
{
    (void)st;
    for (int k = 0; k < 15; k++) frame(70, 0, false); /* the wall, known */
    for (int k = 0; k < 20; k++) assert_int_equal(frame(70, 2500, false), 10 * 51); /* 2 s: not yet */
    for (int k = 0; k < 40; k++) frame(70, 2500, false); /* 6 s in all: absorbed */
    assert_int_equal(frame(70, 2500, false), 0);
    for (int k = 0; k < 6; k++) frame(70, 0, false); /* gone: the wall again */
    assert_int_equal(left_anywhere(), 0);
    /* and a child stepping where it stood is foreground at once */
    assert_int_equal(frame(70, 2400, false), 10 * 51);
}

/* The camera bumped (every depth 500 mm farther): the room is forgotten,
 * the view is all foreground until it has been still again. */
static void test_bump_forgets_the_room(void **st)
{
    (void)st;
    for (int k = 0; k < 15; k++) frame(70, 2500, false);
    assert_int_equal(left_anywhere(), 0);
    int32_t resets = t->bg_resets;
    paint(4000, 0, 0, 0, 0, 0);
    trk_bg_learn(t, FRAME_US);
    trk_bg_remove(t);
    assert_int_equal(t->bg_resets, resets + 1);
    assert_int_equal(left_anywhere(), TRK_CELLS);
}

/* Frames without time between them (single frames, as the real frames'
 * test gives them) learn nothing: the tracker sees as it did without a
 * model. */
static void test_no_time_learns_nothing(void **st)
{
    (void)st;
    for (int k = 0; k < 100; k++) {
        paint(3500, 70, 79, 40, 90, 2500);
        trk_bg_learn(t, 0);
        trk_bg_remove(t);
        assert_int_equal(left_anywhere(), TRK_CELLS);
    }
}

/* Each test on a fresh tracker. */
#define FRESH(f) cmocka_unit_test_setup_teardown(f, tracker_fixture_open, tracker_fixture_close)

int main(void)
{
    const struct CMUnitTest tests[] = {
        FRESH(test_still_object_becomes_background),
        FRESH(test_moving_child_is_not_background),
        FRESH(test_still_player_is_not_absorbed),
        FRESH(test_player_is_never_absorbed),
        FRESH(test_revealed_background_returns),
        FRESH(test_bump_forgets_the_room),
        FRESH(test_no_time_learns_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* words: every coach hint and every tracker status maps to the words the
 * child reads, and nothing else does. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "cub/coach.h"
#include "cub/track.h"
#include "words.h"

static cub_song two_moves(void)
{
    cub_song s;
    memset(&s, 0, sizeof s);
    s.move_count = 2;
    strcpy(s.moves[0].hint, "Clap with me!");
    /* move 1 has no hint of its own */
    return s;
}

static void test_each_coach_hint_has_its_words(void **state)
{
    (void)state;
    cub_song song = two_moves();
    assert_string_equal(cub_words_hint(&song, CUB_COACH_HINT_COME_CLOSER), "Come closer!");
    assert_string_equal(cub_words_hint(&song, CUB_COACH_HINT_CANT_SEE), "I can't see you!");
    assert_string_equal(cub_words_hint(&song, 0), "Clap with me!");
    assert_null(cub_words_hint(&song, CUB_COACH_HINT_NONE));
    assert_null(cub_words_hint(&song, 1)); /* a move without words shows none */
}

static void test_a_hint_outside_the_song_has_no_words(void **state)
{
    (void)state;
    cub_song song = two_moves();
    assert_null(cub_words_hint(&song, 2));
    assert_null(cub_words_hint(&song, -4));
    assert_null(cub_words_hint(NULL, 0));
    /* The coach's own hints need no song. */
    assert_string_equal(cub_words_hint(NULL, CUB_COACH_HINT_CANT_SEE), "I can't see you!");
}

static void test_each_tracker_status_has_its_cue(void **state)
{
    (void)state;
    assert_string_equal(cub_words_cue(CUB_TRACK_TOO_CLOSE), "Step back");
    assert_string_equal(cub_words_cue(CUB_TRACK_TOO_FAR), "Come closer");
    assert_string_equal(cub_words_cue(CUB_TRACK_PARTLY_OUT), "Step into the middle");
    assert_null(cub_words_cue(CUB_TRACK_OK));        /* seen well: nothing to say */
    assert_null(cub_words_cue(CUB_TRACK_NO_PLAYER)); /* nobody: the coach's hint says it */
    assert_null(cub_words_cue(-1));
    assert_null(cub_words_cue(99));
}

static void test_the_idle_screen_asks_for_start(void **state)
{
    (void)state;
    assert_string_equal(cub_words_title(), "Press START!");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_each_coach_hint_has_its_words),
        cmocka_unit_test(test_a_hint_outside_the_song_has_no_words),
        cmocka_unit_test(test_each_tracker_status_has_its_cue),
        cmocka_unit_test(test_the_idle_screen_asks_for_start),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

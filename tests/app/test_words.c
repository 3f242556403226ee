/* words: every coach hint, every fault and every tracker status maps to
 * the words the child reads, and nothing else does; every phrase is listed. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "cub/coach.h"
#include "cub/faults.h"
#include "cub/judge.h"
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
    assert_string_equal(cub_words_hint(&song, CUB_COACH_HINT_WHERE), "Where are you?");
    assert_string_equal(cub_words_hint(&song, CUB_COACH_HINT_STEP_BACK), "Step back");
    assert_string_equal(cub_words_hint(&song, 0), "Clap with me!");
    assert_null(cub_words_hint(&song, CUB_COACH_HINT_NONE));
    assert_null(cub_words_hint(&song, 1)); /* a move without words shows none */
}

static void test_a_hint_outside_the_song_has_no_words(void **state)
{
    (void)state;
    cub_song song = two_moves();
    assert_null(cub_words_hint(&song, 2));
    assert_null(cub_words_hint(&song, -6));
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

/* A song of a clap and a jumping jack, and a table with the clap's own
 * words for a missed clap and the general ones. */
static void fault_song(cub_song *song, cub_faults *faults)
{
    memset(song, 0, sizeof *song);
    song->move_count = 2;
    strcpy(song->moves[0].clip, "clap");
    strcpy(song->moves[0].hint, "Clap, clap, clap!");
    strcpy(song->moves[1].clip, "jumping_jacks");
    strcpy(song->moves[1].hint, "Jump out, jump in!");
    const char *text = "RHE=true missed            Bend your arms!\n"
                       "RHE=true missed for=clap   Clap with me!\n"
                       "RHE=true mirror            The other arm!\n"
                       "RH=mid   missed for=jumping_jacks Jump!\n";
    cub_diag d = {0};
    assert_int_equal(cub_faults_parse(text, strlen(text), "t.words", NULL, faults, &d), CUB_OK);
}

static int32_t code(int32_t how, int32_t feature, int32_t set)
{
    return cub_judge_fault_code((cub_judge_fault){how, feature, set, 0});
}

/* The fault's words: the move's own, else the general, else the move's
 * hint (a table without the line, no table, no fault). */
static void test_a_fault_has_its_words(void **state)
{
    (void)state;
    static cub_song song;
    static cub_faults faults;
    fault_song(&song, &faults);
    const int32_t missed_clap = code(CUB_JUDGE_HOW_MISSED, CUB_FUZZY_RHE, 1);
    assert_string_equal(cub_words_fault(&song, &faults, 0, missed_clap), "Clap with me!");
    assert_string_equal(cub_words_fault(&song, &faults, 1, missed_clap), "Bend your arms!");
    assert_string_equal(
        cub_words_fault(&song, &faults, 0, code(CUB_JUDGE_HOW_MIRROR, CUB_FUZZY_RHE, 1)),
        "The other arm!");
    assert_string_equal(
        cub_words_fault(&song, &faults, 1, code(CUB_JUDGE_HOW_MISSED, CUB_FUZZY_RH, 1)), "Jump!");
    /* no line for it: the move's own hint */
    assert_string_equal(
        cub_words_fault(&song, &faults, 0, code(CUB_JUDGE_HOW_MISSED, CUB_FUZZY_RH, 1)),
        "Clap, clap, clap!");
    assert_string_equal(cub_words_fault(&song, NULL, 0, missed_clap), "Clap, clap, clap!");
    assert_string_equal(cub_words_fault(&song, &faults, 1, 0), "Jump out, jump in!");
    assert_string_equal(cub_words_fault(&song, &faults, 1, 7), "Jump out, jump in!"); /* invalid */
    assert_null(cub_words_fault(&song, &faults, 2, missed_clap));
    assert_null(cub_words_fault(NULL, &faults, 0, missed_clap));
}

typedef struct phrases {
    int n;
    const char *p[64];
} phrases;

static void collect(void *ctx, const char *phrase)
{
    phrases *ps = ctx;
    assert_true(ps->n < 64);
    ps->p[ps->n++] = phrase;
}

static int listed(const phrases *ps, const char *phrase)
{
    int n = 0;
    for (int i = 0; i < ps->n; i++)
        n += !strcmp(ps->p[i], phrase);
    return n;
}

/* Every phrase the box can show is listed once: the fixed ones, the
 * moves' hints, the fault words (for the speech that says them). */
static void test_every_phrase_is_listed_once(void **state)
{
    (void)state;
    static cub_song song;
    static cub_faults faults;
    fault_song(&song, &faults);
    strcpy(song.moves[1].hint, "Clap with me!"); /* the same words twice: listed once */
    phrases ps = {0};
    cub_words_each(&song, &faults, collect, &ps);
    const char *const want[] = {"Press START!",      "Hooray! You did it!", "Come closer!",
                                "I can't see you!",  "Where are you?",      "Step back",
                                "Come closer",
                                "Step into the middle", "Clap, clap, clap!", "Clap with me!",
                                "Bend your arms!",   "The other arm!",      "Jump!"};
    for (size_t i = 0; i < sizeof want / sizeof want[0]; i++)
        if (listed(&ps, want[i]) != 1)
            fail_msg("'%s' listed %d times", want[i], listed(&ps, want[i]));
    assert_int_equal(ps.n, (int)(sizeof want / sizeof want[0]));
    /* what cub_words_fault and cub_words_hint can return is among them */
    for (int m = 0; m < song.move_count; m++)
        assert_int_equal(listed(&ps, cub_words_hint(&song, m)), 1);
    ps.n = 0;
    cub_words_each(NULL, NULL, collect, &ps);
    assert_int_equal(ps.n, 8);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_each_coach_hint_has_its_words),
        cmocka_unit_test(test_a_hint_outside_the_song_has_no_words),
        cmocka_unit_test(test_each_tracker_status_has_its_cue),
        cmocka_unit_test(test_the_idle_screen_asks_for_start),
        cmocka_unit_test(test_a_fault_has_its_words),
        cmocka_unit_test(test_every_phrase_is_listed_once),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* test_groove — seed 001's firmware (cub/groove.h) on hand-made songs: bad
 * input first, then the tempo map, the track choice, the notes, the DP on a
 * case computed by hand (values in the comments), the wrist keys. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <stdlib.h>
#include <string.h>

#include "cub/groove.h"

#define ONE CUB_Q16_ONE
#define Q(num, den) ((cub_q16)(((int64_t)(num) * ONE + (den) / 2) / (den)))

static cub_groove_work work; /* 25 KB: not on the stack */

/* A pitched note of 1 beat (4/4, division 480) unless len_beats says. */
static cub_groove_note note(int pitch, int len_beats, bool beat)
{
    return (cub_groove_note){0, 0, CUB_Q16_INT(len_beats), (uint8_t)pitch, 100, beat, 0, 0};
}

static void assert_near(cub_q16 got, cub_q16 want)
{
    if (abs(got - want) > 2)
        fail_msg("got %d (%.5f), want %d (%.5f)", got, got / 65536.0, want, want / 65536.0);
}

static void test_bad_input_is_refused(void **state)
{
    (void)state;
    cub_groove_params p;
    assert_int_equal(cub_groove_params_set('c', &p), CUB_ERR_ARG);
    assert_int_equal(cub_groove_params_set('a', &p), CUB_OK);
    cub_groove_note n[2] = {note(60, 1, true), note(62, 1, false)};
    cub_groove_segment segs[2];
    int count = 0;
    assert_int_equal(cub_groove_segment_notes(&p, n, 0, 0, &work, segs, 2, &count, NULL),
                     CUB_ERR_ARG);
    assert_int_equal(cub_groove_segment_notes(&p, n, 2, 1, &work, segs, 2, &count, NULL),
                     CUB_ERR_ARG);
    assert_int_equal(
        cub_groove_segment_notes(&p, n, 2, CUB_GROOVE_WINDOW_MAX + 1, &work, segs, 2, &count, NULL),
        CUB_ERR_ARG);
    /* segments that do not tile the notes */
    cub_groove_key keys[2];
    cub_groove_segment gap[2] = {{0, 1}, {0, 2}};
    assert_int_equal(cub_groove_keys(&p, n, 2, gap, 2, keys), CUB_ERR_RANGE);
    cub_groove_segment short_of_end[1] = {{0, 1}};
    assert_int_equal(cub_groove_keys(&p, n, 2, short_of_end, 1, keys), CUB_ERR_RANGE);
}

static void test_tempo_map_sums_every_tempo_event(void **state)
{
    (void)state;
    /* 120 bpm by default, 240 from beat 2, 60 from beat 4 */
    cub_groove_tempo t[2] = {{960, 250000}, {1920, 1000000}};
    cub_groove_song s = {.division = 480, .tracks = 1, .tempos = t, .tempo_count = 2};
    assert_int_equal(cub_groove_tick_us(&s, 0), 0);
    assert_int_equal(cub_groove_tick_us(&s, 480), 500000);
    assert_int_equal(cub_groove_tick_us(&s, 960), 1000000);
    assert_int_equal(cub_groove_tick_us(&s, 1440), 1250000);
    assert_int_equal(cub_groove_tick_us(&s, 1920), 1500000);
    assert_int_equal(cub_groove_tick_us(&s, 2400), 2500000);
}

/* Track 0 the conductor, 1 a bass line, 2 a higher part with a chord, 3 drums. */
static const cub_groove_midi_note band[] = {
    {0, 480, 1, 0, 40, 100},   {0, 480, 2, 1, 64, 100},   {0, 480, 2, 1, 67, 100},
    {0, 100, 3, 9, 36, 100},   {480, 960, 1, 0, 43, 100}, {480, 960, 2, 1, 65, 80},
    {960, 1440, 2, 1, 65, 80}, {980, 1100, 3, 9, 38, 90}, {1920, 2400, 2, 1, 72, 127},
};

static cub_groove_song band_song(int with_drums)
{
    static cub_groove_midi_note no_drums[16];
    int n = 0;
    for (size_t i = 0; i < sizeof band / sizeof band[0]; i++)
        if (with_drums || band[i].channel != 9) no_drums[n++] = band[i];
    return (cub_groove_song){.division = 480,
                             .tracks = 4,
                             .end_tick = 2400,
                             .notes = with_drums ? band : no_drums,
                             .note_count = with_drums ? (int)(sizeof band / sizeof band[0]) : n};
}

static void test_track_choice(void **state)
{
    (void)state;
    cub_groove_song s = band_song(1);
    cub_groove_pick p;
    assert_int_equal(cub_groove_pick_tracks(&s, -1, -1, &p), CUB_OK);
    assert_int_equal(p.melody_track, 2); /* higher than the bass; drums never count */
    assert_int_equal(p.rhythm, CUB_GROOVE_RHYTHM_DRUMS);
    assert_int_equal(cub_groove_pick_tracks(&s, 1, 1, &p), CUB_OK);
    assert_int_equal(p.melody_track, 1);
    assert_int_equal(p.rhythm, CUB_GROOVE_RHYTHM_TRACK);
    assert_int_equal(p.rhythm_track, 1);
    assert_int_equal(cub_groove_pick_tracks(&s, 0, -1, &p), CUB_ERR_RANGE); /* no notes */
    assert_int_equal(cub_groove_pick_tracks(&s, 3, -1, &p), CUB_ERR_RANGE); /* drums only */
    assert_int_equal(cub_groove_pick_tracks(&s, 4, -1, &p), CUB_ERR_RANGE); /* no such track */
    assert_int_equal(cub_groove_pick_tracks(&s, -1, 0, &p), CUB_ERR_RANGE);
    s = band_song(0);
    assert_int_equal(cub_groove_pick_tracks(&s, -1, -1, &p), CUB_OK);
    assert_int_equal(p.rhythm, CUB_GROOVE_RHYTHM_METER);
    cub_groove_song empty = {.division = 480, .tracks = 1};
    assert_int_equal(cub_groove_pick_tracks(&empty, -1, -1, &p), CUB_ERR_EMPTY);
}

static void test_notes_top_line_rests_and_beats(void **state)
{
    (void)state;
    cub_groove_song s = band_song(1);
    cub_groove_pick p;
    cub_groove_note n[8];
    int count = 0;
    assert_int_equal(cub_groove_pick_tracks(&s, -1, -1, &p), CUB_OK);
    assert_int_equal(cub_groove_notes(&s, &p, n, 8, &count), CUB_OK);
    /* the chord's top (67), two repeated 65s kept apart, a rest, 72 */
    assert_int_equal(count, 5);
    int pitch[5] = {67, 65, 65, CUB_GROOVE_REST, 72};
    bool beat[5] = {true, false, true, false, false}; /* drums at 0 and 980 (±30 ticks) */
    for (int i = 0; i < 5; i++) {
        assert_int_equal(n[i].pitch, pitch[i]);
        assert_int_equal(n[i].is_beat, beat[i]);
    }
    assert_int_equal(n[3].tick, 1440);
    assert_int_equal(n[3].length_beats, ONE);
    assert_int_equal(n[4].intensity, 120);
    assert_int_equal(n[4].start_us, 2000000);
    /* without drums, the meter's beats: every note here starts on one */
    s = band_song(0);
    assert_int_equal(cub_groove_pick_tracks(&s, -1, -1, &p), CUB_OK);
    assert_int_equal(cub_groove_notes(&s, &p, n, 8, &count), CUB_OK);
    assert_true(n[0].is_beat && n[1].is_beat && n[2].is_beat && n[4].is_beat);
    assert_int_equal(cub_groove_notes(&s, &p, n, 2, &count), CUB_ERR_NOMEM);
    assert_int_equal(count, 5);
}

static void test_meter_sets_beat_length(void **state)
{
    (void)state;
    /* 6/8 from the start: a beat is an eighth (240 ticks); a note off the
     * eighths' grid is no beat */
    cub_groove_meter m[1] = {{0, 6, 8}};
    cub_groove_midi_note mn[2] = {{0, 480, 0, 0, 60, 64}, {560, 720, 0, 0, 62, 64}};
    cub_groove_song s = {
        .division = 480, .tracks = 1, .notes = mn, .note_count = 2, .meters = m, .meter_count = 1};
    cub_groove_pick p;
    cub_groove_note n[4];
    int count = 0;
    assert_int_equal(cub_groove_pick_tracks(&s, -1, -1, &p), CUB_OK);
    assert_int_equal(cub_groove_notes(&s, &p, n, 4, &count), CUB_OK);
    assert_int_equal(count, 2); /* the gap (80 ticks) is under half a beat */
    assert_int_equal(n[0].length_beats, CUB_Q16_INT(2));
    assert_true(n[0].is_beat);
    assert_false(n[1].is_beat);
    /* the grid for the beat stop: an eighth at 120 quarters a minute is
     * 250 ms; tick 560 lies 80 ticks (83 333 us) after the beat at 480 */
    assert_int_equal(n[0].grid_us, 0);
    assert_int_equal(n[0].beat_us, 250000);
    assert_int_equal(n[1].grid_us, -83333);
    assert_int_equal(n[1].beat_us, 250000);
}

/* By hand, set a (w = 1, v = 2), global density 2/4 = 1/2:
 *   n0 60 -, n1 72 beat, n2 60 -, n3 72 beat, 1 beat each.
 * [0,2) and [2,4): f1 0, range 12 so f2 0, density 1/2 so f3 0, length 2
 * so f4 0: f = 0. [0,4): f4 = |4-2|/2 = 1, f = 1/4. Single notes: 60 -:
 * (1 + 1 + 1/2 + 1/2)/4 = 3/4; 72 beat: (0 + 1 + 1/2 + 1/2)/4 = 1/2.
 * [0,3): unsplit (1 + 0 + 1/6 + 1/2)/4 = 5/12; split at 2: (0 + 3/4)/2 =
 * 3/8 wins. [1,4): unsplit (0 + 0 + 1/6 + 1/2)/4 = 1/6 beats its splits
 * (1/4 at 2, 3/8 at 3). [0,4): mid 1: (3/4 + 1/6)/2 = 11/24; mid 2:
 * (0 + 0)/2 = 0; mid 3: (2 x 3/8 + 1/2)/3 = 5/12: split at 2, value 0. */
static void test_dp_hand_computed_case(void **state)
{
    (void)state;
    cub_groove_params p;
    cub_groove_params_set('a', &p);
    cub_groove_note n[4] = {note(60, 1, false), note(72, 1, true), note(60, 1, false),
                            note(72, 1, true)};
    cub_q16 g = cub_groove_density(n, 0, 4);
    assert_int_equal(g, ONE / 2);
    assert_near(cub_groove_objective(&p, n, 0, 2, g), 0);
    assert_near(cub_groove_objective(&p, n, 0, 4, g), Q(1, 4));
    assert_near(cub_groove_objective(&p, n, 0, 1, g), Q(3, 4));
    assert_near(cub_groove_objective(&p, n, 1, 2, g), Q(1, 2));
    assert_near(cub_groove_objective(&p, n, 0, 3, g), Q(5, 12));
    assert_near(cub_groove_objective(&p, n, 1, 4, g), Q(1, 6));
    cub_groove_segment segs[4];
    cub_groove_cost cost;
    int count = 0;
    assert_int_equal(cub_groove_segment_notes(&p, n, 4, 0, &work, segs, 4, &count, &cost), CUB_OK);
    assert_int_equal(count, 2);
    assert_int_equal(segs[0].first, 0);
    assert_int_equal(segs[0].end, 2);
    assert_int_equal(segs[1].first, 2);
    assert_int_equal(segs[1].end, 4);
    assert_int_equal(work.value[0][4], 0);
    assert_near(work.value[0][3], Q(3, 8));
    assert_int_equal(work.split[0][3], 2);
    assert_near(work.value[1][4], Q(1, 6));
    assert_int_equal(work.split[1][4], 0);
    assert_int_equal(cost.windows, 1);
    assert_int_equal(cost.splits, 3 + 2 * 2 + 1 * 3); /* length 2: 3 ranges x 1 mid, ... */
    assert_int_equal(cost.mean_f, 0);
    assert_int_equal(cub_groove_segment_notes(&p, n, 4, 0, &work, segs, 1, &count, NULL),
                     CUB_ERR_NOMEM);
}

/* Only f1 weighs: every range ending on a beat is 0, so every split ties
 * and takes the split, the later mid winning. */
static void test_dp_ties_take_the_later_split(void **state)
{
    (void)state;
    cub_groove_params p = {.w = {1, 0, 0, 0}};
    cub_groove_note n[3] = {note(60, 1, true), note(62, 1, true), note(64, 1, true)};
    cub_groove_segment segs[3];
    int count = 0;
    assert_int_equal(cub_groove_segment_notes(&p, n, 3, 0, &work, segs, 3, &count, NULL), CUB_OK);
    assert_int_equal(count, 3);
    assert_int_equal(work.split[0][3], 2);
    assert_int_equal(work.split[0][2], 1);
}

/* A long melody: windows of at most W notes, cut after a beat or rest in
 * the second half; the segments tile the notes. */
static void test_dp_windows_bound_long_melodies(void **state)
{
    (void)state;
    cub_groove_params p;
    cub_groove_params_set('b', &p);
    enum { N = 500 };
    static cub_groove_note n[N];
    static cub_groove_segment segs[N];
    for (int i = 0; i < N; i++)
        n[i] = note(60 + (i * 7) % 13, 1 + i % 2, i % 3 == 0);
    int count = 0;
    cub_groove_cost cost;
    assert_int_equal(cub_groove_segment_notes(&p, n, N, 16, &work, segs, N, &count, &cost), CUB_OK);
    assert_true(cost.windows >= N / 16 && cost.windows <= N / 8 + 1);
    assert_true(cost.splits <= (int64_t)cost.windows * 16 * 16 * 16 / 6);
    for (int k = 0, at = 0; k < count; at = segs[k++].end) {
        assert_int_equal(segs[k].first, at);
        assert_true(segs[k].end > at && segs[k].end - at <= 16);
    }
    assert_int_equal(segs[count - 1].end, N);
}

/* The hand case's segments [0,2) [2,4), set a: span 400 mm, Yscale 14. */
static void test_keys_advance_flip_and_follow_pitch(void **state)
{
    (void)state;
    cub_groove_params p;
    cub_groove_params_set('a', &p);
    cub_groove_note n[5] = {note(60, 1, false), note(72, 1, true), note(60, 1, false),
                            note(72, 1, true), note(CUB_GROOVE_REST, 2, false)};
    cub_groove_segment segs[2] = {{0, 2}, {2, 5}};
    cub_groove_key k[5];
    assert_int_equal(cub_groove_keys(&p, n, 5, segs, 2, k), CUB_OK);
    /* note 0 keeps the wrist; note 1: +1/2 of the span, (72 - 66) x 14 */
    assert_int_equal(k[0].x_mm, 0);
    assert_int_equal(k[0].y_mm, 0);
    assert_int_equal(k[1].x_mm, CUB_Q16_INT(200));
    assert_int_equal(k[1].y_mm, CUB_Q16_INT(84));
    /* segment 2 (4 beats) runs back from 200 mm: 100, 0, -200; the rest
     * keeps the last y */
    assert_int_equal(k[2].x_mm, CUB_Q16_INT(100));
    assert_int_equal(k[2].y_mm, CUB_Q16_INT(-84));
    assert_int_equal(k[3].x_mm, 0);
    assert_int_equal(k[3].y_mm, CUB_Q16_INT(84));
    assert_int_equal(k[4].x_mm, CUB_Q16_INT(-200));
    assert_int_equal(k[4].y_mm, CUB_Q16_INT(84));
    /* out of reach: the segment's y scaled in, keeping its shape */
    p.y_reach_mm = CUB_Q16_INT(42);
    assert_int_equal(cub_groove_keys(&p, n, 5, segs, 2, k), CUB_OK);
    assert_int_equal(k[2].y_mm, CUB_Q16_INT(-42));
    assert_int_equal(k[3].y_mm, CUB_Q16_INT(42));
}

static void test_parameter_sets_are_table_1(void **state)
{
    (void)state;
    cub_groove_params a, b;
    cub_groove_params_set('a', &a);
    cub_groove_params_set('b', &b);
    assert_int_equal(a.yscale_mm, CUB_Q16_INT(14));
    assert_int_equal(b.yscale_mm, CUB_Q16_INT(3));
    assert_int_equal(a.smooth_mm, CUB_Q16_INT(100));
    assert_int_equal(b.smooth_mm, CUB_Q16_INT(11));
    assert_int_equal(a.reflectance, ONE);
    assert_int_equal(b.reflectance, Q(12, 100));
    assert_int_equal(a.l1_mm, CUB_Q16_INT(85));
    assert_int_equal(b.l1_mm, CUB_Q16_INT(26));
    assert_int_equal(a.l2_mm, CUB_Q16_INT(50));
    assert_int_equal(b.l2_mm, CUB_Q16_INT(58));
    assert_int_equal(a.swing_deg, b.swing_deg);
    assert_int_equal(a.nod_deg, CUB_Q16_INT(10));
    assert_int_equal(b.v_beats, CUB_Q16_INT(2));
    for (int k = 0; k < 4; k++)
        assert_int_equal(a.w[k], 1);
}

/* The count-in (issue 23): before the melody's first note (here a bar of
 * 4/4 at 120 bpm) the meter's beats sway the waist: each swing leaves on
 * its beat and arrives by the next, a bar's first beat by the full swing,
 * the others by half, alternating sides; the melody's turns follow from
 * where the last one left the body. */
static void test_count_in_sways_on_the_beats(void **state)
{
    (void)state;
    static const cub_groove_midi_note mel[] = {
        {1920, 2400, 1, 0, 72, 127}, {2400, 2880, 1, 0, 74, 127}, {2880, 3840, 1, 0, 76, 127}};
    cub_groove_song s = {.division = 480, .tracks = 2, .end_tick = 3840, .notes = mel,
                         .note_count = 3};
    enum { CAP = 16 };
    static cub_groove_note notes[CAP];
    static cub_groove_segment segs[CAP];
    static cub_groove_key keys[CAP];
    static cub_groove_handles handles[CAP];
    static cub_groove_turn waist[CAP], head[CAP];
    cub_groove_store mem = {CAP, notes, segs, keys, handles, waist, head, &work};
    cub_groove_pick pick;
    cub_groove_params p;
    cub_groove_plan plan;
    cub_groove_params_set('a', &p);
    assert_int_equal(cub_groove_pick_tracks(&s, -1, -1, &pick), CUB_OK);
    assert_int_equal(cub_groove_plan_build(&s, &pick, &p, 0, &mem, &plan, NULL, NULL), CUB_OK);
    assert_true(plan.waist_count >= 5); /* 4 count-in beats, then the melody's */
    for (int b = 0; b < 4; b++) {
        const cub_groove_turn *t = &plan.waist[b];
        assert_int_equal(t->start_us, b * 500000);
        assert_int_equal(t->turn_us, t->start_us);
        assert_int_equal(t->end_us, (b + 1) * 500000);
        cub_q16 amount = b == 0 ? p.swing_deg : p.swing_deg / 2;
        assert_int_equal(t->to_deg, b % 2 ? -amount : amount);
        assert_int_equal(t->from_deg, b ? plan.waist[b - 1].to_deg : 0);
        /* at rest on the beat, on its way by the middle */
        assert_int_equal(cub_groove_turn_at(plan.waist, plan.waist_count, t->start_us),
                         t->from_deg);
        assert_true(cub_groove_turn_at(plan.waist, plan.waist_count, t->start_us + 250000) !=
                    t->from_deg);
    }
    assert_int_equal(plan.waist[4].start_us, 2000000); /* the first note */
    assert_int_equal(plan.waist[4].from_deg, plan.waist[3].to_deg);
    assert_true(plan.waist[4].to_deg > 0); /* the other side */
    assert_int_equal(plan.head[0].to_deg, p.nod_deg);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_input_is_refused),
        cmocka_unit_test(test_tempo_map_sums_every_tempo_event),
        cmocka_unit_test(test_track_choice),
        cmocka_unit_test(test_notes_top_line_rests_and_beats),
        cmocka_unit_test(test_meter_sets_beat_length),
        cmocka_unit_test(test_dp_hand_computed_case),
        cmocka_unit_test(test_dp_ties_take_the_later_split),
        cmocka_unit_test(test_dp_windows_bound_long_melodies),
        cmocka_unit_test(test_keys_advance_flip_and_follow_pitch),
        cmocka_unit_test(test_parameter_sets_are_table_1),
        cmocka_unit_test(test_count_in_sways_on_the_beats),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

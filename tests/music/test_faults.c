/* faults: the fault words table (app/io/faults.c): what bad lines get
 * (file:line and the problem), the lookup (a move's own line before the
 * general one), and the shipped table against the shipped songs: every key
 * of every move has words for each way it can fail. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/faults.h"
#include "cub/judge.h"
#include "cub/song.h"

/* Three kid moves and a coach clip. */
static cub_library_clip lib_clips[4];
static cub_library lib = {.clip_count = 4, .clips = lib_clips};

static void make_lib(void)
{
    static const char *const names[4][2] = {
        {"clap", "dance"}, {"jumping_jacks", "dance"}, {"squat", "dance"}, {"head_shake", "coach"}};
    for (int i = 0; i < 4; i++) {
        snprintf(lib_clips[i].name, sizeof lib_clips[i].name, "%s", names[i][0]);
        snprintf(lib_clips[i].kind, sizeof lib_clips[i].kind, "%s", names[i][1]);
    }
}

static void expect_error(const char *text, int line, const char *words)
{
    cub_faults *f = malloc(sizeof *f);
    cub_diag d = {0};
    char msg[600];
    cub_err e = cub_faults_parse(text, strlen(text), "songs/t.words", &lib, f, &d);
    printf("faults: rejected: %s\n", cub_diag_str(&d, msg, sizeof msg));
    assert_int_equal(e, CUB_ERR_FORMAT);
    assert_string_equal(d.file, "songs/t.words");
    assert_int_equal(d.line, line);
    if (!strstr(d.msg, words)) fail_msg("message '%s' lacks '%s'", d.msg, words);
    assert_int_equal(f->count, 0);
    free(f);
}

static void test_bad_lines_are_refused_naming_file_and_line(void **state)
{
    (void)state;
    expect_error("RH=up missed Reach!\nRH missed Up!\n", 2, "'RH' is not a key point");
    expect_error("Arm=up missed Up!\n", 1, "no fuzzy feature 'Arm'");
    expect_error("RH=high missed Up!\n", 1, "RH has no set 'high'");
    expect_error("RH=up\n", 1, "needs how it failed");
    expect_error("RH=up forgot Up!\n", 1, "'forgot' is not how a key fails");
    expect_error("Posture=jump mirror Jump!\n", 1, "Posture has no other side");
    expect_error("RH=up missed\n", 1, "no words to say");
    expect_error("RH=up missed   # only a comment\n", 1, "no words to say");
    expect_error("RH=mid missed for=skipping Jump!\n", 1, "the library has no clip 'skipping'");
    expect_error("RH=mid missed for=head_shake Jump!\n", 1, "is a coach clip, not a kid's move");
    expect_error("RH=mid missed for= Jump!\n", 1, "for= needs a clip name");
    expect_error("RH=up missed Up!\n\nRH=up missed Higher!\n", 3,
                 "RH=up missed is given twice (first on line 1)");
    expect_error("RH=up missed for=clap A\nRH=up missed for=clap B\n", 2,
                 "RH=up missed for=clap is given twice");
    expect_error("RH=up missed Up\thigh!\n", 1, "control character");
    expect_error("RH=up missed Up \xff\xfe\xc3(!\n", 1, "not UTF-8");
    expect_error("RH=up missed Up \xed\xa0\x80!\n", 1, "not UTF-8");
    char big[400];
    snprintf(big, sizeof big, "RH=up missed %0200d\n", 7);
    expect_error(big, 1, "longer than 127 bytes");
}

/* More lines than the table holds: the first one too many is named. */
static void test_too_many_lines_are_refused(void **state)
{
    (void)state;
    static char text[(CUB_FAULTS_MAX + 1) * 48];
    static const char *const clips[4] = {"", " for=clap", " for=jumping_jacks", " for=squat"};
    static const char *const hows[2] = {"missed", "mirror"};
    size_t n = 0;
    int lines = 0;
    for (int c = 0; c < 4; c++)
        for (int f = 0; f < CUB_FUZZY_FEATURE_COUNT; f++)
            for (int s = 0; s < cub_fuzzy_set_count(f); s++)
                for (int h = 0; h < 2 && lines <= CUB_FAULTS_MAX; h++) {
                    if (h && (f == CUB_FUZZY_POSTURE || f == CUB_FUZZY_TRUNK)) continue;
                    n += (size_t)snprintf(text + n, sizeof text - n, "%s=%s %s%s Go!\n",
                                          cub_fuzzy_feature_name(f), cub_fuzzy_set_name(f, s),
                                          hows[h], clips[c]);
                    lines++;
                }
    assert_int_equal(lines, CUB_FAULTS_MAX + 1);
    expect_error(text, CUB_FAULTS_MAX + 1, "more than 128 lines");
}

static void test_lookup_prefers_the_moves_own_line(void **state)
{
    (void)state;
    const char *text = "\xEF\xBB\xBF# a table\r\n"
                       "RH=mid   missed                    Arms out wide!   \r\n"
                       "RH=mid   missed  for=jumping_jacks Jump!\n"
                       "RHE=true mirror                    The other arm!  # said kindly\n"
                       "RFK=true missed  Bend your knees!\n"
                       "LFK=true missed  Plie\xcc\x81 les genoux \xe2\x98\x85\n";
    cub_faults *f = malloc(sizeof *f);
    cub_diag d = {0};
    assert_int_equal(cub_faults_parse(text, strlen(text), "t.words", &lib, f, &d), CUB_OK);
    assert_int_equal(f->count, 5);
    assert_int_equal(f->w[1].line, 3);
    assert_string_equal(f->w[4].words, "Plie\xcc\x81 les genoux \xe2\x98\x85");
    assert_string_equal(cub_faults_words(f, "jumping_jacks", CUB_JUDGE_HOW_MISSED, CUB_FUZZY_RH, 1),
                        "Jump!");
    assert_string_equal(cub_faults_words(f, "clap", CUB_JUDGE_HOW_MISSED, CUB_FUZZY_RH, 1),
                        "Arms out wide!");
    assert_string_equal(cub_faults_words(f, NULL, CUB_JUDGE_HOW_MISSED, CUB_FUZZY_RH, 1),
                        "Arms out wide!");
    assert_string_equal(cub_faults_words(f, "clap", CUB_JUDGE_HOW_MIRROR, CUB_FUZZY_RHE, 1),
                        "The other arm!");
    assert_string_equal(cub_faults_words(f, "squat", CUB_JUDGE_HOW_MISSED, CUB_FUZZY_RFK, 0),
                        "Bend your knees!");
    /* nothing for another how, another set, or no table */
    assert_null(cub_faults_words(f, "clap", CUB_JUDGE_HOW_MISSED, CUB_FUZZY_RHE, 1));
    assert_null(cub_faults_words(f, "clap", CUB_JUDGE_HOW_MISSED, CUB_FUZZY_RH, 2));
    assert_null(cub_faults_words(NULL, "clap", CUB_JUDGE_HOW_MISSED, CUB_FUZZY_RH, 1));
    /* without a library for= is not checked */
    const char *other = "RH=mid missed for=anything Go!\n";
    assert_int_equal(cub_faults_parse(other, strlen(other), "t.words", NULL, f, &d), CUB_OK);
    assert_int_equal(f->count, 1);
    free(f);
}

/* The shipped table: every key of every move of every shipped song has its
 * words for missed, and for mirror when the key has a side. */
static void test_shipped_table_covers_the_shipped_songs(void **state)
{
    (void)state;
    const char *src = getenv("CUB_SOURCE_DIR");
    static const char *const songs[] = {"twinkle", "old_macdonald", "london_bridge"};
    char path[512], msg[600];
    cub_library shipped;
    cub_diag d = {0};
    snprintf(path, sizeof path, "%s/assets/clips/bear.cubclips", src ? src : "..");
    if (cub_pack_read(path, &shipped, &d)) fail_msg("%s", cub_diag_str(&d, msg, sizeof msg));
    cub_song *s = malloc(sizeof *s);
    cub_faults *f = malloc(sizeof *f);
    int said = 0;
    for (int i = 0; i < 3; i++) {
        snprintf(path, sizeof path, "%s/assets/songs/%s.song.xml", src ? src : "..", songs[i]);
        if (cub_song_load(path, &shipped, s, &d)) fail_msg("%s", cub_diag_str(&d, msg, sizeof msg));
        assert_true(s->faults_path[0] != '\0');
        if (cub_faults_load(s->faults_path, &shipped, f, &d))
            fail_msg("%s", cub_diag_str(&d, msg, sizeof msg));
        for (int m = 0; m < s->move_count; m++)
            for (int k = 0; k < s->moves[m].key_count; k++) {
                const cub_song_key *key = &s->moves[m].keys[k];
                int sided = key->feature != CUB_FUZZY_POSTURE && key->feature != CUB_FUZZY_TRUNK;
                for (int how = CUB_JUDGE_HOW_MISSED; how <= (sided ? CUB_JUDGE_HOW_MIRROR : 1);
                     how++) {
                    const char *w =
                        cub_faults_words(f, s->moves[m].clip, how, key->feature, key->set);
                    if (!w)
                        fail_msg("%s: move %s has no words for %s=%s %s", path, s->moves[m].clip,
                                 cub_fuzzy_feature_name(key->feature),
                                 cub_fuzzy_set_name(key->feature, key->set),
                                 cub_judge_how_name(how));
                    said++;
                }
            }
    }
    printf("faults: %d lines in the table; %d (move, key, how) of the shipped songs have words\n",
           f->count, said);
    assert_string_equal(cub_faults_words(f, "jumping_jacks", CUB_JUDGE_HOW_MISSED, CUB_FUZZY_RH, 1),
                        "Jump!");
    assert_string_equal(cub_faults_words(f, "squat", CUB_JUDGE_HOW_MISSED, CUB_FUZZY_RFK, 0),
                        "Bend your knees!");
    assert_string_equal(cub_faults_words(f, "clap", CUB_JUDGE_HOW_MISSED, CUB_FUZZY_LHE, 1),
                        "Clap with me!");
    assert_string_equal(cub_faults_words(f, "boxing", CUB_JUDGE_HOW_MIRROR, CUB_FUZZY_RHE, 1),
                        "The other arm!");
    free(f);
    free(s);
    cub_library_free(&shipped);
}

int main(void)
{
    make_lib();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_lines_are_refused_naming_file_and_line),
        cmocka_unit_test(test_too_many_lines_are_refused),
        cmocka_unit_test(test_lookup_prefers_the_moves_own_line),
        cmocka_unit_test(test_shipped_table_covers_the_shipped_songs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* Choreography files (cub/song.h): every error names its file and line;
 * the three shipped songs load and validate against the shipped clip
 * library. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/song.h"

/* A small library: 14 kid moves "a".."n" of 2 s each (60 frames at 30 fps)
 * and one coach clip "w". The reader needs only names, kinds and lengths. */
static cub_library_clip lib_clips[15];
static cub_library lib = {.clip_count = 15, .clips = lib_clips};

static void make_lib(void)
{
    for (int i = 0; i < 15; i++) {
        snprintf(lib_clips[i].name, sizeof(lib_clips[i].name), "%c", i < 14 ? 'a' + i : 'w');
        snprintf(lib_clips[i].kind, sizeof(lib_clips[i].kind), "%s", i < 14 ? "dance" : "coach");
        lib_clips[i].clip.frame_count = 61; /* 60 intervals: 2 s */
        lib_clips[i].clip.frame_ns = 33333333;
    }
}

#define HEAD "<?xml version=\"1.0\"?>\n"
#define SONG(bars)                                                                                 \
    "<song version=\"1\" name=\"T\" midi=\"t.mid\" bpm=\"120\" meter=\"4/4\" bars=\"" bars "\">\n"
#define MOVE(clip, bar)                                                                            \
    "<move clip=\"" clip "\" reps=\"2\" bar=\"" bar                                                \
    "\" bars=\"2\" keys=\"RHE=true\" hint=\"h\" icon=\"i\"/>\n"
/* Eight moves a..h, two bars each at 120 bpm (2 s a bar: speed exactly 1),
 * on lines 3..10. */
#define EIGHT                                                                                      \
    MOVE("a", "1")                                                                                 \
    MOVE("b", "3") MOVE("c", "5") MOVE("d", "7") MOVE("e", "9") MOVE("f", "11") MOVE("g", "13")    \
        MOVE("h", "15")

static void expect_error(const char *text, int line, const char *words)
{
    cub_song *s = malloc(sizeof(*s));
    cub_diag d = {0};
    char msg[600];
    cub_err err = cub_song_parse(text, strlen(text), "songs/t.song.xml", &lib, s, &d);
    cub_diag_str(&d, msg, sizeof(msg));
    printf("song: rejected: %s\n", msg);
    assert_int_equal(err, CUB_ERR_FORMAT);
    assert_string_equal(d.file, "songs/t.song.xml");
    assert_int_equal(d.line, line);
    if (!strstr(d.msg, words)) fail_msg("message '%s' lacks '%s'", d.msg, words);
    assert_int_equal(s->move_count, 0);
    free(s);
}

static void test_song_accepts_a_good_file(void **state)
{
    (void)state;
    const char *text = HEAD SONG("16") EIGHT "</song>\n";
    cub_song *s = malloc(sizeof(*s));
    cub_diag d = {0};
    assert_int_equal(cub_song_parse(text, strlen(text), "songs/t.song.xml", &lib, s, &d), CUB_OK);
    assert_string_equal(s->midi_path, "songs/t.mid");
    assert_string_equal(s->faults_path, ""); /* no faults= */
    assert_int_equal(s->move_count, 8);
    assert_int_equal(s->distinct_moves, 8);
    assert_int_equal(s->moves[7].line, 10);
    assert_int_equal(s->moves[1].start_us, 4000000);
    assert_int_equal(s->moves[1].end_us, 8000000);
    assert_int_equal(s->moves[1].speed_permille, 1000);
    assert_int_equal(s->moves[0].key_count, 1);
    assert_int_equal(s->moves[0].keys[0].feature, CUB_FUZZY_RHE);
    assert_string_equal(cub_fuzzy_set_name(CUB_FUZZY_RHE, s->moves[0].keys[0].set), "true");
    assert_int_equal(cub_song_length_us(s), 32000000);
    assert_int_equal(cub_song_move_at(s, 0), 0);
    assert_int_equal(cub_song_move_at(s, 3999999), 0);
    assert_int_equal(cub_song_move_at(s, 4000000), 1);
    assert_int_equal(cub_song_move_at(s, 32000000), -1);
    /* Exact integers where a beat is no whole number of µs (112 bpm). */
    s->bpm = 112;
    assert_int_equal(cub_song_bar_us(s, 8), 7LL * 4 * 60000000 / 112);
    s->meter_num = 6;
    s->meter_den = 8; /* 6/8: three quarter notes a bar */
    assert_int_equal(cub_song_bar_us(s, 2), 3LL * 60000000 / 112);
    free(s);
}

/* faults= names a file beside the song, like the MIDI. */
static void test_song_faults_sit_beside_the_song(void **state)
{
    (void)state;
    const char *text = HEAD "<song version=\"1\" name=\"T\" midi=\"t.mid\" faults=\"f.words\" "
                            "bpm=\"120\" meter=\"4/4\" bars=\"16\">\n" EIGHT "</song>\n";
    cub_song *s = malloc(sizeof(*s));
    cub_diag d = {0};
    assert_int_equal(cub_song_parse(text, strlen(text), "songs/t.song.xml", &lib, s, &d), CUB_OK);
    assert_string_equal(s->faults, "f.words");
    assert_string_equal(s->faults_path, "songs/f.words");
    free(s);
    expect_error(HEAD "<song version=\"1\" name=\"T\" midi=\"t.mid\" faults=\"../f.words\" "
                      "bpm=\"120\" meter=\"4/4\" bars=\"16\">\n" EIGHT "</song>\n",
                 2, "faults=\"../f.words\" is not a file name beside the song");
    expect_error(HEAD "<song version=\"1\" name=\"T\" midi=\"t.mid\" faults=\"\" "
                      "bpm=\"120\" meter=\"4/4\" bars=\"16\">\n" EIGHT "</song>\n",
                 2, "faults is empty");
}

static void test_song_rejects_bad_moves(void **state)
{
    (void)state;
    expect_error(HEAD SONG("16") MOVE("zz", "1") "</song>\n", 3, "the library has no clip 'zz'");
    expect_error(HEAD SONG("16") MOVE("w", "1") "</song>\n", 3, "not a kid's move");
    expect_error(HEAD SONG("16") MOVE("a", "1") "<move clip=\"b\" reps=\"1\" bar=\"3\" bars=\"1\" "
                                                "keys=\"RH=up\" hint=\"h\" icon=\"i\"/>\n"
                                                "</song>\n",
                 4, "at least 2 times in a row");
    /* Seven different moves are too few, even with one of them twice. */
    expect_error(HEAD SONG("16") MOVE("a", "1") MOVE("b", "3") MOVE("c", "5") MOVE("d", "7")
                     MOVE("e", "9") MOVE("f", "11") MOVE("g", "13") MOVE("a", "15") "</song>\n",
                 10, "uses 7 different moves");
    expect_error(HEAD SONG("26") EIGHT MOVE("i", "17") MOVE("j", "19") MOVE("k", "21")
                     MOVE("l", "23") MOVE("m", "25") "</song>\n",
                 15, "13th different move");
    /* Overlap: b starts inside a's bars 1-2; and a move out of order. */
    expect_error(HEAD SONG("16") MOVE("a", "1") MOVE("b", "2") "</song>\n", 4,
                 "overlaps the previous move, which lasts until bar 2");
    expect_error(HEAD SONG("16") MOVE("a", "5") MOVE("b", "1") "</song>\n", 4, "overlaps");
    expect_error(HEAD SONG("16") MOVE("a", "16") "</song>\n", 3, "pass the song's end");
    /* Two 2-s reps cannot fill 4 bars (8 s) at the coach's speeds. */
    expect_error(HEAD SONG("16") "<move clip=\"a\" reps=\"2\" bar=\"1\" bars=\"4\" keys=\"RH=up\" "
                                 "hint=\"h\" icon=\"i\"/>\n"
                                 "</song>\n",
                 3, "speed 0.50");
}

static void test_song_rejects_bad_numbers_and_names(void **state)
{
    (void)state;
    const char *tail = MOVE("a", "1") "</song>\n";
    char text[2000];
#define WITH(song_line) (snprintf(text, sizeof(text), HEAD "%s\n%s", song_line, tail), text)
    expect_error(WITH("<song version=\"1\" name=\"T\" midi=\"t.mid\" bpm=\"fast\" meter=\"4/4\" "
                      "bars=\"16\">"),
                 2, "bpm=\"fast\" is not a whole number");
    expect_error(WITH("<song version=\"1\" name=\"T\" midi=\"t.mid\" bpm=\"1000\" meter=\"4/4\" "
                      "bars=\"16\">"),
                 2, "bpm=1000 is outside [30, 300]");
    expect_error(
        WITH(
            "<song version=\"1\" name=\"T\" midi=\"t.mid\" bpm=\"120\" meter=\"4/5\" bars=\"16\">"),
        2, "meter=\"4/5\"");
    expect_error(
        WITH("<song version=\"1\" name=\"T\" midi=\"t.mid\" bpm=\"120\" meter=\"4/4\" bars=\"0\">"),
        2, "bars=0 is outside");
    expect_error(
        WITH(
            "<song version=\"2\" name=\"T\" midi=\"t.mid\" bpm=\"120\" meter=\"4/4\" bars=\"16\">"),
        2, "version=2");
    expect_error(WITH("<song version=\"1\" name=\"T\" bpm=\"120\" meter=\"4/4\" bars=\"16\">"), 2,
                 "<song> needs midi");
    expect_error(WITH("<song version=\"1\" name=\"T\" midi=\"../t.mid\" bpm=\"120\" meter=\"4/4\" "
                      "bars=\"16\">"),
                 2, "not a file name beside the song");
    expect_error(WITH("<song version=\"1\" name=\"T\" midi=\"t.mid\" bpm=\"120\" meter=\"4/4\" "
                      "bars=\"16\" tempo=\"3\">"),
                 2, "unknown attribute 'tempo'");
#undef WITH
    const char *move_errors[][2] = {
        {"<move clip=\"a\" reps=\"2.5\" bar=\"1\" bars=\"2\" keys=\"RH=up\" hint=\"h\" "
         "icon=\"i\"/>",
         "reps=\"2.5\" is not a whole number"},
        {"<move clip=\"a\" reps=\"2\" bar=\"-1\" bars=\"2\" keys=\"RH=up\" hint=\"h\" icon=\"i\"/>",
         "bar=-1 is outside"},
        {"<move clip=\"a\" reps=\"2\" bar=\"1\" bars=\"2\" keys=\"RHX=up\" hint=\"h\" icon=\"i\"/>",
         "no fuzzy feature 'RHX'"},
        {"<move clip=\"a\" reps=\"2\" bar=\"1\" bars=\"2\" keys=\"RHE=maybe\" hint=\"h\" "
         "icon=\"i\"/>",
         "RHE has no set 'maybe'"},
        {"<move clip=\"a\" reps=\"2\" bar=\"1\" bars=\"2\" keys=\"RH=up RH=mid\" hint=\"h\" "
         "icon=\"i\"/>",
         "given twice"},
        {"<move clip=\"a\" reps=\"2\" bar=\"1\" bars=\"2\" keys=\" \" hint=\"h\" icon=\"i\"/>",
         "keys is empty"},
        {"<move clip=\"a\" reps=\"2\" bar=\"1\" bars=\"2\" keys=\"RH\" hint=\"h\" icon=\"i\"/>",
         "not FEATURE=set"},
        {"<move clip=\"a\" reps=\"2\" bar=\"1\" bars=\"2\" keys=\"RH=up\" icon=\"i\"/>",
         "<move> needs hint"},
        {"<move clip=\"a\" reps=\"2\" bar=\"1\" bars=\"2\" keys=\"RH=up\" hint=\"h\" icon=\"Big "
         "Icon\"/>",
         "not a name of [a-z0-9_]"},
        {"<move clip=\"a\" reps=\"2\" bar=\"1\" bars=\"2\" keys=\"RH=up\" hint=\"h\" icon=\"i\" "
         "speed=\"2\"/>",
         "unknown attribute 'speed'"},
        {"<step clip=\"a\"/>", "unknown element <step>"},
    };
    for (size_t i = 0; i < sizeof(move_errors) / sizeof(move_errors[0]); i++) {
        snprintf(text, sizeof(text), HEAD SONG("16") "%s\n</song>\n", move_errors[i][0]);
        expect_error(text, 3, move_errors[i][1]);
    }
    expect_error(HEAD "<dance/>\n", 2, "not <song>");
    expect_error(HEAD SONG("16") "<move clip=\"a\"\n</song>\n", 3, "XML");
}

static void test_song_shipped_songs_validate(void **state)
{
    (void)state;
    const char *src = getenv("CUB_SOURCE_DIR");
    static const char *const names[] = {"twinkle", "old_macdonald", "london_bridge"};
    char path[512], msg[600];
    cub_library shipped;
    cub_diag d = {0};
    snprintf(path, sizeof(path), "%s/assets/clips/bear.cubclips", src ? src : "..");
    if (cub_pack_read(path, &shipped, &d)) fail_msg("%s", cub_diag_str(&d, msg, sizeof(msg)));
    cub_song *s = malloc(sizeof(*s));
    for (int i = 0; i < 3; i++) {
        snprintf(path, sizeof(path), "%s/assets/songs/%s.song.xml", src ? src : "..", names[i]);
        if (cub_song_load(path, &shipped, s, &d))
            fail_msg("%s", cub_diag_str(&d, msg, sizeof(msg)));
        int lo = 1000, hi = 0;
        for (int m = 0; m < s->move_count; m++) {
            lo = s->moves[m].speed_permille < lo ? s->moves[m].speed_permille : lo;
            hi = s->moves[m].speed_permille > hi ? s->moves[m].speed_permille : hi;
            assert_true(s->moves[m].reps >= CUB_SONG_MIN_REPS);
        }
        printf("song: \"%s\" bpm=%d meter=%d/%d bars=%d moves=%d distinct=%d seconds=%.3f "
               "speed=%.2f..%.2f\n",
               s->name, s->bpm, s->meter_num, s->meter_den, s->bars, s->move_count,
               s->distinct_moves, (double)cub_song_length_us(s) / 1e6, lo / 1e3, hi / 1e3);
        assert_true(s->distinct_moves >= CUB_SONG_MIN_MOVES);
        assert_true(s->distinct_moves <= CUB_SONG_MAX_DISTINCT);
    }
    free(s);
    cub_library_free(&shipped);
}

#define FREE(bar, bars) "<free bar=\"" bar "\" bars=\"" bars "\"/>\n"

static void expect_span(const cub_song_span *sp, int kind, int index, int bar, int bars)
{
    printf("song: span %s %d bars %d+%d\n", cub_song_span_name(sp->kind), sp->index, sp->bar,
           sp->bars);
    assert_int_equal(sp->kind, kind);
    assert_int_equal(sp->index, index);
    assert_int_equal(sp->bar, bar);
    assert_int_equal(sp->bars, bars);
}

/* <free> spans sit between moves; the spans cover the song from bar 1 to
 * its end: intro, moves, gaps, frees, outro. */
static void test_song_free_bars_and_spans(void **state)
{
    (void)state;
    const char *text = HEAD SONG("24") MOVE("a", "3") MOVE("b", "5") FREE("7", "2") MOVE(
        "c", "9") MOVE("d", "12") MOVE("e", "14") MOVE("f", "16") MOVE("g", "18") MOVE("h", "20")
        "</song>\n";
    cub_song *s = malloc(sizeof(*s));
    cub_diag d = {0};
    assert_int_equal(cub_song_parse(text, strlen(text), "songs/t.song.xml", &lib, s, &d), CUB_OK);
    assert_int_equal(s->free_count, 1);
    assert_int_equal(s->frees[0].line, 5);
    assert_int_equal(s->frees[0].start_us, 12000000);
    assert_int_equal(s->frees[0].end_us, 16000000);
    cub_song_span sp[CUB_SONG_MAX_SPANS];
    int n = cub_song_spans(s, sp, CUB_SONG_MAX_SPANS);
    assert_int_equal(n, 12);
    expect_span(&sp[0], CUB_SONG_SPAN_INTRO, -1, 1, 2);
    expect_span(&sp[1], CUB_SONG_SPAN_MOVE, 0, 3, 2);
    expect_span(&sp[3], CUB_SONG_SPAN_FREE, 0, 7, 2);
    expect_span(&sp[4], CUB_SONG_SPAN_MOVE, 2, 9, 2);
    expect_span(&sp[5], CUB_SONG_SPAN_GAP, -1, 11, 1);
    expect_span(&sp[11], CUB_SONG_SPAN_OUTRO, -1, 22, 3);
    assert_int_equal(sp[11].end_us, cub_song_length_us(s));
    for (int i = 1; i < n; i++)
        assert_int_equal(sp[i].start_us, sp[i - 1].end_us);
    n = cub_song_groove_spans(s, sp, CUB_SONG_MAX_SPANS);
    assert_int_equal(n, 4); /* intro, free, gap, outro */
    expect_span(&sp[2], CUB_SONG_SPAN_GAP, -1, 11, 1);
    free(s);
}

/* A song with no <move> is a groove song: one span, the whole song. */
static void test_song_without_moves_grooves_throughout(void **state)
{
    (void)state;
    const char *text = HEAD SONG("16") "</song>\n";
    cub_song *s = malloc(sizeof(*s));
    cub_diag d = {0};
    assert_int_equal(cub_song_parse(text, strlen(text), "songs/t.song.xml", &lib, s, &d), CUB_OK);
    assert_int_equal(s->move_count, 0);
    cub_song_span sp[4];
    assert_int_equal(cub_song_groove_spans(s, sp, 4), 1);
    expect_span(&sp[0], CUB_SONG_SPAN_INTRO, -1, 1, 16);
    assert_int_equal(sp[0].end_us, cub_song_length_us(s));
    free(s);
}

static void test_song_rejects_bad_free_bars(void **state)
{
    (void)state;
    expect_error(HEAD SONG("16") FREE("2", "2") MOVE("a", "3") "</song>\n", 4, "overlaps");
    expect_error(HEAD SONG("16") MOVE("a", "3") FREE("4", "2") "</song>\n", 4,
                 "overlaps the move or <free> before");
    expect_error(HEAD SONG("16") FREE("15", "3") "</song>\n", 3, "pass the song's end");
    expect_error(HEAD SONG("16") "<free bar=\"1\" bars=\"2\" why=\"x\"/>\n</song>\n", 3,
                 "unknown attribute 'why'");
    expect_error(HEAD SONG("16") "<free bar=\"1\"/>\n</song>\n", 3, "bars");
    expect_error(HEAD SONG("16") FREE("0", "2") "</song>\n", 3, "bar");
    expect_error(HEAD SONG("16") MOVE("a", "1") "</song>\n", 3, "(or none: a groove song)");
}

int main(void)
{
    make_lib();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_song_accepts_a_good_file),
        cmocka_unit_test(test_song_faults_sit_beside_the_song),
        cmocka_unit_test(test_song_rejects_bad_moves),
        cmocka_unit_test(test_song_rejects_bad_numbers_and_names),
        cmocka_unit_test(test_song_shipped_songs_validate),
        cmocka_unit_test(test_song_free_bars_and_spans),
        cmocka_unit_test(test_song_without_moves_grooves_throughout),
        cmocka_unit_test(test_song_rejects_bad_free_bars),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* test_groove_midi — the MIDI note reader for seed 001 (app/music/
 * midi_groove.c): bad files first, then the pairing of note-ons and
 * note-offs, the tempo map and meters as read, then every file of
 * ../shared/data/midi and the box's songs through the whole groove
 * pipeline (skipped with a message when the shared data is absent). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/music.h"

/* A file being built: format 1, division 480. */
typedef struct smf {
    uint8_t b[1024];
    size_t len, track_at;
} smf;

static void put(smf *f, const uint8_t *p, size_t n)
{
    assert_true(f->len + n <= sizeof f->b);
    memcpy(f->b + f->len, p, n);
    f->len += n;
}

static void header(smf *f, int tracks)
{
    uint8_t h[14] = {'M',      'T',       'h', 'd', 0, 0, 0, 6, 0, 1, 0, (uint8_t)tracks,
                     480 >> 8, 480 & 0xFF};
    f->len = 0;
    put(f, h, sizeof h);
}

static void track_begin(smf *f)
{
    uint8_t h[8] = {'M', 'T', 'r', 'k', 0, 0, 0, 0};
    f->track_at = f->len;
    put(f, h, sizeof h);
}

/* A delta time (< 2^14 here) then the event's bytes. */
static void ev(smf *f, int delta, const uint8_t *p, size_t n)
{
    uint8_t d[2] = {(uint8_t)(0x80 | delta >> 7), (uint8_t)(delta & 0x7F)};
    if (delta < 128)
        put(f, d + 1, 1);
    else
        put(f, d, 2);
    put(f, p, n);
}

static void track_end(smf *f)
{
    uint8_t eot[3] = {0xFF, 0x2F, 0};
    ev(f, 0, eot, 3);
    size_t n = f->len - f->track_at - 8;
    f->b[f->track_at + 6] = (uint8_t)(n >> 8);
    f->b[f->track_at + 7] = (uint8_t)(n & 0xFF);
}

#define EV(f, delta, ...)                                                                          \
    do {                                                                                           \
        const uint8_t e_[] = {__VA_ARGS__};                                                        \
        ev(f, delta, e_, sizeof e_);                                                               \
    } while (0)

/* Conductor: 120 bpm, 3/4, 240 bpm from tick 960. Notes: 60 on at 0; at
 * 480 a new 60 on *before* the old one's off; 60 off at 960 (velocity-0
 * note-on, running status); 62 at 960..1440, off then on again at 1440,
 * retriggered at 1920 without an off; one off at 2400 ends both; a tempo
 * event in the note track at 1920 (60 bpm). */
static void song(smf *f)
{
    header(f, 2);
    track_begin(f);
    EV(f, 0, 0xFF, 0x51, 3, 0x07, 0xA1, 0x20);
    EV(f, 0, 0xFF, 0x58, 4, 3, 2, 24, 8);
    EV(f, 960, 0xFF, 0x51, 3, 0x03, 0xD0, 0x90);
    track_end(f);
    track_begin(f);
    EV(f, 0, 0x90, 60, 100);
    EV(f, 480, 0x90, 60, 90);
    EV(f, 0, 0x80, 60, 0);
    EV(f, 480, 60, 0); /* running status: note-on velocity 0 */
    EV(f, 0, 0x90, 62, 80);
    EV(f, 480, 0x80, 62, 0);
    EV(f, 0, 0x90, 62, 81);
    EV(f, 480, 0x90, 62, 82);
    EV(f, 0, 0xFF, 0x51, 3, 0x0F, 0x42, 0x40);
    EV(f, 480, 0x80, 62, 0);
    track_end(f);
}

static void test_bad_files_name_the_file(void **state)
{
    (void)state;
    cub_midi_groove g;
    cub_diag d = {0};
    char msg[600];
    uint8_t junk[4] = {'M', 'T', 'h', 'x'};
    assert_int_equal(cub_midi_groove_read(junk, sizeof junk, "junk.mid", &g, &d), CUB_ERR_FORMAT);
    assert_non_null(strstr(cub_diag_str(&d, msg, sizeof msg), "junk.mid"));
    assert_null(g.notes);
    smf f;
    song(&f);
    assert_int_equal(cub_midi_groove_read(f.b, f.len - 5, "cut.mid", &g, &d), CUB_ERR_FORMAT);
    assert_non_null(strstr(cub_diag_str(&d, msg, sizeof msg), "cut.mid"));
    /* a time signature of 3/2^9 */
    song(&f);
    size_t at = 0;
    while (at + 5 <= f.len && memcmp(f.b + at, "\xFF\x58\x04\x03\x02", 5))
        at++;
    assert_true(at + 5 <= f.len);
    f.b[at + 4] = 9;
    assert_int_equal(cub_midi_groove_read(f.b, f.len, "meter.mid", &g, &d), CUB_ERR_FORMAT);
    cub_diag_str(&d, msg, sizeof msg);
    assert_non_null(strstr(msg, "meter.mid"));
    assert_non_null(strstr(msg, "time signature"));
    assert_int_equal(cub_midi_groove_load("/nonexistent/x.mid", &g, &d), CUB_ERR_IO);
}

static void test_pairing_keeps_every_note(void **state)
{
    (void)state;
    smf f;
    song(&f);
    cub_midi_groove g;
    cub_diag d = {0};
    char msg[600];
    if (cub_midi_groove_read(f.b, f.len, "pairs.mid", &g, &d))
        fail_msg("%s", cub_diag_str(&d, msg, sizeof msg));
    const int32_t want[5][3] = {
        {0, 480, 60}, {480, 960, 60}, {960, 1440, 62}, {1440, 2400, 62}, {1920, 2400, 62}};
    assert_int_equal(g.song.note_count, 5);
    for (int i = 0; i < 5; i++) {
        assert_int_equal(g.song.notes[i].on_tick, want[i][0]);
        assert_int_equal(g.song.notes[i].off_tick, want[i][1]);
        assert_int_equal(g.song.notes[i].pitch, want[i][2]);
        assert_int_equal(g.song.notes[i].track, 1);
    }
    assert_int_equal(g.song.notes[1].velocity, 90);
    cub_midi_groove_free(&g);
}

static void test_tempo_map_and_meter_as_read(void **state)
{
    (void)state;
    smf f;
    song(&f);
    cub_midi_groove g;
    assert_int_equal(cub_midi_groove_read(f.b, f.len, "tempo.mid", &g, NULL), CUB_OK);
    assert_int_equal(g.song.division, 480);
    assert_int_equal(g.song.tempo_count, 3);
    assert_int_equal(g.song.meter_count, 1);
    assert_int_equal(g.song.meters[0].numerator, 3);
    assert_int_equal(g.song.meters[0].denominator, 4);
    /* 2 quarters at 120, 2 at 240, then 60 bpm */
    assert_int_equal(cub_groove_tick_us(&g.song, 960), 1000000);
    assert_int_equal(cub_groove_tick_us(&g.song, 1920), 1500000);
    assert_int_equal(cub_groove_tick_us(&g.song, 2400), 2500000);
    /* the melody's notes carry those times; the 3/4 meter's beats */
    cub_groove_pick pick;
    cub_groove_note n[12];
    int count = 0;
    assert_int_equal(cub_groove_pick_tracks(&g.song, -1, -1, &pick), CUB_OK);
    assert_int_equal(cub_groove_notes(&g.song, &pick, n, 12, &count), CUB_OK);
    assert_int_equal(count, 5);
    assert_int_equal(n[4].start_us, 1500000);
    assert_int_equal(n[3].length_beats, CUB_Q16_ONE); /* cut where the retrigger starts */
    assert_true(n[4].is_beat);
    cub_midi_groove_free(&g);
}

/* The song's length as the box's scan measures it (midi_scan.c: its own
 * walk of the tempo map), to check the groove's tempo map against. */
static int64_t scan_length_us(const char *path)
{
    static uint8_t buf[1 << 22];
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    size_t len = fread(buf, 1, sizeof buf, f);
    fclose(f);
    cub_midi_info info;
    assert_int_equal(cub_midi_scan(buf, len, path, &info, NULL), CUB_OK);
    return info.length_us;
}

/* The whole slice on one file: loads, picks, segments, keys. */
static void groove_file(const char *path, int *songs)
{
    cub_midi_groove g;
    cub_diag d = {0};
    char msg[600];
    if (cub_midi_groove_load(path, &g, &d)) fail_msg("%s", cub_diag_str(&d, msg, sizeof msg));
    int cap = 2 * g.song.note_count + 1, n = 0, k = 0;
    cub_groove_note *notes = calloc((size_t)cap, sizeof(*notes));
    cub_groove_segment *segs = calloc((size_t)cap, sizeof(*segs));
    cub_groove_key *keys = calloc((size_t)cap, sizeof(*keys));
    static cub_groove_work work;
    cub_groove_pick pick;
    cub_groove_params p;
    cub_groove_params_set('a', &p);
    assert_int_equal(cub_groove_pick_tracks(&g.song, -1, -1, &pick), CUB_OK);
    assert_int_equal(cub_groove_notes(&g.song, &pick, notes, cap, &n), CUB_OK);
    assert_true(n > 8);
    assert_int_equal(cub_groove_segment_notes(&p, notes, n, 0, &work, segs, cap, &k, NULL), CUB_OK);
    assert_int_equal(cub_groove_keys(&p, notes, n, segs, k, keys), CUB_OK);
    for (int i = 1; i < n; i++)
        assert_true(notes[i].start_us >= notes[i - 1].start_us);
    if (strstr(path, "beethoven") || strstr(path, "joplin")) assert_true(g.song.tempo_count > 1);
    assert_int_equal(cub_groove_tick_us(&g.song, g.song.end_tick), scan_length_us(path));
    free(notes), free(segs), free(keys);
    cub_midi_groove_free(&g);
    (*songs)++;
}

static int groove_dir(const char *dir, int *songs)
{
    DIR *dp = opendir(dir);
    if (!dp) return 0;
    struct dirent *e;
    char path[1024];
    while ((e = readdir(dp)))
        if (strlen(e->d_name) > 4 && !strcmp(e->d_name + strlen(e->d_name) - 4, ".mid")) {
            snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
            groove_file(path, songs);
        }
    closedir(dp);
    return 1;
}

static void test_every_real_file_grooves(void **state)
{
    (void)state;
    const char *data = getenv("CUB_DATA_DIR");
    char dir[1024];
    int songs = 0;
    assert_true(groove_dir(CUB_ASSETS_DIR "/songs", &songs));
    assert_int_equal(songs, 3);
    snprintf(dir, sizeof dir, "%s/midi", data ? data : "../shared/data");
    if (!groove_dir(dir, &songs)) skip();
    assert_true(songs >= 3 + 16);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_files_name_the_file),
        cmocka_unit_test(test_pairing_keeps_every_note),
        cmocka_unit_test(test_tempo_map_and_meter_as_read),
        cmocka_unit_test(test_every_real_file_grooves),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

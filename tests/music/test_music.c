/* FluidSynth playback (cub/music.h): the shipped MIDI files parse, play
 * non-silent audio for the length their notation says (within 1 %); the
 * music clock is exactly frames / rate, scaled when a test asks; a missing
 * SoundFont or a bad MIDI file is a clear error. Under qemu (CUB_QUICK) the
 * whole-song renders run at 8 kHz to stay quick. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/music.h"
#include "cub/song.h"

static const char *src_dir(void)
{
    const char *s = getenv("CUB_SOURCE_DIR");
    return s ? s : "..";
}

static const char *build_path(const char *name, char *buf, size_t size)
{
    const char *b = getenv("CUB_BUILD_DIR");
    snprintf(buf, size, "%s/%s", b ? b : ".", name);
    return buf;
}

static void write_file(const char *path, const void *data, size_t len)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, len, f), len);
    fclose(f);
}

static cub_music *open_music(int rate)
{
    cub_music *m = NULL;
    cub_diag d = {0};
    char msg[600];
    cub_music_desc desc = {.rate = rate};
    if (cub_music_open(&desc, &m, &d)) fail_msg("%s", cub_diag_str(&d, msg, sizeof(msg)));
    return m;
}

static void test_music_missing_soundfont_is_an_error(void **state)
{
    (void)state;
    cub_music *m = (cub_music *)1;
    cub_diag d = {0};
    char msg[600], path[512];
    cub_music_desc desc = {.soundfont = "/nonexistent/none.sf2"};
    assert_int_equal(cub_music_open(&desc, &m, &d), CUB_ERR_IO);
    assert_null(m);
    printf("music: rejected: %s\n", cub_diag_str(&d, msg, sizeof(msg)));
    assert_string_equal(d.file, "/nonexistent/none.sf2");
    assert_non_null(strstr(d.msg, "cannot read the SoundFont"));
    /* A file that is there but is no SoundFont. */
    desc.soundfont = build_path("music_not_a_soundfont.sf2", path, sizeof(path));
    write_file(path, "RIFF\4\0\0\0junk", 12);
    assert_int_equal(cub_music_open(&desc, &m, &d), CUB_ERR_FORMAT);
    printf("music: rejected: %s\n", cub_diag_str(&d, msg, sizeof(msg)));
    assert_non_null(strstr(d.msg, "not a SoundFont 2 file"));
    /* The right header on a broken body: FluidSynth's own error. */
    write_file(path, "RIFF\x40\0\0\0sfbkLIST\x30\0\0\0INFOjunkjunk", 32);
    assert_int_equal(cub_music_open(&desc, &m, &d), CUB_ERR_FORMAT);
    printf("music: rejected: %s\n", cub_diag_str(&d, msg, sizeof(msg)));
    assert_non_null(strstr(d.msg, "FluidSynth cannot load this SoundFont"));
    desc = (cub_music_desc){.rate = 1000};
    assert_int_equal(cub_music_open(&desc, &m, &d), CUB_ERR_ARG);
}

/* A minimal format-0 file: one note, tempo 500000, 96 ticks a quarter. */
static const uint8_t
    good_midi[] = {'M',  'T',  'h',  'd',  0,    0,    0,    6,    0,    0,
                   0,    1,    0,    96,   'M',  'T',  'r',  'k',  0,    0,
                   0,    18,   0x00, 0xFF, 0x51, 0x03, 0x07, 0xA1, 0x20, /* tempo 500000 */
                   0x00, 0x90, 60,   100,  0x60, 60,   0, /* note on, running status off */
                   0x00, 0xFF, 0x2F, 0x00};

static void expect_bad_midi(cub_music *m, const uint8_t *data, size_t len, const char *words)
{
    char path[512], msg[600];
    cub_diag d = {0};
    build_path("music_bad.mid", path, sizeof(path));
    write_file(path, data, len);
    assert_int_equal(cub_music_load(m, path, &d), CUB_ERR_FORMAT);
    printf("music: rejected: %s\n", cub_diag_str(&d, msg, sizeof(msg)));
    assert_string_equal(d.file, path);
    if (!strstr(d.msg, words)) fail_msg("message '%s' lacks '%s'", d.msg, words);
}

static void test_music_bad_midi_is_an_error(void **state)
{
    (void)state;
    cub_music *m = open_music(44100);
    cub_diag d = {0};
    uint8_t b[sizeof(good_midi)];
    assert_int_equal(cub_music_play(m), CUB_ERR_EMPTY); /* nothing loaded */
    assert_int_equal(cub_music_load(m, "/nonexistent/song.mid", &d), CUB_ERR_IO);
    expect_bad_midi(m, (const uint8_t *)"hello, not midi at all", 22, "no MThd header");
    expect_bad_midi(m, good_midi, 30, "a chunk longer than the file");
    memcpy(b, good_midi, sizeof(b));
    b[sizeof(b) - 2] = 0x2E; /* no End of Track */
    expect_bad_midi(m, b, sizeof(b), "without End of Track");
    memcpy(b, good_midi, sizeof(b));
    b[30] = 0x40; /* a data byte where the first status should be */
    expect_bad_midi(m, b, sizeof(b), "no running status");
    memcpy(b, good_midi, sizeof(b));
    b[12] = 0xE7; /* SMPTE timing */
    expect_bad_midi(m, b, sizeof(b), "SMPTE");
    memcpy(b, good_midi, sizeof(b));
    b[32] = 200; /* velocity above 127 */
    expect_bad_midi(m, b, sizeof(b), "above 127");
    /* The good one plays: 1 quarter at 120 bpm = 0.5 s. */
    char path[512];
    build_path("music_good.mid", path, sizeof(path));
    write_file(path, good_midi, sizeof(good_midi));
    assert_int_equal(cub_music_load(m, path, &d), CUB_OK);
    assert_int_equal(cub_music_length_us(m), 500000);
    assert_int_equal(cub_music_play(m), CUB_OK);
    cub_music_close(m);
}

static void test_music_clock_is_frames_over_rate(void **state)
{
    (void)state;
    static const int rates[] = {44100, 48000, 22050};
    static const double scales[] = {1.0, 0.95, 1.05};
    char path[512];
    snprintf(path, sizeof(path), "%s/assets/songs/london_bridge.mid", src_dir());
    int16_t *buf = malloc(2 * 4096 * sizeof(int16_t));
    for (int r = 0; r < 3; r++) {
        cub_music *m = open_music(rates[r]);
        cub_diag d = {0};
        assert_int_equal(cub_music_load(m, path, &d), CUB_OK);
        cub_music_render(m, buf, 100); /* not playing: silence, no time */
        assert_int_equal(cub_music_frames(m), 0);
        assert_int_equal(buf[0] | buf[199], 0);
        assert_int_equal(cub_music_play(m), CUB_OK);
        uint64_t frames = 0;
        for (int i = 0; i < 60; i++) {
            int n = 1 + (i * 977) % 4096; /* odd block sizes, as audio devices ask */
            assert_int_equal(cub_music_set_clock_scale(m, scales[i % 3]), CUB_OK);
            cub_music_render(m, buf, n);
            frames += (uint64_t)n;
            int64_t exact = (int64_t)(frames * 1000000 / (uint64_t)rates[r]);
            int64_t ppm = (int64_t)(scales[i % 3] * 1e6 + 0.5);
            assert_int_equal(cub_music_frames(m), frames);
            assert_int_equal(cub_music_clock_us(m), exact * ppm / 1000000);
        }
        cub_music_set_clock_scale(m, 1.0);
        int64_t t = cub_music_clock_us(m);
        cub_music_set_clock_scale(m, 0.95);
        int64_t slow = cub_music_clock_us(m);
        cub_music_set_clock_scale(m, 1.05);
        int64_t fast = cub_music_clock_us(m);
        printf("music: clock rate=%d frames=%llu t_us=%lld scale0.95=%lld scale1.05=%lld\n",
               rates[r], (unsigned long long)frames, (long long)t, (long long)slow,
               (long long)fast);
        assert_true(llabs(slow - t * 95 / 100) <= 1 && llabs(fast - t * 105 / 100) <= 1);
        assert_int_equal(cub_music_set_clock_scale(m, 0.2), CUB_ERR_ARG);
        cub_music_stop(m); /* the clock stops where it is */
        cub_music_render(m, buf, 512);
        assert_int_equal(cub_music_frames(m), frames);
        assert_int_equal(cub_music_play(m), CUB_OK); /* and restarts at 0 */
        assert_int_equal(cub_music_clock_us(m), 0);
        cub_music_close(m);
    }
    free(buf);
}

/* RIFF WAVE, 16-bit stereo, little-endian. */
static FILE *wav_open(const char *path, int rate)
{
    FILE *f = fopen(path, "wb");
    uint8_t h[44] = {'R', 'I', 'F', 'F', 0,  0, 0, 0, 'W', 'A', 'V', 'E',
                     'f', 'm', 't', ' ', 16, 0, 0, 0, 1,   0,   2,   0};
    for (int i = 0; i < 4; i++) {
        h[24 + i] = (uint8_t)(rate >> (8 * i));
        h[28 + i] = (uint8_t)((rate * 4) >> (8 * i));
    }
    h[32] = 4;
    h[34] = 16;
    memcpy(h + 36, "data", 4);
    if (f) fwrite(h, 1, 44, f);
    return f;
}

static void wav_close(FILE *f, uint64_t frames)
{
    uint32_t data = (uint32_t)(frames * 4), riff = data + 36;
    uint8_t b[4];
    for (int i = 0; i < 4; i++)
        b[i] = (uint8_t)(riff >> (8 * i));
    fseek(f, 4, SEEK_SET);
    fwrite(b, 1, 4, f);
    for (int i = 0; i < 4; i++)
        b[i] = (uint8_t)(data >> (8 * i));
    fseek(f, 40, SEEK_SET);
    fwrite(b, 1, 4, f);
    fclose(f);
}

static void test_music_songs_play_their_length(void **state)
{
    (void)state;
    static const char *const names[] = {"twinkle", "old_macdonald", "london_bridge"};
    int quick = getenv("CUB_QUICK") != NULL, rate = quick ? 8000 : 44100, block = 512;
    char path[512], msg[600];
    cub_library lib;
    cub_diag d = {0};
    snprintf(path, sizeof(path), "%s/assets/clips/bear.cubclips", src_dir());
    if (cub_pack_read(path, &lib, &d)) fail_msg("%s", cub_diag_str(&d, msg, sizeof(msg)));
    cub_song *song = malloc(sizeof(*song));
    int16_t *buf = malloc(2 * (size_t)block * sizeof(int16_t));
    cub_music *m = open_music(rate);
    for (int i = 0; i < 3; i++) {
        snprintf(path, sizeof(path), "%s/assets/songs/%s.song.xml", src_dir(), names[i]);
        if (cub_song_load(path, &lib, song, &d)) fail_msg("%s", cub_diag_str(&d, msg, sizeof(msg)));
        if (cub_music_load(m, song->midi_path, &d))
            fail_msg("%s", cub_diag_str(&d, msg, sizeof(msg)));
        int64_t notation_us = cub_song_length_us(song);
        /* The file ends exactly where its notation does. */
        assert_true(llabs(cub_music_length_us(m) - notation_us) <= 1);
        FILE *wav = NULL;
        if (i == 0 && !quick) wav = wav_open(build_path("twinkle.wav", msg, sizeof(msg)), rate);
        assert_int_equal(cub_music_play(m), CUB_OK);
        double sum2 = 0;
        int peak = 0;
        uint64_t cap = (uint64_t)(notation_us / 1000000 + 10) * (uint64_t)rate;
        while (cub_music_playing(m) && cub_music_frames(m) < cap) {
            cub_music_render(m, buf, block);
            for (int k = 0; k < 2 * block; k++) {
                sum2 += (double)buf[k] * buf[k];
                peak = abs(buf[k]) > peak ? abs(buf[k]) : peak;
            }
            if (wav) fwrite(buf, sizeof(int16_t), 2 * (size_t)block, wav);
        }
        uint64_t frames = cub_music_frames(m);
        if (wav) wav_close(wav, frames);
        int64_t played_us = cub_music_clock_us(m);
        double rms = sqrt(sum2 / (2.0 * (double)frames));
        double err = fabs((double)(played_us - notation_us)) / (double)notation_us;
        printf("music: %s rate=%d played=%.3f s notation=%.3f s err=%.3f%% rms=%.0f (%.1f dBFS) "
               "peak=%d\n",
               names[i], rate, played_us / 1e6, notation_us / 1e6, 100 * err, rms,
               20 * log10(rms / 32768.0), peak);
        assert_true(err < 0.01);
        assert_true(rms > 300);    /* well above FluidSynth's dither */
        assert_true(peak < 32767); /* and not clipping */
    }
    cub_music_close(m);
    free(buf);
    free(song);
    cub_library_free(&lib);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_music_missing_soundfont_is_an_error),
        cmocka_unit_test(test_music_bad_midi_is_an_error),
        cmocka_unit_test(test_music_clock_is_frames_over_rate),
        cmocka_unit_test(test_music_songs_play_their_length),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

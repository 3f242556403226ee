/* voicepack: the bear's spoken words on disk. First what bad packs get (a
 * message with the file and the byte), then the round trip, the lookup by
 * text, and the pack the build made: every phrase the box can show for
 * each shipped song is in it (skipped when the build had no espeak-ng). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "cub/faults.h"
#include "cub/pack.h"
#include "cub/song.h"
#include "cub/voicepack.h"
#include "pack_internal.h" /* pack_crc32: a damaged pack with a good CRC */
#include "words.h"

static int16_t pcm1[300], pcm2[500];

static const char *tmp_path(void)
{
    static char path[64];
    snprintf(path, sizeof path, "/tmp/test_voicepack_%d.cubvoice", (int)getpid());
    return path;
}

/* A two-phrase pack's bytes (heap) and its length. */
static uint8_t *two_phrases(size_t *len)
{
    for (int i = 0; i < 300; i++) pcm1[i] = (int16_t)(i * 100 - 15000);
    for (int i = 0; i < 500; i++) pcm2[i] = (int16_t)(-i * 60);
    cub_voice_phrase ph[2] = {{.text = "Clap with me!", .pcm = pcm1, .frames = 300},
                              {.text = "Jump!", .pcm = pcm2, .frames = 500}};
    cub_diag diag;
    assert_int_equal(cub_voicepack_write(tmp_path(), 22050, ph, 2, &diag), CUB_OK);
    FILE *f = fopen(tmp_path(), "rb");
    assert_non_null(f);
    uint8_t *buf = malloc(8192);
    *len = fread(buf, 1, 8192, f);
    fclose(f);
    remove(tmp_path());
    return buf;
}

static void put_u32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++) p[i] = (uint8_t)(v >> (8 * i));
}

static void fix_crc(uint8_t *b, size_t len)
{
    put_u32(b + len - 4, pack_crc32(b, len - 4));
}

/* Parse b as "bad.cubvoice"; the message must hold want. */
static void refused(const uint8_t *b, size_t len, const char *want)
{
    cub_voicepack p;
    cub_diag diag;
    char buf[600];
    assert_int_equal(cub_voicepack_parse(b, len, "bad.cubvoice", &p, &diag), CUB_ERR_FORMAT);
    cub_diag_str(&diag, buf, sizeof buf);
    if (!strstr(buf, "bad.cubvoice: at byte ") || !strstr(buf, want))
        fail_msg("message '%s' lacks '%s'", buf, want);
    assert_null(p.mem);
}

static void test_bad_packs_are_refused_with_the_byte(void **state)
{
    (void)state;
    size_t len;
    uint8_t *good = two_phrases(&len), *b = malloc(len + 16);
    refused(good, 0, "too short");
    refused(good, 10, "too short");
    memcpy(b, good, len), b[0] = 'X', refused(b, len, "not a voice pack");
    memcpy(b, good, len), b[len - 1] ^= 1, refused(b, len, "CRC mismatch");
    memcpy(b, good, len), put_u32(b + 8, 2), fix_crc(b, len), refused(b, len, "version 2");
    memcpy(b, good, len), put_u32(b + 12, 100), fix_crc(b, len), refused(b, len, "rate 100 Hz");
    memcpy(b, good, len), put_u32(b + 16, 0), fix_crc(b, len), refused(b, len, "phrase count 0");
    memcpy(b, good, len), put_u32(b + 16, 3), fix_crc(b, len), refused(b, len, "phrase 2: the header");
    memcpy(b, good, len), b[20] ^= 1, fix_crc(b, len), refused(b, len, "is not its text's");
    memcpy(b, good, len), put_u32(b + 24, 0), fix_crc(b, len), refused(b, len, "text of 0 bytes");
    memcpy(b, good, len), put_u32(b + 24, 99999), fix_crc(b, len), refused(b, len, "text of 99999");
    memcpy(b, good, len), b[30] = 0, fix_crc(b, len), refused(b, len, "NUL byte");
    memcpy(b, good, len), put_u32(b + 41, 0xffffffffu), fix_crc(b, len), refused(b, len, "frames is not in");
    memcpy(b, good, len), put_u32(b + 41, 100000), fix_crc(b, len), refused(b, len, "only");
    memcpy(b, good, len - 4), memset(b + len - 4, 0, 8), fix_crc(b, len + 4),
        refused(b, len + 4, "after the last phrase");
    free(good);
    free(b);
}

static void test_a_pack_with_one_text_twice_is_refused(void **state)
{
    (void)state;
    cub_voice_phrase ph[2] = {{.text = "Jump!", .pcm = pcm1, .frames = 10},
                              {.text = "Jump!", .pcm = pcm2, .frames = 10}};
    cub_diag diag;
    assert_int_equal(cub_voicepack_write(tmp_path(), 22050, ph, 2, &diag), CUB_ERR_ARG);
    assert_non_null(strstr(diag.msg, "twice"));
    /* made by hand from two copies of phrase 0: the reader refuses it too */
    size_t len;
    uint8_t *good = two_phrases(&len);
    size_t p0 = 20, p0_len = 8 + 13 + 4 + 300 * 2;
    uint8_t *b = malloc(20 + 2 * p0_len + 4);
    memcpy(b, good, 20);
    memcpy(b + 20, good + p0, p0_len);
    memcpy(b + 20 + p0_len, good + p0, p0_len);
    fix_crc(b, 20 + 2 * p0_len + 4);
    refused(b, 20 + 2 * p0_len + 4, "the same text as phrase 0");
    free(b);
    free(good);
}

static void test_a_missing_file_is_named(void **state)
{
    (void)state;
    cub_voicepack p;
    cub_diag diag;
    char buf[600];
    assert_int_equal(cub_voicepack_read("/nonexistent/bear.cubvoice", &p, &diag), CUB_ERR_IO);
    assert_non_null(strstr(cub_diag_str(&diag, buf, sizeof buf), "/nonexistent/bear.cubvoice"));
}

static void test_round_trip_keeps_every_sample(void **state)
{
    (void)state;
    size_t len;
    uint8_t *b = two_phrases(&len);
    cub_voicepack p;
    cub_diag diag;
    assert_int_equal(cub_voicepack_parse(b, len, "good.cubvoice", &p, &diag), CUB_OK);
    assert_int_equal(p.rate, 22050);
    assert_int_equal(p.count, 2);
    assert_string_equal(p.phrases[0].text, "Clap with me!");
    assert_int_equal(p.phrases[0].id, cub_voicepack_id("Clap with me!"));
    assert_int_equal(p.phrases[1].frames, 500);
    assert_memory_equal(p.phrases[0].pcm, pcm1, sizeof pcm1);
    assert_memory_equal(p.phrases[1].pcm, pcm2, sizeof pcm2);
    assert_int_equal(cub_voicepack_find(&p, "Jump!"), 1);
    assert_int_equal(cub_voicepack_find(&p, "Jump"), -1);
    assert_int_equal(cub_voicepack_find(&p, NULL), -1);
    /* the same phrases write the same bytes */
    size_t len2;
    uint8_t *b2 = two_phrases(&len2);
    assert_int_equal(len, len2);
    assert_memory_equal(b, b2, len);
    cub_voicepack_free(&p);
    free(b);
    free(b2);
}

static void test_the_id_is_fnv1a_of_the_text(void **state)
{
    (void)state;
    assert_int_equal(cub_voicepack_id(""), 0x811c9dc5u);
    assert_int_equal(cub_voicepack_id("a"), 0xe40c292cu); /* FNV-1a's published value */
}

/* ---- the pack the build made ------------------------------------------------ */

static const char *built_pack, *assets_dir;

typedef struct coverage {
    const cub_voicepack *pack;
    int missing, seen;
} coverage;

static void check_phrase(void *user, const char *text)
{
    coverage *c = user;
    c->seen++;
    if (cub_voicepack_find(c->pack, text) < 0) {
        print_error("no voice for \"%s\"\n", text);
        c->missing++;
    }
}

static void test_the_built_pack_speaks_every_phrase_of_every_song(void **state)
{
    (void)state;
    cub_voicepack p;
    cub_diag diag;
    char buf[600];
    if (cub_voicepack_read(built_pack, &p, &diag)) {
        print_message("SKIP: %s (espeak-ng missing at build time?)\n", cub_diag_str(&diag, buf, sizeof buf));
        skip();
    }
    cub_library lib;
    char path[1024];
    snprintf(path, sizeof path, "%s/clips/bear.cubclips", assets_dir);
    assert_int_equal(cub_pack_read(path, &lib, &diag), CUB_OK);
    coverage c = {.pack = &p};
    cub_words_each(NULL, NULL, check_phrase, &c);
    static const char *songs[] = {"twinkle", "old_macdonald", "london_bridge"};
    static cub_song song;
    static cub_faults faults;
    for (size_t i = 0; i < sizeof songs / sizeof *songs; i++) {
        snprintf(path, sizeof path, "%s/songs/%s.song.xml", assets_dir, songs[i]);
        assert_int_equal(cub_song_load(path, &lib, &song, &diag), CUB_OK);
        faults.count = 0;
        if (song.faults_path[0])
            assert_int_equal(cub_faults_load(song.faults_path, &lib, &faults, &diag), CUB_OK);
        cub_words_each(&song, &faults, check_phrase, &c);
    }
    double seconds = 0;
    size_t bytes = 0;
    for (int i = 0; i < p.count; i++) {
        seconds += (double)p.phrases[i].frames / p.rate;
        bytes += p.phrases[i].frames * 2u;
        assert_true(p.phrases[i].frames > (uint32_t)p.rate / 5); /* words, not a click */
    }
    printf("voice pack: %d phrases, %.1f s at %d Hz, %zu kB of samples; %d lookups, %d missing\n",
           p.count, seconds, p.rate, bytes / 1024, c.seen, c.missing);
    assert_int_equal(c.missing, 0);
    cub_library_free(&lib);
    cub_voicepack_free(&p);
}

int main(int argc, char **argv)
{
    built_pack = argc > 1 ? argv[1] : "build/host/assets/voice/bear.cubvoice";
    assets_dir = argc > 2 ? argv[2] : "assets";
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_packs_are_refused_with_the_byte),
        cmocka_unit_test(test_a_pack_with_one_text_twice_is_refused),
        cmocka_unit_test(test_a_missing_file_is_named),
        cmocka_unit_test(test_round_trip_keeps_every_sample),
        cmocka_unit_test(test_the_id_is_fnv1a_of_the_text),
        cmocka_unit_test(test_the_built_pack_speaks_every_phrase_of_every_song),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

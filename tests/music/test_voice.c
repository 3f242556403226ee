/* voice: the bear's words over the music. First what it does with nothing
 * to say, then the timing of a phrase, the duck and its ramps, replacing,
 * and that the output depends on the requests only, not on buffer sizes. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/voice.h"

#define RATE 44100
#define MUSIC 10000
#define N 2000 /* frames of each test phrase at the pack's 22050 Hz */

static int16_t pcm_a[N], pcm_b[N];
static cub_voice_phrase phrases[2];
static cub_voicepack pack = {.rate = 22050, .count = 2, .phrases = phrases};

static int setup(void **state)
{
    (void)state;
    for (int i = 0; i < N; i++) {
        pcm_a[i] = 8000;                           /* a flat phrase: easy to read back */
        pcm_b[i] = (int16_t)(i % 2 ? -6000 : 6000); /* another, unlike it */
    }
    phrases[0] = (cub_voice_phrase){.text = "Clap!", .pcm = pcm_a, .frames = N};
    phrases[1] = (cub_voice_phrase){.text = "Jump!", .pcm = pcm_b, .frames = N};
    return 0;
}

static int16_t *music(int frames, int16_t level)
{
    int16_t *s = malloc((size_t)frames * 2 * sizeof *s);
    for (int i = 0; i < 2 * frames; i++) s[i] = level;
    return s;
}

static void test_without_a_pack_the_music_is_untouched(void **state)
{
    (void)state;
    cub_voice v;
    assert_int_equal(cub_voice_init(&v, NULL, RATE), CUB_OK);
    cub_voice_say(&v, 0);
    int16_t *s = music(512, MUSIC);
    cub_voice_mix(&v, s, 512);
    for (int i = 0; i < 1024; i++) assert_int_equal(s[i], MUSIC);
    free(s);
    assert_int_equal(cub_voice_init(&v, &pack, 100), CUB_ERR_ARG); /* a rate out of range */
    assert_int_equal(cub_voice_init(NULL, &pack, RATE), CUB_ERR_ARG);
}

static void test_nothing_said_leaves_the_music_as_it_is(void **state)
{
    (void)state;
    cub_voice v;
    cub_voice_init(&v, &pack, RATE);
    cub_voice_say(&v, 7); /* not a phrase of the pack: ignored */
    int16_t *s = music(1024, MUSIC);
    cub_voice_mix(&v, s, 1024);
    for (int i = 0; i < 2048; i++) assert_int_equal(s[i], MUSIC);
    free(s);
}

static void test_a_phrase_starts_at_the_next_buffer(void **state)
{
    (void)state;
    cub_voice v;
    cub_voice_init(&v, &pack, RATE);
    int16_t *s = music(1024, 0);
    cub_voice_mix(&v, s, 1024);
    for (int i = 0; i < 2048; i++) assert_int_equal(s[i], 0);
    cub_voice_say(&v, 0);
    cub_voice_mix(&v, s, 1024);
    /* from the buffer's first frame, both channels, upsampled 2x */
    assert_int_equal(s[0], 8000);
    assert_int_equal(s[1], 8000);
    for (int i = 0; i < 2048; i++) assert_int_equal(s[i], 8000);
    free(s);
}

static void test_the_music_ducks_to_30_percent_with_ramps(void **state)
{
    (void)state;
    cub_voice v;
    cub_voice_init(&v, &pack, RATE);
    cub_voice_say(&v, 1);
    int frames = 2 * N + RATE / 2; /* the phrase (4000 frames at 44.1 kHz) and half a second */
    int16_t *s = music(frames, MUSIC);
    cub_voice_mix(&v, s, frames);
    int attack = RATE * CUB_VOICE_ATTACK_MS / 1000, release = RATE * CUB_VOICE_RELEASE_MS / 1000;
    /* voice b alternates +-6000 every two device frames: the pair's mean is the music */
    for (int f = attack + 4; f < 2 * N - 4; f += 4) {
        int mean = (s[2 * f] + s[2 * (f + 2)]) / 2;
        assert_in_range(mean, 3000 - 2, 3000 + 2);
    }
    for (int f = 1; f < attack; f += 4) /* the ramp down: between full and ducked */
        assert_in_range((s[2 * f] + s[2 * (f + 2)]) / 2, 2990, MUSIC);
    int back = 2 * N + release + 2;
    for (int f = back; f < frames; f++) assert_int_equal(s[2 * f], MUSIC);
    assert_in_range(s[2 * (2 * N + release / 2)], 3000, MUSIC - 1); /* on its way back */
    free(s);
}

static void test_a_new_phrase_replaces_the_old_after_a_short_fade(void **state)
{
    (void)state;
    cub_voice v;
    cub_voice_init(&v, &pack, RATE);
    int16_t *s = music(4096, 0);
    cub_voice_say(&v, 0);
    cub_voice_mix(&v, s, 1024);
    cub_voice_say(&v, 1);
    memset(s, 0, 4096 * 4);
    cub_voice_mix(&v, s, 4096);
    int fade = RATE * CUB_VOICE_FADE_MS / 1000;
    /* the old phrase only, fading (never both at once) */
    for (int f = 1; f < fade; f++) {
        assert_true(s[2 * f] <= s[2 * (f - 1)]);
        assert_true(s[2 * f] >= 0);
    }
    /* then the new one from its start, alone */
    for (int f = fade; f < 4096; f += 2) assert_int_equal(abs(s[2 * f]), 6000);
    free(s);
}

static void test_the_same_phrase_asked_again_goes_on(void **state)
{
    (void)state;
    cub_voice v;
    cub_voice_init(&v, &pack, RATE);
    int16_t *s = music(1024, 0);
    cub_voice_say(&v, 1);
    cub_voice_mix(&v, s, 1001); /* frame 1000 is b[500] = +6000 */
    assert_int_equal(s[2 * 1000], 6000);
    cub_voice_say(&v, 1);
    memset(s, 0, 1024 * 4);
    cub_voice_mix(&v, s, 2);
    /* frames 1001 (between b[500] and b[501]) and 1002 (b[501]); a restart
     * would give b[0] = +6000 and the midpoint 0 */
    assert_int_equal(s[0], 0);
    assert_int_equal(s[2], -6000);
    free(s);
}

static void test_stop_fades_out_and_the_music_comes_back(void **state)
{
    (void)state;
    cub_voice v;
    cub_voice_init(&v, &pack, RATE);
    int frames = RATE;
    int16_t *s = music(frames, MUSIC);
    cub_voice_say(&v, 0);
    cub_voice_mix(&v, s, 1024);
    cub_voice_say(&v, -1);
    cub_voice_mix(&v, s, frames);
    assert_int_equal(s[2 * (frames - 1)], MUSIC);
    free(s);
}

/* The same requests give the same samples, whatever the device's buffers. */
static void test_output_does_not_depend_on_buffer_size(void **state)
{
    (void)state;
    int total = 8192;
    int16_t *a = music(total, 1234), *b = music(total, 1234);
    cub_voice va, vb;
    cub_voice_init(&va, &pack, RATE);
    cub_voice_init(&vb, &pack, 48000 - 3900); /* 44100, spelt otherwise */
    cub_voice_say(&va, 1);
    cub_voice_say(&vb, 1);
    cub_voice_mix(&va, a, total);
    for (int at = 0; at < total; at += 512) cub_voice_mix(&vb, b + 2 * at, 512);
    assert_memory_equal(a, b, (size_t)total * 4);
    free(a);
    free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_without_a_pack_the_music_is_untouched),
        cmocka_unit_test(test_nothing_said_leaves_the_music_as_it_is),
        cmocka_unit_test(test_a_phrase_starts_at_the_next_buffer),
        cmocka_unit_test(test_the_music_ducks_to_30_percent_with_ramps),
        cmocka_unit_test(test_a_new_phrase_replaces_the_old_after_a_short_fade),
        cmocka_unit_test(test_the_same_phrase_asked_again_goes_on),
        cmocka_unit_test(test_stop_fades_out_and_the_music_comes_back),
        cmocka_unit_test(test_output_does_not_depend_on_buffer_size),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}

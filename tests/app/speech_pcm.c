/* speech_pcm — what the box wrote through SDL's disk audio driver, against
 * its event log (check_speech.sh runs the box):
 *   speech_pcm PCM_ON LOG_ON PCM_OFF LOG_OFF PACK "PHRASE" HINT
 * The speech=1 run: the phrase lands in its audio within one audio buffer
 * of its `speech say` line, that line is at the tick of the `coach hint
 * show=HINT` line, and the music under it is ducked to 0.3 of the same
 * music in the speech=0 run (lined up by correlation), and comes back
 * after. The speech=0 run: no `speech` line, no sign of the phrase
 * anywhere in its audio. PCM is interleaved stereo int16 at 44.1 kHz; the
 * phrase as the mixer adds it comes from the mixer itself (cub_voice_mix
 * over silence). Prints the figures; exit 0 when all hold, 1 when one does
 * not, 77 without a pack. */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/voice.h"
#include "cub/voicepack.h"

#define RATE 44100
#define BUFFER_FRAMES 1024 /* board/common/audio_sdl.c */
#define DECIM 8            /* the search over the whole file runs at 5.5 kHz */

typedef struct pcm {
    int16_t *s; /* stereo */
    long frames;
} pcm;

static int fail(const char *what)
{
    printf("FAIL: %s\n", what);
    return 1;
}

static int read_pcm(const char *path, pcm *p)
{
    FILE *f = fopen(path, "rb");
    if (!f) return -1;
    fseek(f, 0, SEEK_END);
    long bytes = ftell(f);
    fseek(f, 0, SEEK_SET);
    p->frames = bytes / 4;
    p->s = malloc((size_t)p->frames * 4 + 4);
    size_t got = p->s ? fread(p->s, 4, (size_t)p->frames, f) : 0;
    fclose(f);
    return got == (size_t)p->frames ? 0 : -1;
}

/* The phrase exactly as the mixer adds it at RATE (one channel). */
static int32_t *voice_alone(const cub_voicepack *pack, int phrase, long *n)
{
    const cub_voice_phrase *ph = &pack->phrases[phrase];
    *n = (long)((uint64_t)ph->frames * RATE / (uint64_t)pack->rate) + 1;
    int16_t *st = calloc((size_t)*n * 2, sizeof *st);
    int32_t *v = malloc((size_t)*n * sizeof *v);
    static cub_voice voice;
    if (!st || !v || cub_voice_init(&voice, pack, RATE)) return NULL;
    cub_voice_say(&voice, phrase);
    cub_voice_mix(&voice, st, (int)*n);
    for (long i = 0; i < *n; i++) v[i] = st[2 * i];
    free(st);
    return v;
}

/* Normalised correlation of the file's left channel at lag with v[0..n). */
static double ncc(const pcm *p, long lag, const int32_t *v, long n)
{
    double xv = 0, xx = 0, vv = 0;
    for (long i = 0; i < n && lag + i < p->frames; i++) {
        double x = p->s[2 * (lag + i)], y = v[i];
        xv += x * y, xx += x * x, vv += y * y;
    }
    return xx > 0 && vv > 0 ? xv / sqrt(xx * vv) : 0;
}

/* p averaged over DECIM frames (kept stereo-shaped, both channels the left). */
static pcm decimate(const pcm *p)
{
    pcm d = {.frames = p->frames / DECIM};
    d.s = malloc((size_t)d.frames * 4 + 4);
    for (long k = 0; d.s && k < d.frames; k++) {
        int32_t sum = 0;
        for (int i = 0; i < DECIM; i++) sum += p->s[2 * (k * DECIM + i)];
        d.s[2 * k] = d.s[2 * k + 1] = (int16_t)(sum / DECIM);
    }
    return d;
}

static int32_t *decimate_v(const int32_t *v, long n)
{
    int32_t *d = malloc((size_t)(n / DECIM + 1) * sizeof *d);
    for (long k = 0; d && k < n / DECIM; k++) {
        int32_t sum = 0;
        for (int i = 0; i < DECIM; i++) sum += v[k * DECIM + i];
        d[k] = sum / DECIM;
    }
    return d;
}

static long best_lag(const pcm *p, long from, long to, const int32_t *v, long n, double *score)
{
    long best = from;
    *score = -2;
    for (long lag = from < 0 ? 0 : from; lag <= to && lag < p->frames; lag++) {
        double c = ncc(p, lag, v, n);
        if (c > *score) *score = c, best = lag;
    }
    return best;
}

/* RMS of the left channel over [a, b), less v aligned at lag (NULL: none). */
static double rms(const pcm *p, long a, long b, const int32_t *v, long lag)
{
    double sum = 0;
    long n = 0;
    for (long i = a < 0 ? 0 : a; i < b && i < p->frames; i++, n++) {
        double x = p->s[2 * i] - (v ? v[i - lag] : 0);
        sum += x * x;
    }
    return n ? sqrt(sum / (double)n) : 0;
}

/* The t= of the first line holding key, and its audio_frame= (or -1). */
static int find_line(const char *log, const char *key, double *t, long *frame)
{
    FILE *f = fopen(log, "r");
    char line[1024];
    int found = 0;
    while (f && !found && fgets(line, sizeof line, f)) {
        if (!strstr(line, key)) continue;
        found = sscanf(line, "t=%lf", t) == 1;
        const char *a = strstr(line, "audio_frame=");
        *frame = a ? atol(a + 12) : -1;
    }
    if (f) fclose(f);
    return found;
}

/* Where the same music stands in the other run: the offset d (frames) that
 * lines other[i + d] up with p[i] over [a, b), coarse then exact. */
static long align(const pcm *p, const pcm *other, long a, long b)
{
    long n = b - a, best = 0;
    int32_t *ref = malloc((size_t)n * sizeof *ref);
    if (!ref) return 0;
    for (long i = 0; i < n; i++) ref[i] = p->s[2 * (a + i)];
    double score;
    pcm od = decimate(other);
    int32_t *rd = decimate_v(ref, n);
    long coarse = od.s && rd ? DECIM * best_lag(&od, (a - RATE) / DECIM, (a + RATE) / DECIM, rd,
                                               n / DECIM, &score)
                             : a;
    best = best_lag(other, coarse - 2 * DECIM, coarse + 2 * DECIM, ref, n, &score) - a;
    free(od.s);
    free(rd);
    free(ref);
    return best;
}

/* RMS of p over [a, b) less v at lag (or nothing), over other's at [a+d, b+d). */
static double ratio(const pcm *p, const pcm *other, long d, long a, long b, const int32_t *v,
                    long lag)
{
    double o = rms(other, a + d, b + d, NULL, 0);
    return o > 0 ? rms(p, a, b, v, lag) / o : 0;
}

/* The audio_frame of the first `speech say` line past frame (LONG_MAX: none). */
static long next_say_frame(const char *log, long frame)
{
    FILE *f = fopen(log, "r");
    char line[1024];
    long next = LONG_MAX;
    while (f && fgets(line, sizeof line, f)) {
        const char *a = strstr(line, " speech say ") ? strstr(line, "audio_frame=") : NULL;
        long at = a ? atol(a + 12) : -1;
        if (at > frame && at < next) next = at;
    }
    if (f) fclose(f);
    return next;
}

static int check_on(const pcm *p, const pcm *off, const char *log, const char *phrase,
                    const char *hint, const int32_t *v, long n)
{
    char key[512];
    double t_say = 0, t_hint = 0;
    long frame = -1, unused;
    snprintf(key, sizeof key, "speech say text=\"%s\"", phrase);
    if (!find_line(log, key, &t_say, &frame)) return fail("no speech say line for the phrase");
    snprintf(key, sizeof key, "coach hint show=%s", hint);
    if (!find_line(log, key, &t_hint, &unused)) return fail("no coach hint line");
    double score;
    long onset = best_lag(p, frame - 4 * BUFFER_FRAMES, frame + 8 * BUFFER_FRAMES, v,
                          n < RATE / 2 ? n : RATE / 2, &score);
    printf("hint t=%.3f, speech say t=%.3f audio_frame=%ld; voice found at frame %ld (%+ld frames,"
           " %.1f ms after asked), correlation %.3f\n", t_hint, t_say, frame, onset, onset - frame,
           (onset - frame) * 1000.0 / RATE, score);
    if (t_say != t_hint) return fail("the phrase was not asked for at the hint's tick");
    if (score < 0.9) return fail("the phrase is not in the written audio near its frame");
    if (onset < frame || onset > frame + BUFFER_FRAMES)
        return fail("the voice does not start within one audio buffer of its line");
    /* The music alone is the speech=0 run's, at the same place in the song. */
    long attack = RATE * CUB_VOICE_ATTACK_MS / 1000, rel = RATE * CUB_VOICE_RELEASE_MS / 1000;
    long b0 = onset - RATE / 2, b1 = onset - RATE / 50, a0 = onset + n + rel, a1 = a0 + RATE / 2;
    long next = next_say_frame(log, frame); /* what comes next must not be measured */
    if (a1 > next) a1 = next;
    if (a1 - a0 < RATE / 10)
        return fail("the next phrase came before the music could be heard back after the voice");
    long d = align(p, off, b0, b1);
    double before = ratio(p, off, d, b0, b1, NULL, 0), under = ratio(p, off, d, onset + attack,
                                                                      onset + n, v, onset);
    double after = ratio(p, off, d, a0, a1, NULL, 0), music = rms(off, b0 + d, b1 + d, NULL, 0);
    printf("music (RMS against the speech=0 run's, lined up %+ld frames; music RMS %.0f): "
           "%.2f before the voice, %.2f under it (the duck: %.2f), %.2f after\n", d, music, before,
           under, CUB_VOICE_DUCK_PERMILLE / 1000.0, after);
    if (music < 8) return fail("no music before the voice to measure the duck against");
    if (before < 0.9 || before > 1.1) return fail("the two runs' music does not line up");
    if (under > 0.4 || under < 0.2) return fail("the music is not ducked to 0.3 under the voice");
    if (after < 0.9 || after > 1.1) return fail("the music does not come back after the voice");
    return 0;
}

static int check_off(const pcm *p, const char *log, const char *hint, const int32_t *v, long n)
{
    double t = 0, score;
    long frame;
    char key[256];
    if (find_line(log, "speech ", &t, &frame)) return fail("a speech line with speech=0");
    snprintf(key, sizeof key, "coach hint show=%s", hint);
    if (!find_line(log, key, &t, &frame)) return fail("no coach hint line");
    pcm pd = decimate(p);
    int32_t *vd = decimate_v(v, n);
    long nd = (n < RATE ? n : RATE) / DECIM;
    long at = pd.s && vd ? DECIM * best_lag(&pd, 0, pd.frames - nd, vd, nd, &score) : 0;
    free(pd.s);
    free(vd);
    if (!pd.s || !vd) return fail("out of memory");
    printf("speech=0: hint t=%.3f; the best match of the phrase anywhere: correlation %.3f at "
           "frame %ld; audio %.2f s\n", t, score, at, (double)p->frames / RATE);
    return score > 0.5 ? fail("the phrase is in the audio with speech=0") : 0;
}

int main(int argc, char **argv)
{
    if (argc != 8) {
        fprintf(stderr, "usage: speech_pcm PCM_ON LOG_ON PCM_OFF LOG_OFF PACK PHRASE HINT\n");
        return 2;
    }
    cub_voicepack pack;
    cub_diag diag;
    char buf[600];
    if (cub_voicepack_read(argv[5], &pack, &diag)) {
        printf("SKIP: %s\n", cub_diag_str(&diag, buf, sizeof buf));
        return 77;
    }
    int phrase = cub_voicepack_find(&pack, argv[6]);
    pcm on = {0}, off = {0};
    long n = 0;
    int32_t *v = phrase >= 0 ? voice_alone(&pack, phrase, &n) : NULL;
    int rc = 0;
    if (!v) rc = fail("the phrase is not in the pack");
    else if (read_pcm(argv[1], &on) || read_pcm(argv[3], &off) || on.frames < RATE || off.frames < RATE)
        rc = fail("cannot read the written audio");
    else
        rc = check_off(&off, argv[4], argv[7], v, n) | check_on(&on, &off, argv[2], argv[6], argv[7], v, n);
    free(v);
    free(on.s);
    free(off.s);
    cub_voicepack_free(&pack);
    return rc;
}

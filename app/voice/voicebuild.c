/* cubvoice: the bear's spoken words, a build step (app/voice/CMakeLists.txt).
 * Every phrase the box can show for the songs given (words.c's cub_words_each: the moves' hints, the
 * coach's own hints, the title, the cheer, the inset's cues) is spoken by
 * espeak-ng into <work>/<id>.wav (id: the phrase's FNV-1a, so a phrase is
 * found by its text), trimmed of the silence espeak puts around it,
 * brought to one peak level and packed into one voice pack
 * (cub/voicepack.h). A small program of its own, not a cubtool command,
 * so that a tree that builds only the box (the packages) builds it fast. */
#include <errno.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "cub/faults.h"
#include "cub/pack.h"
#include "cub/song.h"
#include "cub/voicepack.h"
#include "words.h"

extern char **environ;

#define MAX_SONGS 64
#define PEAK 23197         /* -3 dBFS: above the music ducked under it, never clipped */
#define QUIET 96           /* |sample| below this is espeak's lead-in or tail */
#define KEEP_MS 5          /* of it kept before and after the words */

typedef struct voice_opts {
    const char *out, *work, *espeak, *library, *voice;
    int pitch, speed;
    const char *songs[MAX_SONGS];
    int song_count;
} voice_opts;

typedef struct phrase_list {
    const char *text[CUB_VOICEPACK_MAX_PHRASES];
    int count, overflow;
} phrase_list;

static void usage(FILE *f)
{
    fprintf(f,
            "usage: cubvoice --out FILE [--work DIR] [--espeak PROG] [--library FILE]\n"
            "                [--voice NAME] [--pitch 0..99] [--speed WPM] SONG.song.xml...\n"
            "Speak every phrase the box can show for these songs with espeak-ng and pack\n"
            "them into a voice pack. --work (an existing folder) keeps each phrase's\n"
            "<id>.txt and <id>.wav (default: FILE's folder); --voice (default en-us+f3), --pitch (70) and\n"
            "--speed (135 words a minute): a friendly voice, higher and slower than\n"
            "espeak's own. --phrases instead of --out only lists the phrases.\n");
}

static int parse_args(int argc, char **argv, voice_opts *o, int *list_only)
{
    *o = (voice_opts){.espeak = "espeak-ng", .voice = "en-us+f3", .pitch = 70, .speed = 135,
                      .library = CUB_ASSETS_DIR "/clips/bear.cubclips"};
    *list_only = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        const char **slot = !strcmp(a, "--out")       ? &o->out
                            : !strcmp(a, "--work")    ? &o->work
                            : !strcmp(a, "--espeak")  ? &o->espeak
                            : !strcmp(a, "--library") ? &o->library
                            : !strcmp(a, "--voice")   ? &o->voice
                                                      : NULL;
        if (!strcmp(a, "--help")) return usage(stdout), 1;
        if (!strcmp(a, "--phrases")) {
            *list_only = 1;
        } else if (slot || !strcmp(a, "--pitch") || !strcmp(a, "--speed")) {
            if (!v) return fprintf(stderr, "cubvoice: %s needs a value\n", a), -1;
            if (slot) *slot = v;
            else if (!strcmp(a, "--pitch")) o->pitch = atoi(v);
            else o->speed = atoi(v);
            i++;
        } else if (a[0] == '-') {
            return fprintf(stderr, "cubvoice: unknown option '%s'\n", a), -1;
        } else if (o->song_count < MAX_SONGS) {
            o->songs[o->song_count++] = a;
        } else {
            return fprintf(stderr, "cubvoice: more than %d songs\n", MAX_SONGS), -1;
        }
    }
    if (!*list_only && !o->out) return fprintf(stderr, "cubvoice: --out FILE is needed\n"), -1;
    if (o->pitch < 0 || o->pitch > 99 || o->speed < 80 || o->speed > 450)
        return fprintf(stderr, "cubvoice: --pitch 0..99, --speed 80..450\n"), -1;
    return 0;
}

/* ---- the phrases ---------------------------------------------------------- */

static void add_phrase(void *user, const char *text)
{
    phrase_list *l = user;
    for (int i = 0; i < l->count; i++)
        if (!strcmp(l->text[i], text)) return;
    if (l->count == CUB_VOICEPACK_MAX_PHRASES || strlen(text) > CUB_VOICEPACK_TEXT_MAX) {
        l->overflow = 1;
        return;
    }
    l->text[l->count++] = text;
}

/* A song and its fault words, as the box loads them. */
typedef struct song_words {
    cub_song song;
    cub_faults faults;
} song_words;

static int load_song(const char *path, const cub_library *lib, song_words *sw, cub_diag *diag)
{
    if (cub_song_load(path, lib, &sw->song, diag)) return -1;
    sw->faults.count = 0;
    return sw->song.faults_path[0] ? (int)cub_faults_load(sw->song.faults_path, lib, &sw->faults,
                                                          diag)
                                   : 0;
}

/* The songs stay loaded: the list points into them. */
static int collect(const voice_opts *o, cub_library *lib, song_words *songs, phrase_list *l)
{
    cub_diag diag;
    char buf[600];
    if (cub_pack_read(o->library, lib, &diag))
        return fprintf(stderr, "cubvoice: %s\n", cub_diag_str(&diag, buf, sizeof buf)), -1;
    cub_words_each(NULL, NULL, add_phrase, l);
    for (int i = 0; i < o->song_count; i++) {
        if (load_song(o->songs[i], lib, &songs[i], &diag))
            return fprintf(stderr, "cubvoice: %s\n", cub_diag_str(&diag, buf, sizeof buf)), -1;
        cub_words_each(&songs[i].song, &songs[i].faults, add_phrase, l);
    }
    if (l->overflow)
        return fprintf(stderr, "cubvoice: more than %d phrases, or one over %d bytes\n",
                       CUB_VOICEPACK_MAX_PHRASES, CUB_VOICEPACK_TEXT_MAX), -1;
    return 0;
}

/* ---- speaking one ---------------------------------------------------------- */

static int run_espeak(const voice_opts *o, const char *txt, const char *wav)
{
    char pitch[8], speed[8];
    snprintf(pitch, sizeof pitch, "%d", o->pitch);
    snprintf(speed, sizeof speed, "%d", o->speed);
    char *argv[] = {(char *)o->espeak, "-v", (char *)o->voice, "-p", pitch, "-s", speed,
                    "-w", (char *)wav, "-f", (char *)txt, NULL};
    pid_t pid;
    int e = posix_spawnp(&pid, o->espeak, NULL, NULL, argv, environ);
    if (e) return fprintf(stderr, "cubvoice: cannot run %s: %s\n", o->espeak, strerror(e)), -1;
    int status = 0;
    if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
        return fprintf(stderr, "cubvoice: %s failed on %s\n", o->espeak, txt), -1;
    return 0;
}

static uint32_t le32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

/* The samples of a mono 16-bit PCM WAV file (espeak's -w): heap, in *pcm. */
static int read_wav(const char *path, int16_t **pcm, uint32_t *frames, int *rate)
{
    FILE *f = fopen(path, "rb");
    static uint8_t buf[CUB_VOICEPACK_RATE_MAX * CUB_VOICEPACK_MAX_SECONDS * 2 + 4096];
    size_t n = f ? fread(buf, 1, sizeof buf, f) : 0;
    if (f) fclose(f);
    if (n < 12 || memcmp(buf, "RIFF", 4) || memcmp(buf + 8, "WAVE", 4))
        return fprintf(stderr, "cubvoice: %s: not a WAV file\n", path), -1;
    int fmt_ok = 0;
    for (size_t at = 12; at + 8 <= n;) {
        uint32_t size = le32(buf + at + 4);
        const uint8_t *body = buf + at + 8;
        if (size > n - at - 8) size = (uint32_t)(n - at - 8); /* espeak may leave it open */
        if (!memcmp(buf + at, "fmt ", 4) && size >= 16) {
            fmt_ok = body[0] == 1 && body[1] == 0 && body[2] == 1 && body[3] == 0 && body[14] == 16;
            *rate = (int)le32(body + 4);
        } else if (!memcmp(buf + at, "data", 4) && fmt_ok && size >= 2) {
            *frames = size / 2;
            if (!(*pcm = malloc((size_t)*frames * 2))) return -1;
            for (uint32_t k = 0; k < *frames; k++)
                (*pcm)[k] = (int16_t)(uint16_t)(body[2 * k] | (body[2 * k + 1] << 8));
            return 0;
        }
        at += 8 + (size_t)size + (size & 1);
    }
    return fprintf(stderr, "cubvoice: %s: no mono 16-bit PCM data\n", path), -1;
}

/* Cut espeak's silence to KEEP_MS either side and scale the peak to PEAK. */
static void trim_and_level(cub_voice_phrase *ph, int16_t *pcm, int rate)
{
    uint32_t first = 0, last = ph->frames, keep = (uint32_t)(rate * KEEP_MS / 1000);
    while (first < last && abs(pcm[first]) < QUIET) first++;
    while (last > first && abs(pcm[last - 1]) < QUIET) last--;
    first = first > keep ? first - keep : 0;
    last = last + keep < ph->frames ? last + keep : ph->frames;
    int peak = 1;
    for (uint32_t k = first; k < last; k++)
        if (abs(pcm[k]) > peak) peak = abs(pcm[k]);
    for (uint32_t k = first; k < last; k++) pcm[k - first] = (int16_t)(pcm[k] * PEAK / peak);
    ph->frames = last > first ? last - first : 1;
}

static int speak(const voice_opts *o, const char *work, cub_voice_phrase *ph, int *rate)
{
    char txt[1200], wav[1200];
    snprintf(txt, sizeof txt, "%s/%08x.txt", work, ph->id);
    snprintf(wav, sizeof wav, "%s/%08x.wav", work, ph->id);
    FILE *f = fopen(txt, "w");
    if (!f || fputs(ph->text, f) < 0 || fclose(f) != 0)
        return fprintf(stderr, "cubvoice: cannot write %s\n", txt), -1;
    int16_t *pcm = NULL;
    int wav_rate = 0;
    if (run_espeak(o, txt, wav) || read_wav(wav, &pcm, &ph->frames, &wav_rate)) return -1;
    if (*rate && wav_rate != *rate)
        return free(pcm), fprintf(stderr, "cubvoice: %s at %d Hz, the rest at %d\n", wav,
                                  wav_rate, *rate), -1;
    *rate = wav_rate;
    trim_and_level(ph, pcm, wav_rate);
    ph->pcm = pcm;
    return 0;
}

static int pack_all(const voice_opts *o, const phrase_list *l)
{
    char work[1024];
    const char *slash = strrchr(o->out, '/');
    snprintf(work, sizeof work, "%.*s", slash ? (int)(slash - o->out) : 1, slash ? o->out : ".");
    if (o->work) snprintf(work, sizeof work, "%s", o->work);
    cub_voice_phrase *ph = calloc((size_t)l->count, sizeof *ph);
    int rate = 0, bad = !ph;
    size_t bytes = 0;
    double seconds = 0;
    for (int i = 0; !bad && i < l->count; i++) {
        ph[i] = (cub_voice_phrase){.id = cub_voicepack_id(l->text[i]), .text = l->text[i]};
        bad = speak(o, work, &ph[i], &rate) != 0;
        if (!bad) bytes += ph[i].frames * 2u, seconds += (double)ph[i].frames / rate;
    }
    cub_diag diag;
    char buf[600];
    if (!bad && cub_voicepack_write(o->out, rate, ph, l->count, &diag))
        bad = fprintf(stderr, "cubvoice: %s\n", cub_diag_str(&diag, buf, sizeof buf)) > 0;
    if (!bad)
        printf("voice: %d phrases, %.1f s of speech at %d Hz, %zu kB of samples in %s\n",
               l->count, seconds, rate, bytes / 1024, o->out);
    for (int i = 0; ph && i < l->count; i++) free((void *)ph[i].pcm);
    free(ph);
    return bad;
}

int main(int argc, char **argv)
{
    voice_opts o;
    int list_only = 0, r = parse_args(argc, argv, &o, &list_only);
    if (r) return r > 0 ? 0 : 2;
    static song_words songs[MAX_SONGS];
    static phrase_list l;
    cub_library lib = {0};
    l.count = l.overflow = 0;
    int rc = collect(&o, &lib, songs, &l) ? 1 : 0;
    for (int i = 0; !rc && list_only && i < l.count; i++)
        printf("%08x %s\n", cub_voicepack_id(l.text[i]), l.text[i]);
    if (!rc && !list_only) rc = pack_all(&o, &l);
    cub_library_free(&lib);
    return rc;
}

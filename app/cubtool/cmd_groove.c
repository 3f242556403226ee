/* cubtool groove — seed 001 on a MIDI file (cub/groove.h): the melody's
 * notes, their segmentation by the seed's DP and what the DP cost, and with
 * --keys every note's right-wrist key. The motion itself (BVH, PNG) is the
 * next slice (docs/groove.md). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "commands.h"
#include "cub/music.h"

static const char usage[] =
    "usage: cubtool groove SONG.mid [--melody N] [--rhythm M] [--set a|b] [--window W] [--keys]\n";

typedef struct groove_opts {
    const char *path;
    int melody, rhythm, window, keys;
    char set;
} groove_opts;

static int parse_int(const char *s, int lo, int hi, int *out)
{
    char *end = NULL;
    long v = strtol(s, &end, 10);
    if (!*s || *end || v < lo || v > hi) return 0;
    *out = (int)v;
    return 1;
}

static int parse(int argc, char **argv, groove_opts *o)
{
    *o = (groove_opts){NULL, -1, -1, 0, 0, 'a'};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        int ok = 1;
        if (!strcmp(a, "--keys"))
            o->keys = 1;
        else if (!strcmp(a, "--melody") && v)
            ok = parse_int(v, 0, 65535, &o->melody), i++;
        else if (!strcmp(a, "--rhythm") && v)
            ok = parse_int(v, 0, 65535, &o->rhythm), i++;
        else if (!strcmp(a, "--window") && v)
            ok = parse_int(v, 2, CUB_GROOVE_WINDOW_MAX, &o->window), i++;
        else if (!strcmp(a, "--set") && v)
            ok = (!strcmp(v, "a") || !strcmp(v, "b")) && (o->set = v[0]), i++;
        else if (a[0] != '-' && !o->path)
            o->path = a;
        else
            ok = 0;
        if (!ok) {
            fprintf(stderr, "cubtool groove: bad argument '%s%s%s'\n%s", a,
                    v && a[0] == '-' ? " " : "", v && a[0] == '-' ? v : "", usage);
            return 0;
        }
    }
    if (!o->path) fprintf(stderr, "%s", usage);
    return o->path != NULL;
}

static const char *rhythm_name(const cub_groove_pick *p)
{
    return p->rhythm == CUB_GROOVE_RHYTHM_DRUMS   ? "drums"
           : p->rhythm == CUB_GROOVE_RHYTHM_METER ? "meter"
                                                  : "track";
}

static void print_notes(const cub_groove_song *song, const cub_groove_pick *pick,
                        const cub_groove_note *n, int count)
{
    int rests = 0, beats = 0;
    for (int i = 0; i < count; i++)
        rests += n[i].pitch == CUB_GROOVE_REST, beats += n[i].is_beat;
    printf("tracks %d division %d tempo_events %d meters %d midi_notes %d\n", song->tracks,
           song->division, song->tempo_count, song->meter_count, song->note_count);
    printf("melody track %d rhythm %s", pick->melody_track, rhythm_name(pick));
    if (pick->rhythm == CUB_GROOVE_RHYTHM_TRACK) printf(" %d", pick->rhythm_track);
    printf("\nnotes %d rests %d beats %d length_s %.3f\n", count, rests, beats,
           (double)cub_groove_tick_us(song, song->end_tick) / 1e6);
}

static void print_segments(const cub_groove_note *n, const cub_groove_segment *s, int k,
                           const cub_groove_cost *c, double ms)
{
    printf("segments %d mean_notes %.2f\n", k, k ? (double)s[k - 1].end / k : 0.0);
    printf("dp windows %d splits %lld mean_f %.4f time_ms %.3f\n", c->windows, (long long)c->splits,
           c->mean_f / 65536.0, ms);
    for (int i = 0; i < k; i++) {
        long long len = 0;
        for (int j = s[i].first; j < s[i].end; j++)
            len += n[j].length_beats;
        printf("segment %d notes %d..%d beats %.3f t_s %.3f\n", i, s[i].first, s[i].end - 1,
               len / 65536.0, (double)n[s[i].first].start_us / 1e6);
    }
}

static void print_keys(const cub_groove_note *n, const cub_groove_key *keys, int count)
{
    for (int i = 0; i < count; i++)
        printf("note %d t_s %.4f pitch %d beats %.4f intensity %d beat %d x_mm %.2f y_mm %.2f\n", i,
               (double)n[i].start_us / 1e6, n[i].pitch == CUB_GROOVE_REST ? -1 : n[i].pitch,
               n[i].length_beats / 65536.0, n[i].intensity, n[i].is_beat, keys[i].x_mm / 65536.0,
               keys[i].y_mm / 65536.0);
}

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec / 1e6;
}

static int fail(const char *path, const char *what, cub_err e)
{
    fprintf(stderr, "cubtool groove: %s: %s (%s)\n", path, what, cub_err_str(e));
    return 1;
}

/* Notes, segments, keys of one song; 0 or the exit code. */
static int run(const groove_opts *o, const cub_groove_song *song, cub_groove_note *notes,
               cub_groove_segment *segs, cub_groove_key *keys, cub_groove_work *work)
{
    cub_groove_pick pick;
    cub_groove_params p;
    cub_groove_cost cost;
    int n = 0, k = 0;
    cub_err e = cub_groove_pick_tracks(song, o->melody, o->rhythm, &pick);
    if (e == CUB_ERR_RANGE) return fail(o->path, "no such track with notes", e);
    if (e == CUB_ERR_UNSUPPORTED) return fail(o->path, "more than 256 tracks", e);
    if (e) return fail(o->path, "no track with pitched notes", e);
    if ((e = cub_groove_notes(song, &pick, notes, 2 * song->note_count + 1, &n)))
        return fail(o->path, "the melody's notes", e);
    cub_groove_params_set(o->set, &p);
    double t0 = now_ms();
    e = cub_groove_segment_notes(&p, notes, n, o->window, work, segs, n, &k, &cost);
    double ms = now_ms() - t0;
    if (e) return fail(o->path, "segmentation", e);
    if ((e = cub_groove_keys(&p, notes, n, segs, k, keys))) return fail(o->path, "keys", e);
    print_notes(song, &pick, notes, n);
    print_segments(notes, segs, k, &cost, ms);
    if (o->keys) print_keys(notes, keys, n);
    return 0;
}

int cub_cmd_groove(int argc, char **argv)
{
    if (argc == 2 && !strcmp(argv[1], "--help")) {
        printf("%s"
               "Seed 001 on a MIDI file: the melody's notes (the top line of the highest\n"
               "track unless --melody; isBeat from channel-10 drums, else the time signature,\n"
               "unless --rhythm), its segments by the seed's DP (parameter set a or b;\n"
               "DP windows of W notes, default 48) with the DP's cost, and with --keys\n"
               "each note's right-wrist key (mm). Tracks count from 0 in file order.\n",
               usage);
        return 0;
    }
    groove_opts o;
    if (!parse(argc, argv, &o)) return 2;
    cub_midi_groove g;
    cub_diag d = {0};
    char msg[600];
    if (cub_midi_groove_load(o.path, &g, &d)) {
        fprintf(stderr, "cubtool groove: %s\n", cub_diag_str(&d, msg, sizeof msg));
        return 1;
    }
    size_t cap = 2 * (size_t)g.song.note_count + 1;
    cub_groove_note *notes = calloc(cap, sizeof(*notes));
    cub_groove_segment *segs = calloc(cap, sizeof(*segs));
    cub_groove_key *keys = calloc(cap, sizeof(*keys));
    cub_groove_work *work = malloc(sizeof(*work));
    int rc = notes && segs && keys && work ? run(&o, &g.song, notes, segs, keys, work)
                                           : fail(o.path, "out of memory", CUB_ERR_NOMEM);
    free(notes), free(segs), free(keys), free(work);
    cub_midi_groove_free(&g);
    return rc;
}

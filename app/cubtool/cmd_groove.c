/* cubtool groove — seed 001 on a MIDI file (cub/groove.h): the melody's
 * notes, their segmentation by the seed's DP and what the DP cost, with
 * --keys every note's right-wrist key; with --out the bear dancing it as
 * a BVH (read back by our own reader), with --png the wrist's path and
 * timing curves against the notes. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "cub/io.h"
#include "groove_tool.h"
#include "tool_util.h"

static const char usage[] =
    "usage: cubtool groove SONG.mid [--melody N] [--rhythm M] [--set a|b] [--window W] [--keys]\n"
    "                      [--out CLIP.bvh] [--fps F] [--png PATH.png]\n";

typedef struct groove_opts {
    groove_args a;
    int keys, fps;
    const char *out, *png;
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
    *o = (groove_opts){{NULL, -1, -1, 0, 'a'}, 0, 60, NULL, NULL};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        int ok = 1;
        if (!strcmp(a, "--keys"))
            o->keys = 1;
        else if (!strcmp(a, "--melody") && v)
            ok = parse_int(v, 0, 65535, &o->a.melody), i++;
        else if (!strcmp(a, "--rhythm") && v)
            ok = parse_int(v, 0, 65535, &o->a.rhythm), i++;
        else if (!strcmp(a, "--window") && v)
            ok = parse_int(v, 2, CUB_GROOVE_WINDOW_MAX, &o->a.window), i++;
        else if (!strcmp(a, "--fps") && v)
            ok = parse_int(v, 1, 240, &o->fps), i++;
        else if (!strcmp(a, "--set") && v)
            ok = (!strcmp(v, "a") || !strcmp(v, "b")) && (o->a.set = v[0]), i++;
        else if (!strcmp(a, "--out") && v)
            o->out = v, i++;
        else if (!strcmp(a, "--png") && v)
            o->png = v, i++;
        else if (a[0] != '-' && !o->a.path)
            o->a.path = a;
        else
            ok = 0;
        if (!ok) {
            fprintf(stderr, "cubtool groove: bad argument '%s%s%s'\n%s", a,
                    v && a[0] == '-' ? " " : "", v && a[0] == '-' ? v : "", usage);
            return 0;
        }
    }
    if (!o->a.path) fprintf(stderr, "%s", usage);
    return o->a.path != NULL;
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
    printf("dp windows %d splits %lld mean_f %.4f plan_ms %.3f\n", c->windows, (long long)c->splits,
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

/* The bear dancing the whole song, as BVH, read back by our own reader. */
static int write_bvh(const groove_song *s, const groove_opts *o)
{
    static cub_skeleton bear; /* static: large */
    cub_groove_rig rig;
    cub_clip clip;
    void *mem = NULL;
    if (groove_bear(&bear, "groove")) return 1;
    cub_groove_rig_bind(&bear, &rig);
    int rc = groove_song_clip(s, &rig, o->fps, &clip, &mem);
    if (rc) fprintf(stderr, "cubtool groove: %s: the clip (out of memory)\n", o->a.path);
    if (!rc) rc = cub_tool_save_clip_bvh(&bear, &clip, o->out) ? 1 : 0;
    free(mem);
    if (rc) return rc;
    static cub_io_motion back; /* static: large */
    cub_diag d = {0};
    char msg[600];
    if (cub_io_load_bvh(o->out, &(cub_io_desc){10.0}, &back, &d)) {
        fprintf(stderr, "cubtool groove: reading back %s\n", cub_diag_str(&d, msg, sizeof msg));
        return 1;
    }
    printf("bvh %s frames %d joints %d fps %d read back\n", o->out, back.clip.frame_count,
           back.skel.joint_count, o->fps);
    cub_io_motion_free(&back);
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
               "each note's right-wrist key (mm). Tracks count from 0 in file order.\n"
               "--out writes the bear dancing the whole song (F frames a second, default\n"
               "60) and reads it back; --png draws the wrist's path and timing curves\n"
               "against the notes (8 s from the melody's start).\n",
               usage);
        return 0;
    }
    groove_opts o;
    if (!parse(argc, argv, &o)) return 2;
    groove_song s;
    int rc = groove_song_load(&o.a, "groove", &s);
    if (!rc) {
        const cub_groove_plan *pl = &s.plan;
        print_notes(&s.midi.song, &s.pick, pl->notes, pl->n);
        print_segments(pl->notes, s.mem.segs, s.seg_count, &s.cost, s.plan_ms);
        if (o.keys) print_keys(pl->notes, pl->keys, pl->n);
        if (o.out) rc = write_bvh(&s, &o);
        if (!rc && o.png) rc = groove_png(&s, o.png);
    }
    groove_song_free(&s);
    return rc;
}

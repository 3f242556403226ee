/* cubtool gait-eval — the figures of issue 24's "Measured" section: the
 * walker and the game-engine baseline (the clip with per-frame foot IK
 * down to the ground) side by side, per clip and terrain, in one run;
 * and each capture on its own floor (the reference rows). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "gait_tool.h"
#include "tool_util.h"

#define WHO "gait-eval"
#define MAX_LIST 16

static const char *const usage_text =
    "usage: cubtool gait-eval [--clips A,B,..] [--held-out A,B,..] [--reference A,B,..]\n"
    "                         [--terrains flat,slope,rolling,forest] [--frames N] [--data DIR]\n"
    "                         [--check] [--key-swing] [--straight] [--repeat N]\n"
    "                         [--without pin,close,drop,floor,keys,ahead,follow]\n"
    "The walker (firmware/gait) and the game-engine baseline on each clip and\n"
    "terrain (forest = rolling + a log + two stones), N frames each (720):\n"
    "penetration of the sole box, stance slide per step, clearance over\n"
    "obstacles, foot rotation per frame, leg joint speed against the\n"
    "source's 99th percentile, mean joint error against the source on flat\n"
    "ground, time per frame (the thread's CPU time; printed, never checked; --repeat N: each\n"
    "frame's least over N runs of the same walk, the machine's other load taken out). Reference clips (real\n"
    "walks on uneven ground) are measured on their own floor only.\n"
    "Defaults: --clips 02_01 (tuning), --held-out 16_11,07_01,08_01 (labelled\n"
    "\"seen\": each has been looked at, docs/gait.md),\n"
    "--reference 03_01,03_02. --check: exit 1 when a walker figure of the\n"
    "tuning clips is out of its sanity bound (docs/gait.md). --key-swing: on\n"
    "flat ground the walker's swing is a Bezier through the swing's key frames,\n"
    "not the captured swing; --straight: the seed's straight segments between them.\n"
    "--without: the walker with those parts left out (the stance pin, the\n"
    "cycle's closing, the pelvis drop, the per-step floor, the key configurations\n"
    "by height difference, the plan made ahead, the root's follow of the pinned\n"
    "feet), to price each one's share of the joint error or time.\n";

static int split(char *s, const char **out)
{
    int n = 0;
    for (char *t = strtok(s, ","); t && n < MAX_LIST; t = strtok(NULL, ","))
        out[n++] = t;
    return n;
}

static void row(const char *clip, const char *set, const char *terrain, const char *method,
                const gait_figures *g, double p99)
{
    char clear[32] = "-", err[40] = "-";
    if (g->clear_min_mm > -1 || g->clear_frames)
        snprintf(clear, sizeof clear, "%.1f (%d fr)", g->clear_min_mm, g->clear_frames);
    if (g->err_all_mm >= 0) snprintf(err, sizeof err, "%.1f / %.1f", g->err_all_mm, g->err_leg_mm);
    printf("| %s | %s | %s | %s | %.1f | %.1f / %.1f | %s | %.1f | %.0f (p99 %.0f) | %.2f | %s | "
           "%.1f / %.0f | %d | %d |\n",
           clip, set, terrain, method, g->pen_max_mm, g->slide_max_mm, g->slide_mean_mm, clear,
           g->rot_max_deg, g->speed_max_dps, p99, g->speed_over_pct, err, g->us_mean, g->us_max,
           g->steps, g->backtracks);
}

static int make_terrain(gait_ground *g, const char *name)
{
    if (strcmp(name, "forest")) return gait_ground_make(g, name, WHO);
    if (gait_ground_make(g, "rolling", WHO)) return 1;
    snprintf(g->name, sizeof g->name, "forest");
    return gait_ground_add(g, "log", WHO) || gait_ground_add(g, "stone", WHO) ||
           gait_ground_add(g, "stone", WHO);
}

/* The sanity bounds (the targets where the walker meets them). */
static int check(const char *clip, const char *terrain, const gait_figures *g)
{
    int bad = 0;
#define BOUND(cond, what)                                                                          \
    if (!(cond)) {                                                                                 \
        fprintf(stderr, "cubtool " WHO ": %s on %s: %s\n", clip, terrain, what);                   \
        bad = 1;                                                                                   \
    }
    BOUND(g->pen_max_mm <= 0.5, "penetration over 0.5 mm");
    BOUND(g->slide_max_mm <= 5.0, "stance slide over 5 mm");
    BOUND(g->clear_frames == 0 || g->clear_min_mm >= 0, "a swinging foot inside an obstacle");
    BOUND(g->rot_max_deg <= 10.0, "a foot turning over 10 degrees in a frame");
    BOUND(g->err_all_mm < 0 || g->err_all_mm <= 12.0, "mean joint error on flat over 12 mm");
    BOUND(g->steps >= 6, "fewer than 6 steps");
    BOUND(g->blocked == 0, "a step found no foothold");
#undef BOUND
    return bad;
}

static int key_swing;  /* --key-swing: the Bezier through the key frames on flat ground */
static int without;    /* --without: CUB_GAIT_NO_* bits */
static int straight;   /* --straight: the seed's straight key-frame segments on flat ground */
static int repeat = 1; /* --repeat: runs timed per row, each frame's least time kept */

/* "pin,close,drop,floor,keys,ahead,follow" to CUB_GAIT_NO_* bits (in the
 * enum's order); -1 for an unknown name. */
static int parse_without(char *s)
{
    static const char *const names[] = {"pin", "close", "drop", "floor", "keys", "ahead", "follow"};
    const int n = (int)(sizeof names / sizeof *names);
    int bits = 0;
    for (char *t = strtok(s, ","); t; t = strtok(NULL, ",")) {
        int i = 0;
        while (i < n && strcmp(t, names[i]))
            i++;
        if (i == n) return -1;
        bits |= 1 << i;
    }
    return bits;
}

static int run_clip(const char *clip, const char *set, const char **terrains, int nt, int frames,
                    const char *data, int do_check)
{
    static gait_src src;
    static gait_ground ground;
    if (gait_src_load(&src, clip, data, WHO)) return 1;
    double p99 = gait_src_p99_dps(&src);
    gait_figures g;
    int bad = 0;
    gait_run src_run = {.method = GAIT_SOURCE};
    gait_measure(&src, NULL, &src_run, &g, WHO);
    row(clip, set, "own floor", "source", &g, p99);
    for (int t = 0; t < nt && strcmp(set, "reference"); t++) {
        if (make_terrain(&ground, terrains[t])) {
            gait_src_free(&src);
            return 2;
        }
        for (int m = GAIT_WALKER; m <= GAIT_BASELINE; m++) {
            gait_run r = {.method = (gait_method)m, .frames = frames, .repeat = repeat,
                          .params = {.dir_z = CUB_Q16_ONE, .key_swing = key_swing,
                                     .straight_swing = straight, .without = without}};
            if (gait_measure(&src, &ground, &r, &g, WHO)) {
                bad = 1;
                break;
            }
            row(clip, set, terrains[t], m == GAIT_WALKER ? "walker" : "baseline", &g, p99);
            if (do_check && m == GAIT_WALKER && !strcmp(set, "tuning"))
                bad |= check(clip, terrains[t], &g);
        }
    }
    gait_src_free(&src);
    return bad;
}

int cub_cmd_gait_eval(int argc, char **argv)
{
    const char *clips = NULL, *held = NULL, *ref = NULL, *ters = NULL, *nframes = NULL,
               *data = NULL, *wo = NULL, *nrep = NULL;
    int do_check = 0;
    const cub_tool_opt opts[] = {{"--clips", &clips, NULL},     {"--held-out", &held, NULL},
                                 {"--reference", &ref, NULL},   {"--terrains", &ters, NULL},
                                 {"--frames", &nframes, NULL},  {"--data", &data, NULL},
                                 {"--check", NULL, &do_check},  {"--key-swing", NULL, &key_swing},
                                 {"--without", &wo, NULL},      {"--straight", NULL, &straight},
                                 {"--repeat", &nrep, NULL}};
    switch (cub_tool_parse_opts(argc, argv, opts, sizeof opts / sizeof *opts, NULL, 0)) {
    case CUB_TOOL_HELP: fputs(usage_text, stdout); return 0;
    case CUB_TOOL_BAD: fputs(usage_text, stderr); return 2;
    default: break;
    }
    char wb[64];
    snprintf(wb, sizeof wb, "%s", wo ? wo : "");
    without = parse_without(wb);
    if (without < 0) {
        fprintf(stderr, "cubtool " WHO ": --without %s: expected pin, close, drop, floor, keys, ahead, follow\n", wo);
        return 2;
    }
    int frames = nframes ? atoi(nframes) : 720;
    if (frames < 10 || frames > 100000) {
        fprintf(stderr, "cubtool " WHO ": --frames %s: expected 10..100000\n", nframes);
        return 2;
    }
    repeat = nrep ? atoi(nrep) : 1;
    if (repeat < 1 || repeat > 100) {
        fprintf(stderr, "cubtool " WHO ": --repeat %s: expected 1..100\n", nrep);
        return 2;
    }
    if (!data) data = getenv("CUB_DATA_DIR") ? getenv("CUB_DATA_DIR") : CUB_DATA_DIR_DEFAULT;
    char cb[256], hb[256], rb[256], tb[256];
    snprintf(cb, sizeof cb, "%s", clips ? clips : "02_01");
    snprintf(hb, sizeof hb, "%s", held ? held : (clips ? "" : "16_11,07_01,08_01"));
    snprintf(rb, sizeof rb, "%s", ref ? ref : (clips ? "" : "03_01,03_02"));
    snprintf(tb, sizeof tb, "%s", ters ? ters : "flat,slope,rolling,forest");
    const char *cl[MAX_LIST], *hl[MAX_LIST], *rl[MAX_LIST], *tl[MAX_LIST];
    int nc = split(cb, cl), nh = split(hb, hl), nr = split(rb, rl), nt = split(tb, tl);
    printf("| clip | set | terrain | method | penetration mm | slide max / mean mm | clearance mm "
           "| foot turn deg/frame | leg joint max deg/s | > src p99 %% | joint err all / leg mm "
           "| us/frame mean / max | steps | backtracks |\n");
    printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    int bad = 0;
    for (int i = 0; i < nc; i++)
        bad |= run_clip(cl[i], "tuning", tl, nt, frames, data, do_check);
    for (int i = 0; i < nh; i++)
        bad |= run_clip(hl[i], "seen", tl, nt, frames, data, 0);
    for (int i = 0; i < nr; i++)
        bad |= run_clip(rl[i], "reference", tl, nt, frames, data, 0);
    return bad ? (bad == 2 ? 2 : 1) : 0;
}

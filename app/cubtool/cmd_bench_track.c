/* cubtool bench-track [DUMP_DIR] — the tracker's cost on one core:
 * milliseconds of CPU per frame (median, p95) over a dump (default: the real
 * Skeltrack frames under the data dir), repeated to at least 300 frames,
 * and the tracker's memory. Then the whole tick: the real cubdance replays
 * the dump through fakenect while it leads the demo song headless
 * (`--stats`: the loop thread's CPU per tick, from polling the camera to
 * rendering, and the peak resident memory). Build Release for figures that
 * mean anything. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "commands.h"
#include "cub/track.h"
#include "track_dump.h"

#define BENCH_MIN_RUNS 300

/* The thread's CPU time: on a machine others share, wall time counts
 * their work too (a median of 1.2 ms wall went to 13 ms under a load of
 * 8 on 2 cores); the CPU the tracker itself spends is what the box pays. */
static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The whole tick, measured by the box itself on the same dump (with the
 * forest when `forest` is not empty): `env` goes before the command,
 * `lines` picks what to show of --stats. */
typedef struct box_run {
    const char *dir, *forest;
    int frames;
} box_run;

static int run_box(const box_run *b, const char *env, const char *lines)
{
    char cmd[20000], fopt[4200] = "--forest off";
    if (b->forest[0]) snprintf(fopt, sizeof fopt, "--forest '%s'", b->forest);
    snprintf(cmd, sizeof cmd,
             "FAKENECT_PATH='%s' LD_LIBRARY_PATH='%s' EGL_PLATFORM=surfaceless SDL_AUDIODRIVER=dummy %s "
             "'%s' --headless --replay '%s' --clock virtual --song '%s' --buttons '%s' %s "
             "--seconds %.1f --log /dev/null --stats 2>/dev/null | grep -E '%s'",
             b->dir, CUB_FAKENECT_DIR, env, CUB_CUBDANCE_EXE, b->dir, CUB_ASSETS_DIR "/songs/twinkle.song.xml",
             CUB_ASSETS_DIR "/../scripts/demo.buttons", fopt, b->frames / 30.0 + 1.0, lines);
    return system(cmd);
}

static void whole_tick(const box_run *b)
{
    printf("bench-track: the whole tick, cubdance leading Twinkle at 1280x720 on this dump%s:\n",
           b->forest[0] ? ", the tracker with the forest" : ", the tracker alone");
    fflush(stdout);
    if (run_box(b, "", "tick CPU") != 0)
        printf("bench-track: (the box did not run: see `%s --help`)\n", CUB_CUBDANCE_EXE);
#ifdef CUB_ALLOC_COUNT_LIB
    /* Again with the counter, which tells whose each heap block is (its
     * stack walks would distort the tick's CPU time, hence a second run). */
    printf("bench-track: the box's memory, ours apart from the GL driver's (docs/memory.md):\n");
    fflush(stdout);
    run_box(b, "LD_PRELOAD='" CUB_ALLOC_COUNT_LIB "' CUB_ALLOC_OWNERS=1",
            "^stats: memory (ours|gl_driver|heap by owner)");
#else
    printf("bench-track: (no allocation counter in a sanitizer build: the box's own memory is "
           "measured in a Release build)\n");
#endif
}

/* Milliseconds per frame of a tracker over the dump, repeated to at
 * least BENCH_MIN_RUNS frames: sorted into ms[runs]. */
static void time_frames(cub_tracker *t, const cub_tool_dump *d, double *ms, int runs)
{
    for (int r = 0; r < runs; r++) {
        cub_track_skeleton s;
        int f = r % d->n;
        double t0 = now_ms();
        cub_track_frame(t, d->raw + (size_t)f * CUB_TOOL_FRAME_PIXELS, (int64_t)r * 33333, NULL, &s);
        ms[r] = now_ms() - t0;
    }
    qsort(ms, (size_t)runs, sizeof *ms, cmp_double);
}

/* One line of figures: a tracker (with the forest f or not) on the dump;
 * its median into *median. -1 when it cannot be set up. */
static int bench_one(const cub_tool_dump *d, const char *dir, const cub_forest *f, size_t forest_bytes,
                     double *median)
{
    void *mem = NULL;
    cub_tracker *t = cub_tool_tracker_new(&mem, f, "bench-track");
    int runs = d->n < BENCH_MIN_RUNS ? (BENCH_MIN_RUNS + d->n - 1) / d->n * d->n : d->n;
    double *ms = malloc((size_t)runs * sizeof *ms);
    if (!t || !ms) {
        free(mem), free(ms);
        return -1;
    }
    time_frames(t, d, ms, runs);
    size_t sz = cub_track_mem_size(&(cub_track_desc){.forest = f});
    *median = ms[runs / 2];
    printf("bench-track: %s%s frames=%d runs=%d median=%.3f ms p95=%.3f ms max=%.3f ms memory=%zu bytes",
           f ? "tracker+forest " : "tracker ", dir, d->n, runs, ms[runs / 2], ms[runs * 95 / 100],
           ms[runs - 1], sz);
    if (f) printf(" + forest %zu bytes = state %zu bytes", forest_bytes, sz + forest_bytes);
    printf("\n");
    fflush(stdout);
    free(ms);
    free(mem);
    return 0;
}

int cub_cmd_bench_track(int argc, char **argv)
{
    char def[4096];
    const char *dir = NULL, *forest_path = CUB_ASSETS_DIR "/forest/body.forest";
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help")) {
            printf("usage: cubtool bench-track [DUMP_DIR] [--forest FILE|off]\n"
                   "Milliseconds per frame (median, p95) of the tracker on one core, and its memory.\n"
                   "DUMP_DIR defaults to <data>/depth/skeltrack ($CUB_DATA_DIR or the build's data dir).\n"
                   "--forest FILE|off: the body-part forest (default " CUB_ASSETS_DIR "/forest/body.forest,\n"
                   "as the box): the tracker alone, then with the forest: its time, the forest's share\n"
                   "(the medians' difference), the state's bytes; the whole tick with it.\n");
            return 0;
        }
        if (!strcmp(argv[i], "--forest") && i + 1 < argc) forest_path = argv[++i];
        else dir = argv[i];
    }
    if (!dir) {
        const char *data = getenv("CUB_DATA_DIR");
        snprintf(def, sizeof def, "%s/depth/skeltrack", data ? data : CUB_DATA_DIR_DEFAULT);
        dir = def;
    }
    cub_tool_dump d;
    if (cub_tool_dump_load(dir, &d, 2000, "bench-track")) return 1;
    char *fbytes = NULL;
    cub_forest f;
    double alone = 0, both = 0;
    int rc = bench_one(&d, dir, NULL, 0, &alone);
    if (!strcmp(forest_path, "off")) forest_path = NULL;
    if (!rc && forest_path) {
        rc = cub_tool_forest_load(forest_path, &fbytes, &f, "bench-track");
        size_t fb = rc ? 0 : CUB_FOREST_HEADER_BYTES + 4 * (size_t)f.trees +
                                 (size_t)f.node_count * CUB_FOREST_NODE_BYTES +
                                 (size_t)f.leaf_count * (size_t)f.classes * 2;
        if (!rc) rc = bench_one(&d, dir, &f, fb, &both);
        if (!rc) printf("bench-track: forest (the medians' difference) %.3f ms a frame\n", both - alone);
    }
    if (!rc) whole_tick(&(box_run){dir, forest_path ? forest_path : "", d.n});
    free(fbytes);
    cub_tool_dump_free(&d);
    return rc ? 1 : 0;
}

/* cubtool eval-track DUMP_DIR [TRUTH] — run the tracker over a fakenect
 * dump (INDEX.txt + d-*.pgm, raw 11-bit little-endian) and compare with the
 * true joints: per-joint mean error (mm), share within 10 cm per joint and
 * overall, status counts, frames per second. Also: --print (each frame's
 * joints as pixels and mm). The dump loader is track_dump.c (shared with
 * bench-track). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/stat.h>

#include "commands.h"
#include "cub/synth.h"
#include "cub/track.h"
#include "track_dump.h"

#define EVAL_MAX_FRAMES 20000

/* The truth (cub/synth.h's reader: checked line by line, fuzzed), or NULL
 * when there is none; a truth that is there but bad is an error. */
static int load_truth(const char *path, cub_synth_truth *t, int *have)
{
    *have = 0;
    struct stat st;
    if (stat(path, &st) != 0 && errno == ENOENT) return 0; /* no truth: statuses and speed only */
    cub_diag diag = {0};
    char msg[600];
    if (cub_synth_truth_read(path, t, &diag)) {
        fprintf(stderr, "eval-track: %s\n", cub_diag_str(&diag, msg, sizeof msg));
        return -1;
    }
    *have = 1;
    return 0;
}

/* The truth of dump frame f (matched by its frame number), or NULL. */
static const cub_synth_truth_frame *truth_of(const cub_synth_truth *t, int have, int f)
{
    if (!have) return NULL;
    if (f < t->frame_count && t->frames[f].frame == f) return &t->frames[f];
    for (int i = 0; i < t->frame_count; i++)
        if (t->frames[i].frame == f) return &t->frames[i];
    return NULL;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

static void print_frame(const char *name, const cub_track_skeleton *s)
{
    printf("%s status=%d id=%d\n", name, (int)s->status, (int)s->player_id);
    for (int j = 0; j < CUB_KJ_COUNT; j++) {
        double x = s->joint_mm[j].x / 65536.0, y = s->joint_mm[j].y / 65536.0, z = s->joint_mm[j].z / 65536.0;
        double u = z > 0 ? CUB_KINECT_CX + x * CUB_KINECT_FOCAL_PX / z : 0;
        double v = z > 0 ? CUB_KINECT_CY - y * CUB_KINECT_FOCAL_PX / z : 0;
        printf("  %-15s u=%4.0f v=%4.0f  x=%6.0f y=%6.0f z=%6.0f conf=%.2f\n", cub_kinect_joint_name(j), u, v, x, y,
               z, s->confidence[j] / 65536.0);
    }
}

int cub_cmd_eval_track(int argc, char **argv)
{
    const char *dir = NULL, *truth = NULL;
    int print = 0, no_gravity = 0, per_frame = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help")) {
            printf("usage: cubtool eval-track DUMP_DIR [TRUTH] [--print] [--per-frame] [--no-gravity]\n"
                   "Runs the tracker over a fakenect dump; with TRUTH (default DUMP_DIR/truth.txt)\n"
                   "prints per-joint mean error, share within 10 cm, status counts, fps. The\n"
                   "truth's gravity is given to the tracker unless --no-gravity. --per-frame: one\n"
                   "line per frame (status, mean error, the joints off by more than 10 cm).\n");
            return 0;
        }
        if (!strcmp(argv[i], "--print")) print = 1;
        else if (!strcmp(argv[i], "--per-frame")) per_frame = 1;
        else if (!strcmp(argv[i], "--no-gravity")) no_gravity = 1;
        else if (!dir) dir = argv[i];
        else if (!truth) truth = argv[i];
    }
    if (!dir) {
        fprintf(stderr, "usage: cubtool eval-track DUMP_DIR [TRUTH] [--print]\n");
        return 2;
    }
    /* The truth first: a bad one is refused before the frames (600 kB each)
     * are read. */
    char tpath[4096];
    if (!truth) snprintf(tpath, sizeof tpath, "%s/truth.txt", dir), truth = tpath;
    cub_synth_truth tt = {0};
    int have_truth = 0;
    if (load_truth(truth, &tt, &have_truth)) return 1;
    cub_tool_dump d;
    if (cub_tool_dump_load(dir, &d, EVAL_MAX_FRAMES, "eval-track")) {
        cub_synth_truth_free(&tt);
        return 1;
    }
    cub_vec3 grav = {(cub_q16)(tt.gravity[0] * 65536), (cub_q16)(tt.gravity[1] * 65536),
                     (cub_q16)(tt.gravity[2] * 65536)};
    int have_grav = have_truth && !no_gravity;

    void *mem = NULL;
    cub_tracker *t = cub_tool_tracker_new(&mem, "eval-track");
    if (!t) return 1;
    double err_sum[CUB_KJ_COUNT] = {0};
    int within[CUB_KJ_COUNT] = {0}, count[CUB_KJ_COUNT] = {0}, status[5] = {0};
    double secs = 0;
    for (int f = 0; f < d.n; f++) {
        cub_track_skeleton s;
        double t0 = now_s();
        cub_track_frame(t, d.raw + (size_t)f * CUB_TOOL_FRAME_PIXELS, d.t_us[f],
                        have_grav ? &grav : NULL, &s);
        secs += now_s() - t0;
        if (s.status >= 0 && s.status < 5) status[s.status]++;
        if (print) print_frame(d.name[f], &s);
        const cub_synth_truth_frame *tr = truth_of(&tt, have_truth, f);
        if (!tr) continue;
        double f_sum = 0;
        int f_n = 0;
        char f_off[512] = "";
        for (int j = 0; j < CUB_KJ_COUNT; j++) {
            if (!tr->visible[j]) continue;
            double dx = s.joint_mm[j].x / 65536.0 - tr->joint_mm[j][0],
                   dy = s.joint_mm[j].y / 65536.0 - tr->joint_mm[j][1],
                   dz = s.joint_mm[j].z / 65536.0 - tr->joint_mm[j][2];
            double e = dx * dx + dy * dy + dz * dz;
            e = e > 0 ? sqrt(e) : 0;
            err_sum[j] += e, count[j]++, within[j] += e <= 100.0;
            f_sum += e, f_n++;
            if (e > 100.0 && strlen(f_off) < sizeof f_off - 32)
                snprintf(f_off + strlen(f_off), sizeof f_off - strlen(f_off), " %s=%.0f", cub_kinect_joint_name(j), e);
        }
        if (per_frame)
            printf("frame %d status=%d mean=%.0fmm off:%s\n", f, (int)s.status, f_n ? f_sum / f_n : 0.0, f_off);
    }
    int all_n = 0, all_in = 0;
    if (have_truth) {
        printf("%-15s %8s %8s %6s\n", "joint", "mean_mm", "<=10cm", "n");
        for (int j = 0; j < CUB_KJ_COUNT; j++) {
            if (!count[j]) continue;
            printf("%-15s %8.0f %7.1f%% %6d\n", cub_kinect_joint_name(j), err_sum[j] / count[j],
                   100.0 * within[j] / count[j], count[j]);
            all_n += count[j], all_in += within[j];
        }
        if (all_n) printf("eval-track: %.1f%% of joints within 10 cm (%d of %d)\n", 100.0 * all_in / all_n, all_in, all_n);
    } else {
        printf("eval-track: no truth at %s (status and speed only)\n", truth);
    }
    printf("eval-track: frames=%d ok=%d no_player=%d too_close=%d too_far=%d partly_out=%d fps=%.0f\n", d.n,
           status[0], status[1], status[2], status[3], status[4], secs > 0 ? d.n / secs : 0.0);
    cub_synth_truth_free(&tt);
    free(mem);
    cub_tool_dump_free(&d);
    return 0;
}

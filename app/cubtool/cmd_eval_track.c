/* cubtool eval-track DUMP_DIR [TRUTH] — run the tracker over a fakenect
 * dump (INDEX.txt + d-*.pgm, raw 11-bit little-endian) and compare with the
 * true joints: per-joint mean error (mm) and share within 10 cm, overall and
 * per facing band (the body's true yaw to the camera, from the truth's hips
 * and shoulders), the frames whose player is the second person (when
 * DUMP_DIR/truth_second.txt is there), status counts, frames per second;
 * --csv FILE writes the same figures for scripts. Also: --print (each
 * frame's joints as pixels and mm). The dump loader is track_dump.c (shared
 * with bench-track). */
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
#define EVAL_BANDS 4
#define WITHIN_MM 100.0

/* |yaw| <= 30, 30-60, 60-120, > 120 degrees. */
static const char *const band_name[EVAL_BANDS] = {"yaw0-30", "yaw30-60", "yaw60-120",
                                                  "yaw120-180"};

typedef struct tally {
    double err_sum;
    int n, within;
    int sure_n, sure_within; /* of those, reported confident (>= CUB_TRACK_CONFIDENT) */
} tally;

typedef struct eval_acc {
    tally joint[EVAL_BANDS + 1][CUB_KJ_COUNT]; /* [EVAL_BANDS]: all bands */
    int band_frames[EVAL_BANDS];
    int status[5];
    int second_frames; /* a second person's truth and a tracked player */
    int wrong, wrong_in_view;
} eval_acc;

/* The truth (cub/synth.h's reader: checked line by line, fuzzed), or none
 * when the file is absent; a truth that is there but bad is an error. */
static int load_truth(const char *path, cub_synth_truth *t, int *have)
{
    *have = 0;
    struct stat st;
    if (stat(path, &st) != 0 && errno == ENOENT) return 0;
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
        double x = s->joint_mm[j].x / 65536.0, y = s->joint_mm[j].y / 65536.0,
               z = s->joint_mm[j].z / 65536.0;
        double u = z > 0 ? CUB_KINECT_CX + x * CUB_KINECT_FOCAL_PX / z : 0;
        double v = z > 0 ? CUB_KINECT_CY - y * CUB_KINECT_FOCAL_PX / z : 0;
        printf("  %-15s u=%4.0f v=%4.0f  x=%6.0f y=%6.0f z=%6.0f conf=%.2f\n",
               cub_kinect_joint_name(j), u, v, x, y, z, s->confidence[j] / 65536.0);
    }
}

static void sub3(const float a[3], const float b[3], double out[3])
{
    for (int k = 0; k < 3; k++) out[k] = (double)a[k] - b[k];
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* v without its part along the unit up. */
static void flatten(double v[3], const double up[3])
{
    double d = dot3(v, up);
    for (int k = 0; k < 3; k++) v[k] -= d * up[k];
}

/* The body's yaw to the camera in degrees (0 facing it, +-180 its back to
 * it, + = turned towards its own left): the angle from the line to the
 * camera to the facing (left x up, left from the truth's hips and
 * shoulders), about up (against gravity), both on the floor plane. */
static double truth_yaw_deg(const cub_synth_truth_frame *tr, const float gravity[3])
{
    const float(*j)[3] = tr->joint_mm;
    double g = sqrt((double)gravity[0] * gravity[0] + (double)gravity[1] * gravity[1] +
                    (double)gravity[2] * gravity[2]);
    double up[3] = {0, 1, 0}, hl[3], sl[3], left[3], cam[3];
    if (g > 0)
        for (int k = 0; k < 3; k++) up[k] = -gravity[k] / g;
    sub3(j[CUB_KJ_HIP_L], j[CUB_KJ_HIP_R], hl);
    sub3(j[CUB_KJ_SHOULDER_L], j[CUB_KJ_SHOULDER_R], sl);
    for (int k = 0; k < 3; k++) left[k] = hl[k] + sl[k], cam[k] = -j[CUB_KJ_HIP_CENTRE][k];
    flatten(left, up);
    flatten(cam, up);
    double face[3] = {left[1] * up[2] - left[2] * up[1], left[2] * up[0] - left[0] * up[2],
                      left[0] * up[1] - left[1] * up[0]};
    double cross[3] = {cam[1] * face[2] - cam[2] * face[1], cam[2] * face[0] - cam[0] * face[2],
                       cam[0] * face[1] - cam[1] * face[0]};
    return atan2(dot3(cross, up), dot3(cam, face)) * 180.0 / M_PI;
}

static int band_of(double yaw_deg)
{
    double a = fabs(yaw_deg);
    return a <= 30 ? 0 : a <= 60 ? 1 : a <= 120 ? 2 : 3;
}

/* The mean of hip centre, spine and shoulder centre. */
static void truth_torso(const cub_synth_truth_frame *tr, double out[3])
{
    static const int part[3] = {CUB_KJ_HIP_CENTRE, CUB_KJ_SPINE, CUB_KJ_SHOULDER_CENTRE};
    for (int k = 0; k < 3; k++) {
        out[k] = 0;
        for (int i = 0; i < 3; i++) out[k] += tr->joint_mm[part[i]][k] / 3.0;
    }
}

static void tracked_torso(const cub_track_skeleton *s, double out[3])
{
    static const int part[3] = {CUB_KJ_HIP_CENTRE, CUB_KJ_SPINE, CUB_KJ_SHOULDER_CENTRE};
    memset(out, 0, 3 * sizeof *out);
    for (int i = 0; i < 3; i++) {
        const cub_vec3 *p = &s->joint_mm[part[i]];
        out[0] += p->x / 65536.0 / 3, out[1] += p->y / 65536.0 / 3, out[2] += p->z / 65536.0 / 3;
    }
}

static double dist3(const double a[3], const double b[3])
{
    double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return sqrt(dot3(d, d));
}

/* Wrong person: a tracked player whose torso is nearer the second
 * person's true torso than the child's. In view: the child's true torso
 * joints are seen. */
static int score_identity(eval_acc *acc, const cub_track_skeleton *s,
                          const cub_synth_truth_frame *child, const cub_synth_truth_frame *other)
{
    if (!child || !other || s->status == CUB_TRACK_NO_PLAYER) return 0;
    double t[3], c[3], o[3];
    tracked_torso(s, t);
    truth_torso(child, c);
    truth_torso(other, o);
    acc->second_frames++;
    if (dist3(t, o) >= dist3(t, c)) return 0;
    acc->wrong++;
    acc->wrong_in_view += child->visible[CUB_KJ_SPINE] || child->visible[CUB_KJ_SHOULDER_CENTRE];
    return 1;
}

/* For --per-frame with a second person: where the player's torso is, and
 * the child's and the second person's (x and z along the floor, mm), so a
 * wrong frame can be read without a viewer. */
static void identity_note(const cub_track_skeleton *s, const cub_synth_truth_frame *child,
                          const cub_synth_truth_frame *other, int wrong, char *buf, size_t len)
{
    buf[0] = 0;
    if (!child || !other) return;
    double t[3], c[3], o[3];
    tracked_torso(s, t);
    truth_torso(child, c);
    truth_torso(other, o);
    snprintf(buf, len, "%s torso=%.0f,%.0f child=%.0f,%.0f second=%.0f,%.0f",
             wrong ? " WRONG-PERSON" : "", t[0], t[2], c[0], c[2], o[0], o[2]);
}

/* The joints of one frame into its band and the whole; one line of
 * --per-frame (note: identity_note); one row per joint into joints_out
 * (--joints) when not NULL. */
static void score_joints(eval_acc *acc, const cub_track_skeleton *s, const cub_synth_truth_frame *tr,
                         double yaw_deg, int per_frame, const char *note, FILE *joints_out)
{
    int band = band_of(yaw_deg);
    double f_sum = 0;
    int f_n = 0;
    char f_off[512] = "";
    acc->band_frames[band]++;
    for (int j = 0; j < CUB_KJ_COUNT; j++) {
        if (!tr->visible[j]) continue;
        double dx = s->joint_mm[j].x / 65536.0 - tr->joint_mm[j][0],
               dy = s->joint_mm[j].y / 65536.0 - tr->joint_mm[j][1],
               dz = s->joint_mm[j].z / 65536.0 - tr->joint_mm[j][2];
        double e = sqrt(dx * dx + dy * dy + dz * dz);
        int sure = s->confidence[j] >= CUB_TRACK_CONFIDENT;
        for (int b = 0; b < 2; b++) {
            tally *t = &acc->joint[b ? EVAL_BANDS : band][j];
            t->err_sum += e, t->n++, t->within += e <= WITHIN_MM;
            t->sure_n += sure, t->sure_within += sure && e <= WITHIN_MM;
        }
        if (joints_out)
            fprintf(joints_out, "%d,%s,%d,%d,%.0f,%.0f,%d\n", tr->frame, cub_kinect_joint_name(j),
                    (int)s->status, (int)s->confidence[j], yaw_deg, e, e <= WITHIN_MM);
        f_sum += e, f_n++;
        if (e > WITHIN_MM && strlen(f_off) < sizeof f_off - 32)
            snprintf(f_off + strlen(f_off), sizeof f_off - strlen(f_off), " %s=%.0f",
                     cub_kinect_joint_name(j), e);
    }
    if (per_frame)
        printf("frame %d status=%d id=%d%s yaw=%.0f mean=%.0fmm off:%s\n", tr->frame,
               (int)s->status, (int)s->player_id, note, yaw_deg,
               f_n ? f_sum / f_n : 0.0, f_off);
}

static tally sum_joints(const eval_acc *acc, int band)
{
    tally all = {0};
    for (int j = 0; j < CUB_KJ_COUNT; j++) {
        const tally *t = &acc->joint[band][j];
        all.err_sum += t->err_sum, all.n += t->n, all.within += t->within;
        all.sure_n += t->sure_n, all.sure_within += t->sure_within;
    }
    return all;
}

static double pct(int a, int n)
{
    return n ? 100.0 * a / n : 0.0;
}

static void print_table(const eval_acc *acc)
{
    printf("%-15s %8s %8s %6s", "joint", "mean_mm", "<=10cm", "n");
    for (int b = 0; b < EVAL_BANDS; b++) printf(" %10s", band_name[b]);
    printf("\n");
    for (int j = 0; j < CUB_KJ_COUNT; j++) {
        const tally *t = &acc->joint[EVAL_BANDS][j];
        if (!t->n) continue;
        printf("%-15s %8.0f %7.1f%% %6d", cub_kinect_joint_name(j), t->err_sum / t->n,
               pct(t->within, t->n), t->n);
        for (int b = 0; b < EVAL_BANDS; b++) {
            const tally *u = &acc->joint[b][j];
            if (u->n) printf(" %9.1f%%", pct(u->within, u->n));
            else printf(" %10s", "-");
        }
        printf("\n");
    }
    for (int b = 0; b < EVAL_BANDS; b++) {
        tally t = sum_joints(acc, b);
        printf("eval-track: band %-10s %5.1f%% of joints within 10 cm (%d of %d), %d frames\n",
               band_name[b], pct(t.within, t.n), t.within, t.n, acc->band_frames[b]);
    }
    tally all = sum_joints(acc, EVAL_BANDS);
    if (all.n)
        printf("eval-track: %.1f%% of joints within 10 cm (%d of %d)\n", pct(all.within, all.n),
               all.within, all.n);
}

/* One row of the confidence table: the share reported confident, the
 * share within 10 cm of those, and of the others. */
static void print_sure_row(const char *name, const tally *t)
{
    int un = t->n - t->sure_n, uw = t->within - t->sure_within;
    printf("%-15s %6d %9.1f%% %9.1f%% %9.1f%%\n", name, t->n, pct(t->sure_n, t->n),
           pct(t->sure_within, t->sure_n), pct(uw, un));
}

/* Is the confidence honest? Per joint and overall (every band). */
static void print_sure_table(const eval_acc *acc)
{
    printf("%-15s %6s %10s %10s %10s   (confident: confidence >= %.2f)\n", "joint", "n",
           "confident", "<=10cm|c", "<=10cm|not", CUB_TRACK_CONFIDENT / 65536.0);
    for (int j = 0; j < CUB_KJ_COUNT; j++)
        if (acc->joint[EVAL_BANDS][j].n) print_sure_row(cub_kinect_joint_name(j), &acc->joint[EVAL_BANDS][j]);
    tally all = sum_joints(acc, EVAL_BANDS);
    print_sure_row("all", &all);
    int un = all.n - all.sure_n, uw = all.within - all.sure_within;
    printf("eval-track: %.1f%% of joints confident (%d of %d), %.1f%% of them within 10 cm "
           "(%d); not confident: %.1f%% within 10 cm (%d of %d)\n",
           pct(all.sure_n, all.n), all.sure_n, all.n, pct(all.sure_within, all.sure_n),
           all.sure_within, pct(uw, un), uw, un);
}

/* One row per (band or "all", joint or "all"): n, within, mean error, and
 * the same of the joints reported confident (kind confident, no mean);
 * then the identity and status rows. */
static int write_csv(const char *path, const eval_acc *acc, int frames)
{
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "eval-track: %s: cannot write: %s\n", path, strerror(errno));
        return -1;
    }
    fprintf(f, "kind,band,joint,n,within,mean_mm\n");
    for (int b = 0; b <= EVAL_BANDS; b++) {
        const char *bn = b < EVAL_BANDS ? band_name[b] : "all";
        for (int j = 0; j < CUB_KJ_COUNT; j++) {
            const tally *t = &acc->joint[b][j];
            fprintf(f, "joint,%s,%s,%d,%d,%.1f\n", bn, cub_kinect_joint_name(j), t->n, t->within,
                    t->n ? t->err_sum / t->n : 0.0);
        }
        for (int j = 0; j < CUB_KJ_COUNT; j++) {
            const tally *t = &acc->joint[b][j];
            fprintf(f, "confident,%s,%s,%d,%d,\n", bn, cub_kinect_joint_name(j), t->sure_n, t->sure_within);
        }
        tally t = sum_joints(acc, b);
        fprintf(f, "joint,%s,all,%d,%d,%.1f\n", bn, t.n, t.within, t.n ? t.err_sum / t.n : 0.0);
        fprintf(f, "confident,%s,all,%d,%d,\n", bn, t.sure_n, t.sure_within);
        if (b < EVAL_BANDS) fprintf(f, "frames,%s,all,%d,,\n", bn, acc->band_frames[b]);
    }
    fprintf(f, "frames,all,all,%d,,\n", frames);
    fprintf(f, "second,all,all,%d,,\n", acc->second_frames);
    fprintf(f, "wrong_person,all,all,%d,,\n", acc->wrong);
    fprintf(f, "wrong_person_in_view,all,all,%d,,\n", acc->wrong_in_view);
    fprintf(f, "status_ok,all,all,%d,,\n", acc->status[CUB_TRACK_OK]);
    return fclose(f) == 0 ? 0 : -1;
}

typedef struct eval_opts {
    const char *dir, *truth, *csv, *joints, *forest;
    int print, no_gravity, per_frame;
} eval_opts;

/* The child's truth and the second person's, each there or not. */
typedef struct eval_truths {
    cub_synth_truth child, second;
    int have_child, have_second;
} eval_truths;

static int parse_args(int argc, char **argv, eval_opts *o)
{
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help")) {
            printf(
                "usage: cubtool eval-track DUMP_DIR [TRUTH] [--csv FILE] [--print] [--per-frame]\n"
                "                          [--no-gravity] [--joints FILE] [--forest FILE]\n"
                "Runs the tracker over a fakenect dump; with TRUTH (default DUMP_DIR/truth.txt)\n"
                "prints per joint the mean error and the share within 10 cm, overall and per\n"
                "facing band (the body's true yaw to the camera: |yaw| <= 30, 30-60, 60-120,\n"
                "> 120 degrees), status counts, fps; and whether the confidence is honest: per\n"
                "joint the share reported confident (confidence >= CUB_TRACK_CONFIDENT, what this\n"
                "eval says honest), the share of those within 10 cm, and of the others. With DUMP_DIR/truth_second.txt (a second\n"
                "person, cubtool synth-depth --second-person) also the frames whose player is\n"
                "the wrong person (its torso nearer the second person's than the child's).\n"
                "The truth's gravity is given to the tracker unless --no-gravity. Frames before\n"
                "the truth's first (synth-depth --prelude: attract mode) are tracked, not scored;\n"
                "the truth's first frame is START: the tracker chooses its player afresh there.\n"
                "--csv FILE: the same figures as kind,band,joint,n,within,mean_mm rows (kind\n"
                "confident: the joints reported confident).\n"
                "--joints FILE: one row per scored joint: frame,joint,status,confidence (Q16),\n"
                "true yaw, error (mm), within 10 cm (1/0).\n"
                "--per-frame: one line per frame (status, player id, WRONG-PERSON when the player\n"
                "is the second person, true yaw, mean error, the joints off by more than 10 cm;\n"
                "with a second person also torso= child= second=: the player's torso, the child's\n"
                "and the second person's, x,z in mm).\n"
                "--forest FILE: the tracker with the body-part forest (e.g. assets/forest/body.forest):\n"
                "a joint the forest is confident of replaces the tracker's (docs/forest.md).\n");
            return 1;
        }
        if (!strcmp(argv[i], "--csv") && i + 1 < argc) o->csv = argv[++i];
        else if (!strcmp(argv[i], "--joints") && i + 1 < argc) o->joints = argv[++i];
        else if (!strcmp(argv[i], "--forest") && i + 1 < argc) o->forest = argv[++i];
        else if (!strcmp(argv[i], "--print")) o->print = 1;
        else if (!strcmp(argv[i], "--per-frame")) o->per_frame = 1;
        else if (!strcmp(argv[i], "--no-gravity")) o->no_gravity = 1;
        else if (argv[i][0] == '-' && argv[i][1] == '-') {
            fprintf(stderr, "eval-track: unknown option or missing value: %s\n", argv[i]);
            return 2;
        } else if (!o->dir) o->dir = argv[i];
        else if (!o->truth) o->truth = argv[i];
    }
    if (!o->dir) {
        fprintf(stderr, "usage: cubtool eval-track DUMP_DIR [TRUTH] [--csv FILE] [--print]\n");
        return 2;
    }
    return 0;
}

/* The tracker over every frame of d, scored against the truths. */
static int run_frames(const eval_opts *o, const cub_tool_dump *d, const eval_truths *tr_all,
                      eval_acc *acc, double *secs)
{
    const cub_synth_truth *tt = &tr_all->child;
    int have = tr_all->have_child;
    cub_vec3 grav = {(cub_q16)(tt->gravity[0] * 65536), (cub_q16)(tt->gravity[1] * 65536),
                     (cub_q16)(tt->gravity[2] * 65536)};
    int have_grav = have && !o->no_gravity;
    FILE *jf = NULL;
    if (o->joints && !(jf = fopen(o->joints, "w"))) {
        fprintf(stderr, "eval-track: %s: cannot write: %s\n", o->joints, strerror(errno));
        return -1;
    }
    if (jf) fprintf(jf, "frame,joint,status,confidence,yaw,err_mm,within\n");
    void *mem = NULL;
    char *fbytes = NULL;
    cub_forest forest;
    int with_forest = o->forest != NULL;
    cub_tracker *t = NULL;
    if (!with_forest || !cub_tool_forest_load(o->forest, &fbytes, &forest, "eval-track"))
        t = cub_tool_tracker_new(&mem, with_forest ? &forest : NULL, "eval-track");
    if (!t) {
        if (jf) fclose(jf);
        free(fbytes);
        return -1;
    }
    /* A truth that starts after the dump's first frame (synth-depth
     * --prelude): the frames before are attract mode, its first frame is
     * START, where the box has the player chosen afresh. */
    int start = have && tt->frame_count > 0 ? tt->frames[0].frame : 0;
    for (int f = 0; f < d->n; f++) {
        cub_track_skeleton s;
        if (f > 0 && f == start) cub_track_choose_afresh(t);
        double t0 = now_s();
        cub_track_frame(t, d->raw + (size_t)f * CUB_TOOL_FRAME_PIXELS, d->t_us[f],
                        have_grav ? &grav : NULL, &s);
        *secs += now_s() - t0;
        if (s.status >= 0 && s.status < 5) acc->status[s.status]++;
        if (o->print) print_frame(d->name[f], &s);
        const cub_synth_truth_frame *tr = truth_of(tt, have, f);
        if (!tr) continue;
        const cub_synth_truth_frame *other = truth_of(&tr_all->second, tr_all->have_second, f);
        char note[128];
        identity_note(&s, tr, other, score_identity(acc, &s, tr, other), note, sizeof note);
        score_joints(acc, &s, tr, truth_yaw_deg(tr, tt->gravity), o->per_frame, note, jf);
    }
    free(mem);
    free(fbytes);
    if (jf && fclose(jf) != 0) {
        fprintf(stderr, "eval-track: %s: cannot write\n", o->joints);
        return -1;
    }
    return 0;
}

int cub_cmd_eval_track(int argc, char **argv)
{
    eval_opts o = {0};
    int rc = parse_args(argc, argv, &o);
    if (rc) return rc == 1 ? 0 : rc;
    /* The truths first: a bad one is refused before the frames (600 kB
     * each) are read. */
    char tpath[4096], spath[4096];
    if (!o.truth) snprintf(tpath, sizeof tpath, "%s/truth.txt", o.dir), o.truth = tpath;
    snprintf(spath, sizeof spath, "%s/truth_second.txt", o.dir);
    eval_truths tr = {0};
    if (load_truth(o.truth, &tr.child, &tr.have_child)) return 1;
    if (tr.have_child && load_truth(spath, &tr.second, &tr.have_second)) {
        cub_synth_truth_free(&tr.child);
        return 1;
    }
    cub_tool_dump d;
    eval_acc *acc = calloc(1, sizeof *acc);
    double secs = 0;
    rc = !acc || cub_tool_dump_load(o.dir, &d, EVAL_MAX_FRAMES, "eval-track") ? 1 : 0;
    if (!rc) {
        rc = run_frames(&o, &d, &tr, acc, &secs) ? 1 : 0;
        if (!rc && tr.have_child) print_table(acc), print_sure_table(acc);
        if (!rc && !tr.have_child)
            printf("eval-track: no truth at %s (status and speed only)\n", o.truth);
        if (!rc && tr.have_second)
            printf("eval-track: wrong person in %d of %d frames with a player and a second person "
                   "(%d with the child in view)\n",
                   acc->wrong, acc->second_frames, acc->wrong_in_view);
        if (!rc)
            printf("eval-track: frames=%d ok=%d no_player=%d too_close=%d too_far=%d "
                   "partly_out=%d fps=%.0f\n",
                   d.n, acc->status[0], acc->status[1], acc->status[2], acc->status[3],
                   acc->status[4], secs > 0 ? d.n / secs : 0.0);
        if (!rc && o.csv && write_csv(o.csv, acc, d.n)) rc = 1;
        cub_tool_dump_free(&d);
    }
    free(acc);
    cub_synth_truth_free(&tr.child);
    cub_synth_truth_free(&tr.second);
    return rc;
}

/* kinect_read — UTKinect and MSR Action3D skeleton files; see kinect_read.h. */
#define _POSIX_C_SOURCE 200809L
#include "kinect_read.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <string.h>
#include <strings.h>

static int fail(char *err, size_t size, const char *path, int line, const char *fmt, ...)
{
    char msg[200];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (line > 0)
        snprintf(err, size, "%s:%d: %s", path, line, msg);
    else
        snprintf(err, size, "%s: %s", path, msg);
    return -1;
}

/* Append one frame, growing the arrays by doubling. */
static int push_frame(kinect_seq *s, int *cap, int frame_no, const cub_vec3 *j)
{
    if (s->count == *cap) {
        int n = *cap ? 2 * *cap : 256;
        int *fn = realloc(s->frame_no, (size_t)n * sizeof *fn);
        if (!fn) return -1;
        s->frame_no = fn;
        void *jj = realloc(s->joint, (size_t)n * sizeof *s->joint);
        if (!jj) return -1;
        s->joint = jj;
        *cap = n;
    }
    s->frame_no[s->count] = frame_no;
    memcpy(s->joint[s->count], j, sizeof s->joint[0]);
    s->count++;
    return 0;
}

/* Metres to Q16.16 mm; reject what no Kinect reports (|v| > 20 m, NaN). */
static int metres(double m, cub_q16 *out)
{
    if (!(fabs(m) <= 20.0)) return -1;
    *out = fz_q16(m * 1000.0);
    return 0;
}

/* Parse n doubles from s; returns how many were read. */
static int numbers(const char *s, double *v, int n)
{
    int got = 0;
    while (got < n) {
        char *end;
        errno = 0;
        double x = strtod(s, &end);
        if (end == s || errno) break;
        v[got++] = x;
        s = end;
    }
    return got;
}

static int blank(const char *s)
{
    return s[strspn(s, " \t\r\n")] == '\0';
}

int kinect_read_utkinect(const char *path, kinect_seq *out, char *err, size_t err_size)
{
    memset(out, 0, sizeof *out);
    FILE *f = fopen(path, "r");
    if (!f) return fail(err, err_size, path, 0, "cannot open: %s", strerror(errno));
    char line[4096];
    int cap = 0, ln = 0, prev = -1;
    while (fgets(line, sizeof line, f)) {
        ln++;
        if (blank(line)) continue;
        double v[61];
        cub_vec3 j[CUB_KJ_COUNT];
        int got = numbers(line, v, 61);
        if (got != 61) {
            fclose(f);
            kinect_free(out);
            return fail(err, err_size, path, ln,
                        "expected a frame number and 60 "
                        "coordinates, got %d numbers",
                        got);
        }
        for (int k = 0; k < CUB_KJ_COUNT; k++) {
            if (metres(v[1 + 3 * k], &j[k].x) || metres(v[2 + 3 * k], &j[k].y) ||
                metres(v[3 + 3 * k], &j[k].z)) {
                fclose(f);
                kinect_free(out);
                return fail(err, err_size, path, ln, "joint %d out of range", k + 1);
            }
        }
        int fn = (int)v[0];
        if (fn == prev) continue; /* a re-save of the same frame */
        prev = fn;
        if (push_frame(out, &cap, fn, j)) {
            fclose(f);
            kinect_free(out);
            return fail(err, err_size, path, ln, "out of memory");
        }
    }
    fclose(f);
    if (out->count == 0) return fail(err, err_size, path, 0, "no frames");
    return 0;
}

/* MSR's 1-based joint numbers in Kinect order, with the pairs given as
 * (first, second) of the dataset; side_b_right says whether the second of
 * each pair is the right side. */
static void msr_map(const double v[20][3], int side_b_right, cub_vec3 *j)
{
    /* Kinect index -> MSR number, for side_b_right (second of pair = right). */
    static const int msr_of[CUB_KJ_COUNT] = {
        7, 4,  3,  20, /* hip centre, spine, shoulder centre, head */
        1, 8,  10, 12, /* left shoulder, elbow, wrist, hand */
        2, 9,  11, 13, /* right ... */
        5, 14, 16, 18, /* left hip, knee, ankle, foot */
        6, 15, 17, 19, /* right ... */
    };
    for (int k = 0; k < CUB_KJ_COUNT; k++) {
        int m = msr_of[k];
        if (!side_b_right && k >= CUB_KJ_SHOULDER_L) {
            /* swap the pair: left takes the second, right the first */
            int is_left = (k >= CUB_KJ_SHOULDER_L && k <= CUB_KJ_HAND_L) ||
                          (k >= CUB_KJ_HIP_L && k <= CUB_KJ_FOOT_L);
            m = is_left ? msr_of[k + 4] : msr_of[k - 4];
        }
        j[k] = fz_mm(v[m - 1][0] * 1000.0, v[m - 1][1] * 1000.0, v[m - 1][2] * 1000.0);
    }
}

static int all_zero(const double v[20][3])
{
    for (int k = 0; k < 20; k++)
        if (v[k][0] != 0 || v[k][1] != 0 || v[k][2] != 0) return 0;
    return 1;
}

int kinect_read_msr(const char *path, kinect_seq *out, char *err, size_t err_size)
{
    memset(out, 0, sizeof *out);
    FILE *f = fopen(path, "r");
    if (!f) return fail(err, err_size, path, 0, "cannot open: %s", strerror(errno));
    char line[512];
    int ln = 0, n = 0, cap_frames = 0;
    double(*raw)[20][3] = NULL;
    while (fgets(line, sizeof line, f)) {
        ln++;
        if (blank(line)) continue;
        double v[4];
        if (numbers(line, v, 4) != 4 ||
            !(fabs(v[0]) <= 20 && fabs(v[1]) <= 20 && fabs(v[2]) <= 20)) {
            free(raw);
            fclose(f);
            return fail(err, err_size, path, ln, "expected \"x y z confidence\" in metres");
        }
        if (n / 20 == cap_frames) {
            cap_frames = cap_frames ? 2 * cap_frames : 64;
            void *r = realloc(raw, (size_t)cap_frames * sizeof *raw);
            if (!r) {
                free(raw);
                fclose(f);
                return fail(err, err_size, path, ln, "out of memory");
            }
            raw = r;
        }
        memcpy(raw[n / 20][n % 20], v, 3 * sizeof(double));
        n++;
    }
    fclose(f);
    if (n == 0 || n % 20) {
        free(raw);
        return fail(err, err_size, path, ln,
                    "%d joint lines: not a whole number of "
                    "20-joint frames",
                    n);
    }
    /* Facing the sensor, the right shoulder has the larger x. */
    double xa = 0, xb = 0;
    for (int i = 0; i < n / 20; i++) {
        xa += raw[i][0][0];
        xb += raw[i][1][0];
    }
    int cap = 0;
    for (int i = 0; i < n / 20; i++) {
        if (all_zero(raw[i])) continue; /* the sensor lost the person */
        cub_vec3 j[CUB_KJ_COUNT];
        msr_map((const double(*)[3])raw[i], xb > xa, j);
        if (push_frame(out, &cap, i, j)) {
            free(raw);
            kinect_free(out);
            return fail(err, err_size, path, 0, "out of memory");
        }
    }
    free(raw);
    if (out->count == 0) return fail(err, err_size, path, 0, "no tracked frame (all zero)");
    return 0;
}

void kinect_free(kinect_seq *s)
{
    free(s->frame_no);
    free(s->joint);
    memset(s, 0, sizeof *s);
}

enum { UTK_INTERVAL, UTK_MISSING, UTK_RUN, UTK_BAD, UTK_HALF_NAN };

/* One line of actionLabel.txt: "action: first last", "action: NaN NaN"
 * (the real file's mark of an action the run lacks) or a run "sSS_eEE". */
static int utk_line(const char *line, char name[32], int *a, int *b)
{
    char na[8], nb[8], tail[2];
    if (sscanf(line, "%31[A-Za-z]: %7s %7s %1s", name, na, nb, tail) == 3) {
        int nan_a = !strcasecmp(na, "nan"), nan_b = !strcasecmp(nb, "nan");
        if (nan_a && nan_b) return UTK_MISSING;
        if (nan_a || nan_b) return UTK_HALF_NAN;
    }
    if (sscanf(line, "%31[A-Za-z]: %d %d", name, a, b) == 3) return UTK_INTERVAL;
    char run[16];
    if (sscanf(line, "%15s", run) == 1 && sscanf(run, "s%d_e%d%1s", a, b, tail) == 2) {
        snprintf(name, 32, "%s", run);
        return UTK_RUN;
    }
    return UTK_BAD;
}

int kinect_read_utk_labels(const char *path, utk_interval *out, int max, char *err, size_t err_size)
{
    FILE *f = fopen(path, "r");
    if (!f) return fail(err, err_size, path, 0, "cannot open: %s", strerror(errno));
    char line[256], run[16] = "";
    int ln = 0, n = 0;
    while (fgets(line, sizeof line, f)) {
        ln++;
        if (blank(line)) continue;
        char name[32];
        int a = 0, b = 0, kind = utk_line(line, name, &a, &b);
        const char *bad = kind == UTK_BAD ? "expected \"sSS_eEE\" or \"action: first last\""
                          : kind == UTK_HALF_NAN ? "one NaN: a missing action is \"NaN NaN\""
                          : kind != UTK_RUN && (!run[0] || (kind == UTK_INTERVAL && (n == max || a > b)))
                              ? "interval outside a run, or too many"
                              : NULL;
        if (bad) {
            fclose(f);
            return fail(err, err_size, path, ln, "%s", bad);
        }
        if (kind == UTK_RUN) snprintf(run, sizeof run, "%.15s", name);
        if (kind != UTK_INTERVAL) continue; /* a run, or an action missing from it */
        snprintf(out[n].run, sizeof out[n].run, "%s", run);
        snprintf(out[n].action, sizeof out[n].action, "%s", name);
        out[n].first = a;
        out[n].last = b;
        n++;
    }
    fclose(f);
    return n;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The p-quantile (0..1) of v[0..n), sorting v. */
static double quantile(double *v, int n, double p)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    int i = (int)(p * (n - 1) + 0.5);
    return v[i < 0 ? 0 : i >= n ? n - 1 : i];
}

cub_fuzzy_body kinect_body_for(const kinect_seq *s, int from, int to)
{
    cub_fuzzy_body body = fz_kinect_body(0, 1);
    double *v = malloc((size_t)s->count * sizeof *v);
    if (!v) return body;
    for (int i = 0; i < s->count; i++) {
        cub_q16 l = s->joint[i][CUB_KJ_FOOT_L].y, r = s->joint[i][CUB_KJ_FOOT_R].y;
        v[i] = (l < r ? l : r) / 65536.0;
    }
    body.floor_y_mm = fz_q16(quantile(v, s->count, 0.05));
    int n = 0, all = from < 0;
    if (all) {
        from = 0;
        to = s->count;
    }
    for (int i = from; i < to && i < s->count; i++)
        v[n++] = cub_fuzzy_cog_height_mm(&body, s->joint[i], CUB_KJ_COUNT) / 65536.0;
    if (n > 0) body.stand_cog_mm = fz_q16(quantile(v, n, all ? 0.9 : 0.5));
    free(v);
    return body;
}

int kinect_data_dir(const char *sub, char *buf, size_t size)
{
    const char *data = getenv("CUB_DATA_DIR");
    struct stat st;
    if (!data) return 0;
    snprintf(buf, size, "%s/skeletons/%s", data, sub);
    return stat(buf, &st) == 0 && S_ISDIR(st.st_mode);
}

/* The fakenect dump: INDEX.txt plus one d-<time>-<timestamp>.pgm per frame
 * ("P5 640 480 65535\n", then little-endian uint16 raw values, as
 * fakenect-record writes and ../shared/data/depth/skeltrack holds), each
 * followed by the accelerometer as fakenect-record writes it
 * (a-<time>-<timestamp>.dump, the scene's gravity), and truth.txt beside
 * them (truth_second.txt too when there is a second person), and on request
 * the body-part labels p-<time>-<timestamp>.pgm (not in INDEX.txt: fakenect
 * plays only d- and a- files). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cub/kinect.h"
#include "synth_internal.h"

#define T0_S 1300000000.0 /* the first frame's time, as in the real dump */
#define TS0 1000000u      /* the first timestamp */

void cub_synth_frame_name(int frame, float fps, char *buf, size_t size, double *t_s, uint32_t *ts)
{
    double t = T0_S + frame / (double)fps;
    /* The Kinect's frame timestamps tick at about 60 MHz. */
    uint32_t stamp = TS0 + (uint32_t)frame * (uint32_t)lround(60e6 / fps);
    if (buf) snprintf(buf, size, "d-%f-%u.pgm", t, stamp);
    if (t_s) *t_s = t;
    if (ts) *ts = stamp;
}

static cub_err io_fail(cub_diag *diag, const char *file, const char *what)
{
    if (diag) {
        memset(diag, 0, sizeof(*diag));
        snprintf(diag->file, sizeof(diag->file), "%.250s", file);
        snprintf(diag->msg, sizeof(diag->msg), "%s: %s", what, strerror(errno));
    }
    return CUB_ERR_IO;
}

static int make_dirs(const char *dir)
{
    char p[512];
    snprintf(p, sizeof(p), "%s", dir);
    for (char *c = p + 1; *c; c++)
        if (*c == '/') {
            *c = 0;
            if (mkdir(p, 0777) != 0 && errno != EEXIST) return -1;
            *c = '/';
        }
    return (mkdir(p, 0777) != 0 && errno != EEXIST) ? -1 : 0;
}

static int write_pgm(const char *path, const uint16_t *raw)
{
    FILE *f = fopen(path, "wb");
    if (!f) return -1;
    static unsigned char bytes[CUB_KINECT_WIDTH * CUB_KINECT_HEIGHT * 2];
    for (int i = 0; i < CUB_KINECT_WIDTH * CUB_KINECT_HEIGHT; i++) {
        bytes[2 * i] = (unsigned char)(raw[i] & 0xff);
        bytes[2 * i + 1] = (unsigned char)(raw[i] >> 8);
    }
    int ok = fprintf(f, "P5 %d %d 65535\n", CUB_KINECT_WIDTH, CUB_KINECT_HEIGHT) > 0 &&
             fwrite(bytes, 1, sizeof(bytes), f) == sizeof(bytes);
    return (fclose(f) == 0 && ok) ? 0 : -1;
}

/* libfreenect's freenect_raw_tilt_state as it lies in memory on the box
 * (little-endian): int16 x y z in counts (819 a g), int8 motor angle, a pad
 * byte, int32 motor status (0 stopped). The accelerometer reads the push
 * that holds the camera up: the opposite of gravity (down, length 1000). */
static int write_accel(const char *path, const float down[3])
{
    unsigned char st[12] = {0};
    for (int i = 0; i < 3; i++) {
        long counts = lround(-down[i] * CUB_KINECT_ACCEL_COUNTS_PER_G / 1000.0);
        st[2 * i] = (unsigned char)(counts & 0xff);
        st[2 * i + 1] = (unsigned char)((counts >> 8) & 0xff);
    }
    FILE *f = fopen(path, "wb");
    if (!f) return -1;
    int ok = fwrite(st, 1, sizeof st, f) == sizeof st;
    return (fclose(f) == 0 && ok) ? 0 : -1;
}

/* The part labels beside a depth frame: p-<time>-<timestamp>.pgm. */
static int write_parts(cub_synth *s, const char *dir, const char *name, char *path, size_t size)
{
    static uint8_t part[CUB_KINECT_WIDTH * CUB_KINECT_HEIGHT];
    if (cub_synth_parts(s, part) != CUB_OK) return -1;
    snprintf(path, size, "%s/p-%s", dir, name + 2);
    FILE *f = fopen(path, "wb");
    if (!f) return -1;
    int ok = fprintf(f, "P5 %d %d 255\n", CUB_KINECT_WIDTH, CUB_KINECT_HEIGHT) > 0 &&
             fwrite(part, 1, sizeof(part), f) == sizeof(part);
    return (fclose(f) == 0 && ok) ? 0 : -1;
}

/* One frame's two files and INDEX lines: the depth, then the accelerometer
 * under the frame's name, as fakenect-record orders them. */
static int write_frame(const char *dir, FILE *index, const char *name, const uint16_t *raw,
                       const float down[3], char *path, size_t path_size)
{
    snprintf(path, path_size, "%s/%s", dir, name);
    if (write_pgm(path, raw) != 0) return -1;
    char accel[96];
    snprintf(accel, sizeof accel, "a-%.*s.dump", (int)(strlen(name) - 6), name + 2);
    snprintf(path, path_size, "%s/%s", dir, accel);
    if (write_accel(path, down) != 0) return -1;
    fprintf(index, "%s\n%s\n", name, accel);
    return 0;
}

static void write_truth_head(FILE *f, const float g[3])
{
    fprintf(f, "# cub-synth truth v1: line 2 'gravity gx gy gz' (down, camera space, length "
               "1000); then per frame: frame t_s ts, then 20 joints (");
    for (int j = 0; j < CUB_KJ_COUNT; j++)
        fprintf(f, "%s%s", j ? " " : "", cub_kinect_joint_name(j));
    fprintf(f, ") as x y z v: mm, camera space (x right, y up, z away), v 1 = visible\n");
    fprintf(f, "gravity %.3f %.3f %.3f\n", g[0], g[1], g[2]);
}

static void write_truth_frame(FILE *f, const cub_synth_truth_frame *t)
{
    fprintf(f, "%d %f %u", t->frame, t->t_s, t->ts);
    for (int j = 0; j < CUB_KJ_COUNT; j++)
        fprintf(f, " %.1f %.1f %.1f %d", t->joint_mm[j][0], t->joint_mm[j][1], t->joint_mm[j][2],
                t->visible[j]);
    fputc('\n', f);
}

/* dir/name opened for writing, its truth head written when g is given. */
static FILE *open_out(const char *dir, const char *name, const float *g, cub_diag *diag)
{
    char path[700];
    snprintf(path, sizeof(path), "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (!f) io_fail(diag, path, "cannot write");
    if (f && g) write_truth_head(f, g);
    return f;
}

cub_err cub_synth_write_dump(cub_synth *s, const char *dir, int frames, int flags, cub_diag *diag)
{
    int verbose = flags & CUB_SYNTH_DUMP_VERBOSE;
    if (!s || !dir) return CUB_ERR_ARG;
    int total = cub_synth_frame_count(s);
    if (frames <= 0 || frames > total) frames = total;
    if (make_dirs(dir) != 0) return io_fail(diag, dir, "cannot create the folder");
    char path[700], name[96];
    float g[3];
    cub_synth_gravity(s, g);
    FILE *index = open_out(dir, "INDEX.txt", NULL, diag), *truth = NULL, *second = NULL;
    if (index) truth = open_out(dir, "truth.txt", g, diag);
    if (truth && cub_synth_has_second(s)) second = open_out(dir, "truth_second.txt", g, diag);
    if (!index || !truth || (cub_synth_has_second(s) && !second)) {
        if (index) fclose(index);
        if (truth) fclose(truth);
        return CUB_ERR_IO;
    }
    uint16_t *raw = malloc(CUB_KINECT_WIDTH * CUB_KINECT_HEIGHT * sizeof(uint16_t));
    cub_err err = raw ? CUB_OK : CUB_ERR_NOMEM;
    for (int i = 0; i < frames && !err; i++) {
        cub_synth_truth_frame t;
        err = cub_synth_render(s, i, raw, &t, NULL, NULL);
        if (err) break;
        cub_synth_frame_name(i, synth_fps(s), name, sizeof(name), NULL, NULL);
        if (write_frame(dir, index, name, raw, g, path, sizeof(path)) != 0 ||
            ((flags & CUB_SYNTH_DUMP_PARTS) && write_parts(s, dir, name, path, sizeof(path)) != 0)) {
            err = io_fail(diag, path, "cannot write");
            break;
        }
        if (i >= cub_synth_prelude_frames(s)) { /* the prelude has no child: no truth */
            write_truth_frame(truth, &t);
            if (second && cub_synth_second_truth(s, &t) == CUB_OK) write_truth_frame(second, &t);
        }
        if (verbose && (i % 30 == 29 || i + 1 == frames))
            fprintf(stderr, "\rsynth-depth: frame %d/%d", i + 1, frames);
    }
    if (verbose) fputc('\n', stderr);
    free(raw);
    int bad = fclose(index) != 0;
    bad |= fclose(truth) != 0;
    if (second) bad |= fclose(second) != 0;
    if (!err && bad) err = io_fail(diag, dir, "cannot finish writing INDEX.txt or a truth file");
    return err;
}

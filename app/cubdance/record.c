/* record — the opt-in fakenect recorder (see record.h). */
#include "record.h"

#include <dirent.h>
#include <errno.h>
#include <libfreenect.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <time.h>

#define PGM_HEADER "P5 640 480 65535\n"
#define FRAME_BYTES ((int64_t)sizeof PGM_HEADER - 1 + CUB_DEPTH_W * CUB_DEPTH_H * 2)
#define DISK_CHECK_EVERY 30 /* frames between free-space checks (about a second) */

struct cub_record {
    cub_record_desc desc;
    char dir[1024];     /* the recording directory */
    char folder[1100];  /* the current recording's folder, "" between them */
    FILE *index;        /* its INDEX.txt while recording */
    int64_t used_bytes; /* what dir holds, this run's frames included */
    int64_t t0_s;       /* wall clock (s) when the current recording began */
    uint32_t frames;
    int full;           /* the cap or the disk stopped recording for good */
    uint16_t row[CUB_DEPTH_W * CUB_DEPTH_H]; /* one frame, little-endian */
};

/* Bytes of the regular files in dir and its folders (recordings are one
 * level deep). */
static int64_t dir_bytes(const char *dir, int depth)
{
    DIR *d = opendir(dir);
    if (!d) return 0;
    int64_t sum = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        char path[2048];
        struct stat st;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        if (lstat(path, &st) != 0) continue;
        if (S_ISREG(st.st_mode)) sum += st.st_size;
        else if (S_ISDIR(st.st_mode) && depth > 0) sum += dir_bytes(path, depth - 1);
    }
    closedir(d);
    return sum;
}

cub_err cub_record_open(const cub_record_desc *desc, cub_record **out, char *err,
                        size_t err_size)
{
    *out = NULL;
    if (!desc || !desc->dir || !desc->dir[0] || strlen(desc->dir) >= 1000) {
        snprintf(err, err_size, "recording: no recording directory (or its name is too long)");
        return CUB_ERR_ARG;
    }
    if (mkdir(desc->dir, 0700) != 0 && errno != EEXIST) {
        snprintf(err, err_size, "cannot create the recording directory %s: %s", desc->dir,
                 strerror(errno));
        return CUB_ERR_IO;
    }
    struct stat st;
    if (stat(desc->dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        snprintf(err, err_size, "recording directory %s: not a directory", desc->dir);
        return CUB_ERR_IO;
    }
    cub_record *r = calloc(1, sizeof *r);
    if (!r) return snprintf(err, err_size, "recording: out of memory"), CUB_ERR_NOMEM;
    r->desc = *desc;
    if (r->desc.max_bytes <= 0) r->desc.max_bytes = (int64_t)2048 << 20;
    if (r->desc.reserve_bytes <= 0) r->desc.reserve_bytes = (int64_t)256 << 20;
    snprintf(r->dir, sizeof r->dir, "%s", desc->dir);
    r->desc.dir = r->dir;
    r->used_bytes = dir_bytes(r->dir, 1);
    *out = r;
    return CUB_OK;
}

static void log_line(cub_record *r, int64_t t_us, const char *event, const char *fmt,
                     const char *a, const char *b)
{
    if (r->desc.log) cub_log_event(r->desc.log, t_us, "record", event, fmt, a, b);
}

/* <dir>/<YYYYmmdd-HHMMSS>[-n]: a fresh folder every time. */
static int make_folder(cub_record *r)
{
    time_t now = time(NULL);
    struct tm tm;
    char stamp[32];
    strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", localtime_r(&now, &tm));
    r->t0_s = (int64_t)now;
    for (int n = 1; n < 100; n++) {
        if (n == 1) snprintf(r->folder, sizeof r->folder, "%s/%s", r->dir, stamp);
        else snprintf(r->folder, sizeof r->folder, "%s/%s-%d", r->dir, stamp, n);
        if (mkdir(r->folder, 0700) == 0) return 0;
        if (errno != EEXIST) break;
    }
    return -1;
}

void cub_record_begin(cub_record *r, int64_t t_us)
{
    if (!r || r->index || r->full) return;
    char path[1200];
    if (make_folder(r) == 0) {
        snprintf(path, sizeof path, "%s/INDEX.txt", r->folder);
        r->index = fopen(path, "w");
    }
    if (!r->index) {
        fprintf(stderr, "cubdance: cannot record into %s: %s\n", r->folder, strerror(errno));
        log_line(r, t_us, "error", "dir=%s error=\"%s\"", r->folder, strerror(errno));
        r->folder[0] = '\0';
        r->full = 1; /* a directory that refuses once will refuse again */
        return;
    }
    r->frames = 0;
    const char *name = strrchr(r->folder, '/') + 1;
    log_line(r, t_us, "start", "dir=%s%s", name, "");
}

void cub_record_end(cub_record *r, int64_t t_us, const char *reason)
{
    if (!r || !r->index) return;
    fclose(r->index);
    r->index = NULL;
    char frames[32], why[64];
    snprintf(frames, sizeof frames, "%u", r->frames);
    snprintf(why, sizeof why, "%s", reason);
    log_line(r, t_us, "stop", "frames=%s reason=%s", frames, why);
    r->folder[0] = '\0';
}

/* Room for one more frame: under the cap, and the disk keeps its reserve. */
static const char *no_room(cub_record *r)
{
    if (r->used_bytes + FRAME_BYTES + 64 > r->desc.max_bytes) return "cap";
    if (r->frames % DISK_CHECK_EVERY == 0) {
        struct statvfs vfs;
        if (statvfs(r->folder, &vfs) != 0) return "disk";
        int64_t avail = (int64_t)vfs.f_bavail * (int64_t)vfs.f_frsize;
        if (avail < r->desc.reserve_bytes + DISK_CHECK_EVERY * (FRAME_BYTES + 64)) return "disk";
    }
    return NULL;
}

static int write_file(const char *path, const void *head, size_t head_size, const void *body,
                      size_t body_size)
{
    FILE *f = fopen(path, "wb");
    if (!f) return -1;
    int ok = fwrite(head, 1, head_size, f) == head_size &&
             (body_size == 0 || fwrite(body, 1, body_size, f) == body_size);
    return fclose(f) == 0 && ok ? 0 : -1;
}

/* fakenect's names: d-<seconds>-<timestamp>.pgm, a-... .dump. The seconds
 * pace the replay; the timestamp is the camera's own (60 MHz ticks). As
 * fakenect-record does, the accelerometer is written after the frame, named
 * with the frame's timestamp: fakenect hands the frame after it this
 * reading. */
static int write_frame(cub_record *r, const cub_depth_frame *f)
{
    int64_t us = r->t0_s * 1000000 + (f->t_us > 0 ? f->t_us : 0);
    char stamp[64], name[96], path[1300];
    snprintf(stamp, sizeof stamp, "%lld.%06lld-%u", (long long)(us / 1000000),
             (long long)(us % 1000000), f->timestamp);
    for (int i = 0; i < CUB_DEPTH_W * CUB_DEPTH_H; i++) { /* little-endian on any CPU */
        uint8_t *b = (uint8_t *)&r->row[i];
        b[0] = (uint8_t)(f->raw[i] & 0xff);
        b[1] = (uint8_t)(f->raw[i] >> 8);
    }
    snprintf(name, sizeof name, "d-%s.pgm", stamp);
    snprintf(path, sizeof path, "%s/%s", r->folder, name);
    if (write_file(path, PGM_HEADER, sizeof PGM_HEADER - 1, r->row, sizeof r->row)) return -1;
    fprintf(r->index, "%s\n", name);
    freenect_raw_tilt_state tilt;
    memset(&tilt, 0, sizeof tilt); /* the pad byte too: the same file every run */
    tilt.accelerometer_x = f->accel[0];
    tilt.accelerometer_y = f->accel[1];
    tilt.accelerometer_z = f->accel[2];
    snprintf(name, sizeof name, "a-%s.dump", stamp);
    snprintf(path, sizeof path, "%s/%s", r->folder, name);
    if (write_file(path, &tilt, sizeof tilt, NULL, 0)) return -1;
    fprintf(r->index, "%s\n", name);
    return fflush(r->index) == 0 ? 0 : -1;
}

void cub_record_frame(void *user, const cub_depth_frame *f)
{
    cub_record *r = user;
    if (!r || !r->index || !f || !f->raw) return;
    const char *why = no_room(r);
    if (!why && write_frame(r, f) != 0) why = "error";
    if (why) {
        r->full = 1;
        cub_record_end(r, f->t_us, why);
        return;
    }
    r->frames++;
    r->used_bytes += FRAME_BYTES + (int64_t)sizeof(freenect_raw_tilt_state) + 128;
}

int cub_record_active(const cub_record *r)
{
    return r && r->index != NULL;
}

void cub_record_close(cub_record *r)
{
    if (!r) return;
    if (r->index) fclose(r->index);
    free(r);
}

/* The box watching the child (see watch.h). */
#include "watch.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *status_name(int32_t status)
{
    switch (status) {
    case CUB_TRACK_OK: return "ok";
    case CUB_TRACK_NO_PLAYER: return "no_player";
    case CUB_TRACK_TOO_CLOSE: return "too_close";
    case CUB_TRACK_TOO_FAR: return "too_far";
    case CUB_TRACK_PARTLY_OUT: return "partly_out";
    default: return "?";
    }
}

static size_t align16(size_t n)
{
    return (n + 15) & ~(size_t)15;
}

/* The forest's bytes into w (they must outlive the tracker), opened. */
static cub_err load_forest(cub_watch *w, const char *path)
{
    FILE *f = fopen(path, "rb");
    long len = -1;
    if (f && !fseek(f, 0, SEEK_END)) len = ftell(f);
    if (len > 0 && !fseek(f, 0, SEEK_SET) && (w->forest_bytes = malloc((size_t)len)) &&
        fread(w->forest_bytes, 1, (size_t)len, f) != (size_t)len)
        len = -1;
    if (f) fclose(f);
    if (len <= 0 || !w->forest_bytes) {
        fprintf(stderr, "cubdance: %s: cannot read the forest: %s\n", path, f ? "short read" : strerror(errno));
        return CUB_ERR_IO;
    }
    cub_forest_problem why = {0};
    if (cub_forest_open(w->forest_bytes, (size_t)len, &w->forest, &why)) {
        fprintf(stderr, "cubdance: %s: not a forest: %s at byte %zu\n", path, why.what, why.offset);
        return CUB_ERR_FORMAT;
    }
    return CUB_OK;
}

cub_err cub_watch_open(cub_watch *w, cub_log *log, const char *forest_path)
{
    memset(w, 0, sizeof *w);
    w->log = log;
    w->status = -1;
    w->skel.status = CUB_TRACK_NO_PLAYER;
    cub_err fe = forest_path ? load_forest(w, forest_path) : CUB_OK;
    if (fe) {
        cub_watch_close(w);
        return fe;
    }
    cub_track_desc td = {.forest = forest_path ? &w->forest : NULL};
    cub_judge_desc jd = {.log = log};
    size_t track_size = align16(cub_track_mem_size(&td));
    size_t judge_size = align16(cub_judge_mem_size(&jd));
    /* aligned_alloc wants a multiple of the alignment: both parts are. */
    w->mem = aligned_alloc(16, track_size + judge_size);
    if (!w->mem) return CUB_ERR_NOMEM;
    cub_err e = cub_track_init(&td, w->mem, track_size, &w->tracker);
    if (!e) e = cub_judge_init(&jd, (uint8_t *)w->mem + track_size, judge_size, &w->judge);
    if (e) cub_watch_close(w);
    return e;
}

void cub_watch_close(cub_watch *w)
{
    free(w->mem);
    free(w->forest_bytes);
    w->mem = NULL;
    w->forest_bytes = NULL;
    w->tracker = NULL;
    w->judge = NULL;
}

static void post(cub_loop *loop, int64_t t_us, int32_t type, int32_t a, int32_t b)
{
    cub_event ev = {.t_us = t_us, .type = type, .a = a, .b = b};
    cub_loop_post(loop, &ev);
}

static void camera_back(cub_watch *w, cub_loop *loop, int64_t t_us)
{
    if (!w->camera_lost) return;
    w->camera_lost = 0;
    cub_log_event(w->log, t_us, "watch", "camera", "state=back frames=%u", w->frames);
    post(loop, t_us, CUB_EV_CAMERA, 1, 0);
}

static void camera_gone(cub_watch *w, cub_loop *loop, int64_t t_us, const char *why)
{
    if (w->camera_lost || !w->frames) return;
    w->camera_lost = 1;
    cub_judge_cancel_reps(w->judge); /* no frames: nothing to judge them on */
    cub_log_event(w->log, t_us, "watch", "camera", "state=lost why=%s frames=%u", why, w->frames);
    post(loop, t_us, CUB_EV_CAMERA, 0, 0);
}

/* The judge's events go to the coach (a wave is only logged: the judge's
 * own log line tells it). */
static void post_judged(cub_loop *loop, const cub_judge_out *out)
{
    for (int32_t i = 0; i < out->count; i++)
        if (out->events[i].ev.type != CUB_EV_NONE) cub_loop_post(loop, &out->events[i].ev);
}

/* Once when the accelerometer starts (or stops) giving the tracker its
 * floor, not every frame: a real reading moves by a count or two. */
static void log_gravity(cub_watch *w, int64_t t_us, const int16_t accel[3], int known)
{
    w->gravity_known = known;
    cub_log_event(w->log, t_us, "watch", "gravity", "state=%s accel=%d,%d,%d",
                  known ? "known" : "unknown", accel[0], accel[1], accel[2]);
}

void cub_watch_frame(cub_watch *w, cub_loop *loop, int64_t t_us, const uint16_t *raw,
                     const int16_t accel[3])
{
    if (!w->tracker) return;
    if (w->frames) w->gap_us = t_us - w->last_frame_us;
    w->last_frame_us = t_us;
    w->frames++;
    camera_back(w, loop, t_us);
    /* The accelerometer measures the push that holds the Kinect up: a level
     * Kinect reads about +819 counts on y (1 g), y being up as in camera
     * space; down is the opposite of the reading. (x and z are taken to
     * match camera space too: not checked on hardware.) */
    cub_vec3 gravity = {CUB_Q16_INT(-accel[0]), CUB_Q16_INT(-accel[1]), CUB_Q16_INT(-accel[2])};
    const int known = accel[0] || accel[1] || accel[2];
    if (known != w->gravity_known) log_gravity(w, t_us, accel, known);
    cub_track_frame(w->tracker, raw, t_us, known ? &gravity : NULL, &w->skel);
    if (w->skel.status != w->status) {
        cub_log_event(w->log, t_us, "track", "status", "from=%s to=%s player=%d",
                      w->status < 0 ? "none" : status_name(w->status),
                      status_name(w->skel.status), w->skel.player_id);
        w->status = w->skel.status;
    }
    cub_judge_out out;
    if (cub_judge_frame(w->judge, t_us, &w->skel, &out) == CUB_OK) post_judged(loop, &out);
}

void cub_watch_source_gone(cub_watch *w, cub_loop *loop, int64_t t_us, const char *why)
{
    camera_gone(w, loop, t_us, why);
}

void cub_watch_tick(cub_watch *w, cub_loop *loop, int64_t now_us)
{
    if (!w->frames || w->camera_lost) return;
    int64_t limit = 3 * w->gap_us > CUB_WATCH_LOST_US ? 3 * w->gap_us : CUB_WATCH_LOST_US;
    if (now_us - w->last_frame_us > limit) camera_gone(w, loop, now_us, "silent");
}

void cub_watch_start(cub_watch *w)
{
    if (w && w->tracker) cub_track_choose_afresh(w->tracker);
}

const cub_track_skeleton *cub_watch_skeleton(const cub_watch *w)
{
    return &w->skel;
}

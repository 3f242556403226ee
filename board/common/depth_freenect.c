/* depth_freenect — depth frames from libfreenect: a live Kinect, or a dump
 * replayed by fakenect (LD_LIBRARY_PATH=/usr/lib/<multiarch>/fakenect,
 * FAKENECT_PATH=<dump>). The same calls run in both cases, so a replay
 * exercises exactly the code the box runs.
 *
 * libfreenect delivers frames from inside freenect_process_events, on the
 * caller's thread: the callback copies into the back half of a double
 * buffer and the poll hands out the newest one. No locks needed.
 *
 * fakenect (Debian 0.5.3) differs from a live device in ways that matter:
 * it serves only FREENECT_DEPTH_11BIT, its process_events sleeps until the
 * next recorded frame time (it ignores the timeout), returns < 0 at the end
 * of the dump, calls exit() on a missing FAKENECT_PATH or a missing file
 * named in INDEX.txt, and over-reads a short frame file. fakenect_dump.c
 * checks the dump first: a missing or truncated depth frame is replayed as
 * a frame without readings (through a private view of the dump), anything
 * else bad is an error instead of a dead program.
 *
 * Under the virtual clock a replay is paced by its recorded timestamps
 * (60 MHz ticks) on the loop's own clock: a frame is handed out once the
 * loop reaches its recorded time after the first, with that time as its
 * arrival. A recording then plays at its own rate whatever the machine's
 * speed, and a gap in it (a camera that stopped) is a gap in the loop. */
#define _GNU_SOURCE /* RTLD_DEFAULT */

#include "clock.h"
#include "depth.h"
#include "fakenect_dump.h"

#include <dlfcn.h>
#include <libfreenect.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/time.h>

#define FRAME_PIXELS (CUB_DEPTH_W * CUB_DEPTH_H)
#define FRAME_BYTES (FRAME_PIXELS * sizeof(uint16_t))

struct cub_depth_freenect {
    freenect_context *ctx;
    freenect_device *dev;
    const cub_board_clock *clock;
    uint16_t bufs[2][FRAME_PIXELS];
    int held;            /* buffer the caller may be reading (-1: none yet) */
    int back;            /* buffer the newest frame was copied into */
    int fresh;           /* back holds a frame not handed out yet */
    uint32_t arrived;    /* frames delivered by libfreenect so far */
    uint32_t back_seq, back_timestamp;
    int64_t back_t_us;
    int ended;
    int tilt_ok;
    int replay;          /* fakenect is serving a recorded dump */
    int paced;           /* a replay under the virtual clock: see above */
    int have_first;
    uint32_t last_timestamp;
    uint64_t ticks;      /* 60 MHz ticks since the first frame, past the counter's wraps */
    int64_t first_t_us;
    cub_fakenect_view view; /* the mended dump fakenect replays, if any */
};

/* When a replayed frame is due on the virtual clock. The Kinect's 60 MHz
 * counter is 32 bits and wraps every 71.6 s: the ticks are summed frame to
 * frame (each step taken modulo 2^32), so any length of recording works. */
static int64_t due_us(cub_depth_freenect *s, uint32_t timestamp)
{
    s->ticks += (uint32_t)(timestamp - s->last_timestamp);
    s->last_timestamp = timestamp;
    return s->first_t_us + (int64_t)(s->ticks / 60);
}

static void on_depth(freenect_device *dev, void *depth, uint32_t timestamp)
{
    cub_depth_freenect *s = freenect_get_user(dev);
    s->back = s->held == 0 ? 1 : 0;
    memcpy(s->bufs[s->back], depth, FRAME_BYTES);
    s->back_seq = s->arrived++;
    s->back_timestamp = timestamp;
    s->back_t_us = cub_board_clock_now_us(s->clock);
    if (s->paced && !s->have_first) {
        s->have_first = 1;
        s->last_timestamp = timestamp;
        s->first_t_us = s->back_t_us;
    }
    if (s->paced) s->back_t_us = due_us(s, timestamp);
    s->fresh = 1;
}

/* fakenect exports helpers the real library does not have. */
static int fakenect_loaded(void)
{
    return dlsym(RTLD_DEFAULT, "sleep_highres") != NULL;
}

static cub_err start(cub_depth_freenect *s, char *err, size_t err_size)
{
    if (freenect_init(&s->ctx, NULL) < 0) {
        s->ctx = NULL;
        snprintf(err, err_size, "depth: libfreenect could not start (USB)");
        return CUB_ERR_DEVICE;
    }
    freenect_set_log_level(s->ctx, FREENECT_LOG_ERROR);
    /* The camera, and the motor subdevice because it carries the
     * accelerometer (gravity, for the floor); we never move the motor. Not
     * the audio subdevice: it wants firmware uploaded. */
    freenect_select_subdevices(s->ctx, FREENECT_DEVICE_CAMERA | FREENECT_DEVICE_MOTOR);
    if (freenect_num_devices(s->ctx) <= 0) {
        snprintf(err, err_size, "depth: no Kinect found");
        return CUB_ERR_DEVICE;
    }
    if (freenect_open_device(s->ctx, &s->dev, 0) < 0) {
        /* Some Kinect models expose no motor: read depth without gravity. */
        s->dev = NULL;
        s->tilt_ok = 0;
        freenect_select_subdevices(s->ctx, FREENECT_DEVICE_CAMERA);
    }
    if (!s->dev && freenect_open_device(s->ctx, &s->dev, 0) < 0) {
        s->dev = NULL;
        snprintf(err, err_size, "depth: the Kinect is there but would not open (permissions? "
                                "see board/pi/55-cubdance.rules)");
        return CUB_ERR_DEVICE;
    }
    freenect_set_user(s->dev, s);
    freenect_frame_mode mode = freenect_find_depth_mode(FREENECT_RESOLUTION_MEDIUM,
                                                        FREENECT_DEPTH_11BIT);
    if (!mode.is_valid || freenect_set_depth_mode(s->dev, mode) < 0) {
        snprintf(err, err_size, "depth: the Kinect refused 640x480 11-bit depth");
        return CUB_ERR_DEVICE;
    }
    freenect_set_depth_callback(s->dev, on_depth);
    if (freenect_start_depth(s->dev) < 0) {
        snprintf(err, err_size, "depth: the Kinect would not start streaming depth");
        return CUB_ERR_DEVICE;
    }
    return CUB_OK;
}

cub_err cub_depth_freenect_open(const cub_board_clock *clock, cub_depth_freenect **out,
                                char *err, size_t err_size)
{
    *out = NULL;
    cub_depth_freenect *s = calloc(1, sizeof *s);
    if (!s) {
        snprintf(err, err_size, "depth: out of memory");
        return CUB_ERR_NOMEM;
    }
    s->clock = clock;
    s->held = -1;
    s->tilt_ok = 1;
    s->replay = fakenect_loaded();
    s->paced = s->replay && clock->is_virtual;
    cub_err e = s->replay ? cub_fakenect_dump_prepare(&s->view, err, err_size) : CUB_OK;
    if (!e) {
        e = start(s, err, err_size);
    }
    if (e) {
        cub_depth_freenect_close(s);
        return e;
    }
    *out = s;
    return CUB_OK;
}

/* The accelerometer, if this libfreenect can read it; zeros otherwise. */
static void read_accel(cub_depth_freenect *s, int16_t accel[3])
{
    accel[0] = accel[1] = accel[2] = 0;
    if (!s->tilt_ok || freenect_update_tilt_state(s->dev) < 0) {
        s->tilt_ok = 0;
        return;
    }
    freenect_raw_tilt_state *st = freenect_get_tilt_state(s->dev);
    if (st) {
        accel[0] = st->accelerometer_x;
        accel[1] = st->accelerometer_y;
        accel[2] = st->accelerometer_z;
    }
}

cub_err cub_depth_freenect_poll(cub_depth_freenect *s, cub_depth_frame *out)
{
    /* Paced: a frame waiting for its time is not overwritten by the next
     * one (and is not handed out early, below). */
    if (!s->ended && !(s->paced && s->fresh)) {
        struct timeval no_wait = {0, 0};
        int got = freenect_process_events_timeout(s->ctx, &no_wait);
        /* fakenect has read FAKENECT_PATH by now (0.5.3: at its first event). */
        cub_fakenect_dump_restore_env(&s->view);
        if (got < 0) {
            /* Only a replay ends: on a live Kinect an error (a USB hiccup,
             * an unplug) is reported and the next poll tries again. */
            if (!s->replay || (s->arrived == 0 && !s->fresh)) {
                return CUB_ERR_DEVICE;
            }
            s->ended = 1; /* a frame still fresh is handed out first */
        }
    }
    if (!s->fresh) {
        return s->ended ? CUB_ERR_END : CUB_ERR_EMPTY;
    }
    if (s->paced && cub_board_clock_now_us(s->clock) < s->back_t_us) {
        return CUB_ERR_EMPTY;
    }
    s->held = s->back;
    s->fresh = 0;
    out->raw = s->bufs[s->held];
    out->seq = s->back_seq;
    out->timestamp = s->back_timestamp;
    out->t_us = s->back_t_us;
    read_accel(s, out->accel);
    return CUB_OK;
}

int cub_depth_freenect_is_replay(const cub_depth_freenect *s)
{
    return s->replay;
}

void cub_depth_freenect_close(cub_depth_freenect *s)
{
    if (!s) {
        return;
    }
    if (s->dev) {
        freenect_stop_depth(s->dev);
        freenect_close_device(s->dev);
    }
    if (s->ctx) {
        freenect_shutdown(s->ctx);
    }
    cub_fakenect_dump_release(&s->view);
    free(s);
}

/* depth_freenect — depth frames from libfreenect: a live Kinect, or a dump
 * replayed by fakenect (LD_LIBRARY_PATH=/usr/lib/<multiarch>/fakenect,
 * FAKENECT_PATH=<dump>). The same calls run in both cases, so a replay
 * exercises exactly the code the box runs.
 *
 * libfreenect delivers frames from inside freenect_process_events: the
 * callback copies into a spare buffer of three and makes it the newest; the
 * poll hands out the newest one, and the caller reads it until the next
 * poll. A lock keeps the three apart when a reader thread fills them.
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
 * Each fakenect call serves one INDEX.txt line, and a recording from a live
 * Kinect holds a colour frame and several accelerometer lines (a-*.dump:
 * the freenect_raw_tilt_state fakenect then reports) beside every depth
 * frame. One call per poll would fall behind the recording, so a replay is
 * drained: under the real clock by a reader thread, which sleeps in
 * fakenect to each line's recorded time while the loop runs on (a frame
 * not yet taken holds the next one back); under the
 * virtual clock in the poll itself, line by line until the next depth frame
 * (a count of lines, not a time, so the same on every machine). Each
 * replayed frame carries the accelerometer reading of the lines before it.
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
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/time.h>

#define FRAME_PIXELS (CUB_DEPTH_W * CUB_DEPTH_H)
#define FRAME_BYTES (FRAME_PIXELS * sizeof(uint16_t))
/* Lines one virtual-clock poll reads looking for a depth frame: far more
 * than a recording has between two (a colour frame, a few accelerometer
 * lines), few enough that a dump of accelerometer lines only cannot hold
 * the loop. */
#define MAX_LINES_PER_POLL 256

struct cub_depth_freenect {
    freenect_context *ctx;
    freenect_device *dev;
    const cub_board_clock *clock;
    uint16_t bufs[3][FRAME_PIXELS];
    pthread_mutex_t lock; /* the fields down to stop, when a reader thread runs */
    pthread_cond_t taken; /* the poll took the newest frame */
    int held;            /* buffer the caller may be reading (-1: none yet) */
    int back;            /* buffer the newest frame was copied into (-1: none yet) */
    int fresh;           /* back holds a frame not handed out yet */
    uint32_t arrived;    /* frames delivered by libfreenect so far */
    uint32_t back_seq, back_timestamp;
    int64_t back_t_us;
    int16_t back_accel[3]; /* a replay's accelerometer when back arrived */
    int ended;
    int stop;            /* asks the reader thread to return */
    pthread_t reader;
    int threaded;        /* the reader thread runs (a replay under the real clock) */
    int64_t last_poll_us; /* board time of the previous poll */
    int tilt_ok;
    int replay;          /* fakenect is serving a recorded dump */
    int paced;           /* a replay under the virtual clock: see above */
    int have_first;
    uint32_t last_timestamp;
    uint64_t ticks;      /* 60 MHz ticks since the first frame, past the counter's wraps */
    int warned_step;     /* a step back or a jump was reported */
    int64_t first_t_us;
    cub_fakenect_view view; /* the mended dump fakenect replays, if any */
};

/* When a replayed frame is due on the virtual clock. The Kinect's 60 MHz
 * counter is 32 bits and wraps every 71.6 s: the ticks are summed frame to
 * frame (each step taken modulo 2^32), so any length of recording works.
 * A step back (a timestamp smaller than the one before, or an unparsable
 * name, which fakenect reads as 0) would be taken modulo 2^32 as a
 * 71.5 s wait, and a jump past MAX_STEP_TICKS is no camera pause a
 * recording holds: both are taken as one frame's step, said once. */
#define FRAME_TICKS 2000000u          /* 60 MHz / 30 fps */
#define MAX_STEP_TICKS (60000000u * 10) /* 10 s: a recorded gap longer is a jump */
static int64_t due_us(cub_depth_freenect *s, uint32_t timestamp)
{
    uint32_t step = (uint32_t)(timestamp - s->last_timestamp);
    if (step > MAX_STEP_TICKS) {
        if (!s->warned_step++)
            fprintf(stderr,
                    "depth: replay: the frame timestamp %s (%u after %u): taken as one frame's "
                    "step\n",
                    step >= 0x80000000u ? "steps back" : "jumps more than 10 s", timestamp,
                    s->last_timestamp);
        step = FRAME_TICKS;
    }
    s->ticks += step;
    s->last_timestamp = timestamp;
    return s->first_t_us + (int64_t)(s->ticks / 60);
}

/* The buffer neither handed out nor newest. */
static int spare_buffer(const cub_depth_freenect *s)
{
    int i = 0;
    while (i == s->held || i == s->back) i++;
    return i;
}

/* fakenect's tilt state is what the last a- line said (zeros before one). */
static void replay_accel(freenect_device *dev, int16_t accel[3])
{
    freenect_raw_tilt_state *st = freenect_get_tilt_state(dev);
    accel[0] = st ? st->accelerometer_x : 0;
    accel[1] = st ? st->accelerometer_y : 0;
    accel[2] = st ? st->accelerometer_z : 0;
}

static void on_depth(freenect_device *dev, void *depth, uint32_t timestamp)
{
    cub_depth_freenect *s = freenect_get_user(dev);
    pthread_mutex_lock(&s->lock);
    /* A replay loses no frame to a slow loop: the frame before waits for
     * the poll. (Only then: fakenect times each line from the end of the
     * call before, so a wait between its calls would add up frame by frame.) */
    while (s->threaded && s->fresh && !s->stop) pthread_cond_wait(&s->taken, &s->lock);
    int spare = spare_buffer(s);
    pthread_mutex_unlock(&s->lock);
    memcpy(s->bufs[spare], depth, FRAME_BYTES); /* the poll never touches the spare */
    pthread_mutex_lock(&s->lock);
    s->back = spare;
    s->back_seq = s->arrived++;
    s->back_timestamp = timestamp;
    s->back_t_us = cub_board_clock_now_us(s->clock);
    if (s->replay) replay_accel(dev, s->back_accel);
    if (s->paced && !s->have_first) {
        s->have_first = 1;
        s->last_timestamp = timestamp;
        s->first_t_us = s->back_t_us;
    }
    if (s->paced) s->back_t_us = due_us(s, timestamp);
    s->fresh = 1;
    pthread_mutex_unlock(&s->lock);
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
    s->held = s->back = -1;
    pthread_mutex_init(&s->lock, NULL);
    pthread_cond_init(&s->taken, NULL);
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

/* One fakenect line, or a live Kinect's pending events. CUB_ERR_DEVICE
 * when nothing can be read at all; the end of a replay sets ended. */
static cub_err process_once(cub_depth_freenect *s)
{
    struct timeval no_wait = {0, 0};
    int got = freenect_process_events_timeout(s->ctx, &no_wait);
    /* fakenect has read FAKENECT_PATH by now (0.5.3: at its first event). */
    cub_fakenect_dump_restore_env(&s->view);
    if (got >= 0) return CUB_OK;
    pthread_mutex_lock(&s->lock);
    /* Only a replay ends: on a live Kinect an error (a USB hiccup, an
     * unplug) is reported and the next poll tries again. */
    cub_err e = !s->replay || (s->arrived == 0 && !s->fresh) ? CUB_ERR_DEVICE : CUB_OK;
    if (!e) s->ended = 1; /* a frame still fresh is handed out first */
    pthread_mutex_unlock(&s->lock);
    return e;
}

static int reader_go_on(cub_depth_freenect *s)
{
    pthread_mutex_lock(&s->lock);
    int go_on = !s->stop && !s->ended;
    pthread_mutex_unlock(&s->lock);
    return go_on;
}

/* The real clock's replay: fakenect sleeps here, not in the loop. */
static void *read_replay(void *arg)
{
    cub_depth_freenect *s = arg;
    while (reader_go_on(s)) {
        if (process_once(s) != CUB_OK) {
            pthread_mutex_lock(&s->lock);
            s->ended = 1; /* nothing came: the poll says the replay is over */
            pthread_mutex_unlock(&s->lock);
        }
    }
    return NULL;
}

/* The virtual clock's replay: lines until a depth frame waits for its time.
 * A frame already waiting is not overwritten by the next one. */
static cub_err drain_to_depth(cub_depth_freenect *s)
{
    cub_err e = CUB_OK;
    for (int n = 0; n < MAX_LINES_PER_POLL && !e && !s->fresh && !s->ended; n++)
        e = process_once(s);
    return e;
}

/* Bring frames in on the loop's thread (all but the real clock's replay,
 * whose first line is read here so that FAKENECT_PATH is put back before
 * another thread runs). */
static cub_err pump(cub_depth_freenect *s)
{
    if (s->threaded || s->ended) return CUB_OK;
    if (s->paced) return drain_to_depth(s);
    cub_err e = process_once(s);
    if (e || !s->replay || s->ended) return e;
    pthread_mutex_lock(&s->lock); /* the reader's callback reads threaded */
    s->threaded = 1;
    pthread_mutex_unlock(&s->lock);
    if (pthread_create(&s->reader, NULL, read_replay, s) != 0) s->threaded = 0;
    return CUB_OK;
}

/* The newest frame, if any is due. Called with the lock held. */
static cub_err hand_out(cub_depth_freenect *s, int64_t now_us, cub_depth_frame *out)
{
    if (!s->fresh) return s->ended ? CUB_ERR_END : CUB_ERR_EMPTY;
    if (s->paced && now_us < s->back_t_us) return CUB_ERR_EMPTY;
    s->held = s->back;
    s->fresh = 0;
    pthread_cond_signal(&s->taken);
    out->raw = s->bufs[s->held];
    out->seq = s->back_seq;
    out->timestamp = s->back_timestamp;
    /* Never older than the previous poll: what the loop logged then came
     * first. (A replayed frame is due after it unless two fall into one
     * tick.) */
    out->t_us = s->back_t_us > s->last_poll_us ? s->back_t_us : s->last_poll_us;
    memcpy(out->accel, s->back_accel, sizeof out->accel);
    return CUB_OK;
}

cub_err cub_depth_freenect_poll(cub_depth_freenect *s, cub_depth_frame *out)
{
    int64_t now_us = cub_board_clock_now_us(s->clock);
    cub_err e = pump(s);
    if (e) return e;
    pthread_mutex_lock(&s->lock);
    e = hand_out(s, now_us, out);
    pthread_mutex_unlock(&s->lock);
    s->last_poll_us = now_us;
    if (!e && !s->replay) read_accel(s, out->accel);
    return e;
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
    if (s->threaded) {
        pthread_mutex_lock(&s->lock);
        s->stop = 1;
        pthread_cond_broadcast(&s->taken);
        pthread_mutex_unlock(&s->lock);
        pthread_join(s->reader, NULL); /* at most one line's recorded wait */
    }
    if (s->dev) {
        freenect_stop_depth(s->dev);
        freenect_close_device(s->dev);
    }
    if (s->ctx) {
        freenect_shutdown(s->ctx);
    }
    cub_fakenect_dump_release(&s->view);
    pthread_cond_destroy(&s->taken);
    pthread_mutex_destroy(&s->lock);
    free(s);
}

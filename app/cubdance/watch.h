/* watch — the box watching the child. Each depth frame goes through the
 * tracker (firmware/track) and the judge (firmware/judge); what they find
 * becomes the coach's events (verdicts, claps, a player coming into view or
 * leaving) and log lines. A camera that stops sending frames becomes
 * CUB_EV_CAMERA (a = 0), and its first frame back CUB_EV_CAMERA (a = 1), so
 * the coach pauses the song and resumes it.
 *
 * "Stops sending": the board says the source failed or ended, or no frame
 * came for CUB_WATCH_LOST_US or three times the last gap between frames,
 * whichever is longer (a live Kinect sends 30 a second; a sparse recording
 * is not taken for a lost camera between its frames).
 *
 * The camera's data stays in memory for this frame only: nothing is stored
 * or sent. */
#ifndef CUB_APP_WATCH_H
#define CUB_APP_WATCH_H

#include <stdint.h>

#include "cub/forest.h"
#include "cub/judge.h"
#include "cub/loop.h"
#include "cub/track.h"

#define CUB_WATCH_LOST_US 1000000

typedef struct cub_watch {
    cub_tracker *tracker;
    cub_judge *judge;
    void *mem; /* both live here */
    void *forest_bytes; /* the forest's asset, or NULL */
    cub_forest forest;
    cub_log *log;
    cub_track_skeleton skel; /* the last frame's */
    int32_t status;          /* the last status logged */
    uint32_t frames;
    int64_t last_frame_us, gap_us;
    int camera_lost;
    int gravity_known; /* the last frame had an accelerometer reading */
} cub_watch;

/* Set up the tracker (with the body-part forest at forest_path, or NULL:
 * without) and the judge. CUB_ERR_NOMEM, a tracker/judge error, or
 * CUB_ERR_IO / CUB_ERR_FORMAT for a forest that cannot be read (said on
 * stderr with the file's name). */
cub_err cub_watch_open(cub_watch *w, cub_log *log, const char *forest_path);
void cub_watch_close(cub_watch *w);

/* A depth frame that arrived at t_us (accel: the raw accelerometer, all
 * zero when unknown): track, judge, post what they found. */
void cub_watch_frame(cub_watch *w, cub_loop *loop, int64_t t_us, const uint16_t *raw,
                     const int16_t accel[3]);
/* The depth source failed or ended (why: for the log). */
void cub_watch_source_gone(cub_watch *w, cub_loop *loop, int64_t t_us, const char *why);
/* START was pressed: the tracker chooses its player afresh on the next
 * frame (the child at the box, not whoever it followed in attract mode). */
void cub_watch_start(cub_watch *w);
/* Every tick: frames stopped coming at their pace? */
void cub_watch_tick(cub_watch *w, cub_loop *loop, int64_t now_us);

/* The player's skeleton in the last frame (status NO_PLAYER before any). */
const cub_track_skeleton *cub_watch_skeleton(const cub_watch *w);

#endif

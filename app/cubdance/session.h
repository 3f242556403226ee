/* session — one run of the box program: the loop's hooks, the waiting /
 * playing states (the coach FSM of a later issue will replace them), the
 * depth inset, and headless frames. */
#ifndef CUB_APP_SESSION_H
#define CUB_APP_SESSION_H

#include <stdint.h>
#include <stdio.h>

#include "cub/board.h"
#include "cub/floor.h"
#include "cub/io.h"
#include "cub/loop.h"
#include "cub/render.h"
#include "bridge_speed.h"
#include "dance.h"
#include "mem_stats.h"
#include "options.h"
#include "record.h"
#include "timeline.h"
#include "watch.h"

typedef enum cub_app_state { CUB_APP_WAITING = 0, CUB_APP_PLAYING } cub_app_state;

typedef struct cub_session {
    const cub_app_options *opt;
    cub_board *board;
    cub_render *render;      /* NULL when there is no display */
    cub_floor *floor;        /* the forest floor (owned), or NULL: the flat meadow */
    const cub_io_motion *clip; /* without a song: the clip played on START */
    cub_dance *dance;          /* with a song: the coach leads it (else NULL) */
    cub_timeline *timeline;    /* scripted judge events, or NULL */
    cub_watch *watch;          /* the tracker and judge on the depth frames, or NULL */
    const char *clip_name;   /* its file name, for the log */
    cub_loop *loop;
    cub_app_state state;
    int ready_shown;         /* what the ready light shows: 1, 0, or -1 before the first tick */
    int64_t play_start_us;
    int64_t stop_at_us;      /* 0 = no limit */
    uint16_t *depth_copy;    /* the last depth frame, for the inset */
    uint32_t depth_frames;
    cub_err depth_state;     /* the last poll's answer other than OK/EMPTY, logged once */
    uint8_t *rgba;           /* read-back buffer for headless frames */
    /* This tick's coach pose, kept here rather than on the stack (the
     * pose is 3.6 KB) or in hidden statics. */
    cub_pose pose;
    cub_vec3 world_mm[CUB_MOTION_MAX_JOINTS];
    float world_xyz[CUB_MOTION_MAX_JOINTS * 3];
    float world_rot[CUB_MOTION_MAX_JOINTS * 4]; /* the bear's, x y z w */
    int pose_error;          /* the clip could not be sampled: reported once */
    uint32_t frames_written;
    int frame_error;         /* a frame could not be written: reported once */
    /* --stats: CPU time per tick, poll to render, in 25 us bins */
    uint32_t *tick_hist;
    uint32_t tick_count, tick_over; /* ticks counted; ... beyond the last bin */
    int64_t tick_cpu0_us, tick_max_us;
    cub_mem_stats *mem;      /* --stats: memory and allocations per tick, or NULL */
    cub_bridge_speed *speed; /* --bridge-speed: the joints' speed measured, or NULL */
    /* Opt-in recording (--record, config recording=1), or NULL */
    cub_record *rec;
    int recording_on;        /* the recorder was told to begin */
    int display_lost;        /* the loop was stopped because the display went */
} cub_session;

#define CUB_SESSION_TICK_BIN_US 25
#define CUB_SESSION_TICK_BINS 4000 /* up to 100 ms */

/* The hooks that plug a session into cub_loop_run. Each tick also checks
 * that the display is still there (if not: an error line and the loop
 * stops, with display_lost set) and starts or ends s->rec's recording. */
cub_loop_hooks cub_session_hooks(cub_session *s);
/* Begin or end s->rec's recording as the session now wants: the whole run
 * (--record), or only while a dance runs (config recording=1). */
void cub_session_follow_recording(cub_session *s, int64_t t_us);
/* --stats: the ticks' CPU time and the peak resident memory, one line. */
void cub_session_print_stats(const cub_session *s, FILE *out);

#endif

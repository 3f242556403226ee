/* walk_box — the bear walks in the box (issue 24, seed 003's "what the
 * box gets"): in from the trees to its place when START wakes it, off
 * to the trees at STOP or after the cheer, wandering while it attracts.
 * The walk clip (assets/clips/bear_walk.bvh, on the bear's skeleton)
 * plays through the gait walker (cub/gait.h) over the floor's terrain;
 * the footsteps go into the event log as `walk` lines. The walk enters
 * and leaves the dance at the bridge frames the coach's own planner
 * gives for the walk's key poses (added to its table, cub/coachlib.h).
 *
 * The walk only draws and logs: it follows the coach's state and never
 * changes what the coach decides or when (the song's first beat stays at
 * the same tick after START). docs/gait.md "The bear walks in the box". */
#ifndef CUB_APP_WALK_BOX_H
#define CUB_APP_WALK_BOX_H

#include <stdint.h>

#include "cub/bridge.h"
#include "cub/floor.h"
#include "cub/gait.h"
#include "cub/io.h"
#include "cub/loop.h"
#include "cub/walk_clip.h"
#include "dance.h"

/* What a walk is for. */
typedef enum cub_walk_why { CUB_WALK_IN = 0, CUB_WALK_OFF, CUB_WALK_WANDER } cub_walk_why;

/* The walk's poses the bridge table holds, one frame each (every frame a
 * bridge frame): where a walk begins, and the two it stops on. */
enum { CUB_WALK_KEY_START = 0, CUB_WALK_KEY_STOP_LEFT, CUB_WALK_KEY_STOP_RIGHT, CUB_WALK_KEYS };

typedef struct cub_walk_box {
    cub_io_motion m;               /* the walk clip */
    cub_walk_clip walk;            /* its analysis for the walker */
    cub_clip keys[CUB_WALK_KEYS];  /* on the coach's skeleton, for the bridge table */
    void *key_mem;
    int key_first;                 /* keys[0]'s clip index in the table, -1: not added */
    void *plan_work;               /* the bridge planner's scratch */
    size_t plan_work_size;
    int hand;                      /* 1: a walk in stopped, waiting for the dance's bridge frame */
    int hand_clip, hand_frame;     /* ... planned: the coach's clip and frame it enters at */
    int64_t hand_at_q16;           /* ... that frame on the clip's unwrapped time */
    const char **names;            /* the table's clip names (the dance's) */
    int64_t leave_us;              /* > 0: the walk off starts then (its bridge frame) */
    int rate_q8;                   /* walker frames per clip frame period, Q8 */
    int64_t blend_us;              /* the picture's fade since switch_us */
    cub_gait_terrain terrain;      /* the floor's (points into it), or flat */
    cub_gait_walker walker;
    cub_log *log;
    const cub_skeleton *skel;           /* the coach's */
    int16_t map[CUB_MOTION_MAX_JOINTS]; /* coach joint -> walk clip joint */
    int joint_count;                    /* the coach's */
    int foot_j[2];                      /* the coach's LeftFoot, RightFoot (-1: none) */
    int walking;                   /* 1: the walker leads the picture */
    cub_walk_why why;
    cub_vec3 place;                /* standing: where (x, z) */
    cub_vec3 target;               /* walking: where to (x, z) */
    int64_t walk_t0_us, deadline_us; /* the walk's start; stop by then (0: none) */
    int frames;                    /* walker frames since walk_t0_us */
    int settled;                   /* a walk in on the dance's feet: the stop foot flat */
    int32_t best_mm;               /* the nearest the root came to the target */
    int64_t switch_us;             /* the last switch (walk <-> stand): the blend's start */
    int64_t now_us;
    int32_t last_state;            /* the coach's state last tick */
    int wander;                    /* the next wander point */
    int drawn;                     /* shown holds a picture */
    cub_pose from, shown;          /* the picture at the switch; the last one drawn */
    cub_pose end_pose;             /* a walk in on the dance's feet: the coach's pose at its
                                      place, on the walk clip's skeleton (the walker arrives in it) */
    cub_quat prev_rot[CUB_MOTION_MAX_JOINTS]; /* the walker's last pose (the coach's joints) */
    cub_q16 arrive_rad;            /* the fastest joint turn while arriving, rad per clip frame */
    cub_q16 walk_rad;              /* ... and while walking before it */
    cub_q16 p99_rad;               /* the walk clip's 99th percentile of the same */
} cub_walk_box;

/* Load the walk clip at path (a BVH on coach's skeleton: same joint
 * names; end sites matched by parent) and stand the bear at its start
 * point in the trees. floor may be NULL (a flat meadow); it and log must
 * outlive w. A clip on another skeleton (the seal) leaves w off
 * (joint_count 0) and returns CUB_OK. CUB_ERR_* with diag for a file
 * that cannot be read or is no walk. */
cub_err cub_walk_box_open(cub_walk_box *w, const char *path, const cub_floor *floor,
                          const cub_skeleton *coach, cub_log *log, cub_diag *diag);
void cub_walk_box_close(cub_walk_box *w);
/* The dance's walks (d->walk) from the clip at path over floor (or NULL),
 * for the coach's skeleton. On failure a message naming the file
 * and problem is in err. */
cub_err cub_dance_open_walk(cub_dance *d, const char *path, const cub_floor *floor, char *err,
                            size_t err_size);
/* The walk's key poses (keys) into the coach's bridge table, after the
 * clips it holds; before the director is built on the table. */
cub_err cub_walk_box_add_keys(cub_walk_box *w, cub_coachlib *cl, const char **names,
                              char *err, size_t err_size);
/* Once per tick, after the coach's: follow its state (walks start and
 * stop, handed to and from the coach's clips at the bridge frames the
 * planner finds on player's table), step the walker, log its footsteps. */
void cub_walk_box_tick(cub_walk_box *w, const cub_bridge_player *player, int32_t coach_state,
                       int64_t t_us);
/* The picture: the coach's pose (local rotations, root) rewritten where
 * the bear walks or stands away from its place. */
void cub_walk_box_pose(cub_walk_box *w, cub_pose *pose);

#endif

/* bridge_speed — what the box shows measured against the clip library's
 * joint speed (issue 23: "no joint faster than the clip library's 99th
 * percentile", bridges included). cubdance --bridge-speed FILE: every
 * tick the bear's pose as shown (the player's blend, the walk), every
 * joint's speed since the tick before; each of the player's switches
 * opens a bridge that lasts until its blend has faded; per bridge the
 * fastest joint and the ticks with a joint over the library's p99, by
 * kind (into a groove, out of one, between taught clips), and the same
 * for the ticks outside the bridges. Measures only: decides nothing, so
 * the event log is the same with it. */
#ifndef CUB_APP_BRIDGE_SPEED_H
#define CUB_APP_BRIDGE_SPEED_H

#include <stdio.h>

#include "dance.h"

typedef enum cub_bridge_kind {
    CUB_BRIDGE_KIND_TAUGHT = 0, /* between two of the library's clips */
    CUB_BRIDGE_KIND_INTO_GROOVE,
    CUB_BRIDGE_KIND_OUT_OF_GROOVE,
    CUB_BRIDGE_KINDS
} cub_bridge_kind;

typedef struct cub_bridge_span {
    int64_t t_us;              /* the tick that shows the switch */
    cub_bridge_step step;      /* the switch */
    cub_bridge_kind kind;
    int ticks, over;           /* ticks measured, with a joint over p99 */
    double max_mm_s;
    int max_joint;
    double own_mm_s;           /* the clip's own fastest joint, unblended, over the same
                                  ticks but the switch's (what the blend alone adds shows) */
} cub_bridge_span;

typedef struct cub_bridge_speed {
    double p99_mm_s;
    cub_vec3 prev[CUB_MOTION_MAX_JOINTS], raw[CUB_MOTION_MAX_JOINTS], prev_raw[CUB_MOTION_MAX_JOINTS];
    cub_pose pose;             /* scratch: the clip's own pose */
    int prev_clip;             /* the player's clip at the last tick */
    int64_t prev_us;           /* < 0: no tick yet */
    uint32_t switches;         /* the director's switch_count seen */
    int open;                  /* the last span is still blending */
    cub_bridge_span *spans;    /* heap */
    int count, cap;
    cub_bridge_span plain[2];  /* outside the bridges: [0] taught clips, [1] grooves */
} cub_bridge_speed;

/* Against the p99 of d's library (cub_library_joint_speed_pct). */
cub_err cub_bridge_speed_init(cub_bridge_speed *b, const cub_dance *d);
/* This tick's pose: d->world_mm after cub_dance_pose. */
void cub_bridge_speed_tick(cub_bridge_speed *b, const cub_dance *d, int64_t t_us);
/* One line per bridge, then the sums by kind. */
void cub_bridge_speed_print(const cub_bridge_speed *b, const cub_dance *d, FILE *out);
void cub_bridge_speed_free(cub_bridge_speed *b);

#endif

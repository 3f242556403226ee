/* join_bridge — today's box switch (firmware/bridge's planner and player,
 * inertial smoothing) on the same joins `cubtool join --all` measures:
 * clip A playing (looped, as a move does) from its last window of frames,
 * then B asked for and entered at one of its first frames as the director
 * enters a move; the poses the player shows from the request until its
 * blend is over, measured like the joins (cub_join_measure). With the
 * seed's tween clip in the table (cub_coachlib_add_tween, via_tween), the
 * planner routes through it where no direct switch is found. */
#ifndef CUB_CUBTOOL_JOIN_BRIDGE_H
#define CUB_CUBTOOL_JOIN_BRIDGE_H

#include "cub/coachlib.h"
#include "cub/join.h"

typedef struct join_bridge {
    cub_coachlib cl;
    cub_bridge_player player;
    void *work;
    int *db_of;        /* table clip -> db clip, -1 when not in the db */
    cub_join_db tween; /* the tween clip's contacts (via_tween) */
    int via_tween;
} join_bridge;

/* Load the shipped assets' library, tags and bear (and build the tween
 * when via_tween). 0 ok, -1 (stderr). */
int join_bridge_open(join_bridge *jb, const char *assets, const cub_join_db *db, int via_tween);
/* The figures of switching from db clip a to db clip b; -1 when either is
 * not in the library or no route exists. ms: request to first switch;
 * *tweened: the route passes the tween clip. */
int join_bridge_measure(join_bridge *jb, const cub_join_db *db, int a, int b, cub_join_figures *out,
                        double *ms, int *tweened);
void join_bridge_close(join_bridge *jb);

#endif

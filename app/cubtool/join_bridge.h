/* join_bridge — the box's switch (firmware/bridge's planner and player,
 * inertial smoothing, with or without its leg phase) on the same joins `cubtool join --all` measures:
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

/* Load the shipped assets' library, tags, routes and bear (and build the
 * tween when via_tween); legs = 0 turns the player's leg phase off, routes
 * = 0 has the planner ignore the searched routes (the box before them).
 * 0 ok, -1 (stderr). */
int join_bridge_open(join_bridge *jb, const char *assets, const cub_join_db *db, int via_tween,
                     int legs, int routes);
typedef struct join_bridge_fig {
    cub_join_figures fig; /* what the player shows */
    cub_join_figures own; /* the clips it plays, unsmoothed, over the same frames
                             (no foot counted across a cut): their own slide */
    double ms;            /* request to first switch */
    int tweened;          /* the route passes the tween clip */
    int routed;           /* the plan is a searched route (cub_bridge_route) */
    int steps;            /* switches in the plan */
} join_bridge_fig;

/* The figures of switching from db clip a to db clip b; -1 when either is
 * not in the library or no route exists. */
int join_bridge_measure(join_bridge *jb, const cub_join_db *db, int a, int b, join_bridge_fig *out);
/* The searched route the box would take for the seed's join of db clips a
 * and b through pick's C: from A's last frame (where the join is defined)
 * into C's frame after its first window, out of C's frame before its last
 * window into B's first frame (the frames the seed's seams line up). -1
 * when a clip is not in the library or C is too short. */
int join_bridge_route_of(const join_bridge *jb, const cub_join_db *db, int a, int b,
                         const cub_join_pick *pick, cub_bridge_route *out);
/* join_bridge_measure with the table's routes replaced by r alone (the
 * player must take routes), then put back. */
int join_bridge_measure_route(join_bridge *jb, const cub_join_db *db, int a, int b,
                              const cub_bridge_route *r, join_bridge_fig *out);
void join_bridge_close(join_bridge *jb);

#endif

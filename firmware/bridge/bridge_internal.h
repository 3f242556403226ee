/* bridge internals shared by the table, the planner and the player. */
#ifndef CUB_BRIDGE_INTERNAL_H
#define CUB_BRIDGE_INTERNAL_H

#include "cub/bridge.h"

/* World joint positions of a pose with the root's x and z taken off: the
 * body's shape and height, wherever on the floor it stands (the root's
 * drift over the floor is smoothed apart, see the player). */
cub_err cub_bridge_body_mm(const cub_skeleton *skel, const cub_pose *pose, cub_vec3 *out);
/* The first of clip c's bridge frames (ascending) that is >= f, as an index
 * from the clip's first bridge: bridge_count when none is. */
int cub_bridge_lower_bound(const cub_bridge_table *t, int c, int f);
/* The largest distance between matching joints of two such shapes, mm Q16. */
cub_q16 cub_bridge_shape_dist_mm(const cub_vec3 *a, const cub_vec3 *b, int joints);

#endif

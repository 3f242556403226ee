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

/* The leg phase (bridge_legs.c), called by the player. Bytes its contacts
 * and floors take in the player's memory: */
size_t cub_bridge_legs_mem_size(const cub_bridge_table *t);
/* Find the legs and mark every frame's standing feet into mem (l->speed_mm
 * and l->min_frames set by the caller). */
void cub_bridge_legs_init(cub_bridge_legs *l, const cub_bridge_table *t, void *mem);
/* A cut: what was shown at it, the frame of the clip playing then, and
 * the new clip's frame (its raw pose dst). */
typedef struct cub_bridge_cut {
    const cub_pose *src, *dst;
    int src_clip, src_frame, to_clip, to_frame;
} cub_bridge_cut;
/* At a cut: which feet are held, where, which leg goes first and for how
 * long. */
void cub_bridge_legs_begin(cub_bridge_legs *l, const cub_bridge_table *t, const cub_bridge_cut *c);
/* The frames the leg phase lasts (both legs), 0 when off. */
int cub_bridge_legs_frames(const cub_bridge_legs *l);
/* Onto out (raw with the offset on), progress_q16 frames into the blend:
 * the held feet kept, the legs over to raw's one at a time. */
void cub_bridge_legs_apply(cub_bridge_legs *l, const cub_skeleton *sk, const cub_pose *raw,
                           int64_t progress_q16, cub_pose *out);

#endif

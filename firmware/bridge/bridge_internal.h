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
 * the new clip's frame (its raw pose dst), at position from_q16 of the new
 * clip's time line; wrap: a looping clip's own next pass (pass_frames
 * long). */
typedef struct cub_bridge_cut {
    const cub_pose *src, *dst;
    int src_clip, src_frame, to_clip, to_frame;
    int64_t from_q16;
    int wrap, pass_frames;
} cub_bridge_cut;
/* At a cut: which feet are held, where, which leg goes first and for how
 * long. A seamless loop's own wrap starts none and leaves a running one
 * going; any other wrap's phase ends within its pass. */
void cub_bridge_legs_begin(cub_bridge_legs *l, const cub_bridge_table *t, const cub_bridge_cut *c);
/* Onto out (raw with the offset on), at position pos_q16: the held feet
 * kept, the legs over to raw's one at a time. */
void cub_bridge_legs_apply(cub_bridge_legs *l, const cub_skeleton *sk, const cub_pose *raw,
                           int64_t pos_q16, cub_pose *out);
/* Frames left of the leg phase at position pos_q16 (Q16), 0 when over. */
int64_t cub_bridge_legs_left_q16(const cub_bridge_legs *l, int64_t pos_q16);

#endif

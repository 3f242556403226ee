/* join internals shared by its files. Not public. */
#ifndef CUB_JOIN_INTERNAL_H
#define CUB_JOIN_INTERNAL_H

#include "cub/join.h"

/* Frame period of a clip in seconds (1/30 when unset). */
double join_dt_s(const cub_clip *clip);
/* World positions (and rotations, rot may be NULL) of one frame. */
void join_frame_world(const cub_clip *clip, int f, cub_dv3 *pos, cub_dq *rot);
void join_clip_free(cub_join_clip *c);

#endif

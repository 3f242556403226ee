/* retarget internals: forward kinematics in doubles (the vector and
 * quaternion maths are cub/vec.h). Not public. */
#ifndef CUB_RT_INTERNAL_H
#define CUB_RT_INTERNAL_H

#include "cub/fx.h"
#include "cub/io.h"
#include "cub/motion.h"
#include "cub/vec.h"

/* Forward kinematics in doubles; rot[j] local rotations, root position
 * root (the root offset is ignored, as in cub_motion_forward). trans may
 * be NULL (joints at their rest offsets). */
void rt_forward(const cub_skeleton *skel, cub_dv3 root, const cub_dq *rot, const cub_dv3 *trans,
                cub_dv3 *world_pos, cub_dq *world_rot);

#endif

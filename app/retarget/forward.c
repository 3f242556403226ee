/* Forward kinematics in doubles for the offline retargeter. */
#include "rt_internal.h"

void rt_forward(const cub_skeleton *skel, cub_dv3 root, const cub_dq *rot, const cub_dv3 *trans,
                cub_dv3 *world_pos, cub_dq *world_rot)
{
    for (int j = 0; j < skel->joint_count; j++) {
        int p = skel->joints[j].parent;
        if (p < 0) {
            world_pos[j] = root;
            world_rot[j] = rot[j];
            continue;
        }
        cub_dv3 off = trans ? trans[j] : cub_dv3_from_fx(skel->joints[j].offset_mm);
        world_pos[j] = cub_dv3_add(world_pos[p], cub_dq_rotate(world_rot[p], off));
        world_rot[j] = cub_dq_norm(cub_dq_mul(world_rot[p], rot[j]));
    }
}

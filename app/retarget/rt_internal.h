/* retarget internals: small double-precision vector and quaternion maths,
 * and the fixed-point conversions. Not public. */
#ifndef CUB_RT_INTERNAL_H
#define CUB_RT_INTERNAL_H

#include "cub/fx.h"
#include "cub/io.h"
#include "cub/motion.h"

#define RT_PI 3.14159265358979323846

typedef struct rt_v3 {
    double x, y, z;
} rt_v3;

typedef struct rt_q {
    double w, x, y, z;
} rt_q;

rt_v3 rt_v3_make(double x, double y, double z);
rt_v3 rt_v3_add(rt_v3 a, rt_v3 b);
rt_v3 rt_v3_sub(rt_v3 a, rt_v3 b);
rt_v3 rt_v3_scale(rt_v3 a, double s);
double rt_v3_dot(rt_v3 a, rt_v3 b);
rt_v3 rt_v3_cross(rt_v3 a, rt_v3 b);
double rt_v3_len(rt_v3 a);
/* a / |a|, or fallback when a is (nearly) zero. */
rt_v3 rt_v3_norm(rt_v3 a, rt_v3 fallback);
/* Angle between two directions, radians. */
double rt_v3_angle(rt_v3 a, rt_v3 b);

rt_q rt_q_identity(void);
rt_q rt_q_mul(rt_q a, rt_q b);
rt_q rt_q_conj(rt_q q);
rt_q rt_q_norm(rt_q q);
rt_v3 rt_q_rotate(rt_q q, rt_v3 v);
rt_q rt_q_axis_angle(rt_v3 unit_axis, double angle_rad);
/* The smallest rotation taking direction a onto direction b. */
rt_q rt_q_arc(rt_v3 a, rt_v3 b);
/* The rotation taking the orthonormal frame (a0, a1) onto (b0, b1)
 * (third axes by cross product). */
rt_q rt_q_frames(rt_v3 a0, rt_v3 a1, rt_v3 b0, rt_v3 b1);
/* Shortest-path spherical interpolation. */
rt_q rt_q_slerp(rt_q a, rt_q b, double t);
double rt_q_dot(rt_q a, rt_q b);
/* Angle of the rotation from a to b, radians (0..pi). */
double rt_q_angle_between(rt_q a, rt_q b);

rt_q rt_q_from_fx(cub_quat q);
cub_quat rt_q_to_fx(rt_q q);
rt_v3 rt_v3_from_fx(cub_vec3 v);
cub_vec3 rt_v3_to_fx(rt_v3 v);

/* Forward kinematics in doubles; rot[j] local rotations, root position
 * root (the root offset is ignored, as in cub_motion_forward). trans may
 * be NULL (joints at their rest offsets). */
void rt_forward(const cub_skeleton *skel, rt_v3 root, const rt_q *rot, const rt_v3 *trans,
                rt_v3 *world_pos, rt_q *world_rot);

#endif

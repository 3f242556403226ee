/* vec — the host tools' vectors and quaternions in floating point, beside
 * the firmware's fixed-point ones (cub/fx.h).
 *
 * cub_dv3 and cub_dq are doubles: the offline code (import, retargeting)
 * works in them. cub_fv3 is floats, with the same vector operations, for
 * the depth synthesizer's ray caster, whose output is pinned bit for bit.
 * Units are the caller's (millimetres in practice); angles are radians.
 * Quaternions are {w, x, y, z}, rotating column vectors: q*p acts p first.
 * Conversions to and from Q16.16 (cub_vec3) and Q2.30 (cub_quat) at the
 * end. No allocation; host only (libm). */
#ifndef CUB_VEC_H
#define CUB_VEC_H

#include <math.h>

#include "cub/fx.h"

#define CUB_VEC_PI 3.14159265358979323846

typedef struct cub_dv3 {
    double x, y, z;
} cub_dv3;

typedef struct cub_fv3 {
    float x, y, z;
} cub_fv3;

typedef struct cub_dq {
    double w, x, y, z;
} cub_dq;

/* The vector operations, written once for both precisions. For V in
 * cub_dv3 and cub_fv3 (T its scalar), each V_<op>:
 *   make(x, y, z)  add(a, b)  sub(a, b)  scale(a, k)  dot(a, b)  cross(a, b)
 *   len(a)  lerp(a, b, t) (a at 0, b at 1)
 *   norm(a, fallback): a / |a|, or fallback when |a| <= eps (a tiny a has
 *   no direction). */
#define CUB_VEC_OPS(V, T, SQRT, EPS)                                                             \
    static inline V V##_make(T x, T y, T z)                                                      \
    {                                                                                            \
        V v = {x, y, z};                                                                         \
        return v;                                                                                \
    }                                                                                            \
    static inline V V##_add(V a, V b) { return V##_make(a.x + b.x, a.y + b.y, a.z + b.z); }      \
    static inline V V##_sub(V a, V b) { return V##_make(a.x - b.x, a.y - b.y, a.z - b.z); }      \
    static inline V V##_scale(V a, T k) { return V##_make(a.x * k, a.y * k, a.z * k); }          \
    static inline T V##_dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }              \
    static inline V V##_cross(V a, V b)                                                          \
    {                                                                                            \
        return V##_make(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);    \
    }                                                                                            \
    static inline T V##_len(V a) { return SQRT(V##_dot(a, a)); }                                 \
    static inline V V##_lerp(V a, V b, T t) { return V##_add(a, V##_scale(V##_sub(b, a), t)); }  \
    static inline V V##_norm(V a, V fallback)                                                    \
    {                                                                                            \
        T n = V##_len(a);                                                                        \
        return n > EPS ? V##_scale(a, (T)1 / n) : fallback;                                      \
    }

CUB_VEC_OPS(cub_dv3, double, sqrt, 1e-12)
CUB_VEC_OPS(cub_fv3, float, sqrtf, 1e-6f)

/* Angle between two directions (0..pi), accurate near 0 and pi. */
double cub_dv3_angle(cub_dv3 a, cub_dv3 b);

/* ---- quaternions (doubles) ---------------------------------------------- */

cub_dq cub_dq_identity(void);
/* a*b: b acts first. */
cub_dq cub_dq_mul(cub_dq a, cub_dq b);
cub_dq cub_dq_conj(cub_dq q);
double cub_dq_dot(cub_dq a, cub_dq b);
/* q / |q|, or the identity when q is (nearly) zero. */
cub_dq cub_dq_norm(cub_dq q);
/* v rotated by the unit quaternion q. */
cub_dv3 cub_dq_rotate(cub_dq q, cub_dv3 v);
/* Rotation by angle_rad about a unit axis. */
cub_dq cub_dq_axis_angle(cub_dv3 unit_axis, double angle_rad);
/* Rotation by angle_rad about axis 0 (x), 1 (y) or 2 (z); exact zeros in
 * the other two components. */
cub_dq cub_dq_about(int axis, double angle_rad);
/* The smallest rotation taking direction a onto direction b. */
cub_dq cub_dq_arc(cub_dv3 a, cub_dv3 b);
/* The rotation taking the frame (a0, a1) onto (b0, b1): a0 onto b0, then
 * about b0 so that a1 lands on b1. */
cub_dq cub_dq_frames(cub_dv3 a0, cub_dv3 a1, cub_dv3 b0, cub_dv3 b1);
/* Shortest-path spherical interpolation, a at t = 0, b at t = 1. */
cub_dq cub_dq_slerp(cub_dq a, cub_dq b, double t);
/* Angle of the rotation from a to b, radians (0..pi). */
double cub_dq_angle_between(cub_dq a, cub_dq b);
/* Euler angles (radians) about axes[0..count) (each 0..2) as the product
 * R[axes[0]] * R[axes[1]] * ...: the last listed acts first (BVH order). */
cub_dq cub_dq_euler(const int *axes, const double *angle_rad, int count);
/* Inverse of cub_dq_euler for 1..3 distinct axes: angles whose product
 * reproduces q as closely as those axes can. */
void cub_dq_to_euler(cub_dq q, const int *axes, int count, double *angle_rad);

/* ---- fixed point -------------------------------------------------------- */

/* Q2.30 to doubles, exactly (not renormalised). */
cub_dq cub_dq_from_fx(cub_quat q);
/* Normalised, then rounded (halves away from zero) to Q2.30. */
cub_quat cub_dq_to_fx(cub_dq q);
/* Q16.16 millimetres to doubles, exactly. */
cub_dv3 cub_dv3_from_fx(cub_vec3 v);
/* Rounded (halves away from zero) to Q16.16; the caller checks the range. */
cub_vec3 cub_dv3_to_fx(cub_dv3 v);

#endif

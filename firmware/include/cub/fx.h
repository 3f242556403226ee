/* fx — plain fixed-point arithmetic, the number system of the firmware.
 *
 * Scalars are Q16.16 (`cub_q16`, int32: 16 integer bits, 16 fraction bits,
 * range ±32768, step 1/65536). Angles are Q16.16 radians. Unit quaternions
 * are Q2.30 (`cub_quat`, int32 per component, 1.0 = 1<<30) so that a chain
 * of thirty joints keeps sub-micrometre accuracy. Positions are `cub_vec3`,
 * Q16.16 millimetres. Everything here is integer-only and bit-identical on
 * every CPU; no libm, no float, no allocation.
 *
 * Accuracy (measured by tests/unit/test_fx.c over the whole domain):
 *   sqrt   correctly rounded (within 1/2 ulp)
 *   sin/cos/atan2/acos  within 2e-4 absolute
 */
#ifndef CUB_FX_H
#define CUB_FX_H

#include <stdbool.h>
#include <stdint.h>

typedef int32_t cub_q16;

#define CUB_Q16_ONE ((cub_q16)65536)
#define CUB_Q16_HALF ((cub_q16)32768)
#define CUB_Q16_MAX ((cub_q16)INT32_MAX)
#define CUB_Q16_MIN ((cub_q16)INT32_MIN)
#define CUB_Q16_PI ((cub_q16)205887)      /* pi rounded to Q16.16 */
#define CUB_Q16_HALF_PI ((cub_q16)102944) /* pi/2 rounded */
#define CUB_Q16_TWO_PI ((cub_q16)411775)  /* 2 pi rounded */

/* Whole numbers to Q16.16. Constants only: values past ±32767 overflow. */
#define CUB_Q16_INT(n) ((cub_q16)((n) * 65536))

/* ---- scalars ----------------------------------------------------------- */

/* a*b, rounded to nearest, saturated to the Q16.16 range. */
cub_q16 cub_fx_mul(cub_q16 a, cub_q16 b);
/* a/b, rounded to nearest, saturated; b == 0 gives ±MAX by a's sign (0 for 0). */
cub_q16 cub_fx_div(cub_q16 a, cub_q16 b);
/* a+b and a-b, saturated. */
cub_q16 cub_fx_add(cub_q16 a, cub_q16 b);
cub_q16 cub_fx_sub(cub_q16 a, cub_q16 b);
cub_q16 cub_fx_abs(cub_q16 a); /* saturates MIN to MAX */
/* a + (b - a)*t with t in [0, 1] Q16.16. */
cub_q16 cub_fx_lerp(cub_q16 a, cub_q16 b, cub_q16 t);
cub_q16 cub_fx_clamp(cub_q16 x, cub_q16 lo, cub_q16 hi);

/* Square root of x >= 0, correctly rounded; negative x gives 0. */
cub_q16 cub_fx_sqrt(cub_q16 x);
/* Integer square root of a 64-bit value, rounded down. */
uint32_t cub_fx_isqrt64(uint64_t x);

/* Sine and cosine of any angle (radians, Q16.16), by table. */
cub_q16 cub_fx_sin(cub_q16 angle_rad);
cub_q16 cub_fx_cos(cub_q16 angle_rad);
/* atan2(y, x) in (-pi, pi]; atan2(0, 0) is 0. Any magnitudes. */
cub_q16 cub_fx_atan2(cub_q16 y, cub_q16 x);
/* acos(x) in [0, pi]; x is clamped to [-1, 1]. */
cub_q16 cub_fx_acos(cub_q16 x);
/* Wrap an angle into (-pi, pi]. */
cub_q16 cub_fx_wrap_angle(cub_q16 angle_rad);

/* ---- vectors (Q16.16, usually millimetres) ------------------------------ */

typedef struct cub_vec3 {
    cub_q16 x, y, z;
} cub_vec3;

cub_vec3 cub_fx_vec3_add(cub_vec3 a, cub_vec3 b);
cub_vec3 cub_fx_vec3_sub(cub_vec3 a, cub_vec3 b);
cub_vec3 cub_fx_vec3_scale(cub_vec3 a, cub_q16 s);
cub_vec3 cub_fx_vec3_lerp(cub_vec3 a, cub_vec3 b, cub_q16 t);
/* Dot product and length, computed in 64 bits, saturated on return. */
cub_q16 cub_fx_vec3_dot(cub_vec3 a, cub_vec3 b);
cub_q16 cub_fx_vec3_length(cub_vec3 a);
cub_vec3 cub_fx_vec3_cross(cub_vec3 a, cub_vec3 b);
/* Angle between two vectors in [0, pi]; 0 if either is zero. Robust for
 * long vectors (works on the 64-bit dot and cross, not on normalised ones). */
cub_q16 cub_fx_vec3_angle(cub_vec3 a, cub_vec3 b);

/* ---- unit quaternions (Q2.30) ------------------------------------------ */

#define CUB_QUAT_ONE ((int32_t)1 << 30)

typedef struct cub_quat {
    int32_t w, x, y, z; /* Q2.30; a unit quaternion has w*w+x*x+y*y+z*z = 1 */
} cub_quat;

cub_quat cub_fx_quat_identity(void);
/* Rotation by angle_rad about a unit axis (Q16.16 components). */
cub_quat cub_fx_quat_from_axis_angle(cub_vec3 unit_axis, cub_q16 angle_rad);
/* a*b: rotate by b first, then by a (the usual composition). */
cub_quat cub_fx_quat_mul(cub_quat a, cub_quat b);
cub_quat cub_fx_quat_conj(cub_quat q);
/* Rescale to unit length; the zero quaternion becomes identity. */
cub_quat cub_fx_quat_normalize(cub_quat q);
/* Dot product, Q2.30. */
int32_t cub_fx_quat_dot(cub_quat a, cub_quat b);
/* Rotate a Q16.16 vector by a unit quaternion. */
cub_vec3 cub_fx_quat_rotate(cub_quat q, cub_vec3 v);
/* Normalised linear interpolation along the shorter arc; t in [0, 1] Q16.16.
 * t = 0 gives a and t = 1 gives b exactly (as given), and a == b gives a.
 * For neighbouring animation frames nlerp and slerp differ by far less than
 * a Q2.30 step's worth of joint position, and nlerp is cheap and exact. */
cub_quat cub_fx_quat_nlerp(cub_quat a, cub_quat b, cub_q16 t);
/* Spherical interpolation along the shorter arc (for large angles). */
cub_quat cub_fx_quat_slerp(cub_quat a, cub_quat b, cub_q16 t);
/* The rotation angle of q, in [0, pi] (Q16.16 radians). */
cub_q16 cub_fx_quat_angle(cub_quat q);

#endif

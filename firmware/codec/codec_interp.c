/* Restoring a dropped frame half way between two neighbours: the seed's
 * Squad, and Slerp and Catmull-Rom to compare it with; the cubic spline for
 * positions. */
#include "cub/codec.h"

/* q or -q, whichever lies on ref's side: the same rotation, the short arc. */
static cub_quat align(cub_quat q, cub_quat ref)
{
    if (cub_fx_quat_dot(q, ref) >= 0) return q;
    return (cub_quat){-q.w, -q.x, -q.y, -q.z};
}

/* log of a unit quaternion: half its angle times its axis (Q16.16 rad). */
static cub_vec3 quat_log(cub_quat q)
{
    if (q.w < 0) q = (cub_quat){-q.w, -q.x, -q.y, -q.z};
    uint64_t v2 = (uint64_t)((int64_t)q.x * q.x) + (uint64_t)((int64_t)q.y * q.y) +
                  (uint64_t)((int64_t)q.z * q.z);
    int64_t vlen = cub_fx_isqrt64(v2);
    if (vlen == 0) return (cub_vec3){0, 0, 0};
    int64_t half = cub_fx_quat_angle(q) / 2;
    return (cub_vec3){(cub_q16)(q.x * half / vlen), (cub_q16)(q.y * half / vlen),
                      (cub_q16)(q.z * half / vlen)};
}

/* exp of a pure quaternion u: the rotation by 2|u| about u. */
static cub_quat quat_exp(cub_vec3 u)
{
    return cub_fx_quat_from_axis_angle(u, 2 * cub_fx_vec3_length(u));
}

cub_quat cub_codec_squad_control(cub_quat prev, cub_quat q, cub_quat next)
{
    cub_quat inv = cub_fx_quat_conj(q);
    cub_vec3 a = quat_log(cub_fx_quat_mul(inv, next));
    cub_vec3 b = quat_log(cub_fx_quat_mul(inv, prev));
    cub_vec3 sum = cub_fx_vec3_add(a, b);
    cub_vec3 u = {-sum.x / 4, -sum.y / 4, -sum.z / 4};
    return cub_fx_quat_normalize(cub_fx_quat_mul(q, quat_exp(u)));
}

static cub_quat squad_mid(const cub_quat q[4])
{
    cub_quat s1 = cub_codec_squad_control(q[0], q[1], q[2]);
    cub_quat s2 = cub_codec_squad_control(q[1], q[2], q[3]);
    /* squad(h) = slerp(slerp(q1, q2, h), slerp(s1, s2, h), 2h(1-h)); h = 1/2. */
    cub_quat a = cub_fx_quat_slerp(q[1], q[2], CUB_Q16_HALF);
    cub_quat b = cub_fx_quat_slerp(s1, s2, CUB_Q16_HALF);
    return cub_fx_quat_slerp(a, b, CUB_Q16_HALF);
}

/* The uniform Catmull-Rom spline at t = 1/2: (-a + 9b + 9c - d) / 16. */
static int64_t cubic_mid(int64_t a, int64_t b, int64_t c, int64_t d)
{
    int64_t s = -a + 9 * b + 9 * c - d;
    return s >= 0 ? (s + 8) / 16 : -((-s + 8) / 16);
}

static cub_quat catmull_mid(const cub_quat q[4])
{
    cub_quat m = {
        (int32_t)cubic_mid(q[0].w, q[1].w, q[2].w, q[3].w),
        (int32_t)cubic_mid(q[0].x, q[1].x, q[2].x, q[3].x),
        (int32_t)cubic_mid(q[0].y, q[1].y, q[2].y, q[3].y),
        (int32_t)cubic_mid(q[0].z, q[1].z, q[2].z, q[3].z),
    };
    return cub_fx_quat_normalize(m);
}

cub_quat cub_codec_rot_mid(const cub_quat q[4], cub_codec_method method)
{
    /* Neighbours on q1's side, chained outwards, so no step takes the long arc. */
    cub_quat a[4];
    a[1] = q[1];
    a[2] = align(q[2], a[1]);
    a[0] = align(q[0], a[1]);
    a[3] = align(q[3], a[2]);
    if (method == CUB_CODEC_SLERP) return cub_fx_quat_slerp(a[1], a[2], CUB_Q16_HALF);
    if (method == CUB_CODEC_CATMULL) return catmull_mid(a);
    return squad_mid(a);
}

static cub_q16 sat_q16(int64_t v)
{
    return v > INT32_MAX ? INT32_MAX : v < INT32_MIN ? INT32_MIN : (cub_q16)v;
}

cub_vec3 cub_codec_pos_mid(const cub_vec3 p[4])
{
    return (cub_vec3){sat_q16(cubic_mid(p[0].x, p[1].x, p[2].x, p[3].x)),
                      sat_q16(cubic_mid(p[0].y, p[1].y, p[2].y, p[3].y)),
                      sat_q16(cubic_mid(p[0].z, p[1].z, p[2].z, p[3].z))};
}

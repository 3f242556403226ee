/* fx vectors: Q16.16 three-vectors (usually millimetres), 64-bit
 * intermediates, saturated results. */
#include "fx_internal.h"

cub_vec3 cub_fx_vec3_add(cub_vec3 a, cub_vec3 b)
{
    return (cub_vec3){cub_fx_add(a.x, b.x), cub_fx_add(a.y, b.y), cub_fx_add(a.z, b.z)};
}

cub_vec3 cub_fx_vec3_sub(cub_vec3 a, cub_vec3 b)
{
    return (cub_vec3){cub_fx_sub(a.x, b.x), cub_fx_sub(a.y, b.y), cub_fx_sub(a.z, b.z)};
}

cub_vec3 cub_fx_vec3_scale(cub_vec3 a, cub_q16 s)
{
    return (cub_vec3){cub_fx_mul(a.x, s), cub_fx_mul(a.y, s), cub_fx_mul(a.z, s)};
}

cub_vec3 cub_fx_vec3_lerp(cub_vec3 a, cub_vec3 b, cub_q16 t)
{
    return (cub_vec3){cub_fx_lerp(a.x, b.x, t), cub_fx_lerp(a.y, b.y, t), cub_fx_lerp(a.z, b.z, t)};
}

cub_q16 cub_fx_vec3_dot(cub_vec3 a, cub_vec3 b)
{
    static const int8_t plus[3] = {1, 1, 1};
    const int64_t p[3] = {(int64_t)a.x * b.x, (int64_t)a.y * b.y, (int64_t)a.z * b.z};
    return cub_fxi_sat32(cub_fxi_sum_shift(p, plus, 3, 16));
}

static uint64_t sum_squares(int64_t x, int64_t y, int64_t z)
{
    /* Each square <= 2^62, so three fit in 64 unsigned bits. */
    return (uint64_t)(x * x) + (uint64_t)(y * y) + (uint64_t)(z * z);
}

cub_q16 cub_fx_vec3_length(cub_vec3 a)
{
    /* sqrt(sum of Q.32 squares) is the length in Q16.16 directly. */
    uint32_t len = cub_fxi_sqrt64_round(sum_squares(a.x, a.y, a.z));
    return len > (uint32_t)CUB_Q16_MAX ? CUB_Q16_MAX : (cub_q16)len;
}

/* a1*b2 - a2*b1 in Q16.16, exact before rounding. */
static cub_q16 cross_term(cub_q16 a1, cub_q16 b2, cub_q16 a2, cub_q16 b1)
{
    static const int8_t sign[2] = {1, -1};
    const int64_t p[2] = {(int64_t)a1 * b2, (int64_t)a2 * b1};
    return cub_fxi_sat32(cub_fxi_sum_shift(p, sign, 2, 16));
}

cub_vec3 cub_fx_vec3_cross(cub_vec3 a, cub_vec3 b)
{
    return (cub_vec3){cross_term(a.y, b.z, a.z, b.y), cross_term(a.z, b.x, a.x, b.z),
                      cross_term(a.x, b.y, a.y, b.x)};
}

static uint64_t max_abs3(cub_vec3 v)
{
    uint64_t m = 0, c[3] = {(uint64_t)(v.x < 0 ? -(int64_t)v.x : v.x),
                            (uint64_t)(v.y < 0 ? -(int64_t)v.y : v.y),
                            (uint64_t)(v.z < 0 ? -(int64_t)v.z : v.z)};
    for (int i = 0; i < 3; i++)
        if (c[i] > m) m = c[i];
    return m;
}

/* Halve v until every component is below 2^30; the direction is kept. */
static cub_vec3 shrink(cub_vec3 v)
{
    while (max_abs3(v) >= ((uint64_t)1 << 30)) {
        v.x >>= 1;
        v.y >>= 1;
        v.z >>= 1;
    }
    return v;
}

cub_q16 cub_fx_vec3_angle(cub_vec3 a, cub_vec3 b)
{
    if (max_abs3(a) == 0 || max_abs3(b) == 0) return 0;
    a = shrink(a);
    b = shrink(b);
    /* Components < 2^30: dot < 3*2^60 and cross components < 2^61, exact. */
    int64_t v[4] = {
        (int64_t)a.x * b.x + (int64_t)a.y * b.y + (int64_t)a.z * b.z,
        (int64_t)a.y * b.z - (int64_t)a.z * b.y,
        (int64_t)a.z * b.x - (int64_t)a.x * b.z,
        (int64_t)a.x * b.y - (int64_t)a.y * b.x,
    };
    /* Scale all four into [2^29, 2^30) so |cross| below keeps ~30 bits. */
    uint64_t m = 0;
    for (int i = 0; i < 4; i++) {
        uint64_t mi = v[i] < 0 ? (uint64_t)0 - (uint64_t)v[i] : (uint64_t)v[i];
        if (mi > m) m = mi;
    }
    int up = 0, down = 0;
    while ((m >> down) >= ((uint64_t)1 << 30))
        down++;
    while (m != 0 && (m << up) < ((uint64_t)1 << 29))
        up++;
    for (int i = 0; i < 4; i++)
        v[i] = (v[i] >> down) * ((int64_t)1 << up);
    int64_t cross_len = cub_fxi_sqrt64_round(sum_squares(v[1], v[2], v[3]));
    return (cub_q16)cub_fxi_round_shift(cub_fxi_atan2_q30(cross_len, v[0]), 14);
}

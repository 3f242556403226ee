/* fx trigonometry: sin/cos from a quarter-wave table, atan2 from an atan
 * table on [0, 1] with octant reduction, acos through atan2, angle wrap.
 * Tables: fx_tables.c (tests/unit/gen_fx_tables.py): the nearest entry
 * plus a short series for the rest, good to ~1e-9 inside (Q2.30), so the
 * Q16.16 results are limited only by their own rounding. Angles are
 * reduced in Q.48 radians against a 48-bit pi/2, so even angles of
 * thousands of radians lose nothing to the reduction. */
#include "fx_internal.h"

#define N CUB_FXI_TABLE_N
#define ONE_Q30 ((int64_t)1 << 30)

void cub_fxi_sincos_q48(int64_t angle_q48, int32_t *sin_q30, int32_t *cos_q30)
{
    /* Reduce to a quadrant k and a remainder in [0, pi/2). */
    int64_t k = angle_q48 / CUB_FXI_HALF_PI_Q48, rem = angle_q48 % CUB_FXI_HALF_PI_Q48;
    if (rem < 0) {
        rem += CUB_FXI_HALF_PI_Q48;
        k--;
    }
    /* Nearest table angle a = idx * pi/(2N), and the small rest d. */
    int64_t idx = (rem * (2 * N) + CUB_FXI_PI_Q48 / 2) / CUB_FXI_PI_Q48; /* 0..N */
    int64_t d = cub_fxi_round_shift(rem - ((idx * CUB_FXI_PI_Q48) >> (CUB_FXI_TABLE_BITS + 1)), 18);
    /* |d| <= pi/(4N) < 2e-3: sin d = d - d^3/6, cos d = 1 - d^2/2 to 1e-13. */
    int64_t d2 = (d * d + (ONE_Q30 >> 1)) >> 30;
    int64_t sin_d = d - cub_fxi_round_shift(d2 * d, 30) / 6;
    int64_t cos_d = ONE_Q30 - d2 / 2;
    int64_t sa = cub_fxi_sin_table[idx], ca = cub_fxi_sin_table[N - idx];
    int64_t s = (sa * cos_d + ca * sin_d + (ONE_Q30 >> 1)) >> 30;
    int64_t c = (ca * cos_d - sa * sin_d + (ONE_Q30 >> 1)) >> 30;
    int64_t out_s, out_c;
    switch (k & 3) { /* sin/cos of (k * pi/2 + r) */
    case 0: out_s = s, out_c = c; break;
    case 1: out_s = c, out_c = -s; break;
    case 2: out_s = -s, out_c = -c; break;
    default: out_s = -c, out_c = s; break;
    }
    if (sin_q30) *sin_q30 = (int32_t)out_s;
    if (cos_q30) *cos_q30 = (int32_t)out_c;
}

/* atan(t) in Q.30 for t in [0, 1] given in Q0.32 (so t <= 2^32):
 * atan(t) = atan(t0) + atan(u), u = (t - t0) / (1 + t t0), |u| <= 1/(2N). */
static int64_t atan_unit(uint64_t t)
{
    uint64_t i = (t + ((uint64_t)1 << (31 - CUB_FXI_TABLE_BITS))) >> (32 - CUB_FXI_TABLE_BITS);
    int64_t num = (int64_t)t - (int64_t)(i << (32 - CUB_FXI_TABLE_BITS));
    int64_t den = ((int64_t)1 << 32) + (int64_t)((t * i) >> CUB_FXI_TABLE_BITS); /* Q.32 */
    int64_t scaled = num * ONE_Q30;                                              /* < 2^53 */
    int64_t u = (scaled + (scaled < 0 ? -den : den) / 2) / den;                  /* Q.30 */
    int64_t u2 = (u * u + (ONE_Q30 >> 1)) >> 30;
    return cub_fxi_atan_table[i] + u - cub_fxi_round_shift(u2 * u, 30) / 3;
}

static int64_t q16_to_q48(cub_q16 a)
{
    return (int64_t)a * ((int64_t)1 << 32);
}

cub_q16 cub_fx_sin(cub_q16 angle_rad)
{
    int32_t s;
    cub_fxi_sincos_q48(q16_to_q48(angle_rad), &s, NULL);
    return (cub_q16)cub_fxi_round_shift(s, 14);
}

cub_q16 cub_fx_cos(cub_q16 angle_rad)
{
    int32_t c;
    cub_fxi_sincos_q48(q16_to_q48(angle_rad), NULL, &c);
    return (cub_q16)cub_fxi_round_shift(c, 14);
}

static uint64_t magnitude(int64_t v)
{
    return v < 0 ? (uint64_t)0 - (uint64_t)v : (uint64_t)v;
}

int64_t cub_fxi_atan2_q30(int64_t y, int64_t x)
{
    uint64_t ay = magnitude(y), ax = magnitude(x);
    if (ay == 0 && ax == 0) return 0;
    /* Only the ratio matters: bring both below 2^31 so small << 32 fits. */
    while (ay > ((uint64_t)1 << 31) || ax > ((uint64_t)1 << 31)) {
        ay >>= 1;
        ax >>= 1;
    }
    int64_t a; /* angle in the first quadrant, Q.30 */
    if (ay <= ax) {
        a = atan_unit((ay << 32) / ax);
    } else {
        a = CUB_FXI_HALF_PI_Q30 - atan_unit((ax << 32) / ay);
    }
    if (x < 0) a = CUB_FXI_PI_Q30 - a;
    return y < 0 ? -a : a;
}

cub_q16 cub_fx_atan2(cub_q16 y, cub_q16 x)
{
    /* |result| <= pi * 2^30 rounds to at most 205887 < pi * 2^16: always in
     * (-pi, pi] even for y just below zero with x < 0. */
    return (cub_q16)cub_fxi_round_shift(cub_fxi_atan2_q30(y, x), 14);
}

cub_q16 cub_fx_acos(cub_q16 x)
{
    int64_t c = cub_fx_clamp(x, -CUB_Q16_ONE, CUB_Q16_ONE);
    /* sin = sqrt(1 - x^2) computed in Q.30 from the exact Q.32 1 - x^2, so
     * the steep ends near +-1 keep their accuracy. */
    uint64_t one_minus_sq_q32 = ((uint64_t)1 << 32) - (uint64_t)(c * c);
    int64_t s_q30 = cub_fx_isqrt64(one_minus_sq_q32 << 28);
    return (cub_q16)cub_fxi_round_shift(cub_fxi_atan2_q30(s_q30, c * (1 << 14)), 14);
}

cub_q16 cub_fx_wrap_angle(cub_q16 angle_rad)
{
    int64_t r = q16_to_q48(angle_rad) % CUB_FXI_TWO_PI_Q48;
    if (r > CUB_FXI_PI_Q48) r -= CUB_FXI_TWO_PI_Q48;
    if (r <= -CUB_FXI_PI_Q48) r += CUB_FXI_TWO_PI_Q48;
    /* Angles already in (-pi, pi] come back unchanged. */
    return (cub_q16)cub_fxi_round_shift(r, 32);
}

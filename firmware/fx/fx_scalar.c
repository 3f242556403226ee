/* fx scalars: Q16.16 arithmetic with rounding and saturation, and the
 * square roots. */
#include "fx_internal.h"

int32_t cub_fxi_sat32(int64_t v)
{
    if (v > INT32_MAX) return INT32_MAX;
    if (v < INT32_MIN) return INT32_MIN;
    return (int32_t)v;
}

int64_t cub_fxi_round_shift(int64_t v, int s)
{
    int64_t half = (int64_t)1 << (s - 1);
    /* Halves away from zero keep f(-x) == -f(x) for odd functions. */
    return v >= 0 ? (v + half) >> s : -((-v + half) >> s);
}

int64_t cub_fxi_sum_shift(const int64_t *p, const int8_t *sign, int n, int s)
{
    /* Each product splits exactly into (p >> s) * 2^s + low bits, so the
     * two partial sums stay small whatever the magnitudes. */
    int64_t mask = ((int64_t)1 << s) - 1;
    int64_t hi = 0, lo = 0;
    for (int i = 0; i < n; i++) {
        hi += sign[i] * (p[i] >> s);
        lo += sign[i] * (p[i] & mask);
    }
    return hi + ((lo + ((int64_t)1 << (s - 1))) >> s);
}

cub_q16 cub_fx_mul(cub_q16 a, cub_q16 b)
{
    return cub_fxi_sat32(cub_fxi_round_shift((int64_t)a * b, 16));
}

cub_q16 cub_fx_div(cub_q16 a, cub_q16 b)
{
    if (b == 0) return a > 0 ? CUB_Q16_MAX : a < 0 ? -CUB_Q16_MAX : 0;
    uint64_t n = (a < 0 ? (uint64_t)0 - (uint64_t)(int64_t)a : (uint64_t)a) << 16;
    uint64_t d = b < 0 ? (uint64_t)0 - (uint64_t)(int64_t)b : (uint64_t)b;
    int64_t q = (int64_t)((n + d / 2) / d); /* < 2^48: rounds halves up in magnitude */
    return cub_fxi_sat32((a < 0) != (b < 0) ? -q : q);
}

cub_q16 cub_fx_add(cub_q16 a, cub_q16 b)
{
    return cub_fxi_sat32((int64_t)a + b);
}

cub_q16 cub_fx_sub(cub_q16 a, cub_q16 b)
{
    return cub_fxi_sat32((int64_t)a - b);
}

cub_q16 cub_fx_abs(cub_q16 a)
{
    return a == CUB_Q16_MIN ? CUB_Q16_MAX : (a < 0 ? -a : a);
}

cub_q16 cub_fx_lerp(cub_q16 a, cub_q16 b, cub_q16 t)
{
    t = cub_fx_clamp(t, 0, CUB_Q16_ONE);
    /* With t in [0, 1] the result lies between a and b: no saturation, and
     * t = 0 / t = 1 give a / b exactly. */
    return (cub_q16)(a + cub_fxi_round_shift(((int64_t)b - a) * t, 16));
}

cub_q16 cub_fx_clamp(cub_q16 x, cub_q16 lo, cub_q16 hi)
{
    if (x < lo) return lo;
    if (x > hi) return hi;
    return x;
}

uint32_t cub_fx_isqrt64(uint64_t x)
{
    /* Digit by digit, two bits of x per step: exact, no division. */
    uint64_t rem = x, root = 0, bit = (uint64_t)1 << 62;
    while (bit > rem)
        bit >>= 2;
    while (bit != 0) {
        if (rem >= root + bit) {
            rem -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    return (uint32_t)root;
}

uint32_t cub_fxi_sqrt64_round(uint64_t x)
{
    uint64_t r = cub_fx_isqrt64(x);
    /* x >= (r + 1/2)^2 = r^2 + r + 1/4 exactly when x - r^2 > r (integers). */
    if (x - r * r > r) r++;
    return (uint32_t)(r > UINT32_MAX ? UINT32_MAX : r);
}

cub_q16 cub_fx_sqrt(cub_q16 x)
{
    if (x <= 0) return 0;
    /* sqrt(x / 2^16) * 2^16 = sqrt(x * 2^16); below 2^24, so no saturation. */
    return (cub_q16)cub_fxi_sqrt64_round((uint64_t)x << 16);
}

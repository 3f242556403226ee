/* fx internals shared by the fx_*.c files; not part of the public API.
 *
 * Conventions: "Q.n" is an int64 with n fraction bits; "Q2.30" an int32 with
 * 30. Right shifts of negative values are arithmetic (checked below), which
 * every compiler we target (GCC, Clang) documents; everything else is plain
 * integer arithmetic, so results are bit-identical on every CPU. */
#ifndef CUB_FX_INTERNAL_H
#define CUB_FX_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "cub/fx.h"

_Static_assert((-1 >> 1) == -1, "fx needs arithmetic right shifts");
_Static_assert(((int64_t)-5 >> 1) == -3, "fx needs arithmetic right shifts");

#define CUB_FXI_TABLE_N 512 /* segments in each table (power of two) */
#define CUB_FXI_TABLE_BITS 9

/* pi and friends at high precision (rounded from 60-digit decimals). */
#define CUB_FXI_PI_Q30 ((int64_t)3373259426)
#define CUB_FXI_HALF_PI_Q30 ((int64_t)1686629713)
#define CUB_FXI_PI_Q48 ((int64_t)884279719003555)
#define CUB_FXI_TWO_PI_Q48 ((int64_t)1768559438007110)
#define CUB_FXI_HALF_PI_Q48 ((int64_t)442139859501778)

extern const int32_t cub_fxi_sin_table[CUB_FXI_TABLE_N + 1];
extern const int32_t cub_fxi_atan_table[CUB_FXI_TABLE_N + 1];

/* v clamped to the int32 range. */
int32_t cub_fxi_sat32(int64_t v);
/* v / 2^s rounded to nearest, halves away from zero; |v| <= 2^62, 1<=s<=62. */
int64_t cub_fxi_round_shift(int64_t v, int s);
/* Exact sum of sign[i] * p[i] (sign in {-2..2}) divided by 2^s and rounded
 * (halves up), without overflow for any int32*int32 products p[i]; n <= 8. */
int64_t cub_fxi_sum_shift(const int64_t *p, const int8_t *sign, int n, int s);
/* Rounded square root of a 64-bit value. */
uint32_t cub_fxi_sqrt64_round(uint64_t x);

/* sin and cos of an angle in Q.48 radians (any value), in Q2.30. */
void cub_fxi_sincos_q48(int64_t angle_q48, int32_t *sin_q30, int32_t *cos_q30);
/* atan2(y, x) in Q.30 radians, [-pi, pi]; any int64 inputs; (0, 0) -> 0. */
int64_t cub_fxi_atan2_q30(int64_t y, int64_t x);

#endif

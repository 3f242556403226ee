/* The seed's 16-bit quantiser (algorithm 3.1) with its +1.0 edge fixed. */
#include "cub/codec.h"

#define CODE_ZERO 32768
#define CODE_MAX 65535
#define Q30_PER_CODE 15           /* a code step is 2^-15 = 2^15 Q2.30 steps */
#define Q16_MM_PER_M 65536000LL   /* one metre in Q16.16 millimetres */
#define Q16_MM_PER_CODE 2000      /* 65536000 / 32768: exact */

uint16_t cub_codec_quant_unit(int32_t x_q30)
{
    /* C division truncates toward zero, as the seed's static_cast does. */
    int32_t n = x_q30 / (1 << Q30_PER_CODE) + CODE_ZERO;
    /* The seed masks with 0xFFFF, which sends +1.0 (65536) to -1.0's code
     * 0; clamping keeps it at the top code instead (SEEDS.md § 002 [fix]). */
    if (n > CODE_MAX) n = CODE_MAX;
    if (n < 0) n = 0;
    return (uint16_t)n;
}

int32_t cub_codec_dequant_unit(uint16_t code)
{
    return ((int32_t)code - CODE_ZERO) * (1 << Q30_PER_CODE);
}

void cub_codec_quant_split(cub_q16 mm, int8_t *int_m, uint16_t *frac_code)
{
    /* int32 Q16.16 mm is within ±32.8 m, so the whole metres fit a byte. */
    int64_t whole = (int64_t)mm / Q16_MM_PER_M;
    int64_t rest = (int64_t)mm - whole * Q16_MM_PER_M; /* |rest| < 1 m */
    *int_m = (int8_t)whole;
    *frac_code = (uint16_t)(rest * 32768 / Q16_MM_PER_M + CODE_ZERO);
}

cub_q16 cub_codec_dequant_split(int8_t int_m, uint16_t frac_code)
{
    int64_t v = (int64_t)int_m * Q16_MM_PER_M + ((int64_t)frac_code - CODE_ZERO) * Q16_MM_PER_CODE;
    if (v > INT32_MAX) return INT32_MAX;
    if (v < INT32_MIN) return INT32_MIN;
    return (cub_q16)v;
}

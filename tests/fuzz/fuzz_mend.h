/* For the codec fuzz targets: make a stream's length field (bytes 20..23)
 * and its closing CRC-32 match its bytes, so that the fuzzer gets past
 * them into what follows. Needs codec_internal.h (codec_crc32). */
#ifndef CUB_FUZZ_MEND_H
#define CUB_FUZZ_MEND_H

#include <stddef.h>
#include <stdint.h>

static inline void fuzz_put_u32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        p[i] = (uint8_t)(v >> (8 * i));
}

static inline void fuzz_mend_stream(uint8_t *s, size_t n)
{
    if (n < 28) return;
    fuzz_put_u32(s + 20, (uint32_t)n);
    fuzz_put_u32(s + n - 4, codec_crc32(s, n - 4));
}

#endif

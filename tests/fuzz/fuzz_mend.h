/* For the codec fuzz targets: the stream is the input past its first byte,
 * copied to a buffer of exactly its size (so ASan sees any read past it);
 * bit 0 of the first byte makes the stream's length field (bytes 20..23)
 * and its closing CRC-32 match its bytes, so that the fuzzer gets past
 * them into what follows. Needs codec_internal.h (codec_crc32). */
#ifndef CUB_FUZZ_MEND_H
#define CUB_FUZZ_MEND_H

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

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

/* The stream of an input (free it), or NULL for an empty input. */
static inline uint8_t *fuzz_stream(const uint8_t *data, size_t size, size_t *n)
{
    if (size < 1) return NULL;
    *n = size - 1;
    uint8_t *s = malloc(*n ? *n : 1);
    if (!s) return NULL;
    memcpy(s, data + 1, *n);
    if (data[0] & 1) fuzz_mend_stream(s, *n);
    return s;
}

#endif

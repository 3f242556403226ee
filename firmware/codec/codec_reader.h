/* A little-endian byte cursor and the refusal helper, shared by the two
 * stream readers (cubseed, cubkeys); not public. Reads past the end give 0:
 * the callers check positions against the length before trusting a value. */
#ifndef CUB_CODEC_READER_H
#define CUB_CODEC_READER_H

#include <stddef.h>
#include <stdint.h>

#include "cub/codec.h"

typedef struct reader {
    const uint8_t *p;
    size_t len, pos;
} reader;

static inline uint8_t rd_u8(reader *r)
{
    return r->pos < r->len ? r->p[r->pos++] : 0;
}

static inline uint16_t rd_u16(reader *r)
{
    uint16_t lo = rd_u8(r);
    return (uint16_t)(lo | (uint16_t)rd_u8(r) << 8);
}

static inline uint32_t rd_u32(reader *r)
{
    uint32_t lo = rd_u16(r);
    return lo | (uint32_t)rd_u16(r) << 16;
}

static inline cub_err refuse(cub_codec_problem *why, const char *what, size_t offset)
{
    if (why) {
        why->what = what;
        why->offset = offset;
    }
    return CUB_ERR_FORMAT;
}

/* The stream's length field against its bytes, then its CRC. */
cub_err codec_check_crc(reader *r, uint32_t length, cub_codec_problem *why);
/* One joint: name, parent, end site, offset (exact: 3 x i32 Q16.16 mm, the
 * cubkeys way; else split metres, the cubseed way, with the CRC still in
 * r->len). */
cub_err codec_read_joint(reader *r, cub_skeleton *skel, int j, int exact, cub_codec_problem *why);

#endif

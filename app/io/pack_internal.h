/* pack internals shared by the writer (pack.c) and the reader
 * (pack_read.c): the record sizes of the format in cub/pack.h, little-endian
 * byte access, CRC-32 and the Q1.14 quaternion conversions. Not public. */
#ifndef CUB_PACK_INTERNAL_H
#define CUB_PACK_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "cub/codec.h"
#include "cub/codec_enc.h"
#include "cub/pack.h"

#define PACK_MAGIC "CUBCLIPS"
#define PACK_VERSION_RAW 1u  /* frames as Q1.14 quaternions */
#define PACK_VERSION_KEYS 2u /* frames as cubkeys streams (cub/codec.h) */
#define PACK_HEADER_BYTES 20u      /* magic, version, joint_count, clip_count */
#define PACK_JOINT_BYTES 48u       /* name[32], parent, end_site, 0, offset */
#define PACK_CLIP_HEADER_BYTES 56u /* name[32], kind[16], frame_ns, frame_count */
#define PACK_KEYS_LEN_BYTES 4u     /* version 2: the clip's stream length follows */
#define PACK_KEYS_BOUND_MM 0.1     /* version 2: the encoder's bound, 0.01 cm */
#define PACK_CRC_BYTES 4u

static inline uint32_t pack_get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

/* Two's complement by arithmetic, not by an implementation-defined cast. */
static inline int32_t pack_get_i32(const uint8_t *p)
{
    uint32_t u = pack_get_u32(p);
    return u <= INT32_MAX ? (int32_t)u : (int32_t)(u - 0x80000000u) - INT32_MAX - 1;
}

static inline int16_t pack_get_i16(const uint8_t *p)
{
    int u = p[0] | (p[1] << 8);
    return (int16_t)(u <= INT16_MAX ? u : u - 65536);
}

/* CRC-32 (IEEE 802.3: reflected, polynomial 0xEDB88320, init and final
 * xor 0xFFFFFFFF); "123456789" gives 0xCBF43926. */
uint32_t pack_crc32(const void *data, size_t len);

/* Q1.14 (w >= 0) to a renormalised Q2.30 quaternion, as reading does. */
cub_quat pack_q14_to_quat(const int16_t c[4]);
/* Q2.30 to Q1.14 with w >= 0, chosen so that reading it back and writing
 * again gives the same four numbers. */
void pack_quat_to_q14(cub_quat q, int16_t out[4]);
/* Norm squared within 2% of one. */
int pack_q14_roughly_unit(const int16_t c[4]);

/* A name field: printable, NUL-terminated within cap, zero-padded. */
int pack_name_field_ok(const uint8_t *field, size_t cap);

/* The library as pack bytes of a version (heap, free with free()). */
cub_err pack_encode(const cub_library *lib, const char *file, uint32_t version, uint8_t **out,
                    size_t *out_len, cub_diag *diag);

/* Version 2: every clip of lib as a cubkeys stream within PACK_KEYS_BOUND_MM
 * (streams[i].data on the heap, free with pack_keys_free). */
cub_err pack_keys_encode_all(const cub_library *lib, const char *file, cub_keys_result *streams,
                             cub_diag *diag);
void pack_keys_free(cub_keys_result *streams, int count);
/* Version 2: the stream at data[at .. at + len) checked against the pack's
 * skeleton and clip header (frames, frame_ns), opened into *k. A
 * message for the reader in *why on refusal (its offset within the stream). */
cub_err pack_keys_check(const uint8_t *data, size_t len, const cub_skeleton *skel, int frames,
                        uint32_t frame_ns, cub_keys *k, cub_codec_problem *why);

#endif

/* codec — the folk-dance seed's clip codec (SEEDS.md § 002), as a stream
 * ("cubseed") the box decodes in fixed point.
 *
 * Rotations in time: the first and last 6 frames and every frame whose index
 * is a multiple of 4 are kept; the decoder restores the frames at multiples
 * of 2 by Squad from the kept ones, then the odd frames from those. Every
 * kept number is quantised to 16 bits (n = trunc(x * 32768) + 32768; numbers
 * past ±1, in metres, as a signed integer byte plus the fraction's code).
 * Positions (root, animated joint offsets) are keyframes on the same frames,
 * restored by the uniform cubic (Catmull-Rom) spline. End effectors (feet,
 * hands) of the restored frames are then pulled by CCD (parent and
 * grandparent, root to tip) towards targets spline-interpolated from the
 * kept frames' effectors, where the encoder found that this helps.
 * docs/codec.md describes the byte layout and the figures.
 *
 * Units: as cub/motion.h (Q16.16 mm, Q2.30 quaternions); in the stream,
 * metres and unit quaternion components. Integer only, no heap: decoding is
 * bit-identical on every CPU.
 *
 * Accuracy (tests/unit/test_codec.c, cubtool codec-figures): a quantised
 * quaternion component is within 2^-15 of the true one; kept frames decode
 * within 0.01 degree and 0.031 mm per coordinate of the source.
 */
#ifndef CUB_CODEC_H
#define CUB_CODEC_H

#include <stddef.h>
#include <stdint.h>

#include "cub/err.h"
#include "cub/fx.h"
#include "cub/motion.h"

#define CUB_CODEC_VERSION 1
#define CUB_CODEC_MAX_EFFECTORS 8
#define CUB_CODEC_KEEP_EDGE 6  /* frames kept at each end */
#define CUB_CODEC_KEEP_EVERY 4 /* and every 4th frame */
#define CUB_CODEC_IK_ITERATIONS 32 /* sweeps; a 0.4 rad hip error closes to 0.3 mm */

/* ---- the 16-bit quantiser ---------------------------------------------- */

/* A unit-range number x = x_q30 / 2^30 to its code, trunc(x * 32768) +
 * 32768, clamped to [0, 65535]: +1.0 gives 65535, not the 0 of -1.0. */
uint16_t cub_codec_quant_unit(int32_t x_q30);
/* A code back to Q2.30: (code - 32768) / 32768. */
int32_t cub_codec_dequant_unit(uint16_t code);
/* A length (Q16.16 mm, so within ±33 m) as metres split into an integer
 * part (trunc, in *int_m) and its fraction's code. */
void cub_codec_quant_split(cub_q16 mm, int8_t *int_m, uint16_t *frac_code);
/* The split form back to Q16.16 mm (saturated). */
cub_q16 cub_codec_dequant_split(int8_t int_m, uint16_t frac_code);

/* ---- restoring a frame between neighbours (h = 1/2) --------------------- */

typedef enum cub_codec_method {
    CUB_CODEC_SQUAD = 0, /* the seed's: Squad with its control points */
    CUB_CODEC_SLERP,     /* slerp(q1, q2, 1/2), for the figures */
    CUB_CODEC_CATMULL,   /* component Catmull-Rom, normalised, for the figures */
    CUB_CODEC_METHOD_COUNT_
} cub_codec_method;

/* Squad control point s_i = q_i exp(-(log(q_i^-1 q_next) + log(q_i^-1 q_prev)) / 4). */
cub_quat cub_codec_squad_control(cub_quat prev, cub_quat q, cub_quat next);
/* The rotation half way from q1 to q2 by a method, with neighbours q0, q3 (q[0..3]). */
cub_quat cub_codec_rot_mid(const cub_quat q[4], cub_codec_method method);
/* The cubic spline's midpoint of p1..p2 with neighbours p0, p3 (p[0..3]). */
cub_vec3 cub_codec_pos_mid(const cub_vec3 p[4]);

/* ---- the CCD step ------------------------------------------------------ */

/* Pull joint `effector` of pose towards target_mm by CCD on its parent and
 * grandparent, root to tip, up to CUB_CODEC_IK_ITERATIONS sweeps. Joints
 * outside the grandparent's subtree do not move. */
cub_err cub_codec_ccd(const cub_skeleton *skel, cub_pose *pose, int effector, cub_vec3 target_mm);

/* ---- the stream -------------------------------------------------------- */

/* Whether frame f of n is kept. */
int cub_codec_is_kept(int f, int n);
/* Up to max joints whose names end in "foot", "ankle" or "hand" (any case), are
 * not end sites and have a grandparent other than the root, in skeleton
 * order; returns how many. */
int cub_codec_pick_effectors(const cub_skeleton *skel, int *out, int max);

typedef enum cub_codec_ik {
    CUB_CODEC_IK_STREAM = 0, /* where the encoder's flags say (the box's way) */
    CUB_CODEC_IK_OFF,
    CUB_CODEC_IK_ALL,
} cub_codec_ik;

typedef struct cub_codec_opts {
    cub_codec_method method;
    cub_codec_ik ik;
} cub_codec_opts;

/* What a stream holds, from its header. */
typedef struct cub_codec_info {
    int joint_count, frame_count, effector_count, has_trans;
    uint32_t frame_ns;
    size_t mem_size; /* bytes cub_codec_decode needs in mem */
} cub_codec_info;

/* Why a stream was refused: a fixed message and the byte it is about. */
typedef struct cub_codec_problem {
    const char *what;
    size_t offset;
} cub_codec_problem;

/* Read and check the header (and the CRC of the whole stream). */
cub_err cub_codec_peek(const void *data, size_t len, cub_codec_info *info,
                       cub_codec_problem *why);

/* Where a decoded clip goes: skel is filled, clip laid out in mem. */
typedef struct cub_codec_out {
    cub_skeleton *skel;
    cub_clip *clip;
    void *mem;
    size_t mem_size;
} cub_codec_out;

/* Decode a stream (opts NULL: Squad, IK where flagged). CUB_ERR_FORMAT with
 * *why for anything malformed, CUB_ERR_NOMEM if mem is short. */
cub_err cub_codec_decode(const void *data, size_t len, const cub_codec_opts *opts,
                         const cub_codec_out *out, cub_codec_problem *why);

/* What to encode: a clip, its effectors (from cub_codec_pick_effectors) and
 * scratch for the encoder's own trial decodes (cub_codec_encode_work_size). */
typedef struct cub_codec_enc {
    const cub_clip *clip;
    const int *effectors;
    int effector_count;
    void *work;
    size_t work_size;
} cub_codec_enc;

/* Bytes of stream an encoding of this clip takes at most. */
size_t cub_codec_encoded_max(const cub_clip *clip, int effector_count);
/* Bytes of work the encoder needs for this clip. */
size_t cub_codec_encode_work_size(const cub_clip *clip, int effector_count);
/* Encode into buf; *out_len the stream's length. CUB_ERR_NOMEM for a short
 * buf or work, CUB_ERR_ARG for a bad clip or effector. */
cub_err cub_codec_encode(const cub_codec_enc *in, void *buf, size_t cap, size_t *out_len);

/* ---- the error-bounded stream ("cubkeys", issue 21 § 2) ------------------
 *
 * Every joint's local rotation (x y z of the quaternion put on w >= 0; w is
 * restored as sqrt(1 - x^2 - y^2 - z^2)), the root's position and, for
 * clips that animate them, the joints' translations are tracks. A track is
 * either its default (identity, or the skeleton's offset), a constant, or
 * keys: the frames the encoder kept (the first, the last, and never more
 * than CUB_KEYS_MAX_GAP apart), each a code above its segment's minimum
 * (a segment is CUB_KEYS_SEGMENT frames: range reduction) at that segment's
 * bit width per component, in steps of 2^shift (a shift per component);
 * between keys the value is linear in the frame number. The encoder
 * (cub/codec_enc.h)
 * drops keys and bits until the error at virtual vertices 3 cm from every
 * bone, in object space, would pass its bound. One pose is decoded at a
 * time, from any frame (random access): a bit set of key frames per track
 * and each segment's code offset find the two keys around it.
 * docs/codec.md describes the byte layout. Integer only, no heap:
 * bit-identical on every CPU (test_codec_keys). */

#define CUB_KEYS_VERSION 1
#define CUB_KEYS_MAX_GAP 64 /* frames between two keys of a track, at most */
#define CUB_KEYS_SEGMENT 32 /* frames of a segment (part of the format; 16, 32 or 64 build) */
#define CUB_KEYS_MAX_TRACKS (2 * CUB_MOTION_MAX_JOINTS)

typedef enum cub_keys_kind {
    CUB_KEYS_DEFAULT = 0, /* identity rotation, or the skeleton's offset */
    CUB_KEYS_CONSTANT,    /* one value, 3 x i32 */
    CUB_KEYS_ANIMATED,    /* keys */
    CUB_KEYS_KIND_COUNT_
} cub_keys_kind;

/* One track of an opened stream: where its parts start in the stream. The
 * keys of each segment are coded above the segment's own minimum
 * (range reduction), at the segment's own bit widths. */
typedef struct cub_keys_track {
    uint8_t kind, shift[3], rotation;  /* steps 2^shift; rotation: keys clamped to +-1 (Q2.30) */
    uint8_t range_bits[3], seg_bits;   /* widths of a segment's minimum; its header's */
    int32_t base[3];                   /* the constant, or the codes' zero */
    uint32_t keyset, segoff, segs, codes, code_bytes; /* byte offsets (animated only) */
} cub_keys_track;

/* An opened, fully checked stream; it points into the caller's bytes,
 * which must outlive it. */
typedef struct cub_keys {
    const uint8_t *data;
    size_t len;
    int joint_count, frame_count, has_trans;
    uint32_t frame_ns;
    int16_t rot_track[CUB_MOTION_MAX_JOINTS];   /* -1 for end sites */
    int16_t trans_track[CUB_MOTION_MAX_JOINTS]; /* the root's: its position; -1: none */
    cub_vec3 offsets[CUB_MOTION_MAX_JOINTS];    /* the skeleton's, for default tracks */
    int track_count;
    cub_keys_track tracks[CUB_KEYS_MAX_TRACKS];
} cub_keys;

/* The value at frame f between keys a < b of values va, vb: va + (vb - va)
 * * floor((f - a) * 2^16 / (b - a)) / 2^16 (the decoder's own arithmetic,
 * for the encoder to measure with). */
int32_t cub_keys_lerp(int32_t va, int32_t vb, int a, int b, int f);
/* A key's value: base + code * 2^shift, a rotation's clamped to +-1. */
int32_t cub_keys_key(int32_t base, uint64_t code, int shift, int rotation);
/* A rotation from its x y z (Q2.30) on w >= 0. */
cub_quat cub_keys_quat(int32_t x, int32_t y, int32_t z);
/* Check a whole stream (header, skeleton, every track, CRC) and open it;
 * fills skel. CUB_ERR_FORMAT with *why for anything malformed. */
cub_err cub_keys_open(const void *data, size_t len, cub_skeleton *skel, cub_keys *out,
                      cub_codec_problem *why);
/* Decode frame f (0 .. frame_count - 1) of an opened stream into out. */
cub_err cub_keys_pose(const cub_keys *k, int frame, cub_pose *out);

#endif

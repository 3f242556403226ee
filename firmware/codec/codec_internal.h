/* codec internals shared by the encoder and the decoder; not public.
 *
 * Stream layout (little-endian; docs/codec.md):
 *   header   "CUBSEED" u8 version, u16 joint_count, u8 effector_count,
 *            u8 flags (bit 0: joint translations), u32 frame_count,
 *            u32 frame_ns, u32 stream length (all of it, CRC included)
 *   joints   u8 name length, name, u8 parent + 1 (0: the root), u8 end site,
 *            offset x y z as split metres (i8 + u16 each)
 *   effectors  u8 joint index each
 *   kept frames, ascending: root x y z split, per joint but end sites a
 *            quaternion w x y z (u16 codes), [then per such joint a
 *            translation, split]
 *   IK flags  one bit per 4-frame block and effector (bit block * E + e)
 *   u32 CRC-32 (IEEE) of everything before it */
#ifndef CUB_CODEC_INTERNAL_H
#define CUB_CODEC_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "cub/codec.h"

#define CODEC_MAGIC "CUBSEED"
#define CODEC_MAGIC_LEN 7
#define CODEC_HEADER_BYTES 24
#define CODEC_CRC_BYTES 4
#define CODEC_SPLIT_BYTES 3 /* i8 whole metres + u16 fraction code */
#define CODEC_QUAT_BYTES 8
#define CODEC_FLAG_TRANS 1u
#define CODEC_MAX_FRAMES (1 << 20) /* 2.4 hours at 120 fps */
#define CODEC_MAX_JOINT_FRAMES (1 << 24) /* a decoded clip within 256 MB */

uint32_t codec_crc32(const uint8_t *p, size_t len);
int codec_kept_count(int n);
int codec_block_count(int n);
size_t codec_flag_bytes(int n, int effector_count);
/* Bytes of one kept frame: end sites (no channels in a BVH, identity
 * always) store nothing, so they count out of animated. */
size_t codec_frame_bytes(int animated, int has_trans);
/* Joints that are not end sites. */
int codec_animated(const cub_skeleton *skel);
/* Bytes the decoder needs: the clip's frames plus the IK targets. */
size_t codec_mem_size(int joint_count, int frame_count, int has_trans, int effector_count);

/* Restore every dropped frame of a clip whose kept frames are filled. */
void codec_restore(cub_clip *clip, cub_codec_method method);
/* Pull the effectors of the restored frames onto spline targets from the
 * kept frames; flags NULL means every block. targets: n * E scratch. */
cub_err codec_correct(cub_clip *clip, const int *effectors, int effector_count,
                      const uint8_t *flags, cub_vec3 *targets);

#endif

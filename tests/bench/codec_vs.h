/* codec_vs — one codec as bench_codec_vs drives it: compress a clip, then
 * give back any one decoded pose (local transforms, in doubles) and time
 * decoding every pose. The C side (the seed's codec, ours) and the C++ side
 * (ACL, codec_vs_acl.cpp, built only when ../shared/peers/acl exists) meet
 * here. */
#ifndef CUB_BENCH_CODEC_VS_H
#define CUB_BENCH_CODEC_VS_H

#include <stddef.h>

#include "cub/motion.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A decoded pose: per joint its local rotation (w x y z) and translation
 * (mm: the root's position for the root, the offset or animated
 * translation for the others). End sites are left as the source has them. */
typedef struct vs_pose {
    double rot[CUB_MOTION_MAX_JOINTS][4];
    double pos[CUB_MOTION_MAX_JOINTS][3];
} vs_pose;

typedef struct vs_codec {
    const char *name;
    /* Compress clip; *bytes its compressed size. 0 ok. */
    int (*encode)(void *self, const cub_clip *clip, size_t *bytes);
    /* Decoded frame f of the last encoded clip. 0 ok. */
    int (*pose)(void *self, int frame, vs_pose *out);
    /* Seconds to decode every pose once, one at a time (<0 on failure). */
    double (*time_all)(void *self);
    void (*release)(void *self);
    void *self;
} vs_codec;

/* ACL at its "medium" level, error threshold 0.01 cm, 3 cm shell; returns 0
 * and fills *out, or -1 when built without ACL. */
int vs_acl_codec(vs_codec *out);

#ifdef __cplusplus
}
#endif

#endif

/* pack — the clip library the box ships, in a packed binary format of ours
 * (assets/clips/<name>.cubclips): one skeleton and named clips on it.
 *
 * Format (little-endian, versioned, byte-for-byte reproducible: the same
 * library always packs to the same bytes):
 *   "CUBCLIPS" u32 version, u32 joint_count, u32 clip_count
 *   joints:   name[32], i16 parent, u8 end_site, u8 0, offset x y z (i32 Q16.16 mm)
 *   clips:    name[32], kind[16], u32 frame_ns, u32 frame_count, then
 *     version 1: per frame: root x y z (i32 Q16.16 mm),
 *                per joint a unit quaternion as 4 x i16 Q1.14 (w >= 0)
 *     version 2: u32 length, a cubkeys stream (cub/codec.h) of that many
 *                bytes, within 0.01 cm at virtual vertices 3 cm from every
 *                bone; its skeleton, frames and period are the pack's
 *   u32 CRC-32 of everything before it
 * Reading checks every count, name, index and the CRC, and says what is
 * wrong; both versions read, and clips are decoded whole at load (the box
 * keeps plain frames: docs/codec.md, "the pack"). */
#ifndef CUB_PACK_H
#define CUB_PACK_H

#include "cub/err.h"
#include "cub/io.h"
#include "cub/motion.h"

#define CUB_PACK_KIND_LEN 16
#define CUB_PACK_VERSION 2 /* what cub_pack_write writes */

typedef struct cub_library_clip {
    char name[CUB_MOTION_NAME_LEN];
    char kind[CUB_PACK_KIND_LEN]; /* "dance" (a kid move) or "coach" */
    cub_clip clip;                /* clip.skel points at the library's skel */
} cub_library_clip;

typedef struct cub_library {
    cub_skeleton skel;
    int clip_count;
    cub_library_clip *clips; /* heap, owned */
    void *mem;               /* frame data, owned */
} cub_library;

/* Index of the clip with this name, or -1. */
int cub_library_find(const cub_library *lib, const char *name);
cub_err cub_pack_write(const char *path, const cub_library *lib, cub_diag *diag);
/* Write a given version (1 or 2): version 1 for tests and older readers. */
cub_err cub_pack_write_version(const char *path, const cub_library *lib, int version,
                               cub_diag *diag);
cub_err cub_pack_read(const char *path, cub_library *out, cub_diag *diag);
cub_err cub_pack_parse(const void *data, size_t len, const char *name, cub_library *out,
                       cub_diag *diag);
void cub_library_free(cub_library *lib);
/* The q-quantile (0..1, nearest rank) of every joint's speed between
 * consecutive frames of every clip, in mm/s at each clip's own rate: the
 * bound a made motion is held to (groove-eval's p99, cubdance's
 * --bridge-speed). -1 when out of memory; 0 for a library without motion. */
double cub_library_joint_speed_pct(const cub_library *lib, double q);

#endif

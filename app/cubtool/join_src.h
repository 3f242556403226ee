/* join_src — the clips `cubtool join` and `cubtool graph` work on: clip
 * libraries (.cubclips) and BVH files, all on one skeleton, in one motion
 * database (cub/join.h). Errors name the file. */
#ifndef CUB_CUBTOOL_JOIN_SRC_H
#define CUB_CUBTOOL_JOIN_SRC_H

#include "cub/io.h"
#include "cub/join.h"
#include "cub/pack.h"

#define JOIN_SRC_MAX 64

typedef struct join_src {
    int nlib, nbvh;
    cub_library lib[JOIN_SRC_MAX];
    cub_io_motion *bvh[JOIN_SRC_MAX];
    const char *kind[1024]; /* per db clip: the library kind ("dance", "coach") or "bvh" */
    cub_join_db db;
} join_src;

/* Add every clip of a .cubclips or the one of a .bvh; the first file sets
 * the skeleton. 0 ok, -1 with the reason on stderr. */
int join_src_add(join_src *s, const char *path, const cub_join_cfg *cfg);
/* A clip by name, or by path (a .bvh not yet added is added): its db
 * index, or -1 with the reason on stderr. */
int join_src_find(join_src *s, const char *name_or_path, const cub_join_cfg *cfg);
void join_src_free(join_src *s);

#endif

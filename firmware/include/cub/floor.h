/* floor — the ground the coach stands and walks on (issue 24, the box's
 * part of seed 003): a heightfield of gently rolling ground and the things
 * lying on it (a log, stones). The app reads it from an asset (app/io
 * floor_file.c, assets/floor/forest.floor); the renderer draws it and the
 * gait planner walks on it, both through cub_floor_terrain, so the heights
 * drawn are the heights planned on.
 *
 * World frame as in cub/motion.h: millimetres, y up, the coach's dancing
 * spot at x = z = 0, the camera on +z. Fixed point, no allocation. */
#ifndef CUB_FLOOR_H
#define CUB_FLOOR_H

#include <stdint.h>

#include "cub/err.h"
#include "cub/fx.h"
#include "cub/gait.h"

#define CUB_FLOOR_MAX_SIDE 48       /* samples along x or z */
#define CUB_FLOOR_MAX_THINGS 12     /* leaves the gait planner room for its own obstacles */
#define CUB_FLOOR_MIN_CELL_MM 100
#define CUB_FLOOR_MAX_CELL_MM 5000
#define CUB_FLOOR_MAX_RISE_MM 2000  /* |height| of a sample */
#define CUB_FLOOR_EXTENT_MM 30000   /* |x|, |z| of everything (Q16.16 mm holds 32767) */
#define CUB_FLOOR_MIN_SIZE_MM 10    /* a thing's half side or height */
#define CUB_FLOOR_MAX_SIZE_MM 5000

typedef enum cub_floor_kind {
    CUB_FLOOR_LOG = 0, /* a round log lying along x or z */
    CUB_FLOOR_STONE    /* a rock resting on the ground */
} cub_floor_kind;

/* A thing on the ground, resting on the lowest ground under its footprint. */
typedef struct cub_floor_thing {
    cub_floor_kind kind;
    int32_t x_mm, z_mm;           /* the middle of its footprint */
    int32_t half_x_mm, half_z_mm; /* its footprint's half sides; a log lies along the longer,
                                     its radius is the shorter */
    int32_t height_mm;            /* its top over where it rests (a log: 2 radii) */
} cub_floor_thing;

typedef struct cub_floor {
    int nx, nz;                   /* 2..CUB_FLOOR_MAX_SIDE samples */
    int32_t cell_mm;              /* between samples */
    int32_t origin_x_mm, origin_z_mm; /* where sample (0, 0) is */
    /* nx * nz heights, row major (x fastest), Q16.16 mm; outside the grid
     * the nearest edge sample holds (cub_gait_ground_height). */
    cub_q16 heights_mm[CUB_FLOOR_MAX_SIDE * CUB_FLOOR_MAX_SIDE];
    cub_floor_thing things[CUB_FLOOR_MAX_THINGS];
    int thing_count;
} cub_floor;

/* CUB_ERR_ARG when f breaks a limit above (the grid past the extent, a
 * sample too high, a thing too small or too large or off the extent). */
cub_err cub_floor_check(const cub_floor *f);
/* The terrain the gait planner and the renderer read: the heightfield
 * (pointing into f, which must outlive t) and box obstacle k per thing k,
 * from the lowest ground under its footprint to its top. CUB_ERR_ARG as cub_floor_check. */
cub_err cub_floor_terrain(const cub_floor *f, cub_gait_terrain *t);

#endif

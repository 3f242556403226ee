/* gait_tool — what cubtool gait and gait-eval share: a captured walk
 * loaded and analysed for the walker (cub/gait.h), the named terrains and
 * obstacles, and one run of the walker (or of the game-engine baseline)
 * with the figures measured on it. */
#ifndef CUB_CUBTOOL_GAIT_TOOL_H
#define CUB_CUBTOOL_GAIT_TOOL_H

#include "cub/floor.h"
#include "cub/gait.h"
#include "cub/io.h"
#include "cub/walk_clip.h"

/* A walk, loaded and analysed. */
typedef struct gait_src {
    cub_io_motion m;
    cub_walk_clip walk; /* its analysis for the walker */
    char name[64];
} gait_src;

/* clip: a file path, or a CMU name looked up under data_dir/mocap/cmu (and
 * its daz43 folder). 0, or 1 with "cubtool <who>: <file>: <why>" said. */
int gait_src_load(gait_src *s, const char *clip, const char *data_dir, const char *who);
void gait_src_free(gait_src *s);

#define GAIT_GRID 96
#define GAIT_MAX_STONES 6

/* A terrain and its heightfield's storage. */
typedef struct gait_ground {
    cub_gait_terrain t;
    cub_q16 heights[GAIT_GRID * GAIT_GRID];
    cub_floor floor; /* a terrain file's floor (the terrain points into it) */
    char name[48];
} gait_ground;

/* name: flat, slope (5 degrees up), rolling, steps (10 cm every 1.2 m),
 * or a floor file (the box's format, cub/floor_file.h: a heightfield with
 * logs and stones; cub_floor_terrain makes the terrain). The walk goes
 * along +z from the origin. 0; 2 for an unknown name, 1 for a bad file,
 * the reason said. */
int gait_ground_make(gait_ground *g, const char *name, const char *who);

/* obstacle: log (15 cm across the path at z = 1.5 m), stone (the n-th at
 * z = 3 m, 4.2 m, ... alternately under the two feet' lines). */
int gait_ground_add(gait_ground *g, const char *obstacle, const char *who);

/* The figures of one run (docs/gait.md says how each is measured). */
typedef struct gait_figures {
    int frames, steps, planned, backtracks, blocked;
    double pen_max_mm;      /* deepest sole point below the terrain, any frame */
    double slide_max_mm;    /* the stance ankle's largest slide in one step */
    double slide_mean_mm;   /* ... mean over steps */
    double clear_min_mm;    /* lowest sole point over an obstacle while swinging */
    int clear_frames;       /* frames with a swinging sole over an obstacle */
    double rot_max_deg;     /* the foot's largest turn from one frame to the next */
    double speed_max_dps;   /* the fastest leg joint (hip, knee, ankle) */
    double speed_over_pct;  /* leg joint samples faster than the source's p99 */
    double err_all_mm;      /* flat: mean joint error vs the source (root-relative) */
    double err_leg_mm;      /* ... over the leg joints */
    double us_mean, us_max; /* the walker's (or baseline's) time per frame */
} gait_figures;

typedef enum gait_method { GAIT_WALKER = 0, GAIT_BASELINE, GAIT_SOURCE } gait_method;

/* Called per frame with the posed skeleton's world joints (may be NULL). */
typedef void (*gait_frame_fn)(void *ctx, const cub_gait_walker *w, const cub_vec3 *world, int i);

typedef struct gait_run {
    gait_method method;
    int frames;
    cub_gait_walk_params params; /* on_event may be set */
    gait_frame_fn on_frame;
    void *ctx;
    int repeat; /* > 1: each frame's time the least over this many runs of the walk */
} gait_run;

/* The source's leg joint speed, 99th percentile, deg/s. */
double gait_src_p99_dps(const gait_src *s);
/* Run and measure. GAIT_SOURCE measures the capture on its own floor
 * (slide, rotation, speed only). 0, or 1 with the reason said. */
int gait_measure(const gait_src *s, const gait_ground *g, const gait_run *r, gait_figures *out,
                 const char *who);

#endif

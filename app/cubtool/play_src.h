/* play_src — one input of `cubtool play`: a clip from a pack
 * (PACK.cubclips:NAME), a .bvh, or an ASF/AMC pair, loaded and put on the
 * figure that will show it: the bear when the clip is on the bear's own
 * skeleton or a mapping table retargets it there, else the stick figure. */
#ifndef CUB_CUBTOOL_PLAY_SRC_H
#define CUB_CUBTOOL_PLAY_SRC_H

#include "cub/character.h"
#include "cub/io.h"
#include "cub/pack.h"
#include "cub/trc.h"

typedef enum play_figure {
    PLAY_FIGURE_AUTO = 0, /* the bear when it can, else the stick figure */
    PLAY_FIGURE_BEAR,
    PLAY_FIGURE_STICK,
} play_figure;

typedef struct play_src {
    const char *path, *amc_path; /* as given; amc_path only for ASF */
    char name[64];               /* for messages: the clip or the file's base name */
    cub_library lib;             /* a pack's, owned */
    cub_io_motion motion;        /* a file's or the retargeted clip, owned */
    const cub_clip *clip;        /* the clip played (in lib or motion); NULL for markers */
    cub_trc trc;                 /* a .trc's markers (clip NULL), owned */
    int on_bear;                 /* 1: drawn as the bear */
    float height_mm;             /* the figure's rest height */
} play_src;

/* Load spec (a pack clip, a file, or a .trc of markers, which always
 * plays as numbered points; amc for an .asf) into src and pick its
 * figure. bear may be NULL (no character: always the stick figure);
 * map_path retargets a non-bear skeleton onto the bear. 0 on success; 1
 * with a message naming the file and the problem on stderr. */
int play_src_load(play_src *src, const char *spec, const char *amc, play_figure want,
                  const cub_character *bear, const char *map_path);
void play_src_free(play_src *src);
/* How long one play-through lasts, seconds. */
double play_src_seconds(const play_src *src);
/* Where each joint (or marker) is at t_s (looping, or held at the end
 * when once), world mm, 3 floats each; a lost marker's x is NaN. Returns
 * how many (0 on failure). */
int play_src_sample(const play_src *src, double t_s, int once, float *xyz);

/* Does this path name an input of its own kind (".bvh", ".asf", ".amc", a
 * pack clip)? Used to pair an .asf with the .amc after it. */
int play_src_is_amc(const char *path);

#endif

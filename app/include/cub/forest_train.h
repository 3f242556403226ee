/* forest_train — training and scoring the body-part forest (cub/forest.h)
 * on renders of cub/synth.h, host side (doubles and the heap are fine).
 *
 * A training frame is the player alone: depth in mm from the render's raw
 * Kinect values (noise, shadow and holes included), every pixel not the
 * player's set to 0, as the box's player mask will give it; and the body
 * part under every pixel. Clips are rendered turning (a new yaw every
 * 1.5 s from the seed) and moving about (+-0.7 m): the forest must name a
 * child's left arm with its back to the camera.
 *
 * Training (Shotton et al. 2011): every tree draws its own pixels, then
 * grows depth first; at every node it draws candidate probe pairs and
 * thresholds and keeps the split of the highest information gain (Shannon
 * entropy of the part counts), until the depth limit, too few pixels or
 * one part. Seeded: the same inputs and seed give the same bytes.
 * docs/forest.md: the commands, the folds and the figures. */
#ifndef CUB_FOREST_TRAIN_H
#define CUB_FOREST_TRAIN_H

#include <stddef.h>
#include <stdint.h>

#include "cub/err.h"
#include "cub/forest.h"
#include "cub/io.h"
#include "cub/synth.h"

typedef struct cub_ft_frame {
    uint16_t *mm;  /* 640x480, player only, 0 elsewhere */
    uint8_t *part; /* cub_synth_part per pixel */
} cub_ft_frame;

typedef struct cub_ft_set {
    cub_ft_frame *frames;
    int n, cap;
} cub_ft_set;

/* How clips become frames. */
typedef struct cub_ft_render {
    const char *data_dir;
    int frames; /* per clip */
    int step;   /* every step-th frame at 30 fps */
    uint64_t seed;
} cub_ft_render;

/* A clip "name" or "name@from_s": its frames appended to set. */
cub_err cub_ft_add_clip(cub_ft_set *set, const cub_ft_render *r, const char *spec,
                        cub_diag *diag);
void cub_ft_set_free(cub_ft_set *set);
/* 0 for motion we may not ship what derives from (Bandai, the dog). */
int cub_ft_shippable(const char *clip);

/* The leave-one-source-out folds of docs/tracker_eval.md that may train
 * (CMU and AnimatedDrawings), by name; NULL-terminated clip specs. */
const char *const *cub_ft_fold(const char *name);
const char *cub_ft_fold_name(int i); /* i-th shippable fold; NULL past the end */

typedef struct cub_ft_params {
    int trees, depth, features, thresholds;
    int pixels_per_frame, min_samples;
    int32_t max_offset; /* probe offsets within +-this, pixel·mm */
    uint64_t seed;
} cub_ft_params;

/* Train on set; *asset is malloc'd bytes that cub_forest_open accepts. */
cub_err cub_ft_train(const cub_ft_set *set, const cub_ft_params *p, uint8_t **asset, size_t *len);

typedef struct cub_ft_score {
    long n[CUB_PART_COUNT], right[CUB_PART_COUNT];
    long named[CUB_PART_COUNT][CUB_PART_COUNT]; /* [true part][the forest's] */
    long ties; /* pixels whose best score another part equals (the lower part wins) */
} cub_ft_score;

/* Every stride-th player pixel of every frame classified; counts added. */
void cub_ft_score_set(const cub_forest *f, const cub_ft_set *set, int stride, cub_ft_score *s);

#endif

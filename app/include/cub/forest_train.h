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
#include "cub/kinect.h"
#include "cub/synth.h"
#include "cub/track.h"

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
    int no_turn; /* 1: the clip's own facing (no new yaw every 1.5 s): facing known */
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

/* ---- proposals against the heuristic tracker (issue 20 point 4) ---- */

/* How a clip is compared: rendered at 10 fps for `seconds` (turning and
 * moving about as train-forest renders, seed), the tracker on every frame,
 * both scored on every `every`-th; the forest on every stride-th pixel. */
typedef struct cub_ft_compare {
    const char *data_dir;
    double seconds;
    int every, stride;
    uint64_t seed;
} cub_ft_compare;

/* Per joint, over the frames scored: the true joints in view (n), those
 * within 10 cm for the tracker, the forest, two combinations (combined: a
 * tracker joint of confidence < 1/2 replaced by a confident forest joint;
 * override: every confident forest joint replaces the tracker's); the
 * forest's confident joints and those within 10 cm; the tracker's guessed
 * joints (confidence < 1/2). */
typedef struct cub_ft_vs {
    long n[CUB_KJ_COUNT], tracker[CUB_KJ_COUNT], forest[CUB_KJ_COUNT], combined[CUB_KJ_COUNT];
    long override[CUB_KJ_COUNT], have[CUB_KJ_COUNT]; /* have: the forest gave the joint */
    long confident[CUB_KJ_COUNT], confident_right[CUB_KJ_COUNT], guessed[CUB_KJ_COUNT];
    long frames, tracker_frames;
    double forest_s, tracker_s; /* wall time: gather + proposals + joints; the tracker */
} cub_ft_vs;

cub_err cub_ft_compare_clip(const cub_forest *f, const cub_ft_compare *c, const char *spec,
                            cub_ft_vs *vs, cub_diag *diag);
/* One frame's tracker skeleton and forest joints scored against a truth
 * (its visible joints) into vs. */
void cub_ft_score_joints(const cub_track_skeleton *s, const cub_forest_joints *fj,
                         const cub_synth_truth_frame *tr, cub_ft_vs *vs);

/* Hand labels of real frames (tests/labels/skeltrack_labels.txt): lines
 * `frame joint u v` ('#' comments; u v `- -` when not in view). */
#define CUB_FT_MAX_LABELS 256
typedef struct cub_ft_label {
    char frame[64];
    int joint, u, v; /* u = v = -1: not in view */
    int line;        /* in the labels file, for errors about its frame */
} cub_ft_label;
typedef struct cub_ft_labels {
    cub_ft_label l[CUB_FT_MAX_LABELS];
    int n;
    const char *name; /* the labels file (the parser's name, not copied) */
} cub_ft_labels;
/* Errors name name:line and the problem (CUB_ERR_FORMAT); a UTF-8 BOM is
 * skipped; a file of no labels is refused. */
cub_err cub_ft_labels_parse(const char *text, size_t len, const char *name, cub_ft_labels *out,
                            cub_diag *diag);
/* Where the real frames are and how they are read: dir (fakenect .pgm),
 * the forest on every stride-th pixel; seam: the tracker runs with the
 * forest in its seam (cub_track_desc.forest), as the box would. */
typedef struct cub_ft_real {
    const char *dir;
    int stride, seam;
} cub_ft_real;
/* The labelled frames in the labels' order: the tracker on each, the
 * forest on the readings within 600 mm of the tracker's spine, both scored
 * against the labels (their 3D points made as test_tracker makes them). */
cub_err cub_ft_compare_real(const cub_forest *f, const cub_ft_real *r, const cub_ft_labels *lab,
                            cub_ft_vs *vs, cub_diag *diag);

#endif

/* walk_clip — a walk clip's analysis for the gait walker (cub/gait.h),
 * owned: the per-frame ankle and toe tracks and the phases that
 * cub_gait_walk_clip_make fills, on the heap. The box's walks
 * (app/cubdance/walk_box.c) and cubtool gait / gait-eval share it. */
#ifndef CUB_WALK_CLIP_H
#define CUB_WALK_CLIP_H

#include <stdint.h>

#include "cub/gait.h"

typedef struct cub_walk_clip {
    cub_gait_walk_clip wc; /* what the walker plays (points into the arrays below) */
    cub_vec3 *track[4];    /* left ankle, left toe, right ankle, right toe */
    uint8_t *phase[2];     /* left, right */
} cub_walk_clip;

/* Analyse clip (which must outlive w) with the feet's ankle and toe joints
 * ([0] the left). CUB_ERR_NOMEM, or cub_gait_walk_clip_make's errors; on
 * any failure w holds nothing (freed). */
cub_err cub_walk_clip_make(cub_walk_clip *w, const cub_clip *clip, const int ankle[2],
                           const int toe[2]);
/* Free the arrays; w is zeroed. */
void cub_walk_clip_free(cub_walk_clip *w);

#endif

/* Private to app/tag: the steps of cub_tag_library, one file each. */
#ifndef CUB_TAG_INTERNAL_H
#define CUB_TAG_INTERNAL_H

#include <stdio.h>

#include "cub/tags.h"

/* Every frame of every clip, measured (tag_frames.c). */
typedef struct cub_tag_measured {
    int clip_count;
    cub_tag_frame **frames; /* [clip][frame] */
} cub_tag_measured;

/* Steps 1 and 2 and the thinning: fill tags->clips[c].bridges
 * (tag_bridges.c). */
cub_err cub_tag_pick_bridges(const cub_library *lib, const cub_tag_measured *m,
                             const cub_tag_params *p, cub_tags *tags);

/* Step 3: fill tags->pairs (tag_links.c). */
cub_err cub_tag_link_pairs(const cub_library *lib, const cub_tag_measured *m,
                           const cub_tag_params *p, cub_tags *tags, cub_tag_progress progress,
                           void *user);

#endif

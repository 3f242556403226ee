/* walk_clip — see cub/walk_clip.h. */
#include "cub/walk_clip.h"

#include <stdlib.h>
#include <string.h>

static cub_err alloc(cub_walk_clip *w, size_t n)
{
    for (int i = 0; i < 4; i++)
        if (!(w->track[i] = calloc(n, sizeof(cub_vec3)))) return CUB_ERR_NOMEM;
    for (int i = 0; i < 2; i++)
        if (!(w->phase[i] = calloc(n, 1))) return CUB_ERR_NOMEM;
    return CUB_OK;
}

cub_err cub_walk_clip_make(cub_walk_clip *w, const cub_clip *clip, const int ankle[2],
                           const int toe[2])
{
    memset(w, 0, sizeof *w);
    if (!clip || clip->frame_count < 1) return CUB_ERR_ARG;
    cub_err e = alloc(w, (size_t)clip->frame_count);
    cub_vec3 *const am[2] = {w->track[0], w->track[2]}, *const tm[2] = {w->track[1], w->track[3]};
    if (!e) e = cub_gait_walk_clip_make(clip, ankle, toe, am, tm, w->phase, &w->wc);
    if (e) cub_walk_clip_free(w);
    return e;
}

void cub_walk_clip_free(cub_walk_clip *w)
{
    for (int i = 0; i < 4; i++)
        free(w->track[i]);
    for (int i = 0; i < 2; i++)
        free(w->phase[i]);
    memset(w, 0, sizeof *w);
}

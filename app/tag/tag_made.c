/* tag_made — bridge frames for a clip made after the library was tagged
 * (the groove's, issue 23), by the tagger's own rules (tag_bridges.c):
 * step 1's frequent classes are the library's, read from the bridge
 * table's features of its frames; steps 2 and the thinning run on the new
 * clip as on any library clip. */
#include <stdlib.h>

#include "tag_internal.h"

cub_err cub_tag_table_classes(const cub_bridge_table *t, int clip_count, const cub_tag_params *p,
                              cub_tag_classes *out)
{
    if (!t || !t->finished || clip_count < 1 || clip_count > t->desc.clip_count || !p || !out)
        return CUB_ERR_ARG;
    size_t total = 0;
    for (int c = 0; c < clip_count; c++)
        total += (size_t)t->clips[c].clip.frame_count;
    uint32_t *classes = malloc(sizeof *classes * total);
    int *clips = malloc(sizeof *clips * total);
    cub_err e = classes && clips ? CUB_OK : CUB_ERR_NOMEM;
    size_t k = 0;
    for (int c = 0; !e && c < clip_count; c++)
        for (int f = 0; f < t->clips[c].clip.frame_count; f++, k++) {
            classes[k] = cub_fuzzy_crisp_class(&t->fuzzy[t->clips[c].first_frame + f]);
            clips[k] = c;
        }
    if (!e) e = cub_tag_frequent_classes(classes, clips, total, p, &out->classes, &out->count);
    free(classes);
    free(clips);
    return e;
}

cub_err cub_tag_made_clip(const cub_clip *clip, const cub_fuzzy_body *body,
                          const cub_tag_classes *freq, const cub_tag_params *p,
                          cub_tag_frame *frames, cub_tag_clip *out)
{
    if (!freq) return CUB_ERR_ARG;
    cub_err e = cub_tag_analyse_clip(clip, body, frames);
    return e ? e : cub_tag_pick_clip(clip, frames, freq->classes, freq->count, p, out);
}

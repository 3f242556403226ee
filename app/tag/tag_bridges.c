/* tag_bridges — steps 1 and 2 of SEEDS.md § 000 "Bridge-frame tagging":
 * candidates are frames whose crisp pose class is frequent across the whole
 * library; frames where the head moves fast are dropped; then each run of
 * consecutive candidates is thinned to bridge frames at least a spacing
 * window apart, stillest first (a switch at a still moment hides best). */
#include <stdlib.h>
#include <string.h>

#include "tag_internal.h"

typedef struct class_use {
    uint32_t crisp_class;
    int clip;
} class_use;

static int cmp_use(const void *pa, const void *pb)
{
    const class_use *a = pa, *b = pb;
    if (a->crisp_class != b->crisp_class) return a->crisp_class < b->crisp_class ? -1 : 1;
    return (a->clip > b->clip) - (a->clip < b->clip);
}

static int cmp_u32(const void *pa, const void *pb)
{
    uint32_t a = *(const uint32_t *)pa, b = *(const uint32_t *)pb;
    return (a > b) - (a < b);
}

/* The frequent classes, ascending (step 1), of the frames in use[0..total). */
static cub_err frequent_of(class_use *use, size_t total, const cub_tag_params *p, uint32_t **out,
                           int *out_count)
{
    uint32_t *freq = malloc(sizeof *freq * (total ? total : 1));
    if (!freq) return CUB_ERR_NOMEM;
    qsort(use, total, sizeof *use, cmp_use);
    int count = 0;
    for (size_t i = 0; i < total;) {
        size_t j = i;
        int clips = 0;
        for (; j < total && use[j].crisp_class == use[i].crisp_class; j++)
            clips += j == i || use[j].clip != use[j - 1].clip;
        int64_t frames = (int64_t)(j - i);
        if (frames * 65536 >= (int64_t)p->class_share * (int64_t)total || clips >= p->class_clips)
            freq[count++] = use[i].crisp_class;
        i = j;
    }
    *out = freq;
    *out_count = count;
    return CUB_OK;
}

cub_err cub_tag_frequent_classes(const uint32_t *classes, const int *clips, size_t total,
                                 const cub_tag_params *p, uint32_t **out, int *out_count)
{
    if (!classes || !clips || !p || !out || !out_count) return CUB_ERR_ARG;
    class_use *use = malloc(sizeof *use * (total ? total : 1));
    if (!use) return CUB_ERR_NOMEM;
    for (size_t i = 0; i < total; i++)
        use[i] = (class_use){classes[i], clips[i]};
    cub_err e = frequent_of(use, total, p, out, out_count);
    free(use);
    return e;
}

/* The library's frequent classes (step 1). */
static cub_err frequent_classes(const cub_library *lib, const cub_tag_measured *m,
                                const cub_tag_params *p, uint32_t **out, int *out_count)
{
    size_t total = 0;
    for (int c = 0; c < lib->clip_count; c++)
        total += (size_t)lib->clips[c].clip.frame_count;
    class_use *use = malloc(sizeof *use * (total ? total : 1));
    if (!use) return CUB_ERR_NOMEM;
    size_t k = 0;
    for (int c = 0; c < lib->clip_count; c++)
        for (int f = 0; f < lib->clips[c].clip.frame_count; f++)
            use[k++] = (class_use){m->frames[c][f].crisp_class, c};
    cub_err e = frequent_of(use, total, p, out, out_count);
    free(use);
    return e;
}

static int is_candidate(const cub_tag_frame *f, const uint32_t *freq, int freq_count,
                        const cub_tag_params *p)
{
    if (f->head_dps > p->head_dps) /* step 2 */
        return 0;
    return bsearch(&f->crisp_class, freq, (size_t)freq_count, sizeof *freq, cmp_u32) != NULL;
}

/* Frames per thinning window: spacing_ms in this clip's frame periods. */
static int window_frames(const cub_clip *clip, int spacing_ms)
{
    int64_t w = ((int64_t)spacing_ms * 1000000 + clip->frame_ns / 2) / clip->frame_ns;
    return w < 1 ? 1 : w > 100000 ? 100000 : (int)w;
}

static const cub_tag_frame *g_sort_frames; /* qsort has no user pointer */

/* Stillest first, then the earlier frame. */
static int cmp_still(const void *pa, const void *pb)
{
    int a = *(const int *)pa, b = *(const int *)pb;
    cub_q16 ma = g_sort_frames[a].motion_mm, mb = g_sort_frames[b].motion_mm;
    if (ma != mb) return ma < mb ? -1 : 1;
    return (a > b) - (a < b);
}

/* Thin one run [start, end) of candidates: take frames stillest first,
 * skipping any within w-1 frames of one already taken. Every candidate
 * then lies within w-1 frames of a bridge frame (the run stays covered)
 * and no two bridge frames are closer than w. */
static void thin_run(const cub_tag_frame *frames, int start, int end, int w, int *order,
                     unsigned char *taken)
{
    int n = end - start;
    for (int i = 0; i < n; i++)
        order[i] = start + i;
    g_sort_frames = frames;
    qsort(order, (size_t)n, sizeof *order, cmp_still);
    for (int i = 0; i < n; i++) {
        int f = order[i], lo = f - w + 1 < start ? start : f - w + 1;
        int hi = f + w - 1 >= end ? end - 1 : f + w - 1, clear = 1;
        for (int g = lo; g <= hi && clear; g++)
            clear = !taken[g];
        taken[f] = (unsigned char)clear;
    }
}

cub_err cub_tag_pick_clip(const cub_clip *clip, const cub_tag_frame *frames, const uint32_t *freq,
                          int freq_count, const cub_tag_params *p, cub_tag_clip *out)
{
    if (!clip || !frames || (freq_count > 0 && !freq) || !p || !out || clip->frame_count < 1 ||
        clip->frame_ns == 0)
        return CUB_ERR_ARG;
    int n = clip->frame_count, w = window_frames(clip, p->spacing_ms);
    int *order = malloc(sizeof *order * (size_t)n);
    unsigned char *taken = calloc((size_t)n, 1);
    out->bridges = malloc(sizeof *out->bridges * (size_t)n);
    out->bridge_count = 0;
    if (!order || !taken || !out->bridges) {
        free(order);
        free(taken);
        return CUB_ERR_NOMEM;
    }
    for (int f = 0; f < n;) {
        int end = f;
        while (end < n && is_candidate(&frames[end], freq, freq_count, p))
            end++;
        if (end > f) thin_run(frames, f, end, w, order, taken);
        f = end > f ? end : f + 1;
    }
    for (int f = 0; f < n; f++)
        if (taken[f])
            out->bridges[out->bridge_count++] = (cub_tag_bridge){f, frames[f].crisp_class};
    free(order);
    free(taken);
    return CUB_OK;
}

cub_err cub_tag_pick_bridges(const cub_library *lib, const cub_tag_measured *m,
                             const cub_tag_params *p, cub_tags *tags)
{
    uint32_t *freq = NULL;
    int freq_count = 0;
    cub_err e = frequent_classes(lib, m, p, &freq, &freq_count);
    for (int c = 0; !e && c < lib->clip_count; c++)
        e = cub_tag_pick_clip(&lib->clips[c].clip, m->frames[c], freq, freq_count, p, &tags->clips[c]);
    free(freq);
    return e;
}

/* tag_library — cub_tag_library: measure every frame, pick bridge frames
 * (steps 1 and 2), link them (step 3). The defaults and why they are what
 * they are: README.md, "Bridge tags (XML)". */
#include <stdlib.h>
#include <string.h>

#include "tag_internal.h"

cub_tag_params cub_tag_params_defaults(const cub_tag_params *p)
{
    cub_tag_params d = p ? *p : (cub_tag_params){0};
    d.fuzzy = cub_fuzzy_config_defaults(&d.fuzzy);
    if (d.class_share <= 0) d.class_share = CUB_Q16_ONE / 50; /* 2% */
    if (d.class_clips <= 0) d.class_clips = 3;
    if (d.head_dps <= 0) d.head_dps = CUB_Q16_INT(120);
    if (d.spacing_ms <= 0) d.spacing_ms = 200;
    if (d.max_links == 0) d.max_links = 3;
    return d;
}

static void free_measured(cub_tag_measured *m)
{
    for (int c = 0; c < m->clip_count && m->frames; c++)
        free(m->frames[c]);
    free(m->frames);
}

static cub_err measure(const cub_library *lib, const cub_fuzzy_body *body, cub_tag_measured *m,
                       cub_tag_progress progress, void *user)
{
    m->clip_count = lib->clip_count;
    m->frames = calloc((size_t)lib->clip_count, sizeof *m->frames);
    if (!m->frames) return CUB_ERR_NOMEM;
    for (int c = 0; c < lib->clip_count; c++) {
        if (progress) progress(user, "measure", c, lib->clip_count);
        const cub_clip *clip = &lib->clips[c].clip;
        if (clip->frame_count < 1) return CUB_ERR_ARG;
        m->frames[c] = malloc(sizeof **m->frames * (size_t)clip->frame_count);
        if (!m->frames[c]) return CUB_ERR_NOMEM;
        cub_err e = cub_tag_analyse_clip(clip, body, m->frames[c]);
        if (e) return e;
    }
    return CUB_OK;
}

static cub_err start_tags(const cub_library *lib, const char *name, const cub_tag_params *p,
                          cub_tags *out)
{
    memset(out, 0, sizeof *out);
    snprintf(out->library, sizeof out->library, "%s", name ? name : "");
    out->params = *p;
    out->clip_count = lib->clip_count;
    out->clips = calloc((size_t)lib->clip_count, sizeof *out->clips);
    out->pairs = calloc((size_t)lib->clip_count * (size_t)lib->clip_count, sizeof *out->pairs);
    if (!out->clips || !out->pairs) return CUB_ERR_NOMEM;
    for (int c = 0; c < lib->clip_count; c++) {
        snprintf(out->clips[c].name, sizeof out->clips[c].name, "%s", lib->clips[c].name);
        out->clips[c].frame_count = lib->clips[c].clip.frame_count;
    }
    return CUB_OK;
}

cub_err cub_tag_library(const cub_library *lib, const char *library_name,
                        const cub_fuzzy_body *body, const cub_tag_params *params, cub_tags *out,
                        cub_tag_progress progress, void *user)
{
    if (!lib || !body || !out || lib->clip_count < 1 || !lib->clips) return CUB_ERR_ARG;
    cub_tag_params p = cub_tag_params_defaults(params);
    if (p.fuzzy.threshold <= 0 || p.fuzzy.threshold > CUB_Q16_ONE || p.max_links < -1)
        return CUB_ERR_ARG;
    cub_tag_measured m = {0};
    cub_err e = start_tags(lib, library_name, &p, out);
    if (!e) e = measure(lib, body, &m, progress, user);
    if (!e) {
        if (progress) progress(user, "bridges", 0, 1);
        e = cub_tag_pick_bridges(lib, &m, &p, out);
    }
    if (!e) e = cub_tag_link_pairs(lib, &m, &p, out, progress, user);
    free_measured(&m);
    if (e) cub_tags_free(out);
    return e;
}

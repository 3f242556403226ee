/* groove_box — see groove_box.h. */
#include "groove_box.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The song's MIDI -> the plan (tracks chosen by the song: set a). */
static cub_err plan_song(cub_groove_box *g, const cub_song *song, char *err, size_t size)
{
    cub_diag d = {0};
    char msg[600];
    if (cub_midi_groove_load(song->midi_path, &g->midi, &d)) {
        snprintf(err, size, "groove: %s", cub_diag_str(&d, msg, sizeof msg));
        return CUB_ERR_FORMAT;
    }
    cub_groove_params p;
    cub_err e = cub_groove_pick_tracks(&g->midi.song, -1, -1, &g->pick);
    if (!e) e = cub_groove_store_alloc(&g->mem, g->midi.song.note_count);
    if (!e) e = cub_groove_params_set('a', &p);
    if (!e) e = cub_groove_plan_build(&g->midi.song, &g->pick, &p, 0, &g->mem, &g->plan, NULL, NULL);
    if (e) snprintf(err, size, "groove: %s: no dance from its notes (%s)", song->midi_path,
                    cub_err_str(e));
    return e;
}

/* Every frame's fuzzy features (as cub_bridge_table_add_clip measures a
 * clip) and the clip's bridge frames by the tagger's rules: frames of a
 * pose class frequent in the library, the head still, thinned (app/tag). */
static cub_err tag_clip(cub_groove_box *g, int i, const cub_coachlib *cl,
                        const cub_tag_classes *freq)
{
    const cub_clip *clip = &g->clips[i];
    cub_tag_frame *frames = malloc(sizeof *frames * (size_t)clip->frame_count);
    cub_tag_clip picked = {0};
    cub_err e = frames ? cub_tag_made_clip(clip, &cl->table.desc.body, freq, &cl->tags.params,
                                           frames, &picked)
                       : CUB_ERR_NOMEM;
    g->bridges[i] = e ? NULL : malloc(sizeof *g->bridges[i] * (size_t)(picked.bridge_count + 1));
    if (!e && !g->bridges[i]) e = CUB_ERR_NOMEM;
    for (int f = 0; !e && f < clip->frame_count; f++)
        g->fuzzy[i][f] = frames[f].fuzzy;
    for (int b = 0; !e && b < picked.bridge_count; b++)
        g->bridges[i][b] = picked.bridges[b].frame;
    g->bridge_count[i] = e ? 0 : picked.bridge_count;
    free(picked.bridges);
    free(frames);
    return e;
}

/* FNV-1a over every frame's memberships, value by value (the same on any CPU). */
static uint32_t fuzzy_hash(const cub_fuzzy_frame *f, int frames)
{
    uint32_t h = 2166136261u;
    for (int i = 0; i < frames; i++)
        for (int k = 0; k < CUB_FUZZY_FEATURE_COUNT; k++)
            for (int s = 0; s < CUB_FUZZY_MAX_SETS; s++) {
                h = (h ^ (f[i].mu[k][s] & 0xffu)) * 16777619u;
                h = (h ^ (uint32_t)(f[i].mu[k][s] >> 8)) * 16777619u;
            }
    return h;
}

/* Distinct crisp pose classes among the frames: how much the dance varies. */
static int class_count(const cub_fuzzy_frame *f, int frames)
{
    uint32_t seen[64];
    int n = 0;
    for (int i = 0; i < frames; i++) {
        uint32_t c = cub_fuzzy_crisp_class(&f[i]);
        int j = 0;
        while (j < n && seen[j] != c)
            j++;
        if (j == n && n < 64) seen[n++] = c;
    }
    return n;
}

/* Span i's clip: frame f is the groove at the span's start + f frames. */
static cub_err fill_span(cub_groove_box *g, int i, const cub_coachlib *cl,
                         const cub_tag_classes *freq)
{
    const cub_song_span *sp = &g->spans[i];
    int frames = (int)((sp->end_us - sp->start_us) * 1000 / CUB_GROOVE_BOX_FRAME_NS) + 1;
    size_t size = cub_motion_clip_mem_size(g->rig.skel->joint_count, frames, 0);
    g->clip_mem[i] = malloc(size);
    g->fuzzy[i] = malloc(sizeof **g->fuzzy * (size_t)frames);
    if (!g->clip_mem[i] || !g->fuzzy[i]) return CUB_ERR_NOMEM;
    cub_err e = cub_motion_clip_init(&g->clips[i], g->rig.skel, frames, CUB_GROOVE_BOX_FRAME_NS,
                                     0, g->clip_mem[i], size);
    if (!e) e = cub_groove_clip_fill(&g->plan, &g->rig, sp->start_us, &g->clips[i]);
    if (!e) e = tag_clip(g, i, cl, freq);
    snprintf(g->names[i], sizeof g->names[i], "groove_%s_%d", cub_song_span_name(sp->kind),
             sp->bar);
    return e;
}

/* The range of one feature's input (degrees) over the frames. */
static void input_range(const cub_fuzzy_frame *f, int frames, int k, cub_q16 *lo, cub_q16 *hi)
{
    *lo = *hi = f[0].input[k];
    for (int i = 1; i < frames; i++) {
        *lo = f[i].input[k] < *lo ? f[i].input[k] : *lo;
        *hi = f[i].input[k] > *hi ? f[i].input[k] : *hi;
    }
}

static void log_span(const cub_groove_box *g, int i, cub_log *log)
{
    const cub_song_span *sp = &g->spans[i];
    const cub_fuzzy_frame *f = g->fuzzy[i];
    int frames = g->clips[i].frame_count;
    cub_q16 rh_lo, rh_hi, rhe_lo, rhe_hi;
    input_range(f, frames, CUB_FUZZY_RH, &rh_lo, &rh_hi);
    input_range(f, frames, CUB_FUZZY_RHE, &rhe_lo, &rhe_hi);
    cub_log_event(log, 0, "groove", "span",
                  "kind=%s bar=%d bars=%d start_ms=%d end_ms=%d frames=%d classes=%d "
                  "rh_deg=%q..%q rhe_deg=%q..%q fuzzy=%x bridges=%d",
                  cub_song_span_name(sp->kind), sp->bar, sp->bars, (int)(sp->start_us / 1000),
                  (int)(sp->end_us / 1000), frames, class_count(f, frames), rh_lo, rh_hi, rhe_lo,
                  rhe_hi, fuzzy_hash(f, frames), g->bridge_count[i]);
}

/* The spans' clips, made and tagged against the library's classes. */
static cub_err fill_spans(cub_groove_box *g, const cub_coachlib *cl, cub_log *log)
{
    cub_tag_classes freq = {0};
    cub_err e = cub_tag_table_classes(&cl->table, cl->lib.clip_count, &cl->tags.params, &freq);
    for (int i = 0; !e && i < g->span_count; i++) {
        e = fill_span(g, i, cl, &freq);
        if (!e) log_span(g, i, log);
    }
    free(freq.classes);
    return e;
}

cub_err cub_groove_box_open(cub_groove_box *g, const cub_song *song, const cub_coachlib *cl,
                            cub_log *log, char *err, size_t size)
{
    memset(g, 0, sizeof *g);
    cub_err e = plan_song(g, song, err, size);
    if (e) return e;
    /* A coach of another build (the seal) has no arms to groove with: it
     * keeps to its clips. */
    if (cub_groove_rig_bind(&cl->lib.skel, &g->rig)) {
        cub_log_event(log, 0, "groove", "none", "why=skeleton");
        return CUB_OK;
    }
    g->span_count = cub_song_groove_spans(song, g->spans, CUB_SONG_MAX_SPANS);
    e = fill_spans(g, cl, log);
    if (e) snprintf(err, size, "groove: %s: the dance of its free bars (%s)", song->midi_path,
                    cub_err_str(e));
    return e;
}

void cub_groove_box_close(cub_groove_box *g)
{
    for (int i = 0; i < CUB_SONG_MAX_SPANS; i++)
        free(g->clip_mem[i]), free(g->fuzzy[i]), free(g->bridges[i]);
    cub_groove_store_free(&g->mem);
    cub_midi_groove_free(&g->midi);
    memset(g, 0, sizeof *g);
}

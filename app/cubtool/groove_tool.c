/* groove_tool — see groove_tool.h. */
#include "groove_tool.h"

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "cub/character.h"

double groove_now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec / 1e6;
}

static int fail(const char *who, const char *path, const char *what, cub_err e)
{
    fprintf(stderr, "cubtool %s: %s: %s (%s)\n", who, path, what, cub_err_str(e));
    return 1;
}

int groove_song_load(const groove_args *a, const char *who, groove_song *s)
{
    *s = (groove_song){0};
    cub_diag d = {0};
    char msg[600];
    if (cub_midi_groove_load(a->path, &s->midi, &d)) {
        fprintf(stderr, "cubtool %s: %s\n", who, cub_diag_str(&d, msg, sizeof msg));
        return 1;
    }
    cub_err e = cub_groove_pick_tracks(&s->midi.song, a->melody, a->rhythm, &s->pick);
    if (e == CUB_ERR_RANGE) return fail(who, a->path, "no such track with notes", e);
    if (e == CUB_ERR_UNSUPPORTED) return fail(who, a->path, "more than 256 tracks", e);
    if (e) return fail(who, a->path, "no track with pitched notes", e);
    if (cub_groove_store_alloc(&s->mem, s->midi.song.note_count))
        return fail(who, a->path, "out of memory", CUB_ERR_NOMEM);
    cub_groove_params p;
    cub_groove_params_set(a->set, &p);
    double t0 = groove_now_ms();
    e = cub_groove_plan_build(&s->midi.song, &s->pick, &p, a->window, &s->mem, &s->plan,
                              &s->seg_count, &s->cost);
    s->plan_ms = groove_now_ms() - t0;
    return e ? fail(who, a->path, "planning the motion", e) : 0;
}

void groove_song_free(groove_song *s)
{
    cub_groove_store_free(&s->mem);
    cub_midi_groove_free(&s->midi);
    *s = (groove_song){0};
}

int groove_bear(cub_skeleton *skel, const char *who)
{
    static cub_character bear; /* static: large */
    cub_diag d = {0};
    char msg[600];
    if (cub_character_load(CUB_ASSETS_DIR "/bear/bear.xml", &bear, &d)) {
        fprintf(stderr, "cubtool %s: %s\n", who, cub_diag_str(&d, msg, sizeof msg));
        return 1;
    }
    *skel = bear.skel;
    return 0;
}

int groove_song_clip(const groove_song *s, const cub_groove_rig *rig, int fps, cub_clip *clip,
                     void **mem)
{
    int frames = (int)(s->plan.end_us * fps / 1000000) + 1;
    size_t size = cub_motion_clip_mem_size(rig->skel->joint_count, frames, 0);
    *mem = malloc(size);
    if (!*mem ||
        cub_motion_clip_init(clip, rig->skel, frames, (uint32_t)(1000000000 / fps), 0, *mem, size))
        return 1;
    return cub_groove_clip_fill(&s->plan, rig, 0, clip) != CUB_OK;
}

/* One beat of meter m in ticks: a quarter x 4 / denominator. */
static int32_t beat_ticks(const cub_groove_song *song, const cub_groove_meter *m)
{
    int den = m ? m->denominator : 4;
    int32_t t = song->division * 4 / (den ? den : 4);
    return t > 0 ? t : 1;
}

int64_t *groove_beats_us(const cub_groove_song *song, int *count)
{
    int cap = 64, n = 0, mi = -1;
    int64_t *out = malloc((size_t)cap * sizeof *out);
    for (int32_t tick = 0; out && tick <= song->end_tick;) {
        while (mi + 1 < song->meter_count && song->meters[mi + 1].tick <= tick)
            mi++;
        if (n == cap) {
            int64_t *grown = realloc(out, (size_t)(cap *= 2) * sizeof *out);
            if (!grown) free(out);
            out = grown;
            if (!out) break;
        }
        out[n++] = cub_groove_tick_us(song, tick);
        tick += beat_ticks(song, mi >= 0 ? &song->meters[mi] : NULL);
        /* a new meter restarts the grid at its own tick */
        if (mi + 1 < song->meter_count && song->meters[mi + 1].tick < tick)
            tick = song->meters[mi + 1].tick;
    }
    *count = n;
    return out;
}

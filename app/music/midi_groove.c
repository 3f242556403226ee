/* midi_groove — a MIDI file's notes, tempo map and meters for the groove
 * module (cub/music.h), read on top of the scan (midi_scan.c walks and
 * checks the file; this pairs notes and sorts). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/text.h"
#include "midi_internal.h"

#define MAX_METERS 1024
#define KEYS (16 * 128) /* channel x pitch */

/* Open notes per channel and pitch, oldest first (a linked list through
 * next[]). */
typedef struct reader {
    cub_midi_groove *g;
    int capacity, tempo_cap;
    int *next;
    int head[KEYS], tail[KEYS];
    int open;          /* notes sounding: End of Track sweeps the keys only then */
    char problem[160]; /* the first event this reader refuses */
} reader;

static void open_note(reader *r, int track, int64_t tick, int ch, const uint8_t *d)
{
    cub_groove_song *s = &r->g->song;
    if (s->note_count == r->capacity) return; /* the scan counted them: cannot happen */
    int i = s->note_count++, key = ch * 128 + d[0];
    r->g->notes[i] = (cub_groove_midi_note){(int32_t)tick, (int32_t)tick, (uint16_t)track,
                                            (uint8_t)ch,   d[0],          d[1]};
    r->next[i] = -1;
    r->open++;
    if (r->tail[key] >= 0)
        r->next[r->tail[key]] = i;
    else
        r->head[key] = i;
    r->tail[key] = i;
}

static void close_head(reader *r, int key, int64_t tick)
{
    int i = r->head[key];
    r->g->notes[i].off_tick = (int32_t)tick;
    r->head[key] = r->next[i];
    if (r->head[key] < 0) r->tail[key] = -1;
    r->open--;
}

/* A note-off ends every note of its key that started before it, as
 * FluidSynth releases every voice of the key; only when none did does it
 * end those starting at its own tick (a zero-length note). A note-on just
 * before it at the same tick thus survives it. */
static void close_note(reader *r, int key, int64_t tick)
{
    int closed = 0;
    while (r->head[key] >= 0 && r->g->notes[r->head[key]].on_tick < tick)
        close_head(r, key, tick), closed++;
    while (!closed && r->head[key] >= 0)
        close_head(r, key, tick);
}

static void on_channel(void *ctx, int track, int64_t tick, uint8_t status, const uint8_t *d)
{
    reader *r = ctx;
    int kind = status & 0xF0, ch = status & 0x0F;
    if (kind == 0x90 && d[1] > 0)
        open_note(r, track, tick, ch, d);
    else if (kind == 0x80 || kind == 0x90)
        close_note(r, ch * 128 + d[0], tick);
}

static void add_tempo(reader *r, int64_t tick, const uint8_t *d)
{
    cub_groove_song *s = &r->g->song;
    if (s->tempo_count == r->tempo_cap) return; /* the scan counted them */
    cub_groove_tempo t = {(int32_t)tick, (uint32_t)(d[0] << 16 | d[1] << 8 | d[2])};
    int j = s->tempo_count++;
    for (; j > 0 && r->g->tempos[j - 1].tick > t.tick; j--) /* stable: file order at one tick */
        r->g->tempos[j] = r->g->tempos[j - 1];
    r->g->tempos[j] = t;
}

static void add_meter(reader *r, int track, int64_t tick, const uint8_t *d, uint32_t n)
{
    cub_groove_song *s = &r->g->song;
    if (r->problem[0]) return;
    if (n < 2 || d[0] == 0 || d[1] > 6) {
        snprintf(r->problem, sizeof r->problem,
                 "track %d tick %lld: a time signature that is not n/1..n/64", track,
                 (long long)tick);
        return;
    }
    if (s->meter_count == MAX_METERS) {
        snprintf(r->problem, sizeof r->problem, "more than %d time signatures", MAX_METERS);
        return;
    }
    cub_groove_meter m = {(int32_t)tick, d[0], (uint8_t)(1u << d[1])};
    int j = s->meter_count++;
    for (; j > 0 && r->g->meters[j - 1].tick > m.tick; j--)
        r->g->meters[j] = r->g->meters[j - 1];
    r->g->meters[j] = m;
}

static void on_meta(void *ctx, int track, int64_t tick, uint8_t type, const uint8_t *d, uint32_t n)
{
    reader *r = ctx;
    if (type == 0x51) add_tempo(r, tick, d); /* the scan checked its length */
    if (type == 0x58) add_meter(r, track, tick, d, n);
    if (type == 0x2F) /* End of Track ends what still sounds */
        for (int key = 0; key < KEYS && r->open > 0; key++)
            while (r->head[key] >= 0)
                close_head(r, key, tick);
}

static int by_onset(const void *a, const void *b)
{
    const cub_groove_midi_note *x = a, *y = b;
    if (x->on_tick != y->on_tick) return x->on_tick < y->on_tick ? -1 : 1;
    if (x->track != y->track) return x->track < y->track ? -1 : 1;
    if (x->pitch != y->pitch) return x->pitch < y->pitch ? -1 : 1;
    if (x->channel != y->channel) return x->channel < y->channel ? -1 : 1;
    if (x->off_tick != y->off_tick) return x->off_tick < y->off_tick ? -1 : 1;
    return (x->velocity > y->velocity) - (x->velocity < y->velocity);
}

static cub_err allocate(reader *r, const cub_midi_info *info)
{
    cub_midi_groove *g = r->g;
    r->capacity = info->notes;
    r->tempo_cap = info->tempo_changes;
    g->notes = malloc(sizeof(*g->notes) * (size_t)(info->notes + 1));
    g->tempos = malloc(sizeof(*g->tempos) * (size_t)(info->tempo_changes + 1));
    g->meters = malloc(sizeof(*g->meters) * MAX_METERS);
    r->next = malloc(sizeof(int) * (size_t)(info->notes + 1));
    for (int k = 0; k < KEYS; k++)
        r->head[k] = r->tail[k] = -1;
    return g->notes && g->tempos && g->meters && r->next ? CUB_OK : CUB_ERR_NOMEM;
}

static cub_err read_events(reader *r, const uint8_t *data, size_t len, const char *name,
                           cub_diag *diag)
{
    cub_midi_info info;
    cub_err e = cub_midi_scan(data, len, name, &info, diag);
    if (e) return e;
    if (info.end_tick >= INT32_MAX)
        return cub_diag_fail(diag, CUB_ERR_FORMAT, name, 0, "a song longer than 2^31 - 1 ticks");
    if (allocate(r, &info)) return cub_diag_fail(diag, CUB_ERR_NOMEM, name, 0, "out of memory");
    cub_midi_sink sink = {r, on_channel, on_meta};
    r->g->song.division = info.division;
    r->g->song.tracks = info.tracks;
    r->g->song.end_tick = (int32_t)info.end_tick;
    e = cub_midi_walk(data, len, name, &sink, &info, diag);
    if (!e && r->problem[0]) e = cub_diag_fail(diag, CUB_ERR_FORMAT, name, 0, "%s", r->problem);
    return e;
}

cub_err cub_midi_groove_read(const uint8_t *data, size_t len, const char *name,
                             cub_midi_groove *out, cub_diag *diag)
{
    cub_diag scratch;
    if (!diag) diag = &scratch;
    if (!name) name = "(midi)";
    if (!out) return cub_diag_fail(diag, CUB_ERR_ARG, name, 0, "cub_midi_groove_read: no output");
    memset(out, 0, sizeof(*out));
    reader *r = calloc(1, sizeof(*r));
    if (!r) return cub_diag_fail(diag, CUB_ERR_NOMEM, name, 0, "out of memory");
    r->g = out;
    cub_err e = read_events(r, data, len, name, diag);
    free(r->next);
    free(r);
    if (e) {
        cub_midi_groove_free(out);
        return e;
    }
    qsort(out->notes, (size_t)out->song.note_count, sizeof(*out->notes), by_onset);
    out->song.notes = out->notes;
    out->song.tempos = out->tempos;
    out->song.meters = out->meters;
    return CUB_OK;
}

cub_err cub_midi_groove_load(const char *path, cub_midi_groove *out, cub_diag *diag)
{
    cub_diag scratch;
    if (!diag) diag = &scratch;
    if (out) memset(out, 0, sizeof(*out));
    if (!path || !out)
        return cub_diag_fail(diag, CUB_ERR_ARG, path, 0, "cub_midi_groove_load: bad arguments");
    char *data = NULL;
    size_t len = 0;
    cub_text_src src = {path, "MIDI file", CUB_TEXT_MAX_MIDI};
    cub_err e = cub_text_read(&src, &data, &len, diag);
    if (!e) e = cub_midi_groove_read((const uint8_t *)data, len, path, out, diag);
    free(data);
    return e;
}

void cub_midi_groove_free(cub_midi_groove *g)
{
    if (!g) return;
    free(g->notes);
    free(g->tempos);
    free(g->meters);
    memset(g, 0, sizeof(*g));
}

void cub_groove_store_free(cub_groove_store *m)
{
    free(m->notes), free(m->segs), free(m->keys), free(m->handles);
    free(m->waist), free(m->head), free(m->work);
    memset(m, 0, sizeof *m);
}

cub_err cub_groove_store_alloc(cub_groove_store *m, int note_count)
{
    memset(m, 0, sizeof *m);
    if (note_count < 0) return CUB_ERR_ARG;
    int cap = 2 * note_count + 1;
    m->cap = cap;
    m->notes = calloc((size_t)cap, sizeof *m->notes);
    m->segs = calloc((size_t)cap, sizeof *m->segs);
    m->keys = calloc((size_t)cap, sizeof *m->keys);
    m->handles = calloc((size_t)cap, sizeof *m->handles);
    m->waist = calloc((size_t)cap, sizeof *m->waist);
    m->head = calloc((size_t)cap, sizeof *m->head);
    m->work = malloc(sizeof *m->work);
    if (m->notes && m->segs && m->keys && m->handles && m->waist && m->head && m->work)
        return CUB_OK;
    cub_groove_store_free(m);
    return CUB_ERR_NOMEM;
}

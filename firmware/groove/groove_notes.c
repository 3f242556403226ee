/* groove — the melody as the seed's notes [pitch, length in beats,
 * intensity, isBeat] (SEEDS.md § 001, "Notes"). Ours: the melody track's
 * top line (of notes starting together the highest; a note ends where the
 * next one starts), a rest where the line is silent half a beat or more,
 * and isBeat when a rhythm onset (or a meter beat) lies within 1/16 of a
 * quarter note of the note's onset. */
#include "cub/groove.h"

#include "groove_internal.h"

typedef struct walk {
    const cub_groove_song *song;
    const cub_groove_pick *pick;
    cub_groove_note *out;
    int cap, count;
    int meter_cursor, rhythm_cursor;
} walk;

static bool is_melody(const walk *w, int i)
{
    const cub_groove_midi_note *n = &w->song->notes[i];
    return n->track == w->pick->melody_track && !groove_is_drum(n);
}

static bool is_rhythm(const walk *w, const cub_groove_midi_note *n)
{
    if (w->pick->rhythm == CUB_GROOVE_RHYTHM_TRACK) return n->track == w->pick->rhythm_track;
    return groove_is_drum(n);
}

static int32_t tolerance(const cub_groove_song *song)
{
    return song->division / 16;
}

static bool on_meter_beat(walk *w, int32_t tick)
{
    cub_groove_meter m = groove_meter_at(w->song, tick, &w->meter_cursor);
    int32_t beat = groove_beat_ticks(w->song, m), off = (tick - m.tick) % beat;
    int32_t tol = tolerance(w->song);
    return off <= tol || beat - off <= tol;
}

/* Rhythm onsets only grow with the melody's, so one cursor walks them. */
static bool on_rhythm_note(walk *w, int32_t tick)
{
    const cub_groove_song *s = w->song;
    int32_t tol = tolerance(s);
    int i = w->rhythm_cursor;
    while (i < s->note_count && (s->notes[i].on_tick < tick - tol || !is_rhythm(w, &s->notes[i])))
        i++;
    w->rhythm_cursor = i;
    return i < s->note_count && s->notes[i].on_tick <= tick + tol;
}

static cub_q16 beats(walk *w, int32_t from, int32_t to)
{
    cub_groove_meter m = groove_meter_at(w->song, from, &w->meter_cursor);
    int64_t q = ((int64_t)(to - from) << 16) / groove_beat_ticks(w->song, m);
    int64_t max = (int64_t)CUB_GROOVE_MAX_BEATS << 16;
    return (cub_q16)(q > max ? max : q);
}

/* The meter's grid at tick: the beat at or before it, and its length. */
static void grid(walk *w, cub_groove_note *n)
{
    cub_groove_meter m = groove_meter_at(w->song, n->tick, &w->meter_cursor);
    int32_t beat = groove_beat_ticks(w->song, m), off = (n->tick - m.tick) % beat;
    int32_t b0 = off < 0 ? n->tick - off - beat : n->tick - off;
    int64_t at = cub_groove_tick_us(w->song, b0);
    int64_t len = cub_groove_tick_us(w->song, b0 + beat) - at, back = n->start_us - at;
    bool fits = len > 0 && len <= INT32_MAX && back >= 0 && back <= INT32_MAX;
    n->grid_us = fits ? (int32_t)-back : 0;
    n->beat_us = fits ? (int32_t)len : 0;
}

static void emit(walk *w, int32_t tick, int32_t end, int pitch, int velocity)
{
    if (w->count < w->cap) {
        cub_groove_note *n = &w->out[w->count];
        n->tick = tick;
        n->start_us = cub_groove_tick_us(w->song, tick);
        n->length_beats = beats(w, tick, end);
        n->pitch = (uint8_t)pitch;
        n->intensity = (uint8_t)((velocity * 120 + 63) / 127);
        n->is_beat = false;
        if (pitch != CUB_GROOVE_REST)
            n->is_beat = w->pick->rhythm == CUB_GROOVE_RHYTHM_METER ? on_meter_beat(w, tick)
                                                                    : on_rhythm_note(w, tick);
        grid(w, n);
    }
    w->count++;
}

/* The next melody note at or after i whose onset is later than tick. */
static int next_onset(const walk *w, int i, int32_t tick)
{
    while (i < w->song->note_count && (!is_melody(w, i) || w->song->notes[i].on_tick <= tick))
        i++;
    return i;
}

/* Of the melody notes starting at notes[i]'s tick, the highest (the
 * notes are sorted by pitch within a tick and track). */
static int top_of_chord(const walk *w, int i)
{
    int top = i;
    for (int k = i + 1;
         k < w->song->note_count && w->song->notes[k].on_tick == w->song->notes[i].on_tick; k++)
        if (is_melody(w, k) && w->song->notes[k].pitch >= w->song->notes[top].pitch) top = k;
    return top;
}

cub_err cub_groove_notes(const cub_groove_song *song, const cub_groove_pick *pick,
                         cub_groove_note *out, int cap, int *count)
{
    if (!song || !pick || !count || cap < 0 || (cap > 0 && !out) || song->division <= 0)
        return CUB_ERR_ARG;
    walk w = {song, pick, out, cap, 0, 0, 0};
    int i = next_onset(&w, 0, INT32_MIN);
    while (i < song->note_count) {
        const cub_groove_midi_note *n = &song->notes[top_of_chord(&w, i)];
        int next = next_onset(&w, i, n->on_tick);
        int32_t end = n->off_tick;
        if (next < song->note_count && song->notes[next].on_tick < end)
            end = song->notes[next].on_tick;
        emit(&w, n->on_tick, end, n->pitch, n->velocity);
        if (next < song->note_count) {
            int32_t gap_to = song->notes[next].on_tick;
            cub_groove_meter m = groove_meter_at(song, end, &w.meter_cursor);
            if ((int64_t)(gap_to - end) * 2 >= groove_beat_ticks(song, m))
                emit(&w, end, gap_to, CUB_GROOVE_REST, 0);
        }
        i = next;
    }
    *count = w.count;
    return w.count > cap ? CUB_ERR_NOMEM : CUB_OK;
}

/* groove — the song's clock (the tempo map, the meter) and the choice of
 * the melody and rhythm tracks (SEEDS.md § 001: the user picks them; without
 * a choice, ours: the top line of the highest track, channel-10 drums, else the
 * time signature's beats). */
#include "cub/groove.h"

#include "groove_internal.h"

#define DEFAULT_US_PER_QUARTER 500000 /* 120 bpm until the first Set Tempo */
#define DRUM_CHANNEL 9
#define MAX_PICK_TRACKS 256

int64_t cub_groove_tick_us(const cub_groove_song *song, int32_t tick)
{
    /* Sum ticks x microseconds per quarter, divide once: exact to the
     * microsecond however many tempo events come before the tick. */
    int64_t sum = 0, from = 0;
    uint32_t us = DEFAULT_US_PER_QUARTER;
    for (int i = 0; i < song->tempo_count && song->tempos[i].tick < tick; i++) {
        sum += (song->tempos[i].tick - from) * (int64_t)us;
        from = song->tempos[i].tick;
        us = song->tempos[i].us_per_quarter;
    }
    sum += (tick - from) * (int64_t)us;
    return sum / song->division;
}

cub_groove_meter groove_meter_at(const cub_groove_song *song, int32_t tick, int *cursor)
{
    cub_groove_meter m = {0, 4, 4};
    int i = cursor ? *cursor : 0;
    while (i + 1 < song->meter_count && song->meters[i + 1].tick <= tick)
        i++;
    if (song->meter_count > 0 && song->meters[i].tick <= tick) m = song->meters[i];
    if (cursor) *cursor = i;
    if (m.numerator == 0) m.numerator = 4;
    if (m.denominator == 0) m.denominator = 4;
    return m;
}

int32_t groove_beat_ticks(const cub_groove_song *song, cub_groove_meter m)
{
    int32_t t = (int32_t)((int64_t)song->division * 4 / m.denominator);
    return t > 0 ? t : 1;
}

bool groove_is_drum(const cub_groove_midi_note *n)
{
    return n->channel == DRUM_CHANNEL;
}

typedef struct track_stats {
    int32_t count;
    int64_t pitch_sum;
} track_stats;

static void gather(const cub_groove_song *song, track_stats *st, int tracks)
{
    for (int i = 0; i < song->note_count; i++) {
        const cub_groove_midi_note *n = &song->notes[i];
        if (groove_is_drum(n) || n->track >= tracks) continue;
        st[n->track].count++;
        st[n->track].pitch_sum += n->pitch;
    }
}

/* The highest line: the track of the highest mean pitch (ties keep the
 * earlier track); cub_groove_notes takes its top line, so it is monophonic.
 * Ours: a test for monophony first (notes overlapping at most one time in
 * ten) picked the cello of all three string quartets in ../shared/data/midi,
 * whose first violins play double stops, trills and chords. */
static int highest_line(const track_stats *st, int tracks)
{
    int best = -1;
    for (int t = 0; t < tracks; t++)
        if (st[t].count > 0 &&
            (best < 0 || st[t].pitch_sum * st[best].count > st[best].pitch_sum * st[t].count))
            best = t;
    return best;
}

static int track_has_notes(const cub_groove_song *song, int track, bool pitched)
{
    for (int i = 0; i < song->note_count; i++)
        if (song->notes[i].track == track && !(pitched && groove_is_drum(&song->notes[i])))
            return 1;
    return 0;
}

static cub_err pick_rhythm(const cub_groove_song *song, int rhythm_track, cub_groove_pick *out)
{
    out->rhythm_track = -1;
    if (rhythm_track >= 0) {
        if (rhythm_track >= song->tracks || !track_has_notes(song, rhythm_track, false))
            return CUB_ERR_RANGE;
        out->rhythm = CUB_GROOVE_RHYTHM_TRACK;
        out->rhythm_track = rhythm_track;
        return CUB_OK;
    }
    out->rhythm = CUB_GROOVE_RHYTHM_METER;
    for (int i = 0; i < song->note_count; i++)
        if (groove_is_drum(&song->notes[i])) out->rhythm = CUB_GROOVE_RHYTHM_DRUMS;
    return CUB_OK;
}

cub_err cub_groove_pick_tracks(const cub_groove_song *song, int melody_track, int rhythm_track,
                               cub_groove_pick *out)
{
    if (!song || !out || song->division <= 0 || song->note_count < 0) return CUB_ERR_ARG;
    if (song->tracks > MAX_PICK_TRACKS) return CUB_ERR_UNSUPPORTED;
    cub_err e = pick_rhythm(song, rhythm_track, out);
    if (e) return e;
    if (melody_track >= 0) {
        if (melody_track >= song->tracks || !track_has_notes(song, melody_track, true))
            return CUB_ERR_RANGE;
        out->melody_track = melody_track;
        return CUB_OK;
    }
    track_stats st[MAX_PICK_TRACKS] = {{0}};
    gather(song, st, song->tracks);
    out->melody_track = highest_line(st, song->tracks);
    return out->melody_track < 0 ? CUB_ERR_EMPTY : CUB_OK;
}

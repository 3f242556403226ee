/* groove — seed 001 (SEEDS.md § 001): the bear moves to a song's own notes.
 * Input: a song's notes in MIDI ticks, its tempo map and time signatures
 * (app/music's MIDI reader fills a cub_groove_song). Output: the melody as
 * the seed's notes [pitch, length in beats, intensity, isBeat] with times in
 * microseconds through the tempo map; its segmentation by the seed's dynamic
 * programme; one right-wrist key per note (mm, relative to where the wrist
 * starts). Fixed point (Q16.16), no allocation: the caller owns every array.
 * Next (docs/groove.md): the Bézier paths, timing curves, left hand, waist
 * and head, arm IK. */
#ifndef CUB_GROOVE_H
#define CUB_GROOVE_H

#include <stdbool.h>
#include <stdint.h>

#include "cub/err.h"
#include "cub/fx.h"

/* ---- the song as read ---------------------------------------------------- */

/* One sounding note: a note-on paired with its note-off (ticks from the
 * start of the file; off_tick >= on_tick). channel 0..15 (9 = GM drums). */
typedef struct cub_groove_midi_note {
    int32_t on_tick, off_tick;
    uint16_t track;
    uint8_t channel, pitch, velocity;
} cub_groove_midi_note;

typedef struct cub_groove_tempo {
    int32_t tick;
    uint32_t us_per_quarter;
} cub_groove_tempo;

typedef struct cub_groove_meter {
    int32_t tick;
    uint8_t numerator, denominator; /* 4/4, 6/8; denominator a power of two */
} cub_groove_meter;

/* Arrays sorted by tick (notes: by on_tick, then track, then pitch). No
 * tempo event before a tick means 120 bpm; no meter means 4/4. */
typedef struct cub_groove_song {
    int division; /* ticks per quarter note, > 0 */
    int tracks;
    int32_t end_tick;
    const cub_groove_midi_note *notes;
    int note_count;
    const cub_groove_tempo *tempos;
    int tempo_count;
    const cub_groove_meter *meters;
    int meter_count;
} cub_groove_song;

/* A tick through the tempo map, in microseconds. */
int64_t cub_groove_tick_us(const cub_groove_song *song, int32_t tick);

/* ---- which track is the melody, which the rhythm --------------------------- */

typedef enum cub_groove_rhythm {
    CUB_GROOVE_RHYTHM_TRACK, /* the notes of one track (the user's choice) */
    CUB_GROOVE_RHYTHM_DRUMS, /* every note on channel 10 */
    CUB_GROOVE_RHYTHM_METER  /* the time signature's beats */
} cub_groove_rhythm;

typedef struct cub_groove_pick {
    int melody_track;
    cub_groove_rhythm rhythm;
    int rhythm_track; /* for CUB_GROOVE_RHYTHM_TRACK, else -1 */
} cub_groove_pick;

/* Choose the tracks: melody_track / rhythm_track >= 0 are the user's, -1
 * lets the song decide (melody: the top line of the highest track; rhythm: the
 * channel-10 drums, else the meter's beats). CUB_ERR_RANGE for a track the
 * song lacks or one with no notes; CUB_ERR_EMPTY if no track has a melody. */
cub_err cub_groove_pick_tracks(const cub_groove_song *song, int melody_track, int rhythm_track,
                               cub_groove_pick *out);

/* ---- the seed's notes ------------------------------------------------------ */

#define CUB_GROOVE_REST 255 /* the pitch of a rest */
#define CUB_GROOVE_MAX_BEATS 4

typedef struct cub_groove_note {
    int64_t start_us; /* through the tempo map */
    int32_t tick;
    cub_q16 length_beats; /* 0..4 (the seed's range; longer ones clamped) */
    uint8_t pitch;        /* 0..127, or CUB_GROOVE_REST */
    uint8_t intensity;    /* 0..120 (velocity scaled) */
    bool is_beat;         /* a rhythm note (or a meter beat) starts with it */
} cub_groove_note;

/* The melody as the seed's notes, rests between them where the line is
 * silent for half a beat or more. Writes at most cap notes; *count is how
 * many the melody has (CUB_ERR_NOMEM when that is more than cap). */
cub_err cub_groove_notes(const cub_groove_song *song, const cub_groove_pick *pick,
                         cub_groove_note *out, int cap, int *count);

/* ---- parameters (the seed's table 1) ---------------------------------------- */

typedef struct cub_groove_params {
    int w[4];             /* weights of f1..f4 (all 0: all 1) */
    cub_q16 v_beats;      /* preferred segment length (0: 2 beats) */
    cub_q16 swing_deg;    /* waist rotation per unit intensity */
    cub_q16 nod_deg;      /* head nod per unit intensity */
    cub_q16 yscale_mm;    /* wrist height per semitone from the median */
    cub_q16 smooth_mm;    /* distance between P1 and P2 at a non-beat key */
    cub_q16 reflectance;  /* 0..1: how far P1 mirrors P2 at a beat key */
    cub_q16 l1_mm, l2_mm; /* beat-key handles: G1 above, G2 back */
    cub_q16 x_span_mm;    /* the usable x span of the wrist (0: 400) */
    cub_q16 y_reach_mm;   /* |y| beyond this is scaled in (0: 250) */
} cub_groove_params;

/* Set 'a' or 'b' of the seed's table 1 (reflectance from percent).
 * CUB_ERR_ARG for another letter. */
cub_err cub_groove_params_set(char set, cub_groove_params *out);

/* ---- segmentation (the seed's DP, fig. 2) ------------------------------------ */

#define CUB_GROOVE_WINDOW_MAX 64 /* notes per DP window: O(window^3) each */

typedef struct cub_groove_segment {
    int first, end; /* notes [first, end) */
} cub_groove_segment;

/* The DP's table for one window: a caller-owned scratch area (25 KB). */
typedef struct cub_groove_work {
    cub_q16 value[CUB_GROOVE_WINDOW_MAX][CUB_GROOVE_WINDOW_MAX + 1];
    uint8_t split[CUB_GROOVE_WINDOW_MAX][CUB_GROOVE_WINDOW_MAX + 1]; /* 0: unsplit */
    uint8_t parts[CUB_GROOVE_WINDOW_MAX][CUB_GROOVE_WINDOW_MAX + 1]; /* segments inside */
} cub_groove_work;

typedef struct cub_groove_cost {
    int windows;    /* DP runs: long melodies are cut into windows first */
    int64_t splits; /* split points the DP weighed: its O(n^3) work */
    cub_q16 mean_f; /* the chosen segments' mean objective */
} cub_groove_cost;

/* The objective f of notes [first, end) in [0, 1] (f1..f4 weighted,
 * divided by the weights' sum); global_density is the whole melody's. */
cub_q16 cub_groove_objective(const cub_groove_params *p, const cub_groove_note *notes, int first,
                             int end, cub_q16 global_density);

/* Beat notes per note over notes [first, end) (0 when empty). */
cub_q16 cub_groove_density(const cub_groove_note *notes, int first, int end);

/* Segment n notes. window (2..CUB_GROOVE_WINDOW_MAX, 0: 48) bounds the DP:
 * a longer melody is cut after a rest or beat note near each window's end.
 * Writes at most cap segments, *count how many; cost may be NULL.
 * CUB_ERR_NOMEM when the segments do not fit, CUB_ERR_ARG for n < 1. */
cub_err cub_groove_segment_notes(const cub_groove_params *p, const cub_groove_note *notes, int n,
                                 int window, cub_groove_work *work, cub_groove_segment *out,
                                 int cap, int *count, cub_groove_cost *cost);

/* ---- right-wrist keys ----------------------------------------------------------- */

typedef struct cub_groove_key {
    cub_q16 x_mm, y_mm; /* relative to where the wrist is when the melody starts */
} cub_groove_key;

/* One key per note (keys[i] for notes[i]): x advances by the note's share
 * of its segment's length × x_span, the direction flipping each segment;
 * y = (pitch - the segment's median pitch) × Yscale, the segment's y scaled
 * in when beyond y_reach; a rest keeps the previous y; note 0 stays at 0. */
cub_err cub_groove_keys(const cub_groove_params *p, const cub_groove_note *notes, int n,
                        const cub_groove_segment *segs, int seg_count, cub_groove_key *keys);

#endif

/* groove — seed 001 (SEEDS.md § 001): the bear moves to a song's own notes.
 * Input: a song's notes in MIDI ticks, its tempo map and time signatures
 * (app/music's MIDI reader fills a cub_groove_song). Output: the melody as
 * the seed's notes [pitch, length in beats, intensity, isBeat] with times in
 * microseconds through the tempo map; its segmentation by the seed's dynamic
 * programme; one right-wrist key per note (mm, relative to where the wrist
 * starts); the Bézier paths between keys and their timing curves, the
 * waist's and head's turns, the left hand; the bear's pose at any time of
 * the song (arms by cub/motion.h's two-bone IK). Fixed point (Q16.16), no
 * allocation: the caller owns every array. */
#ifndef CUB_GROOVE_H
#define CUB_GROOVE_H

#include <stdbool.h>
#include <stdint.h>

#include "cub/err.h"
#include "cub/fx.h"
#include "cub/motion.h"

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
    /* The meter's beat grid where the note starts (ours, for the beat stop):
     * the meter beat at or before the onset, as an offset (<= 0) from
     * start_us, and that beat's length through the tempo map. beat_us 0:
     * no grid (then the motion has no stop on the beats). */
    int32_t grid_us, beat_us;
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
    cub_q16 pace_mm_s;    /* the fastest a key may follow the last (0: 1200) */
    cub_q16 peak_mm_s;    /* the wrist's fastest along its path (0: CUB_GROOVE_PEAK_MM_S) */
    /* The beat stop (ours): the pose's clock slows to a stop on every meter
     * beat over stop_before of a beat before it and starts again over
     * stop_after after it (fractions of a beat, each < 1, sum <= 1; 0 and 0:
     * no stop); the speed ramps as the stop_power-th (1..3) power of the
     * time from the beat. */
    cub_q16 stop_before, stop_after;
    int stop_power;
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

/* The wrist's peak speed along its path, key mm/s (ours, session 35;
 * the bear's wrist moves 0.4 of it; docs/groove.md "The speed bound"). */
#define CUB_GROOVE_PEAK_MM_S CUB_Q16_INT(2400)

/* Too fast to follow (ours): a key farther from the previous one than
 * pace_mm_s x the time between their notes is pulled toward it along the
 * same line, so no path asks the arm for more than the clip library's own
 * speeds (docs/groove.md). Notes without times (equal starts) are left. */
void cub_groove_keys_pace(const cub_groove_params *p, const cub_groove_note *notes, int n,
                          cub_groove_key *keys);

/* ---- paths between keys (cubic Bézier) and their timing ----------------------- */

/* The wrist's handles at one key: in_mm = the seed's P2 (the path into the
 * key leaves toward it), out_mm = P1 (the path out of the key starts toward
 * it). The path from key i to key i+1 is the cubic Bézier key i,
 * out[i], in[i+1], key i+1. */
typedef struct cub_groove_handles {
    cub_groove_key in_mm, out_mm;
    cub_q16 len_mm; /* the arc length of the path from this key to the next (0 for the last) */
} cub_groove_handles;

/* Handles for every key. Non-beat key: in and out on the line through the
 * key along previous -> next key, smooth apart, shared in proportion to the
 * times of the paths into and out of the key (the wrist's speed is then
 * continuous through it; the first key uses the next, the last the
 * previous). Beat key: in = G2 +
 * (intensity/120)(G1 - G2), G1 = L1 x the note's length (at most 2 beats)
 * straight above the key, G2 = L2 horizontally toward the previous key;
 * out = lerp(key, in mirrored about the key's vertical, reflectance).
 * Then (ours) each handle is kept within pace_mm_s x its path's time / 3
 * of its key, the most a Bézier end may run at that pace. */
cub_err cub_groove_handles_make(const cub_groove_params *p, const cub_groove_note *notes, int n,
                                const cub_groove_key *keys, cub_groove_handles *out);

/* The speed bound (ours): each stretch's arc length x its timing's and
 * the beat stop's steepest gain / its time is the wrist's peak speed;
 * where that exceeds peak_mm_s the stretch is drawn in about its first key
 * (keys, handles, lengths), so the wrist never runs faster, for any music. */
void cub_groove_stretch_limit(const cub_groove_params *p, const cub_groove_note *notes, int n,
                              cub_groove_key *keys, cub_groove_handles *h);

/* The point at u (0..1) of the cubic Bézier p0, p1, p2, p3. */
cub_groove_key cub_groove_bezier(const cub_groove_key pt[4], cub_q16 u);

typedef enum cub_groove_timing {
    CUB_GROOVE_UNIFORM, /* non-beat after non-beat: u = tau */
    CUB_GROOVE_EASE_IN, /* non-beat after a beat: starts at rest, speeds up */
    CUB_GROOVE_ACCENT   /* a beat note: fast start dropping quickly, gentle,
                           speeding up again, stopping at once at the end
                           (at rest on the next key) */
} cub_groove_timing;

/* The timing of the path during note i (from key i to key i+1). */
cub_groove_timing cub_groove_timing_of(const cub_groove_note *notes, int i);

/* The timing curve: the path parameter u (0..1) at time fraction tau
 * (0..1), monotone, u(0) = 0, u(1) = 1 (piecewise cubic Bézier in tau). */
cub_q16 cub_groove_timing_at(cub_groove_timing kind, cub_q16 tau);

/* The beat stretch (ours, docs/groove.md): the paths from a beat note's key
 * to the next beat note's key are one stretch; the accent runs over it by
 * arc length, the non-beat keys between passed at speed. A stretch also
 * starts at note 0 and every 16th note. [*first, *last] the keys of the
 * stretch holding the path during note i (i + 1 < n). */
void cub_groove_stretch_of(const cub_groove_note *notes, int n, int i, int *first, int *last);
/* The arc length of a path (mm, Q16: |B'| sampled 8 times, linear between). */
cub_q16 cub_groove_path_length(const cub_groove_key pt[4]);
/* The parameter u where the arc length along the path reaches s_mm, the
 * inverse of cub_groove_path_length's measure (the speed continuous). */
cub_q16 cub_groove_path_u(const cub_groove_key pt[4], cub_q16 s_mm);

/* ---- waist, head, left hand (SEEDS.md § 001, fig. 10) ----------------------- */

/* One turn of the waist (about the vertical) or of the head (a nod):
 * back to rest over [start_us, turn_us) (ease in and out, from from_deg),
 * then the swing to to_deg over [turn_us, end_us) (fast start, settling).
 * When start_us == turn_us (no note between two turns) the swing runs
 * from from_deg. Before start_us the previous turn's to_deg holds. */
typedef struct cub_groove_turn {
    int64_t start_us, turn_us, end_us;
    cub_q16 from_deg, to_deg;
} cub_groove_turn;

/* Fig. 10: a beat note of at least one beat turns to (intensity / 120) x
 * amount_deg x a direction alternating +-1; the notes before it since the
 * last turn (the seed's accumulate) are the time of the way back to rest.
 * end_us is the song's end (the last note's end). At most n turns. */
cub_err cub_groove_turns(const cub_groove_note *notes, int n, int64_t end_us, cub_q16 amount_deg,
                         cub_groove_turn *out, int *count);
/* The angle at t_us (degrees, Q16). */
cub_q16 cub_groove_turn_at(const cub_groove_turn *turns, int count, int64_t t_us);

/* ---- the plan of a song and the bear's pose ----------------------------------- */

/* Everything the motion needs, computed once per song (two passes: all
 * keys first, then the paths, as the seed's fig. 9). Arrays caller-owned. */
typedef struct cub_groove_plan {
    cub_groove_params params;
    const cub_groove_note *notes;
    int n;
    const cub_groove_key *keys;
    const cub_groove_handles *handles;
    const cub_groove_turn *waist, *head;
    int waist_count, head_count;
    int64_t end_us; /* the song's end: the last note holds until it */
} cub_groove_plan;

/* Caller-owned storage for cub_groove_plan_build: every array holds cap
 * entries (cap >= 2 x the song's MIDI notes + 1 is always enough). */
typedef struct cub_groove_store {
    int cap;
    cub_groove_note *notes;
    cub_groove_segment *segs;
    cub_groove_key *keys;
    cub_groove_handles *handles;
    cub_groove_turn *waist, *head;
    cub_groove_work *work;
} cub_groove_store;

/* Song -> plan: notes, segments (DP windows of window notes, 0: 48),
 * keys, handles, turns. seg_count and cost may be NULL. */
cub_err cub_groove_plan_build(const cub_groove_song *song, const cub_groove_pick *pick,
                              const cub_groove_params *p, int window, cub_groove_store *mem,
                              cub_groove_plan *out, int *seg_count, cub_groove_cost *cost);

/* The beat stop (ours): the music time t_us as the motion reads it. Every
 * meter beat stays where it is; between two beats the clock's speed rises
 * from 0 on the beat over params.stop_after of a beat, stays level, and
 * falls to 0 on the next beat over params.stop_before (each ramp a power
 * params.stop_power of the time from the beat). So every beat, inside a
 * long note too, is a short stop. */
int64_t cub_groove_clock(const cub_groove_plan *plan, int64_t t_us);

/* The right wrist in key space at t_us (mm): on the path of the note
 * sounding, along its timing curve; key 0 before the first note. */
cub_groove_key cub_groove_wrist_at(const cub_groove_plan *plan, int64_t t_us);

/* The left hand's offset from its home (mm; x outward, y up) at t_us: a
 * note longer than a beat reaches out and back; a note shorter than a
 * beat followed by a rest (staccato, ours) lifts during the note and drops
 * during the rest, accelerating, stopping at once at the next note. */
cub_groove_key cub_groove_left_at(const cub_groove_plan *plan, int64_t t_us);

/* Where the groove puts the motion on a skeleton: joints found by the
 * bear's names (Spine turns the waist, Head nods, RightArm / LeftArm head
 * two-bone arms); key space mapped about each wrist's home in the Chest's
 * frame, scaled by scale (the bear's arm is about 0.4 of a grown-up's). */
typedef struct cub_groove_rig {
    const cub_skeleton *skel;
    int spine, chest, head, right_arm, left_arm;
    cub_q16 scale;
} cub_groove_rig;

/* CUB_ERR_FORMAT naming no joint: the skeleton lacks one of the above. */
cub_err cub_groove_rig_bind(const cub_skeleton *skel, cub_groove_rig *out);

/* The bear's pose at t_us on the music clock: the rest pose with the
 * root at the skeleton's rest height (legs untouched: the feet stay
 * planted), the waist and head turned, both arms by analytic IK. */
cub_err cub_groove_pose_at(const cub_groove_plan *plan, const cub_groove_rig *rig, int64_t t_us,
                           cub_pose *out);

/* Fill a caller-initialised clip (cub_motion_clip_init on rig->skel): frame
 * f is the pose at t0_us + f x the clip's period. What the box calls for a
 * time range of a song (its intro, free bars, the cheer). */
cub_err cub_groove_clip_fill(const cub_groove_plan *plan, const cub_groove_rig *rig, int64_t t0_us,
                             cub_clip *clip);

#endif

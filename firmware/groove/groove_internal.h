/* groove's shared internals: the meter at a tick, a beat's length. */
#ifndef CUB_GROOVE_INTERNAL_H
#define CUB_GROOVE_INTERNAL_H

#include "cub/groove.h"

/* The time signature in force at tick; *cursor (may be NULL) remembers
 * where the last look-up ended, for ticks that only grow. */
cub_groove_meter groove_meter_at(const cub_groove_song *song, int32_t tick, int *cursor);
/* One beat of meter m in ticks (a quarter in 4/4, an eighth in 6/8). */
int32_t groove_beat_ticks(const cub_groove_song *song, cub_groove_meter m);
bool groove_is_drum(const cub_groove_midi_note *n);
/* The last note starting at or before t_us, -1 before the first. */
int groove_note_at(const cub_groove_note *notes, int n, int64_t t_us);
/* Where note i ends: the next note's start, the last one's end_us. */
int64_t groove_note_end(const cub_groove_note *notes, int n, int64_t end_us, int i);
/* tau in [0, 1] of t_us over [t0, t1) (1 for an empty span). */
cub_q16 groove_tau(int64_t t_us, int64_t t0, int64_t t1);
/* cub_groove_turns with the count-in first: before the melody's first
 * note, the meter's beats sway (groove_body.c). At most cap turns. */
cub_err groove_song_turns(const cub_groove_song *song, const cub_groove_note *notes, int n,
                          int64_t end_us, cub_q16 amount_deg, cub_groove_turn *out, int cap,
                          int *count);

/* The meter beat holding t_us as the beat stop sees it: its start and
 * length, and the stop's ramps there (fractions of the beat): the set's,
 * or in a slow beat with at most one key inside, the whole beat, straight
 * (groove_clock.c). False where the clock runs plain. */
typedef struct groove_beat {
    int64_t start_us, len_us;
    cub_q16 before, after;
    int power;
} groove_beat;
bool groove_beat_at(const cub_groove_params *p, const cub_groove_note *notes, int n, int64_t t_us,
                    groove_beat *out);

#endif

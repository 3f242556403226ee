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

#endif

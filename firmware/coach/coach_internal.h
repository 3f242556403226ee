/* coach internals shared by coach.c (the state machine), coach_out.c (the
 * actions and their log lines) and coach_sync.c (following the music). */
#ifndef CUB_COACH_INTERNAL_H
#define CUB_COACH_INTERNAL_H

#include "cub/coach.h"

/* Steps inside a state (cub_coach.phase). */
enum {
    COACH_PH_NONE = 0,
    COACH_PH_WAIT,  /* dance: the idle clip until the music reaches the move's tag */
    COACH_PH_MOVES, /* dance: a move's repetitions are playing */
    COACH_PH_OUTRO, /* dance: every move done, the music plays on to its end */
    COACH_PH_FIX,   /* correct: the correcting clip plays */
    COACH_PH_DEMO,  /* correct: the move again, slower */
};

/* Each appends one action and writes its log line. */
void coach_out_state(cub_coach *c, int32_t to, int32_t reason);
void coach_out_clip(cub_coach *c, int32_t clip, cub_q16 speed_q16, bool loop, int32_t reason);
void coach_out_speed(cub_coach *c, cub_q16 speed_q16, int32_t reason);
void coach_out_music(cub_coach *c, bool on, int32_t reason);
/* Hold (paused = true) or go on with the music; its clock holds too, so
 * the rate measurement starts afresh. */
void coach_music_pause(cub_coach *c, bool paused, int32_t reason);
/* Only when the hint changes; coach_out_hint shows no fault. */
void coach_out_hint(cub_coach *c, int32_t hint, int32_t reason);
void coach_out_fault_hint(cub_coach *c, int32_t hint, int32_t fault, int32_t reason);
/* A log line without an action (events the coach set aside). */
void coach_out_ignore(cub_coach *c, const cub_event *ev);
/* A verdict about the slower demonstration: the child watched it. */
void coach_out_watched(cub_coach *c, const cub_event *ev);

/* Note the music clock (starts the rate measurement); call on every input. */
void coach_sync_observe(cub_coach *c, int32_t music_ms);
/* The sync factor for a dance at song time pos_ms with its target tag
 * target_ms ahead, to be reached lead_ms of music early (the next move's
 * route); updates c->sync_q16 and c->rate_q16 and logs it. Keeps the
 * current factor when the music clock is unknown. */
cub_q16 coach_sync_at(cub_coach *c, int32_t pos_ms, int32_t target_ms, int32_t lead_ms,
                      int32_t music_ms);

#endif

/* director internals shared by director.c (the calls, the coach's actions,
 * the music) and director_route.c (requests, windows, leads, the player's
 * time). */
#ifndef CUB_DIRECTOR_INTERNAL_H
#define CUB_DIRECTOR_INTERNAL_H

#include "cub/director.h"

/* The clip's name for the log, "?" when unknown. */
const char *director_clip_name(const cub_director *d, int clip);
/* Carry out one ACT_CLIP of the coach at t_us: the judge's window, the
 * entry policy, the plan (or a cut). */
void director_request(cub_director *d, const cub_coach_action *a, int64_t t_us, int32_t music_ms);
/* Plan every move's lead_ms and rep_lead_ms (from the last frame of the
 * move before, of itself); one log line each. */
void director_plan_leads(cub_director *d);
/* The entry leads of the moves after an intro or a gap, from where the
 * player is now (kept while the player stands where it stood), and of the
 * groove of the span the music (music_ms) is in. */
void director_entry_leads(cub_director *d, int32_t music_ms);

/* director_keys.c: each move's key frame in its own clip and whether its
 * keys' mirror is a mistake (logged); at init, after the judge is known. */
void director_find_keys(cub_director *d);
/* Fill r's key moment (has_key, key_us, mirror_wrong, other) for a repetition of
 * move entered at entry_frame of its clip after wait_frames, at speed. */
void director_key_moment(const cub_director *d, int move, int32_t entry_frame, int32_t wait_frames,
                         cub_q16 speed, cub_judge_rep *r);

#endif

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
void director_request(cub_director *d, const cub_coach_action *a, int64_t t_us);
/* Plan every move's lead_ms and rep_lead_ms (from the last frame of the
 * move before, of itself); one log line each. */
void director_plan_leads(cub_director *d);
/* The entry leads of the moves after an intro or a gap, from where the
 * player is now (kept while the player stands where it stood). */
void director_entry_leads(cub_director *d);

#endif

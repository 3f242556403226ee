/* The director's calls. Each event or tick goes one way:
 *
 *   event/tick --> entry leads from where the player is --> coach
 *   coach's actions --> CLIP:  judge window, entry policy, plan or cut
 *                       SPEED: the player's speed
 *                       MUSIC_*, HINT: out[] for the app (music logged here)
 *                       STATE: nothing (the coach logged it)
 *
 * and the player's time (cub_director_advance, director_route.c) posts
 * clip ends and music tags back to the loop, for the coach. */
#include <string.h>

#include "director_internal.h"

#define DEFAULT_START_FRAMES 4

static void push_out(cub_director *d, int32_t what, int32_t hint, int32_t fault)
{
    if (d->out_count >= CUB_DIRECTOR_MAX_OUT) return; /* the coach gives at most as many */
    d->out[d->out_count++] = (cub_director_out){.what = what, .hint = hint, .fault = fault};
}

/* ---- the music, as asked of the app ---------------------------------------- */

static void music_start(cub_director *d, int64_t t_us)
{
    d->music_on = true;
    d->music_paused = false;
    d->music_start_us = t_us;
    cub_log_event(d->desc.coach.log, t_us, "music", "start", "song=\"%s\" bpm=%d length_ms=%d",
                  d->desc.song_name ? d->desc.song_name : "", d->desc.bpm,
                  d->desc.song_length_ms);
    push_out(d, CUB_DIRECTOR_MUSIC_START, 0, 0);
}

static void music_stop(cub_director *d)
{
    d->music_on = d->music_paused = false;
    push_out(d, CUB_DIRECTOR_MUSIC_STOP, 0, 0);
}

/* Hold the music or go on; only a change reaches the app. */
static void music_pause(cub_director *d, bool paused, int64_t t_us, int32_t music_ms)
{
    if (!d->music_on || paused == d->music_paused) return;
    d->music_paused = paused;
    cub_log_event(d->desc.coach.log, t_us, "music", paused ? "pause" : "resume", "music_ms=%d",
                  music_ms);
    push_out(d, paused ? CUB_DIRECTOR_MUSIC_PAUSE : CUB_DIRECTOR_MUSIC_RESUME, 0, 0);
}

/* ---- the coach's actions ------------------------------------------------- */

static void carry_out(cub_director *d, int64_t t_us, int32_t music_ms)
{
    d->out_count = 0;
    for (int i = 0; i < d->coach.action_count; i++) {
        const cub_coach_action *a = &d->coach.actions[i];
        switch (a->kind) {
        case CUB_COACH_ACT_CLIP: director_request(d, a, t_us, music_ms); break;
        case CUB_COACH_ACT_SPEED: cub_bridge_player_set_speed(&d->player, a->speed_q16); break;
        case CUB_COACH_ACT_MUSIC_START: music_start(d, t_us); break;
        case CUB_COACH_ACT_MUSIC_STOP: music_stop(d); break;
        case CUB_COACH_ACT_MUSIC_PAUSE: music_pause(d, true, t_us, music_ms); break;
        case CUB_COACH_ACT_MUSIC_RESUME: music_pause(d, false, t_us, music_ms); break;
        case CUB_COACH_ACT_HINT: push_out(d, CUB_DIRECTOR_HINT, a->hint, a->fault); break;
        default: break; /* states: logged by the coach */
        }
    }
}

/* ---- the calls --------------------------------------------------------------- */

size_t cub_director_mem_size(const cub_director_desc *desc)
{
    if (!desc || !desc->table) return 0;
    cub_bridge_player_desc pd = {.table = desc->table};
    return cub_bridge_player_mem_size(&pd);
}

static cub_err start_coach(cub_director *d, const cub_director_desc *desc, int64_t now_us)
{
    const int32_t n = desc->coach.move_count;
    const int32_t ng = desc->coach.groove_count;
    if (n < 0 || n > CUB_DIRECTOR_MAX_MOVES || (n > 0 && !desc->coach.moves)) return CUB_ERR_ARG;
    if (ng < 0 || ng > CUB_DIRECTOR_MAX_GROOVES || (ng > 0 && !desc->coach.grooves))
        return CUB_ERR_ARG;
    for (int32_t i = 0; i < n; i++) {
        d->moves[i] = desc->coach.moves[i];
        d->moves[i].lead_ms = d->moves[i].rep_lead_ms = d->moves[i].entry_lead_ms = 0;
    }
    for (int32_t i = 0; i < ng; i++) {
        d->grooves[i] = desc->coach.grooves[i];
        d->grooves[i].entry_lead_ms = 0;
    }
    cub_coach_desc cd = desc->coach;
    cd.moves = d->moves;
    cd.grooves = ng > 0 ? d->grooves : NULL;
    cub_err e = cub_coach_init(&d->coach, &cd, now_us);
    if (e) return e;
    /* The coach's first request (its idle clip) starts playback directly. */
    const cub_coach_action *a = &d->coach.actions[0];
    if (d->coach.action_count > 0 && a->kind == CUB_COACH_ACT_CLIP)
        e = cub_bridge_player_start(&d->player, a->clip, 0, a->speed_q16, a->loop);
    return e;
}

cub_err cub_director_init(cub_director *d, const cub_director_desc *desc, void *mem,
                          size_t mem_size, int64_t now_us)
{
    if (!d || !desc || !desc->table || desc->start_frames < 0 || desc->react_frames < 0)
        return CUB_ERR_ARG;
    memset(d, 0, sizeof *d);
    d->desc = *desc;
    if (!d->desc.start_frames) d->desc.start_frames = DEFAULT_START_FRAMES;
    if (!d->desc.react_frames) d->desc.react_frames = CUB_DIRECTOR_REACT_FRAMES;
    /* Searched routes on: director_request allows them per request where
     * the leads were planned through them (director_route.c). */
    cub_bridge_player_desc pd = {.table = desc->table};
    cub_err e = cub_bridge_player_init(&d->player, &pd, mem, mem_size);
    if (!e) e = start_coach(d, desc, now_us);
    if (e) return e;
    d->desc.coach = d->coach.desc; /* with the coach's defaults, and our moves */
    d->now_us = now_us;
    d->played_clip = d->requested_clip = d->lead_clip = -1;
    d->out_count = 0;
    director_plan_leads(d); /* the coach reads the moves through its desc */
    director_find_keys(d);
    return CUB_OK;
}

cub_event cub_director_scripted(const cub_director *d, const cub_event *ev)
{
    cub_event e = *ev;
    if (e.type == CUB_EV_VERDICT && e.a < 0) e.a = d && d->coach.move >= 0 ? d->coach.move : 0;
    return e;
}

cub_err cub_director_handle(cub_director *d, const cub_event *ev, int32_t music_ms)
{
    if (!d || !ev) return CUB_ERR_ARG;
    d->out_count = 0;
    cub_event e = cub_director_scripted(d, ev);
    director_entry_leads(d, music_ms);
    cub_err err = cub_coach_handle(&d->coach, &e, music_ms);
    if (!err) carry_out(d, e.t_us, music_ms);
    return err;
}

cub_err cub_director_tick(cub_director *d, int64_t now_us, int32_t music_ms)
{
    if (!d) return CUB_ERR_ARG;
    d->out_count = 0;
    director_entry_leads(d, music_ms);
    cub_err err = cub_coach_tick(&d->coach, now_us, music_ms);
    if (!err) carry_out(d, now_us, music_ms);
    return err;
}

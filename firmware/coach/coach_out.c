/* The coach's output: every action goes into the call's action queue and,
 * in the same words, into the event log, so that the log alone tells what
 * the bear was asked to do and why. */
#include <string.h>

#include "coach_internal.h"
#include "cub/judge.h"

static const char *const state_names[CUB_COACH_STATE_COUNT] = {
    "idle", "wake", "dance", "correct", "worried", "attract", "doze", "cheer", "paused",
};

static const char *const reason_names[CUB_COACH_WHY_COUNT] = {
    "init",  "start", "clap",     "stop",  "woke",    "intro",   "move",   "rep",
    "wrong", "right", "correct",  "demo",  "misses",  "worried", "calmed", "resume",
    "sync",  "outro", "song_end", "cheer", "cheered", "quiet",   "player", "idle",
    "camera", "moved_on", "away", "watched", "groove",
};

const char *cub_coach_state_name(int32_t state)
{
    return state >= 0 && state < CUB_COACH_STATE_COUNT ? state_names[state] : "?";
}

const char *cub_coach_reason_name(int32_t reason)
{
    return reason >= 0 && reason < CUB_COACH_WHY_COUNT ? reason_names[reason] : "?";
}

cub_err cub_coach_roles_by_name(const char *const *names, int32_t count, cub_coach_roles *roles)
{
    if (!names || count <= 0 || !roles) return CUB_ERR_ARG;
    struct {
        const char *name;
        int32_t *slot;
    } want[] = {
        {"idle", &roles->idle},
        {"wake_up", &roles->wake_up},
        {"wave", &roles->attract},
        {"doze", &roles->doze},
        {"head_shake", &roles->head_shake},
        {"watch_me", &roles->watch_me},
        {"worried", &roles->worried},
        {"cheer", &roles->cheer},
    };
    cub_err err = CUB_OK;
    for (size_t w = 0; w < sizeof want / sizeof want[0]; w++) {
        *want[w].slot = -1;
        for (int32_t i = 0; i < count; i++)
            if (names[i] && strcmp(names[i], want[w].name) == 0) *want[w].slot = i;
        if (*want[w].slot < 0) err = CUB_ERR_FORMAT;
    }
    return err;
}

/* ---- the action queue --------------------------------------------------- */

static cub_coach_action *push(cub_coach *c, int32_t kind, int32_t reason)
{
    if (c->action_count >= CUB_COACH_MAX_ACTIONS) {
        c->actions_dropped++;
        return NULL;
    }
    cub_coach_action *a = &c->actions[c->action_count++];
    memset(a, 0, sizeof *a);
    a->kind = kind;
    a->reason = reason;
    a->clip = -1;
    a->hint = CUB_COACH_HINT_NONE;
    a->from = a->to = -1;
    a->move = c->move;
    a->rep = c->move >= 0 ? c->rep : -1;
    return a;
}

/* A clip's name for the log, or its index when no names were given. */
static const char *clip_label(const cub_coach *c, int32_t clip, char buf[16])
{
    if (c->desc.clip_names && clip >= 0 && clip < c->desc.clip_count && c->desc.clip_names[clip])
        return c->desc.clip_names[clip];
    cub_log_format(buf, 16, "%d", clip);
    return buf;
}

/* " move=3 rep=1" while the coach is inside the song, else "". */
static const char *position(const cub_coach *c, char buf[40])
{
    buf[0] = '\0';
    if (c->move >= 0) cub_log_format(buf, 40, " move=%d rep=%d", c->move, c->rep);
    return buf;
}

void coach_out_state(cub_coach *c, int32_t to, int32_t reason)
{
    int32_t from = c->state;
    c->state = to;
    c->state_since_us = c->now_us;
    cub_coach_action *a = push(c, CUB_COACH_ACT_STATE, reason);
    if (a) {
        a->from = from;
        a->to = to;
    }
    char pos[40];
    cub_log_event(c->desc.log, c->now_us, "coach", "state", "from=%s to=%s reason=%s%s",
                  cub_coach_state_name(from), cub_coach_state_name(to),
                  cub_coach_reason_name(reason), position(c, pos));
}

void coach_out_clip(cub_coach *c, int32_t clip, cub_q16 speed_q16, bool loop, int32_t reason)
{
    c->clip = clip;
    c->speed_q16 = speed_q16;
    cub_coach_action *a = push(c, CUB_COACH_ACT_CLIP, reason);
    if (a) {
        a->clip = clip;
        a->speed_q16 = speed_q16;
        a->loop = loop;
    }
    char name[16], pos[40];
    cub_log_event(c->desc.log, c->now_us, "coach", "request",
                  "clip=%s speed=%q loop=%d reason=%s%s", clip_label(c, clip, name), speed_q16,
                  loop ? 1 : 0, cub_coach_reason_name(reason), position(c, pos));
}

void coach_out_speed(cub_coach *c, cub_q16 speed_q16, int32_t reason)
{
    c->speed_q16 = speed_q16;
    cub_coach_action *a = push(c, CUB_COACH_ACT_SPEED, reason);
    if (a) {
        a->clip = c->clip;
        a->speed_q16 = speed_q16;
    }
    char name[16], pos[40];
    cub_log_event(c->desc.log, c->now_us, "coach", "speed", "clip=%s speed=%q reason=%s%s",
                  clip_label(c, c->clip, name), speed_q16, cub_coach_reason_name(reason),
                  position(c, pos));
}

void coach_out_music(cub_coach *c, bool on, int32_t reason)
{
    c->music_on = on;
    c->anchor_ms = -1; /* a new clock: measure its rate afresh */
    c->rate_q16 = CUB_Q16_ONE;
    push(c, on ? CUB_COACH_ACT_MUSIC_START : CUB_COACH_ACT_MUSIC_STOP, reason);
    cub_log_event(c->desc.log, c->now_us, "coach", "music", "action=%s reason=%s",
                  on ? "start" : "stop", cub_coach_reason_name(reason));
}

void coach_music_pause(cub_coach *c, bool paused, int32_t reason)
{
    c->anchor_ms = -1; /* the clock stood still: measure the rate afresh */
    push(c, paused ? CUB_COACH_ACT_MUSIC_PAUSE : CUB_COACH_ACT_MUSIC_RESUME, reason);
    cub_log_event(c->desc.log, c->now_us, "coach", "music", "action=%s reason=%s",
                  paused ? "pause" : "resume", cub_coach_reason_name(reason));
}

static const char *hint_name(int32_t hint)
{
    return hint == CUB_COACH_HINT_COME_CLOSER ? "come_closer"
           : hint == CUB_COACH_HINT_CANT_SEE  ? "cant_see"
           : hint == CUB_COACH_HINT_WHERE     ? "where"
           : hint == CUB_COACH_HINT_STEP_BACK ? "step_back"
                                              : "none";
}

void coach_out_fault_hint(cub_coach *c, int32_t hint, int32_t fault, int32_t reason)
{
    if (hint < 0) fault = 0; /* a fault is about a move */
    if (hint == c->hint && fault == c->fault) return;
    c->hint = hint;
    c->fault = fault;
    cub_coach_action *a = push(c, CUB_COACH_ACT_HINT, reason);
    if (a) {
        a->hint = hint;
        a->fault = fault;
    }
    if (fault) {
        cub_judge_fault f = cub_judge_fault_of(fault);
        cub_log_event(c->desc.log, c->now_us, "coach", "hint",
                      "show=fault move=%d how=%s key=%s=%s reason=%s", hint,
                      cub_judge_how_name(f.how), cub_fuzzy_feature_name(f.feature),
                      cub_fuzzy_set_name(f.feature, f.set), cub_coach_reason_name(reason));
    } else if (hint >= 0) {
        cub_log_event(c->desc.log, c->now_us, "coach", "hint", "show=move move=%d reason=%s", hint,
                      cub_coach_reason_name(reason));
    } else {
        cub_log_event(c->desc.log, c->now_us, "coach", "hint", "show=%s reason=%s",
                      hint_name(hint), cub_coach_reason_name(reason));
    }
}

void coach_out_hint(cub_coach *c, int32_t hint, int32_t reason)
{
    coach_out_fault_hint(c, hint, 0, reason);
}

void coach_out_ignore(cub_coach *c, const cub_event *ev)
{
    cub_log_event(c->desc.log, c->now_us, "coach", "ignore", "event=%s a=%d b=%d state=%s move=%d",
                  cub_loop_event_name(ev->type), ev->a, ev->b, cub_coach_state_name(c->state),
                  c->move);
}

void coach_out_watched(cub_coach *c, const cub_event *ev)
{
    cub_log_event(c->desc.log, c->now_us, "coach", "watched", "move=%d result=%s fault=%d",
                  ev->a, ev->b ? "right" : "wrong", ev->c);
}

/* How the director carries out the coach's clip requests: where a clip is
 * entered, the correcting clip substituted when the other is sooner, the
 * judge's window for a repetition, the leads of the routes into the moves,
 * and the player's time with its switches, clip ends and music tags. */
#include "director_internal.h"

static cub_log *dlog(const cub_director *d)
{
    return d->desc.coach.log;
}

static const cub_clip *clip_of(const cub_director *d, int clip)
{
    return &d->desc.table->clips[clip].clip;
}

const char *director_clip_name(const cub_director *d, int clip)
{
    const cub_coach_desc *c = &d->desc.coach;
    if (clip < 0 || clip >= c->clip_count || !c->clip_names || !c->clip_names[clip]) return "?";
    return c->clip_names[clip];
}

/* ---- entering a clip ----------------------------------------------------- */

/* A move (its start, a repetition, a resume, a slower demonstration) is
 * entered at its first frames when a route gets there within 400 ms, so it
 * keeps its music time; anything else, a correction above all, by the
 * quickest switch. */
static bool enters_at_start(int32_t reason)
{
    return reason == CUB_COACH_WHY_MOVE || reason == CUB_COACH_WHY_REP ||
           reason == CUB_COACH_WHY_RESUME || reason == CUB_COACH_WHY_DEMO;
}

/* Where requests for this reason may enter their clip: a move at its first
 * frames; a correction at any frame of its front half close enough (d <
 * 0.4), not only at a tagged one: the quickest way in. */
static int start_frames(const cub_director *d, const cub_coach_action *a)
{
    if (enters_at_start(a->reason) || a->reason == CUB_COACH_WHY_GROOVE)
        return d->desc.start_frames;
    if (a->reason == CUB_COACH_WHY_CORRECT) return clip_of(d, a->clip)->frame_count / 2;
    return 0;
}

/* The two correcting clips do the same job: when the one the coach asked
 * for is only reachable later than react_frames and the other sooner, play
 * the other (the coach hears of its end under the name it asked for). */
static int other_correction(const cub_director *d, int clip)
{
    const cub_coach_roles *r = &d->desc.coach.roles;
    return clip == r->head_shake ? r->watch_me : clip == r->watch_me ? r->head_shake : -1;
}

static cub_err plan_sooner(cub_director *d, const cub_coach_action *a, cub_bridge_plan *plan,
                           int64_t t_us)
{
    cub_bridge_player *p = &d->player;
    cub_err err = cub_bridge_player_request(p, a->clip, a->speed_q16, a->loop, plan);
    int other = other_correction(d, a->clip);
    if (a->reason != CUB_COACH_WHY_CORRECT || other < 0 ||
        (!err && plan->total_frames <= d->desc.react_frames))
        return err;
    cub_bridge_plan alt;
    if (cub_bridge_player_request(p, other, a->speed_q16, a->loop, &alt) ||
        (!err && alt.total_frames >= plan->total_frames))
        return cub_bridge_player_request(p, a->clip, a->speed_q16, a->loop, plan);
    cub_log_event(dlog(d), t_us, "bridge", "substitute", "requested=%s played=%s reason=sooner",
                  director_clip_name(d, a->clip), director_clip_name(d, other));
    d->played_clip = other;
    d->requested_clip = a->clip;
    *plan = alt;
    return CUB_OK;
}

/* A correction must begin within the reaction (react_frames): when no
 * switch within the threshold gets into either correcting clip that soon,
 * enter the one chosen at its closest frame anyway and let the blend cover
 * the distance (a tween through other moves showed the correction 0.27 s
 * after the verdict). */
static cub_err plan_correction(cub_director *d, const cub_coach_action *a, cub_bridge_plan *plan,
                               int64_t t_us)
{
    cub_err err = plan_sooner(d, a, plan, t_us);
    if (a->reason != CUB_COACH_WHY_CORRECT || (!err && plan->total_frames <= d->desc.react_frames))
        return err;
    cub_bridge_player *p = &d->player;
    int clip = d->played_clip >= 0 ? d->played_clip : a->clip;
    cub_bridge_plan quick;
    cub_bridge_player_set_reach_frames(p, d->desc.react_frames);
    cub_err e = cub_bridge_player_request(p, clip, a->speed_q16, a->loop, &quick);
    cub_bridge_player_set_reach_frames(p, 0);
    if (e) return err; /* the player kept the plan it had */
    if (err || quick.total_frames < plan->total_frames)
        cub_log_event(dlog(d), t_us, "bridge", "reach", "to=%s@%d d=%q wait_frames=%d",
                      director_clip_name(d, clip), quick.step[0].to_frame, quick.step[0].d,
                      quick.wait_frames);
    *plan = quick;
    return CUB_OK;
}

/* ---- the judge's windows ------------------------------------------------- */

/* Tell the judge what the child should do now: a repetition of a move
 * (danced or resumed) opens a window as long as the clip plays at its
 * speed, plus a beat for a late child; anything else the coach asks for
 * (a correction, the idle clip) closes what was open. The slower
 * demonstration is watched, not judged (SEEDS.md § 000): it closes them
 * too, and the attempt after it (a resume) is judged. */
static void judge_clip(cub_director *d, const cub_coach_action *a, int64_t t_us,
                       const cub_bridge_plan *plan)
{
    cub_judge *j = d->desc.judge;
    if (!j) return;
    const int m = a->move;
    const bool is_rep = enters_at_start(a->reason) && m >= 0 && m < d->desc.coach.move_count &&
                        d->moves[m].clip == a->clip;
    const cub_director_keys *k = is_rep && d->desc.keys ? &d->desc.keys[m] : NULL;
    if (!k || k->count <= 0 || a->reason == CUB_COACH_WHY_DEMO) {
        cub_judge_cancel_reps(j);
        if (k && k->count > 0)
            cub_log_event(dlog(d), t_us, "judge", "watch", "move=%d rep=%d", m, a->rep);
        return;
    }
    const cub_clip *clip = clip_of(d, a->clip);
    int64_t speed = a->speed_q16 > 0 ? a->speed_q16 : CUB_Q16_ONE;
    int64_t clip_us = (int64_t)(clip->frame_count - 1) * clip->frame_ns / 1000;
    int64_t play_us = clip_us * CUB_Q16_ONE / speed;
    cub_judge_rep r = {.move = m, .rep = a->rep, .key_count = k->count,
                       .start_us = t_us, .end_us = t_us + play_us,
                       .beat_us = d->desc.bpm > 0 ? 60000000 / d->desc.bpm : 0};
    for (int i = 0; i < k->count && i < CUB_JUDGE_MAX_KEYS; i++) r.keys[i] = k->key[i];
    const cub_bridge_step *last = plan && plan->step_count > 0 ? &plan->step[plan->step_count - 1]
                                                               : NULL;
    director_key_moment(d, m, last ? last->to_frame : 0, plan ? plan->total_frames : 0,
                        (cub_q16)speed, &r);
    cub_err e = cub_judge_begin_rep(j, &r);
    if (e == CUB_ERR_FULL) { /* frames stopped coming: nothing closed the old ones */
        cub_judge_cancel_reps(j);
        e = cub_judge_begin_rep(j, &r);
    }
    if (e)
        cub_log_event(dlog(d), t_us, "judge", "error", "what=begin_rep move=%d rep=%d error=\"%s\"",
                      m, a->rep, cub_err_str(e));
    else if (r.has_key) /* when the bear shows the keys: the mistake shows there */
        cub_log_event(dlog(d), t_us, "judge", "window", "move=%d rep=%d key_ms=%d end_ms=%d", m,
                      a->rep, (int)(r.key_us / 1000), (int)(play_us / 1000));
}

static bool after_gap(const cub_director *d, int m);

/* Whether this request may take the table's searched route: where the
 * timing the coach plays to was planned through it. A move asked for at
 * the end of the one before: when its lead_ms was (route_in). A move
 * after a gap: its entry lead is planned from where the player stands,
 * routes and all. A resume into a running move has no lead: never.
 * Anything else is not timed to the music. */
static bool routes_allowed(const cub_director *d, const cub_coach_action *a)
{
    const int m = a->move;
    const bool entry = a->reason == CUB_COACH_WHY_MOVE || a->reason == CUB_COACH_WHY_RESUME;
    if (!entry || m < 0 || m >= d->desc.coach.move_count) return true;
    if (a->rep == 0 && after_gap(d, m)) return true;
    return a->reason == CUB_COACH_WHY_MOVE && d->route_in[m];
}

static bool plan_routed(const cub_bridge_plan *plan)
{
    return plan->step_count > 0 && plan->step[0].via == CUB_BRIDGE_ROUTE;
}

static const cub_coach_groove *groove_of(const cub_director *d, int clip)
{
    for (int32_t g = 0; g < d->desc.coach.groove_count; g++)
        if (d->desc.coach.grooves[g].clip == clip) return &d->desc.coach.grooves[g];
    return NULL;
}

static bool groove_clip(const cub_director *d, int clip)
{
    return groove_of(d, clip) != NULL;
}

/* Groove g's frame (Q16.16) when the music is at music_ms. */
static int64_t groove_clock_q16(const cub_director *d, const cub_coach_groove *g, int32_t music_ms)
{
    const int64_t into_ns = (int64_t)(music_ms - g->tag_ms) * 1000000;
    return into_ns * CUB_Q16_ONE / clip_of(d, g->clip)->frame_ns;
}

/* A groove's frame 0 is its span's start on the music clock: entered at
 * the frame the music has reached when the switch comes (the planner adds
 * the wait), so it plays on the beat, not as late as the wait. Without
 * music (none plays): at its start frames, as before. */
static void set_clock(cub_director *d, const cub_coach_action *a, int32_t music_ms)
{
    const cub_coach_groove *g = a->reason == CUB_COACH_WHY_GROOVE ? groove_of(d, a->clip) : NULL;
    if (!g || music_ms == CUB_COACH_NO_MUSIC) {
        cub_bridge_player_set_clock(&d->player, 0, 0);
        return;
    }
    cub_bridge_player_set_clock(&d->player, 1, groove_clock_q16(d, g, music_ms));
}

/* The log's word on a groove entered: how far the frame it shows now (the
 * switch's overshoot played on) trails the music now (ms; negative: ahead). */
static void log_groove_entry(const cub_director *d, int64_t t_us, int32_t music_ms,
                             const cub_bridge_step *s)
{
    const cub_coach_groove *g = groove_of(d, s->to_clip);
    if (!g || music_ms == CUB_COACH_NO_MUSIC || d->player.clip != s->to_clip) return;
    const int64_t shown_ms =
        (d->player.pos_q16 * (int64_t)clip_of(d, s->to_clip)->frame_ns / 1000000) >> 16;
    cub_log_event(dlog(d), t_us, "groove", "enter", "clip=%s frame=%d music_ms=%d late_ms=%d",
                  director_clip_name(d, s->to_clip), s->to_frame, music_ms,
                  (int)(music_ms - g->tag_ms - shown_ms));
}

/* A groove clip (a span no move teaches) has no tagged links to or from
 * the library's clips, so no chain reaches it and none leaves it: into it
 * and out of it, one direct switch within react_frames (direct_only): into
 * a start frame within the threshold, else the closest, and the blend
 * covers the distance. A tween through another move's frames on the way
 * (two frames of jumping jacks before the still intro) read as a twitch.
 * The music does not wait for the bear either way. */
static int reach_frames(const cub_director *d, const cub_coach_action *a)
{
    return groove_clip(d, a->clip) || groove_clip(d, d->player.clip) ? d->desc.react_frames : 0;
}

/* The music's time where the player stands, when the coach started the
 * music in this call (the intro's request; music_ms was read before it).
 * The app starts the music at the time of the event that started it, and
 * the player already stands at now_us, later by up to a tick when that
 * event was a clip's end within the last advance: the music has played
 * that much (0 for it put the intro's first frame a frame behind the
 * music, late_ms=33: docs/groove.md, session 37). */
static int32_t started_ms(const cub_director *d)
{
    const int64_t ms = (d->now_us - d->music_start_us) / 1000;
    return ms > 0 ? (int32_t)ms : 0;
}

void director_request(cub_director *d, const cub_coach_action *a, int64_t t_us, int32_t music_ms)
{
    cub_bridge_player_set_start_frames(&d->player, start_frames(d, a));
    const int reach = reach_frames(d, a);
    cub_bridge_player_set_reach_frames(&d->player, reach);
    cub_bridge_player_set_direct_only(&d->player, reach > 0);
    const int32_t clock_ms = music_ms == CUB_COACH_NO_MUSIC && d->music_on ? started_ms(d) : music_ms;
    set_clock(d, a, reach > 0 ? clock_ms : CUB_COACH_NO_MUSIC);
    d->played_clip = d->requested_clip = -1;
    cub_bridge_plan plan;
    cub_bridge_player_set_no_routes(&d->player, !routes_allowed(d, a));
    cub_err err = plan_correction(d, a, &plan, t_us);
    cub_bridge_player_set_no_routes(&d->player, 0); /* the leads' previews take them */
    cub_bridge_player_set_reach_frames(&d->player, 0);
    cub_bridge_player_set_direct_only(&d->player, 0);
    cub_bridge_player_set_clock(&d->player, 0, 0);
    judge_clip(d, a, t_us, err ? NULL : &plan);
    if (!err) {
        cub_log_event(dlog(d), t_us, "bridge", "plan", "to=%s steps=%d wait_frames=%d via=%s",
                      director_clip_name(d, a->clip), plan.step_count, plan.wait_frames,
                      plan_routed(&plan)    ? "route"
                      : plan.step_count > 1 ? "tween"
                                            : "direct");
        return;
    }
    /* No chain of bridge frames leads there: cut, and say so. */
    cub_log_event(dlog(d), t_us, "bridge", "cut", "from=%s to=%s@0 reason=\"%s\"",
                  director_clip_name(d, d->player.clip), director_clip_name(d, a->clip),
                  cub_err_str(err));
    cub_bridge_player_start(&d->player, a->clip, 0, a->speed_q16, a->loop);
}

/* ---- leads ---------------------------------------------------------------- */

/* Song ms by which a move should be asked for before its tag: what the
 * planned route takes, less the content it skips (a route may land past
 * the clip's first frame). */
static int32_t route_lead_ms(const cub_director *d, const cub_bridge_plan *plan, int move)
{
    const cub_coach_move *mv = &d->moves[move];
    const cub_clip *clip = clip_of(d, mv->clip);
    int64_t speed = mv->speed_q16 ? mv->speed_q16 : CUB_Q16_ONE;
    int64_t route_ms = (int64_t)plan->total_frames * clip->frame_ns / 1000000 * CUB_Q16_ONE / speed;
    int to_frame = plan->step_count > 0 ? plan->step[plan->step_count - 1].to_frame : 0;
    int64_t skip_ms = (int64_t)mv->span_ms / mv->reps * to_frame / (clip->frame_count - 1);
    return (int32_t)(route_ms - skip_ms);
}

/* The lead of a route into move `to` from `q` (its from-part), or 0 when
 * there is none; *routed (may be NULL): the plan is a searched route. */
static int32_t lead_from(cub_director *d, cub_bridge_query q, int to, bool *routed)
{
    q.to_clip = d->moves[to].clip;
    q.start_frames = d->desc.start_frames;
    cub_bridge_plan plan;
    cub_err e = cub_bridge_player_preview(&d->player, &q, &plan);
    if (routed) *routed = !e && plan_routed(&plan);
    return e ? 0 : route_lead_ms(d, &plan, to);
}

/* From the last frame of clip `from` (where a repetition ends). */
static int32_t lead_from_end(cub_director *d, int from, int to, int no_routes, bool *routed)
{
    int frames = clip_of(d, from)->frame_count;
    cub_bridge_query q = {.from_clip = from, .pos_q16 = (int64_t)(frames - 1) << 16,
                          .no_routes = no_routes};
    return lead_from(d, q, to, routed);
}

/* What the last repetition of move m can give a route's frames: it ends
 * early by lead at rep / (rep - lead) of its speed. Half the coach's sync
 * bound for that; the other half follows the music's clock (a card 5 %
 * off) and what the repetition began late. */
static int32_t route_fit_ms(const cub_director *d, int m)
{
    const cub_coach_move *mv = &d->moves[m];
    const int64_t half = cub_coach_sync_bound(d->desc.coach.sync_bound_q16) / 2;
    return (int32_t)((int64_t)mv->span_ms / mv->reps * half / (CUB_Q16_ONE + half));
}

static int32_t abs32(int32_t v)
{
    return v < 0 ? -v : v;
}

/* Move i's lead_ms from the end of move i - 1: through the table's route
 * when there is one and the music has time for it (route_fit_ms, or it
 * is no longer than the lead without it), else without routes. The
 * request at that end is then planned the same way (route_in). */
static int32_t move_lead_ms(cub_director *d, int i)
{
    const int from = d->moves[i - 1].clip;
    bool routed = false;
    const int32_t lead = lead_from_end(d, from, i, 0, &routed);
    d->route_in[i] = routed;
    if (!routed) return lead;
    const int32_t plain = lead_from_end(d, from, i, 1, NULL), fit = route_fit_ms(d, i - 1);
    d->route_in[i] = abs32(lead) <= fit || abs32(lead) <= abs32(plain);
    cub_log_event(dlog(d), d->now_us, "music", "route",
                  "move=%d from=%s lead_ms=%d fit_ms=%d plain_ms=%d taken=%d", i,
                  director_clip_name(d, from), lead, fit, plain, d->route_in[i]);
    return d->route_in[i] ? lead : plain;
}

/* A repetition, and a move that follows the one before at once, is asked
 * for when the repetition before ends: plan those routes now, from its last
 * frame, so the coach can end that repetition early (or late) by their
 * length. */
void director_plan_leads(cub_director *d)
{
    for (int i = 0; i < d->desc.coach.move_count; i++) {
        cub_coach_move *mv = &d->moves[i];
        /* A repetition has no searched route (a route joins two clips). */
        mv->rep_lead_ms = lead_from_end(d, mv->clip, i, 0, NULL);
        mv->lead_ms = i > 0 ? move_lead_ms(d, i) : 0;
        cub_log_event(dlog(d), d->now_us, "music", "lead",
                      "move=%d clip=%s lead_ms=%d rep_lead_ms=%d", i,
                      director_clip_name(d, mv->clip), mv->lead_ms, mv->rep_lead_ms);
    }
}

/* A move the coach may wait for: after the intro, or after a gap. */
static bool after_gap(const cub_director *d, int m)
{
    const cub_coach_move *prev = m > 0 ? &d->moves[m - 1] : NULL;
    return d->moves[m].tag_ms > (prev ? prev->tag_ms + prev->span_ms : 0);
}

/* Only inside a song (or waking into one) may the coach begin a move. */
static bool in_song(const cub_coach *c)
{
    return c->state == CUB_COACH_WAKE || c->state == CUB_COACH_DANCE ||
           c->state == CUB_COACH_CORRECT || c->state == CUB_COACH_WORRIED ||
           c->state == CUB_COACH_PAUSED;
}

/* Music ms until the player reaches its next frame, rounded up: a switch
 * leaves the current clip at an upcoming frame, not at once, so a plan
 * that waits k frames lands k frames after that one (without it the move
 * after a groove came a frame late: docs/groove.md, session 36). A clip
 * that has ended holds its last frame: 0. */
static int32_t upcoming_ms(const cub_director *d)
{
    const cub_bridge_player *p = &d->player;
    const int64_t last_q16 = (int64_t)(clip_of(d, p->clip)->frame_count - 1) << 16;
    int64_t next_q16 = (p->pos_q16 + 0xFFFF) & ~(int64_t)0xFFFF;
    if (!p->loop && next_q16 > last_q16) next_q16 = last_q16;
    const int64_t ahead_q16 = next_q16 > p->pos_q16 ? next_q16 - p->pos_q16 : 0;
    const int64_t speed = p->speed_q16 > 0 ? p->speed_q16 : CUB_Q16_ONE;
    const int64_t ns = ahead_q16 * (int64_t)clip_of(d, p->clip)->frame_ns / speed;
    return (int32_t)((ns + 999999) / 1000000);
}

/* Whether the coach is past reading groove i's entry lead in this call:
 * it reads it only until it asks for the span's groove (coach.c,
 * join_groove), and a dancing coach that has asked for it forgets that
 * only in a call that began in another state (a correction's or a pause's
 * resume: wait_clip), whose lead is looked at then. So the preview, one a
 * tick through the whole span, is skipped while the groove plays. */
static bool lead_settled(const cub_director *d, int32_t i)
{
    return d->coach.state == CUB_COACH_DANCE && d->coach.groove == i;
}

/* The bridge into the groove of the span the music is in, from where the
 * player is now, as its request would take it (the reach, one direct
 * switch, on the music's clock): the switch's wait. The coach asks for a
 * span it joins late that much before the beat it joins on. */
static void groove_entry_lead(cub_director *d, int32_t music_ms)
{
    if (music_ms == CUB_COACH_NO_MUSIC) return;
    for (int32_t i = 0; i < d->desc.coach.groove_count; i++) {
        cub_coach_groove *g = &d->grooves[i];
        if (music_ms < g->tag_ms || music_ms - g->tag_ms >= g->span_ms) continue;
        if (lead_settled(d, i)) return;
        cub_bridge_query q = {.from_clip = -1, .to_clip = g->clip,
                              .reach_frames = d->desc.react_frames, .direct_only = 1,
                              .on_clock = 1, .clock_q16 = groove_clock_q16(d, g, music_ms)};
        cub_bridge_plan plan;
        const int64_t frame_ns = clip_of(d, g->clip)->frame_ns;
        g->entry_lead_ms = cub_bridge_player_preview(&d->player, &q, &plan)
                               ? 0
                               : upcoming_ms(d) + (int32_t)(plan.wait_frames * frame_ns / 1000000);
        return;
    }
}

/* The coach reads these while it waits for a move's tag: the route from
 * where the player is now. The player stands still within a call, so one
 * look per place it stands in is enough (a groove's, on the music's clock,
 * is looked at on every call). */
void director_entry_leads(cub_director *d, int32_t music_ms)
{
    const cub_bridge_player *p = &d->player;
    if (!in_song(&d->coach)) return;
    groove_entry_lead(d, music_ms);
    if (p->clip == d->lead_clip && p->pos_q16 == d->lead_pos_q16 && p->loop == d->lead_loop)
        return;
    d->lead_clip = p->clip;
    d->lead_pos_q16 = p->pos_q16;
    d->lead_loop = p->loop;
    /* Out of a groove clip the request will take the reach (reach_frames):
     * preview it the same way, so the move is asked for that much before
     * its tag and its first frame lands on its beat. */
    const int reach = groove_clip(d, p->clip) ? d->desc.react_frames : 0;
    cub_bridge_query here = {.from_clip = -1, .reach_frames = reach, .direct_only = reach > 0};
    const int32_t upcoming = upcoming_ms(d);
    for (int m = 0; m < d->desc.coach.move_count; m++)
        if (after_gap(d, m)) d->moves[m].entry_lead_ms = upcoming + lead_from(d, here, m, NULL);
}

/* ---- the player's time ----------------------------------------------------- */

static void post(cub_loop *loop, int64_t t_us, int32_t type, int32_t a, int32_t b)
{
    cub_event ev = {.t_us = t_us, .type = type, .a = a, .b = b};
    cub_loop_post(loop, &ev);
}

/* Entering the clip of the move being danced: its music tag, the song time
 * of the frame shown now (SEEDS.md § 000, "Music sync"). Now, not at the
 * switch: the music clock was read at the end of this advance, and the
 * coach compares the two. */
static void post_music_tag(cub_director *d, cub_loop *loop, int64_t now_us, int32_t music_ms,
                           const cub_bridge_step *s)
{
    const cub_coach *c = &d->coach;
    int m = c->move;
    if (c->state != CUB_COACH_DANCE || m < 0 || m >= d->desc.coach.move_count) return;
    const cub_coach_move *mv = &d->moves[m];
    if (s->to_clip != mv->clip || d->player.clip != mv->clip) return;
    int64_t intervals_q16 = (int64_t)(clip_of(d, mv->clip)->frame_count - 1) << 16;
    int64_t rep_ms = mv->span_ms / mv->reps;
    int64_t in_rep_ms = rep_ms * d->player.pos_q16 / intervals_q16;
    int32_t tag = mv->tag_ms + (int32_t)(rep_ms * c->rep + in_rep_ms);
    cub_log_event(dlog(d), now_us, "music", "tag", "move=%d tag_ms=%d music_ms=%d", m, tag,
                  music_ms);
    post(loop, now_us, CUB_EV_MUSIC_TAG, m, tag);
}

static void on_switch(cub_director *d, cub_loop *loop, int64_t t_us, int64_t now_us,
                      int32_t music_ms, const cub_bridge_step *s)
{
    cub_log_event(dlog(d), t_us, "bridge", "switch", "from=%s@%d to=%s@%d d=%q via=%s",
                  director_clip_name(d, s->from_clip), s->from_frame,
                  director_clip_name(d, s->to_clip), s->to_frame, s->d,
                  s->via == CUB_BRIDGE_TWEEN ? "tween"
                  : s->via == CUB_BRIDGE_ROUTE ? "route"
                                               : "direct");
    d->switch_count++;
    d->last_switch = *s;
    log_groove_entry(d, t_us, music_ms, s);
    post_music_tag(d, loop, now_us, music_ms, s);
}

static void on_done(cub_director *d, cub_loop *loop, int64_t t_us, int clip)
{
    int asked = clip == d->played_clip ? d->requested_clip : clip;
    cub_log_event(dlog(d), t_us, "bridge", "done", "clip=%s", director_clip_name(d, clip));
    post(loop, t_us, CUB_EV_CLIP_DONE, asked, 0);
}

cub_err cub_director_advance(cub_director *d, cub_loop *loop, int64_t now_us, int32_t music_ms)
{
    if (!d || !loop) return CUB_ERR_ARG;
    cub_bridge_event ev[CUB_DIRECTOR_MAX_PLAYER_EVENTS];
    int n = 0;
    int64_t dt = now_us > d->now_us ? now_us - d->now_us : 0;
    d->now_us += dt;
    cub_err err = cub_bridge_player_advance(&d->player, dt, ev, CUB_DIRECTOR_MAX_PLAYER_EVENTS, &n);
    for (int i = 0; !err && i < n; i++) {
        int64_t t = now_us - dt + ev[i].t_us;
        if (ev[i].type == CUB_BRIDGE_EV_SWITCH)
            on_switch(d, loop, t, now_us, music_ms, &ev[i].step);
        else if (ev[i].type == CUB_BRIDGE_EV_DONE && !ev[i].looped)
            on_done(d, loop, t, ev[i].clip);
    }
    return err;
}

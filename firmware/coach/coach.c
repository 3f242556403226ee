/* The coach's state machine (ARCHITECTURE.md "Coach states"):
 *
 *   idle --START/clap--> wake --wake_up done--> dance --wrong--> correct
 *   correct: correcting clip, then the move at demo speed (a wrong
 *            verdict's fault, "The other arm!", is the hint meanwhile; the
 *            move's own words come back with the dance). The child only
 *            watches the demonstration (SEEDS.md § 000): its verdicts are
 *            logged as watched, never acted on; when it ends --> dance
 *            where the music is, and that attempt is judged as usual
 *            (wrong: corrected again, so the demonstration repeats until
 *            the child gets it; N wrong in a row --> worried --done-->
 *            correct). A right verdict during the correcting clip -->
 *            dance (inside the same move's span, found from the music
 *            clock); a correcting clip ending after the music has left
 *            the move's span --> dance with the music
 *   dance --song end--> cheer --done--> idle
 *   dance/correct/worried --camera lost--> paused --camera back--> dance
 *            (the music holds meanwhile; the dance resumes where it is)
 *   dance/correct/worried --child out of view AWAY_PAUSE_MS--> paused
 *            ("Where are you?") --child back--> dance, as for the camera;
 *            verdicts while nobody is in view are set aside, and are no
 *            interaction: a child gone for good brings attract, then doze
 *   idle/dance/correct/worried/paused --quiet attract_after--> attract
 *   attract --quiet doze_after--> doze;   attract/doze --START/clap--> wake
 *   any --STOP--> idle
 *
 * Every change goes out through coach_out.c (actions + log lines). */
#include <string.h>

#include "coach_internal.h"

#define ATTRACT_DEFAULT_MS 20000u
#define DOZE_DEFAULT_MS 60000u
#define WORRIED_DEFAULT 3u
#define DEMO_SPEED_DEFAULT ((cub_q16)45875) /* 0.7 */

/* ---- checking the desc --------------------------------------------------- */

static bool clip_ok(const cub_coach_desc *d, int32_t clip)
{
    return clip >= 0 && clip < d->clip_count;
}

static cub_err check_desc(const cub_coach_desc *d)
{
    /* A groove song (issue 23) has no move: its spans are all it dances. */
    const bool groove_song = d->move_count == 0 && d->groove_count > 0;
    if ((!d->moves && !groove_song) || (d->move_count <= 0 && !groove_song) || d->clip_count <= 0)
        return CUB_ERR_ARG;
    const cub_coach_roles *r = &d->roles;
    const int32_t roles[] = {r->idle,       r->wake_up,  r->attract, r->doze,
                             r->head_shake, r->watch_me, r->worried, r->cheer};
    for (size_t i = 0; i < sizeof roles / sizeof roles[0]; i++)
        if (!clip_ok(d, roles[i])) return CUB_ERR_ARG;
    int64_t prev_end_ms = 0;
    for (int32_t i = 0; i < d->move_count; i++) {
        const cub_coach_move *m = &d->moves[i];
        if (!clip_ok(d, m->clip) || m->reps < 2 || m->span_ms <= 0 || m->speed_q16 < 0)
            return CUB_ERR_ARG;
        if (m->tag_ms < prev_end_ms) return CUB_ERR_ARG; /* tags go back or moves overlap */
        prev_end_ms = (int64_t)m->tag_ms + m->span_ms;
        if (prev_end_ms > INT32_MAX) return CUB_ERR_ARG;
    }
    if (d->groove_count < 0 || (d->groove_count > 0 && !d->grooves)) return CUB_ERR_ARG;
    for (int32_t i = 0; i < d->groove_count; i++) {
        const cub_coach_groove *g = &d->grooves[i];
        if (!clip_ok(d, g->clip) || g->span_ms <= 0 || g->beats < 0 || g->beats > g->span_ms)
            return CUB_ERR_ARG;
    }
    if (d->doze_after_ms <= d->attract_after_ms || d->demo_speed_q16 < 0) return CUB_ERR_ARG;
    return CUB_OK;
}

/* ---- song positions ------------------------------------------------------ */

static const cub_coach_move *cur_move(const cub_coach *c)
{
    return &c->desc.moves[c->move];
}

/* Song time at which repetition rep of move m starts (rep == reps: its end). */
static int32_t rep_start_ms(const cub_coach_move *m, int32_t rep)
{
    return m->tag_ms + (int32_t)((int64_t)m->span_ms * rep / m->reps);
}

static int32_t move_end_ms(const cub_coach_move *m)
{
    return m->tag_ms + m->span_ms;
}

static cub_q16 move_speed(const cub_coach *c, int32_t m, cub_q16 factor_q16)
{
    cub_q16 base = c->desc.moves[m].speed_q16 ? c->desc.moves[m].speed_q16 : CUB_Q16_ONE;
    return cub_fx_mul(base, factor_q16);
}

/* The song time now: the audio clock, or the loop clock since the music
 * started when the app gives no audio clock. */
static int64_t song_now_ms(const cub_coach *c, int32_t music_ms)
{
    return music_ms >= 0 ? music_ms : (c->now_us - c->music_start_us) / 1000;
}

static bool in_song(const cub_coach *c)
{
    return (c->state == CUB_COACH_DANCE || c->state == CUB_COACH_CORRECT ||
            c->state == CUB_COACH_WORRIED) &&
           c->phase != COACH_PH_OUTRO;
}

static void leave_song(cub_coach *c)
{
    c->move = -1;
    c->rep = 0;
    c->phase = COACH_PH_NONE;
    c->misses = 0;
    c->tag_pending = false;
    c->show_again = false;
    c->fix = 0;
    c->groove = c->join_groove = -1;
}

/* ---- entering states ----------------------------------------------------- */

static void go_idle(cub_coach *c, int32_t reason)
{
    coach_out_state(c, CUB_COACH_IDLE, reason);
    if (c->music_on) coach_out_music(c, false, reason);
    leave_song(c);
    coach_out_clip(c, c->desc.roles.idle, CUB_Q16_ONE, true, CUB_COACH_WHY_IDLE);
    if (c->hint >= 0) coach_out_hint(c, CUB_COACH_HINT_NONE, reason);
    c->quiet_since_us = c->now_us;
}

static void go_resting(cub_coach *c, int32_t to, int32_t clip, int32_t reason)
{
    coach_out_state(c, to, reason);
    if (c->music_on) coach_out_music(c, false, reason);
    leave_song(c);
    coach_out_clip(c, clip, CUB_Q16_ONE, true, reason);
    if (c->hint >= 0) coach_out_hint(c, CUB_COACH_HINT_NONE, reason);
}

static void go_wake(cub_coach *c, int32_t reason)
{
    coach_out_state(c, CUB_COACH_WAKE, reason);
    coach_out_clip(c, c->desc.roles.wake_up, CUB_Q16_ONE, false, reason);
}

static void show_move_hint(cub_coach *c, int32_t reason)
{
    if (c->player_in_view) coach_out_hint(c, c->move, reason);
}

/* The dance of repetition rep of move m aims at the next tag: the next
 * repetition's start, or after the last the move's end. It should get
 * there this much early, so that the route on (back to the clip's start,
 * or into the next move when that follows at once) shows the next tag's
 * frame on time. Bounded by half a repetition. */
/* A lead of move mv kept within half a repetition either way. */
static int32_t bounded_lead_ms(const cub_coach_move *mv, int32_t lead)
{
    const int32_t half_rep = mv->span_ms / mv->reps / 2;
    return lead < -half_rep ? -half_rep : lead > half_rep ? half_rep : lead;
}

static int32_t sync_lead_ms(const cub_coach *c, int32_t m, int32_t rep)
{
    const cub_coach_move *mv = &c->desc.moves[m];
    int32_t lead = 0;
    if (rep + 1 < mv->reps)
        lead = mv->rep_lead_ms;
    else if (m + 1 < c->desc.move_count && c->desc.moves[m + 1].tag_ms <= move_end_ms(mv))
        lead = c->desc.moves[m + 1].lead_ms; /* after a gap, the wait has its own lead */
    return bounded_lead_ms(mv, lead);
}

/* The player reached a frame of move m at song time pos_ms: the speed that
 * meets the music at the next tag. */
static cub_q16 sync_move(cub_coach *c, int32_t pos_ms, int32_t music_ms)
{
    const cub_coach_move *mv = cur_move(c);
    const int32_t target_ms = c->rep + 1 < mv->reps ? rep_start_ms(mv, c->rep + 1) : move_end_ms(mv);
    return coach_sync_at(c, pos_ms, target_ms, sync_lead_ms(c, c->move, c->rep), music_ms);
}

/* Start repetition rep of move m now. It plays at the sync factor of the
 * moment until the player reaches its first frame (a bridge, a tween may
 * lie between) and the app posts that frame's music tag: the sync then. */
static void begin_move(cub_coach *c, int32_t m, int32_t rep, int32_t reason)
{
    c->move = m;
    c->rep = rep;
    c->show_again = false;
    c->fix = 0;
    c->groove = c->join_groove = -1;
    c->phase = COACH_PH_MOVES;
    c->tag_pending = true;
    coach_out_clip(c, cur_move(c)->clip, move_speed(c, m, c->sync_q16), false, reason);
    show_move_hint(c, reason);
}

/* While waiting for move m's tag: begin it once the music is that close
 * to the tag that the route there (entry_lead_ms) lands on it. */
static bool time_to_begin(const cub_coach *c, int32_t m, int32_t music_ms)
{
    const cub_coach_move *mv = &c->desc.moves[m];
    return song_now_ms(c, music_ms) + bounded_lead_ms(mv, mv->entry_lead_ms) >= mv->tag_ms;
}

/* ---- groove spans (issue 23) ---------------------------------------------- */

/* The groove span the music is in at song time now_ms; -1 when none. */
static int32_t groove_at(const cub_coach *c, int64_t now_ms)
{
    for (int32_t g = 0; g < c->desc.groove_count; g++) {
        const cub_coach_groove *s = &c->desc.grooves[g];
        if (now_ms >= s->tag_ms && now_ms - s->tag_ms < s->span_ms) return g;
    }
    return -1;
}

/* The bridge into span s, kept within one of its beats. */
static int64_t groove_lead_ms(const cub_coach_groove *s)
{
    const int64_t beat_ms = s->beats > 0 ? s->span_ms / s->beats : 0;
    return s->entry_lead_ms < 0 ? 0 : s->entry_lead_ms > beat_ms ? beat_ms : s->entry_lead_ms;
}

/* When span s, found at song time now_ms, is joined: at once when it began
 * at most CUB_COACH_GROOVE_LATE_MS ago; later on its first beat that the
 * bridge into it still reaches, when a whole beat of the span is left
 * after that beat; -1: never. The beats are the span's integer division
 * (beat k at tag + span * k / beats), so any machine picks the same. */
static int64_t join_at_ms(const cub_coach_groove *s, int64_t now_ms)
{
    if (now_ms - s->tag_ms < CUB_COACH_GROOVE_LATE_MS) return now_ms;
    if (s->beats <= 0) return -1;
    const int64_t reach_ms = now_ms + groove_lead_ms(s) - s->tag_ms; /* > 0: into the span */
    const int64_t k = (reach_ms * s->beats + s->span_ms - 1) / s->span_ms; /* ceil */
    if (k >= s->beats) return -1;
    return s->tag_ms + (int64_t)s->span_ms * k / s->beats;
}

/* While no move plays (waiting for a tag, the outro): the groove of the
 * span the music is in, once per span, when its join comes; false while
 * there is none to ask for. The join is chosen when the coach first finds
 * itself in the span, and kept: the bridge's lead moves with the player. */
static bool join_groove(cub_coach *c, int32_t music_ms)
{
    const int64_t now_ms = song_now_ms(c, music_ms);
    const int32_t g = groove_at(c, now_ms);
    if (g < 0 || g == c->groove) return false;
    const cub_coach_groove *s = &c->desc.grooves[g];
    if (g != c->join_groove) {
        c->join_groove = g;
        c->join_ms = (int32_t)join_at_ms(s, now_ms);
    }
    if (c->join_ms < 0 || now_ms + groove_lead_ms(s) < c->join_ms) return false;
    c->groove = g;
    coach_out_clip(c, s->clip, CUB_Q16_ONE, false, CUB_COACH_WHY_GROOVE);
    return true;
}

/* While no move plays: the span's groove when it is joined now, else the
 * idle clip (and the groove later, from the tick, on its beat). */
static void wait_clip(cub_coach *c, int32_t reason, int32_t music_ms)
{
    c->groove = c->join_groove = -1;
    if (!join_groove(c, music_ms)) coach_out_clip(c, c->desc.roles.idle, CUB_Q16_ONE, true, reason);
}

/* Move m starts now, or, when the song has an intro or a gap before it,
 * after the idle clip once the music reaches its tag. (Between adjacent
 * moves a dance slightly ahead of the music goes on: the sync slows it.) */
static void begin_or_wait(cub_coach *c, int32_t m, int32_t reason, int32_t music_ms)
{
    c->move = m;
    c->rep = 0;
    const int32_t tag_ms = c->desc.moves[m].tag_ms;
    const int32_t prev_end_ms = m > 0 ? move_end_ms(&c->desc.moves[m - 1]) : 0;
    if (tag_ms <= prev_end_ms || time_to_begin(c, m, music_ms)) {
        begin_move(c, m, 0, reason);
        return;
    }
    c->phase = COACH_PH_WAIT;
    c->tag_pending = false;
    wait_clip(c, m == 0 ? CUB_COACH_WHY_INTRO : CUB_COACH_WHY_IDLE, music_ms);
    show_move_hint(c, reason);
}

static void go_outro(cub_coach *c, int32_t music_ms)
{
    c->phase = COACH_PH_OUTRO;
    c->tag_pending = false;
    wait_clip(c, CUB_COACH_WHY_OUTRO, music_ms);
    if (c->hint >= 0) coach_out_hint(c, CUB_COACH_HINT_NONE, CUB_COACH_WHY_OUTRO);
}

static void start_dance(cub_coach *c)
{
    c->move = c->desc.move_count > 0 ? 0 : -1;
    c->rep = 0;
    c->misses = 0;
    c->sync_q16 = CUB_Q16_ONE;
    coach_out_state(c, CUB_COACH_DANCE, CUB_COACH_WHY_WOKE);
    coach_out_music(c, true, CUB_COACH_WHY_WOKE);
    c->music_start_us = c->now_us;
    c->away_since_us = c->now_us; /* a child not in view yet has the grace too */
    /* The audio clock the app passed was read before this start. A groove
     * song has nothing to wait for: the outro from the first bar. */
    if (c->desc.move_count == 0)
        go_outro(c, CUB_COACH_NO_MUSIC);
    else
        begin_or_wait(c, 0, CUB_COACH_WHY_MOVE, CUB_COACH_NO_MUSIC);
}

/* A wrong verdict: the correcting clip at once (head shake and watch me in
 * turn), then the demonstration. */
static void go_correct(cub_coach *c)
{
    if (c->state != CUB_COACH_CORRECT) coach_out_state(c, CUB_COACH_CORRECT, CUB_COACH_WHY_WRONG);
    c->phase = COACH_PH_FIX;
    c->tag_pending = false;
    int32_t clip = (c->corrections & 1u) ? c->desc.roles.watch_me : c->desc.roles.head_shake;
    c->corrections++;
    coach_out_clip(c, clip, CUB_Q16_ONE, false, CUB_COACH_WHY_CORRECT);
}

static void demo(cub_coach *c)
{
    c->phase = COACH_PH_DEMO;
    cub_q16 speed = cub_fx_mul(move_speed(c, c->move, CUB_Q16_ONE), c->desc.demo_speed_q16);
    coach_out_clip(c, cur_move(c)->clip, speed, false, CUB_COACH_WHY_DEMO);
}

static void go_worried(cub_coach *c)
{
    c->misses = 0;
    coach_out_state(c, CUB_COACH_WORRIED, CUB_COACH_WHY_MISSES);
    c->phase = COACH_PH_NONE;
    coach_out_clip(c, c->desc.roles.worried, CUB_Q16_ONE, false, CUB_COACH_WHY_WORRIED);
}

/* A right verdict ends the correction. The music played on meanwhile, so
 * the dance resumes where the music is: the nearest repetition start of
 * the move it is in (normally the corrected move: each move lasts at least
 * two repetitions, seed 000 § Choreography). */
static void resume(cub_coach *c, int32_t music_ms, int32_t why)
{
    int32_t m = c->move, rep = c->rep;
    const int32_t last = c->desc.move_count - 1;
    if (m < 0) { /* a groove song: no move to go back to */
        coach_out_state(c, CUB_COACH_DANCE, why);
        go_outro(c, music_ms);
        return;
    }
    if (music_ms >= 0 && music_ms < c->desc.moves[m].tag_ms) { /* the intro, a gap */
        coach_out_state(c, CUB_COACH_DANCE, why);
        begin_or_wait(c, m, CUB_COACH_WHY_RESUME, music_ms);
        return;
    }
    if (music_ms >= 0) {
        while (m < last && c->desc.moves[m + 1].tag_ms <= music_ms)
            m++;
        const cub_coach_move *mv = &c->desc.moves[m];
        int64_t into_ms = (int64_t)music_ms - mv->tag_ms;
        rep = into_ms <= 0 ? 0 : (int32_t)((into_ms * mv->reps + mv->span_ms / 2) / mv->span_ms);
    }
    if (rep < c->desc.moves[m].reps) {
        c->move = m;
        c->rep = rep;
        coach_out_state(c, CUB_COACH_DANCE, why);
        begin_move(c, m, rep, CUB_COACH_WHY_RESUME);
    } else if (m < last) { /* the move is (nearly) over: on to the next */
        c->move = m + 1;
        c->rep = 0;
        coach_out_state(c, CUB_COACH_DANCE, why);
        begin_or_wait(c, m + 1, CUB_COACH_WHY_RESUME, music_ms);
    } else {
        c->move = m;
        c->rep = c->desc.moves[m].reps - 1;
        coach_out_state(c, CUB_COACH_DANCE, why);
        go_outro(c, music_ms);
    }
}

/* ---- events -------------------------------------------------------------- */

static bool resting(const cub_coach *c)
{
    return c->state == CUB_COACH_IDLE || c->state == CUB_COACH_ATTRACT ||
           c->state == CUB_COACH_DOZE;
}

static void on_button(cub_coach *c, int32_t button)
{
    if (button == CUB_BUTTON_START && resting(c))
        go_wake(c, CUB_COACH_WHY_START);
    else if (button == CUB_BUTTON_STOP && c->state != CUB_COACH_IDLE)
        go_idle(c, CUB_COACH_WHY_STOP);
}

/* A move's last repetition is judged until a beat after the next move
 * began (a late child still counts), so its wrong verdict comes when the
 * coach has moved on: while the next move's first repetition plays, or
 * the coach waits for it, that verdict is still the move just left's. */
static bool just_left(const cub_coach *c, int32_t m)
{
    return c->state == CUB_COACH_DANCE && m >= 0 && m == c->move - 1 &&
           ((c->phase == COACH_PH_MOVES && c->rep == 0) || c->phase == COACH_PH_WAIT);
}

/* What to fix, from a wrong verdict's fault: shown instead of the move's
 * words from the correction it starts until the dance resumes (begin_move
 * shows the move's words again). One short line at a time: most children
 * cannot read yet and hear the hint spoken; the move's own words were
 * shown while it was danced, the slower demonstration shows the move, and
 * the fault is what the child must change in it. */
static void show_fault(cub_coach *c, int32_t fault)
{
    if (!fault) return;
    c->fix = fault;
    if (c->player_in_view) coach_out_fault_hint(c, c->move, fault, CUB_COACH_WHY_WRONG);
}

static void on_verdict(cub_coach *c, const cub_event *ev, int32_t music_ms)
{
    if (!c->player_in_view) { /* nobody to correct or to credit */
        coach_out_ignore(c, ev);
        return;
    }
    if (c->phase == COACH_PH_DEMO) { /* the child watches; the attempt after counts */
        coach_out_watched(c, ev);
        return;
    }
    if (!ev->b && just_left(c, ev->a)) {
        /* back to it: corrected like any other, and shown again once
         * though its music is over (then the dance goes on where the
         * music is) */
        c->move = ev->a;
        c->rep = c->desc.moves[ev->a].reps - 1;
        c->phase = COACH_PH_MOVES;
        c->show_again = true;
        if (!ev->c) show_move_hint(c, CUB_COACH_WHY_WRONG); /* else its fault, below */
    }
    const bool about_this_move = in_song(c) && ev->a == c->move;
    if (ev->b) {
        c->misses = 0;
        if (about_this_move && (c->state == CUB_COACH_CORRECT || c->state == CUB_COACH_WORRIED))
            resume(c, music_ms, CUB_COACH_WHY_RIGHT);
        return;
    }
    const bool dancing = c->state == CUB_COACH_DANCE && c->phase == COACH_PH_MOVES;
    if (!about_this_move || !(dancing || c->state == CUB_COACH_CORRECT)) {
        coach_out_ignore(c, ev);
        return;
    }
    if (++c->misses >= (int32_t)c->desc.worried_after)
        go_worried(c);
    else if (c->phase != COACH_PH_FIX) /* never cut a head shake short */
        go_correct(c);
    show_fault(c, ev->c);
}

static bool correcting(const cub_coach *c)
{
    return c->state == CUB_COACH_CORRECT || c->state == CUB_COACH_WORRIED;
}

/* The music has played past the end of the move being corrected. */
static bool music_left_move(const cub_coach *c, int32_t music_ms)
{
    return music_ms >= 0 && c->move >= 0 && music_ms >= move_end_ms(cur_move(c));
}

static void on_clip_done(cub_coach *c, const cub_event *ev, int32_t music_ms)
{
    if (ev->a != c->clip) { /* a clip already replaced, or a looping one */
        coach_out_ignore(c, ev);
        return;
    }
    switch (c->state) {
    case CUB_COACH_WAKE: start_dance(c); break;
    case CUB_COACH_DANCE:
        if (c->phase == COACH_PH_WAIT || c->phase == COACH_PH_OUTRO) /* a groove ended */
            coach_out_clip(c, c->desc.roles.idle, CUB_Q16_ONE, true, CUB_COACH_WHY_IDLE);
        if (c->phase != COACH_PH_MOVES) break;
        if (c->rep + 1 < cur_move(c)->reps)
            begin_move(c, c->move, c->rep + 1, CUB_COACH_WHY_REP);
        else if (c->move + 1 < c->desc.move_count)
            begin_or_wait(c, c->move + 1, CUB_COACH_WHY_MOVE, music_ms);
        else
            go_outro(c, music_ms);
        break;
    case CUB_COACH_CORRECT:
        if (c->phase == COACH_PH_DEMO) /* watched: now the attempt, with the music */
            resume(c, music_ms, CUB_COACH_WHY_WATCHED);
        else if (music_left_move(c, music_ms) && !c->show_again)
            resume(c, music_ms, CUB_COACH_WHY_MOVED_ON);
        else
            demo(c);
        c->show_again = false;
        break;
    case CUB_COACH_WORRIED:
        coach_out_state(c, CUB_COACH_CORRECT, CUB_COACH_WHY_CALMED);
        if (music_left_move(c, music_ms))
            resume(c, music_ms, CUB_COACH_WHY_MOVED_ON);
        else
            demo(c);
        break;
    case CUB_COACH_CHEER: go_idle(c, CUB_COACH_WHY_CHEERED); break;
    default: break;
    }
}

/* The player reached a frame of move a (its first, or a later one when the
 * route entered past it), at song time b: set the speed that meets the
 * music at the next tag. Once per entry into the move's clip. */
static void on_music_tag(cub_coach *c, const cub_event *ev, int32_t music_ms)
{
    if (c->state != CUB_COACH_DANCE || c->phase != COACH_PH_MOVES || ev->a != c->move ||
        !c->tag_pending || music_ms < 0) {
        coach_out_ignore(c, ev);
        return;
    }
    c->tag_pending = false;
    cub_q16 factor = sync_move(c, ev->b, music_ms);
    coach_out_speed(c, move_speed(c, c->move, factor), CUB_COACH_WHY_SYNC);
}

/* Out of view: nobody (come closer) or a child too close to be seen
 * whole (step back: the judge told so, CUB_EV_PLAYER b = 1). */
static int32_t away_hint(const cub_coach *c)
{
    return c->too_close ? CUB_COACH_HINT_STEP_BACK : CUB_COACH_HINT_COME_CLOSER;
}

/* The camera (why CAMERA) or the child (AWAY) went mid-song: hold the
 * music and the dance, say so. The outro (every move danced, the music
 * playing to its end) pauses for the camera too. */
static void pause_song(cub_coach *c, int32_t why)
{
    c->paused_phase = c->phase;
    c->paused_for = why;
    coach_out_state(c, CUB_COACH_PAUSED, why);
    coach_music_pause(c, true, why);
    c->phase = COACH_PH_NONE;
    c->tag_pending = false;
    coach_out_clip(c, c->desc.roles.idle, CUB_Q16_ONE, true, why);
    coach_out_hint(c, why == CUB_COACH_WHY_AWAY ? (c->too_close ? CUB_COACH_HINT_STEP_BACK : CUB_COACH_HINT_WHERE)
                                                : CUB_COACH_HINT_CANT_SEE,
                   why);
}

static void resume_song(cub_coach *c, int32_t music_ms, int32_t why)
{
    coach_music_pause(c, false, why);
    c->away_since_us = c->now_us; /* a child still missing gets the grace again */
    coach_out_hint(c, c->player_in_view ? CUB_COACH_HINT_NONE : away_hint(c), why);
    if (c->paused_phase == COACH_PH_OUTRO) {
        coach_out_state(c, CUB_COACH_DANCE, why);
        go_outro(c, music_ms);
        return;
    }
    resume(c, music_ms, why);
}

/* The child has been out of view long enough mid-song to pause it (the
 * outro plays on: every move is danced). */
static bool away_too_long(const cub_coach *c)
{
    return !c->player_in_view && in_song(c) &&
           c->now_us - c->away_since_us >= (int64_t)CUB_COACH_AWAY_PAUSE_MS * 1000;
}

static void on_player(cub_coach *c, bool in_view, bool too_close, int32_t music_ms)
{
    bool was_away = !c->player_in_view;
    c->player_in_view = in_view;
    c->too_close = !in_view && too_close;
    if (!in_view) {
        if (!was_away) c->away_since_us = c->now_us;
        if (c->state != CUB_COACH_PAUSED)
            coach_out_hint(c, away_hint(c), CUB_COACH_WHY_PLAYER);
        else if (c->paused_for == CUB_COACH_WHY_AWAY)
            coach_out_hint(c, c->too_close ? CUB_COACH_HINT_STEP_BACK : CUB_COACH_HINT_WHERE, CUB_COACH_WHY_PLAYER);
        return;
    }
    if (c->state == CUB_COACH_PAUSED && c->paused_for == CUB_COACH_WHY_AWAY) {
        resume_song(c, music_ms, CUB_COACH_WHY_PLAYER);
        return;
    }
    if (c->hint == CUB_COACH_HINT_COME_CLOSER || c->hint == CUB_COACH_HINT_STEP_BACK)
        coach_out_fault_hint(c, in_song(c) ? c->move : CUB_COACH_HINT_NONE,
                             correcting(c) ? c->fix : 0, CUB_COACH_WHY_PLAYER);
    if (c->state == CUB_COACH_DOZE)
        go_resting(c, CUB_COACH_ATTRACT, c->desc.roles.attract, CUB_COACH_WHY_PLAYER);
}

static void on_camera(cub_coach *c, const cub_event *ev, int32_t music_ms)
{
    const bool singing = c->state == CUB_COACH_DANCE || c->state == CUB_COACH_CORRECT ||
                         c->state == CUB_COACH_WORRIED;
    if (!ev->a && singing)
        pause_song(c, CUB_COACH_WHY_CAMERA);
    else if (ev->a && c->state == CUB_COACH_PAUSED && c->paused_for == CUB_COACH_WHY_CAMERA)
        resume_song(c, music_ms, CUB_COACH_WHY_CAMERA);
    else
        coach_out_ignore(c, ev);
}

static void on_song_end(cub_coach *c)
{
    c->music_on = false; /* it ended by itself: nothing to stop */
    if (c->state != CUB_COACH_DANCE && c->state != CUB_COACH_CORRECT &&
        c->state != CUB_COACH_WORRIED)
        return;
    coach_out_state(c, CUB_COACH_CHEER, CUB_COACH_WHY_SONG_END);
    leave_song(c);
    coach_out_clip(c, c->desc.roles.cheer, CUB_Q16_ONE, false, CUB_COACH_WHY_CHEER);
    if (c->hint >= 0) coach_out_hint(c, CUB_COACH_HINT_NONE, CUB_COACH_WHY_SONG_END);
}

/* ---- the public calls ---------------------------------------------------- */

cub_err cub_coach_init(cub_coach *c, const cub_coach_desc *desc, int64_t now_us)
{
    if (!c || !desc) return CUB_ERR_ARG;
    cub_coach_desc d = *desc;
    if (!d.attract_after_ms) d.attract_after_ms = ATTRACT_DEFAULT_MS;
    if (!d.doze_after_ms) d.doze_after_ms = DOZE_DEFAULT_MS;
    if (!d.worried_after) d.worried_after = WORRIED_DEFAULT;
    if (!d.demo_speed_q16) d.demo_speed_q16 = DEMO_SPEED_DEFAULT;
    if (d.worried_after > INT32_MAX) return CUB_ERR_ARG;
    cub_err err = check_desc(&d);
    if (err) return err;
    memset(c, 0, sizeof *c);
    c->desc = d;
    c->state = CUB_COACH_IDLE;
    c->move = -1;
    c->clip = -1;
    c->groove = c->join_groove = c->join_ms = -1;
    c->speed_q16 = c->sync_q16 = c->rate_q16 = CUB_Q16_ONE;
    c->player_in_view = true; /* no "come closer" until told nobody is there */
    c->hint = CUB_COACH_HINT_NONE;
    c->fault = 0;
    c->now_us = c->quiet_since_us = c->state_since_us = now_us;
    c->anchor_ms = -1;
    coach_out_clip(c, d.roles.idle, CUB_Q16_ONE, true, CUB_COACH_WHY_IDLE);
    return CUB_OK;
}

cub_err cub_coach_handle(cub_coach *c, const cub_event *ev, int32_t music_ms)
{
    if (!c || !ev) return CUB_ERR_ARG;
    c->action_count = 0; /* even on error: no stale actions to redo */
    const bool names_move = ev->type == CUB_EV_VERDICT || ev->type == CUB_EV_MUSIC_TAG;
    if (names_move && (ev->a < 0 || ev->a >= c->desc.move_count)) return CUB_ERR_RANGE;
    if (ev->t_us > c->now_us) c->now_us = ev->t_us;
    coach_sync_observe(c, music_ms);
    const bool interaction = ev->type == CUB_EV_BUTTON_DOWN || ev->type == CUB_EV_CLAP ||
                             (ev->type == CUB_EV_VERDICT && c->player_in_view) ||
                             (ev->type == CUB_EV_PLAYER && ev->a);
    if (interaction) c->quiet_since_us = c->now_us;
    switch (ev->type) {
    case CUB_EV_BUTTON_DOWN: on_button(c, ev->a); break;
    case CUB_EV_CLAP:
        if (resting(c)) go_wake(c, CUB_COACH_WHY_CLAP);
        break;
    case CUB_EV_VERDICT: on_verdict(c, ev, music_ms); break;
    case CUB_EV_PLAYER: on_player(c, ev->a != 0, ev->b != 0, music_ms); break;
    case CUB_EV_CLIP_DONE: on_clip_done(c, ev, music_ms); break;
    case CUB_EV_MUSIC_TAG: on_music_tag(c, ev, music_ms); break;
    case CUB_EV_SONG_END: on_song_end(c); break;
    case CUB_EV_CAMERA: on_camera(c, ev, music_ms); break;
    default: break;
    }
    return CUB_OK;
}

cub_err cub_coach_tick(cub_coach *c, int64_t now_us, int32_t music_ms)
{
    if (!c) return CUB_ERR_ARG;
    c->action_count = 0;
    if (now_us > c->now_us) c->now_us = now_us;
    coach_sync_observe(c, music_ms);
    if (c->state == CUB_COACH_DANCE && c->phase == COACH_PH_WAIT &&
        time_to_begin(c, c->move, music_ms))
        begin_move(c, c->move, 0, CUB_COACH_WHY_MOVE);
    const bool waiting = c->phase == COACH_PH_WAIT || c->phase == COACH_PH_OUTRO;
    if (c->state == CUB_COACH_DANCE && waiting) join_groove(c, music_ms);
    if (away_too_long(c)) pause_song(c, CUB_COACH_WHY_AWAY);
    const int64_t quiet_ms = (c->now_us - c->quiet_since_us) / 1000;
    switch (c->state) {
    case CUB_COACH_IDLE:
    case CUB_COACH_DANCE:
    case CUB_COACH_CORRECT:
    case CUB_COACH_WORRIED:
    case CUB_COACH_PAUSED:
        if (quiet_ms >= c->desc.attract_after_ms)
            go_resting(c, CUB_COACH_ATTRACT, c->desc.roles.attract, CUB_COACH_WHY_QUIET);
        break;
    case CUB_COACH_ATTRACT:
        if (quiet_ms >= c->desc.doze_after_ms)
            go_resting(c, CUB_COACH_DOZE, c->desc.roles.doze, CUB_COACH_WHY_QUIET);
        break;
    default: break;
    }
    return CUB_OK;
}

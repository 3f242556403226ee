/* The dance glue (see dance.h). */
#include "dance.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PCM_FRAMES 4096
/* What the audio device holds before the speaker: the music clock counts
 * frames handed to SDL, which run about one buffer ahead (board.h). */
#define AUDIO_LATENCY_FRAMES 1024
#define MAX_PLAYER_EVENTS 16
#define START_FRAMES 4 /* a move's "beginning": its first frames */
/* A correction must be on screen within 6 ticks (200 ms); a plan counts
 * whole frames from the next one, so keep a tick for the frame under way. */
#define REACT_FRAMES 5

static const char *clip_name(const cub_dance *d, int clip)
{
    return clip >= 0 && clip < d->cl.lib.clip_count ? d->cl.lib.clips[clip].name : "?";
}

/* The music clock in song milliseconds, or CUB_COACH_NO_MUSIC. */
static int32_t music_ms(const cub_dance *d)
{
    if (!d->music_started) return CUB_COACH_NO_MUSIC;
    int64_t us = cub_music_clock_us(d->music);
    if (d->audio_open) {
        us -= (int64_t)AUDIO_LATENCY_FRAMES * 1000000 / cub_music_rate(d->music);
        if (us < 0) us = 0;
    }
    return (int32_t)(us / 1000);
}

/* ---- the coach's actions ------------------------------------------------ */

/* A move (its start, a repetition, a resume, a slower demonstration) is
 * entered at its first frames when a route gets there within 400 ms, so it
 * keeps its music time; anything else, a correction above all, by the
 * quickest switch. */
static int enters_at_start(int32_t reason)
{
    return reason == CUB_COACH_WHY_MOVE || reason == CUB_COACH_WHY_REP ||
           reason == CUB_COACH_WHY_RESUME || reason == CUB_COACH_WHY_DEMO;
}

/* The two correcting clips do the same job: when the one the coach asked
 * for is only reachable later than REACT_FRAMES and the other sooner, play
 * the other (the coach hears of its end under the name it asked for). */
static int other_correction(const cub_dance *d, int clip)
{
    const cub_coach_roles *r = &d->coach.desc.roles;
    return clip == r->head_shake ? r->watch_me : clip == r->watch_me ? r->head_shake : -1;
}

static cub_err plan_correction(cub_dance *d, const cub_coach_action *a, cub_bridge_plan *plan,
                               int64_t t_us)
{
    cub_err err = cub_bridge_player_request(&d->player, a->clip, a->speed_q16, a->loop, plan);
    int other = other_correction(d, a->clip);
    if (a->reason != CUB_COACH_WHY_CORRECT || other < 0 ||
        (!err && plan->total_frames <= REACT_FRAMES))
        return err;
    cub_bridge_plan alt;
    if (cub_bridge_player_request(&d->player, other, a->speed_q16, a->loop, &alt) ||
        (!err && alt.total_frames >= plan->total_frames))
        return cub_bridge_player_request(&d->player, a->clip, a->speed_q16, a->loop, plan);
    cub_log_event(d->log, t_us, "bridge", "substitute", "requested=%s played=%s reason=sooner",
                  clip_name(d, a->clip), clip_name(d, other));
    d->played_clip = other;
    d->requested_clip = a->clip;
    *plan = alt;
    return CUB_OK;
}

/* Tell the judge what the child should do now: a repetition of a move
 * (danced, resumed or demonstrated) opens a window as long as the clip
 * plays at its speed, plus a beat for a late child; anything else the
 * coach asks for (a correction, the idle clip) closes what was open. */
static void judge_clip(cub_dance *d, const cub_coach_action *a, int64_t t_us)
{
    if (!d->watch) return;
    const int m = a->move;
    const int is_rep = enters_at_start(a->reason) && m >= 0 && m < d->song.move_count &&
                       d->moves[m].clip == a->clip;
    if (!is_rep) {
        cub_watch_cancel_reps(d->watch);
        return;
    }
    const cub_song_move *sm = &d->song.moves[m];
    const cub_clip *clip = &d->cl.lib.clips[a->clip].clip;
    int64_t speed = a->speed_q16 > 0 ? a->speed_q16 : CUB_Q16_ONE;
    int64_t play_us = (int64_t)(clip->frame_count - 1) * clip->frame_ns / 1000 * CUB_Q16_ONE / speed;
    cub_judge_rep r = {.move = m, .rep = a->rep, .key_count = sm->key_count,
                       .start_us = t_us, .end_us = t_us + play_us,
                       .beat_us = d->song.bpm > 0 ? 60000000 / d->song.bpm : 0};
    for (int k = 0; k < sm->key_count && k < CUB_JUDGE_MAX_KEYS; k++)
        r.keys[k] = (cub_judge_key){.feature = sm->keys[k].feature, .set = sm->keys[k].set};
    cub_err e = cub_watch_begin_rep(d->watch, &r);
    if (e == CUB_ERR_FULL) { /* frames stopped coming: nothing closed the old ones */
        cub_watch_cancel_reps(d->watch);
        e = cub_watch_begin_rep(d->watch, &r);
    }
    if (e)
        cub_log_event(d->log, t_us, "judge", "error", "what=begin_rep move=%d rep=%d error=\"%s\"",
                      m, a->rep, cub_err_str(e));
}

static void request_clip(cub_dance *d, const cub_coach_action *a, int64_t t_us)
{
    judge_clip(d, a, t_us);
    /* A correction may enter its clip at any frame of its front half that is
     * close enough (d < 0.4), not only at a tagged one: the quickest way in. */
    int front_half = d->cl.lib.clips[a->clip].clip.frame_count / 2;
    cub_bridge_player_set_start_frames(&d->player, enters_at_start(a->reason) ? START_FRAMES
                                                   : a->reason == CUB_COACH_WHY_CORRECT ? front_half
                                                                                        : 0);
    d->played_clip = d->requested_clip = -1;
    cub_bridge_plan plan;
    cub_err err = plan_correction(d, a, &plan, t_us);
    if (!err) {
        cub_log_event(d->log, t_us, "bridge", "plan", "to=%s steps=%d wait_frames=%d via=%s",
                      clip_name(d, a->clip), plan.step_count, plan.wait_frames,
                      plan.step_count > 1 ? "tween" : "direct");
        return;
    }
    /* No chain of bridge frames leads there: cut, and say so. */
    cub_log_event(d->log, t_us, "bridge", "cut", "from=%s to=%s@0 reason=\"%s\"",
                  clip_name(d, d->player.clip), clip_name(d, a->clip), cub_err_str(err));
    cub_bridge_player_start(&d->player, a->clip, 0, a->speed_q16, a->loop);
}

static void start_music(cub_dance *d, int64_t t_us)
{
    if (cub_music_play(d->music) != CUB_OK) return;
    d->music_started = 1;
    d->music_paused = 0;
    d->song_end_sent = 0;
    d->pull_origin_us = t_us;
    cub_log_event(d->log, t_us, "music", "start", "song=\"%s\" bpm=%d length_ms=%lld",
                  d->song.name, d->song.bpm, (long long)(cub_song_length_us(&d->song) / 1000));
}

/* Hold the music (its clock too) or go on; rendered music starts counting
 * its due frames again from where it held. */
static void pause_music(cub_dance *d, int paused, int64_t t_us)
{
    if (!d->music_started || paused == d->music_paused) return;
    cub_music_pause(d->music, paused);
    d->music_paused = paused;
    if (paused)
        d->paused_at_us = t_us;
    else
        d->pull_origin_us += t_us - d->paused_at_us;
    cub_log_event(d->log, t_us, "music", paused ? "pause" : "resume", "music_ms=%d",
                  music_ms(d));
}

/* ---- what the TV shows -------------------------------------------------- */

/* A move's icon is the move's own pose, so every move a content maker adds
 * has one and nobody draws icon images: the clip's most telling frame,
 * taken as the one farthest from its first frame (sum of squared joint
 * displacements with the root's travel taken out), since a move's clip
 * starts from the neutral stance it returns to and peaks at the pose that
 * names it (the clap with the paws together, the arms up of the stretch).
 * Found once per hint change (a few hundred forward passes), not per frame. */
static void telling_pose(cub_dance *d, const cub_clip *clip, float *out)
{
    const cub_skeleton *skel = clip->skel;
    cub_vec3 first[CUB_MOTION_MAX_JOINTS];
    double best = -1.0;
    for (int k = 0; k < clip->frame_count; k++) {
        int64_t t_us = (int64_t)k * clip->frame_ns / 1000;
        if (cub_motion_sample(clip, t_us, CUB_MOTION_CLAMP, &d->pose) ||
            cub_motion_forward(skel, &d->pose, d->world_mm, NULL))
            return;
        if (k == 0) memcpy(first, d->world_mm, sizeof(cub_vec3) * (size_t)skel->joint_count);
        double dist = 0.0;
        for (int j = 0; j < skel->joint_count; j++) {
            double dx = (double)(d->world_mm[j].x - d->world_mm[0].x) - (first[j].x - first[0].x);
            double dy = (double)(d->world_mm[j].y - d->world_mm[0].y) - (first[j].y - first[0].y);
            double dz = (double)(d->world_mm[j].z - d->world_mm[0].z) - (first[j].z - first[0].z);
            dist += dx * dx + dy * dy + dz * dz;
        }
        if (dist > best) {
            best = dist;
            cub_motion_world_to_float(d->world_mm, skel->joint_count, out);
        }
    }
}

static void show_hint(cub_dance *d, int32_t hint)
{
    d->hint = hint;
    if (hint < 0 || hint >= d->song.move_count || hint == d->icon_move) return;
    int clip = d->song.moves[hint].clip_index;
    d->icon_move = -1;
    if (clip < 0 || clip >= d->cl.lib.clip_count) return;
    telling_pose(d, &d->cl.lib.clips[clip].clip, d->icon_xyz);
    d->icon_move = hint;
}

const char *cub_dance_hint_text(const cub_dance *d)
{
    if (d->hint == CUB_COACH_HINT_COME_CLOSER) return "Come closer!";
    if (d->hint == CUB_COACH_HINT_CANT_SEE) return "I can't see you!";
    if (d->hint < 0 || d->hint >= d->song.move_count) return NULL;
    return d->song.moves[d->hint].hint[0] ? d->song.moves[d->hint].hint : NULL;
}

const float *cub_dance_icon_xyz(const cub_dance *d)
{
    return d->hint >= 0 && d->hint == d->icon_move ? d->icon_xyz : NULL;
}

float cub_dance_progress(const cub_dance *d)
{
    int32_t ms = music_ms(d);
    int64_t len_us = cub_song_length_us(&d->song);
    if (ms == CUB_COACH_NO_MUSIC || ms < 0 || len_us <= 0) return -1.0f;
    float p = (float)((double)ms * 1000.0 / (double)len_us);
    return p > 1.0f ? 1.0f : p;
}

static void execute_actions(cub_dance *d, int64_t t_us)
{
    for (int i = 0; i < d->coach.action_count; i++) {
        const cub_coach_action *a = &d->coach.actions[i];
        switch (a->kind) {
        case CUB_COACH_ACT_CLIP: request_clip(d, a, t_us); break;
        case CUB_COACH_ACT_SPEED: cub_bridge_player_set_speed(&d->player, a->speed_q16); break;
        case CUB_COACH_ACT_MUSIC_START: start_music(d, t_us); break;
        case CUB_COACH_ACT_MUSIC_STOP:
            cub_music_stop(d->music);
            d->music_started = 0;
            d->music_paused = 0;
            break;
        case CUB_COACH_ACT_MUSIC_PAUSE: pause_music(d, 1, t_us); break;
        case CUB_COACH_ACT_MUSIC_RESUME: pause_music(d, 0, t_us); break;
        case CUB_COACH_ACT_HINT: show_hint(d, a->hint); break;
        default: break; /* states: logged by the coach */
        }
    }
}

/* ---- events ------------------------------------------------------------- */

void cub_dance_handle(cub_dance *d, cub_loop *loop, const cub_event *ev)
{
    cub_event e = *ev;
    /* The scripted judge speaks of "the move being taught now". */
    if (e.type == CUB_EV_VERDICT && e.a < 0) e.a = d->coach.move < 0 ? 0 : d->coach.move;
    if (cub_coach_handle(&d->coach, &e, music_ms(d)) == CUB_OK) execute_actions(d, e.t_us);
}

/* ---- the tick ----------------------------------------------------------- */

/* Under the virtual clock the music is rendered here, exactly as much as
 * the loop's time says, so the music clock is as deterministic as the rest. */
static void pull_music(cub_dance *d, int64_t t_us)
{
    if (!d->music_pull || !d->music_started || d->music_paused) return;
    /* A sound card off its rate (--music-clock-scale) takes that many more
     * or fewer frames a second; the music clock counts them, true to the
     * music it played. */
    uint64_t card_us = (uint64_t)(t_us - d->pull_origin_us) * d->pull_scale_ppm / 1000000u;
    uint64_t due = card_us * (uint64_t)cub_music_rate(d->music) / 1000000u;
    while (cub_music_frames(d->music) < due) {
        uint64_t n = due - cub_music_frames(d->music);
        cub_music_render(d->music, d->pcm, (int)(n > PCM_FRAMES ? PCM_FRAMES : n));
    }
}

static void post(cub_loop *loop, int64_t t_us, int32_t type, int32_t a, int32_t b)
{
    cub_event ev = {.t_us = t_us, .type = type, .a = a, .b = b};
    cub_loop_post(loop, &ev);
}

/* Entering the clip of the move being danced: its music tag, the song time
 * of the frame shown now (SEEDS.md § 000, "Music sync"). Now, not at the
 * switch: the music clock was read at the end of this advance, and the
 * coach compares the two. */
static void post_music_tag(cub_dance *d, cub_loop *loop, int64_t now_us, const cub_bridge_step *s)
{
    int m = d->coach.move;
    if (d->coach.state != CUB_COACH_DANCE || m < 0 || m >= d->song.move_count) return;
    const cub_coach_move *mv = &d->moves[m];
    if (s->to_clip != mv->clip || d->player.clip != mv->clip) return;
    int64_t intervals_q16 = (int64_t)(d->cl.lib.clips[mv->clip].clip.frame_count - 1) << 16;
    int64_t rep_ms = mv->span_ms / mv->reps;
    int32_t tag = mv->tag_ms + (int32_t)(rep_ms * d->coach.rep + rep_ms * d->player.pos_q16 / intervals_q16);
    cub_log_event(d->log, now_us, "music", "tag", "move=%d tag_ms=%d music_ms=%d", m, tag,
                  music_ms(d));
    post(loop, now_us, CUB_EV_MUSIC_TAG, m, tag);
}

static void player_events(cub_dance *d, cub_loop *loop, int64_t t0_us, int64_t now_us,
                          const cub_bridge_event *ev, int n)
{
    for (int i = 0; i < n; i++) {
        int64_t t = t0_us + ev[i].t_us;
        if (ev[i].type == CUB_BRIDGE_EV_SWITCH) {
            const cub_bridge_step *s = &ev[i].step;
            cub_log_event(d->log, t, "bridge", "switch", "from=%s@%d to=%s@%d d=%q via=%s",
                          clip_name(d, s->from_clip), s->from_frame, clip_name(d, s->to_clip),
                          s->to_frame, s->d, s->via == CUB_BRIDGE_TWEEN ? "tween" : "direct");
            post_music_tag(d, loop, now_us, s);
        } else if (ev[i].type == CUB_BRIDGE_EV_DONE && !ev[i].looped) {
            int clip = ev[i].clip == d->played_clip ? d->requested_clip : ev[i].clip;
            cub_log_event(d->log, t, "bridge", "done", "clip=%s", clip_name(d, ev[i].clip));
            post(loop, t, CUB_EV_CLIP_DONE, clip, 0);
        }
    }
}

void cub_dance_poll(cub_dance *d, cub_loop *loop, int64_t now_us)
{
    pull_music(d, now_us);
    if (d->music_started && !d->song_end_sent && !cub_music_playing(d->music)) {
        d->song_end_sent = 1;
        cub_log_event(d->log, now_us, "music", "end", "music_ms=%d", music_ms(d));
        post(loop, now_us, CUB_EV_SONG_END, 0, 0);
    }
    cub_bridge_event ev[MAX_PLAYER_EVENTS];
    int n = 0;
    int64_t dt = now_us > d->last_tick_us ? now_us - d->last_tick_us : 0;
    d->last_tick_us += dt;
    if (cub_bridge_player_advance(&d->player, dt, ev, MAX_PLAYER_EVENTS, &n) == CUB_OK)
        player_events(d, loop, now_us - dt, now_us, ev, n);
}

void cub_dance_tick(cub_dance *d, cub_loop *loop, int64_t t_us)
{
    if (cub_coach_tick(&d->coach, t_us, music_ms(d)) == CUB_OK) execute_actions(d, t_us);
}

/* ---- set-up ------------------------------------------------------------- */

static cub_err fail(char *err, size_t size, const cub_diag *diag, const char *what)
{
    char buf[600];
    snprintf(err, size, "%s: %s", what, cub_diag_str(diag, buf, sizeof buf));
    return CUB_ERR_FORMAT;
}

/* The song as the coach's program: clips, reps, speeds, music tags. */
static void fill_moves(cub_dance *d)
{
    for (int i = 0; i < d->song.move_count; i++) {
        const cub_song_move *m = &d->song.moves[i];
        d->moves[i] = (cub_coach_move){
            .clip = m->clip_index, .reps = m->reps,
            .speed_q16 = (cub_q16)((int64_t)m->speed_permille * CUB_Q16_ONE / 1000),
            .tag_ms = (int32_t)(m->start_us / 1000),
            .span_ms = (int32_t)((m->end_us - m->start_us) / 1000)};
    }
}

/* ---- entering a move on its music tag ------------------------------------ */

/* Song ms by which a move should be asked for before its tag: what the
 * planned route takes, less the content it skips (a route may land past
 * the clip's first frame). */
static int32_t route_lead_ms(const cub_dance *d, const cub_bridge_plan *plan, int move)
{
    const cub_coach_move *mv = &d->moves[move];
    const cub_clip *clip = &d->cl.lib.clips[mv->clip].clip;
    int64_t speed = mv->speed_q16 ? mv->speed_q16 : CUB_Q16_ONE;
    int64_t route_ms = (int64_t)plan->total_frames * clip->frame_ns / 1000000 * CUB_Q16_ONE / speed;
    int to_frame = plan->step_count > 0 ? plan->step[plan->step_count - 1].to_frame : 0;
    int64_t skip_ms = (int64_t)mv->span_ms / mv->reps * to_frame / (clip->frame_count - 1);
    return (int32_t)(route_ms - skip_ms);
}

/* The coach asks this while it waits for a move's tag (after the intro or
 * a gap): how long from where the player is now. */
static int32_t entry_lead_now(void *user, int32_t clip)
{
    cub_dance *d = user;
    int m = d->coach.move;
    if (m < 0 || m >= d->song.move_count || d->moves[m].clip != clip) return 0;
    cub_bridge_query q = {.from_clip = -1, .to_clip = clip, .start_frames = START_FRAMES};
    cub_bridge_plan plan;
    if (cub_bridge_player_preview(&d->player, &q, &plan)) return 0;
    return route_lead_ms(d, &plan, m);
}

/* The lead of a route into move `to` from the last frame of clip `from`
 * (where a repetition ends), or 0 when there is none. */
static int32_t lead_from_end(cub_dance *d, int from, int to)
{
    int frames = d->cl.lib.clips[from].clip.frame_count;
    cub_bridge_query q = {.from_clip = from, .pos_q16 = (int64_t)(frames - 1) << 16,
                          .to_clip = d->moves[to].clip, .start_frames = START_FRAMES};
    cub_bridge_plan plan;
    return cub_bridge_player_preview(&d->player, &q, &plan) ? 0 : route_lead_ms(d, &plan, to);
}

/* A repetition, and a move that follows the one before at once, is asked
 * for when the repetition before ends: plan those routes now, from its last
 * frame, so the coach can end that repetition early (or late) by their
 * length. */
static void plan_move_leads(cub_dance *d)
{
    for (int i = 0; i < d->song.move_count; i++) {
        cub_coach_move *mv = &d->moves[i];
        mv->rep_lead_ms = lead_from_end(d, mv->clip, i);
        mv->lead_ms = i > 0 ? lead_from_end(d, d->moves[i - 1].clip, i) : 0;
        cub_log_event(d->log, d->last_tick_us, "music", "lead",
                      "move=%d clip=%s lead_ms=%d rep_lead_ms=%d", i, clip_name(d, mv->clip),
                      mv->lead_ms, mv->rep_lead_ms);
    }
}

static cub_err open_coach(cub_dance *d, const cub_app_options *o, int64_t now_us, char *err,
                          size_t size)
{
    int n = d->cl.lib.clip_count;
    if (n > (int)(sizeof d->clip_names / sizeof *d->clip_names)) n = 256;
    for (int i = 0; i < n; i++) d->clip_names[i] = d->cl.lib.clips[i].name;
    cub_coach_desc cd = {.moves = d->moves, .move_count = d->song.move_count,
                         .clip_count = n, .clip_names = d->clip_names, .log = d->log,
                         .attract_after_ms = (uint32_t)(o->attract_after_s * 1000),
                         .doze_after_ms = (uint32_t)(o->doze_after_s * 1000),
                         .entry_lead_ms = entry_lead_now, .user = d};
    fill_moves(d);
    if (cub_coach_roles_by_name(d->clip_names, n, &cd.roles)) {
        snprintf(err, size, "%s: the library lacks one of the coach's clips (idle, wake_up, "
                            "wave, doze, head_shake, watch_me, worried, cheer)",
                 o->library_path);
        return CUB_ERR_FORMAT;
    }
    cub_err e = cub_coach_init(&d->coach, &cd, now_us);
    if (e) {
        snprintf(err, size, "coach: the song cannot be danced (%s)", cub_err_str(e));
        return e;
    }
    return CUB_OK;
}

static cub_err open_player(cub_dance *d, char *err, size_t size)
{
    cub_bridge_player_desc pd = {.table = &d->cl.table};
    size_t need = cub_bridge_player_mem_size(&pd);
    d->player_mem = malloc(need ? need : 1);
    cub_err e = d->player_mem ? cub_bridge_player_init(&d->player, &pd, d->player_mem, need)
                              : CUB_ERR_NOMEM;
    /* The coach's first request (its idle clip) starts playback directly. */
    const cub_coach_action *a = &d->coach.actions[0];
    if (!e && d->coach.action_count > 0 && a->kind == CUB_COACH_ACT_CLIP)
        e = cub_bridge_player_start(&d->player, a->clip, 0, a->speed_q16, a->loop);
    if (e) snprintf(err, size, "the clip player would not start (%s)", cub_err_str(e));
    return e;
}

static cub_err open_music(cub_dance *d, const cub_app_options *o, char *err, size_t size)
{
    cub_diag diag;
    cub_music_desc md = {.rate = cub_board_audio_rate(d->board), .soundfont = o->soundfont};
    if (cub_music_open(&md, &d->music, &diag)) return fail(err, size, &diag, "music");
    if (cub_music_load(d->music, d->song.midi_path, &diag)) return fail(err, size, &diag, "song");

    d->pcm = malloc(PCM_FRAMES * 2 * sizeof(int16_t));
    if (!d->pcm) return CUB_ERR_NOMEM;
    /* Real time: the audio device plays the music and clocks it. Virtual
     * time, or no audio device: the tick renders it. */
    d->music_pull = o->virtual_clock;
    if (!d->music_pull) {
        if (cub_board_audio_start(d->board, cub_music_fill, d->music) == CUB_OK)
            d->audio_open = 1;
        else
            d->music_pull = 1;
    }
    /* --music-clock-scale: rendered here, the music itself runs off its
     * rate; played by a device we cannot speed up, only its clock lies. */
    d->pull_scale_ppm = (uint32_t)(o->music_clock_scale * 1000000 + 0.5);
    if (d->audio_open && o->music_clock_scale != 1.0 &&
        cub_music_set_clock_scale(d->music, o->music_clock_scale))
        return snprintf(err, size, "--music-clock-scale out of range"), CUB_ERR_ARG;
    return CUB_OK;
}

cub_err cub_dance_open(cub_dance *d, const cub_app_options *o, cub_board *board, cub_log *log,
                       int64_t now_us, char *err, size_t err_size)
{
    memset(d, 0, sizeof *d);
    d->board = board;
    d->log = log;
    cub_diag diag;
    if (cub_coachlib_load(o->library_path, o->tags_path, o->character_path, &d->cl, &diag))
        return fail(err, err_size, &diag, "coach clips");
    if (cub_song_load(o->song_path, &d->cl.lib, &d->song, &diag))
        return fail(err, err_size, &diag, "song");
    cub_err e = open_music(d, o, err, err_size);
    if (!e) e = open_coach(d, o, now_us, err, err_size);
    if (!e) e = open_player(d, err, err_size);
    if (!e) {
        d->last_tick_us = now_us;
        plan_move_leads(d); /* the coach reads the moves through its desc */
    }
    d->played_clip = d->requested_clip = -1;
    d->hint = CUB_COACH_HINT_NONE;
    d->icon_move = -1;
    return e;
}

void cub_dance_close(cub_dance *d)
{
    if (d->audio_open) cub_board_audio_stop(d->board);
    cub_music_close(d->music);
    free(d->pcm);
    free(d->player_mem);
    cub_coachlib_free(&d->cl);
    memset(d, 0, sizeof *d);
}

const cub_skeleton *cub_dance_skeleton(const cub_dance *d) { return &d->cl.lib.skel; }

int cub_dance_waiting(const cub_dance *d)
{
    int32_t st = d->coach.state;
    return st == CUB_COACH_IDLE || st == CUB_COACH_ATTRACT || st == CUB_COACH_DOZE;
}

cub_err cub_dance_pose(cub_dance *d, float *xyz, float *rot_xyzw)
{
    cub_quat rot[CUB_MOTION_MAX_JOINTS];
    const cub_skeleton *skel = &d->cl.lib.skel;
    cub_err e = cub_bridge_player_pose(&d->player, &d->pose);
    if (!e) e = cub_motion_forward(skel, &d->pose, d->world_mm, rot_xyzw ? rot : NULL);
    if (e) return e;
    cub_motion_world_to_float(d->world_mm, skel->joint_count, xyz);
    for (int j = 0; rot_xyzw && j < skel->joint_count; j++) {
        const float one = (float)CUB_QUAT_ONE;
        rot_xyzw[4 * j + 0] = (float)rot[j].x / one;
        rot_xyzw[4 * j + 1] = (float)rot[j].y / one;
        rot_xyzw[4 * j + 2] = (float)rot[j].z / one;
        rot_xyzw[4 * j + 3] = (float)rot[j].w / one;
    }
    return CUB_OK;
}

float cub_dance_figure_height_mm(const cub_dance *d)
{
    static cub_pose rest;
    static cub_vec3 world[CUB_MOTION_MAX_JOINTS];
    const cub_skeleton *skel = &d->cl.lib.skel;
    cub_motion_pose_rest(skel, &rest);
    rest.root_mm = skel->joints[0].offset_mm; /* the rest pose stands on the floor */
    float top_mm = 0;
    if (cub_motion_forward(skel, &rest, world, NULL) == CUB_OK)
        for (int j = 0; j < skel->joint_count; j++)
            if (world[j].y / 65536.0f > top_mm) top_mm = world[j].y / 65536.0f;
    return top_mm > 0 ? 1.3f * top_mm : 0;
}

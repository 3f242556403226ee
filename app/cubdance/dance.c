/* The dance glue (see dance.h). */
#include "dance.h"

/* The clip danced with wings when the coach has them (wings.h). */
#define WINGS_CLIP "bird_flying"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "walk_box.h"
#include "words.h"

/* The music clock in song milliseconds, or CUB_COACH_NO_MUSIC. */
static int32_t music_ms(const cub_dance *d)
{
    return cub_dance_music_ms(&d->music);
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

/* ---- what the bear says ---------------------------------------------------- */

/* The words said now, logged (what the event log says never depends on the
 * voice pack: a missing pack only warns at start; a phrase the pack lacks
 * is a line of its own, which the tests look for). */
static void say(cub_dance *d, const char *text, int64_t t_us)
{
    if (!d->speech || !text) return;
    if (cub_dance_music_say(&d->music, text) == CUB_DANCE_NO_PHRASE)
        cub_log_event(d->log, t_us, "speech", "missing", "text=\"%s\"", text);
    else
        cub_log_event(d->log, t_us, "speech", "say", "text=\"%s\" audio_frame=%llu", text,
                      (unsigned long long)cub_dance_music_device_frames(&d->music));
}

/* "Press START!" when the bear starts waiting and when it tries to attract
 * someone; the cheer when the song is over. */
static void say_state(cub_dance *d, int64_t t_us)
{
    int32_t st = d->dir.coach.state, was = d->said_state;
    if (st == was) return;
    d->said_state = st;
    if (st == CUB_COACH_ATTRACT ||
        (st == CUB_COACH_IDLE && was != CUB_COACH_ATTRACT && was != CUB_COACH_DOZE))
        say(d, cub_words_title(), t_us);
    else if (st == CUB_COACH_CHEER)
        say(d, cub_words_cheer(), t_us);
}

/* The hint's words, or while a correction runs the fault's. */
static const char *hint_words(const cub_dance *d)
{
    return d->fault ? cub_words_fault(&d->song, &d->faults, d->hint, d->fault)
                    : cub_words_hint(&d->song, d->hint);
}

const char *cub_dance_words(const cub_dance *d)
{
    const char *w = hint_words(d);
    return !w && d->dir.coach.state == CUB_COACH_CHEER ? cub_words_cheer() : w;
}

static void show_hint(cub_dance *d, int32_t hint, int32_t fault, int64_t t_us)
{
    d->hint = hint;
    d->fault = fault;
    say(d, hint_words(d), t_us);
    if (hint < 0 || hint >= d->song.move_count || hint == d->icon_move) return;
    int clip = d->song.moves[hint].clip_index;
    d->icon_move = -1;
    if (clip < 0 || clip >= d->cl.lib.clip_count) return;
    telling_pose(d, &d->cl.lib.clips[clip].clip, d->icon_xyz);
    d->icon_move = hint;
}

uint32_t cub_dance_child_mark(const cub_dance *d)
{
    return cub_judge_fault_joints(cub_judge_fault_of(d->fault));
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

static void carry_out(cub_dance *d, int64_t t_us)
{
    for (int i = 0; i < d->dir.out_count; i++) {
        const cub_director_out *o = &d->dir.out[i];
        switch (o->what) {
        case CUB_DIRECTOR_MUSIC_START: cub_dance_music_start(&d->music, t_us); break;
        case CUB_DIRECTOR_MUSIC_STOP: cub_dance_music_stop(&d->music); break;
        case CUB_DIRECTOR_MUSIC_PAUSE: cub_dance_music_pause(&d->music, 1, t_us); break;
        case CUB_DIRECTOR_MUSIC_RESUME: cub_dance_music_pause(&d->music, 0, t_us); break;
        case CUB_DIRECTOR_HINT: show_hint(d, o->hint, o->fault, t_us); break;
        default: break;
        }
    }
}

/* ---- events ------------------------------------------------------------- */

void cub_dance_handle(cub_dance *d, cub_loop *loop, const cub_event *ev)
{
    (void)loop;
    if (cub_director_handle(&d->dir, ev, music_ms(d)) == CUB_OK) carry_out(d, ev->t_us);
}

/* ---- the tick ----------------------------------------------------------- */

void cub_dance_poll(cub_dance *d, cub_loop *loop, int64_t now_us)
{
    if (cub_dance_music_poll(&d->music, now_us)) {
        cub_log_event(d->log, now_us, "music", "end", "music_ms=%d", music_ms(d));
        cub_loop_post(loop, &(cub_event){.t_us = now_us, .type = CUB_EV_SONG_END});
    }
    cub_director_advance(&d->dir, loop, now_us, music_ms(d));
}

void cub_dance_tick(cub_dance *d, cub_loop *loop, int64_t t_us)
{
    (void)loop;
    if (cub_director_tick(&d->dir, t_us, music_ms(d)) == CUB_OK) carry_out(d, t_us);
    say_state(d, t_us);
    if (d->walk) cub_walk_box_tick(d->walk, &d->dir.player, d->dir.coach.state, t_us);
}

/* ---- set-up ------------------------------------------------------------- */

static cub_err fail(char *err, size_t size, const cub_diag *diag, const char *what)
{
    char buf[600];
    snprintf(err, size, "%s: %s", what, cub_diag_str(diag, buf, sizeof buf));
    return CUB_ERR_FORMAT;
}

/* The song as the coach's program (clips, reps, speeds, music tags) and
 * the judge's (each move's key points). */
static void fill_program(cub_dance *d, cub_coach_move *moves)
{
    for (int i = 0; i < d->song.move_count; i++) {
        const cub_song_move *m = &d->song.moves[i];
        moves[i] = (cub_coach_move){
            .clip = m->clip_index, .reps = m->reps,
            .speed_q16 = (cub_q16)((int64_t)m->speed_permille * CUB_Q16_ONE / 1000),
            .tag_ms = (int32_t)(m->start_us / 1000),
            .span_ms = (int32_t)((m->end_us - m->start_us) / 1000)};
        d->keys[i].count = m->key_count < CUB_JUDGE_MAX_KEYS ? m->key_count : CUB_JUDGE_MAX_KEYS;
        for (int k = 0; k < d->keys[i].count; k++)
            d->keys[i].key[k] =
                (cub_judge_key){.feature = m->keys[k].feature, .set = m->keys[k].set};
    }
}

static cub_err open_director(cub_dance *d, const cub_app_options *o, cub_judge *judge,
                             int64_t now_us, char *err, size_t size)
{
    int n = d->cl.lib.clip_count;
    const int most = (int)(sizeof d->clip_names / sizeof *d->clip_names);
    if (n > most) n = most;
    for (int i = 0; i < n; i++) d->clip_names[i] = d->cl.lib.clips[i].name;
    for (int g = 0; g < d->groove_count && n + g < most; g++) /* appended by hand_grooves */
        d->clip_names[n + g] = d->groove->names[d->groove_span[g]];
    cub_coach_move moves[CUB_SONG_MAX_MOVES];
    fill_program(d, moves);
    cub_director_desc dd = {
        .table = &d->cl.table, .keys = d->keys, .bpm = d->song.bpm, .song_name = d->song.name,
        .song_length_ms = (int32_t)(cub_song_length_us(&d->song) / 1000), .judge = judge,
        .coach = {.moves = moves, .move_count = d->song.move_count,
                  .grooves = d->grooves, .groove_count = d->groove_count,
                  .clip_count = d->cl.table.desc.clip_count,
                  .clip_names = d->clip_names, .log = d->log,
                  .attract_after_ms = (uint32_t)(o->attract_after_s * 1000),
                  .doze_after_ms = (uint32_t)(o->doze_after_s * 1000)}};
    if (cub_coach_roles_by_name(d->clip_names, n, &dd.coach.roles)) {
        snprintf(err, size, "%s: the library lacks one of the coach's clips (idle, wake_up, "
                            "wave, doze, head_shake, watch_me, worried, cheer)",
                 o->library_path);
        return CUB_ERR_FORMAT;
    }
    size_t need = cub_director_mem_size(&dd);
    d->dir_mem = malloc(need ? need : 1);
    cub_err e = d->dir_mem ? cub_director_init(&d->dir, &dd, d->dir_mem, need, now_us)
                           : CUB_ERR_NOMEM;
    if (e) snprintf(err, size, "coach: the song cannot be danced (%s)", cub_err_str(e));
    return e;
}

/* Which groove spans the coach dances: every span no move teaches (the
 * intro, the gaps, the <free> bars, the outro up to the cheer); the bear
 * enters and leaves them through the bridge planner (docs/groove.md, the
 * fifth slice). */
static bool danced(const cub_song_span *sp)
{
    return sp->kind != CUB_SONG_SPAN_MOVE;
}

/* The clips of the danced spans into the bridge table, after the library's
 * clips, and their spans on the music clock for the coach. Only those: the
 * table is rebuilt to take them, so a song none of whose spans is danced
 * (every bar a move) keeps its table as loaded. */
static cub_err hand_grooves(cub_dance *d, char *err, size_t size)
{
    const cub_groove_box *g = d->groove;
    const int first = d->cl.table.desc.clip_count;
    cub_coachlib_extra clips[CUB_SONG_MAX_SPANS];
    d->groove_count = 0;
    for (int i = 0; i < g->span_count; i++) {
        if (!danced(&g->spans[i])) continue;
        int k = d->groove_count++;
        clips[k] = (cub_coachlib_extra){&g->clips[i], g->fuzzy[i], g->bridges[i],
                                        g->bridge_count[i]};
        d->groove_span[k] = i;
        /* the meter's beats: a span joined late is joined on one of them */
        d->grooves[k] = (cub_coach_groove){
            .clip = first + k, .tag_ms = (int32_t)(g->spans[i].start_us / 1000),
            .span_ms = (int32_t)((g->spans[i].end_us - g->spans[i].start_us) / 1000),
            .beats = g->spans[i].bars * d->song.meter_num};
    }
    if (d->groove_count == 0) return CUB_OK;
    if (first + d->groove_count > (int)(sizeof d->clip_names / sizeof *d->clip_names)) {
        snprintf(err, size, "groove: %s: %d clips and %d groove spans, more than the box "
                            "names (%d)",
                 d->song.midi_path, first, d->groove_count,
                 (int)(sizeof d->clip_names / sizeof *d->clip_names));
        return CUB_ERR_FULL;
    }
    cub_diag diag = {0};
    if (cub_coachlib_add_clips(&d->cl, clips, d->groove_count, &diag))
        return fail(err, size, &diag, "groove");
    return CUB_OK;
}

/* The dance of the bars no move teaches; a song without moves (the
 * format's groove song) is all groove, unless the coach has no arms for it
 * (the seal). */
static cub_err open_groove(cub_dance *d, char *err, size_t size)
{
    d->groove = malloc(sizeof *d->groove);
    if (!d->groove) return CUB_ERR_NOMEM;
    cub_err e = cub_groove_box_open(d->groove, &d->song, &d->cl, d->log, err, size);
    if (!e) e = hand_grooves(d, err, size);
    if (!e && d->song.move_count == 0 && d->groove_count == 0) {
        snprintf(err, size, "song: \"%s\" has no <move> and its bear cannot groove (%s)",
                 d->song.name, d->song.midi_path);
        e = CUB_ERR_UNSUPPORTED;
    }
    return e;
}

/* The bear's walks (walk_box.h), their key poses added to the bridge
 * table after the groove's clips, before the director plans on it. */
static cub_err open_walk(cub_dance *d, const char *path, const cub_floor *floor, char *err,
                         size_t size)
{
    const int most = (int)(sizeof d->clip_names / sizeof *d->clip_names);
    if (d->cl.table.desc.clip_count + CUB_WALK_KEYS > most) {
        snprintf(err, size, "walk: %s: the table holds %d clips, the box names %d", path,
                 d->cl.table.desc.clip_count + CUB_WALK_KEYS, most);
        return CUB_ERR_FULL;
    }
    cub_err e = cub_dance_open_walk(d, path, floor, err, size);
    return e ? e : cub_walk_box_add_keys(d->walk, &d->cl, d->clip_names, err, size);
}

cub_err cub_dance_open(cub_dance *d, const cub_app_options *o, cub_board *board, cub_log *log,
                       cub_judge *judge, const cub_floor *floor, int64_t now_us, char *err,
                       size_t err_size)
{
    memset(d, 0, sizeof *d);
    d->log = log;
    cub_diag diag;
    if (cub_coachlib_load(o->library_path, o->tags_path, o->character_path, &d->cl, &diag))
        return fail(err, err_size, &diag, "coach clips");
    if (cub_song_load(o->song_path, &d->cl.lib, &d->song, &diag))
        return fail(err, err_size, &diag, "song");
    if (d->song.faults_path[0] &&
        cub_faults_load(d->song.faults_path, &d->cl.lib, &d->faults, &diag))
        return fail(err, err_size, &diag, "fault words");
    cub_err e = cub_dance_music_open(&d->music, o, board, d->song.midi_path, err, err_size);
    if (!e) e = open_groove(d, err, err_size);
    if (!e && o->walk_path) e = open_walk(d, o->walk_path, floor, err, err_size);
    if (!e) e = open_director(d, o, judge, now_us, err, err_size);
    if (!e && cub_wings_open(&d->wings, o->character_path, WINGS_CLIP, &d->cl.lib.skel,
                             cub_library_find(&d->cl.lib, WINGS_CLIP), err, err_size))
        e = CUB_ERR_FORMAT;
    d->hint = CUB_COACH_HINT_NONE;
    d->icon_move = -1;
    d->speech = o->speech;
    d->said_state = -1;
    return e;
}

void cub_dance_close(cub_dance *d)
{
    cub_dance_music_close(&d->music);
    free(d->dir_mem);
    cub_coachlib_free(&d->cl); /* before the groove: its table plays the groove's frames */
    cub_wings_close(&d->wings);
    if (d->groove) cub_groove_box_close(d->groove);
    free(d->groove);
    if (d->walk) cub_walk_box_close(d->walk);
    free(d->walk);
    memset(d, 0, sizeof *d);
}

const cub_skeleton *cub_dance_skeleton(const cub_dance *d) { return &d->cl.lib.skel; }

int cub_dance_waiting(const cub_dance *d)
{
    int32_t st = d->dir.coach.state;
    return st == CUB_COACH_IDLE || st == CUB_COACH_ATTRACT || st == CUB_COACH_DOZE;
}

cub_err cub_dance_pose(cub_dance *d, float *xyz, float *rot_xyzw)
{
    cub_quat rot[CUB_MOTION_MAX_JOINTS];
    const cub_skeleton *skel = &d->cl.lib.skel;
    cub_err e = cub_bridge_player_pose(&d->dir.player, &d->pose);
    if (!e && d->walk) cub_walk_box_pose(d->walk, &d->pose);
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

/* The clip of the song move the coach is dancing or correcting; -1 when
 * it is on none (the wings follow the move, not only its clip). */
static int move_clip(const cub_dance *d)
{
    const cub_coach *c = &d->dir.coach;
    int on = c->state == CUB_COACH_DANCE || c->state == CUB_COACH_CORRECT;
    return on && c->move >= 0 && c->move < c->desc.move_count ? d->dir.moves[c->move].clip : -1;
}

void cub_dance_picture(cub_dance *d, int64_t t_us, const cub_character **ch,
                       const cub_skeleton **skel, const float **xyz, const float **rot,
                       const float **icon)
{
    cub_wings *w = &d->wings;
    *ch = w->loaded ? &w->ch : &d->cl.bear;
    const cub_bridge_player *p = &d->dir.player;
    cub_wings_move(w, move_clip(d));
    if (!cub_wings_pose(w, p->clip, p->pos_q16, t_us, *xyz, *rot)) return;
    *skel = &w->skel;
    *xyz = w->xyz;
    *rot = w->rot;
    *icon = cub_wings_icon(w, *icon);
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

/* The bear's walks in the box: which walk the coach's state asks for, the
 * walker stepped at the clip's rate, its footsteps logged, and the
 * picture handed between the walk and the coach's dance at the bridge
 * frames the coach's own planner finds (docs/gait.md "The bear walks in
 * the box"). */
#include "walk_box.h"

#include <stdlib.h>
#include <string.h>

#include "cub/coach.h"
#include "cub/coachlib.h"

/* The picture's fade at a hand-over [ours: a little over a step's half]. */
#define BLEND_US 400000
#define WANDER_REST_US 2000000 /* attracting: stand this long between wanders */
#define ARRIVE_MM 60          /* the root this near the target: arrived */
#define PASS_MM 30            /* ... or farther than its nearest by this, once within NEAR_MM */
#define NEAR_MM 300
/* The walk in comes from the trees (3 m) while the wake state lasts
 * (2.23 s after START) and into the song's first bars: it hurries, at
 * twice the clip's rate (~0.8 m/s), and stops where it is after WALK_IN_US
 * at the latest [ours; docs/gait.md has the measured times]. */
#define WALK_IN_RATE 2
#define WALK_IN_US 6000000
/* A hand-over waits at most this many of the coach's frames for a bridge
 * frame within the threshold, then takes the closest (the planner's reach). */
#define REACH_FRAMES 15

/* Where the bear goes (x, z mm; its place is the origin, the camera on
 * +z). It comes in from behind the nearest tree on the left (the
 * renderer's trees at (-1700, -1600), (1800, -2000)), over the rolling
 * ground that begins 2 m out, past the log's left end (x >= -700); it
 * walks off past the log's right end; it wanders on the flat clearing
 * within 0.65 m of its place. */
static const int32_t home_xz[2] = {0, 0};
static const int32_t start_xz[2] = {-1900, -2300}; /* among the trees, behind on the left */
/* off to the trees on the right, in front of the log's right end */
static const int32_t off_xz[2] = {2200, -1100};
static const int32_t wander_xz[][2] = {{-500, -350}, {150, -600}, {550, -250}};
#define WANDERS ((int)(sizeof wander_xz / sizeof *wander_xz))
static const char *const key_names[CUB_WALK_KEYS] = {"walk_start", "walk_stop_left",
                                                     "walk_stop_right"};

static cub_vec3 at_xz(const int32_t xz[2])
{
    return (cub_vec3){CUB_Q16_INT(xz[0]), 0, CUB_Q16_INT(xz[1])};
}

static int mm(cub_q16 v)
{
    return (int)((v + (v >= 0 ? 32768 : -32768)) / 65536);
}

/* Squared horizontal distance in whole mm. */
static int64_t dist2(cub_vec3 a, cub_vec3 b)
{
    int64_t dx = mm(a.x - b.x), dz = mm(a.z - b.z);
    return dx * dx + dz * dz;
}

static cub_vec3 root_xz(const cub_walk_box *w)
{
    return (cub_vec3){w->walker.pose.root_mm.x, 0, w->walker.pose.root_mm.z};
}

/* ---- the footsteps into the log ------------------------------------------ */

static void on_event(void *ctx, const cub_gait_event *e)
{
    static const char *const kind[] = {"planned", "backtracked", "taken", "blocked"};
    const cub_walk_box *w = ctx;
    const char *foot = e->left ? "left" : "right";
    if (e->kind == CUB_GAIT_EV_BACKTRACKED)
        cub_log_event(w->log, w->now_us, "walk", kind[e->kind], "step=%d foot=%s count=%d",
                      e->step, foot, e->count);
    else if (e->kind == CUB_GAIT_EV_PLANNED)
        cub_log_event(w->log, w->now_us, "walk", kind[e->kind],
                      "step=%d foot=%s index=%d x=%d y=%d z=%d", e->step, foot, e->index,
                      mm(e->foot_mm.x), mm(e->foot_mm.y), mm(e->foot_mm.z));
    else
        cub_log_event(w->log, w->now_us, "walk", kind[e->kind], "step=%d foot=%s x=%d y=%d z=%d",
                      e->step, foot, mm(e->foot_mm.x), mm(e->foot_mm.y), mm(e->foot_mm.z));
}

/* ---- names, and the picture's switch ----------------------------------------- */

static const char *why_name(cub_walk_why why)
{
    return why == CUB_WALK_IN ? "in" : why == CUB_WALK_OFF ? "off" : "wander";
}

/* The picture switches: what was drawn last fades out from now. */
static void switch_now(cub_walk_box *w, int64_t t_us)
{
    if (w->drawn) w->from = w->shown;
    w->switch_us = t_us;
}

static int resting(int32_t st)
{
    return st == CUB_COACH_IDLE || st == CUB_COACH_ATTRACT || st == CUB_COACH_DOZE ||
           st == CUB_COACH_WAKE;
}

/* ---- the hand-overs through the bridge planner ------------------------------ */

static const char *clip_name(const cub_walk_box *w, int c)
{
    return w->names && c >= 0 && w->names[c] ? w->names[c] : "?";
}

/* The coach's planner, asked from where its player is (its clip's upcoming
 * frames) to one of the walk's key poses: the seed's rule first (both ends
 * bridge frames), else from any upcoming frame. One direct switch: the walk
 * is no clip a chain through other moves belongs to. -1: no plan. */
static int plan_key(cub_walk_box *w, const cub_bridge_player *p, int key, cub_bridge_plan *out,
                    int *strict)
{
    const cub_bridge_table *t = p->desc.table;
    size_t need = cub_bridge_plan_work_size(t);
    if (need > w->plan_work_size) {
        free(w->plan_work);
        w->plan_work_size = (w->plan_work = malloc(need)) ? need : 0;
        if (!w->plan_work) return -1;
    }
    cub_bridge_query q = {.from_clip = p->clip, .pos_q16 = p->pos_q16, .from_loops = p->loop,
                          .to_clip = w->key_first + key, .start_frames = 1,
                          .reach_frames = REACH_FRAMES, .direct_only = 1};
    for (*strict = 1; *strict >= 0; --*strict) {
        q.strict = *strict;
        if (!cub_bridge_plan_switch(t, &q, out, w->plan_work, w->plan_work_size) &&
            out->step_count == 1)
            return 0;
    }
    return -1;
}

static void log_plan(const cub_walk_box *w, int64_t t_us, const char *dir,
                     const cub_bridge_plan *pl, int key, int strict)
{
    const cub_bridge_step *s = &pl->step[0];
    cub_log_event(w->log, t_us, "walk", "bridge",
                  "dir=%s clip=%s@%d key=%s d=%q wait_frames=%d strict=%d", dir,
                  clip_name(w, s->from_clip), s->from_frame, key_names[key], s->d,
                  pl->wait_frames, strict);
}

/* The walk in stopped: the bear holds its last pose until the coach's
 * dance reaches the frame the planner gives for that pose (the fuzzy
 * distance is symmetric: the coach's frame nearest the stop pose is where
 * the pose goes over into the dance). */
static void plan_in(cub_walk_box *w, const cub_bridge_player *p, int64_t t_us)
{
    int key = w->walker.stopped && w->walker.stop_foot ? CUB_WALK_KEY_STOP_RIGHT
                                                       : CUB_WALK_KEY_STOP_LEFT;
    cub_bridge_plan pl;
    int strict;
    w->hand_clip = p->clip;
    if (plan_key(w, p, key, &pl, &strict)) {
        w->hand_frame = -1; /* no plan: hand over at once */
        w->hand_at_q16 = p->pos_q16;
        return;
    }
    w->hand_frame = pl.step[0].from_frame;
    w->hand_at_q16 = pl.step[0].at_q16;
    log_plan(w, t_us, "in", &pl, key, strict);
}

static void hand_over(cub_walk_box *w, int64_t t_us)
{
    cub_log_event(w->log, t_us, "walk", "enter", "clip=%s frame=%d", clip_name(w, w->hand_clip),
                  w->hand_frame);
    w->hand = 0;
    w->place = at_xz(home_xz);
    switch_now(w, t_us);
}

/* Waiting at the stop: the dance has begun (the coach left the waking
 * states and its player is in the clip it asked for, not finishing
 * wake_up) and its player reaches the planned frame; a switch to another
 * clip first asks the planner again. */
static void hand_on(cub_walk_box *w, const cub_bridge_player *p, int32_t st, int64_t t_us)
{
    if (resting(st) || cub_bridge_player_pending(p)) return;
    if (w->hand == 1 || p->clip != w->hand_clip) {
        plan_in(w, p, t_us);
        w->hand = 2;
    }
    if (p->pos_q16 >= w->hand_at_q16) hand_over(w, t_us);
}

/* A song ended or was stopped: the walk off begins when the coach's clip
 * reaches the frame the planner gives for the walk's first pose. */
static void plan_off(cub_walk_box *w, const cub_bridge_player *p, int64_t t_us)
{
    cub_bridge_plan pl;
    int strict;
    w->leave_us = t_us;
    if (plan_key(w, p, CUB_WALK_KEY_START, &pl, &strict)) return;
    log_plan(w, t_us, "off", &pl, CUB_WALK_KEY_START, strict);
    const cub_clip *c = &p->desc.table->clips[p->clip].clip;
    int64_t frames_q16 = ((pl.step[0].at_q16 - p->pos_q16) << 16) / p->speed_q16;
    w->leave_us += frames_q16 * (int64_t)(c->frame_ns / 1000) >> 16;
}

/* ---- walking and standing -------------------------------------------------- */

static void stop(cub_walk_box *w, int64_t t_us, const char *how)
{
    cub_vec3 at = root_xz(w);
    w->place = at; /* a walk in stands here until its hand-over */
    cub_log_event(w->log, t_us, "walk", "stop", "why=%s how=%s x=%d z=%d steps=%d",
                  why_name(w->why), how, mm(at.x), mm(at.z), w->walker.steps);
    w->walking = 0;
    if (w->why == CUB_WALK_IN && w->key_first >= 0) w->hand = 1; /* the picture stays the walk's */
    else switch_now(w, t_us);
}

static void go(cub_walk_box *w, cub_vec3 to, cub_walk_why why, int64_t t_us, int64_t deadline_us)
{
    cub_vec3 at = w->walking ? root_xz(w) : w->place;
    if (dist2(at, to) <= (int64_t)ARRIVE_MM * ARRIVE_MM) return; /* there already */
    cub_gait_walk_params p = {.start_mm = at, .dir_x = to.x - at.x, .dir_z = to.z - at.z,
                              .on_event = on_event, .ctx = w};
    w->now_us = t_us;
    if (cub_gait_walker_init(&w->walker, &w->walk.wc, &w->terrain, &p))
        return; /* checked at open */
    cub_log_event(w->log, t_us, "walk", "start", "why=%s from_x=%d from_z=%d to_x=%d to_z=%d",
                  why_name(why), mm(at.x), mm(at.z), mm(to.x), mm(to.z));
    w->walking = 1;
    w->why = why;
    w->rate = why == CUB_WALK_IN ? WALK_IN_RATE : 1;
    w->target = to;
    w->walk_t0_us = t_us;
    w->deadline_us = deadline_us;
    w->frames = 0;
    w->best_mm = INT32_MAX;
    switch_now(w, t_us);
}

/* Arrived: near enough, or past the nearest point (the root sways side
 * to side and turns at most 10 degrees a step: it may not pass within
 * ARRIVE_MM). */
static int arrived(cub_walk_box *w)
{
    int32_t d = (int32_t)cub_fx_isqrt64((uint64_t)dist2(root_xz(w), w->target));
    if (d < w->best_mm) w->best_mm = d;
    return d <= ARRIVE_MM || (w->best_mm < NEAR_MM && d > w->best_mm + PASS_MM);
}

static void walk_on(cub_walk_box *w, int64_t t_us)
{
    int64_t due = (t_us - w->walk_t0_us) * 1000 * w->rate / (int64_t)w->m.clip.frame_ns;
    w->now_us = t_us;
    while (w->walking && w->frames < due) {
        const cub_pose *pose;
        if (cub_gait_walker_step(&w->walker, w->target, &pose)) {
            stop(w, t_us, "error");
            return;
        }
        w->frames++;
        if (w->walker.blocked) stop(w, t_us, "blocked");
        else if (arrived(w) || w->walker.stopped) stop(w, t_us, "arrived");
    }
    if (w->walking && w->deadline_us && t_us >= w->deadline_us) stop(w, t_us, "time");
}

static void wander(cub_walk_box *w, int64_t t_us)
{
    go(w, at_xz(wander_xz[w->wander]), CUB_WALK_WANDER, t_us, 0);
    w->wander = (w->wander + 1) % WANDERS;
    if (!w->walking) w->switch_us = t_us; /* there already: rest again */
}

/* A new coach state: START woke it (walk in, handed to the dance at its
 * bridge frame), a song ended or was stopped (walk off from the dance's
 * bridge frame), attract (wander); a waking state back to rest ends a wait
 * at the stop; anything else ends a wander. */
static void follow(cub_walk_box *w, const cub_bridge_player *p, int32_t from, int32_t to,
                   int64_t t_us)
{
    int back = resting(to) && to != CUB_COACH_WAKE; /* STOP (or the like) while waking */
    w->leave_us = 0;
    if (back && w->walking && w->why == CUB_WALK_IN) stop(w, t_us, "state");
    if (back && w->hand) {
        w->hand = 0; /* the coach's own clip again, where the bear stands */
        switch_now(w, t_us);
    }
    if (to == CUB_COACH_WAKE)
        go(w, at_xz(home_xz), CUB_WALK_IN, t_us, t_us + WALK_IN_US);
    else if (to == CUB_COACH_ATTRACT)
        wander(w, t_us);
    else if (to == CUB_COACH_IDLE && !resting(from) && w->key_first >= 0)
        plan_off(w, p, t_us);
    else if (to == CUB_COACH_IDLE && !resting(from))
        go(w, at_xz(off_xz), CUB_WALK_OFF, t_us, 0);
    else if (w->walking && w->why == CUB_WALK_WANDER)
        stop(w, t_us, "state");
}

void cub_walk_box_tick(cub_walk_box *w, const cub_bridge_player *player, int32_t coach_state,
                       int64_t t_us)
{
    if (!w->joint_count) return;
    int32_t from = w->last_state;
    w->last_state = coach_state;
    w->now_us = t_us;
    if (coach_state != from) follow(w, player, from, coach_state, t_us);
    if (w->leave_us && t_us >= w->leave_us) {
        w->leave_us = 0;
        go(w, at_xz(off_xz), CUB_WALK_OFF, t_us, 0);
    }
    if (w->walking) walk_on(w, t_us);
    else if (w->hand) hand_on(w, player, coach_state, t_us);
    else if (coach_state == CUB_COACH_ATTRACT && t_us - w->switch_us >= WANDER_REST_US)
        wander(w, t_us);
}

/* ---- the picture ------------------------------------------------------------ */

/* Local translations made explicit (the skeleton's rest offsets), so two
 * poses blend whichever way each was sampled. */
static void with_trans(const cub_walk_box *w, cub_pose *p)
{
    if (p->has_trans) return;
    for (int j = 0; j < p->joint_count; j++)
        p->trans_mm[j] = w->skel->joints[j].offset_mm;
    p->has_trans = 1;
}

/* A pose of the walk clip's skeleton as the coach's. */
static void walker_pose_of(const cub_walk_box *w, const cub_pose *p, cub_pose *out)
{
    out->joint_count = w->joint_count;
    out->root_mm = p->root_mm;
    out->has_trans = 0;
    for (int j = 0; j < w->joint_count; j++)
        out->rot[j] = p->rot[w->map[j]];
}

/* A ramp 0..1 (Q16) over BLEND_US since the last switch, eased both ends. */
static cub_q16 blend_weight(const cub_walk_box *w)
{
    int64_t dt = w->now_us - w->switch_us;
    if (dt >= BLEND_US) return CUB_Q16_ONE;
    cub_q16 x = (cub_q16)(dt * CUB_Q16_ONE / BLEND_US);
    return cub_fx_mul(cub_fx_mul(x, x), 3 * CUB_Q16_ONE - 2 * x); /* smoothstep */
}

void cub_walk_box_pose(cub_walk_box *w, cub_pose *pose)
{
    if (!w->joint_count || pose->joint_count != w->joint_count) return;
    if (w->walking || w->hand) {
        walker_pose_of(w, &w->walker.pose, &w->shown);
    } else {
        w->shown = *pose; /* standing at its place: the coach's own clip, moved there */
        cub_q16 y = cub_gait_ground_height(&w->terrain, w->place.x, w->place.z);
        w->shown.root_mm = cub_fx_vec3_add(pose->root_mm, (cub_vec3){w->place.x, y, w->place.z});
    }
    cub_q16 k = blend_weight(w);
    if (w->drawn && k < CUB_Q16_ONE) {
        with_trans(w, &w->shown);
        with_trans(w, &w->from);
        cub_motion_pose_blend(&w->from, &w->shown, k, &w->shown);
    }
    w->drawn = 1;
    *pose = w->shown;
}

/* ---- set-up ------------------------------------------------------------------ */

/* The walk clip's joint for each of the coach's: the same name, or for an
 * end site the end site under the same parent. -1 when one is missing. */
static int map_joints(cub_walk_box *w, const cub_skeleton *coach)
{
    const cub_skeleton *src = &w->m.skel;
    for (int j = 0; j < coach->joint_count; j++) {
        int k = cub_motion_skeleton_find(src, coach->joints[j].name);
        int parent = coach->joints[j].parent;
        for (int i = 0; k < 0 && parent >= 0 && i < src->joint_count; i++)
            if (src->joints[i].is_end_site && src->joints[i].parent == w->map[parent]) k = i;
        if (k < 0) return -1;
        w->map[j] = (int16_t)k;
    }
    return 0;
}

static cub_err analyse(cub_walk_box *w)
{
    const cub_skeleton *s = &w->m.skel;
    int ankle[2] = {cub_motion_skeleton_find(s, "LeftFoot"), cub_motion_skeleton_find(s, "RightFoot")};
    int toe[2] = {cub_motion_skeleton_find(s, "LeftFoot_end"),
                  cub_motion_skeleton_find(s, "RightFoot_end")};
    if (ankle[0] < 0 || ankle[1] < 0 || toe[0] < 0 || toe[1] < 0) return CUB_ERR_FORMAT;
    return cub_walk_clip_make(&w->walk, &w->m.clip, ankle, toe);
}

/* The clip must hold a walk the walker can start. */
static cub_err check_walk(cub_walk_box *w)
{
    cub_gait_walk_params p = {.start_mm = w->place};
    return cub_gait_walker_init(&w->walker, &w->walk.wc, &w->terrain, &p);
}

/* The clip frames of the key poses: the cycle's first (a walk begins at
 * the left foot-off), and the frames before the left and the right
 * foot-off (the walker holds one when it stops). -1: no right foot-off. */
static int key_frames(const cub_walk_box *w, int out[CUB_WALK_KEYS])
{
    const cub_gait_walker *k = &w->walker; /* as check_walk left it */
    const uint8_t *right = w->walk.phase[1];
    int r = -1;
    for (int f = k->a + 1; f < k->b && r < 0; f++)
        if (right[f] == CUB_GAIT_OFF && right[f - 1] != CUB_GAIT_OFF) r = f;
    out[CUB_WALK_KEY_START] = k->a;
    out[CUB_WALK_KEY_STOP_LEFT] = k->b - 1;
    out[CUB_WALK_KEY_STOP_RIGHT] = r - 1;
    return r < 0 ? -1 : 0;
}

/* Each key pose as a one-frame clip on the coach's skeleton. */
static cub_err make_keys(cub_walk_box *w)
{
    int f[CUB_WALK_KEYS];
    if (key_frames(w, f)) return CUB_ERR_FORMAT;
    size_t size = (cub_motion_clip_mem_size(w->joint_count, 1, 0) + 15) & ~(size_t)15;
    if (!(w->key_mem = malloc(size * CUB_WALK_KEYS))) return CUB_ERR_NOMEM;
    cub_err e = CUB_OK;
    for (int i = 0; i < CUB_WALK_KEYS && !e; i++) {
        e = cub_motion_clip_init(&w->keys[i], w->skel, 1, w->m.clip.frame_ns, 0,
                                 (char *)w->key_mem + size * (size_t)i, size);
        if (!e) e = cub_motion_clip_get_frame(&w->m.clip, f[i], &w->from);
        if (!e) walker_pose_of(w, &w->from, &w->shown);
        if (!e) e = cub_motion_clip_set_frame(&w->keys[i], 0, &w->shown);
    }
    return e;
}

cub_err cub_walk_box_add_keys(cub_walk_box *w, cub_coachlib *cl, const char **names,
                              char *err, size_t err_size)
{
    if (!w->joint_count) return CUB_OK;
    int first = cl->table.desc.clip_count;
    cub_diag diag = {0};
    cub_coachlib_extra extra[CUB_WALK_KEYS]; /* one frame each: itself the bridge frame */
    for (int i = 0; i < CUB_WALK_KEYS; i++)
        extra[i] = (cub_coachlib_extra){.clip = &w->keys[i]};
    if (cub_coachlib_add_clips(cl, extra, CUB_WALK_KEYS, &diag)) {
        cub_diag_report(CUB_ERR_FORMAT, &diag, err, err_size);
        return CUB_ERR_FORMAT;
    }
    for (int i = 0; i < CUB_WALK_KEYS; i++)
        names[first + i] = key_names[i];
    w->names = names;
    w->key_first = first;
    return CUB_OK;
}

cub_err cub_walk_box_open(cub_walk_box *w, const char *path, const cub_floor *floor,
                          const cub_skeleton *coach, cub_log *log, cub_diag *diag)
{
    memset(w, 0, sizeof *w);
    w->log = log;
    w->skel = coach;
    w->place = at_xz(start_xz);
    w->last_state = CUB_COACH_IDLE;
    w->key_first = -1;
    cub_err e = cub_io_load_bvh(path, &(cub_io_desc){0}, &w->m, diag);
    if (e) return e;
    if (!floor) cub_gait_terrain_flat(&w->terrain, 0);
    else if (cub_floor_terrain(floor, &w->terrain))
        return cub_diag_fail(diag, CUB_ERR_ARG, path, 0, "the floor makes no terrain");
    if (map_joints(w, coach)) return CUB_OK; /* another coach: it does not walk */
    w->joint_count = coach->joint_count;
    e = analyse(w);
    if (!e) e = check_walk(w);
    if (!e) e = make_keys(w);
    if (e) {
        w->joint_count = 0;
        return cub_diag_fail(diag, CUB_ERR_FORMAT, path, 0, "not a walk the walker can play (%s)",
                             cub_err_str(e));
    }
    return CUB_OK;
}

void cub_walk_box_close(cub_walk_box *w)
{
    cub_walk_clip_free(&w->walk);
    free(w->key_mem);
    free(w->plan_work);
    if (w->m.frame_mem) cub_io_motion_free(&w->m);
    memset(w, 0, sizeof *w);
}

cub_err cub_dance_open_walk(cub_dance *d, const char *path, const cub_floor *floor, char *err,
                            size_t err_size)
{
    cub_diag diag = {0};
    d->walk = calloc(1, sizeof *d->walk);
    cub_err e = d->walk ? cub_walk_box_open(d->walk, path, floor, &d->cl.lib.skel, d->log, &diag)
                        : CUB_ERR_NOMEM;
    if (e) cub_diag_report(e, &diag, err, err_size);
    return e;
}

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

/* The picture's fade at a hand-over [ours: a little over a step's half];
 * a walk in that lands on the dance's feet fades for as long as its farthest
 * joint needs at BLEND_MM_S (the bridge player's 25 mm a frame at 30 fps),
 * BLEND_MIN_US at least. */
#define BLEND_US 400000
#define BLEND_MM_S 750
#define BLEND_MIN_US 33334 /* one frame of the box's */
#define WANDER_REST_US 2000000 /* attracting: stand this long between wanders */
#define ARRIVE_MM 60          /* the root this near the target: arrived */
#define PASS_MM 30            /* ... or farther than its nearest by this, once within NEAR_MM */
#define NEAR_MM 300
/* The walk in should arrive while the wake lasts (the coach's wake_up
 * clip): its rate is chosen from the distance and the time the clip has
 * left, at least the clip's own, at most WALK_IN_MAX_Q8 (3.25x: the bear's
 * legs are 0.31 of the capture's, and by the speed's square-root scaling
 * with leg length its natural cadence is already ~1.8x the capture's;
 * 3x is a hurried walk; 3.25x since the root follows the pinned feet, its
 * stride ~5 % shorter by the capture's stance slide: the demo's walk in
 * took 12 steps and arrived 33 ms after the dance began at 3x). It stops
 * where it is after WALK_IN_US at the latest [ours; docs/gait.md has the
 * measured times]. */
#define WALK_IN_MAX_Q8 (13 * 64)
#define WALK_IN_US 6000000
/* Steps the walk in adds to the straight distance's: the closing step onto
 * the dance's footholds and the settle, and one more since the root
 * follows the pinned feet (the shorter stride left the demo's step 9 short
 * of its end foothold: 12 steps, not 11) [ours]. */
#define WALK_IN_EXTRA_STEPS 3
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
/* under the round tree on the left (its trunk 0.2 m away, its crown 0.57 m
 * wide over it): 2.12 m out, what a 3x walk covers in the wake */
static const int32_t start_xz[2] = {-1550, -1450};
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

static int32_t dist_mm(cub_vec3 a, cub_vec3 b)
{
    return (int32_t)cub_fx_isqrt64((uint64_t)dist2(a, b));
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
    w->blend_us = BLEND_US;
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
    /* a walk in on the dance's footholds: little to blend, enter at once */
    if (key != CUB_WALK_KEY_START && w->walker.p.has_end) q.reach_frames = 1;
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

static int64_t due_frames(const cub_walk_box *w, int64_t t_us);
static void walker_pose_of(const cub_walk_box *w, const cub_pose *p, cub_pose *out);

/* The coach's picture at its place now: its player's pose as the box
 * shows it, the switch's blend on (the clip's raw frame jumps at a switch,
 * and a walk arriving in it showed the jump; docs/gait.md), the root moved
 * there at the ground's height (as cub_walk_box_pose stands it). The
 * player's pose only writes its scratch and ends a finished blend, as the
 * dance's own pose does at the same position. */
static void coach_at_home(const cub_walk_box *w, const cub_bridge_player *p, cub_pose *out)
{
    cub_vec3 h = at_xz(home_xz);
    cub_bridge_player_pose((cub_bridge_player *)p, out);
    h.y = cub_gait_ground_height(&w->terrain, h.x, h.z);
    out->root_mm = cub_fx_vec3_add(out->root_mm, h);
}

/* The farthest joint and the farther foot (ankle) between the walker's
 * pose and the coach's at its place, whole mm. */
static void pose_gap(cub_walk_box *w, const cub_bridge_player *p, int32_t *joint, int32_t *foot)
{
    cub_vec3 a[CUB_MOTION_MAX_JOINTS], b[CUB_MOTION_MAX_JOINTS];
    cub_pose pc, pw;
    coach_at_home(w, p, &pc);
    walker_pose_of(w, &w->walker.pose, &pw);
    *joint = *foot = 0;
    if (cub_motion_forward(w->skel, &pw, a, NULL) || cub_motion_forward(w->skel, &pc, b, NULL))
        return;
    for (int j = 0; j < w->joint_count; j++) {
        int32_t d = (int32_t)cub_fx_isqrt64((uint64_t)dist2(a[j], b[j]) +
                                            (uint64_t)((int64_t)mm(a[j].y - b[j].y) * mm(a[j].y - b[j].y)));
        if (d > *joint) *joint = d;
        if ((j == w->foot_j[0] || j == w->foot_j[1]) && d > *foot) *foot = d;
    }
}

static cub_q16 deg(cub_q16 rad)
{
    return (cub_q16)((int64_t)rad * 180 * CUB_Q16_ONE / CUB_Q16_PI);
}

/* The angle between two rotations. */
static cub_q16 quat_turn(cub_quat a, cub_quat b)
{
    return cub_fx_quat_angle(cub_fx_quat_mul(cub_fx_quat_conj(a), b));
}

/* The walker stepped `frames` clip frames: the fastest turn of any of
 * the coach's joints (the root's too) per clip frame, while it arrives
 * (an end foot planned) and before: arriving should turn no joint faster
 * than walking does (no pop; the walk's own knees pass the clip's p99). */
static void note_turns(cub_walk_box *w, int frames)
{
    const cub_pose *p = &w->walker.pose;
    int arriving = w->walker.feet[0].at_end || w->walker.feet[1].at_end;
    for (int j = 0; j < w->joint_count; j++) {
        cub_quat q = p->rot[w->map[j]];
        cub_q16 a = frames > 0 ? quat_turn(w->prev_rot[j], q) / frames : 0;
        cub_q16 *most = arriving ? &w->arrive_rad : &w->walk_rad;
        if (a > *most) *most = a;
        w->prev_rot[j] = q;
    }
}

/* The coach's pose at its place now, on the walk clip's skeleton: where
 * a walk in on the dance's feet arrives (the walker eases into it over
 * its end steps and holds it while it waits). */
static void track_coach(cub_walk_box *w, const cub_bridge_player *p)
{
    cub_pose pc;
    if (!w->walker.p.has_end) return;
    coach_at_home(w, p, &pc);
    for (int j = 0; j < w->joint_count; j++)
        w->end_pose.rot[w->map[j]] = pc.rot[j];
    w->end_pose.root_mm = pc.root_mm;
}

/* The picture goes over into the dance: a walk in on the dance's
 * footholds fades for as long as its farthest joint needs. */
static void hand_over(cub_walk_box *w, const cub_bridge_player *p, int64_t t_us)
{
    int32_t joint, foot;
    pose_gap(w, p, &joint, &foot);
    switch_now(w, t_us);
    if (w->walker.p.has_end) {
        int64_t us = (int64_t)joint * 1000000 / BLEND_MM_S;
        w->blend_us = us < BLEND_MIN_US ? BLEND_MIN_US : us > BLEND_US ? BLEND_US : us;
    }
    cub_log_event(w->log, t_us, "walk", "enter",
                  "clip=%s frame=%d foot_mm=%d joint_mm=%d blend_ms=%d arrive_dpf=%q walk_dpf=%q "
                  "p99_dpf=%q",
                  clip_name(w, w->hand_clip), w->hand_frame, foot, joint,
                  (int)(w->blend_us / 1000), deg(w->arrive_rad), deg(w->walk_rad),
                  deg(w->p99_rad));
    w->hand = 0;
    w->place = at_xz(home_xz);
}

/* Waiting at the stop on the dance's footholds: the walker holds its stop
 * frame and settles the lifting foot flat (it walks on no more). */
static void hold_on(cub_walk_box *w, int64_t t_us)
{
    const cub_pose *pose;
    int64_t due = due_frames(w, t_us);
    while (w->walker.p.has_end && w->walker.stopped && w->frames < due) {
        int settle = w->walker.settle;
        if (cub_gait_walker_step(&w->walker, w->target, &pose)) return;
        w->frames++;
        if (w->walker.settle == settle) { /* settled: the pose follows the coach's */
            note_turns(w, 0); /* the coach's own motion, not the arrival's */
            w->frames = (int)due;
            w->settled = 1;
            return;
        }
        note_turns(w, 1);
    }
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
    int settling = w->walker.p.has_end && !w->settled;
    if (p->pos_q16 >= w->hand_at_q16 && !settling) hand_over(w, p, t_us);
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

/* How long the coach's player plays on in the clip it is in, or switching
 * to (the wake_up clip: the dance begins at its end), microseconds. */
static int64_t clip_left_us(const cub_bridge_player *p)
{
    const cub_bridge_table *t = p->desc.table;
    int clip = p->clip;
    int64_t pos = p->pos_q16, wait = 0;
    cub_q16 speed = p->speed_q16;
    if (cub_bridge_player_pending(p) && p->plan.step_count > 0) {
        const cub_bridge_step *s = &p->plan.step[p->plan.step_count - 1];
        wait = p->plan.step[0].at_q16 > pos ? p->plan.step[0].at_q16 - pos : 0;
        clip = s->to_clip;
        pos = CUB_Q16_INT((int64_t)s->to_frame);
        speed = p->want_speed_q16;
    }
    const cub_clip *c = &t->clips[clip].clip;
    int64_t left_q16 = wait + CUB_Q16_INT((int64_t)c->frame_count) - pos;
    if (left_q16 <= 0 || speed <= 0) return 0;
    return ((left_q16 << 16) / speed) * (int64_t)(c->frame_ns / 1000) >> 16;
}

/* The walk in's rate (Q8): the walker frames the distance and the closing
 * steps need, over the time the wake has left; the clip's own rate at
 * least, WALK_IN_MAX_Q8 at most. */
static int in_rate_q8(const cub_walk_box *w, const cub_bridge_player *p, int32_t dist)
{
    const cub_gait_walker *k = &w->walker;
    int64_t cycle = mm(cub_fx_vec3_length(k->travel_u)), len = k->b - k->a; /* its travel */
    int64_t left = clip_left_us(p);
    if (cycle <= 0 || left <= 0) return WALK_IN_MAX_Q8;
    int64_t frames = (dist * len + cycle - 1) / cycle + WALK_IN_EXTRA_STEPS * len / 2;
    int64_t q8 = (frames * (int64_t)w->m.clip.frame_ns / 1000 * 256 + left - 1) / left;
    return q8 < 256 ? 256 : q8 > WALK_IN_MAX_Q8 ? WALK_IN_MAX_Q8 : (int)q8;
}

/* The coach's feet at its place now (x, z): where a walk in ends, so the
 * dance's first frame finds them there (every clip of the bear's library
 * stands its feet at the same place). 0: found. */
static int coach_feet(const cub_walk_box *w, const cub_bridge_player *p, cub_vec3 out[2])
{
    cub_pose pc;
    cub_quat q;
    if (!p || w->foot_j[0] < 0 || w->foot_j[1] < 0) return -1;
    coach_at_home(w, p, &pc);
    for (int i = 0; i < 2; i++)
        if (cub_motion_joint_world(w->skel, &pc, w->foot_j[i], &out[i], &q)) return -1;
    return 0;
}

/* Walk to `to`; p: the coach's player for a walk in (its rate and its end
 * on the dance's feet), else NULL. */
static void go(cub_walk_box *w, const cub_bridge_player *pl, cub_vec3 to, cub_walk_why why,
               int64_t t_us, int64_t deadline_us)
{
    cub_vec3 at = w->walking ? root_xz(w) : w->place;
    if (dist2(at, to) <= (int64_t)ARRIVE_MM * ARRIVE_MM) return; /* there already */
    cub_gait_walk_params p = {.start_mm = at, .dir_x = to.x - at.x, .dir_z = to.z - at.z,
                              .on_event = on_event, .ctx = w};
    p.has_end = why == CUB_WALK_IN && w->key_first >= 0 && !coach_feet(w, pl, p.end_mm);
    if (p.has_end) p.end_pose = &w->end_pose;
    w->now_us = t_us;
    if (cub_gait_walker_init(&w->walker, &w->walk.wc, &w->terrain, &p))
        return; /* checked at open */
    w->rate_q8 = why == CUB_WALK_IN ? in_rate_q8(w, pl, dist_mm(at, to)) : 256;
    cub_log_event(w->log, t_us, "walk", "start",
                  "why=%s from_x=%d from_z=%d to_x=%d to_z=%d rate=%q", why_name(why),
                  mm(at.x), mm(at.z), mm(to.x), mm(to.z), (cub_q16)(w->rate_q8 * 256));
    w->walking = 1;
    w->why = why;
    w->target = to;
    w->walk_t0_us = t_us;
    w->deadline_us = deadline_us;
    w->frames = 0;
    w->settled = 0;
    w->best_mm = INT32_MAX;
    w->arrive_rad = w->walk_rad = 0;
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

/* Walker frames due by t_us since the walk began. */
static int64_t due_frames(const cub_walk_box *w, int64_t t_us)
{
    return (t_us - w->walk_t0_us) * 1000 * w->rate_q8 / ((int64_t)w->m.clip.frame_ns * 256);
}

/* Where the walker steers: the target, or for a walk in on the dance's
 * footholds a point before them along the dance's facing, half the root's
 * distance back, so the walk curves in and ends facing as the dance
 * begins (the walker turns at most 10 degrees a step) [ours]. */
static cub_vec3 aim(const cub_walk_box *w)
{
    const cub_gait_walk_params *p = &w->walker.p;
    if (!p->has_end) return w->target;
    cub_vec3 lr = cub_fx_vec3_sub(p->end_mm[0], p->end_mm[1]); /* right foot -> left */
    cub_q16 len = cub_fx_vec3_length((cub_vec3){lr.x, 0, lr.z});
    if (len <= 0) return w->target;
    cub_q16 back = CUB_Q16_INT(dist_mm(root_xz(w), w->target)) / 2;
    cub_q16 k = cub_fx_div(back, len);
    return (cub_vec3){w->target.x + cub_fx_mul(lr.z, k), 0, w->target.z - cub_fx_mul(lr.x, k)};
}

static void walk_on(cub_walk_box *w, int64_t t_us)
{
    int64_t due = due_frames(w, t_us);
    w->now_us = t_us;
    while (w->walking && w->frames < due) {
        const cub_pose *pose;
        if (cub_gait_walker_step(&w->walker, aim(w), &pose)) {
            stop(w, t_us, "error");
            return;
        }
        w->frames++;
        note_turns(w, w->frames > 1); /* the first: from the last walk's pose */
        if (w->walker.blocked) stop(w, t_us, "blocked");
        else if (w->walker.stopped || (arrived(w) && !w->walker.p.has_end))
            stop(w, t_us, "arrived");
    }
    if (w->walking && w->deadline_us && t_us >= w->deadline_us) stop(w, t_us, "time");
}

static void wander(cub_walk_box *w, int64_t t_us)
{
    go(w, NULL, at_xz(wander_xz[w->wander]), CUB_WALK_WANDER, t_us, 0);
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
        go(w, p, at_xz(home_xz), CUB_WALK_IN, t_us, t_us + WALK_IN_US);
    else if (to == CUB_COACH_ATTRACT)
        wander(w, t_us);
    else if (to == CUB_COACH_IDLE && !resting(from) && w->key_first >= 0)
        plan_off(w, p, t_us);
    else if (to == CUB_COACH_IDLE && !resting(from))
        go(w, NULL, at_xz(off_xz), CUB_WALK_OFF, t_us, 0);
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
        go(w, NULL, at_xz(off_xz), CUB_WALK_OFF, t_us, 0);
    }
    if (w->walking || w->hand) track_coach(w, player);
    if (w->walking) walk_on(w, t_us);
    else if (w->hand) {
        hold_on(w, t_us);
        hand_on(w, player, coach_state, t_us);
    }
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
    if (dt >= w->blend_us) return CUB_Q16_ONE;
    cub_q16 x = (cub_q16)(dt * CUB_Q16_ONE / w->blend_us);
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

static int cmp_q16(const void *a, const void *b)
{
    cub_q16 x = *(const cub_q16 *)a, y = *(const cub_q16 *)b;
    return (x > y) - (x < y);
}

/* The walk clip's 99th percentile of a joint's turn from one frame to
 * the next (the coach's joints), what an arrival's turns are held to. */
static cub_err turn_p99(cub_walk_box *w)
{
    const cub_clip *c = &w->m.clip;
    int nj = w->m.skel.joint_count, n = (c->frame_count - 1) * w->joint_count;
    if (n <= 0) return CUB_ERR_FORMAT;
    cub_q16 *v = malloc(sizeof *v * (size_t)n);
    if (!v) return CUB_ERR_NOMEM;
    for (int f = 1, i = 0; f < c->frame_count; f++)
        for (int j = 0; j < w->joint_count; j++, i++)
            v[i] = quat_turn(c->rot[(f - 1) * nj + w->map[j]], c->rot[f * nj + w->map[j]]);
    qsort(v, (size_t)n, sizeof *v, cmp_q16);
    w->p99_rad = v[(n - 1) * 99 / 100];
    free(v);
    return CUB_OK;
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
    w->foot_j[0] = cub_motion_skeleton_find(coach, "LeftFoot");
    w->foot_j[1] = cub_motion_skeleton_find(coach, "RightFoot");
    e = analyse(w);
    if (!e) e = check_walk(w);
    if (!e) e = make_keys(w);
    if (!e) e = turn_p99(w);
    if (!e) e = cub_motion_clip_get_frame(&w->m.clip, 0, &w->end_pose); /* joints unmapped */
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

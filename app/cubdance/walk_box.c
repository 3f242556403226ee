/* The bear's walks in the box: which walk the coach's state asks for, the
 * walker stepped at the clip's rate, its footsteps logged, and the
 * picture handed between the walk and the coach's clips by a short
 * crossfade (docs/gait.md "The bear walks in the box"). */
#include "walk_box.h"

#include <stdlib.h>
#include <string.h>

#include "cub/coach.h"

#define BLEND_US 400000       /* walk <-> stand crossfade [ours: a little over a step's half] */
#define WANDER_REST_US 2000000 /* attracting: stand this long between wanders */
#define ARRIVE_MM 60          /* the root this near the target: arrived */
#define PASS_MM 30            /* ... or farther than its nearest by this, once within NEAR_MM */
#define NEAR_MM 300
/* The walk in must end, and its crossfade too, before the dance's first
 * frame: the wake state lasts 2.23 s after START (the bridge enters the
 * wake_up clip past its start and leaves it early), so the walk has 1.8 s
 * and the crossfade 0.4 s [ours; measured on the scenario logs]. */
#define WALK_IN_US 1800000

/* Where the bear goes (x, z mm; its place is the origin, the camera on
 * +z). Every point is within 0.65 m of the place: from any of them the
 * walk in (~0.38 m/s with its first step) ends within WALK_IN_US [ours]. */
static const int32_t home_xz[2] = {0, 0};
static const int32_t start_xz[2] = {-400, -500};  /* toward the trees, behind on the left */
static const int32_t off_xz[2] = {450, -450};     /* off toward the trees on the right */
static const int32_t wander_xz[][2] = {{-500, -350}, {150, -600}, {550, -250}};
#define WANDERS ((int)(sizeof wander_xz / sizeof *wander_xz))

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

/* ---- walking and standing -------------------------------------------------- */

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

static void stop(cub_walk_box *w, int64_t t_us, const char *how)
{
    cub_vec3 at = root_xz(w);
    w->place = w->why == CUB_WALK_IN ? at_xz(home_xz) : at; /* the dance is at its place */
    cub_log_event(w->log, t_us, "walk", "stop", "why=%s how=%s x=%d z=%d steps=%d",
                  why_name(w->why), how, mm(at.x), mm(at.z), w->walker.steps);
    w->walking = 0;
    switch_now(w, t_us);
}

static void go(cub_walk_box *w, cub_vec3 to, cub_walk_why why, int64_t t_us, int64_t deadline_us)
{
    cub_vec3 at = w->walking ? root_xz(w) : w->place;
    if (dist2(at, to) <= (int64_t)ARRIVE_MM * ARRIVE_MM) return; /* there already */
    cub_gait_walk_params p = {.start_mm = at, .dir_x = to.x - at.x, .dir_z = to.z - at.z,
                              .on_event = on_event, .ctx = w};
    w->now_us = t_us;
    if (cub_gait_walker_init(&w->walker, &w->wc, &w->terrain, &p)) return; /* checked at open */
    cub_log_event(w->log, t_us, "walk", "start", "why=%s from_x=%d from_z=%d to_x=%d to_z=%d",
                  why_name(why), mm(at.x), mm(at.z), mm(to.x), mm(to.z));
    w->walking = 1;
    w->why = why;
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
    int64_t due = (t_us - w->walk_t0_us) * 1000 / (int64_t)w->m.clip.frame_ns;
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

static int resting(int32_t st)
{
    return st == CUB_COACH_IDLE || st == CUB_COACH_ATTRACT || st == CUB_COACH_DOZE ||
           st == CUB_COACH_WAKE;
}

/* A new coach state: START woke it (walk in, and the crossfade, before
 * the dance begins), a song ended or was stopped (walk off), attract
 * (wander); anything else ends a wander. */
static void follow(cub_walk_box *w, int32_t from, int32_t to, int64_t t_us)
{
    if (to == CUB_COACH_WAKE)
        go(w, at_xz(home_xz), CUB_WALK_IN, t_us, t_us + WALK_IN_US);
    else if (to == CUB_COACH_ATTRACT)
        wander(w, t_us);
    else if (to == CUB_COACH_IDLE && !resting(from))
        go(w, at_xz(off_xz), CUB_WALK_OFF, t_us, 0);
    else if (w->walking && w->why != CUB_WALK_OFF)
        stop(w, t_us, "state");
}

void cub_walk_box_tick(cub_walk_box *w, int32_t coach_state, int64_t t_us)
{
    if (!w->joint_count) return;
    int32_t from = w->last_state;
    w->last_state = coach_state;
    if (coach_state != from) follow(w, from, coach_state, t_us);
    if (w->walking) walk_on(w, t_us);
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

static void walker_pose(const cub_walk_box *w, cub_pose *out)
{
    const cub_pose *p = &w->walker.pose;
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
    if (w->walking) {
        walker_pose(w, &w->shown);
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
    size_t n = (size_t)w->m.clip.frame_count;
    for (int i = 0; i < 4; i++)
        if (!(w->track[i] = calloc(n, sizeof(cub_vec3)))) return CUB_ERR_NOMEM;
    for (int i = 0; i < 2; i++)
        if (!(w->phase[i] = calloc(n, 1))) return CUB_ERR_NOMEM;
    cub_vec3 *const am[2] = {w->track[0], w->track[2]}, *const tm[2] = {w->track[1], w->track[3]};
    return cub_gait_walk_clip_make(&w->m.clip, ankle, toe, am, tm, w->phase, &w->wc);
}

/* The clip must hold a walk the walker can start. */
static cub_err check_walk(cub_walk_box *w)
{
    cub_gait_walk_params p = {.start_mm = w->place};
    return cub_gait_walker_init(&w->walker, &w->wc, &w->terrain, &p);
}

cub_err cub_walk_box_open(cub_walk_box *w, const char *path, const cub_floor *floor,
                          const cub_skeleton *coach, cub_log *log, cub_diag *diag)
{
    memset(w, 0, sizeof *w);
    w->log = log;
    w->skel = coach;
    w->place = at_xz(start_xz);
    w->last_state = CUB_COACH_IDLE;
    cub_err e = cub_io_load_bvh(path, &(cub_io_desc){0}, &w->m, diag);
    if (e) return e;
    if (!floor) cub_gait_terrain_flat(&w->terrain, 0);
    else if (cub_floor_terrain(floor, &w->terrain))
        return cub_diag_fail(diag, CUB_ERR_ARG, path, 0, "the floor makes no terrain");
    if (map_joints(w, coach)) return CUB_OK; /* another coach: it does not walk */
    e = analyse(w);
    if (!e) e = check_walk(w);
    if (e)
        return cub_diag_fail(diag, CUB_ERR_FORMAT, path, 0, "not a walk the walker can play (%s)",
                             cub_err_str(e));
    w->joint_count = coach->joint_count;
    return CUB_OK;
}

void cub_walk_box_close(cub_walk_box *w)
{
    for (int i = 0; i < 4; i++)
        free(w->track[i]);
    for (int i = 0; i < 2; i++)
        free(w->phase[i]);
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

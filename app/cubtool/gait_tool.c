/* gait_tool — a captured walk loaded for the walker, the named terrains,
 * and one measured run (gait_tool.h). Host code: doubles for the figures
 * only; the walk itself is the firmware's fixed point. */
#include "gait_tool.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cub/floor_file.h"
#include "tool_util.h"

#define MM(q) ((q) / 65536.0)
#define RAD2DEG (180.0 / 3.14159265358979)

/* ---- loading ---------------------------------------------------------------- */

/* Leg joint names by skeleton family: CMU's BVH, Daz's (CMU 03, 07, 08),
 * then the bear's (a retargeted clip: the toe is the foot's end site). */
static const char *const leg_names[][4] = {
    {"LeftFoot", "LeftToeBase", "RightFoot", "RightToeBase"},
    {"lFoot", "lFoot_end", "rFoot", "rFoot_end"},
    {"LeftFoot", "LeftFoot_end", "RightFoot", "RightFoot_end"},
};

static int resolve(const char *clip, const char *data_dir, char *path, size_t n)
{
    if (access(clip, R_OK) == 0) return snprintf(path, n, "%s", clip) < (int)n ? 0 : -1;
    snprintf(path, n, "%s/mocap/cmu/%s.bvh", data_dir, clip);
    if (access(path, R_OK) == 0) return 0;
    snprintf(path, n, "%s/mocap/cmu/daz43/%s.bvh", data_dir, clip);
    return access(path, R_OK) == 0 ? 0 : -1;
}

/* The clip's ankle and toe joints ([0] the left) by the first family
 * that names all four; -1 when none does. */
static int find_legs(const gait_src *s, int ankle[2], int toe[2])
{
    for (size_t k = 0; k < sizeof leg_names / sizeof *leg_names; k++) {
        int j[4];
        for (int i = 0; i < 4; i++)
            j[i] = cub_motion_skeleton_find(&s->m.skel, leg_names[k][i]);
        if (j[0] > 0 && j[1] > 0 && j[2] > 0 && j[3] > 0) {
            ankle[0] = j[0], toe[0] = j[1], ankle[1] = j[2], toe[1] = j[3];
            return 0;
        }
    }
    return -1;
}

int gait_src_load(gait_src *s, const char *clip, const char *data_dir, const char *who)
{
    memset(s, 0, sizeof *s);
    char path[800];
    if (resolve(clip, data_dir, path, sizeof path)) {
        fprintf(stderr, "cubtool %s: %s: no such file, nor a CMU clip under %s/mocap/cmu\n", who,
                clip, data_dir);
        return 1;
    }
    snprintf(s->name, sizeof s->name, "%s", clip);
    cub_diag d = {0};
    char msg[700];
    if (cub_io_load_bvh(path, &(cub_io_desc){0}, &s->m, &d)) {
        fprintf(stderr, "cubtool %s: %s\n", who, cub_diag_str(&d, msg, sizeof msg));
        return 1;
    }
    int ankle[2], toe[2];
    if (find_legs(s, ankle, toe)) {
        fprintf(stderr, "cubtool %s: %s: no leg joints (LeftFoot/LeftToeBase or lFoot/rFoot)\n",
                who, path);
        return 1;
    }
    if (s->m.clip.frame_count < 4 || cub_walk_clip_make(&s->walk, &s->m.clip, ankle, toe)) {
        fprintf(stderr, "cubtool %s: %s: too short to analyse as a walk\n", who, path);
        return 1;
    }
    return 0;
}

void gait_src_free(gait_src *s)
{
    cub_walk_clip_free(&s->walk);
    if (s->m.frame_mem) cub_io_motion_free(&s->m);
    memset(s, 0, sizeof *s);
}

/* ---- terrains ----------------------------------------------------------------- */

#define CELL_MM 200
#define ORIGIN_X_MM (-(GAIT_GRID / 2) * CELL_MM)
#define ORIGIN_Z_MM (-2000)

static void grid(gait_ground *g)
{
    g->t.origin_x_mm = CUB_Q16_INT(ORIGIN_X_MM);
    g->t.origin_z_mm = CUB_Q16_INT(ORIGIN_Z_MM);
}

/* ours: 10 cm up every 1.2 m from z = 1 m, four times; the heightfield
 * makes each edge a 20 cm ramp. */
static void steps(gait_ground *g)
{
    cub_gait_terrain_rolling(&g->t, g->heights, GAIT_GRID, GAIT_GRID, CUB_Q16_INT(CELL_MM), 0,
                             CUB_Q16_INT(1000));
    for (int j = 0; j < GAIT_GRID; j++) {
        int z = ORIGIN_Z_MM + j * CELL_MM, n = z < 1000 ? 0 : 1 + (z - 1000) / 1200;
        for (int i = 0; i < GAIT_GRID; i++)
            g->heights[j * GAIT_GRID + i] = CUB_Q16_INT(100 * (n < 4 ? n : 4));
    }
    grid(g);
}

/* A terrain names a file when something is there (even a link that
 * leads nowhere: the reader says why it cannot be read). */
static int is_file(const char *name)
{
    struct stat st;
    return lstat(name, &st) == 0;
}

int gait_ground_make(gait_ground *g, const char *name, const char *who)
{
    memset(g, 0, sizeof *g);
    snprintf(g->name, sizeof g->name, "%s", name);
    if (!strcmp(name, "flat")) {
        cub_gait_terrain_flat(&g->t, 0);
    } else if (!strcmp(name, "slope")) {
        cub_gait_terrain_slope(&g->t, 0, 0, 5733); /* tan 5 degrees */
    } else if (!strcmp(name, "rolling")) {
        /* ours: 6 cm hills, 4 m apart: a forest floor, not a hillside */
        cub_gait_terrain_rolling(&g->t, g->heights, GAIT_GRID, GAIT_GRID, CUB_Q16_INT(CELL_MM),
                                 CUB_Q16_INT(60), CUB_Q16_INT(4000));
        grid(g);
    } else if (!strcmp(name, "steps")) {
        steps(g);
    } else if (is_file(name)) {
        cub_diag d = {0};
        char msg[700];
        if (cub_floor_load(name, &g->floor, &d) || cub_floor_terrain(&g->floor, &g->t)) {
            fprintf(stderr, "cubtool %s: %s\n", who, cub_diag_str(&d, msg, sizeof msg));
            return 1;
        }
    } else {
        fprintf(stderr,
                "cubtool %s: unknown terrain '%s' (flat, slope, rolling, steps, or a floor file)\n",
                who, name);
        return 2;
    }
    return 0;
}

static cub_gait_box box_at(const gait_ground *g, double x, double z, double sx, double sz,
                           double h)
{
    cub_q16 y = cub_gait_ground_height(&g->t, (cub_q16)(x * 65536), (cub_q16)(z * 65536));
    return (cub_gait_box){{(cub_q16)((x - sx / 2) * 65536), y - CUB_Q16_INT(50),
                           (cub_q16)((z - sz / 2) * 65536)},
                          {(cub_q16)((x + sx / 2) * 65536), y + (cub_q16)(h * 65536),
                           (cub_q16)((z + sz / 2) * 65536)}};
}

int gait_ground_add(gait_ground *g, const char *obstacle, const char *who)
{
    cub_gait_box b;
    int stones = 0;
    for (int i = 0; i < g->t.obstacle_count; i++)
        stones += g->t.obstacles[i].max_mm.x - g->t.obstacles[i].min_mm.x < CUB_Q16_INT(1000);
    if (!strcmp(obstacle, "log")) {
        b = box_at(g, 0, 1500, 2000, 150, 150);
    } else if (!strcmp(obstacle, "stone")) {
        if (stones >= GAIT_MAX_STONES) {
            fprintf(stderr, "cubtool %s: at most %d stones\n", who, GAIT_MAX_STONES);
            return 1;
        }
        b = box_at(g, stones % 2 ? -100 : 100, 3000 + 1200 * stones, 160, 160, 70);
    } else {
        fprintf(stderr, "cubtool %s: unknown obstacle '%s' (log, stone)\n", who, obstacle);
        return 1;
    }
    if (cub_gait_terrain_add(&g->t, b)) {
        fprintf(stderr, "cubtool %s: too many obstacles (at most %d)\n", who,
                CUB_GAIT_MAX_OBSTACLES);
        return 1;
    }
    return 0;
}

/* ---- measuring ------------------------------------------------------------------- */

static double quat_deg(cub_quat a, cub_quat b)
{
    return MM(cub_fx_quat_angle(cub_fx_quat_mul(cub_fx_quat_conj(a), b))) * RAD2DEG;
}

static double fps_of(const gait_src *s)
{
    return s->m.clip.frame_ns ? 1e9 / s->m.clip.frame_ns : 120.0;
}

/* hip, knee, ankle of both legs */
static void leg_joints(const gait_src *s, int j[6])
{
    const cub_skeleton *sk = &s->m.skel;
    for (int f = 0; f < 2; f++) {
        j[3 * f + 2] = s->walk.wc.ankle[f];
        j[3 * f + 1] = sk->joints[j[3 * f + 2]].parent;
        j[3 * f] = sk->joints[j[3 * f + 1]].parent;
    }
}

double gait_src_p99_dps(const gait_src *s)
{
    cub_tool_series v = {0};
    int j[6];
    leg_joints(s, j);
    const cub_clip *c = &s->m.clip;
    int nj = s->m.skel.joint_count;
    for (int f = 1; f < c->frame_count; f++)
        for (int k = 0; k < 6; k++)
            cub_tool_series_add(&v, quat_deg(c->rot[(f - 1) * nj + j[k]], c->rot[f * nj + j[k]]) *
                                        fps_of(s),
                                "gait");
    double p = cub_tool_series_pct(&v, 0.99);
    free(v.v);
    return p;
}

/* The thread's CPU time: on the shared machine the wall clock's worst
 * frame was the scheduler's (4-20 ms on flat ground, where no swing is
 * tested). */
static double now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec * 1e6 + ts.tv_nsec / 1e3;
}

static cub_vec3 yaw_rotate(cub_q16 c, cub_q16 s, cub_vec3 v)
{
    return (cub_vec3){cub_fx_add(cub_fx_mul(c, v.x), cub_fx_mul(s, v.z)), v.y,
                      cub_fx_sub(cub_fx_mul(c, v.z), cub_fx_mul(s, v.x))};
}

/* The run's per-frame state. */
typedef struct meter {
    const gait_src *s;
    const gait_ground *g;
    gait_method method;
    gait_figures *fig;
    double p99;
    int legs[6];
    cub_quat prev_rot[6];
    cub_vec3 prev_foot[2], stance_at[2];
    int in_stance[2];
    double slide[2], slide_sum, err_all, err_leg;
    int slide_steps, err_frames, speed_samples, speed_over;
    cub_q16 clip_floor;
} meter;

static void sole(const meter *m, int foot, const cub_vec3 *world, cub_vec3 pts[6])
{
    const cub_gait_walk_clip *wc = &m->s->walk.wc;
    cub_gait_sole_points(world[wc->ankle[foot]], world[wc->toe[foot]], wc->foot[foot].length_mm,
                         wc->foot[foot].ankle_lift_mm, pts);
}

static int over_obstacle(const cub_gait_terrain *t, cub_vec3 p, cub_q16 *top)
{
    for (int i = 0; i < t->obstacle_count; i++) {
        const cub_gait_box *b = &t->obstacles[i];
        if (p.x >= b->min_mm.x && p.x <= b->max_mm.x && p.z >= b->min_mm.z && p.z <= b->max_mm.z) {
            *top = b->max_mm.y;
            return 1;
        }
    }
    return 0;
}

static void ground_figures(meter *m, int foot, const cub_vec3 *world, int swinging)
{
    cub_vec3 pts[6];
    sole(m, foot, world, pts);
    int over = 0;
    for (int k = 0; k < 6; k++) {
        double dip = MM(cub_gait_height(&m->g->t, pts[k].x, pts[k].z) - pts[k].y);
        if (dip > m->fig->pen_max_mm) m->fig->pen_max_mm = dip;
        cub_q16 top;
        if (swinging && over_obstacle(&m->g->t, pts[k], &top)) {
            double c = MM(pts[k].y - top);
            if (c < m->fig->clear_min_mm) m->fig->clear_min_mm = c;
            over = 1;
        }
    }
    m->fig->clear_frames += over;
}

/* The stance ankle's slide: from where its stance began, per step. */
static void slide_figures(meter *m, int foot, cub_vec3 ankle, int stance)
{
    if (stance && !m->in_stance[foot]) {
        m->stance_at[foot] = ankle;
        m->slide[foot] = 0;
    }
    if (stance) {
        double dx = MM(ankle.x - m->stance_at[foot].x), dz = MM(ankle.z - m->stance_at[foot].z);
        double d = sqrt(dx * dx + dz * dz);
        if (d > m->slide[foot]) m->slide[foot] = d;
    }
    if (!stance && m->in_stance[foot]) {
        m->slide_sum += m->slide[foot];
        m->slide_steps++;
        if (m->slide[foot] > m->fig->slide_max_mm) m->fig->slide_max_mm = m->slide[foot];
    }
    m->in_stance[foot] = stance;
}

static void turn_figures(meter *m, const cub_pose *pose, const cub_vec3 *world, int i)
{
    const cub_gait_walk_clip *wc = &m->s->walk.wc;
    for (int f = 0; f < 2; f++) {
        cub_vec3 v = cub_fx_vec3_sub(world[wc->toe[f]], world[wc->ankle[f]]);
        if (i > 0) {
            double a = MM(cub_fx_vec3_angle(m->prev_foot[f], v)) * RAD2DEG;
            if (a > m->fig->rot_max_deg) m->fig->rot_max_deg = a;
        }
        m->prev_foot[f] = v;
    }
    for (int k = 0; k < 6; k++) {
        cub_quat q = pose->rot[m->legs[k]];
        if (i > 0) {
            double dps = quat_deg(m->prev_rot[k], q) * fps_of(m->s);
            if (dps > m->fig->speed_max_dps) m->fig->speed_max_dps = dps;
            m->speed_over += dps > m->p99;
            m->speed_samples++;
        }
        m->prev_rot[k] = q;
    }
}

/* Flat ground: every joint's place from the root against the source's
 * (turned by the walk's yaw), mean mm; the leg joints apart. */
static void error_figures(meter *m, const cub_gait_walker *w, int f, const cub_vec3 *world)
{
    static cub_pose src;
    static cub_vec3 sw[CUB_MOTION_MAX_JOINTS];
    const cub_skeleton *sk = &m->s->m.skel;
    cub_motion_clip_get_frame(&m->s->m.clip, f, &src);
    cub_motion_forward(sk, &src, sw, NULL);
    double all = 0, leg = 0;
    int nleg = 0;
    for (int j = 0; j < sk->joint_count; j++) {
        cub_vec3 a = cub_fx_vec3_sub(world[j], world[0]);
        cub_vec3 b = yaw_rotate(w->yaw_c, w->yaw_s, cub_fx_vec3_sub(sw[j], sw[0]));
        double e = MM(cub_fx_vec3_length(cub_fx_vec3_sub(a, b)));
        all += e;
        int is_leg = 0;
        for (int k = 0; k < 2; k++)
            is_leg |= j == m->s->walk.wc.ankle[k] || j == m->s->walk.wc.toe[k] ||
                      j == sk->joints[m->s->walk.wc.ankle[k]].parent;
        if (is_leg) leg += e, nleg++;
    }
    m->err_all += all / sk->joint_count;
    m->err_leg += nleg ? leg / nleg : 0;
    m->err_frames++;
}

/* The game engine's way: the clip played along the walk's line, each
 * foot raised by the ground under it (a ray down), the pelvis lowered to
 * the lower foot, two-bone IK, the toe put on its own ground. */
static void baseline_pose(const meter *m, const cub_gait_walker *w, int f, int k, cub_pose *pose,
                          cub_vec3 *world)
{
    const cub_clip *c = &m->s->m.clip;
    const cub_skeleton *sk = &m->s->m.skel;
    const cub_gait_terrain *t = &m->g->t;
    cub_motion_clip_get_frame(c, f, pose);
    cub_vec3 ru = c->root_mm[f];
    ru.x += k * w->cycle_u.x;
    ru.z += k * w->cycle_u.z;
    cub_vec3 d = yaw_rotate(w->yaw_c, w->yaw_s, cub_fx_vec3_sub(ru, w->ref_u));
    pose->root_mm = (cub_vec3){w->origin_mm.x + d.x, ru.y - m->clip_floor, w->origin_mm.z + d.z};
    cub_quat yaw = cub_fx_quat_from_axis_angle((cub_vec3){0, CUB_Q16_ONE, 0},
                                               cub_fx_atan2(w->yaw_s, w->yaw_c));
    pose->rot[0] = cub_fx_quat_normalize(cub_fx_quat_mul(yaw, pose->rot[0]));
    cub_motion_forward(sk, pose, world, NULL);
    cub_vec3 at[2], toe[2];
    cub_q16 lift[2];
    for (int ft = 0; ft < 2; ft++) {
        at[ft] = world[m->s->walk.wc.ankle[ft]];
        toe[ft] = world[m->s->walk.wc.toe[ft]];
        lift[ft] = cub_gait_height(t, at[ft].x, at[ft].z);
    }
    pose->root_mm.y += lift[0] < lift[1] ? lift[0] : lift[1];
    for (int ft = 0; ft < 2; ft++) {
        at[ft].y += lift[ft];
        toe[ft].y += cub_gait_height(t, toe[ft].x, toe[ft].z);
        cub_gait_leg_target tg = {m->s->walk.wc.ankle[ft], m->s->walk.wc.toe[ft], at[ft], toe[ft],
                                  {w->dir_x, 0, w->dir_z}};
        cub_gait_leg_pose out;
        cub_gait_leg_apply(sk, pose, &tg, NULL, &out);
    }
}

static void finish(meter *m)
{
    gait_figures *g = m->fig;
    g->slide_mean_mm = m->slide_steps ? m->slide_sum / m->slide_steps : 0;
    g->speed_over_pct = m->speed_samples ? 100.0 * m->speed_over / m->speed_samples : 0;
    g->err_all_mm = m->err_frames ? m->err_all / m->err_frames : -1;
    g->err_leg_mm = m->err_frames ? m->err_leg / m->err_frames : -1;
    if (g->clear_frames == 0) g->clear_min_mm = -1;
}

static void count_event(void *ctx, const cub_gait_event *e)
{
    gait_figures *g = ctx;
    g->planned += e->kind == CUB_GAIT_EV_PLANNED;
    g->backtracks += e->kind == CUB_GAIT_EV_BACKTRACKED ? e->count : 0;
    g->blocked += e->kind == CUB_GAIT_EV_BLOCKED;
}

typedef struct chained {
    cub_gait_event_fn fn;
    void *ctx;
    gait_figures *fig;
} chained;

static void chain_event(void *ctx, const cub_gait_event *e)
{
    chained *c = ctx;
    count_event(c->fig, e);
    if (c->fn) c->fn(c->ctx, e);
}

static cub_q16 lowest_foot(const gait_src *s)
{
    cub_q16 lo = CUB_Q16_MAX;
    for (int i = 0; i < 4; i++)
        for (int f = 0; f < s->m.clip.frame_count; f++)
            if (s->walk.track[i][f].y < lo) lo = s->walk.track[i][f].y;
    return lo;
}

static int source_run(meter *m)
{
    static cub_pose pose;
    static cub_vec3 world[CUB_MOTION_MAX_JOINTS];
    const cub_clip *c = &m->s->m.clip;
    for (int f = 0; f < c->frame_count; f++) {
        cub_motion_clip_get_frame(c, f, &pose);
        cub_motion_forward(&m->s->m.skel, &pose, world, NULL);
        for (int ft = 0; ft < 2; ft++)
            slide_figures(m, ft, world[m->s->walk.wc.ankle[ft]],
                          m->s->walk.phase[ft][f] == CUB_GAIT_STANCE);
        turn_figures(m, &pose, world, f);
        m->fig->frames++;
    }
    return 0;
}

/* The walker's target: far ahead along +z. */
static const cub_vec3 far_ahead = {0, 0, CUB_Q16_INT(30000)};

/* One frame timed: the walker's step, or the baseline's pose at frame f,
 * loop k; *pose the frame's pose. 1 when the walker fails. */
static int timed_frame(const meter *m, cub_gait_walker *w, gait_method method, int f, int k,
                       cub_pose *bpose, cub_vec3 *world, const cub_pose **pose, double *us)
{
    *pose = bpose;
    double t0 = now_us();
    int bad = 0;
    if (method == GAIT_WALKER)
        bad = cub_gait_walker_step(w, far_ahead, pose) != CUB_OK;
    else
        baseline_pose(m, w, f, k, bpose, world);
    *us = now_us() - t0;
    return bad;
}

/* --repeat: the run's frames timed again n times, each frame's least time
 * kept in best (the walk is the same every time): one run's worst frame
 * is the machine's (at load 10-16 on 2 cores the baseline's 13 us frames
 * peaked at 35-102 us). 1 when the walker fails. */
static int time_again(const meter *m, const gait_ground *g, const gait_run *r, double *best)
{
    static cub_gait_walker w;
    static cub_pose bpose;
    static cub_vec3 world[CUB_MOTION_MAX_JOINTS];
    cub_gait_walk_params p = r->params;
    p.on_event = NULL;
    for (int run = 1; run < r->repeat; run++) {
        if (cub_gait_walker_init(&w, &m->s->walk.wc, &g->t, &p)) return 1;
        int f = w.frame, k = w.loops;
        for (int i = 0; i < r->frames; i++) {
            const cub_pose *pose;
            double us;
            if (timed_frame(m, &w, r->method, f, k, &bpose, world, &pose, &us)) return 1;
            if (us < best[i]) best[i] = us;
            if (r->method == GAIT_BASELINE && ++f >= w.b) f = w.a, k++;
        }
    }
    return 0;
}

int gait_measure(const gait_src *s, const gait_ground *g, const gait_run *r, gait_figures *out,
                 const char *who)
{
    *out = (gait_figures){0};
    meter m = {.s = s, .g = g, .method = r->method, .fig = out, .p99 = gait_src_p99_dps(s)};
    leg_joints(s, m.legs);
    m.clip_floor = lowest_foot(s);
    out->clear_min_mm = 1e9;
    if (r->method == GAIT_SOURCE) {
        source_run(&m);
        finish(&m);
        out->steps = m.slide_steps;
        return 0;
    }
    static cub_gait_walker w;
    static cub_pose bpose;
    static cub_vec3 world[CUB_MOTION_MAX_JOINTS];
    chained ch = {r->params.on_event, r->params.ctx, out};
    cub_gait_walk_params p = r->params;
    p.on_event = chain_event;
    p.ctx = &ch;
    if (cub_gait_walker_init(&w, &s->walk.wc, &g->t, &p)) {
        fprintf(stderr, "cubtool %s: %s: no full walk cycle found (a left foot-off to the next)\n",
                who, s->name);
        return 1;
    }
    int f = w.frame, k = w.loops;
    double total = 0, *best = r->repeat > 1 ? malloc(sizeof *best * (size_t)r->frames) : NULL;
    for (int i = 0; best && i < r->frames; i++)
        best[i] = 1e30;
    if (best && time_again(&m, g, r, best)) {
        fprintf(stderr, "cubtool %s: %s: the walker failed in a timing run\n", who, s->name);
        free(best);
        return 1;
    }
    for (int i = 0; i < r->frames; i++) {
        const cub_pose *pose;
        double us;
        if (r->method == GAIT_WALKER) f = w.frame;
        if (timed_frame(&m, &w, r->method, f, k, &bpose, world, &pose, &us)) {
            fprintf(stderr, "cubtool %s: %s: the walker failed at frame %d\n", who, s->name, i);
            free(best);
            return 1;
        }
        if (best && best[i] < us) us = best[i];
        total += us;
        if (us > out->us_max) out->us_max = us;
        cub_motion_forward(&s->m.skel, pose, world, NULL);
        for (int ft = 0; ft < 2; ft++) {
            int stance = s->walk.phase[ft][f] == CUB_GAIT_STANCE;
            int swing = r->method == GAIT_WALKER ? w.feet[ft].swinging
                                                 : s->walk.phase[ft][f] == CUB_GAIT_OFF;
            ground_figures(&m, ft, world, swing);
            slide_figures(&m, ft, world[s->walk.wc.ankle[ft]], stance);
        }
        turn_figures(&m, pose, world, i);
        if (cub_gait_terrain_is_flat(&g->t)) error_figures(&m, &w, f, world);
        if (r->on_frame) r->on_frame(r->ctx, &w, world, i);
        if (r->method == GAIT_BASELINE && ++f >= w.b) f = w.a, k++;
        out->frames++;
    }
    out->steps = r->method == GAIT_WALKER ? w.steps : m.slide_steps;
    free(best);
    out->us_mean = r->frames ? total / r->frames : 0;
    finish(&m);
    return 0;
}

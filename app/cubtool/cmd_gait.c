/* cubtool gait — a captured walk driven over a terrain by the walker
 * (firmware/gait), written as PNG frames seen from the side: the ground
 * under the walk's line, the obstacles, the skeleton, the footholds
 * taken and planned, the swinging foot's path. The footstep events go to
 * stdout, one line each, as the box's log will have them. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "cub/png.h"
#include "gait_tool.h"
#include "tool_util.h"

#define WHO "gait"
#define W 640
#define H 400
#define SPAN_MM 3000.0 /* the view: 3 m along the walk, 1.875 m high */
#define MAX_OBST 8

static const char *const usage_text =
    "usage: cubtool gait CLIP [--terrain flat|slope|rolling|steps|FILE] [--obstacle log|stone]...\n"
    "                    --frames DIR [--count N] [--data DIR]\n"
    "Drive the walk in CLIP (a BVH file, or a CMU name under DIR/mocap/cmu)\n"
    "over the terrain (rolling by default) with the obstacles added, and\n"
    "write N (240) side-view PNG frames into DIR: the ground along the walk,\n"
    "the obstacles, the skeleton (left leg blue, right red), footholds taken\n"
    "(black) and planned (green). The footstep events print to stdout.\n"
    "A terrain FILE is text (app/cubtool/gait_tool.h): 'flat B', 'slope B GX GZ'\n"
    "or 'grid NX NZ CELL X0 Z0' and NZ 'row H..' lines, then 'box X0 Y0 Z0 X1 Y1 Z1'.\n";

static const uint8_t INK[3] = {30, 30, 30}, GROUND[3] = {110, 80, 50}, LOG[3] = {150, 100, 40},
                     LEFT[3] = {40, 90, 220}, RIGHT[3] = {220, 50, 40}, PLAN[3] = {30, 160, 60},
                     HOLD[3] = {0, 0, 0}, PATH[3] = {200, 160, 0};

typedef struct view {
    cub_png_canvas c;
    double z0; /* the left edge, mm along the walk */
    const gait_ground *g;
} view;

static double px(const view *v, double z_mm)
{
    return (z_mm - v->z0) * W / SPAN_MM;
}

static double py(double y_mm)
{
    return H - 60 - y_mm * W / SPAN_MM;
}

static void seg(view *v, cub_vec3 a, cub_vec3 b, int r, const uint8_t rgb[3])
{
    double xy[4] = {px(v, a.z / 65536.0), py(a.y / 65536.0), px(v, b.z / 65536.0),
                    py(b.y / 65536.0)};
    cub_png_line(&v->c, xy, r, rgb);
}

static void dot(view *v, cub_vec3 p, int r, const uint8_t rgb[3])
{
    cub_png_dot(&v->c, (int)px(v, p.z / 65536.0), (int)py(p.y / 65536.0), r, rgb);
}

static void draw_ground(view *v)
{
    for (int x = 0; x < W; x += 4) {
        double z = v->z0 + x * SPAN_MM / W, z2 = v->z0 + (x + 4) * SPAN_MM / W;
        cub_vec3 a = {0, cub_gait_height(&v->g->t, 0, (cub_q16)(z * 65536)), (cub_q16)(z * 65536)};
        cub_vec3 b = {0, cub_gait_height(&v->g->t, 0, (cub_q16)(z2 * 65536)), (cub_q16)(z2 * 65536)};
        seg(v, a, b, 1, GROUND);
    }
    for (int i = 0; i < v->g->t.obstacle_count; i++) {
        const cub_gait_box *o = &v->g->t.obstacles[i];
        cub_vec3 c[4] = {{0, o->min_mm.y, o->min_mm.z},
                         {0, o->max_mm.y, o->min_mm.z},
                         {0, o->max_mm.y, o->max_mm.z},
                         {0, o->min_mm.y, o->max_mm.z}};
        for (int k = 0; k < 4; k++)
            seg(v, c[k], c[(k + 1) % 4], 1, LOG);
    }
}

static int side_of(const gait_src *s, int j)
{
    const cub_skeleton *sk = &s->m.skel;
    for (int f = 0; f < 2; f++)
        for (int k = s->walk.wc.toe[f]; k > 0; k = sk->joints[k].parent)
            if (k == j && sk->joints[sk->joints[k].parent].parent > 0) return f;
    return -1;
}

static void draw_walker(view *v, const gait_src *s, const cub_gait_walker *w, const cub_vec3 *world)
{
    for (int i = 0; i < w->plan.count; i++)
        dot(v, w->plan.steps[i].foot_mm, 4, PLAN);
    for (int f = 0; f < 2; f++) {
        const cub_gait_walk_foot *ft = &w->feet[f];
        dot(v, ft->hold_mm, 5, HOLD);
        if (!ft->swinging || !ft->rough) continue;
        for (int k = 0; k < 16; k++)
            seg(v, cub_gait_bezier4(ft->path.p, k * 4096), cub_gait_bezier4(ft->path.p, (k + 1) * 4096),
                0, PATH);
    }
    const cub_skeleton *sk = &s->m.skel;
    for (int j = 1; j < sk->joint_count; j++) {
        int side = side_of(s, j);
        seg(v, world[sk->joints[j].parent], world[j], 2, side < 0 ? INK : side ? RIGHT : LEFT);
    }
}

typedef struct frames_out {
    const char *dir;
    const gait_src *s;
    const gait_ground *g;
    int failed;
} frames_out;

static void on_frame(void *ctx, const cub_gait_walker *w, const cub_vec3 *world, int i)
{
    frames_out *o = ctx;
    if (o->failed) return;
    static uint8_t px_buf[W * H * 4];
    memset(px_buf, 255, sizeof px_buf);
    view v = {{px_buf, W, H}, w->pose.root_mm.z / 65536.0 - SPAN_MM / 3, o->g};
    draw_ground(&v);
    draw_walker(&v, o->s, w, world);
    char label[160];
    snprintf(label, sizeof label, "%s %s FRAME %d STEP %d", o->s->name, o->g->name, i, w->steps);
    cub_png_text(&v.c, 10, 10, 2, label, INK);
    char path[1100];
    snprintf(path, sizeof path, "%s/frame_%04d.png", o->dir, i);
    if (cub_png_write(path, px_buf, W, H)) {
        fprintf(stderr, "cubtool " WHO ": %s: cannot write\n", path);
        o->failed = 1;
    }
}

static void print_event(void *ctx, const cub_gait_event *e)
{
    (void)ctx;
    static const char *const kinds[] = {"planned", "backtracked", "taken", "blocked"};
    printf("step %d %s %s", e->step, e->left ? "left" : "right", kinds[e->kind]);
    if (e->kind == CUB_GAIT_EV_PLANNED) printf(" #%d", e->index);
    if (e->kind == CUB_GAIT_EV_BACKTRACKED) printf(" x%d", e->count);
    printf(" at %.0f %.0f %.0f mm\n", e->foot_mm.x / 65536.0, e->foot_mm.y / 65536.0,
           e->foot_mm.z / 65536.0);
}

typedef struct gait_args {
    const char *clip, *terrain, *dir, *data;
    const char *obstacles[MAX_OBST];
    int n_obst, count;
} gait_args;

/* 0 ok, 1 help, 2 bad (said). */
static int parse(int argc, char **argv, gait_args *a)
{
    *a = (gait_args){.terrain = "rolling", .count = 240};
    for (int i = 1; i < argc; i++) {
        const char *o = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(o, "--help") || !strcmp(o, "-h")) return 1;
        int takes = !strcmp(o, "--terrain") || !strcmp(o, "--obstacle") || !strcmp(o, "--frames") ||
                    !strcmp(o, "--count") || !strcmp(o, "--data");
        if (takes && !val) {
            fprintf(stderr, "cubtool " WHO ": %s needs a value\n", o);
            return 2;
        }
        if (!strcmp(o, "--terrain")) a->terrain = val;
        else if (!strcmp(o, "--frames")) a->dir = val;
        else if (!strcmp(o, "--data")) a->data = val;
        else if (!strcmp(o, "--count")) a->count = atoi(val);
        else if (!strcmp(o, "--obstacle") && a->n_obst < MAX_OBST) a->obstacles[a->n_obst++] = val;
        else if (!strcmp(o, "--obstacle")) {
            fprintf(stderr, "cubtool " WHO ": at most %d obstacles\n", MAX_OBST);
            return 2;
        } else if (o[0] != '-' && !a->clip) {
            a->clip = o;
            continue;
        } else {
            fprintf(stderr, "cubtool " WHO ": unexpected '%s'\n", o);
            return 2;
        }
        i++;
    }
    if (!a->clip || !a->dir) {
        fprintf(stderr, "cubtool " WHO ": needs CLIP and --frames DIR\n");
        return 2;
    }
    if (a->count < 1 || a->count > 100000) {
        fprintf(stderr, "cubtool " WHO ": --count %d: expected 1..100000\n", a->count);
        return 2;
    }
    return 0;
}

int cub_cmd_gait(int argc, char **argv)
{
    gait_args a;
    int p = parse(argc, argv, &a);
    if (p == 1) fputs(usage_text, stdout);
    if (p == 2) fputs(usage_text, stderr);
    if (p) return p == 1 ? 0 : 2;
    if (!a.data) a.data = getenv("CUB_DATA_DIR") ? getenv("CUB_DATA_DIR") : CUB_DATA_DIR_DEFAULT;
    static gait_ground g;
    int bad = gait_ground_make(&g, a.terrain, WHO);
    if (bad) return bad;
    for (int i = 0; i < a.n_obst; i++)
        if (gait_ground_add(&g, a.obstacles[i], WHO)) return 2;
    static gait_src s;
    if (gait_src_load(&s, a.clip, a.data, WHO)) return 1;
    if (cub_tool_make_dir(a.dir, "cubtool " WHO)) {
        gait_src_free(&s);
        return 1;
    }
    frames_out out = {a.dir, &s, &g, 0};
    gait_run r = {.method = GAIT_WALKER, .frames = a.count,
                  .params = {.dir_z = CUB_Q16_ONE, .on_event = print_event},
                  .on_frame = on_frame, .ctx = &out};
    gait_figures fig;
    int rc = gait_measure(&s, &g, &r, &fig, WHO) || out.failed;
    if (!rc)
        fprintf(stderr, "cubtool " WHO ": %d frames in %s, %d steps, %d backtracks\n", fig.frames,
                a.dir, fig.steps, fig.backtracks);
    gait_src_free(&s);
    return rc;
}

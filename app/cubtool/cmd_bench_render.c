/* cubtool bench-render — the renderer's CPU cost per frame, headless (EGL
 * surfaceless; on a PC and on the box that is Mesa's llvmpipe unless a GPU
 * driver is there), split into our own work and the GL driver's.
 *
 * How the split is made (per frame, all CPU time, not wall time):
 *   own    = the calling thread's CPU over cub_render_frame, minus the time
 *            it spent inside GL calls. Every GL function the renderer calls
 *            is wrapped at link time (bench_gl.h) and timed with the same
 *            thread clock.
 *   driver = the time inside those GL calls
 *          + glFinish on the calling thread (the frame is finished, not
 *            just queued)
 *          + the CPU of the driver's own threads over the frame (llvmpipe
 *            rasterises on worker threads): process CPU minus this thread's.
 *   total  = process CPU over the frame and the glFinish, all threads.
 * The wrappers read the clock twice per GL call; the cost of one read is
 * measured first and taken back out of both own and driver (printed as
 * probe=). So own + driver = total up to rounding.
 * The scene is the box's: the lit bear dancing a clip of the shipped
 * library on the forest stage, with the depth inset. Build Release for
 * figures that mean anything. */
#include <GLES2/gl2.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_gl.h"
#include "commands.h"
#include "cub/board.h"
#include "cub/character.h"
#include "cub/pack.h"
#include "cub/render.h"
#include "cub/track.h"

#define OWN_TARGET_MS 2.0
#define DEPTH_W 640
#define DEPTH_H 480
#define PROBE_READS 20000

typedef struct bench_args {
    int frames, warmup, w, h;
    const char *clip, *pack, *bear;
} bench_args;

/* What the scene is built from, and the per-frame buffers it points into. */
typedef struct bench_ctx {
    cub_library lib;
    cub_character bear;
    const cub_clip *clip;
    const char *clip_name;
    uint16_t *depth;
    float xyz[3 * CUB_MOTION_MAX_JOINTS], rot[4 * CUB_MOTION_MAX_JOINTS];
    float icon_xyz[3 * CUB_MOTION_MAX_JOINTS]; /* the badge's pose: frame 0's */
    cub_track_skeleton child;
} bench_ctx;

typedef struct frame_ns {
    double own, driver, total, gl_thread, finish, workers;
    int64_t calls; /* GL calls in the frame */
} frame_ns;

static void usage(FILE *f)
{
    fprintf(f, "usage: cubtool bench-render [--frames N] [--warmup N] [--size WxH] [--clip NAME]\n"
               "                            [--pack FILE] [--bear FILE]\n"
               "CPU time per frame of the renderer, headless (EGL surfaceless): median and p95 of\n"
               "our own work, the GL driver's (calls, glFinish, its worker threads) and the total.\n"
               "Defaults: 300 frames after 30 warm-up frames at 1280x720, the bear dancing the\n"
               "first dance clip of %s/clips/bear.cubclips, forest and depth inset.\n"
               "Target: own work <= %.0f ms per frame.\n",
            CUB_ASSETS_DIR, OWN_TARGET_MS);
}

static int parse_int(const char *s, int *out)
{
    char *e = NULL;
    long v = strtol(s, &e, 10);
    if (e == s || *e || v <= 0 || v > 1000000) return 0;
    *out = (int)v;
    return 1;
}

/* 0 ok, 1 help shown, 2 bad usage. */
static int parse_args(int argc, char **argv, bench_args *a)
{
    *a = (bench_args){.frames = 300, .warmup = 30, .w = 1280, .h = 720,
                      .pack = CUB_ASSETS_DIR "/clips/bear.cubclips",
                      .bear = CUB_ASSETS_DIR "/bear/bear.xml"};
    for (int i = 1; i < argc; i++) {
        const char *o = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        int ok = 1;
        if (!strcmp(o, "--help") || !strcmp(o, "-h")) {
            usage(stdout);
            return 1;
        } else if (!v) {
            ok = 0;
        } else if (!strcmp(o, "--frames")) {
            ok = parse_int(v, &a->frames);
        } else if (!strcmp(o, "--warmup")) {
            ok = !strcmp(v, "0") ? (a->warmup = 0, 1) : parse_int(v, &a->warmup);
        } else if (!strcmp(o, "--size")) {
            char tail;
            ok = sscanf(v, "%dx%d%c", &a->w, &a->h, &tail) == 2 && a->w > 0 && a->h > 0 &&
                 a->w <= 8192 && a->h <= 8192;
        } else if (!strcmp(o, "--clip") || !strcmp(o, "--pack") || !strcmp(o, "--bear")) {
            *(o[2] == 'c' ? &a->clip : o[2] == 'p' ? &a->pack : &a->bear) = v;
        } else {
            ok = 0;
        }
        if (!ok) {
            fprintf(stderr, "cubtool bench-render: bad option '%s%s%s'\n", o, v ? " " : "", v ? v : "");
            usage(stderr);
            return 2;
        }
        i++;
    }
    return 0;
}

static int load(const bench_args *a, bench_ctx *c)
{
    cub_diag d = {0};
    char msg[600];
    if (cub_pack_read(a->pack, &c->lib, &d) || cub_character_load(a->bear, &c->bear, &d)) {
        fprintf(stderr, "cubtool bench-render: %s\n", cub_diag_str(&d, msg, sizeof msg));
        return 1;
    }
    for (int i = 0; i < c->lib.clip_count && !c->clip; i++) {
        const cub_library_clip *lc = &c->lib.clips[i];
        if (a->clip ? !strcmp(lc->name, a->clip) : !strcmp(lc->kind, "dance"))
            c->clip = &lc->clip, c->clip_name = lc->name;
    }
    if (!c->clip) {
        fprintf(stderr, "cubtool bench-render: %s: no clip %s%s\n", a->pack, a->clip ? "named " : "of kind dance",
                a->clip ? a->clip : "");
        return 1;
    }
    /* A stand-in for the Kinect: a floor-to-wall gradient with a near blob
     * where the child stands; the inset's cost does not depend on content. */
    c->depth = malloc(sizeof(uint16_t) * DEPTH_W * DEPTH_H);
    if (!c->depth) return 1;
    for (int y = 0; y < DEPTH_H; y++)
        for (int x = 0; x < DEPTH_W; x++) {
            int dx = x - DEPTH_W / 2, dy = y - DEPTH_H / 2;
            c->depth[y * DEPTH_W + x] =
                (uint16_t)(dx * dx / 4 + dy * dy / 16 < 70 * 70 ? 620 : 700 + y * 300 / DEPTH_H);
        }
    return 0;
}

/* The child in the inset: 20 of the coach's joints, 2.5 m in front of the
 * camera (which joints does not matter: the inset's cost is the same), and
 * a status that turns to "too close" now and then, so the cue's text comes
 * and goes as it does on the box. */
static void bench_child(bench_ctx *c, const cub_vec3 *world, int joints, int i)
{
    c->child.status = (i / 90) % 2 ? CUB_TRACK_TOO_CLOSE : CUB_TRACK_OK;
    for (int j = 0; j < CUB_KJ_COUNT; j++) {
        cub_vec3 p = world[j * joints / CUB_KJ_COUNT];
        c->child.joint_mm[j] = (cub_vec3){p.x, p.y - 900 * 65536, p.z + 2500 * 65536};
        c->child.confidence[j] = 65536;
    }
}

/* The scene of frame i: everything the renderer draws on the box during a
 * song, in one place: the bear on the forest, the hint (a new one every two
 * seconds, so its layout is timed too), the move's badge, the progress bar
 * and the child inset over the depth image with its cue. */
static cub_err bench_scene(bench_ctx *c, int i, cub_render_scene *scene)
{
    cub_pose pose;
    cub_vec3 world[CUB_MOTION_MAX_JOINTS];
    cub_quat rot[CUB_MOTION_MAX_JOINTS];
    const cub_skeleton *skel = c->clip->skel;
    cub_err e = cub_motion_sample(c->clip, (int64_t)i * 1000000 / 30, CUB_MOTION_LOOP, &pose);
    if (!e) e = cub_motion_forward(skel, &pose, world, rot);
    if (e) return e;
    cub_motion_world_to_float(world, skel->joint_count, c->xyz);
    if (i == 0) memcpy(c->icon_xyz, c->xyz, sizeof c->icon_xyz);
    bench_child(c, world, skel->joint_count, i);
    for (int j = 0; j < skel->joint_count; j++) {
        const float one = (float)CUB_QUAT_ONE;
        c->rot[4 * j + 0] = (float)rot[j].x / one;
        c->rot[4 * j + 1] = (float)rot[j].y / one;
        c->rot[4 * j + 2] = (float)rot[j].z / one;
        c->rot[4 * j + 3] = (float)rot[j].w / one;
    }
    *scene = (cub_render_scene){.skel = skel,
                                .world_xyz_mm = c->xyz,
                                .character = &c->bear,
                                .world_rot_xyzw = c->rot,
                                .face = CUB_RENDER_FACE_HAPPY,
                                .depth_raw = c->depth,
                                .hint = (i / 60) % 2 ? "Clap with me!" : "Wave your paws up high!",
                                .icon_xyz_mm = c->icon_xyz,
                                .progress = (float)(i % 600) / 600.0f,
                                .has_progress = 1,
                                .child = &c->child,
                                .child_cue = c->child.status == CUB_TRACK_OK ? NULL : "Step back"};
    return CUB_OK;
}

/* CPU nanoseconds of one thread-clock read: what each wrapper adds. */
static double probe_ns(void)
{
    int64_t t0 = cub_bench_thread_ns();
    for (int i = 0; i < PROBE_READS; i++) cub_bench_thread_ns();
    return (double)(cub_bench_thread_ns() - t0) / (PROBE_READS + 1);
}

static cub_err measure_frame(cub_render *r, const cub_render_scene *scene, double probe, frame_ns *f)
{
    int64_t frame_gl, frame_calls, fin_gl, fin_calls;
    cub_bench_gl_timing(1);
    int64_t p0 = cub_bench_process_ns(), t0 = cub_bench_thread_ns();
    cub_err e = cub_render_frame(r, scene);
    int64_t t1 = cub_bench_thread_ns();
    cub_bench_gl_take(&frame_gl, &frame_calls);
    glFinish();
    int64_t t2 = cub_bench_thread_ns(), p2 = cub_bench_process_ns();
    cub_bench_gl_take(&fin_gl, &fin_calls);
    cub_bench_gl_timing(0);
    /* Each wrapped call read the clock twice: about one read's cost fell
     * inside the timed span, one outside (charged to the frame). */
    double calls = (double)(frame_calls + fin_calls);
    f->calls = frame_calls;
    f->gl_thread = (double)frame_gl - probe * (double)frame_calls;
    f->own = (double)(t1 - t0 - frame_gl) - probe * (double)frame_calls;
    f->finish = (double)(t2 - t1) - probe * (double)fin_calls * 2.0;
    f->workers = (double)((p2 - p0) - (t2 - t0));
    f->driver = f->gl_thread + f->finish + f->workers;
    f->total = (double)(p2 - p0) - 2.0 * probe * calls;
    return e;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Prints "median=.. p95=.. mean=.." in ms of the n values at v (sorts v). */
static double report(const char *what, double *v, int n)
{
    double sum = 0.0;
    for (int i = 0; i < n; i++) sum += v[i];
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    double med = v[n / 2] * 1e-6;
    printf("bench-render: %-6s median=%.3f ms p95=%.3f ms mean=%.3f ms\n", what, med, v[(n * 95) / 100] * 1e-6,
           sum / n * 1e-6);
    return med;
}

static int run(const bench_args *a, bench_ctx *c, cub_render *r)
{
    double probe = probe_ns();
    int n = a->frames;
    double *own = malloc(sizeof(double) * 6 * (size_t)n);
    if (!own) return 1;
    double *drv = own + n, *tot = drv + n, *glt = tot + n, *fin = glt + n, *wrk = fin + n;
    int64_t calls = 0;
    for (int i = -a->warmup; i < n; i++) {
        cub_render_scene scene;
        frame_ns f;
        cub_err e = bench_scene(c, i + a->warmup, &scene);
        if (!e) e = measure_frame(r, &scene, probe, &f);
        if (e) {
            fprintf(stderr, "cubtool bench-render: frame %d: %s\n", i, cub_err_str(e));
            free(own);
            return 1;
        }
        if (i < 0) continue;
        calls += f.calls;
        own[i] = f.own, drv[i] = f.driver, tot[i] = f.total;
        glt[i] = f.gl_thread, fin[i] = f.finish, wrk[i] = f.workers;
    }
    printf("bench-render: %dx%d frames=%d warmup=%d gl_calls=%.1f per frame probe=%.0f ns per clock read GL_RENDERER=%s\n",
           a->w, a->h, n, a->warmup, (double)calls / n, probe, (const char *)glGetString(GL_RENDERER));
    printf("bench-render: own = this thread's CPU in cub_render_frame outside GL calls; driver = inside GL\n"
           "bench-render: calls + glFinish + the driver's worker threads (process CPU - this thread's)\n");
    double own_med = report("own", own, n);
    report("driver", drv, n);
    report("total", tot, n);
    report("gl", glt, n);
    report("finish", fin, n);
    report("worker", wrk, n);
    printf("bench-render: own work median %.3f ms %s the %.0f ms target\n", own_med,
           own_med <= OWN_TARGET_MS ? "meets" : "MISSES", OWN_TARGET_MS);
    free(own);
    return 0;
}

int cub_cmd_bench_render(int argc, char **argv)
{
    bench_args a;
    int rc = parse_args(argc, argv, &a);
    if (rc) return rc == 1 ? 0 : 2;
    bench_ctx *c = calloc(1, sizeof *c); /* a library and a character: ~60 KB */
    if (!c || load(&a, c)) {
        if (c) cub_library_free(&c->lib), free(c->depth);
        free(c);
        return 1;
    }
    cub_board *board = NULL;
    cub_render *r = NULL;
    char msg[512] = "";
    cub_board_desc bd = {.display = CUB_DISPLAY_HEADLESS, .width = a.w, .height = a.h,
                         .depth = CUB_DEPTH_OFF, .audio_driver = "dummy"};
    cub_render_desc rd = {.width = a.w, .height = a.h};
    if (cub_board_open(&bd, &board, msg, sizeof msg)) {
        fprintf(stderr, "cubtool bench-render: no headless display: %s\n", msg);
        rc = 1;
    } else if (cub_render_create(&rd, &r)) {
        fprintf(stderr, "cubtool bench-render: cannot create the renderer\n");
        rc = 1;
    } else {
        fprintf(stderr, "bench-render: %s on %s, %d+%d frames\n", c->clip_name, a.pack, a.warmup, a.frames);
        rc = run(&a, c, r);
    }
    cub_render_destroy(r);
    cub_board_close(board);
    cub_library_free(&c->lib);
    free(c->depth);
    free(c);
    return rc;
}

/* cubtool play — the content maker's viewer, as the seed's Motion Player
 * (SEEDS.md § 002): one or two characters (clips, BVH, ASE, ASF/AMC, TRC
 * markers) in one scene on one floor, each selectable, movable and
 * scalable, with speed, floor size, camera and zoom on keys (play_keys.c),
 * sticks or numbered points; in a window, or headless as PNG frames with
 * the keys from a script (--keys). --side-by-side is the older viewer: each
 * clip in its own half, on the bear or the stick figure.
 *
 * Playback time advances by the speed over 30 output frames a second (a
 * window by its real frame time), so the frames written headless are the
 * same on every machine. */
#include <SDL2/SDL.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "cub/board.h"
#include "cub/keyscript.h"
#include "cub/png.h"
#include "cub/render.h"
#include "play_keys.h"
#include "play_scene.h"
#include "play_src.h"
#include "tool_util.h"

#define PLAY_FPS 30
#define MAX_SRC 2

typedef struct play_args {
    const char *spec[MAX_SRC], *amc[MAX_SRC];
    int count;
    const char *bear, *map, *frames_dir, *keys_path;
    play_figure figure;
    double speed, scale, seconds, floor_mm;
    int frame_count, once, window, w, h, side_by_side, points;
    cub_render_view view;
} play_args;

/* Everything one run holds. */
typedef struct player {
    play_args a;
    cub_character bear;
    play_src src[MAX_SRC];
    cub_render *r[MAX_SRC];
    cub_board *board;
    double t_s;      /* clip time shown, seconds */
    int paused;
    /* the scene (not --side-by-side) */
    play_view view;
    play_scene scene;
    cub_keyscript keys;
    int next_key; /* the first scripted press not yet made */
} player;

static void usage(FILE *f)
{
    fprintf(f,
            "usage: cubtool play A [B] [options]\n"
            "A and B: PACK.cubclips:CLIP, FILE.bvh, FILE.ase, FILE.trc (markers), or FILE.asf\n"
            "FILE.amc. Both characters stand in one scene on one floor (A blue, B orange), as\n"
            "sticks or as points with their bone numbers; world positions M_i = M_parent T_i R_i.\n"
            "\n"
            "  --speed X                 playback speed (default 1)\n"
            "  --scale X                 both characters' size (default 1)\n"
            "  --floor MM                the floor's side (default 6000)\n"
            "  --points                  start with points and bone numbers (N toggles)\n"
            "  --yaw DEG --pitch DEG     orbit the camera (left/right, up/down)\n"
            "  --zoom X                  camera zoom (default 1)\n"
            "  --once                    play once and hold the last frame (default: loop)\n"
            "  --size WxH                output size (default 1280x720)\n"
            "  --frames DIR              headless: write DIR/frame_00000.png, ... (no window)\n"
            "  --keys FILE               press keys at given frames (headless or not; the format:\n"
            "                            app/include/cub/keyscript.h); each press prints the state\n"
            "  --seconds S | --frame-count N   how long (default: one play-through headless,\n"
            "                            until Esc in a window)\n"
            "  --side-by-side            the older viewer: each clip in its half, on the bear:\n"
            "    --bear-figure | --stick   draw on the bear / on the stick figure (default: the\n"
            "                              bear when the clip is on its skeleton or --map\n"
            "                              retargets it)\n"
            "    --map FILE                retarget other skeletons onto the bear\n"
            "    --bear FILE               the character (default %s/bear/bear.xml)\n"
            "    keys: Space pause, +/- speed, arrows orbit, PgUp/PgDn or the wheel zoom, Home\n"
            "    resets the camera, Esc quits\n"
            "Keys in the scene:\n",
            CUB_ASSETS_DIR);
    play_keys_help(f);
}

static int number(const char *s, double *out)
{
    char *e = NULL;
    *out = strtod(s, &e);
    return e != s && !*e && isfinite(*out);
}

/* One option with a value; 0 when the option or its value is bad. */
static int value_option(play_args *a, const char *o, const char *v)
{
    double x = 0.0;
    if (!strcmp(o, "--map")) return (a->map = v), 1;
    if (!strcmp(o, "--bear")) return (a->bear = v), 1;
    if (!strcmp(o, "--frames")) return (a->frames_dir = v), 1;
    if (!strcmp(o, "--keys")) return (a->keys_path = v), 1;
    if (!strcmp(o, "--size")) {
        char tail;
        return sscanf(v, "%dx%d%c", &a->w, &a->h, &tail) == 2 && a->w >= 16 && a->h >= 16 &&
               a->w <= 8192 && a->h <= 8192;
    }
    if (!number(v, &x)) return 0;
    if (!strcmp(o, "--speed")) return (a->speed = x) > 0.0 && x <= 100.0;
    if (!strcmp(o, "--scale")) return (a->scale = x) > 0.0 && x <= 100.0;
    if (!strcmp(o, "--floor")) return (a->floor_mm = x) >= 1000.0 && x <= 100000.0;
    if (!strcmp(o, "--seconds")) return (a->seconds = x) > 0.0 && x <= 3600.0;
    if (!strcmp(o, "--frame-count")) return (a->frame_count = (int)x) == x && x >= 1 && x <= 1000000;
    if (!strcmp(o, "--yaw")) return (a->view.yaw_deg = (float)x), 1;
    if (!strcmp(o, "--pitch")) return (a->view.pitch_deg = (float)x), 1;
    if (!strcmp(o, "--zoom")) return (a->view.zoom = (float)x) > 0.0f;
    return 0;
}

static int positional(play_args *a, const char *p)
{
    if (play_src_is_amc(p) && a->count > 0 && !a->amc[a->count - 1]) {
        a->amc[a->count - 1] = p; /* the motion of the .asf before it */
        return 1;
    }
    if (a->count == MAX_SRC) return 0;
    a->spec[a->count++] = p;
    return 1;
}

/* 0 ok, 1 help shown, 2 bad usage. */
static int parse_args(int argc, char **argv, play_args *a)
{
    *a = (play_args){.bear = CUB_ASSETS_DIR "/bear/bear.xml", .speed = 1.0, .scale = 1.0, .w = 1280, .h = 720};
    for (int i = 1; i < argc; i++) {
        const char *o = argv[i];
        int ok = 1;
        if (!strcmp(o, "--help") || !strcmp(o, "-h")) {
            usage(stdout);
            return 1;
        } else if (!strcmp(o, "--once")) {
            a->once = 1;
        } else if (!strcmp(o, "--side-by-side")) {
            a->side_by_side = 1;
        } else if (!strcmp(o, "--points")) {
            a->points = 1;
        } else if (!strcmp(o, "--stick") || !strcmp(o, "--bear-figure")) {
            a->figure = o[2] == 's' ? PLAY_FIGURE_STICK : PLAY_FIGURE_BEAR;
        } else if (o[0] == '-' && o[1] == '-') {
            ok = i + 1 < argc && value_option(a, o, argv[i + 1]);
            i += ok;
        } else {
            ok = positional(a, o);
        }
        if (!ok) {
            fprintf(stderr, "cubtool play: bad or unexpected '%s'%s%s\n", o, i + 1 < argc ? " " : "",
                    i + 1 < argc && o[0] == '-' ? argv[i + 1] : "");
            return 2;
        }
    }
    if (a->side_by_side && (a->keys_path || a->points || a->floor_mm > 0.0)) {
        fprintf(stderr, "cubtool play: --keys, --points and --floor are the scene's, not "
                        "--side-by-side's\n");
        return 2;
    }
    if (a->count == 0) {
        fprintf(stderr, "cubtool play: nothing to play\n");
        usage(stderr);
        return 2;
    }
    return 0;
}

/* ---- drawing ------------------------------------------------------------- */

static cub_err draw_src(player *p, int i)
{
    const play_src *s = &p->src[i];
    const cub_clip *clip = s->clip;
    static float xyz[3 * CUB_MOTION_MAX_JOINTS], rot[4 * CUB_MOTION_MAX_JOINTS];
    cub_pose pose;
    cub_vec3 world[CUB_MOTION_MAX_JOINTS];
    cub_quat q[CUB_MOTION_MAX_JOINTS];
    int64_t t_us = (int64_t)llround(p->t_s * 1e6);
    cub_err e = cub_motion_sample(clip, t_us, p->a.once ? CUB_MOTION_CLAMP : CUB_MOTION_LOOP, &pose);
    if (!e) e = cub_motion_forward(clip->skel, &pose, world, q);
    if (e) return e;
    cub_motion_world_to_float(world, clip->skel->joint_count, xyz);
    for (int j = 0; j < clip->skel->joint_count; j++) {
        const float one = (float)CUB_QUAT_ONE;
        float v[4] = {(float)q[j].x / one, (float)q[j].y / one, (float)q[j].z / one, (float)q[j].w / one};
        memcpy(rot + 4 * j, v, sizeof v);
    }
    cub_render_scene scene = {.skel = clip->skel, .world_xyz_mm = xyz};
    if (s->on_bear) scene.character = &p->bear, scene.world_rot_xyzw = rot;
    cub_render_set_view(p->r[i], &p->a.view);
    return cub_render_frame(p->r[i], &scene);
}

static cub_err draw(player *p)
{
    cub_err e = CUB_OK;
    if (!p->a.side_by_side)
        e = play_scene_draw(&p->scene, &p->view, p->t_s, p->a.once, p->r[0]);
    for (int i = 0; p->a.side_by_side && i < p->a.count && !e; i++) e = draw_src(p, i);
    if (e) fprintf(stderr, "cubtool play: drawing %s: %s\n", p->src[0].name, cub_err_str(e));
    return e;
}

/* The scene's one renderer, or (side by side) one per input, each in its
 * share of the width. */
static int make_renderers(player *p)
{
    int n = p->a.side_by_side ? p->a.count : 1, w = p->a.w / n;
    for (int i = 0; i < n; i++) {
        cub_render_desc rd = {.x = i * w, .width = i == n - 1 ? p->a.w - i * w : w, .height = p->a.h,
                              .figure_height_mm = (float)(1.3 * p->src[i].height_mm / p->a.scale)};
        if (cub_render_create(&rd, &p->r[i])) {
            fprintf(stderr, "cubtool play: cannot create the renderer\n");
            return 1;
        }
    }
    return 0;
}

static double longest_s(const player *p)
{
    double s = 0.0;
    for (int i = 0; i < p->a.count; i++) {
        double d = play_src_seconds(&p->src[i]);
        s = d > s ? d : s;
    }
    return s;
}

/* ---- the scene's keys ------------------------------------------------------- */

/* Make the scripted presses due before output frame f, each logged with
 * the state it leaves. 1 when one of them quits. */
static int press_due(player *p, int f)
{
    for (; p->next_key < p->keys.count && p->keys.press[p->next_key].frame <= f; p->next_key++) {
        int key = p->keys.press[p->next_key].key;
        play_key_result r = play_key(&p->view, key);
        printf("play: frame %d key %s: ", f, cub_key_name(key));
        if (r == PLAY_KEY_QUIT) {
            printf("quit\n");
            return 1;
        }
        if (r == PLAY_KEY_UNUSED) printf("(no key of the scene) ");
        play_view_print(&p->view, stdout);
    }
    return 0;
}

/* Clip time for the next output frame. */
static void advance(player *p, int f)
{
    if (p->a.side_by_side)
        p->t_s = (double)(f + 1) / PLAY_FPS * p->a.speed;
    else if (!p->view.paused)
        p->t_s += p->view.speed / PLAY_FPS;
}

/* ---- headless: PNG frames ------------------------------------------------- */

static int write_frames(player *p)
{
    const play_args *a = &p->a;
    int n = a->frame_count ? a->frame_count
            : a->seconds   ? (int)lround(a->seconds * PLAY_FPS)
                           : (int)ceil(longest_s(p) / a->speed * PLAY_FPS) + 1; /* both ends */
    if (n < 1) n = 1;
    if (cub_tool_make_dir(a->frames_dir, "cubtool play")) return 1;
    uint8_t *rgba = malloc((size_t)a->w * (size_t)a->h * 4);
    if (!rgba) return 1;
    int rc = 0;
    p->t_s = 0.0;
    for (int f = 0; f < n && !rc; f++) {
        char path[4096];
        if (!a->side_by_side && press_due(p, f)) break;
        snprintf(path, sizeof path, "%s/frame_%05d.png", a->frames_dir, f);
        rc = draw(p) || cub_board_display_read_rgba(p->board, rgba, (size_t)a->w * (size_t)a->h * 4);
        if (!rc && cub_png_write(path, rgba, a->w, a->h)) {
            fprintf(stderr, "cubtool play: cannot write %s\n", path);
            rc = 1;
        }
        cub_board_display_swap(p->board);
        advance(p, f);
    }
    free(rgba);
    if (!rc) printf("play: wrote %d frames (%dx%d, %d fps, speed %g) to %s\n", n, a->w, a->h, PLAY_FPS, a->speed, a->frames_dir);
    return rc;
}

/* ---- a window: keys --------------------------------------------------------- */

/* 0 to go on, 1 to quit. */
static int on_key(player *p, SDL_Keycode k)
{
    cub_render_view *v = &p->a.view;
    float zoom = v->zoom > 0.0f ? v->zoom : 1.0f;
    switch (k) {
    case SDLK_ESCAPE: return 1;
    case SDLK_SPACE: p->paused = !p->paused; break;
    case SDLK_PLUS: case SDLK_EQUALS: case SDLK_KP_PLUS: p->a.speed = fmin(p->a.speed * 1.25, 100.0); break;
    case SDLK_MINUS: case SDLK_KP_MINUS: p->a.speed = fmax(p->a.speed / 1.25, 0.01); break;
    case SDLK_LEFT: v->yaw_deg -= 10.0f; break;
    case SDLK_RIGHT: v->yaw_deg += 10.0f; break;
    case SDLK_UP: v->pitch_deg = fminf(v->pitch_deg + 5.0f, 80.0f); break;
    case SDLK_DOWN: v->pitch_deg = fmaxf(v->pitch_deg - 5.0f, -80.0f); break;
    case SDLK_PAGEUP: v->zoom = fminf(zoom * 1.1f, 10.0f); break;
    case SDLK_PAGEDOWN: v->zoom = fmaxf(zoom / 1.1f, 0.1f); break;
    case SDLK_HOME: *v = (cub_render_view){0}; break;
    default: break;
    }
    return 0;
}

/* An SDL key as cub/keyscript.h's code, or -1. */
static int scene_key(SDL_Keycode k)
{
    if (k >= SDLK_a && k <= SDLK_z) return 'A' + (int)(k - SDLK_a);
    if (k >= SDLK_0 && k <= SDLK_9) return '0' + (int)(k - SDLK_0);
    switch (k) {
    case SDLK_TAB: return CUB_KEY_TAB;
    case SDLK_SPACE: return CUB_KEY_SPACE;
    case SDLK_ESCAPE: return CUB_KEY_ESC;
    case SDLK_UP: return CUB_KEY_UP;
    case SDLK_DOWN: return CUB_KEY_DOWN;
    case SDLK_LEFT: return CUB_KEY_LEFT;
    case SDLK_RIGHT: return CUB_KEY_RIGHT;
    case SDLK_PLUS: case SDLK_EQUALS: case SDLK_KP_PLUS: return CUB_KEY_PLUS;
    case SDLK_MINUS: case SDLK_KP_MINUS: return CUB_KEY_MINUS;
    case SDLK_HOME: return CUB_KEY_HOME;
    case SDLK_PAGEUP: return CUB_KEY_PAGEUP;
    case SDLK_PAGEDOWN: return CUB_KEY_PAGEDOWN;
    default: return -1;
    }
}

/* 0 to go on, 1 to quit. */
static int key_down(player *p, SDL_Keycode k)
{
    if (p->a.side_by_side) return on_key(p, k);
    return play_key(&p->view, scene_key(k)) == PLAY_KEY_QUIT;
}

static int poll_window(player *p)
{
    SDL_Event ev;
    while (SDL_PollEvent(&ev)) {
        if (ev.type == SDL_QUIT) return 1;
        if (ev.type == SDL_KEYDOWN && key_down(p, ev.key.keysym.sym)) return 1;
        if (ev.type == SDL_MOUSEWHEEL && ev.wheel.y) {
            float zoom = p->a.view.zoom > 0.0f ? p->a.view.zoom : 1.0f;
            p->a.view.zoom = fmaxf(fminf(zoom * powf(1.1f, (float)ev.wheel.y), 10.0f), 0.1f);
        }
    }
    return 0;
}

static int run_window(player *p)
{
    const play_args *a = &p->a;
    int limit = a->frame_count ? a->frame_count : a->seconds ? (int)lround(a->seconds * PLAY_FPS) : -1;
    int64_t next = cub_board_now_us(p->board);
    for (int f = 0; limit < 0 || f < limit; f++) {
        if (poll_window(p) || (!a->side_by_side && press_due(p, f))) break;
        if (draw(p)) return 1;
        cub_board_display_swap(p->board);
        next += 1000000 / PLAY_FPS;
        cub_board_sleep_until_us(p->board, next);
        if (!a->side_by_side)
            advance(p, f);
        else if (!p->paused)
            p->t_s += a->speed / PLAY_FPS;
    }
    return 0;
}

/* ---- the command -------------------------------------------------------------- */

static int load_all(player *p)
{
    cub_diag d = {0};
    char buf[600];
    const cub_character *bear = NULL;
    if (!p->a.side_by_side) p->a.figure = PLAY_FIGURE_STICK; /* the scene draws sticks or points */
    if (p->a.figure != PLAY_FIGURE_STICK) {
        if (cub_character_load(p->a.bear, &p->bear, &d)) {
            fprintf(stderr, "cubtool play: %s\n", cub_diag_str(&d, buf, sizeof buf));
            return 1;
        }
        bear = &p->bear;
    }
    for (int i = 0; i < p->a.count; i++) {
        play_src *s = &p->src[i];
        if (play_src_load(s, p->a.spec[i], p->a.amc[i], p->a.figure, bear, p->a.map)) return 1;
        if (!s->clip && p->a.side_by_side) {
            fprintf(stderr, "cubtool play: %s: markers play in the scene only (no --side-by-side)\n",
                    s->name);
            return 1;
        }
        const char *role = p->a.count == 1 ? "clip" : p->a.side_by_side ? (i ? "right" : "left")
                                                                         : (i ? "B" : "A");
        if (s->clip)
            printf("play: %s %s: %d joints, %d frames at %.2f fps, %.3f s, %s\n", role,
                   s->name, s->clip->skel->joint_count, s->clip->frame_count,
                   1e9 / s->clip->frame_ns, play_src_seconds(s),
                   s->on_bear            ? "on the bear"
                   : p->a.side_by_side ? "on the stick figure"
                                       : "in the scene");
        else
            printf("play: %s %s: %d markers, %d frames at %.2f fps, %.3f s, as points\n", role,
                   s->name, s->trc.markers, s->trc.frames, s->trc.rate, play_src_seconds(s));
    }
    return 0;
}

/* The scene's state from the options, and the key script. */
static int set_up_scene(player *p)
{
    const play_args *a = &p->a;
    play_view *v = &p->view;
    play_view_init(v, a->count);
    v->speed = a->speed;
    v->size[0] = v->size[1] = (float)a->scale;
    if (a->floor_mm > 0.0) v->floor_mm = (float)a->floor_mm;
    v->points = a->points;
    v->yaw_deg = a->view.yaw_deg, v->pitch_deg += a->view.pitch_deg;
    if (a->view.zoom > 0.0f) v->zoom = a->view.zoom;
    cub_diag d = {0};
    char buf[600];
    if (a->keys_path && cub_keyscript_load(a->keys_path, &p->keys, &d)) {
        fprintf(stderr, "cubtool play: %s\n", cub_diag_str(&d, buf, sizeof buf));
        return 1;
    }
    return play_scene_init(&p->scene, p->src, a->count);
}

static int open_display(player *p)
{
    char msg[512] = "";
    cub_board_desc bd = {.display = p->a.frames_dir ? CUB_DISPLAY_HEADLESS : CUB_DISPLAY_WINDOW,
                         .width = p->a.w, .height = p->a.h, .fullscreen = -1,
                         .depth = CUB_DEPTH_OFF, .audio_driver = "dummy"};
    if (cub_board_open(&bd, &p->board, msg, sizeof msg)) {
        fprintf(stderr, "cubtool play: no %s: %s%s\n", p->a.frames_dir ? "headless display" : "window", msg,
                p->a.frames_dir ? "" : " (--frames DIR renders headless)");
        return 1;
    }
    return 0;
}

int cub_cmd_play(int argc, char **argv)
{
    player *p = calloc(1, sizeof *p); /* a character, two skeletons, the scene: ~120 KB */
    if (!p) return 1;
    int rc = parse_args(argc, argv, &p->a);
    if (rc) {
        free(p);
        return rc == 1 ? 0 : 2;
    }
    rc = load_all(p) || (!p->a.side_by_side && set_up_scene(p)) || open_display(p) ||
         make_renderers(p);
    if (!rc) rc = p->a.frames_dir ? write_frames(p) : run_window(p);
    for (int i = 0; i < MAX_SRC; i++) {
        cub_render_destroy(p->r[i]);
        play_src_free(&p->src[i]);
    }
    cub_board_close(p->board);
    cub_keyscript_free(&p->keys);
    free(p);
    return rc;
}

/* cubdance — the box program. Parse the options, open the board, load the
 * coach's clip, run the fixed-tick loop until STOP-and-quit or --seconds,
 * and say where the frames and the event log went. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cub/board.h"
#include "cub/boxconf.h"
#include "cub/floor_file.h"
#include "cub/io.h"
#include "cub/loop.h"
#include "cub/render.h"
#include "event_log.h"
#include "options.h"
#include "record.h"
#include "replay.h"
#include "session.h"
#include "walk_box.h"

static int make_dir(const char *dir)
{
    if (mkdir(dir, 0755) == 0 || errno == EEXIST) return 0;
    fprintf(stderr, "cubdance: cannot create the frames directory %s: %s\n", dir,
            strerror(errno));
    return -1;
}

static cub_board *open_board(const cub_app_options *o)
{
    cub_board_desc d = {.display = o->display, .width = o->width, .height = o->height,
                        .fit_screen = o->fit_screen, .fullscreen = o->fullscreen,
                        .video_driver = o->video_driver, .depth = o->depth,
                        .button_script = o->button_script, .gpio = o->gpio,
                        .audio_driver = o->audio_driver, .audio_volume = o->audio_volume,
                        .virtual_clock = o->virtual_clock};
    if (o->frames_dir && d.display == CUB_DISPLAY_AUTO) d.display = CUB_DISPLAY_HEADLESS;
    cub_board *b = NULL;
    char msg[768] = "";
    cub_err err = cub_board_open(&d, &b, msg, sizeof msg);
    if (err && !strncmp(msg, "no display", 10)) {
        fprintf(stderr, "cubdance: %s\n", msg); /* the board said it all */
        return NULL;
    }
    if (err) {
        fprintf(stderr, "cubdance: cannot open the %s board: %s\n", cub_board_name(),
                *msg ? msg : cub_err_str(err));
        return NULL;
    }
    /* A replay must never quietly read a live camera instead. */
    if (o->replay_dir && strcmp(cub_board_depth_source(b), "fakenect") != 0) {
        fprintf(stderr, "cubdance: --replay %s: fakenect's replay library did not load "
                        "(looked in %s); refusing to read a live camera instead\n",
                o->replay_dir, CUB_FAKENECT_DIR);
        cub_board_close(b);
        return NULL;
    }
    return b;
}

static int load_clip(const char *path, cub_io_motion *m)
{
    cub_diag diag;
    if (cub_io_load_bvh(path, NULL, m, &diag) == CUB_OK) return 0;
    char buf[768];
    fprintf(stderr, "cubdance: cannot load the coach's clip: %s\n",
            cub_diag_str(&diag, buf, sizeof buf));
    return -1;
}

/* The last part of a path: the log names files, not where a checkout lives. */
static const char *file_name(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

/* The judge's timeline and, with a song, the dance. */
static int open_extras(const cub_app_options *o, cub_board *board, cub_loop *loop, int64_t t0,
                       cub_session *s)
{
    char err[768];
    if (o->timeline_path && cub_timeline_load(o->timeline_path, &s->timeline, err, sizeof err)) {
        fprintf(stderr, "cubdance: %s\n", err);
        return -1;
    }
    if (strcmp(cub_board_depth_source(board), "off") != 0) {
        s->watch = calloc(1, sizeof *s->watch);
        cub_err e = s->watch ? cub_watch_open(s->watch, &loop->log, o->forest_path) : CUB_ERR_NOMEM;
        if (e) {
            fprintf(stderr, "cubdance: the tracker would not start (%s)\n", cub_err_str(e));
            return -1;
        }
    }
    if (!o->song_path) return 0;
    s->dance = calloc(1, sizeof *s->dance);
    cub_judge *judge = s->watch ? s->watch->judge : NULL;
    if (!s->dance || cub_dance_open(s->dance, o, board, &loop->log, judge, s->floor, t0, err,
                                     sizeof err)) {
        fprintf(stderr, "cubdance: %s\n", s->dance ? err : "out of memory");
        return -1;
    }
    return 0;
}

static cub_record *open_recorder(const cub_app_options *o, cub_board *board, cub_log *log)
{
    cub_record_desc rd = {.dir = o->record_dir, .max_bytes = (int64_t)o->record_max_mb << 20,
                          .log = log};
    cub_record *rec = NULL;
    char err[1200];
    if (cub_record_open(&rd, &rec, err, sizeof err)) {
        fprintf(stderr, "cubdance: %s\n", err);
        return NULL;
    }
    cub_board_set_depth_tap(board, cub_record_frame, rec);
    return rec;
}

/* The forest floor the coach stands on (the gait planner's terrain too:
 * cub_floor_terrain); a broken file stops the box, naming file and line. */
static cub_floor *load_floor(const char *path)
{
    cub_diag d = {0};
    char msg[600];
    cub_floor *f = calloc(1, sizeof *f); /* 9 kB: not on the stack */
    if (!f) fprintf(stderr, "cubdance: out of memory\n");
    else if (!cub_floor_load(path, f, &d)) return f;
    else fprintf(stderr, "cubdance: %s\n", cub_diag_str(&d, msg, sizeof msg));
    free(f);
    return NULL;
}

/* --bridge-speed needs a song (the coach's clips and their bridges). */
static int open_speed(const cub_app_options *o, cub_session *s, cub_bridge_speed *speed)
{
    if (!s->dance) {
        fprintf(stderr, "cubdance: --bridge-speed %s: needs --song\n", o->bridge_speed_path);
        return -1;
    }
    if (cub_bridge_speed_init(speed, s->dance)) {
        fprintf(stderr, "cubdance: --bridge-speed %s: out of memory\n", o->bridge_speed_path);
        return -1;
    }
    s->speed = speed;
    return 0;
}

static int write_speed(const cub_app_options *o, const cub_session *s)
{
    FILE *f = fopen(o->bridge_speed_path, "w");
    if (!f) {
        fprintf(stderr, "cubdance: --bridge-speed %s: %s\n", o->bridge_speed_path,
                strerror(errno));
        return -1;
    }
    cub_bridge_speed_print(s->speed, s->dance, f);
    if (fclose(f)) {
        fprintf(stderr, "cubdance: --bridge-speed %s: %s\n", o->bridge_speed_path,
                strerror(errno));
        return -1;
    }
    printf("cubdance: bridge speeds written to %s\n", o->bridge_speed_path);
    return 0;
}

static int run(const cub_app_options *o, cub_board *board, cub_event_log_file *log,
               const cub_io_motion *clip)
{
    static cub_event slots[64];
    static cub_loop loop;
    cub_loop_desc ld = {.queue_capacity = 64, .log_sink = cub_event_log_line, .log_user = log};
    if (cub_loop_init(&loop, &ld, slots, sizeof slots)) {
        fprintf(stderr, "cubdance: the event loop would not start\n");
        return -1;
    }
    static cub_session s; /* large (it holds this tick's pose): not on the stack */
    s = (cub_session){.opt = o, .board = board, .clip = clip,
                      .clip_name = file_name(o->clip_path), .loop = &loop,
                      .ready_shown = -1};
    int w = 0, h = 0, rc = -1;
    cub_board_display_size(board, &w, &h);
    /* Each buffer only when something will fill it: without --frames the
     * read-back buffer (3.7 MB at 1280x720) would only hold address space. */
    int depth_on = strcmp(cub_board_depth_source(board), "off") != 0;
    s.depth_copy = depth_on ? calloc(CUB_DEPTH_W * CUB_DEPTH_H, sizeof(uint16_t)) : NULL;
    s.rgba = o->frames_dir ? malloc((size_t)(w > 0 ? w : 1) * (h > 0 ? h : 1) * 4) : NULL;
    if ((depth_on && !s.depth_copy) || (o->frames_dir && !s.rgba)) {
        fprintf(stderr, "cubdance: out of memory\n");
        goto done;
    }
    int64_t t0 = cub_board_now_us(board);
    if (o->seconds > 0) s.stop_at_us = t0 + (int64_t)(o->seconds * 1e6);
    const char *display = !cub_board_display_active(board)   ? "none"
                          : cub_board_display_headless(board) ? "headless"
                                                              : "window";
    const char *clock = o->virtual_clock ? "virtual" : "real";
    if (o->song_path) /* the coach is the bear; its clips come with the song */
        cub_log_event(&loop.log, t0, "app", "start",
                      "board=%s display=%s size=%dx%d depth=%s clock=%s song=%s",
                      cub_board_name(), display, w, h, cub_board_depth_source(board), clock,
                      file_name(o->song_path));
    else
        cub_log_event(&loop.log, t0, "app", "start",
                      "board=%s display=%s size=%dx%d depth=%s clock=%s clip=%s joints=%d",
                      cub_board_name(), display, w, h, cub_board_depth_source(board), clock,
                      s.clip_name, clip->skel.joint_count);
    /* The floor first: the walks go over it. */
    if (o->floor_path && !(s.floor = load_floor(o->floor_path))) goto done;
    if (open_extras(o, board, &loop, t0, &s)) goto done;
    if (cub_board_display_active(board)) {
        /* Frame the coach: the bear is a toy, about a metre tall. */
        char why[600] = "";
        cub_render_desc rd = {.width = w, .height = h,
                              .figure_height_mm = s.dance ? cub_dance_figure_height_mm(s.dance)
                                                          : 0,
                              .font_path = o->font_path, .error = why, .error_size = sizeof why};
        if (cub_render_create(&rd, &s.render)) {
            /* A missing font says which file and why; else it is GL. */
            if (why[0]) fprintf(stderr, "cubdance: %s\n", why);
            else fprintf(stderr, "cubdance: the renderer could not start (GLES2)\n");
            goto done;
        }
        if (s.floor && cub_render_set_floor(s.render, s.floor)) {
            fprintf(stderr, "cubdance: the renderer could not draw the floor (GLES2)\n");
            goto done;
        }
    }
    if (o->stats) s.tick_hist = calloc(CUB_SESSION_TICK_BINS, sizeof *s.tick_hist);
    static cub_bridge_speed speed;
    if (o->bridge_speed_path && open_speed(o, &s, &speed)) goto done;
    static cub_mem_stats mem;
    if (o->stats) cub_mem_stats_open(s.mem = &mem);
    if (o->record_dir && !(s.rec = open_recorder(o, board, &loop.log))) goto done;
    if (s.rec) cub_session_follow_recording(&s, t0); /* --record: from the first frame on */
    cub_loop_hooks hooks = cub_session_hooks(&s);
    cub_err err = cub_loop_run(&loop, &hooks, 0);
    cub_record_end(s.rec, cub_board_now_us(board), "exit");
    cub_log_event(&loop.log, cub_board_now_us(board), "app", "end",
                  "ticks=%llu depth_frames=%u frames_written=%u",
                  (unsigned long long)loop.tick_count, s.depth_frames, s.frames_written);
    if (o->frames_dir)
        printf("cubdance: %u frames written to %s\n", s.frames_written, o->frames_dir);
    cub_session_print_stats(&s, stdout);
    rc = err || s.frame_error ? -1 : 0;
    if (s.speed && write_speed(o, &s)) rc = -1;
    if (s.display_lost) {
        fprintf(stderr, "cubdance: the display went away: %s\n", cub_board_display_lost(board));
        rc = -1;
    }
done:
    cub_board_set_depth_tap(board, NULL, NULL);
    cub_record_close(s.rec);
    s.rec = NULL;
    if (s.dance) cub_dance_close(s.dance);
    free(s.dance);
    if (s.watch) cub_watch_close(s.watch);
    free(s.watch);
    cub_timeline_free(s.timeline);
    if (s.render) cub_render_destroy(s.render);
    free(s.depth_copy);
    free(s.rgba);
    free(s.tick_hist);
    if (s.speed) cub_bridge_speed_free(s.speed);
    free(s.floor);
    return rc;
}

/* --config FILE must exist; the default file may be missing (a PC, the
 * simulator), and then the built-in defaults apply. */
static int load_config(cub_app_options *o)
{
    static cub_boxconf c;
    char err[768];
    const char *path = o->config_path ? o->config_path : CUB_BOXCONF_DEFAULT_PATH;
    int from_file = o->config_path || access(path, F_OK) == 0;
    cub_boxconf_defaults(&c);
    if (from_file && cub_boxconf_load(path, &c, err, sizeof err)) {
        fprintf(stderr, "cubdance: %s\n", err);
        return -1;
    }
    /* A wrong assets_dir is named as such, not as the first file missing from it. */
    struct stat st;
    const char *why = !c.assets_dir[0]                    ? NULL
                      : stat(c.assets_dir, &st) != 0      ? strerror(errno)
                      : !S_ISDIR(st.st_mode)              ? "not a directory"
                                                          : NULL;
    if (why) {
        fprintf(stderr, "cubdance: %s: cannot use assets_dir %s: %s\n", path, c.assets_dir, why);
        return -1;
    }
    return cub_app_apply_config(o, &c, from_file, CUB_ASSETS_DIR, stderr);
}

int main(int argc, char **argv)
{
    cub_app_options o;
    switch (cub_app_parse_options(argc, argv, &o, stderr, stdout)) {
    case CUB_APP_EXIT_OK: return 0;
    case CUB_APP_EXIT_BAD: return 2;
    case CUB_APP_RUN: break;
    }
    if (load_config(&o)) return 1;
    if (o.replay_dir && cub_replay_prepare(o.replay_dir, argv, stderr)) return 1;
    if (o.frames_dir && make_dir(o.frames_dir)) return 1;

    cub_io_motion clip;
    if (load_clip(o.clip_path, &clip)) return 1;
    static cub_event_log_file log;
    if (cub_event_log_open(&log, o.log_path, o.log_max_kb)) {
        cub_io_motion_free(&clip);
        return 1;
    }
    cub_board *board = open_board(&o);
    int rc = 1;
    if (board) {
        rc = run(&o, board, &log, &clip) ? 1 : 0;
        cub_board_close(board);
    }
    int to_file = log.f != stderr;
    if (cub_event_log_close(&log))
        rc = 1; /* a lost event log is a failed run, whatever else went well */
    else if (to_file)
        printf("cubdance: event log written to %s\n", o.log_path);
    cub_io_motion_free(&clip);
    return rc;
}

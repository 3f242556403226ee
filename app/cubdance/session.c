/* The loop's hooks for the box program. poll() brings board events in and
 * logs each depth frame as it arrives, before the tracker and the judge
 * see it; handle() runs the waiting/playing states; tick()
 * samples the clip, renders, writes headless frames and enforces --seconds. */
#include "session.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <time.h>

#include "cub/png.h"
#include "cub/track.h"
#include "words.h"

#define DEPTH_PIXELS (CUB_DEPTH_W * CUB_DEPTH_H)

static int64_t hook_now(void *u)
{
    cub_session *s = u;
    return cub_board_now_us(s->board);
}

static void hook_wait(void *u, int64_t t_us)
{
    cub_session *s = u;
    cub_board_sleep_until_us(s->board, t_us);
}

/* What the log says about one depth frame (see log_depth_frame). */
typedef struct cub_depth_probe {
    uint32_t seq, timestamp, valid;
    int64_t t_us;
    uint16_t near_raw, center_raw;
} cub_depth_probe;

/* One log line per depth frame: its sequence number and Kinect timestamp,
 * how many pixels have a reading, and two probes (the nearest reading and
 * the centre pixel) in raw units and in mm, so a replay can be checked
 * against the recording and against the raw->mm formula. */
static cub_depth_probe probe_depth_frame(const cub_depth_frame *f)
{
    cub_depth_probe p = {.seq = f->seq, .timestamp = f->timestamp, .t_us = f->t_us,
                         .near_raw = CUB_DEPTH_NO_READING};
    for (int i = 0; i < DEPTH_PIXELS; i++) {
        uint16_t r = f->raw[i];
        if (r >= CUB_DEPTH_NO_READING) continue;
        p.valid++;
        if (r < p.near_raw) p.near_raw = r;
    }
    p.center_raw = f->raw[(CUB_DEPTH_H / 2) * CUB_DEPTH_W + CUB_DEPTH_W / 2];
    return p;
}

static void log_depth_frame(cub_session *s, const cub_depth_frame *f)
{
    const cub_depth_probe probe = probe_depth_frame(f), *p = &probe;
    cub_log_event(&s->loop->log, p->t_us, "depth", "frame",
                  "seq=%u ts=%u valid=%u near_raw=%u near_mm=%q center_raw=%u center_mm=%q",
                  p->seq, p->timestamp, p->valid, p->near_raw, cub_track_raw_to_mm(p->near_raw),
                  p->center_raw, cub_track_raw_to_mm(p->center_raw));
}

static void poll_depth(cub_session *s, cub_loop *loop, int64_t now_us)
{
    cub_depth_frame f;
    cub_err err = cub_board_depth_poll(s->board, &f);
    if (err == CUB_OK) {
        memcpy(s->depth_copy, f.raw, DEPTH_PIXELS * sizeof(uint16_t));
        s->depth_frames++;
        s->depth_state = CUB_OK;
        /* One way: the frame's line, then what the tracker and the judge
         * make of it (their lines, and their events for the director). */
        log_depth_frame(s, &f);
        if (s->watch) cub_watch_frame(s->watch, loop, f.t_us, f.raw, f.accel);
    } else if (err != CUB_ERR_EMPTY && err != s->depth_state) {
        /* The end of a replay, or a live camera failing: once per change. */
        s->depth_state = err;
        if (err == CUB_ERR_END)
            cub_log_event(&loop->log, now_us, "depth", "end", "frames=%u", s->depth_frames);
        else
            cub_log_event(&loop->log, now_us, "depth", "error", "frames=%u error=\"%s\"",
                          s->depth_frames, cub_err_str(err));
        if (s->watch) cub_watch_source_gone(s->watch, loop, now_us, err == CUB_ERR_END ? "end" : "error");
    }
}

/* The scripted judge's events (--timeline), logged as the real judge logs
 * its own: a verdict speaks of the move being taught now. */
static void post_scripted(cub_session *s, cub_loop *loop, const cub_event *scripted)
{
    const cub_event e = cub_director_scripted(s->dance ? &s->dance->dir : NULL, scripted);
    const cub_event *ev = &e;
    if (ev->type == CUB_EV_VERDICT)
        cub_log_event(&loop->log, ev->t_us, "judge", "verdict", "move=%d result=%s", ev->a,
                      ev->b ? "right" : "wrong");
    else if (ev->type == CUB_EV_PLAYER)
        cub_log_event(&loop->log, ev->t_us, "judge", "player", "present=%d", ev->a);
    else if (ev->type == CUB_EV_CLAP)
        cub_log_event(&loop->log, ev->t_us, "judge", "clap", NULL);
    cub_loop_post(loop, ev);
}

/* The CPU time of this thread (the loop's): what a tick costs, not the
 * time it waits (fakenect's replay sleeps count for nothing). */
static int64_t thread_cpu_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

static void count_tick(cub_session *s)
{
    if (!s->tick_hist) return;
    int64_t us = thread_cpu_us() - s->tick_cpu0_us;
    int64_t bin = us / CUB_SESSION_TICK_BIN_US;
    if (bin >= CUB_SESSION_TICK_BINS) s->tick_over++;
    else s->tick_hist[bin]++;
    if (us > s->tick_max_us) s->tick_max_us = us;
    s->tick_count++;
}

static void hook_poll(void *u, cub_loop *loop, int64_t now_us)
{
    cub_session *s = u;
    if (s->tick_hist) s->tick_cpu0_us = thread_cpu_us();
    cub_board_poll_buttons(s->board, loop, now_us);
    cub_event ev;
    while (cub_timeline_next(s->timeline, now_us, &ev)) post_scripted(s, loop, &ev);
    if (s->dance) cub_dance_poll(s->dance, loop, now_us);
    if (strcmp(cub_board_depth_source(s->board), "off") != 0) poll_depth(s, loop, now_us);
}

static const char *state_name(cub_app_state st)
{
    return st == CUB_APP_PLAYING ? "playing" : "waiting";
}

static void set_state(cub_session *s, cub_app_state to, int64_t t_us)
{
    if (s->state == to) return;
    cub_log_event(&s->loop->log, t_us, "app", "state", "from=%s to=%s", state_name(s->state),
                  state_name(to));
    s->state = to;
    if (to == CUB_APP_PLAYING) {
        s->play_start_us = t_us;
        cub_log_event(&s->loop->log, t_us, "app", "play", "clip=%s frames=%d", s->clip_name,
                      s->clip->clip.frame_count);
    }
}

static void hook_handle(void *u, cub_loop *loop, const cub_event *ev)
{
    cub_session *s = u;
    switch (ev->type) {
    case CUB_EV_BUTTON_DOWN:
    case CUB_EV_BUTTON_UP:
        cub_log_event(&loop->log, ev->t_us, "button",
                      ev->type == CUB_EV_BUTTON_DOWN ? "down" : "up", "name=%s",
                      cub_loop_button_name((cub_button)ev->a));
        if (ev->type == CUB_EV_BUTTON_DOWN && ev->a == CUB_BUTTON_START && s->watch)
            cub_watch_start(s->watch); /* the one who pressed it is the player */
        if (ev->type == CUB_EV_BUTTON_DOWN && !s->dance)
            set_state(s, ev->a == CUB_BUTTON_START ? CUB_APP_PLAYING : CUB_APP_WAITING, ev->t_us);
        break;
    case CUB_EV_QUIT: cub_log_event(&loop->log, ev->t_us, "app", "quit", "reason=user"); break;
    default: break;
    }
    if (s->dance) cub_dance_handle(s->dance, loop, ev);
}

/* The coach's pose this tick into s->world_xyz (and, for the bear, its
 * joints' rotations into s->world_rot): the clip, looping, while playing;
 * its first frame, standing still, while waiting. */
static cub_err coach_world(cub_session *s, int64_t t_us)
{
    if (s->dance) return cub_dance_pose(s->dance, s->world_xyz, s->world_rot);
    const cub_clip *clip = &s->clip->clip;
    int64_t t = s->state == CUB_APP_PLAYING ? t_us - s->play_start_us : 0;
    cub_err err = cub_motion_sample(clip, t, CUB_MOTION_LOOP, &s->pose);
    if (!err) err = cub_motion_forward(clip->skel, &s->pose, s->world_mm, NULL);
    if (!err) cub_motion_world_to_float(s->world_mm, clip->skel->joint_count, s->world_xyz);
    return err;
}

/* The bear's face from the coach's state: it dozes with its eyes shut and
 * looks worried while it corrects; otherwise it is happy. */
static cub_render_face coach_face(int32_t state)
{
    if (state == CUB_COACH_DOZE) return CUB_RENDER_FACE_SLEEPY;
    if (state == CUB_COACH_CORRECT || state == CUB_COACH_WORRIED) return CUB_RENDER_FACE_WORRIED;
    return CUB_RENDER_FACE_HAPPY;
}

/* What the child reads, all from the tick's state, in words.c's words: the
 * coach's hint and the hinted move's icon, the song's progress, the idle
 * screen while the coach waits, and the tracked child and its cue. */
static void show_what_the_coach_says(cub_session *s, cub_render_scene *scene)
{
    if (s->dance) {
        cub_dance *d = s->dance;
        scene->idle = cub_dance_waiting(d);
        scene->hint = cub_dance_words(d);
        scene->child_mark = cub_dance_child_mark(d);
        scene->icon_xyz_mm = scene->skel ? cub_dance_icon_xyz(d) : NULL;
        scene->progress = cub_dance_progress(d);
        scene->has_progress = scene->progress >= 0.0f;
    } else {
        scene->idle = s->state == CUB_APP_WAITING;
    }
    scene->title = scene->idle ? cub_words_title() : NULL;
    if (s->watch) {
        scene->child = cub_watch_skeleton(s->watch);
        scene->child_cue = cub_words_cue(scene->child->status);
    }
}

static void write_frame(cub_session *s, uint64_t tick)
{
    int w, h;
    cub_board_display_size(s->board, &w, &h);
    char path[1024];
    snprintf(path, sizeof path, "%s/frame_%06llu.png", s->opt->frames_dir,
             (unsigned long long)tick);
    cub_err err = cub_board_display_read_rgba(s->board, s->rgba, (size_t)w * h * 4);
    if (!err) err = cub_png_write(path, s->rgba, w, h);
    if (err) {
        if (!s->frame_error)
            fprintf(stderr, "cubdance: cannot write frame %s: %s\n", path, cub_err_str(err));
        s->frame_error = 1;
        return;
    }
    s->frames_written++;
}

/* The ready light follows whether the box waits for START; only changes
 * reach the board (a GPIO write per tick would be wasted). */
static void show_ready(cub_session *s)
{
    int ready = s->dance ? cub_dance_waiting(s->dance) : s->state == CUB_APP_WAITING;
    if (ready != s->ready_shown) {
        cub_board_set_ready(s->board, ready);
        s->ready_shown = ready;
    }
}

/* --bridge-speed: this tick's pose as the coach shows it, every tick (the
 * drawing may skip ticks); the pose decides nothing. */
static void measure_speed(cub_session *s, int64_t t_us)
{
    if (!s->speed || !s->dance || coach_world(s, t_us)) return;
    cub_bridge_speed_tick(s->speed, s->dance, t_us);
}

static void tick_work(cub_session *s, cub_loop *loop, int64_t t_us)
{
    if (s->stop_at_us && t_us >= s->stop_at_us) {
        cub_log_event(&loop->log, t_us, "app", "stop", "reason=seconds");
        cub_loop_stop(loop);
        return;
    }
    if (s->watch) cub_watch_tick(s->watch, loop, t_us);
    if (s->dance) cub_dance_tick(s->dance, loop, t_us);
    measure_speed(s, t_us);
    show_ready(s);
    /* (--draw-every: the renderer decides nothing, so skipping ticks leaves
     * the event log as it is; a window always draws every tick) */
    if (!s->render || (cub_board_display_headless(s->board) &&
                       loop->tick_count % (uint64_t)s->opt->draw_every))
        return;
    cub_err err = coach_world(s, t_us);
    if (err && !s->pose_error) {
        cub_log_event(&loop->log, t_us, "app", "error", "what=pose error=\"%s\"",
                      cub_err_str(err));
        s->pose_error = 1;
    }
    const cub_skeleton *skel = s->dance ? cub_dance_skeleton(s->dance) : s->clip->clip.skel;
    cub_render_scene scene = {.skel = err ? NULL : skel,
                              .world_xyz_mm = s->world_xyz,
                              .depth_raw = s->depth_frames ? s->depth_copy : NULL};
    if (!err && s->dance) {
        scene.world_rot_xyzw = s->world_rot;
        scene.face = coach_face(s->dance->dir.coach.state);
    }
    show_what_the_coach_says(s, &scene);
    if (!err && s->dance)
        cub_dance_picture(s->dance, t_us, &scene.character, &scene.skel, &scene.world_xyz_mm,
                          &scene.world_rot_xyzw, &scene.icon_xyz_mm);
    cub_render_frame(s->render, &scene);
    if (s->opt->frames_dir && loop->tick_count % (uint64_t)s->opt->frame_every == 0)
        write_frame(s, loop->tick_count);
    cub_board_display_swap(s->board);
}

/* The box records only while a dance runs (config recording=1), or the
 * whole run (--record). */
static int dancing(const cub_session *s)
{
    return s->dance ? !cub_dance_waiting(s->dance) : s->state == CUB_APP_PLAYING;
}

void cub_session_follow_recording(cub_session *s, int64_t t_us)
{
    int want = !s->opt->record_each_dance || dancing(s);
    if (want && !s->recording_on) cub_record_begin(s->rec, t_us);
    else if (!want && s->recording_on) cub_record_end(s->rec, t_us, "idle");
    s->recording_on = want;
}

static void check_display(cub_session *s, cub_loop *loop, int64_t t_us)
{
    const char *lost = cub_board_display_lost(s->board);
    if (lost && !s->display_lost) {
        cub_log_event(&loop->log, t_us, "app", "error", "what=display error=\"%s\"", lost);
        s->display_lost = 1;
        cub_loop_stop(loop);
    }
}

static void hook_tick(void *u, cub_loop *loop, int64_t t_us)
{
    cub_session *s = u;
    tick_work(s, loop, t_us);
    count_tick(s);
    check_display(s, loop, t_us);
    if (s->rec) cub_session_follow_recording(s, t_us);
    if (s->mem) cub_mem_stats_tick(s->mem, t_us, dancing(s));
}

/* The tick's CPU time at quantile q (0..1), ms; from the bins (25 us). */
static double tick_quantile_ms(const cub_session *s, double q)
{
    uint32_t want = (uint32_t)(q * s->tick_count), seen = 0;
    for (int b = 0; b < CUB_SESSION_TICK_BINS; b++) {
        seen += s->tick_hist[b];
        if (seen > want) return (b + 0.5) * CUB_SESSION_TICK_BIN_US / 1000.0;
    }
    return s->tick_max_us / 1000.0;
}

/* One field of /proc/self/status in kB (e.g. "RssAnon"), or -1 where there
 * is no such file (not Linux) or no such field (kernels before 4.5). */
static long proc_status_kb(const char *field)
{
    FILE *f = fopen("/proc/self/status", "r");
    if (!f) return -1;
    char line[256];
    long kb = -1;
    size_t n = strlen(field);
    while (kb < 0 && fgets(line, sizeof line, f))
        if (strncmp(line, field, n) == 0 && line[n] == ':') kb = strtol(line + n + 1, NULL, 10);
    fclose(f);
    return kb;
}

/* The memory line: the peak, and now what is resident split into what we
 * (and the libraries) allocated (RssAnon: heap, stacks, SoundFont samples,
 * GL buffers) and file pages mapped (RssFile: the code of the libraries,
 * mostly Mesa's libLLVM under llvmpipe; shared with every other process and
 * dropped by the kernel under pressure). Fields missing from the system are
 * left out rather than printed as zeros. */
static void print_memory(FILE *out, long peak_kb)
{
    static const char *const fields[][2] = {
        {"VmRSS", "rss"}, {"RssAnon", "rss_anon"}, {"RssFile", "rss_file"}};
    fprintf(out, "stats: memory peak_rss=%.1fMB", peak_kb / 1024.0);
    for (size_t i = 0; i < sizeof fields / sizeof *fields; i++) {
        long kb = proc_status_kb(fields[i][0]);
        if (kb >= 0) fprintf(out, " %s=%.1fMB", fields[i][1], kb / 1024.0);
    }
    fputc('\n', out);
}

void cub_session_print_stats(const cub_session *s, FILE *out)
{
    if (!s->tick_hist || !s->tick_count) return;
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    fprintf(out,
            "cubdance: tick CPU (poll, track, judge, coach, render) median=%.2f ms p95=%.2f ms "
            "max=%.2f ms over %u ticks; peak resident memory %.1f MB\n",
            tick_quantile_ms(s, 0.5), tick_quantile_ms(s, 0.95), s->tick_max_us / 1000.0,
            s->tick_count, ru.ru_maxrss / 1024.0);
    print_memory(out, ru.ru_maxrss);
    if (s->mem) cub_mem_stats_print(s->mem, out);
}

cub_loop_hooks cub_session_hooks(cub_session *s)
{
    cub_loop_hooks h = {.user = s, .now_us = hook_now, .poll = hook_poll,
                        .handle = hook_handle, .tick = hook_tick, .wait_until = hook_wait};
    return h;
}

/* display_sdl — the windowed backend: an SDL2 window with an OpenGL ES 2.0
 * context and vsync. On the box SDL's KMSDRM video driver drives HDMI with
 * no display server; there the window is made full-screen-desktop so it
 * covers the TV at its native mode (the drawable size then replaces the
 * requested size: cub_display_size reports what we really got).
 *
 * read_rgba reads the BACK buffer: call it after drawing and before
 * cub_display_swap, since after a swap the back buffer's content is
 * undefined (EGL_BUFFER_DESTROYED is the usual swap behaviour).
 *
 * The display going away (the TV's HDMI cable pulled) shows in one of three
 * ways, and each marks the display lost (cub_display_lost) for the app to
 * end on: swaps fail (SDL 2's SDL_GL_SwapWindow returns void; its KMSDRM
 * swap reports a failed eglSwapBuffers, GBM lock or page flip only through
 * SDL_LogError, which a log hook catches); SDL posts SDL_DISPLAYEVENT_DISCONNECTED
 * (X11, Wayland; SDL 2.26's KMSDRM posts none); on KMSDRM no HDMI
 * connector reports "connected" in sysfs any more. The last matters most:
 * KMSDRM keeps the CRTC running after an unplug, so page flips go on
 * succeeding and nothing else would tell.
 *
 * A seam for tests (no HDMI to pull here): CUB_DISPLAY_FAULT=swap@N makes
 * swaps from the Nth on fail as SDL reports a failure (its log), disconnect@N posts SDL's
 * disconnect event at the Nth swap, unplug@N reports the HDMI connectors
 * disconnected from the Nth swap on. The paths after that are the real ones.
 */
#include <SDL2/SDL.h>
#include <dirent.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "display_backend.h"

/* How often (in swaps, about once a second at 60 Hz) sysfs is read. */
#define CONNECTOR_CHECK_EVERY 60
/* HDMI connectors watched (a Pi 4 has two). */
#define MAX_HDMI 4
/* Swaps in a row that SDL reported failing before the display counts as lost. */
#define SWAP_FAILS_LOST 30

typedef enum fault_kind { FAULT_NONE, FAULT_SWAP, FAULT_DISCONNECT, FAULT_UNPLUG } fault_kind;

typedef struct sdl_state {
    SDL_Window *win;
    SDL_GLContext ctx;
    cub_display *d;
    char driver[32];       /* SDL's video driver in use */
    int watch_connectors;  /* KMSDRM with an HDMI connector connected at open */
    int watch_added;       /* on_event is registered with SDL */
    unsigned long swaps;
    int failed_swaps;      /* in a row */
    char hdmi_status[MAX_HDMI][128]; /* the connectors' sysfs status files */
    char hdmi_name[MAX_HDMI][32];    /* ... and names, e.g. HDMI-A-1 */
    int hdmi_count;
    fault_kind fault;      /* CUB_DISPLAY_FAULT, for tests */
    unsigned long fault_at;
} sdl_state;

static int is_headless_driver(const char *name)
{
    return name && (strcmp(name, "offscreen") == 0 || strcmp(name, "dummy") == 0);
}

int cub_display_window_available(void)
{
    /* Already up (the app opened a window): judge the driver in use and
     * leave SDL as it is. */
    if (SDL_WasInit(SDL_INIT_VIDEO))
        return !is_headless_driver(SDL_GetCurrentVideoDriver());
    /* Otherwise try SDL's own choice (X11, Wayland, KMSDRM, ... honouring
     * SDL_VIDEODRIVER) and shut video down again, so a later open starts
     * from a clean state. */
    if (SDL_InitSubSystem(SDL_INIT_VIDEO) != 0)
        return 0;
    int ok = !is_headless_driver(SDL_GetCurrentVideoDriver());
    SDL_QuitSubSystem(SDL_INIT_VIDEO);
    return ok;
}

static void mark_lost(sdl_state *s, const char *fmt, const char *what)
{
    if (!s->d->lost[0])
        snprintf(s->d->lost, sizeof s->d->lost, fmt, s->driver, what);
}

/* SDL calls this for every event as it is queued, whoever drains the
 * queue later (the board's key poll). */
static int on_event(void *user, SDL_Event *e)
{
    sdl_state *s = user;
    if (e->type == SDL_DISPLAYEVENT && e->display.event == SDL_DISPLAYEVENT_DISCONNECTED) {
        char what[32];
        snprintf(what, sizeof what, "%d", (int)e->display.display);
        mark_lost(s, "%s: display %s disconnected", what);
    }
    return 1;
}

/* The HDMI connectors (/sys/class/drm/cardN-HDMI-A-M), found once at open:
 * a board's connectors come with its DRM driver and do not change while it
 * runs, and a check that only reads their status files with read(2)
 * allocates nothing in a running box (opendir and fopen would). */
static void find_hdmi(sdl_state *s)
{
    DIR *dir = opendir("/sys/class/drm");
    if (!dir)
        return;
    struct dirent *ent;
    while ((ent = readdir(dir)) && s->hdmi_count < MAX_HDMI) {
        const char *dash = strchr(ent->d_name, '-');
        if (strncmp(ent->d_name, "card", 4) != 0 || !dash || !strstr(dash, "HDMI"))
            continue;
        int n = snprintf(s->hdmi_status[s->hdmi_count], sizeof s->hdmi_status[0],
                         "/sys/class/drm/%s/status", ent->d_name);
        if (n <= 0 || (size_t)n >= sizeof s->hdmi_status[0])
            continue;
        snprintf(s->hdmi_name[s->hdmi_count], sizeof s->hdmi_name[0], "%s", dash + 1);
        s->hdmi_count++;
    }
    closedir(dir);
}

/* How many of the HDMI connectors say "connected"; *name gets the first
 * one's. -1 if there is no HDMI connector at all (nothing to watch). */
static int hdmi_connected(const sdl_state *s, char *name, size_t size)
{
    int seen = 0, connected = 0;
    for (int i = 0; i < s->hdmi_count; i++) {
        char status[32];
        int fd = open(s->hdmi_status[i], O_RDONLY);
        if (fd < 0)
            continue;
        ssize_t got = read(fd, status, sizeof status - 1);
        close(fd);
        status[got > 0 ? got : 0] = '\0';
        if (!seen++)
            snprintf(name, size, "%s", s->hdmi_name[i]);
        connected += strncmp(status, "connected", 9) == 0;
    }
    return seen ? connected : -1;
}

static void read_fault(sdl_state *s)
{
    static const struct { const char *name; fault_kind kind; } kinds[] = {
        {"swap@", FAULT_SWAP}, {"disconnect@", FAULT_DISCONNECT}, {"unplug@", FAULT_UNPLUG}};
    const char *f = getenv("CUB_DISPLAY_FAULT");
    for (size_t i = 0; f && i < sizeof kinds / sizeof *kinds; i++) {
        size_t n = strlen(kinds[i].name);
        if (strncmp(f, kinds[i].name, n) == 0) {
            s->fault = kinds[i].kind;
            s->fault_at = strtoul(f + n, NULL, 10);
        }
    }
}

static void check_connectors(sdl_state *s)
{
    char name[64] = "HDMI";
    int connected = hdmi_connected(s, name, sizeof name);
    if (s->fault == FAULT_UNPLUG && s->swaps >= s->fault_at)
        connected = 0;
    if (connected == 0)
        mark_lost(s, "%s: HDMI not connected any more (%s disconnected)", name);
}

static void sdl_close(cub_display *d)
{
    sdl_state *s = d->impl;
    if (s->watch_added)
        SDL_DelEventWatch(on_event, s);
    if (s->ctx)
        SDL_GL_DeleteContext(s->ctx);
    if (s->win)
        SDL_DestroyWindow(s->win);
    SDL_QuitSubSystem(SDL_INIT_VIDEO);
    free(s);
    free(d);
}

/* SDL 2's SDL_GL_SwapWindow returns nothing: a failing swap only shows as
 * SDL_LogError(VIDEO, ...) from inside it (KMSDRM: "Could not queue
 * pageflip", "eglSwapBuffers failed", ...). The log hook notes those made
 * while one of ours swaps, and passes every message on as before. */
static sdl_state *swapping;
static char swap_error[160];
static SDL_LogOutputFunction prev_log;
static void *prev_log_user;

static void on_log(void *user, int category, SDL_LogPriority priority, const char *message)
{
    if (swapping && category == SDL_LOG_CATEGORY_VIDEO && priority >= SDL_LOG_PRIORITY_ERROR &&
        !swap_error[0])
        snprintf(swap_error, sizeof swap_error, "%s", message);
    if (prev_log)
        prev_log(prev_log_user, category, priority, message);
}

static void sdl_swap(cub_display *d)
{
    sdl_state *s = d->impl;
    if (d->lost[0])
        return; /* nothing shows any more; the app is ending */
    s->swaps++;
    if (s->fault == FAULT_DISCONNECT && s->swaps == s->fault_at) {
        SDL_Event e = {.display = {.type = SDL_DISPLAYEVENT,
                                   .event = SDL_DISPLAYEVENT_DISCONNECTED, .display = 0}};
        SDL_PushEvent(&e);
    }
    swapping = s;
    swap_error[0] = '\0';
    SDL_GL_SwapWindow(s->win);
    if (s->fault == FAULT_SWAP && s->swaps >= s->fault_at)
        SDL_LogError(SDL_LOG_CATEGORY_VIDEO, "Could not queue pageflip: -19 (CUB_DISPLAY_FAULT)");
    swapping = NULL;
    /* One failed flip can be a hiccup (EBUSY); half a second of them is a
     * display that is gone. */
    s->failed_swaps = swap_error[0] ? s->failed_swaps + 1 : 0;
    if (s->failed_swaps >= SWAP_FAILS_LOST) {
        mark_lost(s, "%s: every swap fails: %s", swap_error);
        return;
    }
    if ((s->watch_connectors || s->fault == FAULT_UNPLUG) &&
        s->swaps % CONNECTOR_CHECK_EVERY == 0)
        check_connectors(s);
}

static const cub_display_ops sdl_ops = {sdl_close, sdl_swap};

static cub_err init_video(const char *video_driver, char *err, size_t err_size)
{
    /* An earlier open's choice must not stick: NULL goes back to SDL's own
     * (which honours env SDL_VIDEODRIVER). */
    if (video_driver)
        SDL_SetHint(SDL_HINT_VIDEODRIVER, video_driver);
    else
        SDL_ResetHint(SDL_HINT_VIDEODRIVER);
    /* ES through EGL where the driver offers both (X11 would pick GLX). */
    SDL_SetHint(SDL_HINT_OPENGL_ES_DRIVER, "1");
    SDL_SetHint(SDL_HINT_VIDEO_X11_FORCE_EGL, "1");
    if (SDL_InitSubSystem(SDL_INIT_VIDEO) != 0) {
        cub_display_fail(err, err_size, "window display: SDL video init (driver %s) failed: %s",
             video_driver ? video_driver : "SDL's choice", SDL_GetError());
        return CUB_ERR_DEVICE;
    }
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_PROFILE_MASK, SDL_GL_CONTEXT_PROFILE_ES);
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 2);
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, 0);
    SDL_GL_SetAttribute(SDL_GL_DOUBLEBUFFER, 1);
    SDL_GL_SetAttribute(SDL_GL_RED_SIZE, 8);
    SDL_GL_SetAttribute(SDL_GL_GREEN_SIZE, 8);
    SDL_GL_SetAttribute(SDL_GL_BLUE_SIZE, 8);
    SDL_GL_SetAttribute(SDL_GL_DEPTH_SIZE, 16);
    return CUB_OK;
}

/* Full screen at the asked size changes the screen's mode; the desktop
 * kind keeps the mode the screen has (KMSDRM's default, and "auto"). */
static Uint32 window_flags(const char *driver, int fullscreen, int fit)
{
    Uint32 flags = SDL_WINDOW_OPENGL | SDL_WINDOW_SHOWN;
    if (fullscreen > 0)
        flags |= fit ? SDL_WINDOW_FULLSCREEN_DESKTOP : SDL_WINDOW_FULLSCREEN;
    else if (fullscreen == 0 && driver && strcmp(driver, "KMSDRM") == 0)
        flags |= SDL_WINDOW_FULLSCREEN_DESKTOP;
    return flags;
}

/* w x h 0x0: the size of the screen's current mode (1280x720 if unknown). */
static void fit_size(cub_display *d)
{
    SDL_DisplayMode mode;
    if (d->w > 0 && d->h > 0)
        return;
    if (SDL_GetDesktopDisplayMode(0, &mode) == 0 && mode.w > 0 && mode.h > 0) {
        d->w = mode.w;
        d->h = mode.h;
    } else {
        d->w = 1280;
        d->h = 720;
    }
}

static cub_err make_window(cub_display *d, sdl_state *s, int fullscreen, char *err,
                           size_t err_size)
{
    const char *driver = SDL_GetCurrentVideoDriver();
    Uint32 flags = window_flags(driver, fullscreen, d->w <= 0);
    fit_size(d);
    s->win = SDL_CreateWindow("cubdance", SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, d->w,
                              d->h, flags);
    if (!s->win) {
        cub_display_fail(err, err_size, "window display: SDL_CreateWindow %dx%d on %s failed: %s", d->w,
             d->h, driver ? driver : "?", SDL_GetError());
        return CUB_ERR_DEVICE;
    }
    s->ctx = SDL_GL_CreateContext(s->win);
    if (!s->ctx) {
        cub_display_fail(err, err_size, "window display: SDL_GL_CreateContext(ES 2.0) on %s failed: %s",
             driver ? driver : "?", SDL_GetError());
        return CUB_ERR_UNSUPPORTED;
    }
    if (SDL_GL_MakeCurrent(s->win, s->ctx) != 0) {
        cub_display_fail(err, err_size, "window display: SDL_GL_MakeCurrent failed: %s", SDL_GetError());
        return CUB_ERR_DEVICE;
    }
    /* Vsync paces the loop on the box; some drivers refuse it, which only
     * costs tearing, so it is not an error. */
    if (SDL_GL_SetSwapInterval(1) != 0)
        fprintf(stderr, "window display: no vsync on %s: %s\n", driver ? driver : "?",
                SDL_GetError());
    SDL_GL_GetDrawableSize(s->win, &d->w, &d->h);
    snprintf(s->driver, sizeof s->driver, "%s", driver ? driver : "?");
    char name[64];
    find_hdmi(s);
    s->watch_connectors = !strcmp(s->driver, "KMSDRM") && hdmi_connected(s, name, sizeof name) > 0;
    read_fault(s);
    SDL_AddEventWatch(on_event, s);
    s->watch_added = 1;
    SDL_LogOutputFunction out;
    void *out_user;
    SDL_LogGetOutputFunction(&out, &out_user);
    /* SDL drops VIDEO errors below CRITICAL unless told otherwise. */
    if (SDL_LogGetPriority(SDL_LOG_CATEGORY_VIDEO) > SDL_LOG_PRIORITY_ERROR)
        SDL_LogSetPriority(SDL_LOG_CATEGORY_VIDEO, SDL_LOG_PRIORITY_ERROR);
    if (out != on_log) {
        prev_log = out;
        prev_log_user = out_user;
        SDL_LogSetOutputFunction(on_log, NULL);
    }
    return CUB_OK;
}

cub_err cub_display_open_window(int w, int h, const char *video_driver, cub_display **out,
                                char *err, size_t err_size)
{
    if (w <= 0 || h <= 0) {
        cub_display_fail(err, err_size, "window display: bad arguments (%dx%d)", w, h);
        return CUB_ERR_ARG;
    }
    return cub_display_open_screen(w, h, video_driver, 0, out, err, err_size);
}

cub_err cub_display_open_screen(int w, int h, const char *video_driver, int fullscreen,
                                cub_display **out, char *err, size_t err_size)
{
    int fit = w == 0 && h == 0;
    if (!out || (!fit && (w <= 0 || h <= 0)) || w > 16384 || h > 16384) {
        cub_display_fail(err, err_size, "window display: bad arguments (%dx%d)", w, h);
        return CUB_ERR_ARG;
    }
    *out = NULL;
    cub_err e = init_video(video_driver, err, err_size);
    if (e)
        return e;
    cub_display *d = calloc(1, sizeof *d);
    sdl_state *s = calloc(1, sizeof *s);
    if (!d || !s) {
        free(d);
        free(s);
        SDL_QuitSubSystem(SDL_INIT_VIDEO);
        cub_display_fail(err, err_size, "window display: out of memory");
        return CUB_ERR_NOMEM;
    }
    *d = (cub_display){.ops = &sdl_ops, .w = w, .h = h, .headless = 0, .impl = s};
    s->d = d;
    e = make_window(d, s, fullscreen, err, err_size);
    if (e) {
        sdl_close(d);
        return e;
    }
    *out = d;
    return CUB_OK;
}

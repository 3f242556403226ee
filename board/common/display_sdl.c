/* display_sdl — the windowed backend: an SDL2 window with an OpenGL ES 2.0
 * context and vsync. On the box SDL's KMSDRM video driver drives HDMI with
 * no display server; there the window is made full-screen-desktop so it
 * covers the TV at its native mode (the drawable size then replaces the
 * requested size: cub_display_size reports what we really got).
 *
 * read_rgba reads the BACK buffer: call it after drawing and before
 * cub_display_swap, since after a swap the back buffer's content is
 * undefined (EGL_BUFFER_DESTROYED is the usual swap behaviour).
 */
#include <SDL2/SDL.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "display_backend.h"

typedef struct sdl_state {
    SDL_Window *win;
    SDL_GLContext ctx;
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

static void sdl_close(cub_display *d)
{
    sdl_state *s = d->impl;
    if (s->ctx)
        SDL_GL_DeleteContext(s->ctx);
    if (s->win)
        SDL_DestroyWindow(s->win);
    SDL_QuitSubSystem(SDL_INIT_VIDEO);
    free(s);
    free(d);
}

static void sdl_swap(cub_display *d)
{
    sdl_state *s = d->impl;
    SDL_GL_SwapWindow(s->win);
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
    e = make_window(d, s, fullscreen, err, err_size);
    if (e) {
        sdl_close(d);
        return e;
    }
    *out = d;
    return CUB_OK;
}

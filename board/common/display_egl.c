/* display_egl — the headless backend: an OpenGL ES 2 context on Mesa's
 * surfaceless EGL platform (no X, no Wayland, no DRM master needed), drawing
 * into a framebuffer object. With no GPU, Mesa renders with llvmpipe; the
 * golden-image tests use this.
 *
 * Order of attempts for the display:
 *   1. eglGetPlatformDisplay (EGL 1.5) or eglGetPlatformDisplayEXT with
 *      EGL_PLATFORM_SURFACELESS_MESA, when the client extensions list
 *      EGL_MESA_platform_surfaceless;
 *   2. otherwise eglGetDisplay(EGL_DEFAULT_DISPLAY) with env
 *      EGL_PLATFORM=surfaceless (set here only if the caller has not set it).
 * The context has no surface (EGL_KHR_surfaceless_context); the FBO is the
 * only framebuffer, left bound so callers just draw.
 */
#define _POSIX_C_SOURCE 200809L /* setenv */

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES2/gl2.h>
#include <GLES2/gl2ext.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "display_backend.h"

typedef struct egl_state {
    EGLDisplay dpy;
    EGLContext ctx;
    GLuint fbo, color_rb, depth_rb;
} egl_state;

/* Whole-word search in a space-separated extension list. */
static int has_ext(const char *list, const char *name)
{
    size_t n = strlen(name);
    for (const char *p = list; p && (p = strstr(p, name)) != NULL; p += n) {
        int starts = p == list || p[-1] == ' ';
        int ends = p[n] == '\0' || p[n] == ' ';
        if (starts && ends)
            return 1;
    }
    return 0;
}

static EGLDisplay get_surfaceless_display(char *how, size_t how_size)
{
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (has_ext(client, "EGL_MESA_platform_surfaceless")) {
        PFNEGLGETPLATFORMDISPLAYPROC get15 =
            (PFNEGLGETPLATFORMDISPLAYPROC)eglGetProcAddress("eglGetPlatformDisplay");
        if (get15) {
            snprintf(how, how_size, "eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA)");
            EGLDisplay dpy = get15(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
            if (dpy != EGL_NO_DISPLAY)
                return dpy;
        }
        PFNEGLGETPLATFORMDISPLAYEXTPROC get_ext =
            (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
        if (get_ext && has_ext(client, "EGL_EXT_platform_base")) {
            snprintf(how, how_size, "eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA)");
            EGLDisplay dpy = get_ext(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
            if (dpy != EGL_NO_DISPLAY)
                return dpy;
        }
    }
    /* Older or non-glvnd EGL: Mesa reads the platform from the environment. */
    setenv("EGL_PLATFORM", "surfaceless", 0);
    snprintf(how, how_size, "eglGetDisplay(EGL_DEFAULT_DISPLAY) with EGL_PLATFORM=%s",
             getenv("EGL_PLATFORM"));
    return eglGetDisplay(EGL_DEFAULT_DISPLAY);
}

static cub_err make_context(egl_state *s, char *err, size_t err_size)
{
    char how[128];
    s->dpy = get_surfaceless_display(how, sizeof how);
    if (s->dpy == EGL_NO_DISPLAY) {
        cub_display_fail(err, err_size, "headless display: %s returned EGL_NO_DISPLAY (eglGetError 0x%04x)",
             how, eglGetError());
        return CUB_ERR_DEVICE;
    }
    EGLint major = 0, minor = 0;
    if (!eglInitialize(s->dpy, &major, &minor)) {
        cub_display_fail(err, err_size, "headless display: eglInitialize failed (eglGetError 0x%04x) on %s",
             eglGetError(), how);
        s->dpy = EGL_NO_DISPLAY;
        return CUB_ERR_DEVICE;
    }
    if (!has_ext(eglQueryString(s->dpy, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context")) {
        cub_display_fail(err, err_size, "headless display: EGL %d.%d lacks EGL_KHR_surfaceless_context",
             major, minor);
        return CUB_ERR_UNSUPPORTED;
    }
    if (!eglBindAPI(EGL_OPENGL_ES_API)) {
        cub_display_fail(err, err_size, "headless display: eglBindAPI(EGL_OPENGL_ES_API) failed (0x%04x)",
             eglGetError());
        return CUB_ERR_UNSUPPORTED;
    }
    /* EGL_SURFACE_TYPE 0: we never make a surface, so any config will do. */
    const EGLint cfg_attr[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES2_BIT, EGL_SURFACE_TYPE, 0,
                               EGL_NONE};
    EGLConfig cfg;
    EGLint n = 0;
    if (!eglChooseConfig(s->dpy, cfg_attr, &cfg, 1, &n) || n < 1) {
        cub_display_fail(err, err_size, "headless display: eglChooseConfig found no GLES2 config (0x%04x)",
             eglGetError());
        return CUB_ERR_UNSUPPORTED;
    }
    const EGLint ctx_attr[] = {EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE};
    s->ctx = eglCreateContext(s->dpy, cfg, EGL_NO_CONTEXT, ctx_attr);
    if (s->ctx == EGL_NO_CONTEXT) {
        cub_display_fail(err, err_size, "headless display: eglCreateContext(ES 2) failed (0x%04x)",
             eglGetError());
        return CUB_ERR_DEVICE;
    }
    if (!eglMakeCurrent(s->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, s->ctx)) {
        cub_display_fail(err, err_size, "headless display: eglMakeCurrent(no surface) failed (0x%04x)",
             eglGetError());
        return CUB_ERR_DEVICE;
    }
    return CUB_OK;
}

static cub_err make_fbo(egl_state *s, int w, int h, char *err, size_t err_size)
{
    /* RGBA8 renderbuffers are an extension in ES2; RGBA4 is the core fallback. */
    const char *exts = (const char *)glGetString(GL_EXTENSIONS);
    GLenum color_fmt = has_ext(exts, "GL_OES_rgb8_rgba8") ? GL_RGBA8_OES : GL_RGBA4;
    glGenFramebuffers(1, &s->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo);
    glGenRenderbuffers(1, &s->color_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, s->color_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, color_fmt, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, s->color_rb);
    glGenRenderbuffers(1, &s->depth_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, s->depth_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT16, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, s->depth_rb);
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    GLenum gl_err = glGetError();
    if (status != GL_FRAMEBUFFER_COMPLETE || gl_err != GL_NO_ERROR) {
        cub_display_fail(err, err_size,
             "headless display: framebuffer %dx%d (%s + DEPTH16) incomplete: status 0x%04x, "
             "GL error 0x%04x",
             w, h, color_fmt == GL_RGBA4 ? "RGBA4" : "RGBA8", status, gl_err);
        return CUB_ERR_DEVICE;
    }
    glViewport(0, 0, w, h);
    return CUB_OK;
}

static void egl_close(cub_display *d)
{
    egl_state *s = d->impl;
    if (s->ctx != EGL_NO_CONTEXT) {
        glDeleteRenderbuffers(1, &s->depth_rb);
        glDeleteRenderbuffers(1, &s->color_rb);
        glDeleteFramebuffers(1, &s->fbo);
        eglMakeCurrent(s->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(s->dpy, s->ctx);
    }
    /* No eglTerminate: the surfaceless EGLDisplay is a per-process
     * singleton (the next open gets the same handle back and eglInitialize
     * is then a no-op). Terminating unloads Mesa's driver, which strands its
     * shader caches so LeakSanitizer reports them as our leaks, and buys
     * nothing for a process that is about to exit or reopen. */
    if (s->dpy != EGL_NO_DISPLAY)
        eglReleaseThread();
    free(s);
    free(d);
}

/* No surface to present: finishing the frame is all a swap means here. */
static void egl_swap(cub_display *d)
{
    (void)d;
    glFinish();
}

static const cub_display_ops egl_ops = {egl_close, egl_swap};

cub_err cub_display_open_headless(int w, int h, cub_display **out, char *err, size_t err_size)
{
    if (!out || w <= 0 || h <= 0 || w > 16384 || h > 16384) {
        cub_display_fail(err, err_size, "headless display: bad arguments (%dx%d)", w, h);
        return CUB_ERR_ARG;
    }
    *out = NULL;
    cub_display *d = calloc(1, sizeof *d);
    egl_state *s = calloc(1, sizeof *s);
    if (!d || !s) {
        free(d);
        free(s);
        cub_display_fail(err, err_size, "headless display: out of memory");
        return CUB_ERR_NOMEM;
    }
    s->dpy = EGL_NO_DISPLAY;
    s->ctx = EGL_NO_CONTEXT;
    *d = (cub_display){.ops = &egl_ops, .w = w, .h = h, .headless = 1, .impl = s};
    cub_err e = make_context(s, err, err_size);
    if (!e)
        e = make_fbo(s, w, h, err, err_size);
    if (e) {
        egl_close(d);
        return e;
    }
    *out = d;
    return CUB_OK;
}

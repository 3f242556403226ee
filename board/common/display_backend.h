/* display_backend — what the two display backends (display_egl.c,
 * display_sdl.c) share: the cub_display struct, their operations table, and
 * the one GLES2 read-back both use. Private to the display files. */
#ifndef CUB_BOARD_DISPLAY_BACKEND_H
#define CUB_BOARD_DISPLAY_BACKEND_H

#include <stddef.h>
#include <stdint.h>

#include "display.h"

typedef struct cub_display_ops {
    void (*close)(cub_display *d);
    void (*swap)(cub_display *d);
} cub_display_ops;

struct cub_display {
    const cub_display_ops *ops;
    int w, h;      /* drawable size in pixels */
    int headless;  /* 1: EGL surfaceless + FBO; 0: SDL window */
    void *impl;    /* the backend's own state */
    char lost[256]; /* "" while it works; why it is gone (cub_display_lost) */
};

/* glReadPixels of the bound framebuffer (w x h at 0,0), flipped so the top
 * row comes first. Shared by both backends. */
cub_err cub_display_gl_read_rgba(int w, int h, uint8_t *rgba, size_t size);

/* printf a failure message into err (nothing if err is NULL or empty). */
void cub_display_fail(char *err, size_t err_size, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

#endif

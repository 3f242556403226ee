/* display — the GLES2 context behind cub_board's display functions (private
 * to board/). Two backends, one file each: display_egl.c (headless: EGL on
 * Mesa's surfaceless platform, drawing into an off-screen framebuffer) and
 * display_sdl.c (an SDL2 window; on the box SDL's KMSDRM video driver puts
 * it full screen on HDMI). Both leave a current GLES2 context after open.
 */
#ifndef CUB_BOARD_DISPLAY_H
#define CUB_BOARD_DISPLAY_H

#include <stddef.h>
#include <stdint.h>

#include "cub/err.h"

typedef struct cub_display cub_display;

/* Off-screen, no display server needed. */
cub_err cub_display_open_headless(int w, int h, cub_display **out, char *err, size_t err_size);
/* An SDL2 window. video_driver NULL = SDL's choice; "KMSDRM" on the box. */
cub_err cub_display_open_window(int w, int h, const char *video_driver, cub_display **out,
                                char *err, size_t err_size);
/* The same, on the screen: w x h 0x0 = the screen's own mode; fullscreen
 * 1 = full screen at w x h (the mode changes), 0 = full screen (desktop
 * size) only on KMSDRM, -1 = a window. */
cub_err cub_display_open_screen(int w, int h, const char *video_driver, int fullscreen,
                                cub_display **out, char *err, size_t err_size);
/* 1 if a window could open here (a display server or KMSDRM is present). */
int cub_display_window_available(void);
void cub_display_close(cub_display *d);
int cub_display_is_headless(const cub_display *d);
void cub_display_size(const cub_display *d, int *w, int *h);
void cub_display_swap(cub_display *d);
/* NULL while the display works; once it is gone (the window's swap failed,
 * SDL said the display was disconnected, or on KMSDRM no connector is
 * connected any more) a message naming the driver and why. */
const char *cub_display_lost(const cub_display *d);
/* The frame just drawn, RGBA8, top row first; size must be >= w*h*4. */
cub_err cub_display_read_rgba(cub_display *d, uint8_t *rgba, size_t size);

#endif

/* png — write and read 8-bit RGBA PNG files (libpng), for headless frames,
 * contact sheets and golden-image tests; and a small software canvas to
 * draw them with (round dots, thick lines, a 5x7 pixel font) where no GPU
 * is wanted: contact sheets, the motion graph. */
#ifndef CUB_PNG_H
#define CUB_PNG_H

#include <stddef.h>
#include <stdint.h>

#include "cub/err.h"

/* rgba is w*h*4 bytes, top row first. */
cub_err cub_png_write(const char *path, const uint8_t *rgba, int w, int h);
/* Reads any PNG as RGBA8; *out is malloc'ed (free with free()). */
cub_err cub_png_read(const char *path, uint8_t **out, int *w, int *h);

/* An RGBA canvas, w*h*4 bytes, top row first; drawing clips at its edges. */
typedef struct cub_png_canvas {
    uint8_t *px;
    int w, h;
} cub_png_canvas;

/* A filled disc of radius r (0: one pixel) at (x, y). */
void cub_png_dot(cub_png_canvas *c, int x, int y, int r, const uint8_t rgb[3]);
/* A line from (xy[0], xy[1]) to (xy[2], xy[3]), r pixels thick each side. */
void cub_png_line(cub_png_canvas *c, const double xy[4], int r, const uint8_t rgb[3]);
/* Text in a 5x7 pixel font scaled by scale (>= 1), top-left at (x, y):
 * digits, A-Z (lower case drawn as upper), space and + - = : . , / ( ) %.
 * Other characters draw as a box. Returns the width drawn, pixels. */
int cub_png_text(cub_png_canvas *c, int x, int y, int scale, const char *s, const uint8_t rgb[3]);

#endif

/* png — write and read 8-bit RGBA PNG files (libpng), for headless frames,
 * contact sheets and golden-image tests. */
#ifndef CUB_PNG_H
#define CUB_PNG_H

#include <stddef.h>
#include <stdint.h>

#include "cub/err.h"

/* rgba is w*h*4 bytes, top row first. */
cub_err cub_png_write(const char *path, const uint8_t *rgba, int w, int h);
/* Reads any PNG as RGBA8; *out is malloc'ed (free with free()). */
cub_err cub_png_read(const char *path, uint8_t **out, int *w, int *h);

#endif

/* png — RGBA8 PNG files through libpng's simplified API (png_image), which
 * converts any colour type and bit depth to RGBA8 on read. Failures print
 * one line to stderr naming the file and libpng's message, since the header
 * has no diagnostic struct. */
#include "cub/png.h"

#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Largest side we accept: keeps w*h*4 far from size_t overflow on any
 * target and refuses absurd headers before allocating. */
#define CUB_PNG_MAX_SIDE 16384

cub_err cub_png_write(const char *path, const uint8_t *rgba, int w, int h)
{
    if (!path || !rgba || w <= 0 || h <= 0 || w > CUB_PNG_MAX_SIDE || h > CUB_PNG_MAX_SIDE) {
        fprintf(stderr, "png: write %s: bad arguments (%dx%d)\n", path ? path : "(null)", w, h);
        return CUB_ERR_ARG;
    }
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    img.width = (png_uint_32)w;
    img.height = (png_uint_32)h;
    img.format = PNG_FORMAT_RGBA;
    /* Positive row stride = top row first, as our buffers are laid out. */
    if (!png_image_write_to_file(&img, path, 0, rgba, (png_int_32)(w * 4), NULL)) {
        fprintf(stderr, "png: write %s: %s\n", path, img.message);
        png_image_free(&img);
        return CUB_ERR_IO;
    }
    return CUB_OK;
}

/* libpng reports a missing file and a corrupt one the same way; tell them
 * apart so the caller's error code means something. */
static cub_err classify_open_failure(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return CUB_ERR_IO;
    fclose(f);
    return CUB_ERR_FORMAT;
}

cub_err cub_png_read(const char *path, uint8_t **out, int *w, int *h)
{
    if (!path || !out || !w || !h) {
        fprintf(stderr, "png: read: NULL argument\n");
        return CUB_ERR_ARG;
    }
    *out = NULL;
    *w = *h = 0;
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&img, path)) {
        fprintf(stderr, "png: read %s: %s\n", path, img.message);
        return classify_open_failure(path);
    }
    if (img.width == 0 || img.height == 0 || img.width > CUB_PNG_MAX_SIDE ||
        img.height > CUB_PNG_MAX_SIDE) {
        fprintf(stderr, "png: read %s: unsupported size %ux%u (max side %d)\n", path,
                (unsigned)img.width, (unsigned)img.height, CUB_PNG_MAX_SIDE);
        png_image_free(&img);
        return CUB_ERR_UNSUPPORTED;
    }
    img.format = PNG_FORMAT_RGBA;
    size_t size = (size_t)img.width * img.height * 4;
    uint8_t *buf = malloc(size);
    if (!buf) {
        fprintf(stderr, "png: read %s: out of memory for %zu bytes\n", path, size);
        png_image_free(&img);
        return CUB_ERR_NOMEM;
    }
    if (!png_image_finish_read(&img, NULL, buf, (png_int_32)(img.width * 4), NULL)) {
        fprintf(stderr, "png: read %s: %s\n", path, img.message);
        png_image_free(&img);
        free(buf);
        return CUB_ERR_FORMAT;
    }
    *out = buf;
    *w = (int)img.width;
    *h = (int)img.height;
    return CUB_OK;
}

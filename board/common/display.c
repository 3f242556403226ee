/* display — the backend-independent half of display.h: dispatch to the
 * backend that opened the display, and the GLES2 read-back both share. */
#include <GLES2/gl2.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "display_backend.h"

void cub_display_close(cub_display *d)
{
    if (d)
        d->ops->close(d);
}

int cub_display_is_headless(const cub_display *d)
{
    return d ? d->headless : 0;
}

void cub_display_size(const cub_display *d, int *w, int *h)
{
    if (w)
        *w = d ? d->w : 0;
    if (h)
        *h = d ? d->h : 0;
}

void cub_display_swap(cub_display *d)
{
    if (d)
        d->ops->swap(d);
}

const char *cub_display_lost(const cub_display *d)
{
    return d && d->lost[0] ? d->lost : NULL;
}

cub_err cub_display_read_rgba(cub_display *d, uint8_t *rgba, size_t size)
{
    if (!d || !rgba)
        return CUB_ERR_ARG;
    return cub_display_gl_read_rgba(d->w, d->h, rgba, size);
}

cub_err cub_display_gl_read_rgba(int w, int h, uint8_t *rgba, size_t size)
{
    if (w <= 0 || h <= 0 || size < (size_t)w * (size_t)h * 4)
        return CUB_ERR_NOMEM;
    /* Rows of w*4 bytes are always 4-aligned; set it anyway so a caller's
     * earlier glPixelStorei cannot skew the rows. */
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) {
        fprintf(stderr, "display: glReadPixels %dx%d failed: GL error 0x%04x\n", w, h, e);
        return CUB_ERR_DEVICE;
    }
    /* GL's origin is the bottom-left corner; ours is the top row. */
    size_t row = (size_t)w * 4;
    uint8_t tmp[4096];
    for (int y = 0; y < h / 2; y++) {
        uint8_t *a = rgba + (size_t)y * row;
        uint8_t *b = rgba + (size_t)(h - 1 - y) * row;
        for (size_t off = 0; off < row; off += sizeof tmp) {
            size_t n = row - off < sizeof tmp ? row - off : sizeof tmp;
            memcpy(tmp, a + off, n);
            memcpy(a + off, b + off, n);
            memcpy(b + off, tmp, n);
        }
    }
    return CUB_OK;
}

void cub_display_fail(char *err, size_t err_size, const char *fmt, ...)
{
    if (!err || err_size == 0)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, err_size, fmt, ap);
    va_end(ap);
}

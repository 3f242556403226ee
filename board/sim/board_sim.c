/* board_sim — the PC board: libfreenect (live or fakenect replay), an SDL2
 * window or headless EGL, the keyboard or a scripted timeline for buttons,
 * SDL audio. Everything but open/close lives in board/common. */
#include "board_impl.h"

#include <stdio.h>

static cub_err open_display(cub_board *b, char *err, size_t err_size)
{
    const cub_board_desc *d = &b->desc;
    switch (d->display) {
    case CUB_DISPLAY_NONE:
        return CUB_OK;
    case CUB_DISPLAY_HEADLESS:
        return cub_display_open_headless(d->width, d->height, &b->display, err, err_size);
    case CUB_DISPLAY_WINDOW:
        return cub_display_open_window(d->width, d->height, NULL, &b->display, err, err_size);
    case CUB_DISPLAY_AUTO:
        if (cub_display_window_available() &&
            cub_display_open_window(d->width, d->height, NULL, &b->display, err, err_size) ==
                CUB_OK) {
            return CUB_OK;
        }
        return cub_display_open_headless(d->width, d->height, &b->display, err, err_size);
    }
    snprintf(err, err_size, "board: unknown display mode %d", (int)d->display);
    return CUB_ERR_ARG;
}

cub_err cub_board_open(const cub_board_desc *desc, cub_board **out, char *err_msg, size_t err_size)
{
    char local[512];
    if (!err_msg || err_size == 0) {
        err_msg = local;
        err_size = sizeof local;
    }
    err_msg[0] = '\0';
    if (!out) {
        snprintf(err_msg, err_size, "board: no place for the board (out is NULL)");
        return CUB_ERR_ARG;
    }
    *out = NULL;
    cub_board *b = NULL;
    cub_err e = cub_board_common_open(desc, &b, err_msg, err_size);
    if (e) {
        return e;
    }
    /* Buttons: the script (in common) if given, else the keyboard of the
     * window (keys_sdl, polled by common); no window and no script means no
     * buttons at all. */
    e = open_display(b, err_msg, err_size);
    if (!e) {
        e = cub_board_common_start(b, err_msg, err_size);
    }
    if (e) {
        cub_board_common_close(b);
        return e;
    }
    *out = b;
    return CUB_OK;
}

void cub_board_close(cub_board *board)
{
    cub_board_common_close(board);
}

const char *cub_board_name(void)
{
    return "sim";
}

/* board_pi — the box: libfreenect (live Kinect), START/STOP on GPIO lines
 * (libgpiod), an SDL2 window full screen through KMSDRM on HDMI (or headless
 * EGL if that fails), SDL audio on ALSA. A button script, if given, replaces
 * the GPIO buttons (replays on the box, tests). Everything but open/close
 * lives in board/common. */
#include "board_impl.h"
#include "gpio.h"

#include <stdio.h>
#include <stdlib.h>

/* With no display server the box draws straight to HDMI through KMSDRM. */
static const char *video_driver(void)
{
    return getenv("DISPLAY") || getenv("WAYLAND_DISPLAY") ? NULL : "KMSDRM";
}

static cub_err open_display(cub_board *b, char *err, size_t err_size)
{
    const cub_board_desc *d = &b->desc;
    switch (d->display) {
    case CUB_DISPLAY_NONE:
        return CUB_OK;
    case CUB_DISPLAY_HEADLESS:
        return cub_display_open_headless(d->width, d->height, &b->display, err, err_size);
    case CUB_DISPLAY_WINDOW:
        return cub_display_open_window(d->width, d->height, video_driver(), &b->display, err,
                                       err_size);
    case CUB_DISPLAY_AUTO:
        if (cub_display_open_window(d->width, d->height, video_driver(), &b->display, err,
                                    err_size) == CUB_OK) {
            return CUB_OK;
        }
        fprintf(stderr, "cubdance: %s (drawing headless instead)\n", err);
        return cub_display_open_headless(d->width, d->height, &b->display, err, err_size);
    }
    snprintf(err, err_size, "board: unknown display mode %d", (int)d->display);
    return CUB_ERR_ARG;
}

static void poll_gpio(void *buttons, cub_loop *loop, int64_t now_us)
{
    cub_gpio_buttons_poll(buttons, loop, now_us);
}

static void close_gpio(void *buttons)
{
    cub_gpio_buttons_close(buttons);
}

/* gpio_config NULL: the built-in defaults (the same as cubdance.conf). */
static cub_err open_gpio(cub_board *b, const char *gpio_config, char *err, size_t err_size)
{
    cub_gpio_config cfg;
    cub_gpio_config_defaults(&cfg);
    if (gpio_config) {
        cub_err e = cub_gpio_config_load(gpio_config, &cfg, err, err_size);
        if (e) {
            return e;
        }
    }
    cub_gpio_buttons *g;
    cub_err e = cub_gpio_buttons_open(&cfg, &cub_gpio_libgpiod, cub_board_now_us(b), &g, err,
                                      err_size);
    if (e) {
        return e;
    }
    b->buttons = g;
    b->poll_buttons = poll_gpio;
    b->close_buttons = close_gpio;
    return CUB_OK;
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
    if (!e) {
        e = open_display(b, err_msg, err_size);
    }
    if (!e) {
        e = cub_board_common_start(b, err_msg, err_size);
    }
    /* GPIO last: its debouncer starts from the board's clock. */
    if (!e && !b->script) {
        e = open_gpio(b, desc ? desc->gpio_config : NULL, err_msg, err_size);
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
    return "pi";
}

/* board_pi — the box: libfreenect (live Kinect), START/STOP on GPIO lines
 * (libgpiod), an SDL2 window full screen through KMSDRM on HDMI (no display:
 * an error; --headless asks for EGL off-screen), SDL audio on ALSA. A button script, if given, replaces
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

static void poll_gpio(void *buttons, cub_loop *loop, int64_t now_us)
{
    cub_gpio_buttons_poll(buttons, loop, now_us);
}

static void close_gpio(void *buttons)
{
    cub_gpio_buttons_close(buttons);
}

static void set_ready(void *buttons, int ready)
{
    cub_gpio_buttons_set_ready(buttons, ready);
}

/* The GPIO buttons and LED from desc->gpio (the config file's GPIO keys);
 * none: the built-in defaults (the same as cubdance.conf). */
static cub_err open_gpio(cub_board *b, const cub_board_desc *desc, char *err, size_t err_size)
{
    cub_gpio_config cfg;
    cub_gpio_config_defaults(&cfg);
    if (desc && desc->gpio) {
        cfg = *desc->gpio;
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
    b->set_ready = set_ready;
    return CUB_OK;
}

cub_err cub_board_open(const cub_board_desc *desc, cub_board **out, char *err_msg, size_t err_size)
{
    /* The window goes full screen on HDMI; if that fails the program ends
     * with the reason (systemd tries again), rather than draw unseen. */
    const cub_board_kind pi_kind = {
        .video_driver = video_driver(), .window_required = 1,
        .no_display_hint = "is the TV on and its HDMI cable in? - ", .open_buttons = open_gpio};
    return cub_board_open_kind(&pi_kind, desc, out, err_msg, err_size);
}

void cub_board_close(cub_board *board)
{
    cub_board_common_close(board);
}

const char *cub_board_name(void)
{
    return "pi";
}

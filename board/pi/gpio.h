/* gpio — the box's START and STOP buttons on GPIO lines (board/pi only).
 *
 * Lines are found by NAME (e.g. "GPIO17" on a Raspberry Pi's gpiochip0),
 * as given in the box's config file (cub/boxconf.h, cubdance.conf beside
 * this file):
 *
 *     chip=gpiochip0     start_line=GPIO17     stop_line=GPIO27
 *     active_low=1       debounce_ms=30        led_line=GPIO22
 *
 * Lines are requested as inputs with a pull-up (active_low=1: the button
 * shorts the line to ground) or a pull-down, read every tick and debounced
 * in software: a new level must hold debounce_ms before its edge is posted.
 * An optional LED line is an output, lit while the box is ready.
 *
 * GPIO access goes through cub_gpio_ops so the debounce and config logic can
 * be tested on machines with no GPIO kernel support (tests/board uses a fake
 * chip); cub_gpio_libgpiod is the real one (libgpiod v1). */
#ifndef CUB_BOARD_PI_GPIO_H
#define CUB_BOARD_PI_GPIO_H

#include <stddef.h>
#include <stdint.h>

#include "cub/boxconf.h"
#include "cub/err.h"
#include "cub/loop.h"

/* ---- the seam ---------------------------------------------------------- */

typedef enum cub_gpio_bias {
    CUB_GPIO_BIAS_NONE,
    CUB_GPIO_BIAS_PULL_UP,
    CUB_GPIO_BIAS_PULL_DOWN
} cub_gpio_bias;

typedef struct cub_gpio_ops {
    void *ctx; /* passed to every call */
    void *(*open_chip)(void *ctx, const char *chip_name);             /* NULL on failure */
    void *(*find_line)(void *ctx, void *chip, const char *line_name); /* NULL if absent */
    /* < 0 if the line cannot be taken as an input */
    int (*request_input)(void *ctx, void *line, const char *consumer, cub_gpio_bias bias);
    int (*get_value)(void *ctx, void *line); /* 0, 1, or < 0 on error */
    /* < 0 if the line cannot be taken as an output; it starts at value */
    int (*request_output)(void *ctx, void *line, const char *consumer, int value);
    int (*set_value)(void *ctx, void *line, int value); /* < 0 on error */
    void (*release)(void *ctx, void *line);
    void (*close_chip)(void *ctx, void *chip);
} cub_gpio_ops;

/* libgpiod v1 (gpiod_chip_open_by_name, gpiod_chip_find_line, ...). */
extern const cub_gpio_ops cub_gpio_libgpiod;

/* ---- the config ------------------------------------------------------- */

/* The GPIO section of the box's config file (cub/boxconf.h parses it). */
typedef cub_boxconf_gpio cub_gpio_config;

/* The built-in GPIO settings (those of cub_boxconf_defaults). */
void cub_gpio_config_defaults(cub_gpio_config *cfg);

/* ---- debounced buttons ------------------------------------------------- */

typedef struct cub_gpio_buttons cub_gpio_buttons;

/* Open the chip, find and request both lines. The level read now counts as
 * settled (a button held at start gives no edge). CUB_ERR_DEVICE with a
 * message naming the config file and line on failure. ops is kept. */
cub_err cub_gpio_buttons_open(const cub_gpio_config *cfg, const cub_gpio_ops *ops, int64_t now_us,
                              cub_gpio_buttons **out, char *err, size_t err_size);
void cub_gpio_buttons_close(cub_gpio_buttons *b);
/* Read the lines at now_us; writes the edges that became settled (at most
 * one per button) into out and returns how many. Edge t_us = when the new
 * level was first seen. */
int cub_gpio_buttons_update(cub_gpio_buttons *b, int64_t now_us, cub_event out[CUB_BUTTON_COUNT]);
/* cub_gpio_buttons_update, posting the edges to the loop. */
void cub_gpio_buttons_poll(cub_gpio_buttons *b, cub_loop *loop, int64_t now_us);
/* Light the ready LED (ready = 1) or put it out; nothing without an LED.
 * Close puts it out before releasing the line. */
void cub_gpio_buttons_set_ready(cub_gpio_buttons *b, int ready);

#endif

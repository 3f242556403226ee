/* buttons_gpiod — START/STOP on GPIO lines, debounced in software, through
 * the cub_gpio_ops seam; cub_gpio_libgpiod at the bottom is the real access
 * (libgpiod v1). */
#include "gpio.h"

#include <gpiod.h>
#include <stdio.h>
#include <stdlib.h>

#define CONSUMER "cubdance"

void cub_gpio_config_defaults(cub_gpio_config *cfg)
{
    cub_boxconf c;
    cub_boxconf_defaults(&c);
    *cfg = c.gpio;
}

/* A button's settled state and the change waiting to settle. */
typedef struct debouncer {
    int pressed;       /* settled */
    int pending;       /* a different level has been seen ... */
    int64_t since_us;  /* ... since this time */
} debouncer;

struct cub_gpio_buttons {
    cub_gpio_ops ops;
    void *chip;
    void *line[CUB_BUTTON_COUNT];
    void *led;          /* the ready LED's line, or NULL */
    int led_active_low;
    int active_low;
    int64_t hold_us;
    debouncer deb[CUB_BUTTON_COUNT];
};

static int read_pressed(const cub_gpio_buttons *b, int i, int *pressed)
{
    int v = b->ops.get_value(b->ops.ctx, b->line[i]);
    if (v < 0) {
        return 0;
    }
    *pressed = b->active_low ? v == 0 : v != 0;
    return 1;
}

static const char *const line_keys[CUB_BOXCONF_LINES] = {"start_line", "stop_line", "led_line"};

/* "file:line" of the key naming line i, or just the file for a default. */
static void where_of(const cub_gpio_config *cfg, int i, char *where, size_t size)
{
    if (cfg->line_at[i] > 0) {
        snprintf(where, size, "%s:%d", cfg->file, cfg->line_at[i]);
    } else {
        snprintf(where, size, "%s", cfg->file);
    }
}

static void *find_line(cub_gpio_buttons *b, const cub_gpio_config *cfg, int i, char *err,
                       size_t err_size)
{
    char where[300];
    void *line = b->ops.find_line(b->ops.ctx, b->chip, cfg->line[i]);
    if (!line) {
        where_of(cfg, i, where, sizeof where);
        snprintf(err, err_size, "%s: %s: no GPIO line named \"%s\" on %s", where, line_keys[i],
                 cfg->line[i], cfg->chip);
    }
    return line;
}

/* The LED starts dark: the app lights it when it waits for START. */
static cub_err open_led(cub_gpio_buttons *b, const cub_gpio_config *cfg, char *err,
                        size_t err_size)
{
    if (!cfg->line[CUB_BOXCONF_LINE_LED][0]) {
        return CUB_OK;
    }
    void *line = find_line(b, cfg, CUB_BOXCONF_LINE_LED, err, err_size);
    if (!line) {
        return CUB_ERR_DEVICE;
    }
    b->led_active_low = cfg->led_active_low;
    if (b->ops.request_output(b->ops.ctx, line, CONSUMER, b->led_active_low) < 0) {
        char where[300];
        where_of(cfg, CUB_BOXCONF_LINE_LED, where, sizeof where);
        snprintf(err, err_size, "%s: led_line: cannot take GPIO line \"%s\" on %s as an output "
                 "(in use by another program?)",
                 where, cfg->line[CUB_BOXCONF_LINE_LED], cfg->chip);
        return CUB_ERR_DEVICE;
    }
    b->led = line;
    return CUB_OK;
}

static cub_err open_line(cub_gpio_buttons *b, const cub_gpio_config *cfg, int i, char *err,
                         size_t err_size)
{
    const char *key = line_keys[i];
    const char *name = cfg->line[i];
    char where[300];
    where_of(cfg, i, where, sizeof where);
    void *line = find_line(b, cfg, i, err, err_size);
    if (!line) {
        return CUB_ERR_DEVICE;
    }
    cub_gpio_bias bias = cfg->active_low ? CUB_GPIO_BIAS_PULL_UP : CUB_GPIO_BIAS_PULL_DOWN;
    if (b->ops.request_input(b->ops.ctx, line, CONSUMER, bias) < 0) {
        snprintf(err, err_size, "%s: %s: cannot take GPIO line \"%s\" on %s as an input "
                 "(in use by another program?)",
                 where, key, name, cfg->chip);
        return CUB_ERR_DEVICE;
    }
    b->line[i] = line;
    return CUB_OK;
}

cub_err cub_gpio_buttons_open(const cub_gpio_config *cfg, const cub_gpio_ops *ops, int64_t now_us,
                              cub_gpio_buttons **out, char *err, size_t err_size)
{
    if (!cfg || !ops || !out || !err || err_size == 0) {
        return CUB_ERR_ARG;
    }
    *out = NULL;
    cub_gpio_buttons *b = calloc(1, sizeof *b);
    if (!b) {
        snprintf(err, err_size, "gpio: out of memory");
        return CUB_ERR_NOMEM;
    }
    b->ops = *ops;
    b->active_low = cfg->active_low;
    b->hold_us = (int64_t)cfg->debounce_ms * 1000;
    b->chip = b->ops.open_chip(b->ops.ctx, cfg->chip);
    if (!b->chip) {
        snprintf(err, err_size, "%s: cannot open GPIO chip \"%s\" (does /dev/%s exist? may this "
                 "user open it? see 55-cubdance.rules)",
                 cfg->file, cfg->chip, cfg->chip);
        cub_gpio_buttons_close(b);
        return CUB_ERR_DEVICE;
    }
    for (int i = 0; i < CUB_BUTTON_COUNT; i++) {
        cub_err e = open_line(b, cfg, i, err, err_size);
        if (e) {
            cub_gpio_buttons_close(b);
            return e;
        }
        /* Whatever the line reads now is settled: no edge for a button
         * already held when the program starts. */
        int pressed = 0;
        (void)read_pressed(b, i, &pressed);
        b->deb[i] = (debouncer){pressed, 0, now_us};
    }
    cub_err e = open_led(b, cfg, err, err_size);
    if (e) {
        cub_gpio_buttons_close(b);
        return e;
    }
    *out = b;
    return CUB_OK;
}

void cub_gpio_buttons_close(cub_gpio_buttons *b)
{
    if (!b) {
        return;
    }
    /* A released output may keep its level: put the LED out first, so a
     * box whose program ended does not claim to be ready. */
    if (b->led) {
        cub_gpio_buttons_set_ready(b, 0);
        b->ops.release(b->ops.ctx, b->led);
    }
    for (int i = 0; i < CUB_BUTTON_COUNT; i++) {
        if (b->line[i]) {
            b->ops.release(b->ops.ctx, b->line[i]);
        }
    }
    if (b->chip) {
        b->ops.close_chip(b->ops.ctx, b->chip);
    }
    free(b);
}

/* 1 when a new level has held for hold_us: the settled state flips. */
static int debounce(debouncer *d, int pressed, int64_t now_us, int64_t hold_us)
{
    if (pressed == d->pressed) {
        d->pending = 0; /* a bounce: back to the settled level before it held */
        return 0;
    }
    if (!d->pending) {
        d->pending = 1;
        d->since_us = now_us;
    }
    if (now_us - d->since_us < hold_us) {
        return 0;
    }
    d->pressed = pressed;
    d->pending = 0;
    return 1;
}

int cub_gpio_buttons_update(cub_gpio_buttons *b, int64_t now_us, cub_event out[CUB_BUTTON_COUNT])
{
    int n = 0;
    for (int i = 0; i < CUB_BUTTON_COUNT; i++) {
        int pressed;
        if (!read_pressed(b, i, &pressed)) {
            continue; /* a failed read changes nothing */
        }
        debouncer *d = &b->deb[i];
        if (debounce(d, pressed, now_us, b->hold_us)) {
            out[n++] = (cub_event){
                .t_us = d->since_us,
                .type = d->pressed ? CUB_EV_BUTTON_DOWN : CUB_EV_BUTTON_UP,
                .a = i,
            };
        }
    }
    return n;
}

void cub_gpio_buttons_poll(cub_gpio_buttons *b, cub_loop *loop, int64_t now_us)
{
    cub_event ev[CUB_BUTTON_COUNT];
    int n = cub_gpio_buttons_update(b, now_us, ev);
    for (int i = 0; i < n; i++) {
        (void)cub_loop_post(loop, &ev[i]); /* a full queue drops it; the loop counts drops */
    }
}

void cub_gpio_buttons_set_ready(cub_gpio_buttons *b, int ready)
{
    if (b && b->led) {
        /* A failed write leaves the LED as it was; the buttons still work. */
        (void)b->ops.set_value(b->ops.ctx, b->led, ready ? !b->led_active_low : b->led_active_low);
    }
}

/* ---- libgpiod v1 ------------------------------------------------------- */

static void *lg_open_chip(void *ctx, const char *name)
{
    return name[0] == '/' ? gpiod_chip_open(name) : gpiod_chip_open_by_name(name);
}

static void *lg_find_line(void *ctx, void *chip, const char *name)
{
    return gpiod_chip_find_line(chip, name);
}

static int lg_request_input(void *ctx, void *line, const char *consumer, cub_gpio_bias bias)
{
    int flags = bias == CUB_GPIO_BIAS_PULL_UP     ? GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP
                : bias == CUB_GPIO_BIAS_PULL_DOWN ? GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_DOWN
                                                  : 0;
    if (gpiod_line_request_input_flags(line, consumer, flags) == 0) {
        return 0;
    }
    /* Kernels before 5.5 cannot set bias: fall back to the board's own
     * pull resistors (a Pi's GPIO17/27 default to pull-down, so wire an
     * external pull-up for active-low buttons on such kernels). */
    return flags ? gpiod_line_request_input(line, consumer) : -1;
}

static int lg_get_value(void *ctx, void *line)
{
    return gpiod_line_get_value(line);
}

static int lg_request_output(void *ctx, void *line, const char *consumer, int value)
{
    return gpiod_line_request_output(line, consumer, value);
}

static int lg_set_value(void *ctx, void *line, int value)
{
    return gpiod_line_set_value(line, value);
}

static void lg_release(void *ctx, void *line)
{
    gpiod_line_release(line);
}

static void lg_close_chip(void *ctx, void *chip)
{
    gpiod_chip_close(chip);
}

const cub_gpio_ops cub_gpio_libgpiod = {
    .ctx = NULL,
    .open_chip = lg_open_chip,
    .find_line = lg_find_line,
    .request_input = lg_request_input,
    .get_value = lg_get_value,
    .request_output = lg_request_output,
    .set_value = lg_set_value,
    .release = lg_release,
    .close_chip = lg_close_chip,
};

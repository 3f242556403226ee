/* gpio_config — the pi's button config file: key=value lines. */
#include "gpio.h"
#include "text_file.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_LINE 256
#define MAX_BYTES (64 * 1024)

typedef struct parser {
    cub_gpio_config *cfg;
    int line;
    int seen[5]; /* per key: line it was set on, to refuse repeats */
    char *err;
    size_t err_size;
} parser;

static const char *const keys[5] = {"chip", "start_line", "stop_line", "active_low", "debounce_ms"};

void cub_gpio_config_defaults(cub_gpio_config *cfg)
{
    memset(cfg, 0, sizeof *cfg);
    snprintf(cfg->file, sizeof cfg->file, "(built-in GPIO defaults)");
    snprintf(cfg->chip, sizeof cfg->chip, "gpiochip0");
    snprintf(cfg->line[CUB_BUTTON_START], CUB_GPIO_NAME_MAX, "GPIO17");
    snprintf(cfg->line[CUB_BUTTON_STOP], CUB_GPIO_NAME_MAX, "GPIO27");
    cfg->active_low = 1;
    cfg->debounce_ms = 30;
}

static cub_err fail(const parser *p, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    cub_err e = cub_board_vfail_at(p->err, p->err_size, p->cfg->file, p->line, fmt, ap);
    va_end(ap);
    return e;
}

static int parse_int(const char *s, int lo, int hi, int *out)
{
    long v = 0;
    if (!*s) {
        return 0;
    }
    for (; *s; s++) {
        if (*s < '0' || *s > '9' || (v = v * 10 + (*s - '0')) > hi) {
            return 0;
        }
    }
    if (v < lo) {
        return 0;
    }
    *out = (int)v;
    return 1;
}

static char *trim(char *s)
{
    s += strspn(s, " \t");
    size_t n = strlen(s);
    while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t')) {
        s[--n] = '\0';
    }
    return s;
}

static cub_err set_name(parser *p, char *dst, const char *key, const char *value)
{
    if (strlen(value) >= CUB_GPIO_NAME_MAX || strpbrk(value, " \t")) {
        return fail(p, "%s: \"%s\" is not a GPIO name (no blanks, < %d chars)", key, value,
                    CUB_GPIO_NAME_MAX);
    }
    memcpy(dst, value, strlen(value) + 1);
    return CUB_OK;
}

static cub_err set_key(parser *p, int k, const char *value)
{
    cub_gpio_config *cfg = p->cfg;
    switch (k) {
    case 0:
        return set_name(p, cfg->chip, keys[k], value);
    case 1:
    case 2: {
        int b = k == 1 ? CUB_BUTTON_START : CUB_BUTTON_STOP;
        cfg->line_at[b] = p->line;
        return set_name(p, cfg->line[b], keys[k], value);
    }
    case 3:
        return parse_int(value, 0, 1, &cfg->active_low)
                   ? CUB_OK
                   : fail(p, "active_low: \"%s\" is not 0 or 1", value);
    default:
        return parse_int(value, 0, 1000, &cfg->debounce_ms)
                   ? CUB_OK
                   : fail(p, "debounce_ms: \"%s\" is not a whole number of ms in 0..1000", value);
    }
}

static cub_err parse_line(parser *p, char *text)
{
    char *eq = strchr(text, '=');
    if (!eq) {
        return fail(p, "expected key=value, got \"%s\"", text);
    }
    *eq = '\0';
    char *key = trim(text), *value = trim(eq + 1);
    for (int k = 0; k < 5; k++) {
        if (strcmp(key, keys[k]) == 0) {
            if (p->seen[k]) {
                return fail(p, "%s set again (first set on line %d)", key, p->seen[k]);
            }
            p->seen[k] = p->line;
            if (!*value) {
                return fail(p, "%s has no value", key);
            }
            return set_key(p, k, value);
        }
    }
    return fail(p, "unknown key \"%s\" (known: chip, start_line, stop_line, active_low, "
                   "debounce_ms)",
                key);
}

static cub_err check(parser *p)
{
    cub_gpio_config *cfg = p->cfg;
    if (strcmp(cfg->line[CUB_BUTTON_START], cfg->line[CUB_BUTTON_STOP]) == 0) {
        p->line = cfg->line_at[CUB_BUTTON_STOP] ? cfg->line_at[CUB_BUTTON_STOP]
                                                : cfg->line_at[CUB_BUTTON_START];
        return fail(p, "start_line and stop_line both name %s", cfg->line[CUB_BUTTON_START]);
    }
    return CUB_OK;
}

cub_err cub_gpio_config_parse(const char *text, size_t len, const char *file, cub_gpio_config *cfg,
                              char *err, size_t err_size)
{
    if (!cfg || !err || err_size == 0 || (!text && len)) {
        return CUB_ERR_ARG;
    }
    err[0] = '\0';
    cub_gpio_config_defaults(cfg);
    snprintf(cfg->file, sizeof cfg->file, "%s", file ? file : "(gpio config)");
    parser p = {.cfg = cfg, .line = 1, .err = err, .err_size = err_size};
    const char *end = text + len;
    for (const char *c = text; c < end; p.line++) {
        const char *nl = memchr(c, '\n', (size_t)(end - c));
        size_t n = (size_t)((nl ? nl : end) - c);
        if (memchr(c, '\0', n)) {
            return fail(&p, "contains a NUL byte (not a text file?)");
        }
        /* A comment may be as long as it likes: measure only what precedes it. */
        const char *hash = memchr(c, '#', n);
        size_t used = hash ? (size_t)(hash - c) : n;
        char buf[MAX_LINE];
        if (used >= MAX_LINE) {
            return fail(&p, "line longer than %d characters", MAX_LINE - 1);
        }
        memcpy(buf, c, used);
        buf[used] = '\0';
        buf[strcspn(buf, "\r")] = '\0';
        char *line = trim(buf);
        if (*line) {
            cub_err e = parse_line(&p, line);
            if (e) {
                return e;
            }
        }
        c = nl ? nl + 1 : end; /* never point past the end */
    }
    return check(&p);
}

cub_err cub_gpio_config_load(const char *path, cub_gpio_config *cfg, char *err, size_t err_size)
{
    if (!path || !cfg || !err || err_size == 0) {
        return CUB_ERR_ARG;
    }
    char *text;
    size_t len;
    cub_err e = cub_board_read_text(path, "GPIO config", MAX_BYTES, &text, &len, err, err_size);
    if (!e) {
        e = cub_gpio_config_parse(text, len, path, cfg, err, err_size);
    }
    free(text);
    return e;
}

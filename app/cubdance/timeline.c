#include "timeline.h"

#include "cub/io.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_BYTES (1024 * 1024)
#define MAX_LINE 256
#define MAX_SECONDS 86400.0

struct cub_timeline {
    cub_event *events;
    int count, next;
};

typedef struct what {
    const char *word;
    int32_t type, a, b;
} what;

static const what whats[] = {
    {"wrong", CUB_EV_VERDICT, -1, 0}, {"right", CUB_EV_VERDICT, -1, 1},
    {"nobody", CUB_EV_PLAYER, 0, 0},  {"player", CUB_EV_PLAYER, 1, 0},
    {"clap", CUB_EV_CLAP, 0, 0},
};

static cub_err fail(char *err, size_t size, const char *name, int line, const char *fmt, ...)
{
    char msg[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    snprintf(err, size, "%s:%d: %s", name, line, msg);
    return CUB_ERR_FORMAT;
}

/* One non-empty line "<seconds> <what>" into *ev. */
static cub_err parse_line(char *s, const char *name, int line, double *prev_s, cub_event *ev,
                          char *err, size_t size)
{
    char *end;
    errno = 0;
    double t = strtod(s, &end);
    if (end == s || errno || !isspace((unsigned char)*end))
        return fail(err, size, name, line, "expected `<seconds> <what>`, got \"%s\"", s);
    if (!(t >= 0 && t <= MAX_SECONDS))
        return fail(err, size, name, line, "time %g s is not in [0, %g]", t, MAX_SECONDS);
    if (t < *prev_s)
        return fail(err, size, name, line, "time %g s comes before the line above (%g s)", t,
                    *prev_s);
    while (isspace((unsigned char)*end)) end++;
    char *word = end;
    while (*end && !isspace((unsigned char)*end)) end++;
    char *rest = end;
    while (isspace((unsigned char)*rest)) rest++;
    *end = '\0';
    if (*rest) return fail(err, size, name, line, "unexpected \"%s\" after \"%s\"", rest, word);
    for (size_t i = 0; i < sizeof whats / sizeof *whats; i++) {
        if (strcmp(word, whats[i].word) != 0) continue;
        *ev = (cub_event){.t_us = (int64_t)llround(t * 1e6), .type = whats[i].type,
                          .a = whats[i].a, .b = whats[i].b};
        *prev_s = t;
        return CUB_OK;
    }
    return fail(err, size, name, line,
                "unknown event \"%s\" (want wrong, right, nobody, player or clap)", word);
}

static cub_err parse_all(cub_timeline *t, const char *text, size_t len, const char *name,
                         char *err, size_t size)
{
    double prev_s = 0;
    int line = 1, cap = 0;
    const char *end = text + len;
    for (const char *c = text; c < end; line++) {
        const char *nl = memchr(c, '\n', (size_t)(end - c));
        size_t n = (size_t)((nl ? nl : end) - c);
        if (memchr(c, '\0', n)) return fail(err, size, name, line, "contains a NUL byte");
        const char *hash = memchr(c, '#', n);
        size_t used = hash ? (size_t)(hash - c) : n;
        if (used >= MAX_LINE)
            return fail(err, size, name, line, "line longer than %d characters", MAX_LINE - 1);
        char buf[MAX_LINE];
        memcpy(buf, c, used);
        buf[used] = '\0';
        char *s = buf;
        while (isspace((unsigned char)*s)) s++;
        for (char *e = s + strlen(s); e > s && isspace((unsigned char)e[-1]);) *--e = '\0';
        c = nl ? nl + 1 : end;
        if (!*s) continue;
        if (t->count == cap) {
            cap = cap ? cap * 2 : 16;
            cub_event *grown = realloc(t->events, (size_t)cap * sizeof *grown);
            if (!grown) return CUB_ERR_NOMEM;
            t->events = grown;
        }
        cub_err e = parse_line(s, name, line, &prev_s, &t->events[t->count], err, size);
        if (e) return e;
        t->count++;
    }
    return CUB_OK;
}

cub_err cub_timeline_parse(const char *text, size_t len, const char *name, cub_timeline **out,
                           char *err, size_t err_size)
{
    if (!out || (!text && len) || !err || !err_size) return CUB_ERR_ARG;
    *out = NULL;
    err[0] = '\0';
    cub_timeline *t = calloc(1, sizeof *t);
    if (!t) return CUB_ERR_NOMEM;
    cub_err e = parse_all(t, text, len, name ? name : "(timeline)", err, err_size);
    if (e) {
        cub_timeline_free(t);
        return e;
    }
    *out = t;
    return CUB_OK;
}

cub_err cub_timeline_load(const char *path, cub_timeline **out, char *err, size_t err_size)
{
    if (!path || !out || !err || !err_size) return CUB_ERR_ARG;
    char *text = NULL;
    size_t len = 0;
    cub_diag diag;
    cub_err e = cub_io_read_file(path, &text, &len, &diag);
    if (e) {
        cub_diag_str(&diag, err, err_size);
        return e;
    }
    if (len > MAX_BYTES) {
        snprintf(err, err_size, "%s: larger than %d bytes (not a timeline?)", path, MAX_BYTES);
        e = CUB_ERR_FORMAT;
    } else {
        e = cub_timeline_parse(text, len, path, out, err, err_size);
    }
    free(text);
    return e;
}

void cub_timeline_free(cub_timeline *t)
{
    if (!t) return;
    free(t->events);
    free(t);
}

int cub_timeline_count(const cub_timeline *t) { return t ? t->count : 0; }

int cub_timeline_next(cub_timeline *t, int64_t now_us, cub_event *out)
{
    if (!t || t->next >= t->count || t->events[t->next].t_us > now_us) return 0;
    *out = t->events[t->next++];
    return 1;
}

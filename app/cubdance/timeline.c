#include "timeline.h"

#include "cub/text.h"

#include <errno.h>
#include <math.h>
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

/* What the line parser carries from line to line. */
typedef struct parser {
    cub_timeline *t;
    int cap;
    double prev_s; /* times may not decrease */
} parser;

/* "<seconds> <what>" into *ev. */
static cub_err parse_event(parser *p, char **w, int n, const cub_text_at *at, cub_event *ev)
{
    if (n < 2)
        return cub_text_fail(at, "expected `<seconds> <what>`, got only \"%s\"", w[0]);
    if (n > 2) return cub_text_fail(at, "unexpected \"%s\" after \"%s\"", w[2], w[1]);
    char *end;
    errno = 0;
    double t = strtod(w[0], &end);
    if (end == w[0] || errno || *end)
        return cub_text_fail(at, "expected `<seconds> <what>`, got \"%s\" for the seconds", w[0]);
    if (!(t >= 0 && t <= MAX_SECONDS))
        return cub_text_fail(at, "time %g s is not in [0, %g]", t, MAX_SECONDS);
    if (t < p->prev_s)
        return cub_text_fail(at, "time %g s comes before the line above (%g s)", t, p->prev_s);
    for (size_t i = 0; i < sizeof whats / sizeof *whats; i++) {
        if (strcmp(w[1], whats[i].word) != 0) continue;
        *ev = (cub_event){.t_us = (int64_t)llround(t * 1e6), .type = whats[i].type,
                          .a = whats[i].a, .b = whats[i].b};
        p->prev_s = t;
        return CUB_OK;
    }
    return cub_text_fail(at, "unknown event \"%s\" (want wrong, right, nobody, player or clap)",
                         w[1]);
}

static cub_err parse_line(void *ctx, cub_text_line *ln)
{
    parser *p = ctx;
    cub_timeline *t = p->t;
    if (strlen(ln->s) >= MAX_LINE)
        return cub_text_fail(&ln->at, "line longer than %d characters", MAX_LINE - 1);
    if (t->count == p->cap) {
        p->cap = p->cap ? p->cap * 2 : 16;
        cub_event *grown = realloc(t->events, (size_t)p->cap * sizeof *grown);
        if (!grown)
            return cub_diag_fail(ln->at.diag, CUB_ERR_NOMEM, ln->at.name, 0, "out of memory");
        t->events = grown;
    }
    char *w[3];
    cub_err e = parse_event(p, w, cub_text_words(ln->s, w, 3), &ln->at, &t->events[t->count]);
    if (!e) t->count++;
    return e;
}

/* The whole timeline into *out (a cub_timeline **). */
static cub_err parse_text(const cub_text *text, const void *in, void *out)
{
    cub_timeline *t = calloc(1, sizeof *t);
    if (!t) return cub_diag_fail(text->diag, CUB_ERR_NOMEM, text->name, 0, "out of memory");
    parser p = {t, 0, 0};
    cub_err e = cub_text_lines(text, parse_line, &p);
    if (e) {
        cub_timeline_free(t);
        return e;
    }
    *(cub_timeline **)out = t;
    return CUB_OK;
}

cub_err cub_timeline_parse(const char *text, size_t len, const char *name, cub_timeline **out,
                           char *err, size_t err_size)
{
    if (!out || (!text && len) || !err || !err_size) return CUB_ERR_ARG;
    *out = NULL;
    err[0] = '\0';
    cub_diag d = {0};
    cub_text t = {text, len, name ? name : "(timeline)", &d};
    return cub_diag_report(parse_text(&t, NULL, out), &d, err, err_size);
}

cub_err cub_timeline_load(const char *path, cub_timeline **out, char *err, size_t err_size)
{
    if (!path || !out || !err || !err_size) return CUB_ERR_ARG;
    *out = NULL;
    err[0] = '\0';
    cub_diag d = {0};
    cub_text_src src = {path, "timeline", MAX_BYTES};
    return cub_diag_report(cub_text_load(&src, parse_text, NULL, out, &d), &d, err, err_size);
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

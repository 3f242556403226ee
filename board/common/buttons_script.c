/* buttons_script — parse a button timeline and hand out its due edges. */
#include "buttons_script.h"
#include "cub/text.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_LINE 256
#define MAX_SECONDS 1000000 /* ~11 days: keeps t_us far from overflow */

typedef struct edge {
    int64_t t_us;
    int32_t button; /* cub_button */
    int32_t down;   /* 1 = down, 0 = up */
    int line;       /* source line, for errors */
} edge;

struct cub_button_script {
    edge *edges;
    size_t count, cap;
    size_t next; /* first edge not handed out */
};

/* What a line parser carries from line to line. */
typedef struct parser {
    cub_button_script *s;
    int64_t prev_t_us; /* times may not decrease */
} parser;

static cub_err push_edge(cub_button_script *s, int64_t t_us, int button, int down, int line)
{
    if (s->count == s->cap) {
        size_t cap = s->cap ? s->cap * 2 : 32;
        edge *e = realloc(s->edges, cap * sizeof *e);
        if (!e) {
            return CUB_ERR_NOMEM;
        }
        s->edges = e;
        s->cap = cap;
    }
    s->edges[s->count++] = (edge){t_us, button, down, line};
    return CUB_OK;
}

/* Seconds with up to 6 decimals ("1", "1.5", "0.033333") into microseconds,
 * exactly: no float rounding. */
static int parse_seconds(const char *tok, int64_t *t_us)
{
    int64_t whole = 0, frac = 0;
    int frac_digits = 0;
    const char *c = tok;
    if (*c < '0' || *c > '9') {
        return 0;
    }
    for (; *c >= '0' && *c <= '9'; c++) {
        whole = whole * 10 + (*c - '0');
        if (whole > MAX_SECONDS) {
            return 0;
        }
    }
    if (*c == '.') {
        for (c++; *c >= '0' && *c <= '9'; c++) {
            if (++frac_digits > 6) {
                return 0;
            }
            frac = frac * 10 + (*c - '0');
        }
    }
    if (*c != '\0') {
        return 0;
    }
    for (; frac_digits < 6; frac_digits++) {
        frac *= 10;
    }
    *t_us = whole * 1000000 + frac;
    return 1;
}

/* One non-blank line, comment already cut. */
static cub_err parse_entry(void *ctx, cub_text_line *ln)
{
    parser *ps = ctx;
    cub_button_script *s = ps->s;
    const cub_text_at *p = &ln->at;
    if (strlen(ln->s) >= MAX_LINE) {
        return cub_text_fail(p, "line longer than %d characters", MAX_LINE - 1);
    }
    char *tok[3] = {NULL, NULL, NULL};
    int n = cub_text_words(ln->s, tok, 3);
    if (n < 2) {
        return cub_text_fail(p, "expected \"<seconds> <start|stop> [down|up|press]\"");
    }
    if (n > 3) {
        return cub_text_fail(p, "too many fields (expected \"<seconds> <start|stop> [down|up|press]\")");
    }
    int64_t t_us;
    if (!parse_seconds(tok[0], &t_us)) {
        return cub_text_fail(p, "bad time \"%s\" (want seconds >= 0, at most 6 decimals, e.g. 1.5)",
                    tok[0]);
    }
    if (t_us < ps->prev_t_us) {
        return cub_text_fail(p,
                    "time %s is before the previous entry's %lld.%06lld (times must not decrease)",
                    tok[0], (long long)(ps->prev_t_us / 1000000), (long long)(ps->prev_t_us % 1000000));
    }
    ps->prev_t_us = t_us;
    int button;
    if (strcmp(tok[1], "start") == 0) {
        button = CUB_BUTTON_START;
    } else if (strcmp(tok[1], "stop") == 0) {
        button = CUB_BUTTON_STOP;
    } else {
        return cub_text_fail(p, "unknown button \"%s\" (want start or stop)", tok[1]);
    }
    const char *action = n == 3 ? tok[2] : "press";
    cub_err e;
    if (strcmp(action, "down") == 0 || strcmp(action, "up") == 0) {
        e = push_edge(s, t_us, button, action[0] == 'd', p->line);
    } else if (strcmp(action, "press") == 0) {
        e = push_edge(s, t_us, button, 1, p->line);
        if (!e) {
            e = push_edge(s, t_us + CUB_BUTTON_SCRIPT_PRESS_US, button, 0, p->line);
        }
    } else {
        return cub_text_fail(p, "unknown action \"%s\" (want down, up or press)", action);
    }
    return e ? cub_diag_fail(p->diag, e, p->name, p->line, "out of memory") : CUB_OK;
}

/* A press's release can land after later lines: a stable insertion sort puts
 * edges in time order, keeping file order on ties. */
static void sort_edges(cub_button_script *s)
{
    for (size_t i = 1; i < s->count; i++) {
        edge e = s->edges[i];
        size_t j = i;
        for (; j > 0 && s->edges[j - 1].t_us > e.t_us; j--) {
            s->edges[j] = s->edges[j - 1];
        }
        s->edges[j] = e;
    }
}

/* Each button must alternate down, up, down ... */
static cub_err check_alternation(const cub_button_script *s, const cub_text *t)
{
    cub_text_at at = {t->name, 0, t->diag}, *p = &at;
    int is_down[CUB_BUTTON_COUNT] = {0};
    for (size_t i = 0; i < s->count; i++) {
        const edge *e = &s->edges[i];
        const char *name = e->button == CUB_BUTTON_START ? "start" : "stop";
        if (e->down == is_down[e->button]) {
            p->line = e->line;
            return cub_text_fail(p, "%s %s at %lld.%06lld while %s is already %s", name,
                        e->down ? "down" : "up", (long long)(e->t_us / 1000000),
                        (long long)(e->t_us % 1000000), name, e->down ? "down" : "up");
        }
        is_down[e->button] = e->down;
    }
    return CUB_OK;
}

/* The whole timeline into *out (a cub_button_script **). */
static cub_err parse_text(const cub_text *t, const void *in, void *out)
{
    cub_button_script *s = calloc(1, sizeof *s);
    if (!s) {
        return cub_diag_fail(t->diag, CUB_ERR_NOMEM, t->name, 0, "out of memory");
    }
    parser p = {s, 0};
    cub_err e = cub_text_lines(t, parse_entry, &p);
    if (!e) {
        sort_edges(s);
        e = check_alternation(s, t);
    }
    if (e) {
        cub_button_script_free(s);
        return e;
    }
    *(cub_button_script **)out = s;
    return CUB_OK;
}

cub_err cub_button_script_parse(const char *text, size_t len, const char *file,
                                cub_button_script **out, char *err, size_t err_size)
{
    if (!out || !err || err_size == 0 || (!text && len)) {
        return CUB_ERR_ARG;
    }
    *out = NULL;
    err[0] = '\0';
    cub_diag d = {0};
    cub_text t = {text, len, file ? file : "(script)", &d};
    return cub_diag_report(parse_text(&t, NULL, out), &d, err, err_size);
}

cub_err cub_button_script_load(const char *path, cub_button_script **out, char *err,
                               size_t err_size)
{
    if (!path || !out || !err || err_size == 0) {
        return CUB_ERR_ARG;
    }
    *out = NULL;
    err[0] = '\0';
    cub_diag d = {0};
    cub_text_src src = {path, "button script", CUB_BUTTON_SCRIPT_MAX_BYTES};
    return cub_diag_report(cub_text_load(&src, parse_text, NULL, out, &d), &d, err, err_size);
}

void cub_button_script_free(cub_button_script *s)
{
    if (s) {
        free(s->edges);
        free(s);
    }
}

size_t cub_button_script_edges(const cub_button_script *s)
{
    return s ? s->count : 0;
}

static int peek(const cub_button_script *s, int64_t now_us, cub_event *ev)
{
    if (!s || s->next >= s->count || s->edges[s->next].t_us > now_us) {
        return 0;
    }
    const edge *e = &s->edges[s->next];
    *ev = (cub_event){
        .t_us = e->t_us,
        .type = e->down ? CUB_EV_BUTTON_DOWN : CUB_EV_BUTTON_UP,
        .a = e->button,
    };
    return 1;
}

int cub_button_script_next(cub_button_script *s, int64_t now_us, cub_event *ev)
{
    if (!ev || !peek(s, now_us, ev)) {
        return 0;
    }
    s->next++;
    return 1;
}

void cub_button_script_poll(cub_button_script *s, cub_loop *loop, int64_t now_us)
{
    cub_event ev;
    /* A full queue delays the rest of the script to the next poll: check
     * for room first, so a delayed press is not logged as a dropped one. */
    while (cub_queue_count(&loop->queue) < loop->queue.capacity && peek(s, now_us, &ev) &&
           cub_loop_post(loop, &ev) == CUB_OK) {
        s->next++;
    }
}

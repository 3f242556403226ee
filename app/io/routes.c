/* routes — the bridge planner's searched routes as text (cub/routes.h). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/routes.h"

#define ROUTE_WORDS 10
#define ALIGN_MAX 1e6 /* mm or degrees: far beyond any floor or turn */

typedef struct parse_ctx {
    const cub_library *lib;
    cub_routes *out;
    int have_header;
} parse_ctx;

static int parse_int(const char *s, long lo, long hi, int *out)
{
    char *e = NULL;
    errno = 0;
    long v = strtol(s, &e, 10);
    if (e == s || *e || errno || v < lo || v > hi) return 0;
    *out = (int)v;
    return 1;
}

static int parse_real(const char *s, double *out)
{
    char *e = NULL;
    errno = 0;
    *out = strtod(s, &e);
    return e != s && !*e && !errno && isfinite(*out) && fabs(*out) <= ALIGN_MAX;
}

static cub_err clip_of(const parse_ctx *c, const char *name, int *out, const cub_text_at *at)
{
    *out = cub_library_find(c->lib, name);
    if (*out < 0) return cub_text_fail(at, "clip \"%s\" is not in the clip library", name);
    return CUB_OK;
}

/* A frame of clip `clip`, named `what` in messages. */
static cub_err frame_of(const parse_ctx *c, int clip, const char *w, const char *what, int *out,
                        const cub_text_at *at)
{
    int n = c->lib->clips[clip].clip.frame_count;
    if (!parse_int(w, 0, n - 1, out))
        return cub_text_fail(at, "%s \"%s\" is not a frame of \"%s\" (0..%d)", what, w,
                             c->lib->clips[clip].name, n - 1);
    return CUB_OK;
}

static cub_err pair_once(const parse_ctx *c, const cub_bridge_route *r, const cub_text_at *at)
{
    if (r->from == r->to) return cub_text_fail(at, "a route from a clip to itself");
    for (int i = 0; i < c->out->count; i++)
        if (c->out->route[i].from == r->from && c->out->route[i].to == r->to)
            return cub_text_fail(at, "a second route from \"%s\" to \"%s\" (the first on line %d)",
                                 c->lib->clips[r->from].name, c->lib->clips[r->to].name,
                                 c->out->line[i]);
    return CUB_OK;
}

static cub_err parse_route(parse_ctx *c, char **w, int n, const cub_text_at *at)
{
    if (n != ROUTE_WORDS)
        return cub_text_fail(at, "expected `from to via a in out b turn_deg x_mm z_mm`, got %d words",
                             n);
    if (c->out->count >= CUB_ROUTES_MAX)
        return cub_text_fail(at, "more than %d routes", CUB_ROUTES_MAX);
    int k[7];
    cub_err e = CUB_OK;
    for (int i = 0; i < 3 && !e; i++)
        e = clip_of(c, w[i], &k[i], at);
    if (!e) e = frame_of(c, k[0], w[3], "a", &k[3], at);
    if (!e) e = frame_of(c, k[2], w[4], "in", &k[4], at);
    if (!e) e = frame_of(c, k[2], w[5], "out", &k[5], at);
    if (!e) e = frame_of(c, k[1], w[6], "b", &k[6], at);
    if (e) return e;
    if (k[4] >= k[5]) return cub_text_fail(at, "in %d is not before out %d", k[4], k[5]);
    cub_bridge_route r = {(int16_t)k[0], (int16_t)k[1], (int16_t)k[2], (int16_t)k[3],
                          (int16_t)k[4], (int16_t)k[5], (int16_t)k[6], 0};
    if ((e = pair_once(c, &r, at))) return e;
    double *al = c->out->align[c->out->count];
    for (int i = 0; i < 3; i++)
        if (!parse_real(w[7 + i], &al[i]))
            return cub_text_fail(at, "bad number \"%s\" (turn_deg x_mm z_mm)", w[7 + i]);
    c->out->line[c->out->count] = at->line;
    c->out->route[c->out->count++] = r;
    return CUB_OK;
}

static cub_err route_line(void *ctx, cub_text_line *ln)
{
    parse_ctx *c = ctx;
    char *w[ROUTE_WORDS + 1];
    int n = cub_text_words(ln->s, w, ROUTE_WORDS + 1);
    if (!c->have_header) {
        if (n != 2 || strcmp(w[0], "cubroutes") || strcmp(w[1], "1"))
            return cub_text_fail(&ln->at, "expected the header `cubroutes 1`");
        c->have_header = 1;
        return CUB_OK;
    }
    return parse_route(c, w, n, &ln->at);
}

static cub_err parse_text(const cub_text *t, const void *in, void *out)
{
    parse_ctx c = {in, out, 0};
    memset(c.out, 0, sizeof *c.out);
    cub_err e = cub_text_lines(t, route_line, &c);
    if (!e && !c.have_header)
        e = cub_diag_fail(t->diag, CUB_ERR_FORMAT, t->name, 0, "no `cubroutes 1` header");
    return e;
}

cub_err cub_routes_parse(const char *text, size_t len, const char *name, const cub_library *lib,
                         cub_routes *out, cub_diag *diag)
{
    if (!lib || !out) return CUB_ERR_ARG;
    cub_text t = {text, len, name ? name : "(routes)", diag};
    return cub_text_parse(&t, parse_text, lib, out);
}

cub_err cub_routes_read(const char *path, const cub_library *lib, cub_routes *out, cub_diag *diag)
{
    if (!lib || !out) return CUB_ERR_ARG;
    return cub_text_load(&(cub_text_src){path, "routes", CUB_TEXT_MAX_SMALL}, parse_text, lib, out,
                         diag);
}

cub_err cub_routes_write(const char *path, const cub_library *lib, const cub_routes *r,
                         cub_diag *diag)
{
    FILE *f = fopen(path, "w");
    if (!f) return cub_diag_fail(diag, CUB_ERR_IO, path, 0, "cannot write: %s", strerror(errno));
    fprintf(f, "cubroutes 1\n"
               "# The bridge planner's searched routes (docs/join.md, \"Routes\"), made by\n"
               "#   cubtool join --all --routes-out assets/clips/bear.routes.txt\n"
               "# from to via a in out b turn_deg x_mm z_mm\n");
    for (int i = 0; i < r->count; i++) {
        const cub_bridge_route *q = &r->route[i];
        fprintf(f, "%s %s %s %d %d %d %d %.1f %.1f %.1f\n", lib->clips[q->from].name,
                lib->clips[q->to].name, lib->clips[q->via].name, q->a, q->in, q->out, q->b,
                r->align[i][0], r->align[i][1], r->align[i][2]);
    }
    if (fclose(f)) return cub_diag_fail(diag, CUB_ERR_IO, path, 0, "cannot write");
    return CUB_OK;
}

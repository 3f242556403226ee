/* gait_terrain_file — a terrain as text, for cubtool gait --terrain FILE
 * (gait_tool.h says the format). Line based, '#' comments; every problem
 * is "file:line: what". */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/text.h"
#include "gait_tool.h"

#define MAX_WORDS (GAIT_GRID + 2)
#define LIMIT_MM 100000.0 /* 100 m: far past any forest floor */

typedef struct parse_state {
    gait_ground *g;
    int kind_set; /* 1 once flat, slope or grid was read */
    int nx, nz, rows;
} parse_state;

/* words[i] as a number in [lo, hi], into *v. */
static cub_err number(const cub_text_at *at, const char *word, double lo, double hi, double *v)
{
    char *end;
    *v = strtod(word, &end);
    if (end == word || *end || !isfinite(*v))
        return cub_text_fail(at, "'%.40s' is not a number", word);
    if (*v < lo || *v > hi) return cub_text_fail(at, "%.40s is outside %g..%g", word, lo, hi);
    return CUB_OK;
}

static cub_q16 q16(double mm)
{
    return (cub_q16)lround(mm * 65536.0);
}

static cub_err numbers(const cub_text_at *at, char **w, int n, double lo, double hi, double *out)
{
    for (int i = 0; i < n; i++) {
        cub_err e = number(at, w[i], lo, hi, &out[i]);
        if (e) return e;
    }
    return CUB_OK;
}

static cub_err kind_line(parse_state *p, const cub_text_at *at, char **w, int n)
{
    double v[5];
    if (p->kind_set) return cub_text_fail(at, "a second ground ('%s'): one of flat, slope, grid", w[0]);
    p->kind_set = 1;
    if (!strcmp(w[0], "flat")) {
        if (n != 2) return cub_text_fail(at, "flat takes 1 value (base mm), got %d", n - 1);
        cub_err e = numbers(at, w + 1, 1, -LIMIT_MM, LIMIT_MM, v);
        if (!e) cub_gait_terrain_flat(&p->g->t, q16(v[0]));
        return e;
    }
    if (!strcmp(w[0], "slope")) {
        if (n != 4) return cub_text_fail(at, "slope takes 3 values (base mm, grad x, grad z), got %d", n - 1);
        cub_err e = numbers(at, w + 1, 1, -LIMIT_MM, LIMIT_MM, v);
        if (!e) e = numbers(at, w + 2, 2, -1, 1, v + 1);
        if (!e) cub_gait_terrain_slope(&p->g->t, q16(v[0]), q16(v[1]), q16(v[2]));
        return e;
    }
    if (n != 6) return cub_text_fail(at, "grid takes 5 values (nx nz cell_mm origin_x origin_z), got %d", n - 1);
    cub_err e = numbers(at, w + 1, 2, 2, GAIT_GRID, v);
    if (!e) e = number(at, w[3], 10, 5000, &v[2]);
    if (!e) e = numbers(at, w + 4, 2, -LIMIT_MM, LIMIT_MM, v + 3);
    if (e) return e;
    if (v[0] != floor(v[0]) || v[1] != floor(v[1]))
        return cub_text_fail(at, "grid sizes must be whole numbers");
    p->nx = (int)v[0];
    p->nz = (int)v[1];
    cub_gait_terrain_rolling(&p->g->t, p->g->heights, p->nx, p->nz, q16(v[2]), 0, CUB_Q16_ONE);
    p->g->t.origin_x_mm = q16(v[3]);
    p->g->t.origin_z_mm = q16(v[4]);
    return CUB_OK;
}

static cub_err row_line(parse_state *p, const cub_text_at *at, char **w, int n)
{
    if (!p->nx) return cub_text_fail(at, "a row before 'grid'");
    if (p->rows >= p->nz) return cub_text_fail(at, "more than the grid's %d rows", p->nz);
    if (n - 1 != p->nx) return cub_text_fail(at, "a row holds %d heights, the grid %d", n - 1, p->nx);
    for (int i = 0; i < p->nx; i++) {
        double v;
        cub_err e = number(at, w[1 + i], -LIMIT_MM, LIMIT_MM, &v);
        if (e) return e;
        p->g->heights[p->rows * p->nx + i] = q16(v);
    }
    p->rows++;
    return CUB_OK;
}

static cub_err box_line(parse_state *p, const cub_text_at *at, char **w, int n)
{
    double v[6];
    if (n != 7) return cub_text_fail(at, "box takes 6 values (x0 y0 z0 x1 y1 z1 mm), got %d", n - 1);
    cub_err e = numbers(at, w + 1, 6, -LIMIT_MM, LIMIT_MM, v);
    if (e) return e;
    if (!(v[0] < v[3] && v[1] < v[4] && v[2] < v[5]))
        return cub_text_fail(at, "box corners must be lowest first on every axis");
    cub_gait_box b = {{q16(v[0]), q16(v[1]), q16(v[2])}, {q16(v[3]), q16(v[4]), q16(v[5])}};
    if (cub_gait_terrain_add(&p->g->t, b))
        return cub_text_fail(at, "more than %d boxes", CUB_GAIT_MAX_OBSTACLES);
    return CUB_OK;
}

static cub_err terrain_line(void *ctx, cub_text_line *ln)
{
    parse_state *p = ctx;
    char *w[MAX_WORDS];
    int n = cub_text_words(ln->s, w, MAX_WORDS);
    if (n > MAX_WORDS - 1) return cub_text_fail(&ln->at, "too many values on a line");
    if (!strcmp(w[0], "flat") || !strcmp(w[0], "slope") || !strcmp(w[0], "grid"))
        return kind_line(p, &ln->at, w, n);
    if (!p->kind_set) return cub_text_fail(&ln->at, "'%.40s' before the ground (flat, slope, grid)", w[0]);
    if (!strcmp(w[0], "row")) return row_line(p, &ln->at, w, n);
    if (!strcmp(w[0], "box")) return box_line(p, &ln->at, w, n);
    return cub_text_fail(&ln->at, "unknown word '%.40s' (flat, slope, grid, row, box)", w[0]);
}

cub_err gait_terrain_parse(const char *s, size_t len, const char *name, gait_ground *g,
                           cub_diag *d)
{
    memset(g, 0, sizeof *g);
    snprintf(g->name, sizeof g->name, "%.40s", name);
    parse_state p = {.g = g};
    cub_text t = {s, len, name, d};
    cub_err e = cub_text_lines(&t, terrain_line, &p);
    if (e) return e;
    cub_text_at whole = {name, 0, d};
    if (!p.kind_set) return cub_text_fail(&whole, "no ground (flat, slope or grid)");
    if (p.nx && p.rows != p.nz)
        return cub_text_fail(&whole, "the grid has %d rows of the %d it names", p.rows, p.nz);
    return CUB_OK;
}

static cub_err parse_whole(const cub_text *t, const void *in, void *out)
{
    (void)in;
    return gait_terrain_parse(t->s, t->len, t->name, out, t->diag);
}

cub_err gait_terrain_load(const char *path, gait_ground *g, cub_diag *d)
{
    cub_text_src src = {path, "terrain", CUB_TEXT_MAX_SMALL};
    return cub_text_load(&src, parse_whole, NULL, g, d);
}

/* floor_file — reading the forest floor (cub/floor_file.h). One keyword a
 * line; the line's words are counted before any is read, so a message says
 * what the line should hold. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "cub/floor_file.h"

#define MAX_WORDS (CUB_FLOOR_MAX_SIDE + 1)

typedef struct floor_parse {
    cub_floor *out;
    int seen_header, seen_grid, rows;
    int last_line; /* for "rows too few" at the end */
} floor_parse;

/* words[i] as a whole number within lo..hi. */
static cub_err get_int(const cub_text_at *at, const char *word, const char *what, long lo, long hi,
                       int32_t *out)
{
    char *end;
    errno = 0;
    long v = strtol(word, &end, 10);
    if (end == word || *end || errno)
        return cub_text_fail(at, "%s '%s' is not a whole number", what, word);
    if (v < lo || v > hi) return cub_text_fail(at, "%s %ld is not within %ld..%ld", what, v, lo, hi);
    *out = (int32_t)v;
    return CUB_OK;
}

static cub_err header(floor_parse *p, const cub_text_at *at, char **w, int n)
{
    if (n != 2 || strcmp(w[0], "cubfloor") != 0)
        return cub_text_fail(at, "not a floor file: the first line must be 'cubfloor 1'");
    if (strcmp(w[1], "1") != 0)
        return cub_text_fail(at, "floor format version '%s' is not 1", w[1]);
    p->seen_header = 1;
    return CUB_OK;
}

static cub_err grid(floor_parse *p, const cub_text_at *at, char **w, int n)
{
    const long e = CUB_FLOOR_EXTENT_MM;
    cub_floor *f = p->out;
    if (p->seen_grid) return cub_text_fail(at, "a second grid");
    if (n != 6) return cub_text_fail(at, "grid needs NX NZ CELL_MM X0_MM Z0_MM");
    int32_t nx = 0, nz = 0;
    cub_err r = get_int(at, w[1], "NX", 2, CUB_FLOOR_MAX_SIDE, &nx);
    if (!r) r = get_int(at, w[2], "NZ", 2, CUB_FLOOR_MAX_SIDE, &nz);
    if (!r) r = get_int(at, w[3], "CELL_MM", CUB_FLOOR_MIN_CELL_MM, CUB_FLOOR_MAX_CELL_MM, &f->cell_mm);
    if (!r) r = get_int(at, w[4], "X0_MM", -e, e, &f->origin_x_mm);
    if (!r) r = get_int(at, w[5], "Z0_MM", -e, e, &f->origin_z_mm);
    if (r) return r;
    f->nx = nx;
    f->nz = nz;
    long far_x = (long)f->origin_x_mm + (long)(nx - 1) * f->cell_mm;
    long far_z = (long)f->origin_z_mm + (long)(nz - 1) * f->cell_mm;
    if (far_x > e || far_z > e)
        return cub_text_fail(at, "the grid reaches past %ld mm (x to %ld, z to %ld)", e, far_x,
                             far_z);
    p->seen_grid = 1;
    return CUB_OK;
}

static cub_err row(floor_parse *p, const cub_text_at *at, char **w, int n)
{
    cub_floor *f = p->out;
    if (!p->seen_grid) return cub_text_fail(at, "a row before the grid");
    if (f->thing_count) return cub_text_fail(at, "a row after a log or stone");
    if (p->rows == f->nz) return cub_text_fail(at, "more than NZ = %d rows", f->nz);
    if (n != f->nx + 1)
        return cub_text_fail(at, "row %d has %d heights, the grid has NX = %d", p->rows + 1, n - 1,
                             f->nx);
    const long top = CUB_FLOOR_MAX_RISE_MM;
    for (int i = 0; i < f->nx; i++) {
        int32_t h = 0;
        cub_err r = get_int(at, w[i + 1], "height", -top, top, &h);
        if (r) return r;
        f->heights_mm[p->rows * f->nx + i] = CUB_Q16_INT(h);
    }
    p->rows++;
    return CUB_OK;
}

/* The middle of a thing: within the extent less its size, checked after. */
static cub_err middle(const cub_text_at *at, char **w, cub_floor_thing *t)
{
    const long e = CUB_FLOOR_EXTENT_MM;
    cub_err r = get_int(at, w[1], "X_MM", -e, e, &t->x_mm);
    return r ? r : get_int(at, w[2], "Z_MM", -e, e, &t->z_mm);
}

static cub_err log_thing(const cub_text_at *at, char **w, int n, cub_floor_thing *t)
{
    const long lo = CUB_FLOOR_MIN_SIZE_MM, hi = CUB_FLOOR_MAX_SIZE_MM;
    if (n != 6) return cub_text_fail(at, "log needs X_MM Z_MM LENGTH_MM RADIUS_MM x|z");
    int32_t len = 0, rad = 0;
    cub_err r = middle(at, w, t);
    if (!r) r = get_int(at, w[3], "LENGTH_MM", 2 * lo, 2 * hi, &len);
    if (!r) r = get_int(at, w[4], "RADIUS_MM", lo, hi / 2, &rad);
    if (r) return r;
    if (strcmp(w[5], "x") != 0 && strcmp(w[5], "z") != 0)
        return cub_text_fail(at, "a log lies along x or z, not '%s'", w[5]);
    if (len < 2 * rad) return cub_text_fail(at, "a log %d mm long is shorter than it is thick", len);
    int along_x = w[5][0] == 'x';
    *t = (cub_floor_thing){CUB_FLOOR_LOG, t->x_mm, t->z_mm, along_x ? len / 2 : rad,
                           along_x ? rad : len / 2, 2 * rad};
    return CUB_OK;
}

static cub_err stone_thing(const cub_text_at *at, char **w, int n, cub_floor_thing *t)
{
    const long lo = CUB_FLOOR_MIN_SIZE_MM, hi = CUB_FLOOR_MAX_SIZE_MM;
    if (n != 6) return cub_text_fail(at, "stone needs X_MM Z_MM HALF_X_MM HALF_Z_MM HEIGHT_MM");
    t->kind = CUB_FLOOR_STONE;
    cub_err r = middle(at, w, t);
    if (!r) r = get_int(at, w[3], "HALF_X_MM", lo, hi, &t->half_x_mm);
    if (!r) r = get_int(at, w[4], "HALF_Z_MM", lo, hi, &t->half_z_mm);
    if (!r) r = get_int(at, w[5], "HEIGHT_MM", lo, hi, &t->height_mm);
    return r;
}

static cub_err thing(floor_parse *p, const cub_text_at *at, char **w, int n)
{
    cub_floor *f = p->out;
    if (!p->seen_grid || p->rows < f->nz)
        return cub_text_fail(at, "a %s before the grid's %d rows", w[0], f->nz);
    if (f->thing_count == CUB_FLOOR_MAX_THINGS)
        return cub_text_fail(at, "more than %d logs and stones", CUB_FLOOR_MAX_THINGS);
    cub_floor_thing t = {0};
    cub_err r = w[0][0] == 'l' ? log_thing(at, w, n, &t) : stone_thing(at, w, n, &t);
    if (r) return r;
    const long e = CUB_FLOOR_EXTENT_MM;
    if (labs((long)t.x_mm) + t.half_x_mm > e || labs((long)t.z_mm) + t.half_z_mm > e)
        return cub_text_fail(at, "the %s reaches past %ld mm", w[0], e);
    f->things[f->thing_count++] = t;
    return CUB_OK;
}

static cub_err floor_line(void *ctx, cub_text_line *ln)
{
    floor_parse *p = ctx;
    const cub_text_at *at = &ln->at;
    char *w[MAX_WORDS];
    int n = cub_text_words(ln->s, w, MAX_WORDS);
    p->last_line = at->line;
    if (n > MAX_WORDS) return cub_text_fail(at, "more than %d words", MAX_WORDS);
    if (!p->seen_header) return header(p, at, w, n);
    if (!strcmp(w[0], "grid")) return grid(p, at, w, n);
    if (!strcmp(w[0], "row")) return row(p, at, w, n);
    if (!strcmp(w[0], "log") || !strcmp(w[0], "stone")) return thing(p, at, w, n);
    return cub_text_fail(at, "unknown keyword '%s' (grid, row, log, stone)", w[0]);
}

static cub_err parse_text(const cub_text *t, const void *in, void *out)
{
    (void)in;
    floor_parse p = {.out = out};
    memset(p.out, 0, sizeof *p.out);
    cub_err e = cub_text_lines(t, floor_line, &p);
    cub_text_at end = {t->name, p.last_line, t->diag};
    if (!e && !p.seen_header) e = cub_text_fail(&end, "empty: no 'cubfloor 1' line");
    else if (!e && !p.seen_grid) e = cub_text_fail(&end, "no grid");
    else if (!e && p.rows < p.out->nz)
        e = cub_text_fail(&end, "%d rows, the grid has NZ = %d", p.rows, p.out->nz);
    if (!e && cub_floor_check(p.out)) /* the reader's limits are the firmware's */
        e = cub_text_fail(&end, "the floor breaks a limit of cub/floor.h");
    if (e) memset(p.out, 0, sizeof *p.out);
    return e;
}

cub_err cub_floor_parse(const char *text, size_t len, const char *name, cub_floor *out,
                        cub_diag *diag)
{
    cub_text t = {text, len, name ? name : "(floor)", diag};
    return cub_text_parse(&t, parse_text, NULL, out);
}

cub_err cub_floor_load(const char *path, cub_floor *out, cub_diag *diag)
{
    return cub_text_load(&(cub_text_src){path, "floor file", CUB_TEXT_MAX_SMALL}, parse_text, NULL,
                         out, diag);
}

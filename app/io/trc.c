/* trc — reading marker positions (cub/trc.h). The text is copied and cut
 * into lines in place: cub_text_lines would cut "Frame#" at its '#' and
 * drop the blank cells that mean a marker was lost. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cub/trc.h"

/* Blank cells in a row are kept, so the cells may number this many more
 * than a row needs before the row is refused unread. */
#define TRC_MAX_CELLS (2 + 3 * CUB_TRC_MAX_MARKERS + 1)

typedef struct trc_lines {
    char *buf, *p, *end;
    int line; /* of the line last taken */
    const char *name;
    cub_diag *diag;
} trc_lines;

/* The next line (NUL-terminated, without "\r\n"), or NULL at the end. */
static char *next_line(trc_lines *r)
{
    if (r->p >= r->end) return NULL;
    char *s = r->p, *nl = memchr(s, '\n', (size_t)(r->end - s));
    char *e = nl ? nl : r->end;
    r->p = nl ? nl + 1 : r->end;
    if (e > s && e[-1] == '\r') e--;
    *e = '\0';
    r->line++;
    return s;
}

static cub_err fail(const trc_lines *r, const char *fmt, const char *arg)
{
    cub_text_at at = {r->name, r->line, r->diag};
    return cub_text_fail(&at, fmt, arg);
}

static int blank(const char *s)
{
    return s[strspn(s, " \t")] == '\0';
}

/* Split s in place at tabs into cells[0..max); returns how many, max + 1
 * when there are more. */
static int split_tabs(char *s, char **cells, int max)
{
    int n = 0;
    for (;;) {
        if (n == max) return max + 1;
        cells[n++] = s;
        char *t = strchr(s, '\t');
        if (!t) return n;
        *t = '\0';
        s = t + 1;
    }
}

/* A finite number filling the whole cell (blanks around allowed). */
static int get_num(const char *s, double *v)
{
    char *end;
    *v = strtod(s, &end);
    return end != s && blank(end) && isfinite(*v);
}

typedef struct trc_head {
    double rate, frames, markers, scale;
} trc_head;

static cub_err head_value(trc_lines *r, trc_head *h, const char *key, const char *val)
{
    double v;
    if (!strcmp(key, "Units")) {
        if (!strcmp(val, "mm")) h->scale = 1.0;
        else if (!strcmp(val, "m")) h->scale = 1000.0;
        else return fail(r, "units '%s' are neither mm nor m", val);
        return CUB_OK;
    }
    double *dst = !strcmp(key, "DataRate") ? &h->rate : !strcmp(key, "NumFrames") ? &h->frames
                : !strcmp(key, "NumMarkers") ? &h->markers : NULL;
    if (!dst) return CUB_OK;
    if (!get_num(val, &v) || v <= 0) return fail(r, "%s is not a number above 0", key);
    *dst = v;
    return CUB_OK;
}

/* Lines 2 and 3: the header's names, then its values. */
static cub_err read_head(trc_lines *r, trc_head *h)
{
    char *names = next_line(r), *vals = names ? next_line(r) : NULL;
    if (!vals) return fail(r, "%s", "the header ends before its names and values");
    char *k[16], *v[16];
    int nk = cub_text_words(names, k, 16), nv = cub_text_words(vals, v, 16);
    if (nk > 16 || nv > 16) return fail(r, "%s", "the header has more than 16 values");
    *h = (trc_head){0};
    for (int i = 0; i < nk && i < nv; i++) {
        cub_err e = head_value(r, h, k[i], v[i]);
        if (e) return e;
    }
    if (h->rate <= 0 || h->frames <= 0 || h->markers <= 0 || h->scale <= 0)
        return fail(r, "%s", "the header needs DataRate, NumFrames, NumMarkers and Units");
    if (h->markers > CUB_TRC_MAX_MARKERS || h->markers != floor(h->markers))
        return fail(r, "NumMarkers is not a whole number from 1 to %s", "256");
    if (h->frames > CUB_TRC_MAX_FRAMES || h->frames != floor(h->frames))
        return fail(r, "NumFrames is not a whole number from 1 to %s", "1048576");
    return CUB_OK;
}

/* Line 4: "Frame#  Time  NAME  (tab tab)  NAME ...". */
static cub_err read_names(trc_lines *r, cub_trc *t)
{
    char *s = next_line(r), *cells[TRC_MAX_CELLS];
    if (!s) return fail(r, "%s", "the header ends before the marker names");
    int n = split_tabs(s, cells, TRC_MAX_CELLS), m = 0;
    if (n < 2 || strncmp(cells[0], "Frame#", 6) != 0)
        return fail(r, "%s", "the marker names line does not start with Frame# and Time");
    for (int i = 2; i < n && i < TRC_MAX_CELLS; i++) {
        if (blank(cells[i])) continue;
        if (m == t->markers)
            return fail(r, "more marker names than NumMarkers (at '%s')", cells[i]);
        if (strlen(cells[i]) >= CUB_TRC_NAME_LEN)
            return fail(r, "marker name '%s' is too long", cells[i]);
        strcpy(t->names[m++], cells[i]);
    }
    if (m != t->markers) return fail(r, "fewer marker names than NumMarkers%s", "");
    if (!next_line(r)) return fail(r, "%s", "the header ends before the X1 Y1 Z1 line");
    return CUB_OK;
}

/* One marker of a row: three numbers, or three blanks for a lost one. */
static cub_err read_marker(trc_lines *r, char **c, double scale, float *pos, uint8_t *present)
{
    int blanks = blank(c[0]) + blank(c[1]) + blank(c[2]);
    if (blanks == 3) return CUB_OK;
    if (blanks) return fail(r, "a marker is missing only part of x y z%s", "");
    for (int k = 0; k < 3; k++) {
        double v;
        if (!get_num(c[k], &v)) return fail(r, "'%s' is not a finite number", c[k]);
        pos[k] = (float)(v * scale);
    }
    *present = 1;
    return CUB_OK;
}

static cub_err read_row(trc_lines *r, cub_trc *t, char *s, double scale, int f)
{
    char *c[TRC_MAX_CELLS];
    int need = 2 + 3 * t->markers, n = split_tabs(s, c, TRC_MAX_CELLS);
    if (n == need + 1 && blank(c[need])) n = need;
    if (n < need) return fail(r, "the row is short of cells (frame, time, x y z per marker)%s", "");
    if (n > need)
        return fail(r, "the row has more cells than frame, time and x y z per marker%s", "");
    double v;
    if (!get_num(c[0], &v) || v < 0 || v > 1e9 || v != floor(v))
        return fail(r, "frame '%s' is not a whole number from 0 to 1e9", c[0]);
    if (!get_num(c[1], &v)) return fail(r, "time '%s' is not a finite number", c[1]);
    t->time[f] = v;
    for (int m = 0; m < t->markers; m++) {
        size_t at = (size_t)f * (size_t)t->markers + (size_t)m;
        cub_err e = read_marker(r, c + 2 + 3 * m, scale, t->pos + 3 * at, t->present + at);
        if (e) return e;
    }
    return CUB_OK;
}

static cub_err alloc_trc(cub_trc *t)
{
    size_t cells = (size_t)t->frames * (size_t)t->markers;
    t->names = calloc((size_t)t->markers, sizeof *t->names);
    t->time = calloc((size_t)t->frames, sizeof *t->time);
    t->pos = calloc(cells * 3, sizeof *t->pos);
    t->present = calloc(cells, 1);
    return t->names && t->time && t->pos && t->present ? CUB_OK : CUB_ERR_NOMEM;
}

static cub_err read_rows(trc_lines *r, cub_trc *t, double scale)
{
    int f = 0;
    for (char *s; (s = next_line(r));) {
        if (blank(s)) continue;
        if (f == t->frames) return fail(r, "more rows than NumFrames%s", "");
        cub_err e = read_row(r, t, s, scale, f++);
        if (e) return e;
    }
    if (f != t->frames) return fail(r, "the file ends after %s rows, fewer than NumFrames", "its");
    return CUB_OK;
}

/* NumFrames may claim more than the file holds: refuse before allocating. */
static size_t count_lines(const char *s, const char *end)
{
    size_t n = 1;
    while ((s = memchr(s, '\n', (size_t)(end - s))))
        n++, s++;
    return n;
}

static cub_err parse_lines(trc_lines *r, cub_trc *t)
{
    if (r->end == r->buf) return fail(r, "%s", "the file is empty: no TRC header");
    char *first = next_line(r);
    if (!first || strncmp(first, "PathFileType", 12))
        return fail(r, "%s", "not a TRC file: the first line is not PathFileType");
    trc_head h;
    cub_err e = read_head(r, &h);
    if (e) return e;
    if (h.frames > (double)count_lines(r->p, r->end))
        return fail(r, "NumFrames is more than the file has lines%s", "");
    t->frames = (int)h.frames;
    t->markers = (int)h.markers;
    t->rate = h.rate;
    e = alloc_trc(t);
    if (!e) e = read_names(r, t);
    if (!e) e = read_rows(r, t, h.scale);
    return e;
}

void cub_trc_free(cub_trc *t)
{
    if (!t) return;
    free(t->names);
    free(t->time);
    free(t->pos);
    free(t->present);
    memset(t, 0, sizeof *t);
}

static cub_err parse_text(const cub_text *x, const void *in, void *out)
{
    (void)in;
    cub_trc *t = out;
    memset(t, 0, sizeof *t);
    if (memchr(x->s, '\0', x->len)) {
        cub_text_at at = {x->name, 0, x->diag};
        return cub_text_fail(&at, "the file contains a NUL byte");
    }
    trc_lines r = {malloc(x->len + 1), NULL, NULL, 0, x->name, x->diag};
    if (!r.buf) return CUB_ERR_NOMEM;
    memcpy(r.buf, x->s, x->len);
    r.buf[x->len] = '\0';
    r.p = r.buf;
    r.end = r.buf + x->len;
    cub_err e = parse_lines(&r, t);
    free(r.buf);
    if (e) cub_trc_free(t);
    return e;
}

cub_err cub_trc_parse(const char *text, size_t len, const char *name, cub_trc *out,
                      cub_diag *diag)
{
    cub_text t = {text, len, name ? name : "(trc)", diag};
    return cub_text_parse(&t, parse_text, NULL, out);
}

cub_err cub_trc_load(const char *path, cub_trc *out, cub_diag *diag)
{
    if (out) memset(out, 0, sizeof *out);
    return cub_text_load(&(cub_text_src){path, "TRC marker file", CUB_TEXT_MAX_MOCAP}, parse_text,
                         NULL, out, diag);
}

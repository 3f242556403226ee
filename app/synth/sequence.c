/* Sequence files: one segment a line, `clip from_s to_s [mirror]`, played
 * one after another. to_s may be `end` (the clip's end). '#' starts a
 * comment line. */
#include <stdlib.h>
#include <string.h>

#include "synth_internal.h"

#define SEQ_MAX_SEGMENTS 10000
#define SEQ_MAX_S 1e6

static cub_err parse_segment(const synth_fields *f, const char *name, int line,
                             cub_synth_segment *s, cub_diag *diag)
{
    if (f->nul) return synth_fail(diag, name, line, "a NUL byte in the line (not a text file?)");
    if (f->n < 3 || f->n > 4 || f->too_many)
        return synth_fail(diag, name, line, "expected 'clip from_s to_s [mirror]', got %d fields",
                          f->n);
    if (f->too_long || strlen(f->f[0]) >= sizeof(s->clip))
        return synth_fail(diag, name, line, "clip name too long");
    memset(s, 0, sizeof(*s));
    strcpy(s->clip, f->f[0]);
    if (!synth_parse_num(f->f[1], SEQ_MAX_S, &s->from_s) || s->from_s < 0)
        return synth_fail(diag, name, line, "bad from_s '%.40s' (seconds >= 0)", f->f[1]);
    if (strcmp(f->f[2], "end") == 0)
        s->to_s = 0;
    else if (!synth_parse_num(f->f[2], SEQ_MAX_S, &s->to_s) || s->to_s <= s->from_s)
        return synth_fail(diag, name, line, "bad to_s '%.40s' (seconds after from_s, or 'end')",
                          f->f[2]);
    if (f->n == 4) {
        if (strcmp(f->f[3], "mirror") != 0)
            return synth_fail(diag, name, line,
                              "expected 'mirror' or nothing after to_s, got '%.40s'", f->f[3]);
        s->mirror = 1;
    }
    return CUB_OK;
}

cub_err cub_synth_sequence_parse(const char *text, size_t len, const char *name,
                                 cub_synth_segment **out, int *n, cub_diag *diag)
{
    if (!text || !out || !n) return CUB_ERR_ARG;
    *out = NULL;
    *n = 0;
    name = name ? name : "(memory)";
    synth_lines l = {text, text + len, name, 0};
    synth_fields *f = malloc(sizeof(*f));
    if (!f) return CUB_ERR_NOMEM;
    cub_err err = CUB_OK;
    int cap = 0;
    while (!err && synth_lines_next(&l, f)) {
        if (f->n == 0 || f->f[0][0] == '#') continue;
        if (*n >= SEQ_MAX_SEGMENTS) {
            err = synth_fail(diag, name, l.line, "more than %d segments", SEQ_MAX_SEGMENTS);
            break;
        }
        if (*n == cap) {
            cap = cap ? cap * 2 : 16;
            cub_synth_segment *p = realloc(*out, (size_t)cap * sizeof(*p));
            if (!p) {
                err = CUB_ERR_NOMEM;
                break;
            }
            *out = p;
        }
        err = parse_segment(f, name, l.line, &(*out)[*n], diag);
        if (!err) (*n)++;
    }
    if (!err && *n == 0) err = synth_fail(diag, name, l.line, "no segments");
    free(f);
    if (err) {
        free(*out);
        *out = NULL;
        *n = 0;
    }
    return err;
}

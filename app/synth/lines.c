/* Line splitting and numbers for the two small text formats (truth.txt,
 * sequence files). Reads only inside [p, end): the input need not be
 * NUL-terminated, and no field is read past SYNTH_FIELD_LEN. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "synth_internal.h"

cub_err synth_fail(cub_diag *diag, const char *file, int line, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    cub_err e = cub_diag_vfail(diag, CUB_ERR_FORMAT, file ? file : "(memory)", line, fmt, ap);
    va_end(ap);
    return e;
}

static int blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r';
}

int synth_lines_next(synth_lines *l, synth_fields *out)
{
    if (l->p >= l->end) return 0;
    l->line++;
    out->n = 0;
    out->too_many = out->too_long = out->nul = 0;
    while (l->p < l->end && *l->p != '\n') {
        while (l->p < l->end && blank(*l->p))
            l->p++;
        if (l->p >= l->end || *l->p == '\n') break;
        const char *s = l->p;
        while (l->p < l->end && *l->p != '\n' && !blank(*l->p))
            l->p++;
        size_t n = (size_t)(l->p - s);
        if (memchr(s, 0, n)) out->nul = 1;
        if (out->n >= SYNTH_MAX_FIELDS) {
            out->too_many = 1;
            continue;
        }
        if (n >= SYNTH_FIELD_LEN) {
            out->too_long = 1;
            n = SYNTH_FIELD_LEN - 1;
        }
        memcpy(out->f[out->n], s, n);
        out->f[out->n][n] = 0;
        out->n++;
    }
    if (l->p < l->end) l->p++; /* the newline */
    return 1;
}

int synth_parse_num(const char *s, double limit, double *out)
{
    char *end;
    if (!*s || strchr(s, '\0') - s > 40) return 0;
    double v = strtod(s, &end);
    if (*end || !(v >= -limit && v <= limit)) /* also refuses NaN */
        return 0;
    *out = v;
    return 1;
}

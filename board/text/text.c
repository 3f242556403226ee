/* Reading hand-written text files and walking their lines (cub/text.h). */
#include "cub/text.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define BLANKS " \t\r\v\f"

cub_err cub_diag_vfail(cub_diag *diag, cub_err err, const char *file, int line, const char *fmt,
                       va_list ap)
{
    if (!diag)
        return err;
    snprintf(diag->file, sizeof(diag->file), "%s", file ? file : "");
    diag->line = line;
    vsnprintf(diag->msg, sizeof(diag->msg), fmt, ap);
    return err;
}

cub_err cub_diag_fail(cub_diag *diag, cub_err err, const char *file, int line, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    cub_err e = cub_diag_vfail(diag, err, file, line, fmt, ap);
    va_end(ap);
    return e;
}

const char *cub_diag_str(const cub_diag *d, char *buf, size_t size)
{
    if (!buf || size == 0)
        return "";
    if (!d)
        snprintf(buf, size, "(no diagnostic)");
    else if (d->line > 0)
        snprintf(buf, size, "%s:%d: %s", d->file, d->line, d->msg);
    else
        snprintf(buf, size, "%s: %s", d->file, d->msg);
    return buf;
}

cub_err cub_diag_report(cub_err e, const cub_diag *d, char *buf, size_t size)
{
    if (e && d->msg[0])
        cub_diag_str(d, buf, size);
    return e;
}

cub_err cub_text_fail(const cub_text_at *at, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    cub_err e = cub_diag_vfail(at->diag, CUB_ERR_FORMAT, at->name, at->line, fmt, ap);
    va_end(ap);
    return e;
}

/* The whole of f, at most cap bytes: grown as it comes, so that a large
 * cap costs nothing for a small file. One byte more than the cap is read
 * to tell "exactly full" from "too big"; *len > cap means too big. */
static char *read_all(FILE *f, size_t cap, size_t *len)
{
    size_t size = 1 << 16, got = 0;
    char *buf = NULL;
    for (;;) {
        if (size > cap + 2)
            size = cap + 2;
        char *bigger = realloc(buf, size);
        if (!bigger) {
            free(buf);
            return NULL;
        }
        buf = bigger;
        got += fread(buf + got, 1, size - 1 - got, f);
        if (got < size - 1 || got > cap)
            break;
        size *= 2;
    }
    buf[got] = '\0';
    *len = got;
    return buf;
}

cub_err cub_text_read(const cub_text_src *src, char **out, size_t *len, cub_diag *diag)
{
    const char *path = src && src->path ? src->path : "(null)";
    if (!src || !src->path || !out || !len)
        return cub_diag_fail(diag, CUB_ERR_ARG, path, 0, "no path or output");
    const char *what = src->what ? src->what : "file";
    size_t cap = src->max_bytes ? src->max_bytes : CUB_TEXT_MAX_BYTES;
    *out = NULL;
    *len = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return cub_diag_fail(diag, CUB_ERR_IO, path, 0, "cannot open the %s: %s", what,
                             strerror(errno));
    size_t got = 0;
    char *buf = read_all(f, cap, &got);
    int failed = ferror(f);
    fclose(f);
    cub_err e = CUB_OK;
    if (!buf)
        e = cub_diag_fail(diag, CUB_ERR_NOMEM, path, 0, "out of memory reading the %s", what);
    else if (failed)
        e = cub_diag_fail(diag, CUB_ERR_IO, path, 0, "cannot read the %s", what);
    else if (got > cap)
        e = cub_diag_fail(diag, CUB_ERR_FORMAT, path, 0, "larger than %zu bytes (not a %s?)", cap,
                          what);
    if (e) {
        free(buf);
        return e;
    }
    *out = buf;
    *len = got;
    return CUB_OK;
}

cub_err cub_text_parse(const cub_text *t, cub_text_whole_fn parse, const void *in, void *out)
{
    const char *name = t->name ? t->name : "(text)";
    if (!t->s && t->len)
        return cub_diag_fail(t->diag, CUB_ERR_ARG, name, 0, "no text");
    if (!out)
        return cub_diag_fail(t->diag, CUB_ERR_ARG, name, 0, "no output");
    return parse(t, in, out);
}

cub_err cub_text_load(const cub_text_src *src, cub_text_whole_fn parse, const void *in, void *out,
                      cub_diag *diag)
{
    char *s = NULL;
    size_t len = 0;
    cub_err e = cub_text_read(src, &s, &len, diag);
    if (e)
        return e;
    cub_text t = {s, len, src->path, diag};
    e = cub_text_parse(&t, parse, in, out);
    free(s);
    return e;
}

int cub_text_words(char *s, char **words, int max)
{
    int n = 0;
    for (;;) {
        s += strspn(s, BLANKS);
        if (*s == '\0')
            return n;
        if (n == max)
            return max + 1;
        words[n++] = s;
        s += strcspn(s, BLANKS);
        if (*s != '\0')
            *s++ = '\0';
    }
}

/* Room for n bytes and a NUL in *buf. */
static int fit(char **buf, size_t *cap, size_t n)
{
    if (n < *cap)
        return 1;
    size_t want = n + 1 > 2 * *cap ? n + 1 : 2 * *cap;
    char *bigger = realloc(*buf, want);
    if (!bigger)
        return 0;
    *buf = bigger;
    *cap = want;
    return 1;
}

/* Copy line s[0..n) into *buf, without its '\r' and comment, as ln->s. */
static cub_err take_line(const char *s, size_t n, char **buf, size_t *cap, cub_text_line *ln)
{
    if (memchr(s, '\0', n))
        return cub_text_fail(&ln->at, "contains a NUL byte (not a text file?)");
    if (n > 0 && s[n - 1] == '\r')
        n--;
    const char *hash = memchr(s, '#', n);
    if (hash)
        n = (size_t)(hash - s);
    if (!fit(buf, cap, n))
        return cub_diag_fail(ln->at.diag, CUB_ERR_NOMEM, ln->at.name, ln->at.line,
                             "out of memory");
    memcpy(*buf, s, n);
    (*buf)[n] = '\0';
    ln->s = *buf;
    return CUB_OK;
}

cub_err cub_text_lines(const cub_text *t, cub_text_line_fn fn, void *ctx)
{
    const char *name = t->name ? t->name : "(text)";
    if (!t->s && t->len)
        return cub_diag_fail(t->diag, CUB_ERR_ARG, name, 0, "no text");
    if (t->len == 0)
        return CUB_OK;
    char *buf = NULL;
    size_t cap = 0;
    cub_err e = CUB_OK;
    cub_text_line ln = {NULL, {name, 0, t->diag}};
    const char *end = t->s + t->len;
    for (const char *c = t->s; !e && c < end;) {
        const char *nl = memchr(c, '\n', (size_t)(end - c));
        const char *stop = nl ? nl : end;
        ln.at.line++;
        e = take_line(c, (size_t)(stop - c), &buf, &cap, &ln);
        if (!e && ln.s[strspn(ln.s, BLANKS)] != '\0')
            e = fn(ctx, &ln);
        c = nl ? nl + 1 : end; /* never point past the end */
    }
    free(buf);
    return e;
}

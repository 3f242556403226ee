/* Reading hand-written text files and walking their lines (cub/text.h). */
#define _POSIX_C_SOURCE 200809L /* open flags, fdopen */
#include "cub/text.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

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

/* The whole of f, at most cap bytes: grown as it comes from its stated
 * size, so that a large cap costs nothing for a small file. One byte more
 * than the cap is read to tell "exactly full" from "too big" (a file that
 * grew since it was opened); *len > cap means too big. */
static char *read_all(FILE *f, size_t hint, size_t cap, size_t *len)
{
    size_t size = hint + 2 > 64 ? hint + 2 : 64, got = 0;
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

const char *cub_text_size_str(size_t n, char *buf, size_t size)
{
    if (n >= CUB_TEXT_MB && n % CUB_TEXT_MB == 0)
        snprintf(buf, size, "%zu MB", n / CUB_TEXT_MB);
    else if (n >= CUB_TEXT_KB && n % CUB_TEXT_KB == 0)
        snprintf(buf, size, "%zu kB", n / CUB_TEXT_KB);
    else
        snprintf(buf, size, "%zu bytes", n);
    return buf;
}

static const char *kind_of(mode_t m)
{
    return S_ISDIR(m)    ? "a directory"
           : S_ISFIFO(m) ? "a FIFO"
           : S_ISCHR(m)  ? "a character device"
           : S_ISBLK(m)  ? "a block device"
           : S_ISSOCK(m) ? "a socket"
                         : "not a regular file";
}

cub_err cub_text_open(const cub_text_src *src, int *fd_out, size_t *size, cub_diag *diag)
{
    const char *path = src && src->path ? src->path : "(null)";
    if (!src || !src->path || !fd_out || !size)
        return cub_diag_fail(diag, CUB_ERR_ARG, path, 0, "no path or output");
    const char *what = src->what ? src->what : "file";
    size_t cap = src->max_bytes ? src->max_bytes : CUB_TEXT_MAX_BYTES;
    *fd_out = -1;
    *size = 0;
    /* O_NONBLOCK: opening a FIFO would wait for a writer before fstat
     * could tell what it is. */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0)
        return cub_diag_fail(diag, CUB_ERR_IO, path, 0, "cannot open the %s: %s", what,
                             strerror(errno));
    struct stat st;
    char words[32];
    cub_err e = CUB_OK;
    if (fstat(fd, &st) != 0)
        e = cub_diag_fail(diag, CUB_ERR_IO, path, 0, "cannot read the %s: %s", what,
                          strerror(errno));
    else if (!S_ISREG(st.st_mode))
        e = cub_diag_fail(diag, CUB_ERR_IO, path, 0, "cannot read the %s: it is %s, not a file",
                          what, kind_of(st.st_mode));
    else if ((unsigned long long)st.st_size > cap)
        e = cub_diag_fail(diag, CUB_ERR_FORMAT, path, 0,
                          "the %s is %lld bytes, larger than the %s a %s may be", what,
                          (long long)st.st_size, cub_text_size_str(cap, words, sizeof words),
                          what);
    else if (fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK) != 0)
        e = cub_diag_fail(diag, CUB_ERR_IO, path, 0, "cannot read the %s: %s", what,
                          strerror(errno));
    if (e) {
        close(fd);
        return e;
    }
    *fd_out = fd;
    *size = (size_t)st.st_size;
    return CUB_OK;
}

cub_err cub_text_fopen(const cub_text_src *src, FILE **f, size_t *size, cub_diag *diag)
{
    int fd = -1;
    if (f)
        *f = NULL;
    cub_err e = cub_text_open(src, &fd, size, diag);
    if (e)
        return e;
    if (!f) {
        close(fd);
        return CUB_OK;
    }
    *f = fdopen(fd, "rb");
    if (!*f) {
        int er = errno;
        close(fd);
        return cub_diag_fail(diag, CUB_ERR_NOMEM, src->path, 0, "cannot read the %s: %s",
                             src->what ? src->what : "file", strerror(er));
    }
    return CUB_OK;
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
    FILE *f = NULL;
    size_t stated = 0;
    char words[32];
    cub_err e = cub_text_fopen(src, &f, &stated, diag);
    if (e)
        return e;
    size_t got = 0;
    char *buf = read_all(f, stated, cap, &got);
    int failed = ferror(f) ? errno : 0;
    fclose(f);
    if (!buf)
        e = cub_diag_fail(diag, CUB_ERR_NOMEM, path, 0, "out of memory reading the %s", what);
    else if (failed)
        e = cub_diag_fail(diag, CUB_ERR_IO, path, 0, "cannot read the %s: %s", what,
                          strerror(failed));
    else if (got > cap)
        e = cub_diag_fail(diag, CUB_ERR_FORMAT, path, 0, "the %s grew larger than the %s a %s may be",
                          what, cub_text_size_str(cap, words, sizeof words), what);
    if (e) {
        free(buf);
        return e;
    }
    *out = buf;
    *len = got;
    return CUB_OK;
}

/* t without a UTF-8 byte-order mark at its start: editors on phones and
 * Windows save one, invisible, and every parser would trip on its first
 * word. */
size_t cub_text_bom_len(const char *s, size_t len)
{
    return s && len >= 3 && memcmp(s, "\xEF\xBB\xBF", 3) == 0 ? 3 : 0;
}

static cub_text without_bom(const cub_text *t)
{
    cub_text u = *t;
    size_t bom = cub_text_bom_len(u.s, u.len);
    u.s += bom;
    u.len -= bom;
    return u;
}

cub_err cub_text_parse(const cub_text *t, cub_text_whole_fn parse, const void *in, void *out)
{
    const char *name = t->name ? t->name : "(text)";
    if (!t->s && t->len)
        return cub_diag_fail(t->diag, CUB_ERR_ARG, name, 0, "no text");
    if (!out)
        return cub_diag_fail(t->diag, CUB_ERR_ARG, name, 0, "no output");
    cub_text u = without_bom(t);
    return parse(&u, in, out);
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
    cub_text u = without_bom(t);
    const char *end = u.s + u.len;
    for (const char *c = u.s; !e && c < end;) {
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

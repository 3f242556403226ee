/* The tokenizer under the motion parsers and its failure messages.
 * Tokens are runs of non-blank bytes; the input need not be NUL-terminated
 * and may hold anything (CR, NUL, binary): nothing reads past `end`. */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io_internal.h"

static int is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

void io_lex_init(io_lex *lx, const char *text, size_t len, const char *name, cub_diag *diag)
{
    memset(lx, 0, sizeof(*lx));
    lx->p = text;
    lx->end = text + len;
    lx->line = 1;
    lx->at_line_start = 1;
    lx->name = name ? name : "(memory)";
    lx->diag = diag;
}

size_t io_lex_left(const io_lex *lx)
{
    return (size_t)(lx->end - lx->p);
}

/* Skip blanks and comments, counting lines. */
static void skip_space(io_lex *lx)
{
    while (lx->p < lx->end) {
        char c = *lx->p;
        if (c == '\n') {
            lx->line++;
            lx->at_line_start = 1;
        } else if (lx->hash_comments && c == '#') {
            while (lx->p < lx->end && *lx->p != '\n')
                lx->p++;
            continue;
        } else if (!is_blank(c)) {
            return;
        }
        lx->p++;
    }
}

static int is_brace(const io_lex *lx, char c)
{
    return lx->split_braces && (c == '{' || c == '}');
}

int io_lex_next(io_lex *lx, io_tok *t)
{
    skip_space(lx);
    if (lx->p >= lx->end)
        return 0;
    t->s = lx->p;
    t->line = lx->line;
    t->first_on_line = lx->at_line_start;
    lx->at_line_start = 0;
    if (is_brace(lx, *lx->p)) {
        lx->p++;
    } else {
        while (lx->p < lx->end && !is_blank(*lx->p) && !is_brace(lx, *lx->p))
            lx->p++;
    }
    t->n = (size_t)(lx->p - t->s);
    return 1;
}

int io_lex_next_same_line(io_lex *lx, io_tok *t)
{
    skip_space(lx);
    if (lx->p >= lx->end || lx->at_line_start)
        return 0;
    return io_lex_next(lx, t);
}

int io_lex_peek(const io_lex *lx, io_tok *t)
{
    io_lex copy = *lx;
    return io_lex_next(&copy, t);
}

void io_lex_skip_line(io_lex *lx)
{
    while (lx->p < lx->end && *lx->p != '\n')
        lx->p++;
}

int io_tok_is(const io_tok *t, const char *word)
{
    size_t n = strlen(word);
    return t->n == n && memcmp(t->s, word, n) == 0;
}

int io_tok_is_nocase(const io_tok *t, const char *word)
{
    size_t n = strlen(word);
    if (t->n != n)
        return 0;
    for (size_t i = 0; i < n; i++) {
        char a = t->s[i], b = word[i];
        if (a >= 'A' && a <= 'Z')
            a = (char)(a - 'A' + 'a');
        if (b >= 'A' && b <= 'Z')
            b = (char)(b - 'A' + 'a');
        if (a != b)
            return 0;
    }
    return 1;
}

const char *io_tok_show(const io_tok *t, char *buf, size_t size)
{
    size_t max = size > 4 ? size - 4 : 0, n = t->n < 24 ? t->n : 24, o = 0;
    if (size == 0)
        return "";
    buf[o++] = '\'';
    for (size_t i = 0; i < n && o < max; i++) {
        unsigned char c = (unsigned char)t->s[i];
        buf[o++] = (c >= 32 && c < 127) ? (char)c : '?';
    }
    if (t->n > n && o + 3 < size - 1) {
        memcpy(buf + o, "...", 3);
        o += 3;
    }
    if (o < size - 1)
        buf[o++] = '\'';
    buf[o] = '\0';
    return buf;
}

int io_tok_copy(const io_tok *t, char *buf, size_t size)
{
    if (t->n + 1 > size)
        return 0;
    memcpy(buf, t->s, t->n);
    buf[t->n] = '\0';
    return 1;
}

int io_parse_double(const io_tok *t, double *out)
{
    char buf[64];
    if (t->n == 0 || !io_tok_copy(t, buf, sizeof(buf)))
        return 0;
    /* Plain decimal only: strtod would also take "nan", "inf" and hex. */
    for (size_t i = 0; i < t->n; i++) {
        char c = buf[i];
        if (!((c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.' || c == 'e' || c == 'E'))
            return 0;
    }
    char *end = NULL;
    errno = 0;
    *out = strtod(buf, &end);
    if (end != buf + t->n)
        return 0;
    return errno != ERANGE || *out == 0.0; /* underflow to zero is harmless */
}

cub_err io_tok_double(io_lex *lx, const io_tok *t, const char *what, double *out)
{
    char shown[40];
    if (!io_parse_double(t, out))
        return io_fail(lx, t->line, "bad number %s for %s", io_tok_show(t, shown, sizeof(shown)),
                       what);
    return CUB_OK;
}

cub_err io_tok_long(io_lex *lx, const io_tok *t, const char *what, long *out)
{
    char buf[32], shown[40];
    int ok = io_tok_copy(t, buf, sizeof(buf)) && t->n > 0;
    for (size_t i = 0; ok && i < t->n; i++)
        ok = (buf[i] >= '0' && buf[i] <= '9') || (i == 0 && (buf[i] == '-' || buf[i] == '+'));
    if (ok) {
        char *end = NULL;
        errno = 0;
        *out = strtol(buf, &end, 10);
        ok = end == buf + t->n && end != buf && errno != ERANGE;
    }
    if (!ok)
        return io_fail(lx, t->line, "bad integer %s for %s", io_tok_show(t, shown, sizeof(shown)),
                       what);
    return CUB_OK;
}

cub_err io_fail(io_lex *lx, int line, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    cub_err e = cub_diag_vfail(lx->diag, CUB_ERR_FORMAT, lx->name, line, fmt, ap);
    va_end(ap);
    return e;
}

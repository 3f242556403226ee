/* The library recipe (assets/library/recipe.txt): one clip per line,
 *   name kind source map start_s end_s [speed=S] [mirror] [turn=DEG]
 * '#' starts a comment. The format is documented in the recipe's header. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/retarget.h"
#include "rt_internal.h"

#define RECIPE_MAX_WORDS 12
#define RECIPE_WORD_LEN 256

typedef char recipe_word[RECIPE_WORD_LEN];

static int split(const char *s, const char *end, recipe_word *w)
{
    int n = 0;
    while (s < end) {
        while (s < end && (*s == ' ' || *s == '\t' || *s == '\r'))
            s++;
        if (s >= end || *s == '#')
            break;
        const char *b = s;
        while (s < end && *s != ' ' && *s != '\t' && *s != '\r' && *s != '#')
            s++;
        size_t len = (size_t)(s - b);
        if (n >= RECIPE_MAX_WORDS || len >= RECIPE_WORD_LEN)
            return -1;
        memcpy(w[n], b, len);
        w[n][len] = '\0';
        n++;
    }
    return n;
}

/* A time in seconds, or "-" (0: the start / the end of the source). */
static int parse_num(const char *s, double *out)
{
    if (!strcmp(s, "-")) {
        *out = 0;
        return 1;
    }
    char *e = NULL;
    errno = 0;
    *out = strtod(s, &e);
    return e != s && !*e && !errno && isfinite(*out);
}

static cub_err parse_option(cub_recipe_clip *c, const char *w, const char *file, int line,
                            cub_diag *diag)
{
    if (!strcmp(w, "mirror")) {
        c->mirror = 1;
        return CUB_OK;
    }
    if (!strncmp(w, "speed=", 6) && parse_num(w + 6, &c->speed) && c->speed >= 0.1 &&
        c->speed <= 10)
        return CUB_OK;
    if (!strncmp(w, "turn=", 5) && parse_num(w + 5, &c->turn_deg) && fabs(c->turn_deg) <= 360)
        return CUB_OK;
    return cub_diag_fail(diag, CUB_ERR_FORMAT, file, line,
                   "bad option \"%s\" (speed=0.1..10, turn=-360..360, mirror)", w);
}

static cub_err parse_clip(cub_recipe *r, recipe_word *w, int n, const char *file, int line,
                          cub_diag *diag)
{
    if (n < 6)
        return cub_diag_fail(diag, CUB_ERR_FORMAT, file, line,
                       "expected `name kind source map start_s end_s [options]`, got %d words",
                       n);
    if (r->clip_count >= CUB_RECIPE_MAX_CLIPS)
        return cub_diag_fail(diag, CUB_ERR_FORMAT, file, line, "more than %d clips",
                       CUB_RECIPE_MAX_CLIPS);
    cub_recipe_clip *c = &r->clip[r->clip_count];
    memset(c, 0, sizeof(*c));
    c->line = line;
    c->speed = 1;
    if (strlen(w[0]) >= sizeof(c->name))
        return cub_diag_fail(diag, CUB_ERR_FORMAT, file, line, "clip name \"%s\" over %zu characters",
                       w[0], sizeof(c->name) - 1);
    for (int i = 0; i < r->clip_count; i++)
        if (!strcmp(r->clip[i].name, w[0]))
            return cub_diag_fail(diag, CUB_ERR_FORMAT, file, line, "clip \"%s\" already on line %d",
                           w[0], r->clip[i].line);
    if (strcmp(w[1], "dance") && strcmp(w[1], "coach"))
        return cub_diag_fail(diag, CUB_ERR_FORMAT, file, line,
                       "kind \"%s\" is neither dance nor coach", w[1]);
    snprintf(c->name, sizeof(c->name), "%s", w[0]);
    snprintf(c->kind, sizeof(c->kind), "%s", w[1]);
    snprintf(c->source, sizeof(c->source), "%s", w[2]);
    snprintf(c->map, sizeof(c->map), "%s", w[3]);
    if (!parse_num(w[4], &c->start_s) || !parse_num(w[5], &c->end_s) || c->start_s < 0 ||
        (c->end_s > 0 && c->end_s <= c->start_s))
        return cub_diag_fail(diag, CUB_ERR_FORMAT, file, line,
                       "bad time range \"%s\" .. \"%s\" (seconds, start < end, or -)", w[4], w[5]);
    for (int i = 6; i < n; i++) {
        cub_err err = parse_option(c, w[i], file, line, diag);
        if (err)
            return err;
    }
    r->clip_count++;
    return CUB_OK;
}

cub_err cub_recipe_parse(const char *text, size_t len, const char *name, cub_recipe *out,
                         cub_diag *diag)
{
    const char *file = name ? name : "(recipe)";
    if (!out || (!text && len))
        return cub_diag_fail(diag, CUB_ERR_ARG, file, 0, "no text or output");
    memset(out, 0, sizeof(*out));
    recipe_word *w = malloc(sizeof(recipe_word) * RECIPE_MAX_WORDS);
    if (!w)
        return cub_diag_fail(diag, CUB_ERR_NOMEM, file, 0, "out of memory");
    cub_err err = CUB_OK;
    const char *p = text, *end = text + len;
    for (int line = 1; p < end && !err; line++) {
        const char *eol = memchr(p, '\n', (size_t)(end - p));
        if (!eol)
            eol = end;
        int n = memchr(p, '\0', (size_t)(eol - p)) ? -2 : split(p, eol, w);
        if (n == -2)
            err = cub_diag_fail(diag, CUB_ERR_FORMAT, file, line, "NUL byte in the recipe");
        else if (n < 0)
            err = cub_diag_fail(diag, CUB_ERR_FORMAT, file, line, "too many words or a word too long");
        else if (n > 0)
            err = parse_clip(out, w, n, file, line, diag);
        p = eol + 1;
    }
    free(w);
    if (!err && out->clip_count == 0)
        err = cub_diag_fail(diag, CUB_ERR_FORMAT, file, 0, "no clips in the recipe");
    return err;
}

cub_err cub_recipe_load(const char *path, cub_recipe *out, cub_diag *diag)
{
    char *text = NULL;
    size_t len = 0;
    cub_err err = cub_io_read_file(path, &text, &len, diag);
    if (err)
        return err;
    err = cub_recipe_parse(text, len, path, out, diag);
    free(text);
    return err;
}

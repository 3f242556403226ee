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

static cub_err parse_option(cub_recipe_clip *c, const char *w, const cub_text_at *at)
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
    return cub_text_fail(at, "bad option \"%s\" (speed=0.1..10, turn=-360..360, mirror)", w);
}

static cub_err parse_clip(cub_recipe *r, char **w, int n, const cub_text_at *at)
{
    if (n < 6)
        return cub_text_fail(
            at, "expected `name kind source map start_s end_s [options]`, got %d words", n);
    if (r->clip_count >= CUB_RECIPE_MAX_CLIPS)
        return cub_text_fail(at, "more than %d clips", CUB_RECIPE_MAX_CLIPS);
    cub_recipe_clip *c = &r->clip[r->clip_count];
    memset(c, 0, sizeof(*c));
    c->line = at->line;
    c->speed = 1;
    if (strlen(w[0]) >= sizeof(c->name))
        return cub_text_fail(at, "clip name \"%s\" over %zu characters", w[0],
                             sizeof(c->name) - 1);
    for (int i = 0; i < r->clip_count; i++)
        if (!strcmp(r->clip[i].name, w[0]))
            return cub_text_fail(at, "clip \"%s\" already on line %d", w[0], r->clip[i].line);
    if (strcmp(w[1], "dance") && strcmp(w[1], "coach"))
        return cub_text_fail(at, "kind \"%s\" is neither dance nor coach", w[1]);
    snprintf(c->name, sizeof(c->name), "%s", w[0]);
    snprintf(c->kind, sizeof(c->kind), "%s", w[1]);
    snprintf(c->source, sizeof(c->source), "%s", w[2]);
    snprintf(c->map, sizeof(c->map), "%s", w[3]);
    if (!parse_num(w[4], &c->start_s) || !parse_num(w[5], &c->end_s) || c->start_s < 0 ||
        (c->end_s > 0 && c->end_s <= c->start_s))
        return cub_text_fail(at, "bad time range \"%s\" .. \"%s\" (seconds, start < end, or -)",
                             w[4], w[5]);
    for (int i = 6; i < n; i++) {
        cub_err err = parse_option(c, w[i], at);
        if (err)
            return err;
    }
    r->clip_count++;
    return CUB_OK;
}

static cub_err recipe_line(void *ctx, cub_text_line *ln)
{
    char *w[RECIPE_MAX_WORDS];
    int n = cub_text_words(ln->s, w, RECIPE_MAX_WORDS);
    if (n > RECIPE_MAX_WORDS)
        return cub_text_fail(&ln->at, "more than %d words", RECIPE_MAX_WORDS);
    for (int i = 0; i < n; i++)
        if (strlen(w[i]) >= RECIPE_WORD_LEN)
            return cub_text_fail(&ln->at, "a word over %d characters", RECIPE_WORD_LEN - 1);
    return parse_clip(ctx, w, n, &ln->at);
}

static cub_err parse_text(const cub_text *t, const void *in, void *out)
{
    cub_recipe *r = out;
    memset(r, 0, sizeof(*r));
    cub_err err = cub_text_lines(t, recipe_line, r);
    if (!err && r->clip_count == 0)
        err = cub_diag_fail(t->diag, CUB_ERR_FORMAT, t->name, 0, "no clips in the recipe");
    return err;
}

cub_err cub_recipe_parse(const char *text, size_t len, const char *name, cub_recipe *out,
                         cub_diag *diag)
{
    cub_text t = {text, len, name ? name : "(recipe)", diag};
    return cub_text_parse(&t, parse_text, NULL, out);
}

cub_err cub_recipe_load(const char *path, cub_recipe *out, cub_diag *diag)
{
    return cub_text_load(&(cub_text_src){path, "recipe", CUB_TEXT_MAX_SMALL}, parse_text, NULL, out, diag);
}

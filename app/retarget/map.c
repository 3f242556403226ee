/* Mapping tables (assets/retarget/<kind>.map): which source joints drive each
 * target joint. See cub/retarget.h for the format and the model. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/retarget.h"
#include "rt_internal.h"

#define MAP_MAX_WORDS 8

static cub_err parse_source(const char *word, cub_retarget_source *src, const cub_text_at *at)
{
    const char *colon = strchr(word, ':');
    size_t len = colon ? (size_t)(colon - word) : strlen(word);
    if (len == 0 || len >= CUB_MOTION_NAME_LEN)
        return cub_text_fail(at, "bad source joint name \"%s\"", word);
    memcpy(src->name, word, len);
    src->name[len] = '\0';
    src->joint = -1;
    src->weight = 1.0;
    if (colon) {
        char *e = NULL;
        errno = 0;
        src->weight = strtod(colon + 1, &e);
        if (e == colon + 1 || *e || errno || !isfinite(src->weight) || src->weight <= 0)
            return cub_text_fail(at, "bad weight \"%s\" for \"%s\" (a number > 0)", colon + 1,
                                 src->name);
    }
    return CUB_OK;
}

/* Weights that sum to 1. Each is first divided by the largest, so that the
 * sum is at most the source count: 1e308 + 1e308 would be inf, and every
 * weight 0 (a joint that never moves). */
static void normalise(cub_retarget_link *lk, double top)
{
    double sum = 0;
    for (int i = 0; i < lk->source_count; i++) {
        lk->source[i].weight /= top;
        sum += lk->source[i].weight;
    }
    for (int i = 0; i < lk->source_count; i++)
        lk->source[i].weight /= sum;
}

static cub_err parse_line(cub_retarget_map *map, char **words, int n, const cub_text_at *at)
{
    if (n < 2)
        return cub_text_fail(
            at, "expected `TargetJoint SourceJoint [aim|rot]`, got one word \"%s\"", words[0]);
    if (map->link_count >= CUB_MOTION_MAX_JOINTS)
        return cub_text_fail(at, "more than %d links", CUB_MOTION_MAX_JOINTS);
    if (strlen(words[0]) >= CUB_MOTION_NAME_LEN)
        return cub_text_fail(at, "target name \"%s\" too long", words[0]);
    for (int i = 0; i < map->link_count; i++)
        if (!strcmp(map->link[i].target_name, words[0]))
            return cub_text_fail(at, "target joint \"%s\" already linked on line %d", words[0],
                                 map->link[i].line);
    cub_retarget_link *lk = &map->link[map->link_count];
    memset(lk, 0, sizeof(*lk));
    snprintf(lk->target_name, sizeof(lk->target_name), "%s", words[0]);
    lk->target = -1;
    lk->line = at->line;
    if (!strcmp(words[n - 1], "aim") || !strcmp(words[n - 1], "rot")) {
        lk->policy = words[n - 1][0] == 'a' ? CUB_RETARGET_AIM : CUB_RETARGET_ROT;
        n--;
    }
    if (n < 2)
        return cub_text_fail(at, "\"%s\" has no source joint", words[0]);
    if (n - 1 > CUB_RETARGET_MAX_SOURCES)
        return cub_text_fail(at, "more than %d sources for \"%s\"", CUB_RETARGET_MAX_SOURCES,
                             words[0]);
    double top = 0;
    for (int i = 1; i < n; i++) {
        cub_err err = parse_source(words[i], &lk->source[i - 1], at);
        if (err)
            return err;
        top = fmax(top, lk->source[i - 1].weight);
    }
    lk->source_count = n - 1;
    normalise(lk, top);
    map->link_count++;
    return CUB_OK;
}

static cub_err map_line(void *ctx, cub_text_line *ln)
{
    char *words[MAP_MAX_WORDS];
    int n = cub_text_words(ln->s, words, MAP_MAX_WORDS);
    if (n > MAP_MAX_WORDS)
        return cub_text_fail(&ln->at, "more than %d words", MAP_MAX_WORDS);
    return parse_line(ctx, words, n, &ln->at);
}

static cub_err parse_text(const cub_text *t, const void *in, void *out)
{
    cub_retarget_map *map = out;
    memset(map, 0, sizeof(*map));
    snprintf(map->file, sizeof(map->file), "%s", t->name);
    cub_err err = cub_text_lines(t, map_line, map);
    if (!err && map->link_count == 0)
        err = cub_diag_fail(t->diag, CUB_ERR_FORMAT, t->name, 0, "no links in the table");
    return err;
}

cub_err cub_retarget_map_parse(const char *text, size_t len, const char *name,
                               cub_retarget_map *out, cub_diag *diag)
{
    cub_text t = {text, len, name ? name : "(map)", diag};
    return cub_text_parse(&t, parse_text, NULL, out);
}

cub_err cub_retarget_map_load(const char *path, cub_retarget_map *out, cub_diag *diag)
{
    return cub_text_load(&(cub_text_src){path, "retarget map", CUB_TEXT_MAX_SMALL}, parse_text, NULL, out, diag);
}

cub_err cub_retarget_map_bind(cub_retarget_map *map, const cub_skeleton *target,
                              const cub_skeleton *source, cub_diag *diag)
{
    if (!map || !target || !source)
        return cub_diag_fail(diag, CUB_ERR_ARG, "(map)", 0, "no map or skeleton");
    map->bound = 0;
    for (int i = 0; i < map->link_count; i++) {
        cub_retarget_link *lk = &map->link[i];
        lk->target = cub_motion_skeleton_find(target, lk->target_name);
        if (lk->target < 0)
            return cub_diag_fail(diag, CUB_ERR_FORMAT, map->file, lk->line, "no target joint \"%s\"",
                           lk->target_name);
        for (int s = 0; s < lk->source_count; s++) {
            lk->source[s].joint = cub_motion_skeleton_find(source, lk->source[s].name);
            if (lk->source[s].joint < 0)
                return cub_diag_fail(diag, CUB_ERR_FORMAT, map->file, lk->line,
                               "no source joint \"%s\" in the source skeleton",
                               lk->source[s].name);
        }
    }
    for (int i = 0; i < map->link_count; i++) {
        const cub_retarget_link *lk = &map->link[i];
        int child = 0;
        for (int k = 0; k < map->link_count && lk->policy == CUB_RETARGET_AIM; k++)
            child |= target->joints[map->link[k].target].parent == lk->target;
        if (lk->policy == CUB_RETARGET_AIM && !child)
            return cub_diag_fail(diag, CUB_ERR_FORMAT, map->file, lk->line,
                           "\"%s\" is marked aim but no child of it is linked", lk->target_name);
    }
    map->bound = 1;
    return CUB_OK;
}

int cub_retarget_map_find(const cub_retarget_map *map, int target)
{
    for (int i = 0; map && i < map->link_count; i++)
        if (map->link[i].target == target)
            return i;
    return -1;
}

/* coachlib: the shipped library + tags + bear -> the firmware's bridge
 * table (see cub/coachlib.h). */
#define _XOPEN_SOURCE 700
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cub/coachlib.h"

static cub_err fail(cub_diag *diag, const char *file, cub_err e, const char *fmt, ...)
{
    const char *base = strrchr(file, '/');
    va_list ap;
    va_start(ap, fmt);
    e = cub_diag_vfail(diag, e, base ? base + 1 : file, 0, fmt, ap);
    va_end(ap);
    return e;
}

/* The bear's feature joints, found by name in the library's skeleton (the
 * library is retargeted onto the bear, but its skeleton is its own copy).
 * A joint the library lacks is the character's fault (a character the
 * library was not built for), so the message names the character file. */
static cub_err map_body(const cub_character *bear, const cub_skeleton *to, const char *lib_path,
                        const char *bear_path, cub_fuzzy_body *out, cub_diag *diag)
{
    const char *lib_base = strrchr(lib_path, '/');
    *out = bear->body;
    int16_t *idx[] = {&out->hip_centre, &out->spine,    &out->shoulder_centre, &out->head,
                      &out->shoulder[0], &out->shoulder[1], &out->elbow[0],   &out->elbow[1],
                      &out->wrist[0],    &out->wrist[1],    &out->hip[0],     &out->hip[1],
                      &out->knee[0],     &out->knee[1],     &out->ankle[0],   &out->ankle[1]};
    for (size_t i = 0; i < sizeof idx / sizeof *idx; i++) {
        int j = *idx[i];
        if (j < 0) continue;
        const char *name = bear->skel.joints[j].name;
        int k = cub_motion_skeleton_find(to, name);
        if (k < 0)
            return cub_diag_fail(diag, CUB_ERR_FORMAT, bear_path, 0,
                                 "the character's joint '%s' (its features read it) is not in "
                                 "the skeleton of the clip library %s: a library built for "
                                 "another character",
                                 name, lib_base ? lib_base + 1 : lib_path);
        *idx[i] = (int16_t)k;
    }
    return CUB_OK;
}

static cub_err add_clips(cub_coachlib *cl, const char *tags_path, cub_diag *diag)
{
    for (int c = 0; c < cl->lib.clip_count; c++) {
        const cub_tag_clip *tc = &cl->tags.clips[c];
        int *frames = malloc(sizeof(int) * (size_t)(tc->bridge_count + 1));
        if (!frames) return fail(diag, tags_path, CUB_ERR_NOMEM, "out of memory");
        for (int i = 0; i < tc->bridge_count; i++)
            frames[i] = tc->bridges[i].frame;
        cub_err e = cub_bridge_table_add_clip(&cl->table, &cl->lib.clips[c].clip, frames,
                                              tc->bridge_count, NULL);
        free(frames);
        if (e)
            return fail(diag, tags_path, e,
                        "clip '%s': the bridge table refused it (%s): bad bridge frames or a "
                        "pose the bear's features cannot read",
                        tc->name, cub_err_str(e));
    }
    return CUB_OK;
}

static cub_err add_links(cub_coachlib *cl, const char *tags_path, cub_diag *diag)
{
    int n = cl->lib.clip_count;
    for (int from = 0; from < n; from++)
        for (int to = 0; to < n; to++) {
            const cub_tag_pair *pair = &cl->tags.pairs[from * n + to];
            cub_bridge_link *links = malloc(sizeof *links * (size_t)(pair->link_count + 1));
            if (!links) return fail(diag, tags_path, CUB_ERR_NOMEM, "out of memory");
            for (int i = 0; i < pair->link_count; i++) {
                const cub_tag_link *l = &pair->links[i];
                links[i] = (cub_bridge_link){.a = (int16_t)l->a, .b = (int16_t)l->b,
                                             .back = l->half == CUB_TAG_BACK, .d = l->d};
            }
            cub_err e = cub_bridge_table_set_links(&cl->table, from, to, links, pair->link_count);
            free(links);
            if (e)
                return fail(diag, tags_path, e, "links from '%s' to '%s' refused by the table (%s)",
                            cl->tags.clips[from].name, cl->tags.clips[to].name, cub_err_str(e));
        }
    return CUB_OK;
}

static cub_err build_table(cub_coachlib *cl, const char *lib_path, const char *tags_path,
                           const char *bear_path, cub_diag *diag)
{
    cub_bridge_table_desc d = {.skel = &cl->lib.skel, .fuzzy = cl->tags.params.fuzzy,
                               .clip_count = cl->lib.clip_count};
    cub_err e = map_body(&cl->bear, &cl->lib.skel, lib_path, bear_path, &d.body, diag);
    if (e) return e;
    for (int c = 0; c < cl->lib.clip_count; c++) {
        d.frame_total += cl->lib.clips[c].clip.frame_count;
        d.bridge_total += cl->tags.clips[c].bridge_count;
    }
    for (int i = 0; i < cl->lib.clip_count * cl->lib.clip_count; i++)
        d.link_total += cl->tags.pairs[i].link_count;
    size_t size = cub_bridge_table_mem_size(&d);
    if (size == 0) return fail(diag, lib_path, CUB_ERR_FORMAT, "an empty clip library");
    cl->table_mem = malloc(size);
    if (!cl->table_mem) return fail(diag, lib_path, CUB_ERR_NOMEM, "out of memory");
    e = cub_bridge_table_init(&cl->table, &d, cl->table_mem, size);
    if (e)
        return fail(diag, lib_path, e, "cannot set up the bridge table (%s)", cub_err_str(e));
    if ((e = add_clips(cl, tags_path, diag)) || (e = add_links(cl, tags_path, diag))) return e;
    return cub_bridge_table_finish(&cl->table);
}

/* The routes file beside the tags: X.tags.xml -> X.routes.txt. A missing
 * file is no routes (a tagging of its own has none); a bad one fails, and
 * anything else at that name (a FIFO, a folder, a link loop) is refused by
 * the reader without blocking. */
static cub_err load_routes(cub_coachlib *cl, const char *tags_path, cub_diag *diag)
{
    static const char ext[] = ".tags.xml";
    size_t n = strlen(tags_path), e_len = sizeof ext - 1;
    char path[1024];
    if (n < e_len || strcmp(tags_path + n - e_len, ext) || n - e_len + 12 > sizeof path)
        return CUB_OK;
    snprintf(path, sizeof path, "%.*s.routes.txt", (int)(n - e_len), tags_path);
    struct stat st;
    if (lstat(path, &st) != 0) return CUB_OK; /* none: cub_text refuses FIFOs, folders, loops */
    cl->routes = malloc(sizeof *cl->routes);
    if (!cl->routes) return fail(diag, path, CUB_ERR_NOMEM, "out of memory");
    cub_err e = cub_routes_read(path, &cl->lib, cl->routes, diag);
    if (e) return e;
    e = cub_bridge_table_set_routes(&cl->table, cl->routes->route, cl->routes->count);
    if (e) return fail(diag, path, e, "the bridge table refused the routes (%s)", cub_err_str(e));
    return CUB_OK;
}

cub_err cub_coachlib_load(const char *library_path, const char *tags_path,
                          const char *bear_path, cub_coachlib *out, cub_diag *diag)
{
    if (!out) return CUB_ERR_ARG;
    memset(out, 0, sizeof *out);
    if (!library_path || !tags_path || !bear_path)
        return fail(diag, "coachlib", CUB_ERR_ARG, "a path is missing");
    cub_err e = cub_character_load(bear_path, &out->bear, diag);
    if (!e) e = cub_pack_read(library_path, &out->lib, diag);
    if (!e) e = cub_tags_read(tags_path, &out->lib, &out->tags, diag);
    if (!e) e = build_table(out, library_path, tags_path, bear_path, diag);
    if (!e) e = load_routes(out, tags_path, diag);
    out->tween_index = -1;
    if (e) cub_coachlib_free(out);
    return e;
}

cub_err cub_coachlib_load_assets(const char *assets_dir, cub_coachlib *out, cub_diag *diag)
{
    char lib[1024], tags[1024], bear[1024];
    if (!assets_dir || !out) return CUB_ERR_ARG;
    snprintf(lib, sizeof lib, "%s/clips/bear.cubclips", assets_dir);
    snprintf(tags, sizeof tags, "%s/clips/bear.tags.xml", assets_dir);
    snprintf(bear, sizeof bear, "%s/bear/bear.xml", assets_dir);
    return cub_coachlib_load(lib, tags, bear, out, diag);
}

int cub_coachlib_find(const cub_coachlib *cl, const char *name)
{
    return cl && name ? cub_library_find(&cl->lib, name) : -1;
}

void cub_coachlib_free(cub_coachlib *cl)
{
    if (!cl) return;
    cub_tags_free(&cl->tags);
    cub_library_free(&cl->lib);
    free(cl->table_mem);
    free(cl->tween_mem);
    free(cl->routes);
    memset(cl, 0, sizeof *cl);
}

#include "join_src.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int ends_with(const char *s, const char *tail)
{
    size_t n = strlen(s), k = strlen(tail);
    return n >= k && !strcmp(s + n - k, tail);
}

static int add_clip(join_src *s, const char *path, const char *name, const cub_clip *clip,
                    const char *kind)
{
    if (s->db.count >= (int)(sizeof s->kind / sizeof *s->kind)) {
        fprintf(stderr, "%s: more than %zu clips\n", path, sizeof s->kind / sizeof *s->kind);
        return -1;
    }
    s->kind[s->db.count] = kind;
    cub_err e = cub_join_db_add(&s->db, name, clip, NULL);
    if (e == CUB_ERR_ARG) {
        fprintf(stderr,
                "%s: clip '%s' is not on the skeleton of the first file, or shorter "
                "than two windows (%d frames)\n",
                path, name, 2 * s->db.cfg.window_frames);
        return -1;
    }
    if (e) {
        fprintf(stderr, "%s: out of memory\n", path);
        return -1;
    }
    return 0;
}

/* The db on the first file's skeleton. */
static int start_db(join_src *s, const char *path, const cub_skeleton *skel,
                    const cub_join_cfg *cfg)
{
    if (s->db.skel) return 0;
    cub_diag d = {0};
    char msg[600];
    if (cub_join_db_init(&s->db, skel, cfg, &d)) {
        fprintf(stderr, "%s: %s\n", path, cub_diag_str(&d, msg, sizeof msg));
        return -1;
    }
    return 0;
}

static int add_library(join_src *s, const char *path, const cub_join_cfg *cfg)
{
    cub_diag d = {0};
    char msg[600];
    cub_library *lib = &s->lib[s->nlib];
    if (cub_pack_read(path, lib, &d)) {
        fprintf(stderr, "%s\n", cub_diag_str(&d, msg, sizeof msg));
        return -1;
    }
    s->nlib++;
    if (start_db(s, path, &lib->skel, cfg)) return -1;
    for (int i = 0; i < lib->clip_count; i++)
        if (add_clip(s, path, lib->clips[i].name, &lib->clips[i].clip, lib->clips[i].kind))
            return -1;
    return 0;
}

static int add_bvh(join_src *s, const char *path, const cub_join_cfg *cfg)
{
    cub_diag d = {0};
    char msg[600];
    cub_io_desc desc = {0};
    cub_io_motion *m = calloc(1, sizeof *m);
    if (!m || cub_io_load_bvh(path, &desc, m, &d)) {
        fprintf(stderr, "%s\n", m ? cub_diag_str(&d, msg, sizeof msg) : "out of memory");
        free(m);
        return -1;
    }
    s->bvh[s->nbvh++] = m;
    if (start_db(s, path, &m->skel, cfg)) return -1;
    const char *base = strrchr(path, '/');
    return add_clip(s, path, base ? base + 1 : path, &m->clip, "bvh");
}

int join_src_add(join_src *s, const char *path, const cub_join_cfg *cfg)
{
    if (s->nlib >= JOIN_SRC_MAX || s->nbvh >= JOIN_SRC_MAX) {
        fprintf(stderr, "%s: more than %d files\n", path, JOIN_SRC_MAX);
        return -1;
    }
    if (ends_with(path, ".cubclips")) return add_library(s, path, cfg);
    if (ends_with(path, ".bvh")) return add_bvh(s, path, cfg);
    fprintf(stderr, "%s: not a clip library (.cubclips) or a BVH file\n", path);
    return -1;
}

int join_src_find(join_src *s, const char *name_or_path, const cub_join_cfg *cfg)
{
    for (int i = 0; i < s->db.count; i++)
        if (!strcmp(s->db.clips[i].name, name_or_path)) return i;
    if (ends_with(name_or_path, ".bvh")) {
        if (add_bvh(s, name_or_path, cfg)) return -1;
        return s->db.count - 1;
    }
    fprintf(stderr,
            "join: no clip named '%s' in the database (a library clip's name, or a "
            ".bvh on its skeleton)\n",
            name_or_path);
    return -1;
}

void join_src_free(join_src *s)
{
    cub_join_db_free(&s->db);
    for (int i = 0; i < s->nlib; i++)
        cub_library_free(&s->lib[i]);
    for (int i = 0; i < s->nbvh; i++) {
        cub_io_motion_free(s->bvh[i]);
        free(s->bvh[i]);
    }
    memset(s, 0, sizeof *s);
}

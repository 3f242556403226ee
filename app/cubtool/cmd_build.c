/* cubtool build — rebuild the clip library the box ships from its recipe
 * (assets/library/recipe.txt) and the shared data: load each source, cut,
 * retarget to the bear at 30 fps, pack (cub/pack.h). Deterministic: clips
 * in recipe order, no time stamps, so the same inputs give the same bytes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "tool_util.h"
#include "cub/character.h"
#include "cub/keys.h"
#include "cub/pack.h"
#include "cub/retarget.h"

typedef struct build_args {
    const char *data, *recipe, *out, *bear, *root, *sheets;
} build_args;

static void usage(FILE *f)
{
    fprintf(f,
            "usage: cubtool build [--data DIR] [--recipe FILE] [--out FILE] [options]\n"
            "\n"
            "Rebuilds the bear's clip library from the recipe: every clip's source is\n"
            "loaded from the data dir (mocap) or the source tree (keyframes), cut,\n"
            "retargeted to the bear at 30 fps and packed. Progress on stderr, one\n"
            "summary line per clip on stdout.\n"
            "\n"
            "  --data DIR      the shared data (default $CUB_DATA_DIR, else %s)\n"
            "  --recipe FILE   (default %s/library/recipe.txt)\n"
            "  --out FILE      (default %s/clips/bear.cubclips)\n"
            "  --bear FILE     the character (default %s/bear/bear.xml)\n"
            "  --root DIR      the source tree recipe paths under assets/ are relative to\n"
            "                  (default %s/..)\n"
            "  --sheets DIR    also write a PNG contact sheet per clip into DIR\n"
            "  --help          this text\n",
            CUB_DATA_DIR_DEFAULT, CUB_ASSETS_DIR, CUB_ASSETS_DIR, CUB_ASSETS_DIR, CUB_ASSETS_DIR);
}

static int parse_args(int argc, char **argv, build_args *a)
{
    const char *env = getenv("CUB_DATA_DIR");
    a->data = env && *env ? env : CUB_DATA_DIR_DEFAULT;
    a->recipe = CUB_ASSETS_DIR "/library/recipe.txt";
    a->out = CUB_ASSETS_DIR "/clips/bear.cubclips";
    a->bear = CUB_ASSETS_DIR "/bear/bear.xml";
    a->root = CUB_ASSETS_DIR "/..";
    a->sheets = NULL;
    for (int i = 1; i < argc; i++) {
        const char *o = argv[i];
        const char **str = !strcmp(o, "--data")     ? &a->data
                           : !strcmp(o, "--recipe") ? &a->recipe
                           : !strcmp(o, "--out")    ? &a->out
                           : !strcmp(o, "--bear")   ? &a->bear
                           : !strcmp(o, "--root")   ? &a->root
                           : !strcmp(o, "--sheets") ? &a->sheets
                                                    : NULL;
        if (!strcmp(o, "--help") || !strcmp(o, "-h")) {
            usage(stdout);
            return 1;
        }
        if (!str || i + 1 >= argc) {
            fprintf(stderr, "cubtool build: unexpected '%s'\n", o);
            usage(stderr);
            return 2;
        }
        *str = argv[++i];
    }
    return 0;
}

/* A recipe path: under the source tree when it starts with "assets/",
 * else under the data dir. */
static void resolve(const build_args *a, const char *rel, char *out, size_t size)
{
    snprintf(out, size, "%s/%s", strncmp(rel, "assets/", 7) ? a->data : a->root, rel);
}

static cub_err load_source(const build_args *a, const cub_recipe_clip *rc, cub_io_motion *src,
                           cub_diag *d)
{
    char path[600], amc[600];
    resolve(a, rc->source, path, sizeof(path));
    char *plus = strchr(path, '+'); /* dir/13.asf+13_17.amc: the AMC beside the ASF */
    if (!plus)
        return cub_retarget_load_source(path, NULL, src, d);
    *plus = '\0';
    const char *slash = strrchr(path, '/');
    snprintf(amc, sizeof(amc), "%.*s%s", slash ? (int)(slash - path + 1) : 0, path, plus + 1);
    return cub_retarget_load_source(path, amc, src, d);
}

/* A keyframe clip, authored on the bear: no retargeting, copied into *out
 * so every clip of the library is owned the same way. */
static cub_err keys_clip(const char *path, const cub_character *bear, cub_io_motion *out,
                         cub_diag *d)
{
    cub_keys_clip k;
    memset(&k, 0, sizeof(k));
    memset(out, 0, sizeof(*out));
    cub_err err = cub_keys_load(path, &bear->skel, &k, d);
    if (err)
        return err;
    out->skel = bear->skel;
    out->unit_mm = 10.0;
    int jn = bear->skel.joint_count, fn = k.clip.frame_count;
    size_t size = cub_motion_clip_mem_size(jn, fn, 0);
    out->frame_mem = malloc(size ? size : 1);
    err = out->frame_mem ? cub_motion_clip_init(&out->clip, &out->skel, fn, k.clip.frame_ns, 0,
                                                out->frame_mem, size)
                         : CUB_ERR_NOMEM;
    if (!err) {
        memcpy(out->clip.root_mm, k.clip.root_mm, sizeof(cub_vec3) * (size_t)fn);
        memcpy(out->clip.rot, k.clip.rot, sizeof(cub_quat) * (size_t)fn * (size_t)jn);
    } else {
        snprintf(d->file, sizeof(d->file), "%.255s", path);
        d->line = 0;
        snprintf(d->msg, sizeof(d->msg), "cannot copy the clip: %s", cub_err_str(err));
    }
    cub_keys_free(&k);
    return err;
}

/* The largest local rotation change of any joint between two frames, in
 * degrees: the retarget measures this for mocap; keyframed clips get the
 * same figure so a too-fast key shows up in the build summary. */
static double max_joint_step_deg(const cub_clip *clip)
{
    const double one = (double)(1 << 30); /* Q2.30 */
    int jn = clip->skel->joint_count;
    double max_deg = 0;
    for (int f = 1; f < clip->frame_count; f++)
        for (int j = 0; j < jn; j++) {
            cub_quat a = clip->rot[(size_t)f * (size_t)jn + (size_t)j];
            cub_quat b = clip->rot[(size_t)(f - 1) * (size_t)jn + (size_t)j];
            double dot = ((double)a.w * b.w + (double)a.x * b.x + (double)a.y * b.y +
                          (double)a.z * b.z) / (one * one);
            dot = fabs(dot) > 1 ? 1 : fabs(dot); /* q and -q are one rotation */
            max_deg = fmax(max_deg, 2 * acos(dot) * 180.0 / 3.14159265358979323846);
        }
    return max_deg;
}

/* One recipe line to a bear clip in *out. */
static cub_err build_clip(const build_args *a, const cub_recipe_clip *rc,
                          const cub_character *bear, cub_retarget_map *map, cub_io_motion *out,
                          cub_retarget_report *rep, cub_diag *d)
{
    char path[600];
    size_t n = strlen(rc->source);
    if (n > 5 && !strcmp(rc->source + n - 5, ".keys")) {
        memset(rep, 0, sizeof(*rep));
        resolve(a, rc->source, path, sizeof(path));
        cub_err err = keys_clip(path, bear, out, d);
        if (!err)
            rep->frames = out->clip.frame_count, rep->max_ang_deg = max_joint_step_deg(&out->clip);
        return err;
    }
    resolve(a, rc->map, path, sizeof(path));
    cub_err err = cub_retarget_map_load(path, map, d);
    cub_io_motion src;
    memset(&src, 0, sizeof(src));
    if (!err)
        err = load_source(a, rc, &src, d);
    if (!err)
        err = cub_retarget_map_bind(map, &bear->skel, &src.skel, d);
    if (!err) {
        cub_retarget_desc desc = {0};
        desc.start_s = rc->start_s;
        desc.end_s = rc->end_s;
        desc.speed = rc->speed;
        desc.mirror = rc->mirror;
        desc.turn_deg = rc->turn_deg;
        desc.name = rc->source;
        err = cub_retarget_clip(map, &bear->skel, &src.clip, &desc, out, rep, d);
    }
    cub_io_motion_free(&src);
    return err;
}

static int report_fail(const char *what, const cub_diag *d)
{
    char buf[600];
    fprintf(stderr, "cubtool build: %s: %s\n", what, cub_diag_str(d, buf, sizeof(buf)));
    return 1;
}

static int write_sheet(const build_args *a, const char *name, const cub_clip *clip)
{
    char path[600];
    snprintf(path, sizeof(path), "%s/%s.png", a->sheets, name);
    if (cub_retarget_sheet_png(path, clip, 8)) {
        fprintf(stderr, "cubtool build: cannot write %s\n", path);
        return 1;
    }
    return 0;
}

static int build_all(const build_args *a, const cub_recipe *r, const cub_character *bear,
                     cub_retarget_map *map, cub_io_motion *outs, cub_library *lib)
{
    cub_diag d;
    memset(&d, 0, sizeof(d));
    int total = 0;
    for (int i = 0; i < r->clip_count; i++) {
        const cub_recipe_clip *rc = &r->clip[i];
        cub_retarget_report rep;
        char where[300];
        fprintf(stderr, "cubtool build: [%d/%d] %s <- %s\n", i + 1, r->clip_count, rc->name,
                rc->source);
        if (build_clip(a, rc, bear, map, &outs[i], &rep, &d)) {
            snprintf(where, sizeof(where), "%.200s:%d (%s)", a->recipe, rc->line, rc->name);
            return report_fail(where, &d);
        }
        cub_library_clip *lc = &lib->clips[i];
        snprintf(lc->name, sizeof(lc->name), "%s", rc->name);
        snprintf(lc->kind, sizeof(lc->kind), "%s", rc->kind);
        lc->clip = outs[i].clip;
        lc->clip.skel = &lib->skel;
        lib->clip_count = i + 1;
        total += lc->clip.frame_count;
        printf("clip %-14s %-5s frames=%4d seconds=%5.2f contacts=%d/%d slide_max_mm=%.2f "
               "max_ang_deg=%.1f\n",
               lc->name, lc->kind, lc->clip.frame_count,
               (double)cub_motion_clip_duration_us(&lc->clip) / 1e6, rep.contact_frames[0],
               rep.contact_frames[1], rep.slide_max_mm, rep.max_ang_deg);
        if (a->sheets && write_sheet(a, rc->name, &lc->clip))
            return 1;
    }
    if (cub_pack_write(a->out, lib, &d))
        return report_fail("pack", &d);
    printf("library %s: clips=%d frames=%d seconds=%.1f\n", a->out, lib->clip_count, total,
           total / 30.0);
    return 0;
}

int cub_cmd_build(int argc, char **argv)
{
    build_args a;
    int rc = parse_args(argc, argv, &a);
    if (rc)
        return rc == 1 ? 0 : 2;
    if (a.sheets && cub_tool_make_dir(a.sheets, "cubtool build"))
        return 1;
    cub_diag d;
    memset(&d, 0, sizeof(d));
    cub_recipe *r = calloc(1, sizeof(*r));
    cub_character *bear = calloc(1, sizeof(*bear));
    cub_retarget_map *map = calloc(1, sizeof(*map));
    cub_library *lib = calloc(1, sizeof(*lib));
    cub_io_motion *outs = calloc(CUB_RECIPE_MAX_CLIPS, sizeof(*outs));
    cub_library_clip *clips = calloc(CUB_RECIPE_MAX_CLIPS, sizeof(*clips));
    rc = 1;
    if (!r || !bear || !map || !lib || !outs || !clips)
        fprintf(stderr, "cubtool build: out of memory\n");
    else if (cub_recipe_load(a.recipe, r, &d))
        report_fail("recipe", &d);
    else if (cub_character_load(a.bear, bear, &d))
        report_fail("bear", &d);
    else {
        lib->skel = bear->skel;
        lib->clips = clips;
        rc = build_all(&a, r, bear, map, outs, lib);
    }
    for (int i = 0; outs && i < CUB_RECIPE_MAX_CLIPS; i++)
        cub_io_motion_free(&outs[i]);
    free(outs), free(clips), free(lib), free(map), free(bear), free(r);
    return rc;
}

/* play_src — loading what `cubtool play` shows (see play_src.h). */
#include "play_src.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/ase.h"
#include "cub/retarget.h"

static int ends_with(const char *s, const char *tail)
{
    size_t n = strlen(s), m = strlen(tail);
    return n >= m && !strcmp(s + n - m, tail);
}

int play_src_is_amc(const char *path) { return ends_with(path, ".amc"); }

static int fail(const cub_diag *d)
{
    char buf[600];
    fprintf(stderr, "cubtool play: %s\n", cub_diag_str(d, buf, sizeof buf));
    return 1;
}

/* "dir/x.cubclips:name" -> the pack path and the clip's name. */
static int split_pack(const char *spec, char *pack, size_t size, const char **clip)
{
    const char *colon = strrchr(spec, ':');
    if (!colon || (size_t)(colon - spec) >= size) return 0;
    snprintf(pack, size, "%.*s", (int)(colon - spec), spec);
    *clip = colon + 1;
    return ends_with(pack, ".cubclips");
}

static int load_pack_clip(play_src *s, const char *pack, const char *name)
{
    cub_diag d = {0};
    if (cub_pack_read(pack, &s->lib, &d)) return fail(&d);
    int i = cub_library_find(&s->lib, name);
    if (i < 0) {
        fprintf(stderr, "cubtool play: %s: no clip named '%s'; it has:", pack, name);
        for (int c = 0; c < s->lib.clip_count; c++) fprintf(stderr, " %s", s->lib.clips[c].name);
        fprintf(stderr, "\n");
        return 1;
    }
    s->clip = &s->lib.clips[i].clip;
    snprintf(s->name, sizeof s->name, "%s", name);
    return 0;
}

static int load_file(play_src *s)
{
    cub_diag d = {0};
    const char *base = strrchr(s->path, '/');
    snprintf(s->name, sizeof s->name, "%s", base ? base + 1 : s->path);
    if (ends_with(s->path, ".asf") && !s->amc_path) {
        fprintf(stderr, "cubtool play: %s: an ASF skeleton needs its .amc motion after it\n", s->path);
        return 1;
    }
    if (ends_with(s->path, ".ase")) {
        if (cub_ase_load(s->path, NULL, &s->motion, &d)) return fail(&d);
        s->clip = &s->motion.clip;
        return 0;
    }
    if (!ends_with(s->path, ".bvh") && !ends_with(s->path, ".asf")) {
        fprintf(stderr,
                "cubtool play: %s: not a .bvh, an .ase, a .trc, an .asf + .amc pair or "
                "PACK.cubclips:CLIP\n",
                s->path);
        return 1;
    }
    if (cub_retarget_load_source(s->path, s->amc_path, &s->motion, &d)) return fail(&d);
    s->clip = &s->motion.clip;
    return 0;
}

/* The bear's own skeleton, as the renderer sees it: every joint of the bear
 * (end sites aside) is in skel by name, under the parent of the same name.
 * Returns the first bear joint that is not, or NULL. */
static const char *not_on_bear(const cub_skeleton *skel, const cub_skeleton *bear)
{
    for (int j = 0; j < bear->joint_count; j++) {
        const cub_joint *bj = &bear->joints[j];
        if (bj->is_end_site) continue;
        int k = cub_motion_skeleton_find(skel, bj->name);
        int kp = k >= 0 ? skel->joints[k].parent : -1;
        const char *want = bj->parent >= 0 ? bear->joints[bj->parent].name : NULL;
        if (k < 0 || (want ? kp < 0 || strcmp(skel->joints[kp].name, want) : kp >= 0)) return bj->name;
    }
    return NULL;
}

/* The clip onto the bear through the mapping table at map_path; the
 * retargeted clip replaces the loaded one. */
static int retarget(play_src *s, const cub_character *bear, const char *map_path)
{
    cub_diag d = {0};
    cub_retarget_map *map = calloc(1, sizeof *map); /* ~40 KB */
    cub_io_motion out = {0};
    int rc = 1;
    cub_retarget_desc desc = {.name = s->name};
    if (!map)
        fprintf(stderr, "cubtool play: out of memory\n");
    else if (cub_retarget_map_load(map_path, map, &d) || cub_retarget_map_bind(map, &bear->skel, s->clip->skel, &d) ||
             cub_retarget_clip(map, &bear->skel, s->clip, &desc, &out, NULL, &d))
        fail(&d);
    else
        rc = 0;
    free(map);
    if (rc) return 1;
    cub_io_motion_free(&s->motion);
    cub_library_free(&s->lib);
    s->motion = out;
    s->motion.clip.skel = &s->motion.skel; /* the struct moved */
    s->clip = &s->motion.clip;
    return 0;
}

static float rest_height_mm(const cub_skeleton *skel)
{
    cub_pose rest;
    static cub_vec3 world[CUB_MOTION_MAX_JOINTS];
    cub_motion_pose_rest(skel, &rest);
    float lo = 0.0f, hi = 0.0f;
    if (cub_motion_forward(skel, &rest, world, NULL) == CUB_OK)
        for (int j = 0; j < skel->joint_count; j++) {
            float y = (float)world[j].y / 65536.0f;
            lo = j == 0 || y < lo ? y : lo;
            hi = j == 0 || y > hi ? y : hi;
        }
    return hi - lo > 1.0f ? hi - lo : 1700.0f;
}

static int pick_figure(play_src *s, play_figure want, const cub_character *bear, const char *map_path)
{
    if (want == PLAY_FIGURE_STICK || !bear) {
        if (want == PLAY_FIGURE_BEAR) fprintf(stderr, "cubtool play: %s: no character loaded, stick figure\n", s->name);
        return 0;
    }
    const char *missing = not_on_bear(s->clip->skel, &bear->skel);
    if (!missing) {
        s->on_bear = 1;
    } else if (map_path) {
        if (retarget(s, bear, map_path)) return 1;
        s->on_bear = 1;
    } else {
        fprintf(stderr,
                "cubtool play: %s: not on the bear's skeleton (no joint '%s' where the bear has it), so it "
                "plays on the stick figure; --map FILE (assets/retarget/*.map) retargets it onto the bear\n",
                s->name, missing);
    }
    return 0;
}

/* A .trc: markers only, as points; its height from the first frame. */
static int load_trc(play_src *s)
{
    cub_diag d = {0};
    const char *base = strrchr(s->path, '/');
    snprintf(s->name, sizeof s->name, "%s", base ? base + 1 : s->path);
    if (cub_trc_load(s->path, &s->trc, &d)) return fail(&d);
    float lo = 0.0f, hi = 0.0f;
    int any = 0;
    for (int m = 0; m < s->trc.markers; m++) {
        if (!s->trc.present[m]) continue;
        float y = s->trc.pos[3 * m + 1];
        lo = !any || y < lo ? y : lo;
        hi = !any || y > hi ? y : hi;
        any = 1;
    }
    s->height_mm = hi - lo > 1.0f ? hi - lo : 1700.0f;
    return 0;
}

double play_src_seconds(const play_src *s)
{
    if (!s->clip) return s->trc.frames > 1 ? (s->trc.frames - 1) / s->trc.rate : 0.0;
    return (double)cub_motion_clip_duration_us(s->clip) * 1e-6;
}

/* Markers at t_s: the frame before t (no blending: a marker lost in the
 * next frame would have nothing to blend with). */
static int sample_trc(const cub_trc *t, double t_s, int once, float *xyz)
{
    long f = lround(floor(t_s * t->rate));
    if (once)
        f = f < 0 ? 0 : f >= t->frames ? t->frames - 1 : f;
    else
        f = ((f % t->frames) + t->frames) % t->frames;
    for (int m = 0; m < t->markers; m++) {
        size_t i = (size_t)f * (size_t)t->markers + (size_t)m;
        for (int k = 0; k < 3; k++)
            xyz[3 * m + k] = t->present[i] ? t->pos[3 * i + (size_t)k] : NAN;
    }
    return t->markers;
}

int play_src_sample(const play_src *s, double t_s, int once, float *xyz)
{
    if (!s->clip) return sample_trc(&s->trc, t_s, once, xyz);
    static cub_pose pose;
    static cub_vec3 world[CUB_MOTION_MAX_JOINTS];
    int64_t t_us = (int64_t)llround(t_s * 1e6);
    /* World positions by the seed's M_i = M_parent T_i R_i (cub_motion_forward). */
    if (cub_motion_sample(s->clip, t_us, once ? CUB_MOTION_CLAMP : CUB_MOTION_LOOP, &pose) ||
        cub_motion_forward(s->clip->skel, &pose, world, NULL))
        return 0;
    cub_motion_world_to_float(world, s->clip->skel->joint_count, xyz);
    return s->clip->skel->joint_count;
}

int play_src_load(play_src *s, const char *spec, const char *amc, play_figure want,
                  const cub_character *bear, const char *map_path)
{
    char pack[1024];
    const char *clip = NULL;
    memset(s, 0, sizeof *s);
    s->path = spec;
    s->amc_path = amc;
    if (ends_with(spec, ".trc")) return load_trc(s);
    int rc = split_pack(spec, pack, sizeof pack, &clip) ? load_pack_clip(s, pack, clip) : load_file(s);
    if (!rc && s->clip->frame_count < 1) {
        fprintf(stderr, "cubtool play: %s: the clip has no frames\n", spec);
        rc = 1;
    }
    if (!rc) rc = pick_figure(s, want, bear, map_path);
    if (!rc) s->height_mm = rest_height_mm(s->clip->skel);
    return rc;
}

void play_src_free(play_src *s)
{
    cub_trc_free(&s->trc);
    cub_library_free(&s->lib);
    cub_io_motion_free(&s->motion);
}

/* play_src — loading what `cubtool play` shows (see play_src.h). */
#include "play_src.h"

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
                "cubtool play: %s: not a .bvh, an .ase, an .asf + .amc pair or PACK.cubclips:CLIP\n",
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

int play_src_load(play_src *s, const char *spec, const char *amc, play_figure want,
                  const cub_character *bear, const char *map_path)
{
    char pack[1024];
    const char *clip = NULL;
    memset(s, 0, sizeof *s);
    s->path = spec;
    s->amc_path = amc;
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
    cub_library_free(&s->lib);
    cub_io_motion_free(&s->motion);
}

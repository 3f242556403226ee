/* cubtool coach — a second coach's whole clip library made from the bear's
 * through evolve (SEEDS.md § 004; docs/evolve.md, "The second coach").
 *
 * For every clip of assets/clips/bear.cubclips: parent 1 is the new coach
 * (assets/NAME/NAME.xml) playing its own keys (NAME.keys) along the bear
 * clip's root path; parent 2 is the bear's clip. NAME.map pairs the joints;
 * the crossover appends the bear's joints the coach lacks and the mutation
 * removes exactly those (weight -2 each, as many mutations as there are),
 * so the child's skeleton is the coach's; the survivor at x = 1 in time
 * (no window search: the clips are timed to the songs) moves the coach's
 * paired joints as the bear's move, its own joints as its keys; the floor
 * step keeps it above y = 0. The clips are packed in the bear's order and
 * tagged by `cubtool tag`. Deterministic: the same inputs give the same
 * bytes (test_coach_reproduce). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "cub/character.h"
#include "cub/evolve.h"
#include "cub/keys.h"
#include "cub/pack.h"

typedef struct coach_args {
    const char *name, *assets, *out_dir;
    char character[512], map[512], keys[512], bear_lib[512], bear[512], out[512], tags[512];
} coach_args;

/* What the coach is made from, loaded once. */
typedef struct coach_src {
    cub_character coach, bear;
    cub_evolve_map map;
    cub_keys_clip keys;
    cub_library bear_lib;
} coach_src;

/* The figures of one clip (docs/evolve.md). */
typedef struct coach_figs {
    int below_before, below_after, ik_frames, lifted;
    double bone_err_mm, slide_mm, bear_slide_mm, energy;
    double bear_lowest_mm; /* the bear's lowest joint in its own clip */
} coach_figs;

static void usage(FILE *f)
{
    fprintf(f,
            "usage: cubtool coach NAME [--assets DIR] [--out-dir DIR]\n"
            "\n"
            "Makes coach NAME's clip library and bridge tags from the bear's through\n"
            "evolve (seed 004): reads DIR/NAME/NAME.xml (the character), NAME.map (its\n"
            "joints against the bear's), NAME.keys (its own movement) and\n"
            "DIR/clips/bear.cubclips; writes NAME.cubclips and NAME.tags.xml.\n"
            "One line of figures per clip on stdout (joints below the floor before and\n"
            "after the floor step, kept bones' length error, the coach's floor contact\n"
            "slide against the bear's feet in the bear's clip), a summary at the end.\n"
            "\n"
            "  --assets DIR    (default %s)\n"
            "  --out-dir DIR   where the two files go (default DIR/clips)\n"
            "  --help          this text\n",
            CUB_ASSETS_DIR);
}

static int valid_name(const char *s)
{
    size_t n = strlen(s);
    if (n == 0 || n > 31) return 0;
    for (size_t i = 0; i < n; i++)
        if (!((s[i] >= 'a' && s[i] <= 'z') || (s[i] >= '0' && s[i] <= '9') || s[i] == '_'))
            return 0;
    return strcmp(s, "bear") != 0;
}

static void make_paths(coach_args *a)
{
    const char *n = a->name, *d = a->assets;
    snprintf(a->character, sizeof a->character, "%s/%s/%s.xml", d, n, n);
    snprintf(a->map, sizeof a->map, "%s/%s/%s.map", d, n, n);
    snprintf(a->keys, sizeof a->keys, "%s/%s/%s.keys", d, n, n);
    snprintf(a->bear_lib, sizeof a->bear_lib, "%s/clips/bear.cubclips", d);
    snprintf(a->bear, sizeof a->bear, "%s/bear/bear.xml", d);
    if (a->out_dir) {
        snprintf(a->out, sizeof a->out, "%s/%s.cubclips", a->out_dir, n);
        snprintf(a->tags, sizeof a->tags, "%s/%s.tags.xml", a->out_dir, n);
    } else {
        snprintf(a->out, sizeof a->out, "%s/clips/%s.cubclips", d, n);
        snprintf(a->tags, sizeof a->tags, "%s/clips/%s.tags.xml", d, n);
    }
}

/* 0 run, 1 help printed, 2 bad usage. */
static int parse_args(int argc, char **argv, coach_args *a)
{
    memset(a, 0, sizeof *a);
    a->assets = CUB_ASSETS_DIR;
    for (int i = 1; i < argc; i++) {
        const char *o = argv[i];
        if (!strcmp(o, "--help") || !strcmp(o, "-h")) return usage(stdout), 1;
        const char **slot = !strcmp(o, "--assets")    ? &a->assets
                            : !strcmp(o, "--out-dir") ? &a->out_dir
                                                      : NULL;
        if (slot && i + 1 < argc) *slot = argv[++i];
        else if (!slot && o[0] != '-' && !a->name) a->name = o;
        else return fprintf(stderr, "cubtool coach: unexpected '%s'\n", o), usage(stderr), 2;
    }
    if (!a->name || !valid_name(a->name)) {
        fprintf(stderr, "cubtool coach: NAME wants a coach's name (a-z, 0-9, _; not bear), "
                        "got '%s'\n", a->name ? a->name : "");
        return 2;
    }
    make_paths(a);
    return 0;
}

static int fail(const char *what, const cub_diag *d)
{
    char buf[600];
    fprintf(stderr, "cubtool coach: %s: %s\n", what, cub_diag_str(d, buf, sizeof buf));
    return 1;
}

static int load_sources(const coach_args *a, coach_src *s)
{
    cub_diag d = {0};
    if (cub_character_load(a->character, &s->coach, &d)) return fail("character", &d);
    if (cub_character_load(a->bear, &s->bear, &d)) return fail("bear", &d);
    if (cub_evolve_map_load(a->map, &s->map, &d)) return fail("map", &d);
    if (cub_keys_load(a->keys, &s->coach.skel, &s->keys, &d)) return fail("keys", &d);
    if (cub_pack_read(a->bear_lib, &s->bear_lib, &d)) return fail("bear's library", &d);
    return 0;
}

/* Parent 1: the coach for as long as the bear's clip, carried along that
 * clip's root path (the height scaled by the two characters' hip heights:
 * the coach sits where the bear stands). A joint with a partner holds the
 * partner's mean pose over the clip (several partners: their combination,
 * cub_evolve_partner_rot): the survivor at x = 1 gives it parent 1's mean
 * moving as parent 2 does,
 * so the coach makes the bear's move, not the move about its own T pose
 * (tried first: a seal's jumping jacks with flippers flapping about the
 * horizontal). The coach's own joints play its keys (looped). */
static int coach_parent(const coach_src *s, const cub_evolve_meta *meta,
                        const cub_evolve_motion *bear, cub_evolve_motion *p1)
{
    const cub_skeleton *sk = &s->coach.skel;
    if (cub_evolve_motion_alloc(sk, bear->frames, bear->fps, p1)) return 1;
    double k = (double)sk->joints[0].offset_mm.y / (double)s->bear.skel.joints[0].offset_mm.y;
    static cub_pose pose;
    static cub_dq mean[CUB_EVOLVE_MAX_JOINTS];
    cub_evolve_partner_means(meta, bear, mean);
    for (int f = 0; f < bear->frames; f++) {
        int64_t t_us = (int64_t)(f * 1e6 / bear->fps + 0.5);
        cub_motion_sample(&s->keys.clip, t_us, CUB_MOTION_LOOP, &pose);
        for (int j = 1; j < sk->joint_count; j++) {
            int paired = meta->partner_count[j] > 0;
            *cub_evolve_rot(p1, f, j) = paired ? mean[j] : cub_dq_from_fx(pose.rot[j]);
        }
        *cub_evolve_rot(p1, f, 0) = *cub_evolve_rot(bear, f, 0);
        cub_dv3 r = bear->root_mm[f];
        p1->root_mm[f] = cub_dv3_make(r.x, r.y * k, r.z);
    }
    return 0;
}

/* Every joint the crossover appended from the bear goes, none else. */
static void bear_only_removed(const cub_evolve_meta *meta, cub_evolve_mutation *mut)
{
    memset(mut, 0, sizeof *mut);
    for (int j = 0; j < meta->skel.joint_count; j++)
        if (meta->from[j] == 2) {
            mut->weight[j] = -2;
            mut->count += !meta->skel.joints[j].is_end_site;
        }
}

/* 0 when child has exactly the coach's joints, in order. */
static int same_skeleton(const cub_skeleton *a, const cub_skeleton *b, const char *clip)
{
    int same = a->joint_count == b->joint_count;
    for (int j = 0; same && j < a->joint_count; j++)
        same = !strcmp(a->joints[j].name, b->joints[j].name) &&
               a->joints[j].parent == b->joints[j].parent;
    if (!same)
        fprintf(stderr, "cubtool coach: clip %s: the child's skeleton is not the coach's (%d "
                        "joints, the coach %d): check the map\n", clip, a->joint_count,
                b->joint_count);
    return !same;
}

/* The mean slide (mm a contact frame) over the named joints m has; -1: no contact. */
static double slide_of(const cub_evolve_motion *m, const char *const *names, int n)
{
    double sum = 0;
    int frames = 0;
    for (int i = 0; i < n; i++) {
        cub_evolve_slide_report r;
        int j = cub_motion_skeleton_find(&m->skel, names[i]);
        if (j < 0 || cub_evolve_slide(m, j, &r)) continue;
        sum += r.mean_mm * r.contact_frames;
        frames += r.contact_frames;
    }
    return frames ? sum / frames : -1;
}

/* The lowest y (mm) of any joint of m over its frames. */
static double lowest_mm(const cub_evolve_motion *m)
{
    static cub_dv3 w[CUB_EVOLVE_MAX_JOINTS];
    double low = INFINITY;
    for (int f = 0; f < m->frames; f++) {
        cub_evolve_forward(m, f, w);
        for (int j = 0; j < m->skel.joint_count; j++)
            low = fmin(low, w[j].y);
    }
    return low;
}

static void measure(const cub_evolve_motion *child, const cub_evolve_motion *bear,
                    const cub_evolve_pop *pop, const cub_evolve_meta *meta, coach_figs *f)
{
    static const char *const fin[] = {"TailFin", "TailFin_end", "LeftFoot", "RightFoot"};
    static const char *const feet[] = {"LeftFoot", "RightFoot"};
    f->bone_err_mm = cub_evolve_bone_error_mm(child, pop, meta);
    f->slide_mm = slide_of(child, fin, 4);
    f->bear_slide_mm = slide_of(bear, feet, 2);
    f->bear_lowest_mm = lowest_mm(bear);
}

/* One bear clip -> the coach's clip in *out (io motion, owned). */
static int evolve_clip(const coach_src *s, const cub_library_clip *lc, cub_io_motion *out,
                       coach_figs *f)
{
    static cub_evolve_motion p1, p2;
    static cub_evolve_corr corr;
    static cub_evolve_meta meta;
    static cub_evolve_mutation mut;
    static cub_evolve_pop pop;
    cub_evolve_motion child = {0};
    cub_evolve_survivor_report sr;
    cub_evolve_floor_report fr;
    cub_evolve_survivor_cfg sc = {1.0, 0, 1};
    cub_diag d = {0};
    int rc = 1;
    if (cub_evolve_from_clip(&lc->clip, 30, &p2)) {
        fprintf(stderr, "cubtool coach: clip %s: out of memory\n", lc->name);
        goto out;
    }
    if (cub_evolve_correspond(&s->coach.skel, &p2.skel, &s->map, &corr, &d) ||
        cub_evolve_crossover(&s->coach.skel, &p2.skel, &corr, &meta, &d)) {
        rc = fail(lc->name, &d);
        goto out;
    }
    if (coach_parent(s, &meta, &p2, &p1)) {
        fprintf(stderr, "cubtool coach: clip %s: out of memory\n", lc->name);
        goto out;
    }
    bear_only_removed(&meta, &mut);
    if (cub_evolve_mutate(&meta, &p1, &p2, &mut, &pop, &d) ||
        cub_evolve_survivor(&meta, &pop, &p1, &p2, &sc, &child, &sr, &d)) {
        rc = fail(lc->name, &d);
        goto out;
    }
    cub_evolve_floor(&child, &fr);
    if (same_skeleton(&child.skel, &s->coach.skel, lc->name)) goto out;
    *f = (coach_figs){fr.below_before, fr.below_after, fr.frames_ik, fr.frames_lifted,
                      0, 0, 0, sr.energy, 0};
    measure(&child, &p2, &pop, &meta, f);
    rc = cub_evolve_to_io(&child, 10, out) ? 1 : 0;
out:
    cub_evolve_motion_free(&p1);
    cub_evolve_motion_free(&p2);
    cub_evolve_motion_free(&child);
    return rc;
}

static void print_figs(const char *name, int frames, const coach_figs *f)
{
    printf("clip %-14s frames=%4d below_floor_before=%d below_floor_after=%d ik_frames=%d "
           "lifted_frames=%d bone_err_mm=%.1e slide_mm=%.1f bear_slide_mm=%.1f "
           "bear_lowest_mm=%.1f\n",
           name, frames, f->below_before, f->below_after, f->ik_frames, f->lifted,
           f->bone_err_mm, f->slide_mm, f->bear_slide_mm, f->bear_lowest_mm);
}

/* Summary over the clips: sums and extremes. */
static void add_figs(coach_figs *sum, const coach_figs *f)
{
    sum->below_before += f->below_before;
    sum->below_after += f->below_after;
    sum->ik_frames += f->ik_frames;
    sum->lifted += f->lifted;
    sum->bone_err_mm = fmax(sum->bone_err_mm, f->bone_err_mm);
}

/* The library as the box reads it (the pack's codec rounds): its lowest
 * joint over every clip and frame, printed. */
static int packed_floor(const char *path)
{
    static cub_library lib;
    cub_diag d = {0};
    if (cub_pack_read(path, &lib, &d)) return fail("reading back", &d);
    double low = INFINITY;
    for (int c = 0; c < lib.clip_count; c++) {
        static cub_evolve_motion m;
        if (cub_evolve_from_clip(&lib.clips[c].clip, 0, &m)) continue;
        low = fmin(low, lowest_mm(&m));
        cub_evolve_motion_free(&m);
    }
    printf("packed %s: lowest joint over all clips and frames y=%.2f mm\n", path, low);
    cub_library_free(&lib);
    return 0;
}

static int evolve_all(const coach_args *a, coach_src *s, cub_io_motion *outs, cub_library *lib)
{
    coach_figs sum = {0};
    int n = s->bear_lib.clip_count;
    lib->skel = s->coach.skel;
    for (int i = 0; i < n; i++) {
        const cub_library_clip *bc = &s->bear_lib.clips[i];
        coach_figs f;
        fprintf(stderr, "cubtool coach: [%d/%d] %s\n", i + 1, n, bc->name);
        if (evolve_clip(s, bc, &outs[i], &f)) return 1;
        cub_library_clip *lc = &lib->clips[i];
        snprintf(lc->name, sizeof lc->name, "%s", bc->name);
        snprintf(lc->kind, sizeof lc->kind, "%s", bc->kind);
        lc->clip = outs[i].clip;
        lc->clip.skel = &lib->skel;
        lib->clip_count = i + 1;
        print_figs(bc->name, lc->clip.frame_count, &f);
        add_figs(&sum, &f);
    }
    printf("coach %s: clips=%d below_floor_before=%d below_floor_after=%d ik_frames=%d "
           "lifted_frames=%d largest_bone_err_mm=%.1e\n",
           a->name, n, sum.below_before, sum.below_after, sum.ik_frames, sum.lifted,
           sum.bone_err_mm);
    cub_diag d = {0};
    return cub_pack_write(a->out, lib, &d) ? fail("pack", &d) : packed_floor(a->out);
}

/* The bridge tags, by `cubtool tag` on the new library and character. */
static int tag(const coach_args *a)
{
    char *argv[] = {"tag", "--library", (char *)a->out, "--character", (char *)a->character,
                    "--out", (char *)a->tags, NULL};
    fflush(stdout);
    return cub_cmd_tag(7, argv);
}

int cub_cmd_coach(int argc, char **argv)
{
    static coach_args a;
    int rc = parse_args(argc, argv, &a);
    if (rc) return rc == 1 ? 0 : 2;
    coach_src *s = calloc(1, sizeof *s);
    cub_library *lib = calloc(1, sizeof *lib);
    cub_io_motion *outs = NULL;
    cub_library_clip *clips = NULL;
    rc = 1;
    if (s && lib && !load_sources(&a, s)) {
        int n = s->bear_lib.clip_count;
        outs = calloc((size_t)n + 1, sizeof *outs);
        clips = calloc((size_t)n + 1, sizeof *clips);
        lib->clips = clips;
        rc = outs && clips ? evolve_all(&a, s, outs, lib) : 1;
        if (!rc) rc = tag(&a);
        for (int i = 0; outs && i < n; i++)
            cub_io_motion_free(&outs[i]);
    }
    if (s) cub_library_free(&s->bear_lib), cub_keys_free(&s->keys);
    free(outs), free(clips), free(lib), free(s);
    return rc;
}

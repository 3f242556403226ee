/* cubtool evolve — two clips of different skeletons crossed into a child
 * (SEEDS.md § 004; see cub/evolve.h), written as BVH. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "commands.h"
#include "cub/evolve.h"
#include "evolve_src.h"
#include "cub/retarget.h"

#define EVOLVE_MAX_WEIGHTS 32
#define EVOLVE_BENCH_RUNS 30
#define SHEET_COLUMNS 4 /* frames a clip on the contact sheet */

static void usage(FILE *f)
{
    fprintf(f,
            "usage: cubtool evolve PARENT1 PARENT2 --out CHILD.bvh [options]\n"
            "\n"
            "Crosses two skeletons and their motions (hierarchical evolution, seed 004):\n"
            "joint correspondences, the meta skeleton, mutation of the least active\n"
            "joints, the survivor's blend of the two motions, no joint below the floor.\n"
            "A parent is a .bvh, a pack's clip (LIB.cubclips:NAME) or keys on a\n"
            "character's skeleton (CHARACTER.xml:KEYS.keys).\n"
            "\n"
            "  --out FILE        the child, BVH (centimetres)\n"
            "  --map FILE        correspondences (`P1Joint... = P2Joint...`, `X = -`)\n"
            "  --mutations N     joints removed (default %d; 0: none)\n"
            "  --weight J=W      add W to joint J's activity score (repeatable; -2 removes\n"
            "                    J first, +2 keeps it)\n"
            "  --blend X         x in C_mp = C_m1 + x d (default 0.5; negative allowed)\n"
            "  --fps F           both parents resampled at F (default 30)\n"
            "  --max-frames N    each parent cut to its first N frames (after --fps)\n"
            "  --sheet FILE      also a PNG contact sheet: parent 1, parent 2 and the child\n"
            "                    side by side, %d frames each (the parents as crossed)\n"
            "  --out-character F also the child as a character file: parent 1's parts, and\n"
            "                    parent 2's on the joints it gave (optional=\"1\": drawn only\n"
            "                    while a clip moves them)\n"
            "  --character1 F    parent 1's character (its parts); a CHARACTER.xml:KEYS\n"
            "  --character2 F    parent gives its own\n"
            "  --bench           time the pipeline (%d runs; loading and writing excluded)\n"
            "  --help            this text\n"
            "\n"
            "Progress on stderr; one line of figures on stdout.\n",
            CUB_EVOLVE_MUTATIONS_DEFAULT, SHEET_COLUMNS, EVOLVE_BENCH_RUNS);
}

typedef struct evolve_args {
    const char *p1, *p2, *out, *map, *sheet, *out_char, *char_path[2];
    int mutations, max_frames, bench;
    double blend, fps;
    int weight_count;
    char weight_name[EVOLVE_MAX_WEIGHTS][CUB_MOTION_NAME_LEN];
    double weight[EVOLVE_MAX_WEIGHTS];
} evolve_args;

static int number(const char *s, double *out)
{
    char *e = NULL;
    *out = strtod(s, &e);
    return e != s && !*e && isfinite(*out);
}

static int add_weight(evolve_args *a, const char *s)
{
    const char *eq = strrchr(s, '=');
    double w;
    if (!eq || eq == s || (size_t)(eq - s) >= CUB_MOTION_NAME_LEN || !number(eq + 1, &w) ||
        a->weight_count >= EVOLVE_MAX_WEIGHTS) {
        fprintf(stderr, "cubtool evolve: --weight needs JOINT=NUMBER (at most %d), got '%s'\n",
                EVOLVE_MAX_WEIGHTS, s);
        return 2;
    }
    snprintf(a->weight_name[a->weight_count], CUB_MOTION_NAME_LEN, "%.*s", (int)(eq - s), s);
    a->weight[a->weight_count++] = w;
    return 0;
}

/* One option with a value at argv[i]; 0 ok, 2 bad. */
static int option(evolve_args *a, const char *o, const char *v)
{
    double x = 0;
    const char **str = !strcmp(o, "--out")     ? &a->out
                       : !strcmp(o, "--map")   ? &a->map
                       : !strcmp(o, "--sheet") ? &a->sheet
                       : !strcmp(o, "--out-character") ? &a->out_char
                       : !strcmp(o, "--character1")    ? &a->char_path[0]
                       : !strcmp(o, "--character2")    ? &a->char_path[1]
                                                       : NULL;
    if (str) {
        *str = v;
        return 0;
    }
    if (!strcmp(o, "--weight")) return add_weight(a, v);
    if (!number(v, &x)) {
        fprintf(stderr, "cubtool evolve: %s needs a number, got '%s'\n", o, v);
        return 2;
    }
    if (!strcmp(o, "--blend"))
        a->blend = x;
    else if (!strcmp(o, "--fps") && x > 0 && x <= 1000)
        a->fps = x;
    else if (!strcmp(o, "--mutations") && x >= 0 && x <= CUB_EVOLVE_MAX_JOINTS && x == floor(x))
        a->mutations = (int)x;
    else if (!strcmp(o, "--max-frames") && x >= 2 && x <= 1e6 && x == floor(x))
        a->max_frames = (int)x;
    else {
        fprintf(stderr, "cubtool evolve: %s %s is out of range\n", o, v);
        return 2;
    }
    return 0;
}

/* 0 ok, 1 help shown, 2 bad usage. */
static int parse_args(int argc, char **argv, evolve_args *a)
{
    memset(a, 0, sizeof(*a));
    a->mutations = CUB_EVOLVE_MUTATIONS_DEFAULT;
    a->blend = 0.5;
    a->fps = 30;
    for (int i = 1; i < argc; i++) {
        const char *o = argv[i];
        if (!strcmp(o, "--help") || !strcmp(o, "-h")) {
            usage(stdout);
            return 1;
        } else if (!strcmp(o, "--bench")) {
            a->bench = 1;
        } else if (o[0] == '-' && o[1] == '-' && i + 1 < argc) {
            if (option(a, o, argv[++i])) return 2;
        } else if (o[0] != '-' && (!a->p1 || !a->p2)) {
            *(a->p1 ? &a->p2 : &a->p1) = o;
        } else {
            fprintf(stderr, "cubtool evolve: unexpected '%s'\n", o);
            return 2;
        }
    }
    if (!a->p1 || !a->p2 || !a->out) {
        fprintf(stderr, "cubtool evolve: need PARENT1.bvh PARENT2.bvh and --out\n");
        usage(stderr);
        return 2;
    }
    return 0;
}

static int fail(const char *what, const cub_diag *d)
{
    char buf[600];
    fprintf(stderr, "cubtool evolve: %s: %s\n", what, cub_diag_str(d, buf, sizeof(buf)));
    return 1;
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

/* What one run of the pipeline made. */
typedef struct evolve_run {
    cub_evolve_corr corr;
    cub_evolve_meta meta;
    cub_evolve_mutation mut;
    cub_evolve_pop pop;
    cub_evolve_motion child;
    cub_evolve_survivor_report surv;
    cub_evolve_floor_report floor;
    double ms[4]; /* crossover (with correspondence), mutation, survivor, floor */
} evolve_run;

static int set_weights(const evolve_args *a, evolve_run *r)
{
    memset(&r->mut, 0, sizeof(r->mut));
    r->mut.count = a->mutations;
    for (int i = 0; i < a->weight_count; i++) {
        int j = cub_motion_skeleton_find(&r->meta.skel, a->weight_name[i]);
        if (j < 0) {
            fprintf(stderr, "cubtool evolve: --weight: no joint \"%s\" in the meta skeleton\n",
                    a->weight_name[i]);
            return 1;
        }
        r->mut.weight[j] = a->weight[i];
    }
    return 0;
}

static int pipeline(const evolve_args *a, const cub_evolve_map *map, const cub_evolve_motion *p1,
                    const cub_evolve_motion *p2, evolve_run *r)
{
    cub_diag d = {0};
    double t0 = now_ms();
    if (cub_evolve_correspond(&p1->skel, &p2->skel, map, &r->corr, &d)) return fail("map", &d);
    if (cub_evolve_crossover(&p1->skel, &p2->skel, &r->corr, &r->meta, &d))
        return fail("crossover", &d);
    double t1 = now_ms();
    if (set_weights(a, r)) return 1;
    if (cub_evolve_mutate(&r->meta, p1, p2, &r->mut, &r->pop, &d)) return fail("mutation", &d);
    double t2 = now_ms();
    cub_evolve_survivor_cfg sc = {a->blend, 0, 0};
    if (cub_evolve_survivor(&r->meta, &r->pop, p1, p2, &sc, &r->child, &r->surv, &d))
        return fail("survivor", &d);
    double t3 = now_ms();
    cub_evolve_floor(&r->child, &r->floor);
    double t4 = now_ms();
    double ms[4] = {t1 - t0, t2 - t1, t3 - t2, t4 - t3};
    memcpy(r->ms, ms, sizeof ms);
    return 0;
}

/* Parent side (0, 1): loaded, cut to --max-frames; its character kept in
 * ch[side] when the spec names one or --characterN does. */
static int load_parent(const evolve_args *a, int side, cub_evolve_motion *out, double *unit_mm,
                       cub_character *ch, int *has_ch)
{
    cub_diag d = {0};
    if (evolve_src_load(side ? a->p2 : a->p1, a->fps, out, unit_mm, ch, has_ch)) return 1;
    if (a->max_frames && out->frames > a->max_frames) out->frames = a->max_frames;
    if (!a->char_path[side]) return 0;
    *has_ch = 1;
    return cub_character_load(a->char_path[side], ch, &d) ? fail("character", &d) : 0;
}

/* The child character (--out-character), named after its file. */
static int write_character(const evolve_args *a, const evolve_run *r, const cub_character *ch,
                           const int *has_ch)
{
    if (!has_ch[0] || !has_ch[1]) {
        fprintf(stderr, "cubtool evolve: --out-character needs both parents' characters "
                        "(--character1/2 or CHARACTER.xml:KEYS.keys)\n");
        return 1;
    }
    const char *base = strrchr(a->out_char, '/');
    char name[32];
    snprintf(name, sizeof name, "%s", base ? base + 1 : a->out_char);
    char *dot = strrchr(name, '.');
    if (dot) *dot = 0;
    return evolve_character_write(a->out_char, name, &r->child.skel, &r->meta, &r->pop, &ch[0],
                                  &ch[1]);
}

static void progress(const evolve_run *r, const cub_evolve_motion *p1, const cub_evolve_motion *p2)
{
    int kinds[2][4] = {{0}};
    for (int side = 0; side < 2; side++)
        for (int j = 0; j < (side ? p2 : p1)->skel.joint_count; j++)
            kinds[side][cub_evolve_kind_of(&r->corr, side + 1, j)]++;
    fprintf(stderr,
            "cubtool evolve: correspondence: %d pairs; parent 1 (%d joints): %d one-to-one, %d "
            "many-to-one, "
            "%d one-to-many, %d none; parent 2 (%d joints): %d none\n",
            r->corr.pair_count, p1->skel.joint_count, kinds[0][1], kinds[0][2], kinds[0][3],
            kinds[0][0], p2->skel.joint_count, kinds[1][0]);
    fprintf(stderr,
            "cubtool evolve: crossover: meta skeleton %d joints (%d appended from parent 2)\n",
            r->meta.skel.joint_count, r->meta.appended);
    fprintf(stderr, "cubtool evolve: mutation: %d removed:", r->pop.removed_count);
    for (int j = 0; j < r->meta.skel.joint_count; j++)
        if (r->pop.removed[j] && !r->meta.skel.joints[j].is_end_site)
            fprintf(stderr, " %s(%.2f)", r->meta.skel.joints[j].name, r->pop.score[j]);
    fprintf(stderr, "; %d re-linked\n", r->pop.relinked);
    fprintf(stderr,
            "cubtool evolve: survivor: parent 2 from frame %d, energy (mean sin^2 of half the "
            "angle) %.4f, mean |d| %.1f deg\n",
            r->surv.offset, r->surv.energy, r->surv.mean_d_deg);
    fprintf(stderr,
            "cubtool evolve: floor: %d joint-frames below before (deepest %.1f mm), %d after; "
            "IK on %d frames, root raised on %d\n",
            r->floor.below_before, r->floor.deepest_mm, r->floor.below_after, r->floor.frames_ik,
            r->floor.frames_lifted);
}

static int cmp_double(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

static int dof_of(const cub_skeleton *s)
{
    int n = 0;
    for (int j = 0; j < s->joint_count; j++)
        n += s->joints[j].is_end_site ? 0 : j == 0 ? 6 : 3;
    return n;
}

static int bench(const evolve_args *a, const cub_evolve_map *map, const cub_evolve_motion *p1,
                 const cub_evolve_motion *p2, evolve_run *r)
{
    static double t[5][EVOLVE_BENCH_RUNS];
    for (int i = 0; i < EVOLVE_BENCH_RUNS; i++) {
        cub_evolve_motion_free(&r->child);
        if (pipeline(a, map, p1, p2, r)) return 1;
        t[4][i] = 0;
        for (int s = 0; s < 4; s++)
            t[s][i] = r->ms[s], t[4][i] += r->ms[s];
    }
    static const char *names[5] = {"crossover", "mutation", "survivor", "floor", "total"};
    printf("evolve bench: parents %d frames x %d joints, %d frames x %d joints; child %d joints, "
           "%d DOF; "
           "%d runs, median (max) ms:",
           p1->frames, p1->skel.joint_count, p2->frames, p2->skel.joint_count,
           r->child.skel.joint_count, dof_of(&r->child.skel), EVOLVE_BENCH_RUNS);
    for (int s = 0; s < 5; s++) {
        qsort(t[s], EVOLVE_BENCH_RUNS, sizeof(double), cmp_double);
        printf(" %s=%.2f(%.2f)", names[s], t[s][EVOLVE_BENCH_RUNS / 2],
               t[s][EVOLVE_BENCH_RUNS - 1]);
    }
    printf("\n");
    return 0;
}

/* One contact sheet at path: parent 1, parent 2 and the child side by
 * side, SHEET_COLUMNS frames each (the parents as crossed: resampled).
 * 0 ok. */
static int write_sheet(const char *path, const cub_evolve_motion *const m[3])
{
    static cub_io_motion io[3];
    static const char *const titles[3] = {"parent 1", "parent 2", "child"};
    const cub_clip *clips[3];
    int rc = 0;
    for (int i = 0; i < 3; i++) {
        rc = rc || cub_evolve_to_io(m[i], 10, &io[i]);
        clips[i] = &io[i].clip;
    }
    rc = rc || cub_retarget_sheet_multi_png(path, clips, titles, 3, SHEET_COLUMNS);
    if (rc) fprintf(stderr, "cubtool evolve: cannot write %s\n", path);
    for (int i = 0; i < 3; i++)
        cub_io_motion_free(&io[i]);
    return rc;
}

static int write_child(const evolve_args *a, const evolve_run *r, double unit_mm)
{
    static cub_io_motion io;
    cub_diag d = {0};
    int rc = 0;
    if (cub_evolve_to_io(&r->child, unit_mm, &io)) {
        fprintf(stderr, "cubtool evolve: out of memory\n");
        rc = 1;
    } else if (cub_io_save_bvh(a->out, &io, &d)) {
        rc = fail("write", &d);
    }
    cub_io_motion_free(&io);
    return rc;
}

/* The mean foot slide (mm a contact frame) of the feet (and a quadruped's
 * front paws, named hands) m has, over all their contact frames; -1 when
 * none stands. */
static double feet_slide(const cub_evolve_motion *m)
{
    static const char *feet[] = {"LeftFoot",     "RightFoot", "LeftToeBase",
                                 "RightToeBase", "LeftHand",  "RightHand"};
    double sum = 0;
    int n = 0;
    for (size_t i = 0; i < sizeof feet / sizeof *feet; i++) {
        cub_evolve_slide_report s;
        int j = cub_motion_skeleton_find(&m->skel, feet[i]);
        if (j < 0 || cub_evolve_slide(m, j, &s)) continue;
        sum += s.mean_mm * s.contact_frames;
        n += s.contact_frames;
    }
    return n ? sum / n : -1;
}

/* The round trip A -> child -> A: the child crossed back with parent 1 at
 * x = 1 (no map, weights or mutation), which gives parent 1's movement
 * back on the child's mean pose. The mean distance (mm) of parent 1's
 * joints there from where parent 1 has them, over its frames; the largest
 * in *max_mm. -1 when the cross fails. */
static double round_trip_mm(const cub_evolve_motion *p1, const cub_evolve_motion *child,
                            double *max_mm)
{
    evolve_args back_args = {.blend = 1};
    evolve_run *back = calloc(1, sizeof(*back));
    static cub_dv3 w1[CUB_EVOLVE_MAX_JOINTS], w2[CUB_EVOLVE_MAX_JOINTS];
    double sum = 0;
    int n = 0;
    *max_mm = 0;
    if (!back || pipeline(&back_args, NULL, child, p1, back)) {
        free(back);
        return -1;
    }
    const cub_evolve_motion *m = &back->child;
    for (int f = 0; f < p1->frames; f++) {
        cub_evolve_forward(p1, f, w1);
        cub_evolve_forward(m, f, w2);
        for (int j = 0; j < p1->skel.joint_count; j++) {
            int k = cub_motion_skeleton_find(&m->skel, p1->skel.joints[j].name);
            if (k < 0) continue;
            double d = cub_dv3_len(cub_dv3_sub(w1[j], w2[k]));
            sum += d;
            *max_mm = fmax(*max_mm, d);
            n++;
        }
    }
    cub_evolve_motion_free(&back->child);
    free(back);
    return n ? sum / n : -1;
}

static int run(const evolve_args *a, cub_evolve_map *map, evolve_run *r)
{
    static cub_evolve_motion p1, p2;
    static cub_character ch[2];
    int has_ch[2] = {0, 0};
    double unit1 = 10, unit2 = 10;
    cub_diag d = {0};
    int rc = 1;
    if (a->map && cub_evolve_map_load(a->map, map, &d)) return fail("map", &d);
    if (load_parent(a, 0, &p1, &unit1, &ch[0], &has_ch[0]) ||
        load_parent(a, 1, &p2, &unit2, &ch[1], &has_ch[1]))
        goto out;
    if (pipeline(a, a->map ? map : NULL, &p1, &p2, r)) goto out;
    progress(r, &p1, &p2);
    if (a->bench) {
        rc = bench(a, a->map ? map : NULL, &p1, &p2, r);
        goto out;
    }
    if (write_child(a, r, unit1)) goto out;
    if (a->out_char && write_character(a, r, ch, has_ch)) goto out;
    if (a->sheet && write_sheet(a->sheet, (const cub_evolve_motion *const[3]){&p1, &p2, &r->child}))
        goto out;
    double bone = cub_evolve_bone_error_mm(&r->child, &r->pop, &r->meta);
    double ms = r->ms[0] + r->ms[1] + r->ms[2] + r->ms[3], rt_max = 0;
    double rt = round_trip_mm(&p1, &r->child, &rt_max);
    printf(
        "evolve: %s frames=%d joints=%d dof=%d mutated=%d relinked=%d window=%d mean_d_deg=%.1f "
        "below_floor_before=%d below_floor_after=%d ik_frames=%d lifted_frames=%d bone_err_mm=%.2e "
        "slide_mm=%.1f p1_slide_mm=%.1f round_trip_mm=%.1f(max %.1f) ms=%.2f\n",
        a->out, r->child.frames, r->child.skel.joint_count, dof_of(&r->child.skel),
        r->pop.removed_count, r->pop.relinked, r->surv.offset, r->surv.mean_d_deg,
        r->floor.below_before, r->floor.below_after, r->floor.frames_ik, r->floor.frames_lifted,
        bone, feet_slide(&r->child), feet_slide(&p1), rt, rt_max, ms);
    rc = 0;
out:
    cub_evolve_motion_free(&p1);
    cub_evolve_motion_free(&p2);
    cub_evolve_motion_free(&r->child);
    return rc;
}

int cub_cmd_evolve(int argc, char **argv)
{
    static evolve_args a;
    int rc = parse_args(argc, argv, &a);
    if (rc) return rc == 1 ? 0 : 2;
    cub_evolve_map *map = calloc(1, sizeof(*map));
    evolve_run *r = calloc(1, sizeof(*r));
    rc = map && r ? run(&a, map, r) : 1;
    free(map);
    free(r);
    return rc;
}

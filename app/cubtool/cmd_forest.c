/* cubtool train-forest / eval-forest: the body-part forest (cub/forest.h)
 * trained on and scored against synth-depth renders (cub/forest_train.h);
 * docs/forest.md has the commands, the folds and the figures. */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "cub/forest_train.h"
#include "cub/text.h"
#include "track_dump.h"

#define MAX_CLIPS 96

typedef struct forest_opts {
    const char *clips[MAX_CLIPS];
    int nclips;
    const char *out, *forest, *except, *real, *labels;
    cub_ft_render r;
    cub_ft_params p;
    int stride;
    int vs_tracker, every, pixel_step; /* eval-forest --vs-tracker */
    int seam; /* eval-forest --real --seam */
} forest_opts;

static void help(FILE *f, const char *who)
{
    if (!strcmp(who, "train-forest"))
        fprintf(f, "usage: cubtool train-forest (--clip C ... | --fold F ... | --all-but F | --all)\n"
                   "                            --out FOREST [options]\n"
                   "Trains the body-part forest (cub/forest.h) on synth-depth renders of\n"
                   "shippable motion only (CMU, AnimatedDrawings: Bandai and the dog refused),\n"
                   "rendered turning (a new yaw every 1.5 s) and moving about (+-0.7 m).\n"
                   "  --trees N [3]  --depth N [16]  --features N [200]  --thresholds N [20]\n"
                   "  --pixels N     body pixels a frame for each tree [300]\n"
                   "  --min N        a node with fewer pixels is a leaf [20]\n"
                   "  --offset PXMM  probe offsets within +-PXMM pixel·mm [120000]\n");
    else
        fprintf(f, "usage: cubtool eval-forest --forest FOREST (--clip C ... | --fold F ...)\n"
                   "                           [--stride N] [options]\n"
                   "Per-part share of the player's pixels the forest names right, on\n"
                   "renders made as train-forest makes them (any clip: measuring only).\n"
                   "  --stride N     every N-th body pixel [7]\n"
                   "  --vs-tracker   instead: per joint, the share within 10 cm of the forest's\n"
                   "                 part proposals (mean shift, cub/forest.h), of the tracker\n"
                   "                 (firmware/track) and of the two combined, on the same renders\n"
                   "                 (10 fps, frames x step / 30 s a clip; tracker on every frame)\n"
                   "  --every N      --vs-tracker: score every N-th frame [2]\n"
                   "  --pixel-step N --vs-tracker: the forest reads every N-th pixel in x and y [2]\n"
                   "  --real DIR --labels FILE  the same table on real frames (fakenect .pgm in\n"
                   "                 DIR) against hand labels (tests/labels/skeltrack_labels.txt)\n"
                   "  --seam         (with --real) the tracker runs with the forest in its seam, as\n"
                   "                 the box would (cub_track_desc.forest): its column is that\n");
    fprintf(f, "clips and folds:\n"
               "  --clip C       a clip short name or path, 'C@S' from S seconds\n"
               "  --fold F       the clips of a fold: cmu13 cmu14 cmu_walks cmu_dance_sport\n"
               "                 animdraw (docs/tracker_eval.md)\n"
               "  --all-but F    every shippable fold but F (leave one source out)\n"
               "  --all          every shippable fold\n"
               "  --frames N     frames a clip [20]   --step N  every N-th frame [8]\n"
               "  --no-turn      the clips' own facing, no new yaw every 1.5 s (facing known)\n"
               "  --seed N       [1]   --data DIR   [$CUB_DATA_DIR or the build's]\n");
}

static int add_fold(forest_opts *o, const char *name, const char *who)
{
    const char *const *c = cub_ft_fold(name);
    if (!c) {
        fprintf(stderr, "%s: no fold '%s' (cmu13 cmu14 cmu_walks cmu_dance_sport animdraw)\n", who,
                name);
        return 0;
    }
    for (; *c && o->nclips < MAX_CLIPS; c++)
        o->clips[o->nclips++] = *c;
    return 1;
}

static int num(const char *who, const char *a, const char *v, double lo, double hi, double *x)
{
    char *end;
    *x = v ? strtod(v, &end) : 0;
    if (v && *v && !*end && *x >= lo && *x <= hi) return 1;
    fprintf(stderr, "%s: %s needs a number in [%g, %g], got '%s'\n", who, a, lo, hi, v ? v : "");
    return 0;
}

static int parse_number(forest_opts *o, const char *who, const char *a, const char *v)
{
    static const struct {
        const char *name;
        double lo, hi;
        size_t at;
        int u64;
    } nums[] = {
        {"--trees", 1, CUB_FOREST_MAX_TREES, offsetof(forest_opts, p.trees), 0},
        {"--depth", 1, 30, offsetof(forest_opts, p.depth), 0},
        {"--features", 1, 100000, offsetof(forest_opts, p.features), 0},
        {"--thresholds", 1, 10000, offsetof(forest_opts, p.thresholds), 0},
        {"--pixels", 1, 100000, offsetof(forest_opts, p.pixels_per_frame), 0},
        {"--min", 2, 1e9, offsetof(forest_opts, p.min_samples), 0},
        {"--offset", 1, CUB_FOREST_MAX_OFFSET, offsetof(forest_opts, p.max_offset), 0},
        {"--frames", 1, 100000, offsetof(forest_opts, r.frames), 0},
        {"--step", 1, 10000, offsetof(forest_opts, r.step), 0},
        {"--stride", 1, 1e6, offsetof(forest_opts, stride), 0},
        {"--seed", 0, 1e15, offsetof(forest_opts, p.seed), 1},
        {"--every", 1, 1000, offsetof(forest_opts, every), 0},
        {"--pixel-step", 1, 64, offsetof(forest_opts, pixel_step), 0},
    };
    for (size_t k = 0; k < sizeof(nums) / sizeof(nums[0]); k++) {
        if (strcmp(a, nums[k].name)) continue;
        double x;
        if (!num(who, a, v, nums[k].lo, nums[k].hi, &x)) return 0;
        if (nums[k].u64) *(uint64_t *)((char *)o + nums[k].at) = (uint64_t)x;
        else *(int32_t *)((char *)o + nums[k].at) = (int32_t)x;
        return 1;
    }
    fprintf(stderr, "%s: unknown option or missing value: %s\n", who, a);
    return 0;
}

static int parse(forest_opts *o, int argc, char **argv, const char *who)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        int ok = 1;
        if (!strcmp(a, "--seam")) {
            o->seam = 1;
            continue;
        }
        if (!strcmp(a, "--vs-tracker") || !strcmp(a, "--no-turn")) {
            *(a[2] == 'v' ? &o->vs_tracker : &o->r.no_turn) = 1;
            continue;
        }
        if (!strcmp(a, "--all")) {
            for (int k = 0; cub_ft_fold_name(k) && ok; k++)
                ok = add_fold(o, cub_ft_fold_name(k), who);
            continue;
        }
        if (!v) return parse_number(o, who, a, v);
        if (!strcmp(a, "--clip") && o->nclips < MAX_CLIPS) o->clips[o->nclips++] = v;
        else if (!strcmp(a, "--fold")) ok = add_fold(o, v, who);
        else if (!strcmp(a, "--all-but")) o->except = v;
        else if (!strcmp(a, "--out")) o->out = v;
        else if (!strcmp(a, "--forest")) o->forest = v;
        else if (!strcmp(a, "--real")) o->real = v;
        else if (!strcmp(a, "--labels")) o->labels = v;
        else if (!strcmp(a, "--data")) o->r.data_dir = v;
        else ok = parse_number(o, who, a, v);
        if (!ok) return 0;
        i++;
    }
    if (o->except) {
        if (!cub_ft_fold(o->except)) return add_fold(o, o->except, who);
        for (int k = 0; cub_ft_fold_name(k); k++)
            if (strcmp(cub_ft_fold_name(k), o->except) && !add_fold(o, cub_ft_fold_name(k), who))
                return 0;
    }
    return 1;
}

static int load_clips(forest_opts *o, cub_ft_set *set, const char *who)
{
    o->r.seed = o->p.seed;
    for (int i = 0; i < o->nclips; i++) {
        cub_diag diag;
        char buf[700];
        if (cub_ft_add_clip(set, &o->r, o->clips[i], &diag)) {
            fprintf(stderr, "%s: %s\n", who, cub_diag_str(&diag, buf, sizeof(buf)));
            return 0;
        }
    }
    fprintf(stderr, "%s: %d clips, %d frames\n", who, o->nclips, set->n);
    return set->n > 0;
}

static int setup(forest_opts *o, int argc, char **argv, const char *who)
{
    *o = (forest_opts){.r = {.frames = 20, .step = 8},
                       .p = {.trees = 3, .depth = 16, .features = 200, .thresholds = 20,
                             .pixels_per_frame = 300, .min_samples = 20, .max_offset = 120000,
                             .seed = 1},
                       .stride = 7,
                       .every = 2,
                       .pixel_step = 2};
    for (int i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            help(stdout, who);
            return 0;
        }
    if (!parse(o, argc, argv, who)) return 2;
    if (!o->nclips && !(o->real && o->labels)) {
        fprintf(stderr, "%s: give --clip, --fold, --all-but or --all (see --help)\n", who);
        return 2;
    }
    if (!o->r.data_dir)
        o->r.data_dir = getenv("CUB_DATA_DIR") ? getenv("CUB_DATA_DIR") : CUB_DATA_DIR_DEFAULT;
    return -1;
}

int cub_cmd_train_forest(int argc, char **argv)
{
    forest_opts o;
    int rc = setup(&o, argc, argv, "train-forest");
    if (rc >= 0) return rc;
    if (!o.out) return fprintf(stderr, "train-forest: --out FOREST needed\n"), 2;
    for (int i = 0; i < o.nclips; i++)
        if (!cub_ft_shippable(o.clips[i])) {
            fprintf(stderr, "train-forest: %s: its licence forbids shipping what derives from it "
                            "(Bandai, the dog): measure on it with eval-forest, never train\n",
                    o.clips[i]);
            return 2;
        }
    cub_ft_set set = {0};
    uint8_t *asset = NULL;
    size_t len = 0;
    rc = load_clips(&o, &set, "train-forest") ? 0 : 1;
    if (!rc && cub_ft_train(&set, &o.p, &asset, &len)) rc = 1;
    cub_ft_set_free(&set);
    FILE *f = rc ? NULL : fopen(o.out, "wb");
    if (!rc && (!f || fwrite(asset, 1, len, f) != len || fclose(f) != 0)) {
        fprintf(stderr, "train-forest: cannot write %s\n", o.out);
        rc = 1;
    }
    if (!rc) printf("train-forest: %d trees, %zu bytes -> %s\n", o.p.trees, len, o.out);
    free(asset);
    return rc;
}

/* Per true part (rows) the share named each part (columns), per mille. */
static void confusion(const cub_ft_score *s)
{
    printf("named as (per mille of the row's pixels):\n%-12s", "");
    for (int q = 1; q < CUB_PART_COUNT; q++)
        printf(" %5.5s", cub_synth_part_name(q));
    for (int p = 1; p < CUB_PART_COUNT; p++) {
        printf("\n%-12s", cub_synth_part_name(p));
        for (int q = 1; q < CUB_PART_COUNT; q++)
            printf(" %5ld", s->n[p] ? 1000 * s->named[p][q] / s->n[p] : 0);
    }
    printf("\n");
}

static void report(const cub_ft_score *s)
{
    long n = 0, right = 0, most = 0;
    printf("%-12s %8s %7s\n", "part", "pixels", "right");
    for (int p = 1; p < CUB_PART_COUNT; p++) {
        n += s->n[p], right += s->right[p];
        if (s->n[p] > most) most = s->n[p];
        printf("%-12s %8ld %6.1f%%\n", cub_synth_part_name(p), s->n[p],
               s->n[p] ? 100.0 * s->right[p] / s->n[p] : 0.0);
    }
    printf("%-12s %8ld %6.1f%%   (one part for every pixel: %.1f%%)\n", "all", n,
           n ? 100.0 * right / n : 0.0, n ? 100.0 * most / n : 0.0);
    printf("ties: %.1f%% of the pixels (the lower part, so the left side, wins)\n",
           n ? 100.0 * s->ties / n : 0.0);
    confusion(s);
}

static double pc(long a, long n)
{
    return n ? 100.0 * a / n : 0.0;
}

#define VS_COLS 8

static void vs_row(const char *name, const long r[VS_COLS])
{
    printf("%-15s %6ld %7.1f%% %7.1f%% %7.1f%% %7.1f%% %7.1f%% %7.1f%% %7.1f%%\n", name, r[0],
           pc(r[1], r[0]), pc(r[2], r[0]), pc(r[3], r[0]), pc(r[4], r[0]), pc(r[5], r[0]),
           pc(r[6], r[0]), pc(r[7], r[6]));
}

/* One row a joint, and "vs" rows (counts) that scripts/forest_folds.sh
 * adds up over the folds. */
static void vs_report(const cub_ft_vs *v)
{
    printf("%-15s %6s %8s %8s %8s %8s %8s %8s %8s\n", "joint", "n", "tracker", "forest",
           "combined", "override", "guessed", "f.conf", "f.conf+");
    long all[VS_COLS] = {0}, own[VS_COLS] = {0};
    for (int j = 0; j < CUB_KJ_COUNT; j++) {
        long r[VS_COLS] = {v->n[j],        v->tracker[j], v->forest[j],    v->combined[j],
                           v->override[j], v->guessed[j], v->confident[j], v->confident_right[j]};
        vs_row(cub_kinect_joint_name(j), r);
        printf("vs %s", cub_kinect_joint_name(j));
        for (int k = 0; k < VS_COLS; k++) {
            printf(" %ld", r[k]);
            all[k] += r[k];
            own[k] += v->have[j] ? r[k] : 0;
        }
        printf("\n");
    }
    vs_row("forest's", own);
    vs_row("all", all);
    printf("(%ld frames) columns: share within 10 cm of the joints in view: tracker; forest\n"
           "proposals (head, hands, feet: their parts' centres; elbows, knees: between two\n"
           "segments; 0 for the other joints); combined: a tracker joint of confidence < 1/2\n"
           "taken from a confident forest joint; override: every confident forest joint\n"
           "taken; guessed: tracker confidence < 1/2; f.conf: the forest's confident joints;\n"
           "f.conf+: of those, the share within 10 cm. forest's: the joints the forest gives.\n",
           v->frames);
    if (v->tracker_frames && v->frames)
        printf("time, this build, one core: forest %.2f ms a scored frame (classify every\n"
               "--pixel-step-th pixel, proposals, joints), tracker %.2f ms a frame\n",
               1e3 * v->forest_s / v->frames, 1e3 * v->tracker_s / v->tracker_frames);
}

static int vs_tracker(forest_opts *o, const cub_forest *f)
{
    cub_ft_compare c = {o->r.data_dir, (double)o->r.frames * o->r.step / 30.0, o->every,
                        o->pixel_step, o->p.seed};
    cub_ft_vs *v = calloc(1, sizeof(*v));
    if (!v) return 1;
    for (int i = 0; i < o->nclips; i++) {
        cub_diag diag = {0};
        char buf[700];
        if (cub_ft_compare_clip(f, &c, o->clips[i], v, &diag)) {
            fprintf(stderr, "eval-forest: %s\n", cub_diag_str(&diag, buf, sizeof(buf)));
            free(v);
            return 1;
        }
    }
    vs_report(v);
    free(v);
    return 0;
}

static int vs_real(forest_opts *o, const cub_forest *f)
{
    char *text = NULL, buf[700];
    size_t len = 0;
    cub_diag diag = {0};
    cub_text_src src = {o->labels, "labels", CUB_TEXT_MAX_CLIPS};
    cub_ft_labels *lab = malloc(sizeof(*lab));
    cub_ft_vs *v = calloc(1, sizeof(*v));
    int rc = !lab || !v || cub_text_read(&src, &text, &len, &diag) ||
             cub_ft_labels_parse(text, len, o->labels, lab, &diag) ||
             cub_ft_compare_real(f, &(cub_ft_real){o->real, o->pixel_step, o->seam}, lab, v, &diag);
    if (rc) fprintf(stderr, "eval-forest: %s\n", cub_diag_str(&diag, buf, sizeof(buf)));
    else vs_report(v);
    free(text), free(lab), free(v);
    return rc;
}

int cub_cmd_eval_forest(int argc, char **argv)
{
    forest_opts o;
    int rc = setup(&o, argc, argv, "eval-forest");
    if (rc >= 0) return rc;
    if (!o.forest) return fprintf(stderr, "eval-forest: --forest FOREST needed\n"), 2;
    char *bytes = NULL;
    cub_forest f;
    if (cub_tool_forest_load(o.forest, &bytes, &f, "eval-forest")) return 1;
    if (o.vs_tracker || o.real) {
        rc = o.real ? vs_real(&o, &f) : vs_tracker(&o, &f);
        free(bytes);
        return rc;
    }
    cub_ft_set set = {0};
    cub_ft_score s = {0};
    rc = load_clips(&o, &set, "eval-forest") ? 0 : 1;
    if (!rc) cub_ft_score_set(&f, &set, o.stride, &s);
    if (!rc) report(&s);
    cub_ft_set_free(&set);
    free(bytes);
    return rc;
}

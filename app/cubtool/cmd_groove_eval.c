/* cubtool groove-eval — seed 001's figures (docs/groove.md): for every
 * file, the bear's whole-song motion at 60 fps measured against the
 * song's meter beats through the tempo map. Beat alignment by FACT's
 * definition (motion beats = local minima of the summed joint speed; each
 * scored exp(-d^2 / 2 sigma^2), sigma = 3 frames, d to the nearest music
 * beat; mean over motion beats) and by Bailando's (the speed smoothed by a
 * Gaussian of 5 frames first; mean over music beats, d to the nearest
 * motion beat); the fastest joint beside the clip library's 99th
 * percentile; the feet; the time to plan and make the frames. */
#include <dirent.h>
#include <math.h>
#include <sys/stat.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "cub/pack.h"
#include "groove_tool.h"
#include "tool_util.h"

#define FPS 60
#define SIGMA 3.0  /* frames at 60 fps: 50 ms */
#define SMOOTH 5.0 /* Bailando's Gaussian, frames */
#define MAX_FILES 64

static int fastest_joint, fastest_frame; /* where max_v was, for --dump */
static const char *fastest_name = "";

/* Summed speed of every joint, mm per frame, frame f from f-1 (v[0] = v[1]);
 * *max_mm_s the fastest single joint, *feet_mm the feet's largest move. */
static double *joint_speed(const cub_clip *clip, double *max_mm_s, double *feet_mm)
{
    int n = clip->skel->joint_count, frames = clip->frame_count;
    double *v = calloc((size_t)frames, sizeof *v);
    static cub_pose pose;
    static cub_vec3 now[CUB_MOTION_MAX_JOINTS], prev[CUB_MOTION_MAX_JOINTS],
        first[CUB_MOTION_MAX_JOINTS];
    int lf = cub_motion_skeleton_find(clip->skel, "LeftFoot"),
        rf = cub_motion_skeleton_find(clip->skel, "RightFoot");
    *max_mm_s = 0, *feet_mm = 0;
    for (int f = 0; v && f < frames; f++) {
        cub_motion_clip_get_frame(clip, f, &pose);
        cub_motion_forward(clip->skel, &pose, now, NULL);
        if (f == 0) memcpy(first, now, sizeof now);
        for (int j = 0; f > 0 && j < n; j++) {
            double dx = (now[j].x - prev[j].x) / 65536.0, dy = (now[j].y - prev[j].y) / 65536.0,
                   dz = (now[j].z - prev[j].z) / 65536.0, d = sqrt(dx * dx + dy * dy + dz * dz);
            v[f] += d;
            if (d * 1e9 / clip->frame_ns > *max_mm_s) {
                *max_mm_s = d * 1e9 / clip->frame_ns;
                fastest_joint = j, fastest_frame = f, fastest_name = clip->skel->joints[j].name;
            }
        }
        for (int k = 0; k < 2; k++) {
            int j = k ? rf : lf;
            if (j < 0) continue;
            double d = fabs((double)now[j].x - first[j].x) + fabs((double)now[j].y - first[j].y) +
                       fabs((double)now[j].z - first[j].z);
            if (d / 65536.0 > *feet_mm) *feet_mm = d / 65536.0;
        }
        memcpy(prev, now, sizeof now);
    }
    if (v && frames > 1) v[0] = v[1];
    return v;
}

/* Strict local minima of v -> frame numbers in out (returns how many). */
static int minima(const double *v, int frames, int *out)
{
    int k = 0;
    for (int f = 1; f + 1 < frames; f++)
        if (v[f] < v[f - 1] && v[f] < v[f + 1]) out[k++] = f;
    return k;
}

static double *smoothed(const double *v, int frames)
{
    double *s = calloc((size_t)frames, sizeof *s);
    int r = (int)(4 * SMOOTH);
    for (int f = 0; s && f < frames; f++) {
        double sum = 0, w = 0;
        for (int k = -r; k <= r; k++) {
            int g = f + k < 0 ? -(f + k) : f + k >= frames ? 2 * frames - (f + k) - 1 : f + k;
            double e = exp(-(double)k * k / (2 * SMOOTH * SMOOTH));
            sum += e * v[g], w += e;
        }
        s[f] = sum / w;
    }
    return s;
}

/* Mean over a of exp(-d^2 / 2 sigma^2), d = a's distance to the nearest b
 * (both sorted frame numbers). */
static double score(const double *a, int na, const double *b, int nb)
{
    double sum = 0;
    for (int i = 0, j = 0; i < na && nb > 0; i++) {
        while (j + 1 < nb && b[j + 1] <= a[i])
            j++;
        double d = fabs(a[i] - b[j]);
        if (j + 1 < nb && fabs(b[j + 1] - a[i]) < d) d = fabs(b[j + 1] - a[i]);
        sum += exp(-d * d / (2 * SIGMA * SIGMA));
    }
    return na ? sum / na : 0;
}

typedef struct figures {
    double fact, bailando, max_mm_s, feet_mm, gen_ms, per3min_ms, len_s;
    int motion_beats, music_beats;
} figures;

/* The song's meter beats within the melody's span, as frame numbers. */
static double *music_frames(const groove_song *s, int *count)
{
    int nb = 0, k = 0;
    int64_t *us = groove_beats_us(&s->midi.song, &nb);
    double *out = calloc((size_t)nb + 1, sizeof *out);
    const cub_groove_plan *p = &s->plan;
    for (int i = 0; us && out && i < nb; i++)
        if (us[i] >= p->notes[0].start_us && us[i] <= p->end_us) out[k++] = us[i] * FPS / 1e6;
    free(us);
    *count = k;
    return out;
}

static const char *dump_path; /* --dump: the speed curves of the last file */

static void dump(const double *v, const double *sm, int frames, const double *beats, int nb)
{
    FILE *f = dump_path ? fopen(dump_path, "w") : NULL;
    for (int i = 0, b = 0; f && i < frames; i++) {
        while (b < nb && beats[b] < i - 0.5)
            b++;
        fprintf(f, "%d %.3f %.3f %d\n", i, v[i], sm[i], b < nb && beats[b] < i + 0.5);
    }
    if (f) fclose(f);
    if (dump_path)
        fprintf(stderr, "fastest joint %d (%s) at frame %d (%.3f s)\n", fastest_joint, fastest_name,
                fastest_frame, fastest_frame / (double)FPS);
}

static int measure(const groove_song *s, const cub_groove_rig *rig, figures *fig)
{
    cub_clip clip;
    void *mem = NULL;
    double t0 = groove_now_ms();
    int rc = groove_song_clip(s, rig, FPS, &clip, &mem);
    fig->gen_ms = s->plan_ms + groove_now_ms() - t0;
    fig->len_s = s->plan.end_us / 1e6;
    fig->per3min_ms = fig->gen_ms * 180.0 / (fig->len_s > 0 ? fig->len_s : 1);
    double *v = rc ? NULL : joint_speed(&clip, &fig->max_mm_s, &fig->feet_mm);
    double *sm = v ? smoothed(v, clip.frame_count) : NULL;
    int *mins = v ? calloc((size_t)clip.frame_count, sizeof *mins) : NULL;
    double *mb = v ? calloc((size_t)clip.frame_count, sizeof *mb) : NULL;
    double *beats = music_frames(s, &fig->music_beats);
    if (sm && mins && mb && beats) {
        int first = (int)(s->plan.notes[0].start_us * FPS / 1000000);
        int k = minima(v, clip.frame_count, mins), m = 0;
        for (int i = 0; i < k; i++)
            if (mins[i] >= first) mb[m++] = mins[i];
        fig->motion_beats = m;
        fig->fact = score(mb, m, beats, fig->music_beats);
        k = minima(sm, clip.frame_count, mins), m = 0;
        for (int i = 0; i < k; i++)
            if (mins[i] >= first) mb[m++] = mins[i];
        fig->bailando = score(beats, fig->music_beats, mb, m);
        dump(v, sm, clip.frame_count, beats, fig->music_beats);
    } else
        rc = 1;
    free(v), free(sm), free(mins), free(mb), free(beats), free(mem);
    return rc;
}

/* Every joint's speed over every clip of the library, its 99th percentile. */
static double library_p99(const char *path)
{
    cub_library lib;
    cub_diag d = {0};
    char msg[600];
    if (cub_pack_read(path, &lib, &d)) {
        fprintf(stderr, "cubtool groove-eval: %s\n", cub_diag_str(&d, msg, sizeof msg));
        return -1;
    }
    double p99 = cub_library_joint_speed_pct(&lib, 0.99);
    cub_library_free(&lib);
    return p99;
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The .mid files of dir, sorted, appended to paths. */
static int list_mid(const char *dir, char **paths, int n)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    int start = n;
    while (d && (e = readdir(d)) && n < MAX_FILES) {
        size_t len = strlen(e->d_name);
        if (len < 5 || strcmp(e->d_name + len - 4, ".mid")) continue;
        paths[n] = malloc(strlen(dir) + len + 2);
        if (paths[n]) sprintf(paths[n++], "%s/%s", dir, e->d_name);
    }
    if (d) closedir(d);
    qsort(paths + start, (size_t)(n - start), sizeof *paths, cmp_str);
    return n;
}

static int is_dir(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

static void print_row(const char *path, const groove_song *s, const figures *f)
{
    const char *name = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    printf("%-36s %7.1f %5d %5d %5d  %.3f  %.3f  %7.0f  %5.2f  %6.2f  %6.2f  %6.2f\n", name,
           f->len_s, s->plan.n, f->music_beats, f->motion_beats, f->fact, f->bailando, f->max_mm_s,
           f->feet_mm, s->plan_ms * 180.0 / (f->len_s > 0 ? f->len_s : 1), f->gen_ms,
           f->per3min_ms);
}

/* The held-out protocol (docs/groove.md): whole styles held out, by name. */
static int held_out(const char *path)
{
    const char *name = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    return !strncmp(name, "jazz_", 5) || !strncmp(name, "classical_mozart", 16);
}

/* A file's style for round 2's folds: the box's songs are "box", the
 * others the name's part before its first '_'. */
static void style_of(const char *path, char *out, size_t cap)
{
    const char *name = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    size_t len = strcspn(name, "_.");
    if (strstr(path, "/songs/")) name = "box", len = 3;
    snprintf(out, cap, "%.*s", (int)(len < cap ? len : cap - 1), name);
}

/* fold: NULL (all), "dev", "held" (round 1), STYLE or -STYLE (round 2). */
static int in_fold(const char *path, const char *fold)
{
    char style[32];
    if (!fold) return 1;
    if (!strcmp(fold, "dev") || !strcmp(fold, "held")) return (fold[0] == 'h') == held_out(path);
    style_of(path, style, sizeof style);
    return fold[0] == '-' ? strcmp(style, fold + 1) != 0 : !strcmp(style, fold);
}

/* Keep only the fold's files; returns the new count. */
static int keep_fold(char **paths, int n, const char *fold)
{
    int k = 0;
    for (int i = 0; i < n; i++) {
        if (!in_fold(paths[i], fold)) {
            free(paths[i]);
            continue;
        }
        paths[k++] = paths[i];
    }
    return k;
}

typedef struct means {
    char style[32];
    double fact, bail;
    int files, fact_ok, bail_ok;
} means;

#define MAX_STYLES 16

/* The means of path's style among styles[*count] (a new one if room). */
static means *style_means(means *styles, int *count, const char *path)
{
    char style[32];
    style_of(path, style, sizeof style);
    for (int i = 0; i < *count; i++)
        if (!strcmp(styles[i].style, style)) return &styles[i];
    if (*count == MAX_STYLES) return NULL;
    means *m = &styles[(*count)++];
    *m = (means){0};
    memcpy(m->style, style, sizeof style);
    return m;
}

static void means_add(means *m, const figures *f)
{
    m->fact += f->fact, m->bail += f->bailando, m->files++;
    m->fact_ok += f->fact >= 0.5, m->bail_ok += f->bailando >= 0.5;
}

static void means_print(const means *m)
{
    if (!m->files) return;
    if (m->style[0]) printf("style %-9s ", m->style);
    printf("mean FACT %.3f (%d of %d >= 0.5), Bailando %.3f (%d of %d >= 0.5)\n",
           m->fact / m->files, m->fact_ok, m->files, m->bail / m->files, m->bail_ok, m->files);
}

int cub_cmd_groove_eval(int argc, char **argv)
{
    const char *fold = NULL;
    char set = 'a';
    double stop[2] = {-1, -1};
    int power = 0;
    char *paths[MAX_FILES];
    int n = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--set") && i + 1 < argc && strchr("ab", argv[i + 1][0]))
            set = argv[++i][0];
        else if (!strcmp(argv[i], "--dump") && i + 1 < argc)
            dump_path = argv[++i];
        else if (!strcmp(argv[i], "--fold") && i + 1 < argc && argv[i + 1][0])
            fold = argv[++i];
        else if (!strcmp(argv[i], "--stop") && i + 1 < argc &&
                 sscanf(argv[i + 1], "%lf,%lf,%d", &stop[0], &stop[1], &power) >= 2)
            i++;
        else if (!strcmp(argv[i], "--help") || argv[i][0] == '-') {
            printf("usage: cubtool groove-eval [--set a|b] [--fold dev|held|STYLE|-STYLE] [--stop B,A[,K]]\n"
                   "                           [--dump F.txt] [FILE.mid|DIR...]\n"
                   "Seed 001's figures: beat alignment (FACT's and Bailando's), fastest joint\n"
                   "vs the clip library's p99, feet, generation time. Default files: every\n"
                   ".mid of <data>/midi and %s/songs; a DIR: its .mid files, sorted.\n"
                   "--dump writes the last file's speed curve (frame, summed speed,\n"
                   "smoothed, music beat) to F.txt.\n"
                   "--fold: only round 1's dev or held-out files, or one style (box: the\n"
                   "box's songs), or all but one (-STYLE); means per style (docs/groove.md).\n"
                   "--stop B,A[,K]: the beat stop's ramps before and after a beat (fractions\n"
                   "of a beat; 0,0: none) and their power K (1..3) instead of the set's.\n",
                   CUB_ASSETS_DIR);
            return argv[i][0] == '-' && strcmp(argv[i], "--help") ? 2 : 0;
        } else if (is_dir(argv[i]))
            n = list_mid(argv[i], paths, n);
        else if (n < MAX_FILES && (paths[n] = malloc(strlen(argv[i]) + 1)))
            strcpy(paths[n++], argv[i]);
    }
    if (n == 0) {
        const char *env = getenv("CUB_DATA_DIR");
        char dir[1024];
        snprintf(dir, sizeof dir, "%s/midi", env && *env ? env : CUB_DATA_DIR_DEFAULT);
        n = list_mid(dir, paths, 0);
        n = list_mid(CUB_ASSETS_DIR "/songs", paths, n);
    }
    n = keep_fold(paths, n, fold);
    means all = {0}, styles[MAX_STYLES];
    int style_count = 0;
    double p99 = library_p99(CUB_ASSETS_DIR "/clips/bear.cubclips");
    printf("clip library joint speed p99 %.0f mm/s; set %c, %d fps, sigma %.0f frames\n", p99, set,
           FPS, SIGMA);
    printf("%-36s %7s %5s %5s %5s  %5s  %5s  %7s  %5s  %6s  %6s  %6s\n", "file", "len_s", "notes",
           "beats", "mbeat", "FACT", "Bail", "max_v", "feet", "plan3m", "gen_ms", "gen3m");
    static cub_skeleton bear;
    cub_groove_rig rig;
    int rc = groove_bear(&bear, "groove-eval");
    if (!rc) cub_groove_rig_bind(&bear, &rig);
    for (int i = 0; i < n && !rc; i++) {
        groove_song s;
        figures f = {0};
        groove_args a = {paths[i], -1, -1, 0, set};
        rc = groove_song_load(&a, "groove-eval", &s);
        if (!rc && stop[0] >= 0)
            s.plan.params.stop_before = (cub_q16)lround(stop[0] * CUB_Q16_ONE),
            s.plan.params.stop_after = (cub_q16)lround(stop[1] * CUB_Q16_ONE),
            s.plan.params.stop_power = power ? power : s.plan.params.stop_power;
        if (!rc) rc = measure(&s, &rig, &f);
        means *m = rc ? NULL : style_means(styles, &style_count, paths[i]);
        if (!rc) print_row(paths[i], &s, &f), means_add(&all, &f);
        if (m) means_add(m, &f);
        groove_song_free(&s);
    }
    for (int i = 0; i < style_count && !rc; i++)
        means_print(&styles[i]);
    if (!rc) means_print(&all);
    for (int i = 0; i < n; i++)
        free(paths[i]);
    return rc;
}

/* bench_codec_vs — our codecs against ACL on the same clips, in one run
 * (issue 21 § 2). `cubtool bench-codec` runs this program.
 *
 * Clips: every BVH of ../shared/data/mocap's cmu (with daz43), animdraw and
 * bandai folders, and the bear's library (assets/clips/bear.cubclips).
 * Codecs: ACL at its "medium" level, 0.01 cm, 3 cm shell (codec_vs_acl.cpp,
 * built only when ../shared/peers/acl exists), the seed's codec (cubseed,
 * squad + IK as the box decodes it) and ours (cubkeys, error-bounded).
 * Per clip (--per-clip), per set and in total:
 *   ratio    raw (10 float32 per bone per sample, end sites not bones)
 *            against the compressed bytes
 *   max/p99  error at virtual vertices 3 cm from each bone along its three
 *            axes (the largest of the three), object space, every bone,
 *            every sample, in cm: ACL's qvvf metric, computed here in
 *            doubles for every codec alike from its decoded local pose
 *   decode   microseconds per pose: every pose of the clip decoded one at a
 *            time (ACL: seek + decompress_tracks; ours: one pose by random
 *            access; the seed's: the whole clip at once, divided), best of 3
 * Prints figures and fails only when a clip cannot be read or coded. */
#define _POSIX_C_SOURCE 200809L
#include <fnmatch.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "codec_vs.h"
#include "cub/codec.h"
#include "cub/codec_enc.h"
#include "cub/io.h"
#include "cub/pack.h"
#include "cub/vec.h"

#define SHELL_MM 30.0
#define MAX_FILES 512
#define MAX_CODECS 3
#define DEFAULT_BOUND_CM 0.01
#define QUICK_CLIPS 2
#define QUICK_FRAMES 240
#define TIME_RUNS 3

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + t.tv_nsec * 1e-9;
}

/* ---- errors: FK in doubles, virtual vertices ---------------------------- */

typedef struct dxf {
    cub_dq q;
    cub_dv3 p;
} dxf;

/* Object-space transforms of every joint of a local pose. */
static void forward(const cub_skeleton *sk, const vs_pose *lp, dxf *w)
{
    for (int j = 0; j < sk->joint_count; j++) {
        cub_dq lq =
            cub_dq_norm((cub_dq){lp->rot[j][0], lp->rot[j][1], lp->rot[j][2], lp->rot[j][3]});
        cub_dv3 lt = {lp->pos[j][0], lp->pos[j][1], lp->pos[j][2]};
        int par = sk->joints[j].parent;
        if (par < 0) {
            w[j] = (dxf){lq, lt};
            continue;
        }
        w[j].p = cub_dv3_add(w[par].p, cub_dq_rotate(w[par].q, lt));
        w[j].q = cub_dq_mul(w[par].q, lq);
    }
}

static double vertex_err_cm(const dxf *a, const dxf *b)
{
    double worst = 0;
    for (int axis = 0; axis < 3; axis++) {
        cub_dv3 v = {axis == 0 ? SHELL_MM : 0, axis == 1 ? SHELL_MM : 0, axis == 2 ? SHELL_MM : 0};
        cub_dv3 va = cub_dv3_add(a->p, cub_dq_rotate(a->q, v)),
                vb = cub_dv3_add(b->p, cub_dq_rotate(b->q, v));
        double d = cub_dv3_len(cub_dv3_sub(va, vb));
        worst = d > worst ? d : worst;
    }
    return worst / 10.0;
}

/* The source's frame f as a vs_pose. */
static void source_pose(const cub_clip *c, int f, vs_pose *out)
{
    const cub_skeleton *sk = c->skel;
    int jn = sk->joint_count;
    for (int j = 0; j < jn; j++) {
        cub_quat r = c->rot[(size_t)f * jn + j];
        cub_vec3 t = j == 0        ? c->root_mm[f]
                     : c->trans_mm ? c->trans_mm[(size_t)f * jn + j]
                                   : sk->joints[j].offset_mm;
        double q[4] = {r.w / 1073741824.0, r.x / 1073741824.0, r.y / 1073741824.0,
                       r.z / 1073741824.0};
        memcpy(out->rot[j], q, sizeof q);
        out->pos[j][0] = t.x / 65536.0, out->pos[j][1] = t.y / 65536.0,
        out->pos[j][2] = t.z / 65536.0;
    }
}

/* ---- figures ------------------------------------------------------------ */

typedef struct series {
    double *v;
    size_t n, cap;
} series;

static int series_add(series *s, double x)
{
    if (s->n == s->cap) {
        size_t cap = s->cap ? s->cap * 2 : 4096;
        double *v = realloc(s->v, cap * sizeof *v);
        if (!v) return -1;
        s->v = v, s->cap = cap;
    }
    s->v[s->n++] = x;
    return 0;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double series_pct(series *s, double p)
{
    if (!s->n) return 0;
    qsort(s->v, s->n, sizeof *s->v, cmp_double);
    size_t i = (size_t)ceil(p * (double)s->n) - 1;
    return s->v[i < s->n ? i : s->n - 1];
}

typedef struct figs {
    double raw, bytes, decode_s;
    long poses;
    int clips;
    series err;
} figs;

static int figs_merge(figs *into, const figs *from)
{
    into->raw += from->raw, into->bytes += from->bytes, into->decode_s += from->decode_s;
    into->poses += from->poses, into->clips += from->clips;
    for (size_t i = 0; i < from->err.n; i++)
        if (series_add(&into->err, from->err.v[i])) return -1;
    return 0;
}

static double raw_bytes(const cub_clip *clip)
{
    int bones = 0;
    for (int j = 0; j < clip->skel->joint_count; j++)
        bones += !clip->skel->joints[j].is_end_site;
    return 40.0 * bones * clip->frame_count;
}

/* ---- the seed's codec ---------------------------------------------------- */

typedef struct seed_state {
    uint8_t *stream;
    size_t len, mem_size;
    cub_skeleton skel;
    cub_clip clip;
    void *mem;
} seed_state;

static void seed_release(void *self)
{
    seed_state *s = self;
    free(s->stream);
    free(s->mem);
    s->stream = NULL, s->mem = NULL;
}

static int seed_decode(seed_state *s)
{
    cub_codec_out out = {&s->skel, &s->clip, s->mem, s->mem_size};
    return cub_codec_decode(s->stream, s->len, NULL, &out, NULL) ? -1 : 0;
}

static int seed_encode(void *self, const cub_clip *clip, size_t *bytes)
{
    seed_state *s = self;
    seed_release(s);
    int eff[CUB_CODEC_MAX_EFFECTORS];
    int ne = cub_codec_pick_effectors(clip->skel, eff, CUB_CODEC_MAX_EFFECTORS);
    size_t cap = cub_codec_encoded_max(clip, ne), work_size = cub_codec_encode_work_size(clip, ne);
    void *work = malloc(work_size);
    s->stream = malloc(cap);
    cub_codec_enc in = {clip, eff, ne, work, work_size};
    cub_codec_info info;
    int bad = !work || !s->stream || cub_codec_encode(&in, s->stream, cap, &s->len) ||
              cub_codec_peek(s->stream, s->len, &info, NULL);
    free(work);
    if (bad) return -1;
    s->mem_size = info.mem_size;
    s->mem = malloc(info.mem_size);
    *bytes = s->len;
    return s->mem ? seed_decode(s) : -1;
}

static int seed_pose(void *self, int frame, vs_pose *out)
{
    seed_state *s = self;
    source_pose(&s->clip, frame, out);
    return 0;
}

static double seed_time_all(void *self)
{
    double t0 = now_s();
    return seed_decode(self) ? -1 : now_s() - t0;
}

static seed_state seed_st;

/* ---- ours: the error-bounded stream --------------------------------------- */

typedef struct keys_state {
    double bound_mm;
    cub_keys_result enc;
    cub_skeleton skel;
    cub_keys k;
    cub_pose pose;
} keys_state;

static void keys_release(void *self)
{
    keys_state *s = self;
    free(s->enc.data);
    s->enc.data = NULL;
}

static int keys_encode(void *self, const cub_clip *clip, size_t *bytes)
{
    keys_state *s = self;
    keys_release(s);
    if (cub_keys_encode(clip, s->bound_mm, &s->enc)) return -1;
    *bytes = s->enc.len;
    return cub_keys_open(s->enc.data, s->enc.len, &s->skel, &s->k, NULL) ? -1 : 0;
}

static int keys_pose(void *self, int frame, vs_pose *out)
{
    keys_state *s = self;
    if (cub_keys_pose(&s->k, frame, &s->pose)) return -1;
    for (int j = 0; j < s->skel.joint_count; j++) {
        cub_quat r = s->pose.rot[j];
        out->rot[j][0] = r.w / 1073741824.0, out->rot[j][1] = r.x / 1073741824.0;
        out->rot[j][2] = r.y / 1073741824.0, out->rot[j][3] = r.z / 1073741824.0;
        cub_vec3 t = j == 0              ? s->pose.root_mm
                     : s->pose.has_trans ? s->pose.trans_mm[j]
                                         : s->skel.joints[j].offset_mm;
        out->pos[j][0] = t.x / 65536.0, out->pos[j][1] = t.y / 65536.0,
        out->pos[j][2] = t.z / 65536.0;
    }
    return 0;
}

static double keys_time_all(void *self)
{
    keys_state *s = self;
    double t0 = now_s();
    for (int f = 0; f < s->k.frame_count; f++)
        if (cub_keys_pose(&s->k, f, &s->pose)) return -1;
    return now_s() - t0;
}

static keys_state keys_st = {.bound_mm = 10.0 * DEFAULT_BOUND_CM};

/* ---- the run ------------------------------------------------------------- */

typedef struct run {
    vs_codec codecs[MAX_CODECS];
    int codec_count, per_clip, quick;
    const char *glob;
    figs set[MAX_CODECS], total[MAX_CODECS];
} run;

static int measure(run *r, int c, const cub_clip *clip, figs *fg)
{
    static vs_pose src, dec;
    static dxf ws[CUB_MOTION_MAX_JOINTS], wd[CUB_MOTION_MAX_JOINTS];
    vs_codec *k = &r->codecs[c];
    const cub_skeleton *sk = clip->skel;
    size_t bytes = 0;
    if (k->encode(k->self, clip, &bytes)) return -1;
    for (int f = 0; f < clip->frame_count; f++) {
        source_pose(clip, f, &src);
        dec = src;
        if (k->pose(k->self, f, &dec)) return -1;
        forward(sk, &src, ws);
        forward(sk, &dec, wd);
        for (int j = 0; j < sk->joint_count; j++)
            if (!sk->joints[j].is_end_site && series_add(&fg->err, vertex_err_cm(&ws[j], &wd[j])))
                return -1;
    }
    double best = 1e30;
    for (int i = 0; i < TIME_RUNS; i++) {
        double t = k->time_all(k->self);
        if (t < 0) return -1;
        best = t < best ? t : best;
    }
    fg->raw = raw_bytes(clip), fg->bytes = (double)bytes, fg->decode_s = best;
    fg->poses = clip->frame_count, fg->clips = 1;
    return 0;
}

static void print_row(const char *what, const char *codec, figs *f)
{
    printf("  %-36s %-8s %6d %8ld %10.0f %8.2f : 1 %9.4f %9.4f %9.3f\n", what, codec, f->clips,
           f->poses, f->bytes, f->bytes > 0 ? f->raw / f->bytes : 0, series_pct(&f->err, 1.0),
           series_pct(&f->err, 0.99), f->poses ? 1e6 * f->decode_s / (double)f->poses : 0);
}

static void print_head(void)
{
    printf("  %-36s %-8s %6s %8s %10s %12s %9s %9s %9s\n", "clips", "codec", "clips", "poses",
           "bytes", "ratio", "max cm", "p99 cm", "us/pose");
}

static int run_clip(run *r, cub_clip *clip, const char *name)
{
    int cut = r->quick > 1 ? QUICK_FRAMES / 2 : QUICK_FRAMES; /* under qemu, half */
    if (r->quick && clip->frame_count > cut) clip->frame_count = cut;
    for (int c = 0; c < r->codec_count; c++) {
        figs fg = {0};
        if (measure(r, c, clip, &fg)) {
            fprintf(stderr, "bench_codec_vs: %s: the %s codec failed\n", name, r->codecs[c].name);
            free(fg.err.v);
            return -1;
        }
        if (r->per_clip) print_row(name, r->codecs[c].name, &fg);
        int bad = figs_merge(&r->set[c], &fg);
        free(fg.err.v);
        if (bad) return -1;
    }
    return 0;
}

/* "set/clip" for --clips GLOB. */
static int wanted(const run *r, const char *set, const char *clip, int *taken)
{
    char key[512];
    snprintf(key, sizeof key, "%s/%s", set, clip);
    if (r->glob && fnmatch(r->glob, key, 0)) return 0;
    if (r->quick && *taken >= (r->quick > 1 ? 1 : QUICK_CLIPS)) return 0;
    (*taken)++;
    return 1;
}

static int run_bvh_set(run *r, const char *data, const char *set, int depth)
{
    char dir[1024], *files[MAX_FILES];
    snprintf(dir, sizeof dir, "%s/mocap/%s", data, set);
    int n = cub_io_list_bvh(dir, depth, files, MAX_FILES), rc = 0, taken = 0;
    if (n == 0) printf("bench_codec_vs: no BVH under %s: the %s set is skipped\n", dir, set);
    for (int i = 0; i < n; i++) {
        const char *name = files[i] + strlen(dir) + 1;
        if (!rc && wanted(r, set, name, &taken)) {
            cub_io_motion m;
            cub_io_desc desc = {0};
            cub_diag d = {0};
            char msg[600];
            if (cub_io_load_bvh(files[i], &desc, &m, &d)) {
                fprintf(stderr, "%s\n", cub_diag_str(&d, msg, sizeof msg));
                rc = -1;
            } else {
                rc = run_clip(r, &m.clip, name);
                cub_io_motion_free(&m);
            }
        }
        free(files[i]);
    }
    return rc;
}

static int run_library(run *r, const char *path)
{
    cub_library lib;
    cub_diag d = {0};
    char msg[600];
    if (cub_pack_read(path, &lib, &d)) {
        fprintf(stderr, "%s\n", cub_diag_str(&d, msg, sizeof msg));
        return -1;
    }
    int rc = 0, taken = 0;
    for (int i = 0; i < lib.clip_count && !rc; i++)
        if (wanted(r, "bear", lib.clips[i].name, &taken))
            rc = run_clip(r, &lib.clips[i].clip, lib.clips[i].name);
    cub_library_free(&lib);
    return rc;
}

static int end_set(run *r, const char *set)
{
    int rc = 0;
    for (int c = 0; c < r->codec_count; c++) {
        if (r->set[c].clips) print_row(set, r->codecs[c].name, &r->set[c]);
        rc |= figs_merge(&r->total[c], &r->set[c]);
        free(r->set[c].err.v);
        memset(&r->set[c], 0, sizeof r->set[c]);
    }
    return rc;
}

static void usage(FILE *f)
{
    fprintf(f,
            "usage: bench_codec_vs [--data DIR] [--library FILE] [--clips GLOB] [--quick] "
            "[--per-clip]\n"
            "  (cubtool bench-codec runs this)\n"
            "ACL (medium, 0.01 cm), the seed's codec and ours on every BVH of DIR/mocap's\n"
            "cmu, animdraw and bandai folders and on the bear's library: ratio against raw\n"
            "(10 float32 per bone per sample), max and p99 error at virtual vertices 3 cm\n"
            "from each bone (cm), decode time per pose. docs/codec.md explains each figure.\n"
            "  --data DIR      the shared data (default $CUB_DATA_DIR, else %s)\n"
            "  --library FILE  the clip library (default %s/clips/bear.cubclips)\n"
            "  --clips GLOB    only the clips whose SET/NAME matches (sets: cmu animdraw\n"
            "                  bandai bear; e.g. 'cmu/*' or 'bandai/*walk*')\n"
            "  --bound CM      our codec's bound (default %g cm: ACL's threshold)\n"
            "  --quick         at most %d clips per set, each cut to %d frames (with\n"
            "                  CUB_QUICK set, as under qemu: 1 clip, half the frames)\n"
            "  --per-clip      a row per clip and codec\n",
            CUB_DATA_DIR_DEFAULT, CUB_ASSETS_DIR, DEFAULT_BOUND_CM, QUICK_CLIPS, QUICK_FRAMES);
}

static int parse(int argc, char **argv, run *r, const char **data, const char **library)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int has = i + 1 < argc;
        if (!strcmp(a, "--data") && has)
            *data = argv[++i];
        else if (!strcmp(a, "--library") && has)
            *library = argv[++i];
        else if (!strcmp(a, "--clips") && has)
            r->glob = argv[++i];
        else if (!strcmp(a, "--quick"))
            r->quick = getenv("CUB_QUICK") ? 2 : 1;
        else if (!strcmp(a, "--bound") && has)
            keys_st.bound_mm = 10.0 * atof(argv[++i]);
        else if (!strcmp(a, "--per-clip"))
            r->per_clip = 1;
        else if (!strcmp(a, "--help") || !strcmp(a, "-h"))
            return 1;
        else {
            fprintf(stderr, "bench_codec_vs: unknown or incomplete option '%s'\n", a);
            usage(stderr);
            return 2;
        }
    }
    return 0;
}

int main(int argc, char **argv)
{
    const char *env = getenv("CUB_DATA_DIR");
    const char *data = env && *env ? env : CUB_DATA_DIR_DEFAULT;
    const char *library = CUB_ASSETS_DIR "/clips/bear.cubclips";
    static run r;
    int p = parse(argc, argv, &r, &data, &library);
    if (p) {
        if (p == 1) usage(stdout);
        return p == 1 ? 0 : 2;
    }
    if (vs_acl_codec(&r.codecs[r.codec_count]) == 0)
        r.codec_count++;
    else
        printf("bench_codec_vs: ACL is skipped: ../shared/peers/acl was not there when this was "
               "built\n");
    r.codecs[r.codec_count++] =
        (vs_codec){"ours", keys_encode, keys_pose, keys_time_all, keys_release, &keys_st};
    r.codecs[r.codec_count++] =
        (vs_codec){"seed", seed_encode, seed_pose, seed_time_all, seed_release, &seed_st};
    static const struct {
        const char *set;
        int depth;
    } sets[] = {{"cmu", 1}, {"animdraw", 1}, {"bandai", 2}};
    printf("bench_codec_vs: ratio against raw (10 float32 per bone per sample); error at virtual "
           "vertices\n"
           "3 cm from each bone, object space, every bone and sample (cm); decode per pose, best "
           "of %d\n",
           TIME_RUNS);
    print_head();
    int rc = 0;
    for (size_t s = 0; s < sizeof sets / sizeof *sets && !rc; s++) {
        rc = run_bvh_set(&r, data, sets[s].set, sets[s].depth);
        if (!rc) rc = end_set(&r, sets[s].set);
    }
    if (!rc) rc = run_library(&r, library);
    if (!rc) rc = end_set(&r, "bear");
    if (!rc)
        for (int c = 0; c < r.codec_count; c++)
            print_row("total", r.codecs[c].name, &r.total[c]);
    for (int c = 0; c < r.codec_count; c++) {
        r.codecs[c].release(r.codecs[c].self);
        free(r.total[c].err.v);
    }
    return rc ? 1 : 0;
}

/* cubtool codec-figures — the seed's claim (SEEDS.md § 002) on our clips:
 * the dropped frames restored by Squad, Slerp and Catmull-Rom, each with
 * and without the IK correction, against the source, measured per set of
 * clips (the bear's library, CMU, AnimatedDrawings):
 *   rotation   angle between source and decoded local joint rotations, deg
 *   effector   feet and hands (cub_codec_pick_effectors), world distance, cm
 *   vertex     virtual vertices 3 cm from each bone (joints but end sites)
 *              along its three axes,
 *              the largest of the three, every bone, every frame (as ACL
 *              measures), cm
 *   slip       speed of a decoded effector while the source's is planted
 *              (below 10 cm/s), cm/s; the source's own on the same frames
 * and the sizes: the stream against raw (10 float32 per bone per sample, as
 * ACL counts) and against the seed's own raw (4 floats per joint + 3 for the
 * root per frame). Every frame of every clip counts; nothing is tuned here. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "codec_host.h"
#include "commands.h"
#include "cub/vec.h"
#include "tool_util.h"

#define VERTEX_MM 30.0
#define PLANTED_MM_PER_S 100.0
#define CONFIGS (2 * CUB_CODEC_METHOD_COUNT_)
#define MAX_FILES 64

typedef struct row {
    cub_tool_series rot, eff, vtx;
    double rot_sum, eff_sum, slip_sum, src_slip_sum;
    size_t slip_n;
} row;

typedef struct set_figs {
    const char *name;
    int clips;
    long frames;
    double bytes, raw, seed_raw, decode_s;
    long decoded_frames;
    row rows[CONFIGS];
} set_figs;

static void add(cub_tool_series *s, double x)
{
    cub_tool_series_add(s, x, "codec-figures");
}

/* World positions and rotations of every frame, in doubles (mm). */
typedef struct world {
    cub_dv3 *pos;
    cub_dq *rot;
} world;

static int world_of(const cub_clip *clip, world *w)
{
    int n = clip->frame_count, jn = clip->skel->joint_count;
    w->pos = malloc(sizeof *w->pos * (size_t)n * jn);
    w->rot = malloc(sizeof *w->rot * (size_t)n * jn);
    if (!w->pos || !w->rot) return -1;
    static cub_pose pose;
    cub_vec3 p[CUB_MOTION_MAX_JOINTS];
    cub_quat r[CUB_MOTION_MAX_JOINTS];
    for (int f = 0; f < n; f++) {
        if (cub_motion_clip_get_frame(clip, f, &pose) || cub_motion_forward(clip->skel, &pose, p, r))
            return -1;
        for (int j = 0; j < jn; j++) {
            w->pos[(size_t)f * jn + j] = cub_dv3_from_fx(p[j]);
            w->rot[(size_t)f * jn + j] = cub_dq_from_fx(r[j]);
        }
    }
    return 0;
}

static void world_free(world *w)
{
    free(w->pos);
    free(w->rot);
}

static double vertex_err_mm(cub_dv3 pa, cub_dq ra, cub_dv3 pb, cub_dq rb)
{
    double worst = 0;
    for (int axis = 0; axis < 3; axis++) {
        cub_dv3 v = {axis == 0 ? VERTEX_MM : 0, axis == 1 ? VERTEX_MM : 0, axis == 2 ? VERTEX_MM : 0};
        cub_dv3 a = cub_dv3_add(pa, cub_dq_rotate(ra, v)), b = cub_dv3_add(pb, cub_dq_rotate(rb, v));
        double d = cub_dv3_len(cub_dv3_sub(a, b));
        worst = d > worst ? d : worst;
    }
    return worst;
}

/* The largest rotation error of a clip and where, for --per-clip. */
typedef struct worst {
    double deg;
    int frame, joint;
} worst;

typedef struct compare {
    const cub_clip *src, *dec;
    const world *ws, *wd;
    const int *eff;
    int ne;
    worst *worst; /* NULL: not tracked */
} compare;

static void measure_slip(const compare *c, int f, row *r)
{
    int jn = c->src->skel->joint_count;
    double dt = c->src->frame_ns * 1e-9;
    for (int k = 0; k < c->ne; k++) {
        size_t a = (size_t)f * jn + c->eff[k], b = a + (size_t)jn;
        double vs = cub_dv3_len(cub_dv3_sub(c->ws->pos[b], c->ws->pos[a])) / dt;
        if (vs >= PLANTED_MM_PER_S) continue;
        r->slip_sum += cub_dv3_len(cub_dv3_sub(c->wd->pos[b], c->wd->pos[a])) / dt / 10.0;
        r->src_slip_sum += vs / 10.0;
        r->slip_n++;
    }
}

static void measure(const compare *c, row *r)
{
    int n = c->src->frame_count, jn = c->src->skel->joint_count;
    for (int f = 0; f < n; f++) {
        for (int j = 0; j < jn; j++) {
            size_t i = (size_t)f * jn + j;
            if (c->src->skel->joints[j].is_end_site) continue; /* not a bone */
            double a = cub_dq_angle_between(cub_dq_from_fx(c->src->rot[i]), cub_dq_from_fx(c->dec->rot[i]));
            add(&r->rot, a * 180.0 / CUB_VEC_PI);
            r->rot_sum += a * 180.0 / CUB_VEC_PI;
            if (c->worst && a * 180.0 / CUB_VEC_PI > c->worst->deg)
                *c->worst = (worst){a * 180.0 / CUB_VEC_PI, f, j};
            add(&r->vtx, vertex_err_mm(c->ws->pos[i], c->ws->rot[i], c->wd->pos[i], c->wd->rot[i]) / 10.0);
        }
        for (int k = 0; k < c->ne; k++) {
            size_t i = (size_t)f * jn + c->eff[k];
            double d = cub_dv3_len(cub_dv3_sub(c->ws->pos[i], c->wd->pos[i])) / 10.0;
            add(&r->eff, d);
            r->eff_sum += d;
        }
        if (f + 1 < n) measure_slip(c, f, r);
    }
}

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + t.tv_nsec * 1e-9;
}

/* One decode configuration of one clip into its row. */
static int run_config(const codec_blob *blob, const compare *base, int cfg, set_figs *s,
                      const char *name, worst *w)
{
    cub_codec_opts o = {(cub_codec_method)(cfg / 2), cfg % 2 ? CUB_CODEC_IK_STREAM : CUB_CODEC_IK_OFF};
    codec_decoded d;
    double t0 = now_s();
    if (codec_host_decode(blob, &o, &d, name)) return -1;
    if (cfg == 1) { /* the box's way: Squad with IK */
        s->decode_s += now_s() - t0;
        s->decoded_frames += d.clip.frame_count;
    }
    world wd = {0};
    int rc = world_of(&d.clip, &wd);
    if (!rc) {
        compare c = *base;
        c.dec = &d.clip;
        c.wd = &wd;
        c.worst = cfg == 1 ? w : NULL;
        measure(&c, &s->rows[cfg]);
    }
    world_free(&wd);
    codec_decoded_free(&d);
    return rc;
}

/* The source's largest one-frame rotation change of joint j within the
 * span of kept frames frame f is restored from (f - 4 .. f + 4). */
static double source_step_deg(const cub_clip *clip, int f, int j)
{
    int jn = clip->skel->joint_count;
    double best = 0;
    for (int g = f - 4; g < f + 4; g++) {
        if (g < 0 || g + 1 >= clip->frame_count) continue;
        double a = cub_dq_angle_between(cub_dq_from_fx(clip->rot[(size_t)g * jn + j]),
                                        cub_dq_from_fx(clip->rot[(size_t)(g + 1) * jn + j]));
        best = a > best ? a : best;
    }
    return best * 180.0 / CUB_VEC_PI;
}

static int run_clip(const cub_clip *clip, const char *name, set_figs *s, int per_clip)
{
    codec_blob blob;
    if (codec_host_encode(clip, &blob, name)) return -1;
    int eff[CUB_CODEC_MAX_EFFECTORS];
    int ne = cub_codec_pick_effectors(clip->skel, eff, CUB_CODEC_MAX_EFFECTORS);
    world ws = {0};
    int rc = world_of(clip, &ws);
    compare base = {clip, NULL, &ws, NULL, eff, ne, NULL};
    worst w = {0, 0, 0};
    for (int cfg = 0; cfg < CONFIGS && !rc; cfg++)
        rc = run_config(&blob, &base, cfg, s, name, &w);
    world_free(&ws);
    int jn = clip->skel->joint_count;
    s->clips++;
    s->frames += clip->frame_count;
    s->bytes += (double)blob.len;
    s->raw += codec_raw_bytes(clip);
    s->seed_raw += (16.0 * (codec_raw_bytes(clip) / 40.0 / clip->frame_count) + 12.0) * clip->frame_count;
    if (per_clip)
        fprintf(stderr, "codec-figures: %-24s %5d frames %3d joints %d effectors %7zu bytes %6.2f : 1; "
                "worst rotation %.1f deg (squad + IK), %s frame %d, where the source turns up to "
                "%.1f deg in one frame nearby\n",
                name, clip->frame_count, jn, ne, blob.len, codec_raw_bytes(clip) / (double)blob.len,
                w.deg, clip->skel->joints[w.joint].name, w.frame, source_step_deg(clip, w.frame, w.joint));
    free(blob.data);
    return rc;
}

static int run_bvh_set(const char *dir, int depth, set_figs *s, int per_clip)
{
    char *files[MAX_FILES];
    int n = cub_io_list_bvh(dir, depth, files, MAX_FILES), rc = 0;
    if (n == 0) fprintf(stderr, "codec-figures: no BVH under %s (set skipped)\n", dir);
    for (int i = 0; i < n; i++) {
        codec_source src;
        if (!rc && !codec_source_load(files[i], NULL, &src)) {
            rc = run_clip(src.clip, strrchr(files[i], '/') + 1, s, per_clip);
            codec_source_free(&src);
        } else {
            rc = -1;
        }
        free(files[i]);
    }
    return rc;
}

static int run_library(const char *path, set_figs *s, int per_clip)
{
    cub_library lib;
    cub_diag d = {0};
    char msg[600];
    if (cub_pack_read(path, &lib, &d)) {
        fprintf(stderr, "%s\n", cub_diag_str(&d, msg, sizeof msg));
        return -1;
    }
    int rc = 0;
    for (int i = 0; i < lib.clip_count && !rc; i++)
        rc = run_clip(&lib.clips[i].clip, lib.clips[i].name, s, per_clip);
    cub_library_free(&lib);
    return rc;
}

static void print_set(set_figs *s)
{
    static const char *const methods[] = {"squad", "slerp", "catmull"};
    if (!s->clips) return;
    printf("\n%s: %d clips, %ld frames; %.0f bytes: %.2f : 1 against raw (ACL's 10 floats), "
           "%.2f : 1 against the seed's raw; decode %.1f us per pose (squad + IK, this build)\n",
           s->name, s->clips, s->frames, s->bytes, s->raw / s->bytes, s->seed_raw / s->bytes,
           s->decoded_frames ? 1e6 * s->decode_s / (double)s->decoded_frames : 0.0);
    printf("  %-8s %-3s | rot deg mean   p99    max | effector cm mean   max | vertex cm p99   max | "
           "slip cm/s (source)\n", "method", "ik");
    for (int c = 0; c < CONFIGS; c++) {
        row *r = &s->rows[c];
        double rm = r->rot.n ? r->rot_sum / (double)r->rot.n : 0, em = r->eff.n ? r->eff_sum / (double)r->eff.n : 0;
        double slip = r->slip_n ? r->slip_sum / (double)r->slip_n : 0;
        double src = r->slip_n ? r->src_slip_sum / (double)r->slip_n : 0;
        printf("  %-8s %-3s |     %6.3f %6.3f %6.2f |        %6.3f %6.2f |     %6.3f %6.2f | %6.2f (%5.2f)\n",
               methods[c / 2], c % 2 ? "on" : "off", rm, cub_tool_series_pct(&r->rot, 0.99), cub_tool_series_pct(&r->rot, 1.0), em,
               cub_tool_series_pct(&r->eff, 1.0), cub_tool_series_pct(&r->vtx, 0.99), cub_tool_series_pct(&r->vtx, 1.0), slip, src);
    }
}

static void free_set(set_figs *s)
{
    for (int c = 0; c < CONFIGS; c++) {
        free(s->rows[c].rot.v);
        free(s->rows[c].eff.v);
        free(s->rows[c].vtx.v);
    }
}

static void usage(FILE *f)
{
    fprintf(f, "usage: cubtool codec-figures [--data DIR] [--library FILE] [--per-clip]\n"
               "\n"
               "The seed's codec on the bear's library and on the CMU and AnimatedDrawings\n"
               "BVHs under DIR/mocap: Squad, Slerp and Catmull-Rom restores, IK off and on;\n"
               "rotation, effector, virtual-vertex (3 cm) error, planted-effector slip and\n"
               "the compression ratio (docs/codec.md explains each figure).\n"
               "  --data DIR      the shared data (default $CUB_DATA_DIR, else %s)\n"
               "  --library FILE  the clip library (default %s/clips/bear.cubclips)\n"
               "  --per-clip      one line per clip on stderr\n",
               CUB_DATA_DIR_DEFAULT, CUB_ASSETS_DIR);
}

int cub_cmd_codec_figures(int argc, char **argv)
{
    const char *env = getenv("CUB_DATA_DIR");
    const char *data = env && *env ? env : CUB_DATA_DIR_DEFAULT;
    const char *library = CUB_ASSETS_DIR "/clips/bear.cubclips";
    int per_clip = 0;
    const cub_tool_opt opts[] = {{"--data", &data, NULL}, {"--library", &library, NULL},
                                 {"--per-clip", NULL, &per_clip}};
    cub_tool_parsed p = cub_tool_parse_opts(argc, argv, opts, 3, NULL, 0);
    if (p == CUB_TOOL_HELP) usage(stdout);
    if (p != CUB_TOOL_RUN) return p == CUB_TOOL_HELP ? 0 : 2;
    static set_figs sets[3] = {{.name = "bear library"}, {.name = "cmu"}, {.name = "animdraw"}};
    char dir[1024];
    int rc = run_library(library, &sets[0], per_clip);
    snprintf(dir, sizeof dir, "%s/mocap/cmu", data);
    if (!rc) rc = run_bvh_set(dir, 0, &sets[1], per_clip);
    snprintf(dir, sizeof dir, "%s/mocap/animdraw", data);
    if (!rc) rc = run_bvh_set(dir, 1, &sets[2], per_clip);
    printf("cubtool codec-figures: the seed's codec (SEEDS.md 002), every frame of every clip\n");
    for (int i = 0; i < 3; i++) {
        print_set(&sets[i]);
        free_set(&sets[i]);
    }
    return rc ? 1 : 0;
}

/* The forest's part proposals against the heuristic tracker (firmware/
 * track), joint by joint, on the same renders: the tracker runs on every
 * frame of a clip (it follows the player over time), both are scored on
 * every `every`-th. The forest reads the player's pixels as the render's
 * owner image gives them (a perfect player mask: the tracker finds its
 * player itself). */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cub/forest_train.h"
#include "cub/kinect.h"
#include "cub/track.h"

#define NPIX (CUB_KINECT_WIDTH * CUB_KINECT_HEIGHT)
#define WITHIN_MM 100
#define HALF_Q16 32768

static int near_mm(const float t[3], double x, double y, double z)
{
    double dx = x - t[0], dy = y - t[1], dz = z - t[2];
    return dx * dx + dy * dy + dz * dz <= (double)WITHIN_MM * WITHIN_MM;
}

/* One frame scored: the tracker, the forest, the tracker with its guessed
 * joints (confidence < 1/2) taken from a confident forest joint, and with
 * every joint the forest is confident of taken from the forest. */
void cub_ft_score_joints(const cub_track_skeleton *s, const cub_forest_joints *fj,
                         const cub_synth_truth_frame *tr, cub_ft_vs *vs)
{
    vs->frames++;
    for (int j = 0; j < CUB_KJ_COUNT; j++) {
        if (!tr->visible[j]) continue;
        const float *t = tr->joint_mm[j];
        int trk = near_mm(t, s->joint_mm[j].x / 65536.0, s->joint_mm[j].y / 65536.0,
                          s->joint_mm[j].z / 65536.0);
        int fst = fj->have[j] && near_mm(t, fj->mm[j][0], fj->mm[j][1], fj->mm[j][2]);
        int guessed = s->confidence[j] < HALF_Q16;
        vs->n[j]++;
        vs->have[j] += fj->have[j];
        vs->tracker[j] += trk;
        vs->forest[j] += fst;
        vs->confident[j] += fj->confident[j];
        vs->confident_right[j] += fj->confident[j] && fst;
        vs->guessed[j] += guessed;
        vs->combined[j] += guessed && fj->confident[j] ? fst : trk;
        vs->override[j] += fj->confident[j] ? fst : trk;
    }
}

/* The player's depth in mm from a raw frame, as the firmware reads it. */
static void player_mm(const uint16_t *raw, const uint8_t *owner, uint16_t *mm)
{
    for (int i = 0; i < NPIX; i++)
        mm[i] = owner[i] == 1 ? cub_track_raw_to_mm_int(raw[i]) : 0;
}

typedef struct vs_buf {
    uint16_t *raw, *mm;
    uint8_t *owner;
    cub_forest_points pts;
    void *trk_mem;
    cub_tracker *trk;
} vs_buf;

static void vs_free(vs_buf *b)
{
    free(b->raw), free(b->mm), free(b->owner), free(b->pts.mm), free(b->pts.prob), free(b->pts.part_pts);
    free(b->trk_mem);
}

static cub_err vs_alloc(vs_buf *b, const cub_forest *f, int stride)
{
    memset(b, 0, sizeof(*b));
    int cap = NPIX / (stride * stride) + CUB_KINECT_WIDTH;
    cub_track_desc td = {0};
    size_t sz = (cub_track_mem_size(&td) + 15) / 16 * 16;
    b->raw = malloc(NPIX * sizeof(uint16_t)), b->mm = malloc(NPIX * sizeof(uint16_t));
    b->owner = malloc(NPIX);
    b->pts = (cub_forest_points){malloc((size_t)cap * sizeof(*b->pts.mm)),
                                 malloc((size_t)cap * (size_t)f->classes * sizeof(uint16_t)), 0,
                                 cap, f->classes, stride, malloc((size_t)cap * sizeof(int32_t))};
    b->trk_mem = aligned_alloc(16, sz);
    if (!b->raw || !b->mm || !b->owner || !b->pts.mm || !b->pts.prob || !b->pts.part_pts || !b->trk_mem ||
        cub_track_init(&td, b->trk_mem, sz, &b->trk)) {
        vs_free(b);
        return CUB_ERR_NOMEM;
    }
    return CUB_OK;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

static cub_err run_clip(cub_synth *s, const cub_forest *f, const cub_ft_compare *c, vs_buf *b,
                        cub_ft_vs *vs)
{
    float g[3];
    cub_synth_gravity(s, g);
    cub_vec3 grav = {(cub_q16)(g[0] * 65536), (cub_q16)(g[1] * 65536), (cub_q16)(g[2] * 65536)};
    int total = cub_synth_frame_count(s);
    cub_err err = CUB_OK;
    for (int k = 0; k < total && !err; k++) {
        cub_synth_truth_frame tr;
        cub_track_skeleton sk;
        err = cub_synth_render(s, k, b->raw, &tr, NULL, b->owner);
        if (err) break;
        double t0 = now_s();
        cub_track_frame(b->trk, b->raw, (int64_t)k * 100000, &grav, &sk);
        vs->tracker_s += now_s() - t0, vs->tracker_frames++;
        if (k % c->every) continue;
        player_mm(b->raw, b->owner, b->mm);
        t0 = now_s();
        cub_forest_image im = {b->mm, CUB_KINECT_WIDTH, CUB_KINECT_HEIGHT};
        cub_forest_gather(f, &im, c->stride, &b->pts);
        cub_forest_proposal prop[CUB_PART_COUNT];
        cub_forest_joints fj;
        cub_forest_propose_all(&b->pts, prop);
        cub_forest_joints_of(prop, &fj);
        vs->forest_s += now_s() - t0;
        cub_ft_score_joints(&sk, &fj, &tr, vs);
    }
    return err;
}

cub_err cub_ft_compare_clip(const cub_forest *f, const cub_ft_compare *c, const char *spec,
                            cub_ft_vs *vs, cub_diag *diag)
{
    cub_synth_segment seg = {0};
    snprintf(seg.clip, sizeof(seg.clip), "%s", spec);
    char *at = strchr(seg.clip, '@');
    if (at) *at = 0, seg.from_s = atof(at + 1);
    seg.to_s = seg.from_s + c->seconds;
    cub_synth_desc d = {.data_dir = c->data_dir, .seed = c->seed, .yaw_segment_s = 1.5f,
                        .max_travel_mm = 700, .fps = 10};
    cub_synth *s = NULL;
    cub_err err = cub_synth_open(&d, &seg, 1, &s, diag);
    if (err) return err;
    vs_buf b;
    err = vs_alloc(&b, f, c->stride);
    if (!err) {
        err = run_clip(s, f, c, &b, vs);
        vs_free(&b);
    }
    cub_synth_close(s);
    return err;
}

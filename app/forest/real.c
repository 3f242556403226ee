/* The forest beside the tracker on real Kinect frames with hand labels
 * (tests/labels/: a joint's pixel, its 3D point the median surface depth
 * around it plus the joint's depth behind the surface, as test_tracker
 * makes it). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/forest_train.h"
#include "cub/track.h"

#define W CUB_KINECT_WIDTH
#define H CUB_KINECT_HEIGHT
#define NPIX (W * H)

/* A raw frame as fakenect writes it: 640x480 little-endian u16 at the
 * file's end (after the PGM header). */
/* The frame of label l; a frame that is not there names the label's line. */
static cub_err load_raw(const char *dir, const cub_ft_labels *lab, const cub_ft_label *l,
                        uint16_t *raw, cub_diag *diag)
{
    char path[4096];
    snprintf(path, sizeof(path), "%s/%s", dir, l->frame);
    FILE *f = fopen(path, "rb");
    static uint8_t buf[NPIX * 2];
    size_t got = 0;
    if (f && !fseek(f, -(long)sizeof(buf), SEEK_END)) got = fread(buf, 1, sizeof(buf), f);
    if (f) fclose(f);
    if (got != sizeof(buf))
        return cub_diag_fail(diag, CUB_ERR_IO, lab->name, l->line,
                             "frame %s: not there or not a 640x480 16-bit depth frame", path);
    for (int i = 0; i < NPIX; i++)
        raw[i] = (uint16_t)(buf[2 * i] | buf[2 * i + 1] << 8);
    return CUB_OK;
}

/* The joint's depth behind the surface for the adult of the real frames
 * (tests/labels/README.md). */
static int behind_mm(int j)
{
    if (j == CUB_KJ_HEAD) return 95;
    if (j == CUB_KJ_SHOULDER_L || j == CUB_KJ_SHOULDER_R) return 50;
    if (j == CUB_KJ_ELBOW_L || j == CUB_KJ_ELBOW_R) return 35;
    return 15;
}

static int cmp_int(const void *a, const void *b)
{
    return *(const int *)a - *(const int *)b;
}

/* The label's 3D point: the median depth of the 11x11 pixels around it. */
static int label_point(const uint16_t *raw, const cub_ft_label *l, float out[3])
{
    int zs[121], n = 0;
    for (int v = l->v - 5; v <= l->v + 5; v++)
        for (int u = l->u - 5; u <= l->u + 5; u++)
            if (u >= 0 && v >= 0 && u < W && v < H && cub_track_raw_to_mm_int(raw[v * W + u]))
                zs[n++] = cub_track_raw_to_mm_int(raw[v * W + u]);
    if (!n) return 0;
    qsort(zs, (size_t)n, sizeof(int), cmp_int);
    float z = (float)(zs[n / 2] + behind_mm(l->joint));
    out[0] = (float)(l->u - CUB_KINECT_CX) * z / CUB_KINECT_FOCAL_PX;
    out[1] = (float)(CUB_KINECT_CY - l->v) * z / CUB_KINECT_FOCAL_PX;
    out[2] = z;
    return 1;
}

/* The player for the forest: the readings within `band` mm of the
 * tracker's spine (the tracker found the player; the frames have no
 * floor or room, a second person stands 0.6 m behind). */
static void player_band(const uint16_t *raw, const cub_track_skeleton *s, int band, uint16_t *mm)
{
    int32_t zc = s->joint_mm[CUB_KJ_SPINE].z >> 16;
    for (int i = 0; i < NPIX; i++) {
        int32_t z = cub_track_raw_to_mm_int(raw[i]);
        mm[i] = (uint16_t)(z && z > zc - band && z < zc + band ? z : 0);
    }
}

/* The truth frame of one labelled frame (labels [from, to)). */
static void truth_of(const uint16_t *raw, const cub_ft_labels *lab, int from, int to,
                     cub_synth_truth_frame *tr)
{
    memset(tr, 0, sizeof(*tr));
    for (int k = from; k < to; k++)
        if (lab->l[k].u >= 0)
            tr->visible[lab->l[k].joint] =
                (uint8_t)label_point(raw, &lab->l[k], tr->joint_mm[lab->l[k].joint]);
}

cub_err cub_ft_compare_real(const cub_forest *f, const cub_ft_real *r, const cub_ft_labels *lab,
                            cub_ft_vs *vs, cub_diag *diag)
{
    cub_track_desc td = {.forest = r->seam ? f : NULL};
    int stride = r->stride;
    size_t sz = (cub_track_mem_size(&td) + 15) / 16 * 16;
    int cap = NPIX / (stride * stride) + W;
    uint16_t *raw = malloc(NPIX * 2), *mm = malloc(NPIX * 2);
    cub_forest_points pts = {malloc((size_t)cap * sizeof(*pts.mm)),
                             malloc((size_t)cap * (size_t)f->classes * 2), 0, cap, f->classes,
                             stride, NULL};
    void *mem = aligned_alloc(16, sz);
    cub_tracker *t = NULL;
    cub_err err = raw && mm && pts.mm && pts.prob && mem ? cub_track_init(&td, mem, sz, &t)
                                                          : CUB_ERR_NOMEM;
    for (int k = 0, next, frame = 0; k < lab->n && !err; k = next, frame++) {
        for (next = k; next < lab->n && !strcmp(lab->l[next].frame, lab->l[k].frame); next++) {
        }
        err = load_raw(r->dir, lab, &lab->l[k], raw, diag);
        if (err) break;
        cub_track_skeleton s;
        cub_synth_truth_frame tr;
        cub_track_frame(t, raw, (int64_t)frame * 33333, NULL, &s);
        player_band(raw, &s, 600, mm);
        cub_forest_image im = {mm, W, H};
        cub_forest_gather(f, &im, stride, &pts);
        cub_forest_proposal prop[CUB_PART_COUNT];
        cub_forest_joints fj;
        cub_forest_propose_all(&pts, prop);
        cub_forest_joints_of(prop, &fj);
        truth_of(raw, lab, k, next, &tr);
        cub_ft_score_joints(&s, &fj, &tr, vs);
    }
    free(raw), free(mm), free(pts.mm), free(pts.prob), free(mem);
    return err;
}

/* Part proposals: classified pixels to 3D points, and a weighted mean
 * shift per part (cub/forest.h explains the method). Integers only. */
#include "cub/forest.h"
#include "cub/kinect.h"

void cub_forest_point_at(int u, int v, int32_t z_mm, int32_t out[3])
{
    out[0] = (int32_t)((int64_t)(u - CUB_KINECT_CX) * z_mm / CUB_KINECT_FOCAL_PX);
    out[1] = (int32_t)((int64_t)(CUB_KINECT_CY - v) * z_mm / CUB_KINECT_FOCAL_PX);
    out[2] = z_mm;
}

int cub_forest_gather(const cub_forest *f, const cub_forest_image *im, int stride,
                      cub_forest_points *pts)
{
    uint32_t score[CUB_FOREST_MAX_CLASSES];
    pts->n = 0;
    pts->stride = stride > 0 ? stride : 1;
    if (pts->classes != f->classes) return 0;
    for (int y = 0; y < im->h; y += pts->stride)
        for (int x = 0; x < im->w && pts->n < pts->capacity; x += pts->stride) {
            int32_t z = im->mm[y * im->w + x];
            if (!z) continue;
            cub_forest_classify(f, im, x, y, score);
            uint16_t *p = pts->prob + (size_t)pts->n * (size_t)f->classes;
            for (int c = 0; c < f->classes; c++)
                p[c] = (uint16_t)(score[c] / (uint32_t)f->trees);
            cub_forest_point_at(x, y, z, pts->mm[pts->n++]);
        }
    return pts->n;
}

/* A point's say in its part's density: probability x z^2 (the surface its
 * pixel covers), scaled so that sums of weight x kernel x mm fit 64 bits;
 * 0 when it is left out. */
static int64_t weight(const cub_forest_points *pts, int i, int part, uint16_t min_prob)
{
    uint16_t p = pts->prob[(size_t)i * (size_t)pts->classes + (size_t)part];
    if (!p || p < min_prob) return 0;
    int64_t z = pts->mm[i][2];
    return ((int64_t)p * ((z * z) >> 10)) >> 16;
}

static int64_t dist2(const int32_t a[3], const int64_t b[3])
{
    int64_t d = 0;
    for (int k = 0; k < 3; k++)
        d += (a[k] - b[k]) * (a[k] - b[k]);
    return d;
}

/* The kernel, 256 at the centre, 0 from r on. */
static int64_t kernel(int64_t d2, int64_t r2)
{
    return d2 < r2 ? ((r2 - d2) << 8) / r2 : 0;
}

typedef struct shift_ctx {
    const cub_forest_points *pts;
    int part;
    const cub_forest_shift *sh;
    int64_t r2;
    const int32_t *list; /* the part's points (pts->part_pts), NULL: every point */
    int m;               /* how many points to visit */
} shift_ctx;

/* The k-th point to visit, in the points' own order either way (so the
 * sums, hence the modes, are the same with or without the list). */
static int point_of(const shift_ctx *c, int k)
{
    return c->list ? c->list[k] : k;
}

/* List the part's points (weight > 0) once when there is room for it. */
static void list_part(shift_ctx *c)
{
    c->m = c->pts->n;
    c->list = c->pts->part_pts;
    if (!c->list) return;
    int32_t *out = c->pts->part_pts;
    int m = 0;
    for (int i = 0; i < c->pts->n; i++)
        if (weight(c->pts, i, c->part, c->sh->min_prob)) out[m++] = i;
    c->m = m;
}

/* One mean-shift step from m: the kernel-weighted mean into m; returns
 * the kernel weight (0: nothing within r, m unchanged). */
static int64_t step(const shift_ctx *c, int64_t m[3])
{
    int64_t s = 0, sx[3] = {0, 0, 0};
    for (int q = 0; q < c->m; q++) {
        int i = point_of(c, q);
        int64_t w = weight(c->pts, i, c->part, c->sh->min_prob);
        if (!w) continue;
        int64_t wk = w * kernel(dist2(c->pts->mm[i], m), c->r2);
        s += wk;
        for (int k = 0; k < 3; k++)
            sx[k] += wk * c->pts->mm[i][k];
    }
    if (s)
        for (int k = 0; k < 3; k++)
            m[k] = sx[k] / s;
    return s;
}

/* Shift from m until it moves no more than a millimetre; the mode's weight. */
static int64_t climb(const shift_ctx *c, int64_t m[3])
{
    int64_t s = 0;
    for (int it = 0; it < CUB_FOREST_SHIFT_STEPS; it++) {
        int64_t before[3] = {m[0], m[1], m[2]};
        s = step(c, m);
        int32_t b32[3] = {(int32_t)before[0], (int32_t)before[1], (int32_t)before[2]};
        if (!s || dist2(b32, m) <= 1) break;
    }
    return s;
}

/* The heaviest point farther than r from every mode so far; -1 if none. */
static int next_start(const shift_ctx *c, int64_t modes[][3], int nmodes)
{
    int best = -1;
    int64_t best_w = 0;
    for (int q = 0; q < c->m; q++) {
        int i = point_of(c, q);
        int64_t w = weight(c->pts, i, c->part, c->sh->min_prob);
        if (w <= best_w) continue;
        int far = 1;
        for (int k = 0; k < nmodes && far; k++)
            far = dist2(c->pts->mm[i], modes[k]) >= c->r2;
        if (far) best = i, best_w = w;
    }
    return best;
}

/* Near the mode m (within r): the surface (mm^2) voting for the part,
 * and the share of the part's whole weight (Q16.16). */
static void tally(const shift_ctx *c, const int64_t m[3], cub_forest_proposal *out)
{
    int64_t a = 0, near = 0, all = 0;
    for (int q = 0; q < c->m; q++) {
        int i = point_of(c, q);
        int64_t w = weight(c->pts, i, c->part, c->sh->min_prob);
        if (!w) continue;
        all += w;
        if (dist2(c->pts->mm[i], m) >= c->r2) continue;
        near += w;
        int64_t z = c->pts->mm[i][2];
        a += (int64_t)c->pts->prob[(size_t)i * (size_t)c->pts->classes + (size_t)c->part] *
             ((z * z) >> 8);
    }
    int64_t st = c->pts->stride;
    a = a * st * st / ((int64_t)CUB_KINECT_FOCAL_PX * CUB_KINECT_FOCAL_PX * 256);
    out->area_mm2 = a > INT32_MAX ? INT32_MAX : (int32_t)a;
    out->share = (cub_q16)(all ? (near << 16) / all : 0);
}

void cub_forest_propose(const cub_forest_points *pts, int part, const cub_forest_shift *sh,
                        cub_forest_proposal *out)
{
    *out = (cub_forest_proposal){0};
    if (part < 0 || part >= pts->classes || sh->radius_mm <= 0) return;
    shift_ctx c = {pts, part, sh, (int64_t)sh->radius_mm * sh->radius_mm, NULL, 0};
    list_part(&c);
    int64_t modes[CUB_FOREST_STARTS][3], best_s = 0;
    int n = 0, best = -1;
    for (; n < CUB_FOREST_STARTS; n++) {
        int i = next_start(&c, modes, n);
        if (i < 0) break;
        for (int k = 0; k < 3; k++)
            modes[n][k] = pts->mm[i][k];
        int64_t s = climb(&c, modes[n]);
        if (s > best_s) best_s = s, best = n;
    }
    if (best < 0) return;
    out->found = 1;
    tally(&c, modes[best], out);
    for (int k = 0; k < 3; k++)
        out->mm[k] = (int32_t)modes[best][k];
    out->mm[2] += sh->push_mm;
}

/* Mutation (SEEDS.md § 004, eq. 3-2 and algorithm 3.15): joint activity,
 * the PCA that makes the two parents' activities comparable (ours), the
 * mutation set Mu_s and the population skeleton C_p. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cub/evolve.h"

/* The bone joint j turns: the mean of its children's rest offsets, or, for
 * a leaf, its own offset. */
static cub_dv3 bone_of(const cub_skeleton *s, int j)
{
    cub_dv3 sum = {0, 0, 0};
    int n = 0;
    for (int c = j + 1; c < s->joint_count; c++)
        if (s->joints[c].parent == j) {
            sum = cub_dv3_add(sum, cub_dv3_from_fx(s->joints[c].offset_mm));
            n++;
        }
    return n ? cub_dv3_scale(sum, 1.0 / n) : cub_dv3_from_fx(s->joints[j].offset_mm);
}

void cub_evolve_activity(const cub_evolve_motion *m, double *act_deg)
{
    for (int j = 0; j < m->skel.joint_count; j++) {
        cub_dv3 bone = cub_dv3_norm(bone_of(&m->skel, j), cub_dv3_make(0, 1, 0));
        double sum = 0, sum2 = 0;
        int n = 0;
        cub_dv3 prev = cub_dq_rotate(*cub_evolve_rot(m, 0, j), bone);
        for (int f = 1; f < m->frames; f++) {
            cub_dv3 x = cub_dq_rotate(*cub_evolve_rot(m, f, j), bone);
            double th = cub_dv3_angle(prev, x) * 180.0 / CUB_VEC_PI;
            sum += th;
            sum2 += th * th;
            n++;
            prev = x;
        }
        double mean = n ? sum / n : 0;
        act_deg[j] = n ? sqrt(fmax(0.0, sum2 / n - mean * mean)) : 0;
    }
}

static int candidate(const cub_skeleton *s, int j)
{
    return j > 0 && !s->joints[j].is_end_site;
}

/* act[] to z-scores over the skeleton's candidates (all 0 when flat). */
static void standardise(const cub_skeleton *s, double *act)
{
    double sum = 0, sum2 = 0;
    int n = 0;
    for (int j = 0; j < s->joint_count; j++)
        if (candidate(s, j)) {
            sum += act[j];
            sum2 += act[j] * act[j];
            n++;
        }
    double mean = n ? sum / n : 0, sd = n ? sqrt(fmax(0.0, sum2 / n - mean * mean)) : 0;
    for (int j = 0; j < s->joint_count; j++)
        act[j] = sd > 1e-12 ? (act[j] - mean) / sd : 0;
}

/* The first principal axis of the points (x[i], y[i]), pointing into the
 * first quadrant: the eigenvector of the 2x2 covariance's larger value. */
static cub_dv3 principal_axis(const double *x, const double *y, int n)
{
    double mx = 0, my = 0, sxx = 0, syy = 0, sxy = 0;
    for (int i = 0; i < n; i++)
        mx += x[i], my += y[i];
    mx /= n ? n : 1;
    my /= n ? n : 1;
    for (int i = 0; i < n; i++) {
        sxx += (x[i] - mx) * (x[i] - mx);
        syy += (y[i] - my) * (y[i] - my);
        sxy += (x[i] - mx) * (y[i] - my);
    }
    double ang = 0.5 * atan2(2 * sxy, sxx - syy);
    cub_dv3 u = {cos(ang), sin(ang), 0};
    if (sxx + syy < 1e-12) u = cub_dv3_make(sqrt(0.5), sqrt(0.5), 0);
    return u.x + u.y < 0 ? cub_dv3_scale(u, -1) : u;
}

/* score[j] = the PCA value of each meta candidate, rescaled to 0..1. */
static void pca_scores(const cub_evolve_meta *meta, const double *z1, const double *z2,
                       double *score)
{
    double x[CUB_EVOLVE_MAX_JOINTS], y[CUB_EVOLVE_MAX_JOINTS];
    int idx[CUB_EVOLVE_MAX_JOINTS], n = 0;
    for (int j = 0; j < meta->skel.joint_count; j++) {
        score[j] = 1;
        if (!candidate(&meta->skel, j)) continue;
        int own = meta->src[j], other = meta->from[j] == 1 ? meta->partner[j] : -1;
        x[n] = meta->from[j] == 1 ? z1[own] : z2[own];
        y[n] = other >= 0 ? z2[other] : x[n];
        idx[n++] = j;
    }
    cub_dv3 u = principal_axis(x, y, n);
    double lo = INFINITY, hi = -INFINITY, v[CUB_EVOLVE_MAX_JOINTS];
    for (int i = 0; i < n; i++) {
        v[i] = x[i] * u.x + y[i] * u.y;
        lo = fmin(lo, v[i]);
        hi = fmax(hi, v[i]);
    }
    for (int i = 0; i < n; i++)
        score[idx[i]] = hi > lo ? (v[i] - lo) / (hi - lo) : 0;
}

/* Mark the count lowest-scored candidates; a removed joint's end sites go too. */
static void choose(const cub_evolve_meta *meta, int count, cub_evolve_pop *pop)
{
    const cub_skeleton *s = &meta->skel;
    for (int k = 0; k < count; k++) {
        int best = -1;
        for (int j = 0; j < s->joint_count; j++)
            if (candidate(s, j) && !pop->removed[j] &&
                (best < 0 || pop->score[j] < pop->score[best]))
                best = j;
        if (best < 0) break;
        pop->removed[best] = 1;
        pop->removed_count++;
    }
    for (int j = 1; j < s->joint_count; j++)
        if (s->joints[j].is_end_site && pop->removed[s->joints[j].parent]) pop->removed[j] = 1;
}

/* C_p: the kept joints in meta order, each linked to its nearest kept
 * ancestor with the skipped rest offsets summed (rest rotations are the
 * identity, so the rest pose is unchanged). */
static cub_err build_pop(const cub_evolve_meta *meta, cub_evolve_pop *pop, cub_diag *diag)
{
    const cub_skeleton *s = &meta->skel;
    cub_motion_skeleton_reset(&pop->skel);
    for (int j = 0; j < s->joint_count; j++) {
        pop->child[j] = -1;
        if (pop->removed[j]) continue;
        cub_dv3 off = cub_dv3_from_fx(s->joints[j].offset_mm);
        int p = s->joints[j].parent;
        for (; p >= 0 && pop->removed[p]; p = s->joints[p].parent)
            off = cub_dv3_add(off, cub_dv3_from_fx(s->joints[p].offset_mm));
        pop->relinked += p != s->joints[j].parent;
        int at = -1;
        cub_err err = cub_motion_skeleton_add(&pop->skel, s->joints[j].name,
                                              p < 0 ? -1 : pop->child[p], cub_dv3_to_fx(off), &at);
        if (err)
            return cub_diag_fail(diag, err, "(mutation)", 0, "cannot keep joint \"%s\"",
                                 s->joints[j].name);
        pop->skel.joints[at].is_end_site = s->joints[j].is_end_site;
        pop->child[j] = at;
        pop->meta[at] = j;
    }
    return CUB_OK;
}

cub_err cub_evolve_mutate(const cub_evolve_meta *meta, const cub_evolve_motion *p1,
                          const cub_evolve_motion *p2, const cub_evolve_mutation *cfg,
                          cub_evolve_pop *out, cub_diag *diag)
{
    if (!meta || !p1 || !p2 || !out)
        return cub_diag_fail(diag, CUB_ERR_ARG, "(mutation)", 0, "no input");
    memset(out, 0, sizeof(*out));
    static double z1[CUB_EVOLVE_MAX_JOINTS], z2[CUB_EVOLVE_MAX_JOINTS];
    cub_evolve_activity(p1, z1);
    cub_evolve_activity(p2, z2);
    standardise(&p1->skel, z1);
    standardise(&p2->skel, z2);
    pca_scores(meta, z1, z2, out->score);
    for (int j = 0; j < meta->skel.joint_count && cfg; j++)
        if (isfinite(cfg->weight[j])) out->score[j] += cfg->weight[j];
    choose(meta, cfg && cfg->count > 0 ? cfg->count : 0, out);
    return build_pop(meta, out, diag);
}

/* Survivor (SEEDS.md § 004, "spacetime" fitness; the formula of d(t) is
 * lost, ours): parent 2 laid against parent 1 where the energy loss is
 * least, the child's motion C_mp(t) = C_m1(t) + x·d(t). Rotations are
 * compared relative to each parent's mean pose: a first try on absolute
 * local rotations crossed a dog's rest pose into a human's (mean |d| 86
 * degrees on 02_01 x a dog walk, a child that fell over at x = 0.5). */
#include <math.h>
#include <string.h>

#include "cub/evolve.h"

/* The rotation vector (axis * angle, radians) of a unit quaternion. */
static cub_dv3 q_log(cub_dq q)
{
    if (q.w < 0) q = (cub_dq){-q.w, -q.x, -q.y, -q.z};
    cub_dv3 v = {q.x, q.y, q.z};
    double s = cub_dv3_len(v);
    if (s < 1e-15) return cub_dv3_scale(v, 2.0);
    return cub_dv3_scale(v, 2.0 * atan2(s, q.w) / s);
}

static cub_dq q_exp(cub_dv3 r)
{
    double a = cub_dv3_len(r);
    if (a == 0) return cub_dq_identity();
    double k = sin(0.5 * a) / a;
    return (cub_dq){cos(0.5 * a), r.x * k, r.y * k, r.z * k};
}

/* Several partners that are a chain in p2: each the parent of the next. */
static int is_chain(const cub_evolve_meta *meta, const cub_skeleton *b, int j)
{
    for (int i = 1; i < meta->partner_count[j]; i++)
        if (b->joints[meta->partners[j][i]].parent != meta->partners[j][i - 1]) return 0;
    return 1;
}

cub_dq cub_evolve_partner_rot(const cub_evolve_meta *meta, const cub_evolve_motion *p2, int f,
                              int j)
{
    int n = meta->from[j] == 1 ? meta->partner_count[j] : 0;
    if (n == 0) return cub_dq_identity();
    const int *b = meta->partners[j];
    cub_dq first = *cub_evolve_rot(p2, f, b[0]), acc = first;
    int chain = is_chain(meta, &p2->skel, j);
    for (int i = 1; i < n; i++) {
        cub_dq q = *cub_evolve_rot(p2, f, b[i]);
        double k = cub_dq_dot(q, first) < 0 ? -1 : 1;
        acc = chain ? cub_dq_mul(acc, q)
                    : (cub_dq){acc.w + k * q.w, acc.x + k * q.x, acc.y + k * q.y, acc.z + k * q.z};
    }
    return n == 1 || chain ? acc : cub_dq_norm(acc);
}

void cub_evolve_partner_means(const cub_evolve_meta *meta, const cub_evolve_motion *p2,
                              cub_dq *mean)
{
    for (int j = 0; j < meta->skel.joint_count; j++) {
        cub_dq first = cub_evolve_partner_rot(meta, p2, 0, j), sum = {0, 0, 0, 0};
        for (int f = 0; f < p2->frames; f++) {
            cub_dq q = cub_evolve_partner_rot(meta, p2, f, j);
            double k = cub_dq_dot(q, first) < 0 ? -1 : 1;
            sum = (cub_dq){sum.w + k * q.w, sum.x + k * q.x, sum.y + k * q.y, sum.z + k * q.z};
        }
        mean[j] = cub_dq_norm(sum);
    }
}

typedef struct surv {
    const cub_evolve_meta *meta;
    const cub_evolve_pop *pop;
    const cub_evolve_motion *p1, *p2;
    double x;
    int offset;
    /* inv_mean2: per parent-1 joint, of its partners' combined rotation */
    cub_dq inv_mean1[CUB_EVOLVE_MAX_JOINTS], inv_mean2[CUB_EVOLVE_MAX_JOINTS];
} surv;

static cub_dq rot1(const surv *s, int f, int j)
{
    return *cub_evolve_rot(s->p1, f % s->p1->frames, j);
}
static cub_dq rot2(const surv *s, int f, int j)
{
    return *cub_evolve_rot(s->p2, (f + s->offset) % s->p2->frames, j);
}
/* A joint's rotation relative to its mean over the clip: the parents' rest
 * poses differ (a dog's rest is not a human's), their movements compare. */
static cub_dq delta1(const surv *s, int f, int j)
{
    return cub_dq_mul(s->inv_mean1[j], rot1(s, f, j));
}
/* Parent 2's movement at parent 1's joint j (its partners'), frame f. */
static cub_dq delta2(const surv *s, int f, int j)
{
    int f2 = (f + s->offset) % s->p2->frames;
    return cub_dq_mul(s->inv_mean2[j], cub_evolve_partner_rot(s->meta, s->p2, f2, j));
}

void cub_evolve_mean_pose(const cub_evolve_motion *m, cub_dq *mean)
{
    for (int j = 0; j < m->skel.joint_count; j++) {
        cub_dq first = *cub_evolve_rot(m, 0, j), sum = {0, 0, 0, 0};
        for (int f = 0; f < m->frames; f++) {
            cub_dq q = *cub_evolve_rot(m, f, j);
            double k = cub_dq_dot(q, first) < 0 ? -1 : 1;
            sum = (cub_dq){sum.w + k * q.w, sum.x + k * q.x, sum.y + k * q.y, sum.z + k * q.z};
        }
        mean[j] = cub_dq_norm(sum);
    }
}

static void inverse_means(const cub_evolve_motion *m, cub_dq *inv_mean)
{
    cub_evolve_mean_pose(m, inv_mean);
    for (int j = 0; j < m->skel.joint_count; j++)
        inv_mean[j] = cub_dq_conj(inv_mean[j]);
}

/* Energy loss of parent 2 started at its frame o: the sum of
 * sin²(θ/2) = 1 - (q1·q2)² over partners at parent 1's samples (θ the
 * angle between their rotations; no trigonometry in the O(frames²) loop,
 * as the seed's cost). Stops once past bound: o cannot win. *n: the terms. */
static double energy_at(surv *s, int o, int step, double bound, int *n)
{
    s->offset = o;
    double sum = 0;
    *n = 0;
    for (int f = 0; f < s->p1->frames && sum <= bound; f += step)
        for (int j = 1; j < s->p1->skel.joint_count; j++) {
            if (s->meta->partner[j] < 0) continue;
            double d = cub_dq_dot(delta1(s, f, j), delta2(s, f, j));
            sum += 1 - d * d;
            ++*n;
        }
    return sum;
}

static void best_window(surv *s, int step, int in_time, cub_evolve_survivor_report *rep)
{
    int best = 0, n = 0, n_best = 0;
    double sum_best = INFINITY;
    for (int o = 0; o < (in_time ? 1 : s->p2->frames); o++) {
        double sum = energy_at(s, o, step, sum_best, &n);
        if (sum < sum_best) sum_best = sum, best = o, n_best = n;
    }
    s->offset = best;
    rep->offset = best;
    rep->energy = n_best ? sum_best / n_best : 0;
}

/* Meta joint j's local rotation in the child at frame f; *d_deg gets |d|. */
static cub_dq meta_rot(const surv *s, int f, int j, double *d_deg)
{
    const cub_evolve_meta *m = s->meta;
    *d_deg = -1;
    if (m->from[j] == 2) return rot2(s, f, m->src[j]);
    cub_dq q1 = rot1(s, f, j);
    if (j == 0 || m->partner[j] < 0) return q1;
    cub_dv3 d = q_log(cub_dq_mul(cub_dq_conj(delta1(s, f, j)), delta2(s, f, j)));
    *d_deg = cub_dv3_len(d) * 180.0 / CUB_VEC_PI;
    return cub_dq_mul(q1, q_exp(cub_dv3_scale(d, s->x)));
}

static void fill_frame(const surv *s, int f, cub_evolve_motion *child, double *d_sum, int *d_n)
{
    static cub_dq q[CUB_EVOLVE_MAX_JOINTS];
    const cub_skeleton *ms = &s->meta->skel;
    for (int j = 0; j < ms->joint_count; j++) {
        double d;
        q[j] = meta_rot(s, f, j, &d);
        if (d >= 0 && !s->pop->removed[j]) *d_sum += d, ++*d_n;
    }
    /* parent 1 looping under a longer parent 2 carries on from where its
     * last loop ended (on the floor: x and z), not from its first place */
    const cub_evolve_motion *p1 = s->p1;
    cub_dv3 lap = cub_dv3_sub(p1->root_mm[p1->frames - 1], p1->root_mm[0]);
    double laps = (double)(f / p1->frames);
    child->root_mm[f] =
        cub_dv3_add(p1->root_mm[f % p1->frames], cub_dv3_make(laps * lap.x, 0, laps * lap.z));
    for (int c = 0; c < child->skel.joint_count; c++) {
        int j = s->pop->meta[c];
        cub_dq r = q[j];
        /* a re-linked joint carries the rotations of the removed joints above it */
        for (int p = ms->joints[j].parent; p >= 0 && s->pop->removed[p]; p = ms->joints[p].parent)
            r = cub_dq_mul(q[p], r);
        *cub_evolve_rot(child, f, c) = r;
    }
}

cub_err cub_evolve_survivor(const cub_evolve_meta *meta, const cub_evolve_pop *pop,
                            const cub_evolve_motion *p1, const cub_evolve_motion *p2,
                            const cub_evolve_survivor_cfg *cfg, cub_evolve_motion *child,
                            cub_evolve_survivor_report *rep, cub_diag *diag)
{
    static cub_evolve_survivor_report none;
    if (!rep) rep = &none;
    memset(rep, 0, sizeof(*rep));
    if (!meta || !pop || !p1 || !p2 || !child || p1->frames < 1 || p2->frames < 1)
        return cub_diag_fail(diag, CUB_ERR_ARG, "(survivor)", 0, "no input");
    if (fabs(p1->fps - p2->fps) > 1e-6 * p1->fps)
        return cub_diag_fail(diag, CUB_ERR_ARG, "(survivor)", 0,
                             "the parents' rates differ (%.3f and %.3f fps): resample first",
                             p1->fps, p2->fps);
    double x = cfg ? cfg->blend : 0;
    if (!isfinite(x))
        return cub_diag_fail(diag, CUB_ERR_ARG, "(survivor)", 0, "blend is not a number");
    int step = cfg && cfg->step > 0 ? cfg->step : CUB_EVOLVE_SAMPLE_STEP;
    static surv s;
    memset(&s, 0, sizeof s);
    s = (surv){.meta = meta, .pop = pop, .p1 = p1, .p2 = p2, .x = x};
    inverse_means(p1, s.inv_mean1);
    cub_evolve_partner_means(meta, p2, s.inv_mean2);
    for (int j = 0; j < meta->skel.joint_count; j++)
        s.inv_mean2[j] = cub_dq_conj(s.inv_mean2[j]);
    best_window(&s, step, cfg && cfg->in_time, rep);
    int frames = p1->frames > p2->frames ? p1->frames : p2->frames;
    cub_err err = cub_evolve_motion_alloc(&pop->skel, frames, p1->fps, child);
    if (err) return cub_diag_fail(diag, err, "(survivor)", 0, "out of memory");
    double d_sum = 0;
    int d_n = 0;
    for (int f = 0; f < frames; f++)
        fill_frame(&s, f, child, &d_sum, &d_n);
    rep->mean_d_deg = d_n ? d_sum / d_n : 0;
    return CUB_OK;
}

/* The floor constraint (SEEDS.md § 004): no joint below y = 0, corrected
 * (not rejected) by a Jacobian IK step on the joints' rotations. */
#include <math.h>
#include <string.h>

#include "cub/evolve.h"

#define FLOOR_CHAIN 3      /* ancestors that move a joint back up */
#define FLOOR_ITERS 24     /* IK steps per frame, one joint each */
#define FLOOR_STEP_RAD 0.5 /* the largest turn one step makes: keep it near linear */
#define FLOOR_EPS_MM 1e-6

typedef struct fk_frame {
    cub_dv3 pos[CUB_EVOLVE_MAX_JOINTS];
    cub_dq rot[CUB_EVOLVE_MAX_JOINTS];
} fk_frame;

static void fk(const cub_evolve_motion *m, int f, fk_frame *w)
{
    for (int j = 0; j < m->skel.joint_count; j++) {
        int p = m->skel.joints[j].parent;
        cub_dq r = *cub_evolve_rot(m, f, j);
        if (p < 0) {
            w->pos[j] = m->root_mm[f];
            w->rot[j] = r;
            continue;
        }
        w->pos[j] = cub_dv3_add(
            w->pos[p], cub_dq_rotate(w->rot[p], cub_dv3_from_fx(m->skel.joints[j].offset_mm)));
        w->rot[j] = cub_dq_mul(w->rot[p], r);
    }
}

static int lowest(const cub_evolve_motion *m, const fk_frame *w)
{
    int low = 0;
    for (int j = 1; j < m->skel.joint_count; j++)
        if (w->pos[j].y < w->pos[low].y) low = j;
    return low;
}

/* One damped least-squares step lifting joint j by dy through its chain:
 * each ancestor k turns about the world axes by J_k^T dy / (J J^T + λ²),
 * where J_k = ∂y_j/∂(rx, ry, rz) at k = ((axis × (p_j - p_k)).y). */
static int lift_step(cub_evolve_motion *m, int f, const fk_frame *w, int j, double dy)
{
    int chain[FLOOR_CHAIN], n = 0;
    for (int k = m->skel.joints[j].parent; k > 0 && n < FLOOR_CHAIN; k = m->skel.joints[k].parent)
        chain[n++] = k;
    cub_dv3 jac[FLOOR_CHAIN];
    double jjt = 1.0; /* λ² = 1 mm²: damping for a chain that is nearly vertical */
    for (int i = 0; i < n; i++) {
        cub_dv3 r = cub_dv3_sub(w->pos[j], w->pos[chain[i]]);
        jac[i] = cub_dv3_make(-r.z, 0, r.x); /* (e_x × r).y, (e_y × r).y, (e_z × r).y */
        jjt += cub_dv3_dot(jac[i], jac[i]);
    }
    if (n == 0 || jjt <= 1.0 + 1e-9) return 0;
    for (int i = 0; i < n; i++) {
        cub_dv3 om = cub_dv3_scale(jac[i], dy / jjt);
        double a = cub_dv3_len(om);
        if (a < 1e-15) continue;
        if (a > FLOOR_STEP_RAD) om = cub_dv3_scale(om, FLOOR_STEP_RAD / a), a = FLOOR_STEP_RAD;
        cub_dq turn = cub_dq_axis_angle(cub_dv3_scale(om, 1.0 / a), a);
        int k = chain[i], p = m->skel.joints[k].parent;
        /* new world W_k = turn * W_k, so local = W_p^-1 turn W_p R_k */
        cub_dq *rk = cub_evolve_rot(m, f, k);
        *rk = cub_dq_norm(
            cub_dq_mul(cub_dq_mul(cub_dq_conj(w->rot[p]), turn), cub_dq_mul(w->rot[p], *rk)));
    }
    return 1;
}

static int count_below(const cub_evolve_motion *m, const fk_frame *w, double *deepest)
{
    int n = 0;
    for (int j = 0; j < m->skel.joint_count; j++)
        if (w->pos[j].y < -FLOOR_EPS_MM) {
            n++;
            *deepest = fmin(*deepest, w->pos[j].y);
        }
    return n;
}

static void fix_frame(cub_evolve_motion *m, int f, fk_frame *w, cub_evolve_floor_report *rep)
{
    double deepest = 0;
    fk(m, f, w);
    int before = count_below(m, w, &deepest);
    rep->below_before += before;
    rep->deepest_mm = fmin(rep->deepest_mm, deepest);
    if (!before) return;
    int changed = 0;
    for (int it = 0; it < FLOOR_ITERS; it++) {
        int j = lowest(m, w);
        if (w->pos[j].y >= -FLOOR_EPS_MM) break;
        changed |= lift_step(m, f, w, j, -w->pos[j].y);
        fk(m, f, w);
    }
    rep->frames_ik += changed;
    int j = lowest(m, w);
    if (w->pos[j].y < -FLOOR_EPS_MM) { /* what IK could not reach: raise the whole body */
        m->root_mm[f].y -= w->pos[j].y;
        rep->frames_lifted++;
        fk(m, f, w);
    }
    double d = 0;
    rep->below_after += count_below(m, w, &d);
}

void cub_evolve_floor(cub_evolve_motion *m, cub_evolve_floor_report *rep)
{
    static cub_evolve_floor_report none;
    if (!rep) rep = &none;
    memset(rep, 0, sizeof(*rep));
    static fk_frame w;
    for (int f = 0; f < m->frames; f++)
        fix_frame(m, f, &w, rep);
}

double cub_evolve_bone_error_mm(const cub_evolve_motion *m, const cub_evolve_pop *pop,
                                const cub_evolve_meta *meta)
{
    static fk_frame w;
    double worst = 0;
    for (int f = 0; f < m->frames; f++) {
        fk(m, f, &w);
        for (int c = 1; c < m->skel.joint_count; c++) {
            int j = pop->meta[c], p = m->skel.joints[c].parent;
            if (pop->meta[p] != meta->skel.joints[j].parent) continue; /* re-linked */
            double rest = cub_dv3_len(cub_dv3_from_fx(meta->skel.joints[j].offset_mm));
            worst = fmax(worst, fabs(cub_dv3_len(cub_dv3_sub(w.pos[c], w.pos[p])) - rest));
        }
    }
    return worst;
}

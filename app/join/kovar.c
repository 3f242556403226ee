/* The point-cloud distance of Kovar, Gleicher and Pighin, "Motion Graphs"
 * (SIGGRAPH 2002), § 3.1, the seed's eq. 5.1:
 *   D = min over θ, x0, z0 of Σ_i w_i ‖p_i − T_{θ,x0,z0} p'_i‖²
 * with T a rotation θ about the vertical (y) then a floor translation.
 * Closed form (their eq. for θ, x0, z0; weights normalised to Σ w_i = 1,
 * bars the weighted means):
 *   θ  = arctan( (Σ w_i (x_i z'_i − x'_i z_i) − (x̄ z̄' − x̄' z̄))
 *              / (Σ w_i (x_i x'_i + z_i z'_i) − (x̄ x̄' + z̄ z̄')) )
 *   x0 = x̄ − x̄' cos θ − z̄' sin θ
 *   z0 = z̄ + x̄' sin θ − z̄' cos θ
 * Derivation (ours, to check the signs): with R_y(θ) q = (x' c + z' s, y',
 * −x' s + z' c), the best translation for a given θ brings the means
 * together (the x0, z0 above); what is left is maximising c·A + s·B with A
 * the denominator and B the numerator, at θ = atan2(B, A). The paper's
 * arctan picks the branch by |θ| < 90°, which can give the worst angle
 * instead of the best: atan2 takes the quadrant from both signs. Heights
 * (y) do not depend on T and add their own squared differences. */
#include <math.h>

#include "cub/join.h"

cub_join_align cub_join_kovar(const cub_dv3 *p, const cub_dv3 *q, const double *w, int n)
{
    double ws = 0, mx = 0, mz = 0, nx = 0, nz = 0, sa = 0, sb = 0;
    for (int i = 0; i < n; i++) {
        double wi = w ? w[i] : 1.0;
        ws += wi;
        mx += wi * p[i].x, mz += wi * p[i].z;
        nx += wi * q[i].x, nz += wi * q[i].z;
        sa += wi * (p[i].x * q[i].x + p[i].z * q[i].z);
        sb += wi * (p[i].x * q[i].z - q[i].x * p[i].z);
    }
    cub_join_align t = {0, 0, 0, 0};
    if (n <= 0 || ws <= 0) return t;
    mx /= ws, mz /= ws, nx /= ws, nz /= ws, sa /= ws, sb /= ws;
    double A = sa - (mx * nx + mz * nz), B = sb - (mx * nz - nx * mz);
    t.theta_rad = atan2(B, A);
    double c = cos(t.theta_rad), s = sin(t.theta_rad);
    t.x0_mm = mx - nx * c - nz * s;
    t.z0_mm = mz + nx * s - nz * c;
    t.d_mm2 = cub_join_kovar_cost(p, q, w, n, &t);
    return t;
}

cub_dv3 cub_join_apply(const cub_join_align *t, cub_dv3 q)
{
    double c = cos(t->theta_rad), s = sin(t->theta_rad);
    return cub_dv3_make(q.x * c + q.z * s + t->x0_mm, q.y, -q.x * s + q.z * c + t->z0_mm);
}

cub_dq cub_join_align_rot(const cub_join_align *t)
{
    return cub_dq_axis_angle(cub_dv3_make(0, 1, 0), t->theta_rad);
}

double cub_join_kovar_cost(const cub_dv3 *p, const cub_dv3 *q, const double *w, int n,
                           const cub_join_align *t)
{
    double ws = 0, sum = 0;
    for (int i = 0; i < n; i++) {
        double wi = w ? w[i] : 1.0;
        cub_dv3 d = cub_dv3_sub(p[i], cub_join_apply(t, q[i]));
        ws += wi;
        sum += wi * cub_dv3_dot(d, d);
    }
    return ws > 0 ? sum / ws : 0;
}

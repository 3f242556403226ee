/* Analytic two-bone leg IK (the law of cosines in the leg's bend plane).
 * The retargeter pins contacts with it; the join pins the planted foot. */
#include <math.h>

#include "cub/join.h"

void cub_join_leg_ik(const cub_skeleton *skel, const cub_join_leg *leg, const cub_dv3 *pos,
                     const cub_dq *rot, const cub_join_goal *goal, cub_dq *local)
{
    int hj = leg->hip, kj = leg->knee, aj = leg->ankle;
    cub_dv3 H = pos[hj], K = pos[kj], A = pos[aj];
    double l1 = cub_dv3_len(cub_dv3_sub(K, H)), l2 = cub_dv3_len(cub_dv3_sub(A, K));
    cub_dv3 ht = cub_dv3_sub(goal->ankle, H);
    double d = cub_dv3_len(ht);
    cub_dv3 u = cub_dv3_norm(ht, cub_dv3_make(0, -1, 0));
    d = fmax(fabs(l1 - l2) + 1e-3, fmin(d, (l1 + l2) * 0.9999));
    cub_dv3 hk = cub_dv3_sub(K, H);
    /* The knee's bend direction: where it bends now, plus a little of the
     * body's forward so a nearly straight leg does not pick a plane from
     * noise (and flip from frame to frame). */
    cub_dv3 b = cub_dv3_add(hk, cub_dv3_scale(goal->forward, 0.1 * l1));
    b = cub_dv3_sub(b, cub_dv3_scale(u, cub_dv3_dot(b, u)));
    b = cub_dv3_norm(b, cub_dv3_make(0, 0, 1));
    double ca = (l1 * l1 + d * d - l2 * l2) / (2 * l1 * d);
    ca = fmax(-1, fmin(1, ca));
    cub_dv3 K2 = cub_dv3_add(
        H, cub_dv3_add(cub_dv3_scale(u, l1 * ca), cub_dv3_scale(b, l1 * sqrt(1 - ca * ca))));
    cub_dv3 A2 = cub_dv3_add(H, cub_dv3_scale(u, d));

    cub_dq wu = cub_dq_mul(cub_dq_arc(hk, cub_dv3_sub(K2, H)), rot[hj]);
    cub_dq wl = cub_dq_mul(wu, local[kj]);
    cub_dv3 shin = cub_dq_rotate(wl, cub_dv3_from_fx(skel->joints[aj].offset_mm));
    wl = cub_dq_mul(cub_dq_arc(shin, cub_dv3_sub(A2, K2)), wl);
    int hp = skel->joints[hj].parent;
    cub_dq parent = hp >= 0 ? rot[hp] : cub_dq_identity();
    local[hj] = cub_dq_norm(cub_dq_mul(cub_dq_conj(parent), wu));
    local[kj] = cub_dq_norm(cub_dq_mul(cub_dq_conj(wu), wl));
    local[aj] = cub_dq_norm(cub_dq_mul(cub_dq_conj(wl), goal->foot));
}

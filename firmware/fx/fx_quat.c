/* fx quaternions: Q2.30 unit quaternions (w, x, y, z), composed and
 * applied with exact 64-bit products rounded once. */
#include "fx_internal.h"

#define ONE_Q30 ((int64_t)1 << 30)

cub_quat cub_fx_quat_identity(void)
{
    return (cub_quat){CUB_QUAT_ONE, 0, 0, 0};
}

/* Rescale four int64 components (|c| < 2^63) to a unit Q2.30 quaternion. */
static cub_quat normalize64(const int64_t c_in[4])
{
    int64_t c[4];
    uint64_t m = 0;
    for (int i = 0; i < 4; i++) {
        c[i] = c_in[i];
        uint64_t mi = c[i] < 0 ? (uint64_t)0 - (uint64_t)c[i] : (uint64_t)c[i];
        if (mi > m) m = mi;
    }
    if (m == 0) return cub_fx_quat_identity();
    /* Bring the largest component into [2^30, 2^31): then the squares sum
     * below 2^64 and the norm has at least 31 significant bits. */
    int down = 0, up = 0;
    while ((m >> down) >= ((uint64_t)1 << 31))
        down++;
    while (((m >> down) << up) < ((uint64_t)1 << 30))
        up++;
    uint64_t n2 = 0;
    for (int i = 0; i < 4; i++) {
        c[i] = (c[i] >> down) * ((int64_t)1 << up);
        n2 += (uint64_t)(c[i] * c[i]);
    }
    int64_t norm = cub_fxi_sqrt64_round(n2); /* >= 2^30 */
    int32_t out[4];
    for (int i = 0; i < 4; i++) {
        int64_t num = c[i] * ONE_Q30; /* < 2^61 */
        int64_t q = ((num < 0 ? -num : num) + norm / 2) / norm;
        out[i] = (int32_t)(num < 0 ? -q : q);
    }
    return (cub_quat){out[0], out[1], out[2], out[3]};
}

cub_quat cub_fx_quat_normalize(cub_quat q)
{
    const int64_t c[4] = {q.w, q.x, q.y, q.z};
    return normalize64(c);
}

cub_quat cub_fx_quat_from_axis_angle(cub_vec3 unit_axis, cub_q16 angle_rad)
{
    /* The axis is renormalised in Q.30 first, so a slightly long or short
     * axis does not leak into the angle. */
    const int64_t ax[3] = {unit_axis.x, unit_axis.y, unit_axis.z};
    uint64_t n2 = 0;
    for (int i = 0; i < 3; i++)
        n2 += (uint64_t)(ax[i] * ax[i]);
    if (n2 == 0) return cub_fx_quat_identity();
    int64_t len = cub_fxi_sqrt64_round(n2);
    int32_t s, c;
    cub_fxi_sincos_q48((int64_t)angle_rad * ((int64_t)1 << 31), &s, &c); /* half angle */
    int64_t comp[4] = {c, 0, 0, 0};
    for (int i = 0; i < 3; i++) {
        int64_t u_q30 = ax[i] * ONE_Q30 / len; /* |ax| * 2^30 < 2^61 */
        comp[i + 1] = u_q30 * s;               /* Q.60, < 2^61 */
    }
    comp[0] *= ONE_Q30;
    return normalize64(comp);
}

cub_quat cub_fx_quat_mul(cub_quat a, cub_quat b)
{
    static const int8_t sw[4] = {1, -1, -1, -1}, sx[4] = {1, 1, 1, -1}, sy[4] = {1, -1, 1, 1},
                        sz[4] = {1, 1, -1, 1};
    const int64_t pw[4] = {(int64_t)a.w * b.w, (int64_t)a.x * b.x, (int64_t)a.y * b.y,
                           (int64_t)a.z * b.z};
    const int64_t px[4] = {(int64_t)a.w * b.x, (int64_t)a.x * b.w, (int64_t)a.y * b.z,
                           (int64_t)a.z * b.y};
    const int64_t py[4] = {(int64_t)a.w * b.y, (int64_t)a.x * b.z, (int64_t)a.y * b.w,
                           (int64_t)a.z * b.x};
    const int64_t pz[4] = {(int64_t)a.w * b.z, (int64_t)a.x * b.y, (int64_t)a.y * b.x,
                           (int64_t)a.z * b.w};
    return (cub_quat){cub_fxi_sat32(cub_fxi_sum_shift(pw, sw, 4, 30)),
                      cub_fxi_sat32(cub_fxi_sum_shift(px, sx, 4, 30)),
                      cub_fxi_sat32(cub_fxi_sum_shift(py, sy, 4, 30)),
                      cub_fxi_sat32(cub_fxi_sum_shift(pz, sz, 4, 30))};
}

static int32_t neg_sat(int32_t v)
{
    return v == INT32_MIN ? INT32_MAX : -v;
}

cub_quat cub_fx_quat_conj(cub_quat q)
{
    return (cub_quat){q.w, neg_sat(q.x), neg_sat(q.y), neg_sat(q.z)};
}

int32_t cub_fx_quat_dot(cub_quat a, cub_quat b)
{
    static const int8_t plus[4] = {1, 1, 1, 1};
    const int64_t p[4] = {(int64_t)a.w * b.w, (int64_t)a.x * b.x, (int64_t)a.y * b.y,
                          (int64_t)a.z * b.z};
    return cub_fxi_sat32(cub_fxi_sum_shift(p, plus, 4, 30));
}

/* One rotation-matrix entry in Q.30: base + sum of sign[i] * p[i] / 2^30,
 * clamped to +-2 (a unit quaternion gives +-1 at most). */
static int64_t matrix_entry(int64_t base, int64_t p0, int8_t s0, int64_t p1, int8_t s1)
{
    const int64_t p[2] = {p0, p1};
    const int8_t s[2] = {s0, s1};
    int64_t e = base + cub_fxi_sum_shift(p, s, 2, 30);
    return e > 2 * ONE_Q30 ? 2 * ONE_Q30 : e < -2 * ONE_Q30 ? -2 * ONE_Q30 : e;
}

cub_vec3 cub_fx_quat_rotate(cub_quat q, cub_vec3 v)
{
    int64_t w = q.w, x = q.x, y = q.y, z = q.z;
    int64_t xx = x * x, yy = y * y, zz = z * z, xy = x * y, xz = x * z, yz = y * z, wx = w * x,
            wy = w * y, wz = w * z;
    const int64_t m[3][3] = {
        {matrix_entry(ONE_Q30, yy, -2, zz, -2), matrix_entry(0, xy, 2, wz, -2),
         matrix_entry(0, xz, 2, wy, 2)},
        {matrix_entry(0, xy, 2, wz, 2), matrix_entry(ONE_Q30, xx, -2, zz, -2),
         matrix_entry(0, yz, 2, wx, -2)},
        {matrix_entry(0, xz, 2, wy, -2), matrix_entry(0, yz, 2, wx, 2),
         matrix_entry(ONE_Q30, xx, -2, yy, -2)},
    };
    static const int8_t plus[3] = {1, 1, 1};
    int32_t out[3];
    for (int r = 0; r < 3; r++) {
        const int64_t p[3] = {m[r][0] * v.x, m[r][1] * v.y, m[r][2] * v.z}; /* < 2^62 */
        out[r] = cub_fxi_sat32(cub_fxi_sum_shift(p, plus, 3, 30));
    }
    return (cub_vec3){out[0], out[1], out[2]};
}

/* The exact Q.60 dot product, rounded to Q.30 but not saturated. */
static int64_t dot_q30(cub_quat a, cub_quat b)
{
    static const int8_t plus[4] = {1, 1, 1, 1};
    const int64_t p[4] = {(int64_t)a.w * b.w, (int64_t)a.x * b.x, (int64_t)a.y * b.y,
                          (int64_t)a.z * b.z};
    return cub_fxi_sum_shift(p, plus, 4, 30);
}

static bool same(cub_quat a, cub_quat b)
{
    return a.w == b.w && a.x == b.x && a.y == b.y && a.z == b.z;
}

/* Linear mix (1-t)*a + t*s*b in Q.46, exact, then one rounding. */
static cub_quat nlerp_signed(cub_quat a, cub_quat b, int64_t sign, int64_t t)
{
    const int64_t ua = CUB_Q16_ONE - t, ub = sign * t;
    const int64_t c[4] = {a.w * ua + b.w * ub, a.x * ua + b.x * ub, a.y * ua + b.y * ub,
                          a.z * ua + b.z * ub};
    return normalize64(c);
}

cub_quat cub_fx_quat_nlerp(cub_quat a, cub_quat b, cub_q16 t)
{
    /* The endpoints come back untouched (b as given, even when the path
     * ran to -b, which is the same rotation), and so does a held rotation:
     * a joint that does not move between frames stays bit for bit still. */
    if (t <= 0 || same(a, b)) return a;
    if (t >= CUB_Q16_ONE) return b;
    return nlerp_signed(a, b, dot_q30(a, b) < 0 ? -1 : 1, t);
}

/* Below this angle between a and b (about 0.9 degrees) slerp hands over to
 * nlerp: they differ there by less than 1e-7 rad. */
#define SLERP_MIN_THETA_Q30 ((int64_t)1 << 24)

cub_quat cub_fx_quat_slerp(cub_quat a, cub_quat b, cub_q16 t)
{
    if (t <= 0 || same(a, b)) return a;
    if (t >= CUB_Q16_ONE) return b;
    int64_t d = dot_q30(a, b), sign = 1;
    if (d < 0) {
        d = -d;
        sign = -1;
    }
    if (d > ONE_Q30) d = ONE_Q30;
    int64_t s_q30 = cub_fx_isqrt64((uint64_t)(ONE_Q30 * ONE_Q30 - d * d));
    int64_t theta = cub_fxi_atan2_q30(s_q30, d); /* [0, pi/2] */
    if (theta < SLERP_MIN_THETA_Q30) return nlerp_signed(a, b, sign, t);
    /* sin((1-t)theta) a + sin(t theta) b, then normalise instead of
     * dividing by sin(theta): the same direction, one rounding less. */
    int32_t wa, wb;
    int64_t ta = (theta * (CUB_Q16_ONE - t)) >> 16, tb = (theta * t) >> 16;
    cub_fxi_sincos_q48(ta * ((int64_t)1 << 18), &wa, NULL);
    cub_fxi_sincos_q48(tb * ((int64_t)1 << 18), &wb, NULL);
    const int64_t sb = sign * wb; /* Q.30 weights, products < 2^61 */
    const int64_t c[4] = {wa * (int64_t)a.w + sb * b.w, wa * (int64_t)a.x + sb * b.x,
                          wa * (int64_t)a.y + sb * b.y, wa * (int64_t)a.z + sb * b.z};
    return normalize64(c);
}

cub_q16 cub_fx_quat_angle(cub_quat q)
{
    uint64_t v2 = (uint64_t)((int64_t)q.x * q.x) + (uint64_t)((int64_t)q.y * q.y) +
                  (uint64_t)((int64_t)q.z * q.z);
    int64_t vlen = cub_fxi_sqrt64_round(v2);
    int64_t aw = q.w < 0 ? -(int64_t)q.w : q.w;
    /* q and -q are the same rotation: using |w| keeps the angle in [0, pi]. */
    return (cub_q16)cub_fxi_round_shift(2 * cub_fxi_atan2_q30(vlen, aw), 14);
}

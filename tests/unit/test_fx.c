/* test_fx — the fixed-point core: bad and edge input first, then behaviour,
 * then accuracy against libm over the whole domain (the figures printed).
 *
 * Sweeps: the host run checks the full domains described at each test.
 * With CUB_QUICK set (or on the aarch64 build, which runs under qemu) the
 * sqrt sweep uses a coarser stride; every other sweep stays full. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cub/fx.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define TRIG_TOL 2e-4
#define Q16(x) ((cub_q16)lround((x)*65536.0))
#define Q30(x) ((int32_t)lround((x)*1073741824.0))

static double to_d(cub_q16 v)
{
    return v / 65536.0;
}

static int quick(void)
{
#if defined(__aarch64__)
    return 1; /* cross build: the tests run under qemu, 10-30x slower */
#else
    return getenv("CUB_QUICK") != NULL;
#endif
}

/* splitmix64: a fixed pseudo-random stream, identical on every run. */
static uint64_t rng_state = 0x1234567890abcdefu;
static uint64_t rng_next(void)
{
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}
static double rng_unit(void)
{
    return (rng_next() >> 11) * (1.0 / 9007199254740992.0);
}
static double rng_range(double lo, double hi)
{
    return lo + (hi - lo) * rng_unit();
}

/* ---- bad and edge input ------------------------------------------------- */

static void test_div_by_zero_saturates_by_sign(void **state)
{
    assert_int_equal(cub_fx_div(CUB_Q16_ONE, 0), CUB_Q16_MAX);
    assert_int_equal(cub_fx_div(-CUB_Q16_ONE, 0), -CUB_Q16_MAX);
    assert_int_equal(cub_fx_div(CUB_Q16_MIN, 0), -CUB_Q16_MAX);
    assert_int_equal(cub_fx_div(0, 0), 0);
}

static void test_arithmetic_saturates(void **state)
{
    assert_int_equal(cub_fx_mul(CUB_Q16_MAX, CUB_Q16_MAX), CUB_Q16_MAX);
    assert_int_equal(cub_fx_mul(CUB_Q16_MIN, CUB_Q16_MAX), CUB_Q16_MIN);
    assert_int_equal(cub_fx_mul(CUB_Q16_MIN, CUB_Q16_MIN), CUB_Q16_MAX);
    assert_int_equal(cub_fx_div(CUB_Q16_MAX, 1), CUB_Q16_MAX);
    assert_int_equal(cub_fx_div(CUB_Q16_MIN, 1), CUB_Q16_MIN);
    assert_int_equal(cub_fx_div(CUB_Q16_MIN, -1), CUB_Q16_MAX);
    assert_int_equal(cub_fx_div(CUB_Q16_MIN, -CUB_Q16_ONE), CUB_Q16_MAX);
    assert_int_equal(cub_fx_add(CUB_Q16_MAX, 1), CUB_Q16_MAX);
    assert_int_equal(cub_fx_add(CUB_Q16_MIN, -1), CUB_Q16_MIN);
    assert_int_equal(cub_fx_sub(CUB_Q16_MIN, 1), CUB_Q16_MIN);
    assert_int_equal(cub_fx_sub(CUB_Q16_MAX, CUB_Q16_MIN), CUB_Q16_MAX);
    assert_int_equal(cub_fx_abs(CUB_Q16_MIN), CUB_Q16_MAX);
    assert_int_equal(cub_fx_lerp(CUB_Q16_MIN, CUB_Q16_MAX, CUB_Q16_ONE), CUB_Q16_MAX);
    assert_int_equal(cub_fx_lerp(CUB_Q16_MIN, CUB_Q16_MAX, 0), CUB_Q16_MIN);
    /* t outside [0, 1] is clamped, never extrapolated past the ends. */
    assert_int_equal(cub_fx_lerp(10, 20, 5 * CUB_Q16_ONE), 20);
    assert_int_equal(cub_fx_lerp(10, 20, -CUB_Q16_ONE), 10);
}

static void test_sqrt_of_negative_is_zero(void **state)
{
    assert_int_equal(cub_fx_sqrt(-1), 0);
    assert_int_equal(cub_fx_sqrt(CUB_Q16_MIN), 0);
    assert_int_equal(cub_fx_sqrt(0), 0);
    assert_int_equal(cub_fx_isqrt64(UINT64_MAX), UINT32_MAX);
    assert_int_equal(cub_fx_isqrt64(0), 0);
}

static void test_atan2_of_origin_is_zero(void **state)
{
    assert_int_equal(cub_fx_atan2(0, 0), 0);
    /* The extremes of int32 in every combination stay in (-pi, pi]. */
    const cub_q16 v[] = {CUB_Q16_MIN, CUB_Q16_MIN + 1, -1, 0, 1, CUB_Q16_MAX};
    for (size_t i = 0; i < 6; i++)
        for (size_t j = 0; j < 6; j++) {
            cub_q16 a = cub_fx_atan2(v[i], v[j]);
            assert_true(a > -CUB_Q16_PI - 1 && a <= CUB_Q16_PI);
            assert_true(fabs(to_d(a) - atan2(v[i], v[j])) <= TRIG_TOL);
        }
    assert_int_equal(cub_fx_atan2(0, -5), CUB_Q16_PI);
}

static void test_acos_outside_unit_interval_clamps(void **state)
{
    assert_int_equal(cub_fx_acos(2 * CUB_Q16_ONE), 0);
    assert_int_equal(cub_fx_acos(CUB_Q16_MAX), 0);
    assert_int_equal(cub_fx_acos(-2 * CUB_Q16_ONE), CUB_Q16_PI);
    assert_int_equal(cub_fx_acos(CUB_Q16_MIN), CUB_Q16_PI);
}

static void test_vectors_saturate_and_zero_is_safe(void **state)
{
    const cub_vec3 big = {CUB_Q16_MAX, CUB_Q16_MIN, CUB_Q16_MAX}, zero = {0, 0, 0};
    assert_int_equal(cub_fx_vec3_length(big), CUB_Q16_MAX);
    assert_int_equal(cub_fx_vec3_dot(big, big), CUB_Q16_MAX);
    /* y = z*MIN - x*0: far below the range. */
    assert_int_equal(cub_fx_vec3_cross(big, (cub_vec3){CUB_Q16_MIN, 0, 0}).y, CUB_Q16_MIN);
    assert_int_equal(cub_fx_vec3_angle(zero, big), 0);
    assert_int_equal(cub_fx_vec3_angle(big, zero), 0);
    cub_vec3 s = cub_fx_vec3_add(big, big);
    assert_int_equal(s.x, CUB_Q16_MAX);
    assert_int_equal(s.y, CUB_Q16_MIN);
    /* Antiparallel huge vectors: angle pi, no overflow in dot or cross. */
    assert_int_equal(
        cub_fx_vec3_angle((cub_vec3){CUB_Q16_MAX, 0, 0}, (cub_vec3){CUB_Q16_MIN, 0, 0}),
        CUB_Q16_PI);
}

static void test_quat_degenerate_input(void **state)
{
    const cub_quat id = cub_fx_quat_identity();
    cub_quat n = cub_fx_quat_normalize((cub_quat){0, 0, 0, 0});
    assert_memory_equal(&n, &id, sizeof n);
    n = cub_fx_quat_from_axis_angle((cub_vec3){0, 0, 0}, CUB_Q16_ONE);
    assert_memory_equal(&n, &id, sizeof n);
    n = cub_fx_quat_normalize((cub_quat){INT32_MIN, INT32_MIN, INT32_MIN, INT32_MIN});
    assert_int_equal(n.w, -(1 << 29));
    assert_int_equal(n.z, -(1 << 29));
    n = cub_fx_quat_conj((cub_quat){0, INT32_MIN, 0, 0});
    assert_int_equal(n.x, INT32_MAX);
    /* Garbage in, finite garbage out: no overflow anywhere (UBSan watches). */
    const cub_quat junk = {INT32_MIN, INT32_MAX, INT32_MIN, INT32_MAX};
    (void)cub_fx_quat_mul(junk, junk);
    (void)cub_fx_quat_rotate(junk, (cub_vec3){CUB_Q16_MAX, CUB_Q16_MIN, CUB_Q16_MAX});
    (void)cub_fx_quat_nlerp(junk, cub_fx_quat_conj(junk), CUB_Q16_HALF);
    (void)cub_fx_quat_slerp(junk, id, CUB_Q16_HALF);
    assert_true(cub_fx_quat_angle(junk) >= 0 && cub_fx_quat_angle(junk) <= CUB_Q16_PI);
    assert_int_equal(cub_fx_quat_dot(junk, junk), INT32_MAX);
}

/* ---- behaviour ---------------------------------------------------------- */

static void test_mul_div_round_to_nearest(void **state)
{
    assert_int_equal(cub_fx_mul(Q16(1.5), Q16(2.0)), Q16(3.0));
    assert_int_equal(cub_fx_mul(CUB_Q16_ONE, 12345), 12345);
    assert_int_equal(cub_fx_mul(1, CUB_Q16_HALF), 1);   /* 0.5 ulp rounds away */
    assert_int_equal(cub_fx_mul(-1, CUB_Q16_HALF), -1); /* symmetric */
    assert_int_equal(cub_fx_mul(1, CUB_Q16_HALF - 1), 0);
    assert_int_equal(cub_fx_div(CUB_Q16_ONE, Q16(3.0)), 21845);
    assert_int_equal(cub_fx_div(Q16(2.0), Q16(3.0)), 43691);
    assert_int_equal(cub_fx_div(-Q16(2.0), Q16(3.0)), -43691);
    assert_int_equal(cub_fx_div(Q16(7.5), Q16(-2.5)), Q16(-3.0));
    assert_int_equal(cub_fx_lerp(Q16(1.0), Q16(3.0), CUB_Q16_HALF), Q16(2.0));
    assert_int_equal(cub_fx_clamp(5, -2, 3), 3);
    assert_int_equal(cub_fx_clamp(-5, -2, 3), -2);
}

static void test_trig_special_values(void **state)
{
    assert_int_equal(cub_fx_sin(0), 0);
    assert_int_equal(cub_fx_cos(0), CUB_Q16_ONE);
    assert_int_equal(cub_fx_sin(CUB_Q16_HALF_PI), CUB_Q16_ONE);
    assert_int_equal(cub_fx_acos(CUB_Q16_ONE), 0);
    assert_int_equal(cub_fx_acos(-CUB_Q16_ONE), CUB_Q16_PI);
    assert_int_equal(cub_fx_acos(0), CUB_Q16_HALF_PI);
    assert_int_equal(cub_fx_atan2(CUB_Q16_ONE, 0), CUB_Q16_HALF_PI);
    assert_int_equal(cub_fx_atan2(-CUB_Q16_ONE, 0), -CUB_Q16_HALF_PI);
    assert_int_equal(cub_fx_atan2(7, 7), Q16(M_PI / 4));
    /* wrap: identity inside (-pi, pi], one turn off outside. */
    assert_int_equal(cub_fx_wrap_angle(CUB_Q16_PI), CUB_Q16_PI);
    assert_int_equal(cub_fx_wrap_angle(-CUB_Q16_PI), -CUB_Q16_PI);
    assert_int_equal(cub_fx_wrap_angle(12345), 12345);
    assert_int_equal(cub_fx_wrap_angle(Q16(3 * M_PI / 2)), Q16(-M_PI / 2));
    assert_int_equal(cub_fx_wrap_angle(Q16(-3 * M_PI / 2)), Q16(M_PI / 2));
}

static void test_wrap_angle_whole_domain(void **state)
{
    double max_err = 0;
    long n = 0;
    for (int64_t a = INT32_MIN; a <= INT32_MAX; a += 4099, n++) {
        cub_q16 w = cub_fx_wrap_angle((cub_q16)a);
        assert_true(to_d(w) > -M_PI && to_d(w) <= M_PI);
        double ref = remainder(to_d((cub_q16)a), 2 * M_PI); /* [-pi, pi] */
        double err = fabs(to_d(w) - ref);
        if (err > M_PI) err = fabs(err - 2 * M_PI); /* both ends are pi */
        if (err > max_err) max_err = err;
    }
    printf("fx: wrap_angle max_abs_err=%.1e over %ld angles (whole int32 domain, stride 4099)\n",
           max_err, n);
    assert_true(max_err <= 1.0 / 65536);
}

static void test_vec3_operations(void **state)
{
    const cub_vec3 a = {Q16(1), Q16(2), Q16(3)}, b = {Q16(-4), Q16(5), Q16(0.5)};
    assert_int_equal(cub_fx_vec3_dot(a, b), Q16(7.5));
    cub_vec3 c = cub_fx_vec3_cross(a, b);
    assert_int_equal(c.x, Q16(2 * 0.5 - 3 * 5));
    assert_int_equal(c.y, Q16(3 * -4 - 1 * 0.5));
    assert_int_equal(c.z, Q16(1 * 5 - 2 * -4));
    assert_int_equal(cub_fx_vec3_length((cub_vec3){Q16(3), Q16(4), Q16(12)}), Q16(13));
    cub_vec3 l = cub_fx_vec3_lerp(a, b, CUB_Q16_ONE);
    assert_memory_equal(&l, &b, sizeof l);
    cub_vec3 s = cub_fx_vec3_scale(a, Q16(-2));
    assert_int_equal(s.z, Q16(-6));
    assert_int_equal(cub_fx_vec3_angle((cub_vec3){Q16(1), 0, 0}, (cub_vec3){0, Q16(1), 0}),
                     CUB_Q16_HALF_PI);
    /* Tiny vectors (one ulp) keep their angle too. */
    assert_int_equal(cub_fx_vec3_angle((cub_vec3){1, 0, 0}, (cub_vec3){1, 1, 0}), Q16(M_PI / 4));

    /* Angle against a double reference, from tiny to huge magnitudes. */
    double max_err = 0;
    for (int i = 0; i < 20000; i++) {
        double mag = pow(2.0, rng_range(0, 30));
        double u[3], v[3];
        cub_vec3 p, q;
        for (int k = 0; k < 3; k++) {
            u[k] = round(rng_range(-mag, mag));
            v[k] = round(rng_range(-mag, mag) * pow(2.0, rng_range(-1, 1)));
            if (fabs(v[k]) > 2147483647.0) v[k] = copysign(2147483647.0, v[k]);
        }
        p = (cub_vec3){(cub_q16)u[0], (cub_q16)u[1], (cub_q16)u[2]};
        q = (cub_vec3){(cub_q16)v[0], (cub_q16)v[1], (cub_q16)v[2]};
        double cx = u[1] * v[2] - u[2] * v[1], cy = u[2] * v[0] - u[0] * v[2],
               cz = u[0] * v[1] - u[1] * v[0];
        double dot = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
        if (dot == 0 && cx == 0 && cy == 0 && cz == 0) continue;
        double ref = atan2(sqrt(cx * cx + cy * cy + cz * cz), dot);
        double err = fabs(to_d(cub_fx_vec3_angle(p, q)) - ref);
        if (err > max_err) max_err = err;
    }
    printf("fx: vec3_angle max_abs_err=%.1e over 20000 random pairs (1 ulp to 2^30 ulp)\n",
           max_err);
    assert_true(max_err <= TRIG_TOL);
}

/* ---- accuracy over the domain ------------------------------------------- */

/* The correctly rounded square root of n, by the FPU and integer fix-ups. */
static uint64_t ref_sqrt_round(uint64_t n)
{
    uint64_t r = (uint64_t)sqrt((double)n);
    while (r * r > n)
        r--;
    while ((r + 1) * (r + 1) <= n)
        r++;
    return n - r * r > r ? r + 1 : r;
}

static void check_sqrt(int64_t x, long *count, long *bad, double *max_err)
{
    cub_q16 got = cub_fx_sqrt((cub_q16)x);
    uint64_t want = ref_sqrt_round((uint64_t)x << 16);
    double err = fabs(got - sqrt((double)x * 65536.0)); /* in ulps, vs libm */
    if (err > *max_err) *max_err = err;
    if ((uint64_t)got != want) (*bad)++;
    (*count)++;
}

static void test_sqrt_correctly_rounded(void **state)
{
    /* Host: every value below 2^22, a stride of 13 above, and both sides of
     * every rounding boundary (the x where the result steps from k to k+1),
     * which with the stride pins down every output. Quick: coarser. */
    const int64_t dense = quick() ? (1 << 18) : (1 << 22);
    const int64_t stride = quick() ? 1021 : 13;
    const int64_t kstep = quick() ? 97 : 1;
    long count = 0, bad = 0;
    double max_err = 0;
    for (int64_t x = 0; x < dense; x++)
        check_sqrt(x, &count, &bad, &max_err);
    for (int64_t x = dense; x <= INT32_MAX; x += stride)
        check_sqrt(x, &count, &bad, &max_err);
    check_sqrt(INT32_MAX, &count, &bad, &max_err);
    for (int64_t k = 1;; k += kstep) {
        int64_t x = (k * k + k + 1 + 65535) / 65536; /* first x rounding to k+1 */
        if (x > INT32_MAX) break;
        check_sqrt(x, &count, &bad, &max_err);
        check_sqrt(x - 1, &count, &bad, &max_err);
    }
    printf("fx: sqrt max_err=%.4f ulp, %ld of %ld not correctly rounded "
           "(all x < 2^%d, stride %d above, %s)\n",
           max_err, bad, count, quick() ? 18 : 22, (int)stride,
           kstep == 1 ? "every rounding boundary" : "1/97 of the rounding boundaries");
    assert_int_equal(bad, 0);
    assert_true(max_err <= 0.5 + 1e-9);
}

static void test_sin_cos_accuracy(void **state)
{
    double es = 0, ec = 0;
    long n = 0;
    for (int64_t a = -CUB_Q16_TWO_PI; a <= CUB_Q16_TWO_PI; a++, n++) {
        double s = fabs(to_d(cub_fx_sin((cub_q16)a)) - sin(to_d((cub_q16)a)));
        double c = fabs(to_d(cub_fx_cos((cub_q16)a)) - cos(to_d((cub_q16)a)));
        if (s > es) es = s;
        if (c > ec) ec = c;
    }
    printf("fx: sin max_abs_err=%.1e over %ld angles (every Q16.16 in [-2pi, 2pi])\n", es, n);
    printf("fx: cos max_abs_err=%.1e over %ld angles (every Q16.16 in [-2pi, 2pi])\n", ec, n);
    assert_true(es <= TRIG_TOL);
    assert_true(ec <= TRIG_TOL);

    /* Large angles: the 48-bit reduction keeps them as accurate. */
    double el = 0;
    long m = 0;
    for (int64_t a = INT32_MIN; a <= INT32_MAX; a += 4099, m++) {
        double s = fabs(to_d(cub_fx_sin((cub_q16)a)) - sin(to_d((cub_q16)a)));
        double c = fabs(to_d(cub_fx_cos((cub_q16)a)) - cos(to_d((cub_q16)a)));
        if (s > el) el = s;
        if (c > el) el = c;
    }
    printf("fx: sin/cos max_abs_err=%.1e over %ld angles (whole int32 domain, stride 4099)\n", el,
           m);
    assert_true(el <= TRIG_TOL);
}

static void atan2_check(int64_t y, int64_t x, double *max_err, long *n)
{
    if (y < INT32_MIN) y = INT32_MIN;
    if (y > INT32_MAX) y = INT32_MAX;
    if (x < INT32_MIN) x = INT32_MIN;
    if (x > INT32_MAX) x = INT32_MAX;
    cub_q16 a = cub_fx_atan2((cub_q16)y, (cub_q16)x);
    double err = fabs(to_d(a) - atan2((double)y, (double)x));
    if (err > *max_err) *max_err = err;
    (*n)++;
}

static void test_atan2_accuracy(void **state)
{
    double max_err = 0;
    long n = 0;
    /* Every (y, x) with |y|, |x| <= 128 ulps: the tiny, coarse ratios. */
    for (int y = -128; y <= 128; y++)
        for (int x = -128; x <= 128; x++)
            atan2_check(y, x, &max_err, &n);
    /* Circles of radius 2^(i/4) ulps, 1 to 2^31, 4096 directions each
     * (all octants), offset by a fraction so axes and diagonals vary. */
    for (int i = 0; i <= 124; i++) {
        double r = pow(2.0, i / 4.0);
        for (int k = 0; k < 4096; k++) {
            double th = (k + 0.37 * (i % 3)) * (2 * M_PI / 4096);
            atan2_check(llround(r * sin(th)), llround(r * cos(th)), &max_err, &n);
        }
    }
    /* Very unequal magnitudes: 1 ulp against 2^31 in all sign patterns. */
    const int64_t big[] = {1, 3, 65536, 1 << 20, INT32_MAX};
    for (int i = 0; i < 5; i++)
        for (int j = 0; j < 5; j++)
            for (int s = 0; s < 4; s++)
                atan2_check(s & 1 ? -big[i] : big[i], s & 2 ? -big[j] : big[j], &max_err, &n);
    printf("fx: atan2 max_abs_err=%.1e over %ld points (all |y|,|x| <= 128 ulp; "
           "125 radii 1..2^31 x 4096 directions; extremes)\n",
           max_err, n);
    assert_true(max_err <= TRIG_TOL);
}

static void test_acos_accuracy(void **state)
{
    double max_err = 0;
    long n = 0;
    for (int64_t x = -CUB_Q16_ONE; x <= CUB_Q16_ONE; x++, n++) {
        cub_q16 a = cub_fx_acos((cub_q16)x);
        assert_true(a >= 0 && a <= CUB_Q16_PI);
        double err = fabs(to_d(a) - acos(to_d((cub_q16)x)));
        if (err > max_err) max_err = err;
    }
    printf("fx: acos max_abs_err=%.1e over %ld values (every Q16.16 in [-1, 1])\n", max_err, n);
    assert_true(max_err <= TRIG_TOL);
}

/* ---- quaternions -------------------------------------------------------- */

typedef struct dquat {
    double w, x, y, z;
} dquat;

static dquat to_dq(cub_quat q)
{
    return (dquat){q.w / 1073741824.0, q.x / 1073741824.0, q.y / 1073741824.0, q.z / 1073741824.0};
}

static dquat dq_mul(dquat a, dquat b)
{
    return (dquat){a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z,
                   a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
                   a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
                   a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}

static void dq_rotate(dquat q, const double v[3], double out[3])
{
    double n = sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    dquat u = {q.w / n, q.x / n, q.y / n, q.z / n};
    dquat p = dq_mul(dq_mul(u, (dquat){0, v[0], v[1], v[2]}), (dquat){u.w, -u.x, -u.y, -u.z});
    out[0] = p.x;
    out[1] = p.y;
    out[2] = p.z;
}

static cub_quat random_quat(void)
{
    cub_quat q;
    do {
        q = (cub_quat){
            (int32_t)(rng_next() >> 33) - (1 << 30), (int32_t)(rng_next() >> 33) - (1 << 30),
            (int32_t)(rng_next() >> 33) - (1 << 30), (int32_t)(rng_next() >> 33) - (1 << 30)};
    } while (q.w == 0 && q.x == 0);
    return cub_fx_quat_normalize(q);
}

static double qlen_ulps(cub_quat q)
{
    dquat d = to_dq(q);
    return fabs(sqrt(d.w * d.w + d.x * d.x + d.y * d.y + d.z * d.z) - 1.0) * 1073741824.0;
}

static int max_comp_diff(cub_quat a, cub_quat b)
{
    int64_t d[4] = {llabs((int64_t)a.w - b.w), llabs((int64_t)a.x - b.x), llabs((int64_t)a.y - b.y),
                    llabs((int64_t)a.z - b.z)};
    int64_t m = 0;
    for (int i = 0; i < 4; i++)
        if (d[i] > m) m = d[i];
    return (int)m;
}

static void test_quat_normalize_is_unit(void **state)
{
    double worst = 0;
    for (int i = 0; i < 100000; i++) {
        /* Magnitudes from a few ulps to the top of the range. */
        int shift = (int)(rng_next() % 31);
        cub_quat q = {(int32_t)((int64_t)(int32_t)rng_next() >> shift),
                      (int32_t)((int64_t)(int32_t)rng_next() >> shift),
                      (int32_t)((int64_t)(int32_t)rng_next() >> shift),
                      (int32_t)((int64_t)(int32_t)rng_next() >> shift)};
        if (q.w == 0 && q.x == 0 && q.y == 0 && q.z == 0) continue;
        double l = qlen_ulps(cub_fx_quat_normalize(q));
        if (l > worst) worst = l;
    }
    printf("fx: quat_normalize max_len_err=%.2f Q2.30 ulps over 100000 quaternions\n", worst);
    assert_true(worst <= 3.0);
}

static void test_quat_rotate_matches_double(void **state)
{
    double max_err = 0;
    for (int i = 0; i < 100000; i++) {
        cub_quat q = random_quat();
        double v[3], r[3];
        for (int k = 0; k < 3; k++)
            v[k] = rng_range(-2000, 2000);
        cub_vec3 fv = {Q16(v[0]), Q16(v[1]), Q16(v[2])};
        double vq[3] = {to_d(fv.x), to_d(fv.y), to_d(fv.z)};
        dq_rotate(to_dq(q), vq, r);
        cub_vec3 got = cub_fx_quat_rotate(q, fv);
        double e = fmax(fabs(to_d(got.x) - r[0]),
                        fmax(fabs(to_d(got.y) - r[1]), fabs(to_d(got.z) - r[2])));
        if (e > max_err) max_err = e;
    }
    printf("fx: quat_rotate max_abs_err=%.1e mm over 100000 rotations of |v| <= 2000 mm\n",
           max_err);
    assert_true(max_err <= 2e-5); /* 1.3 Q16.16 ulps */
    /* A quarter turn about z (the Q16.16 pi/2 is 4.6e-6 rad long, which
     * shows at 100 mm): within one ulp of the exact rotation. */
    const double th = to_d(CUB_Q16_HALF_PI);
    cub_quat z90 = cub_fx_quat_from_axis_angle((cub_vec3){0, 0, CUB_Q16_ONE}, CUB_Q16_HALF_PI);
    cub_vec3 y = cub_fx_quat_rotate(z90, (cub_vec3){Q16(100), 0, 0});
    assert_true(fabs(to_d(y.x) - 100 * cos(th)) <= 1.0 / 65536);
    assert_true(fabs(to_d(y.y) - 100 * sin(th)) <= 1.0 / 65536);
    assert_int_equal(y.z, 0);
}

static void test_quat_mul_matches_double_and_associates(void **state)
{
    int worst_ref = 0, worst_assoc = 0;
    for (int i = 0; i < 100000; i++) {
        cub_quat a = random_quat(), b = random_quat(), c = random_quat();
        dquat r = dq_mul(to_dq(a), to_dq(b));
        cub_quat ab = cub_fx_quat_mul(a, b);
        cub_quat ref = {Q30(r.w), Q30(r.x), Q30(r.y), Q30(r.z)};
        int d = max_comp_diff(ab, ref);
        if (d > worst_ref) worst_ref = d;
        d = max_comp_diff(cub_fx_quat_mul(ab, c), cub_fx_quat_mul(a, cub_fx_quat_mul(b, c)));
        if (d > worst_assoc) worst_assoc = d;
    }
    printf("fx: quat_mul max_diff=%d ulps vs double, (ab)c vs a(bc) max_diff=%d ulps "
           "over 100000 triples\n",
           worst_ref, worst_assoc);
    assert_true(worst_ref <= 1);
    assert_true(worst_assoc <= 4);
    cub_quat q = random_quat();
    cub_quat e = cub_fx_quat_mul(q, cub_fx_quat_conj(q));
    assert_true(max_comp_diff(e, cub_fx_quat_identity()) <= 2);
    assert_true(abs(cub_fx_quat_dot(q, q) - CUB_QUAT_ONE) <= 4);
}

static void test_quat_axis_angle_round_trip(void **state)
{
    double max_err = 0;
    for (int i = 0; i < 20000; i++) {
        double th = rng_range(0, M_PI);
        double ax[3] = {rng_range(-1, 1), rng_range(-1, 1), rng_range(-1, 1)};
        double n = sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
        if (n < 1e-3) continue;
        cub_vec3 axis = {Q16(ax[0] / n), Q16(ax[1] / n), Q16(ax[2] / n)};
        cub_quat q = cub_fx_quat_from_axis_angle(axis, Q16(th));
        double e = fabs(to_d(cub_fx_quat_angle(q)) - to_d(Q16(th)));
        if (e > max_err) max_err = e;
        assert_true(qlen_ulps(q) <= 3.0);
    }
    printf("fx: quat_angle(from_axis_angle(th)) max_abs_err=%.1e rad over 20000 rotations\n",
           max_err);
    assert_true(max_err <= TRIG_TOL);
}

static void test_quat_nlerp_and_slerp(void **state)
{
    const cub_quat a = random_quat(), b = random_quat();
    cub_quat r = cub_fx_quat_nlerp(a, b, 0);
    assert_memory_equal(&r, &a, sizeof r);
    r = cub_fx_quat_nlerp(a, b, CUB_Q16_ONE);
    assert_memory_equal(&r, &b, sizeof r);
    r = cub_fx_quat_slerp(a, b, 0);
    assert_memory_equal(&r, &a, sizeof r);
    r = cub_fx_quat_slerp(a, b, CUB_Q16_ONE);
    assert_memory_equal(&r, &b, sizeof r);

    /* Shorter arc: halfway from q to -q (the same rotation) is q again. */
    const cub_quat nb = {-b.w, -b.x, -b.y, -b.z};
    r = cub_fx_quat_nlerp(b, nb, CUB_Q16_HALF);
    assert_true(max_comp_diff(r, b) <= 2);

    /* slerp moves at constant angular speed, even over 170 degrees. */
    const cub_vec3 axis = {Q16(0.6), Q16(0), Q16(0.8)};
    const double th = 170.0 * M_PI / 180.0;
    const cub_quat id = cub_fx_quat_identity();
    const cub_quat far = cub_fx_quat_from_axis_angle(axis, Q16(th));
    double max_err = 0;
    for (int k = 0; k <= 64; k++) {
        cub_q16 t = (cub_q16)(k * 1024);
        double e = fabs(to_d(cub_fx_quat_angle(cub_fx_quat_slerp(id, far, t))) - th * k / 64.0);
        if (e > max_err) max_err = e;
        assert_true(qlen_ulps(cub_fx_quat_slerp(id, far, t)) <= 3.0);
    }
    printf("fx: slerp angle max_abs_err=%.1e rad along a 170 degree arc (65 steps)\n", max_err);
    assert_true(max_err <= TRIG_TOL);
    /* nlerp's midpoint is the slerp midpoint (same direction by symmetry). */
    assert_true(max_comp_diff(cub_fx_quat_nlerp(a, b, CUB_Q16_HALF),
                              cub_fx_quat_slerp(a, b, CUB_Q16_HALF)) <= 64);
    /* Small angles hand over to nlerp smoothly. */
    const cub_quat near = cub_fx_quat_from_axis_angle(axis, Q16(0.01));
    double ang = to_d(cub_fx_quat_angle(cub_fx_quat_slerp(id, near, CUB_Q16_HALF)));
    assert_true(fabs(ang - 0.005) <= 1e-4);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_div_by_zero_saturates_by_sign),
        cmocka_unit_test(test_arithmetic_saturates),
        cmocka_unit_test(test_sqrt_of_negative_is_zero),
        cmocka_unit_test(test_atan2_of_origin_is_zero),
        cmocka_unit_test(test_acos_outside_unit_interval_clamps),
        cmocka_unit_test(test_vectors_saturate_and_zero_is_safe),
        cmocka_unit_test(test_quat_degenerate_input),
        cmocka_unit_test(test_mul_div_round_to_nearest),
        cmocka_unit_test(test_trig_special_values),
        cmocka_unit_test(test_wrap_angle_whole_domain),
        cmocka_unit_test(test_vec3_operations),
        cmocka_unit_test(test_sqrt_correctly_rounded),
        cmocka_unit_test(test_sin_cos_accuracy),
        cmocka_unit_test(test_atan2_accuracy),
        cmocka_unit_test(test_acos_accuracy),
        cmocka_unit_test(test_quat_normalize_is_unit),
        cmocka_unit_test(test_quat_rotate_matches_double),
        cmocka_unit_test(test_quat_mul_matches_double_and_associates),
        cmocka_unit_test(test_quat_axis_angle_round_trip),
        cmocka_unit_test(test_quat_nlerp_and_slerp),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

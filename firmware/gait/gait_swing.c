/* gait — the swing foot's path (SEEDS.md § 003, "Swing foot path"): the
 * quartic Bézier of eq. 4-2 between the current foot and the next
 * foothold, its three inner control points raised together by the least
 * height that clears the terrain, solved for. Q16.16 mm. */
#include "cub/gait.h"

#define DEFAULT_CLEAR_MM CUB_Q16_INT(20) /* the 2 cm over obstacles */
#define DEFAULT_RAISE_MM CUB_Q16_INT(10) /* ours */
#define DEFAULT_MAX_RAISES 100           /* ours: a metre above the line */
#define DEFAULT_SAMPLES 64               /* ours: ~1 cm apart on a 60 cm step */
#define MAX_SAMPLES 1024

/* sum of p[k] * b[k] over k, b Q16.16 weights. */
static cub_q16 weigh(const cub_q16 *v, const cub_q16 *b)
{
    int64_t s = 0;
    for (int k = 0; k < 5; k++)
        s += (int64_t)v[k] * b[k];
    return (cub_q16)((s + (1 << 15)) >> 16);
}

/* The quartic's Bernstein weights at t; they sum to exactly one, so
 * points on a line stay on it. */
static void basis(cub_q16 t, cub_q16 b[5])
{
    t = cub_fx_clamp(t, 0, CUB_Q16_ONE);
    cub_q16 s = CUB_Q16_ONE - t;
    cub_q16 s2 = cub_fx_mul(s, s), t2 = cub_fx_mul(t, t);
    b[1] = 4 * cub_fx_mul(t, cub_fx_mul(s2, s));
    b[2] = 6 * cub_fx_mul(t2, s2);
    b[3] = 4 * cub_fx_mul(cub_fx_mul(t2, t), s);
    b[4] = cub_fx_mul(t2, t2);
    b[0] = CUB_Q16_ONE - b[1] - b[2] - b[3] - b[4];
}

cub_vec3 cub_gait_bezier4(const cub_vec3 p[5], cub_q16 t)
{
    cub_q16 b[5];
    basis(t, b);
    cub_q16 xs[5], ys[5], zs[5];
    for (int k = 0; k < 5; k++) {
        xs[k] = p[k].x;
        ys[k] = p[k].y;
        zs[k] = p[k].z;
    }
    return (cub_vec3){weigh(xs, b), weigh(ys, b), weigh(zs, b)};
}

typedef struct swing_cfg {
    cub_q16 clear, raise, foot, heel, side[2];
    int max_raises, samples;
} swing_cfg;

static swing_cfg config(const cub_gait_swing_params *p)
{
    swing_cfg c = {DEFAULT_CLEAR_MM, DEFAULT_RAISE_MM, 0, 0, {0, 0}, DEFAULT_MAX_RAISES,
                   DEFAULT_SAMPLES};
    if (!p) return c;
    if (p->clearance_mm > 0) c.clear = p->clearance_mm;
    if (p->raise_mm > 0) c.raise = p->raise_mm;
    if (p->max_raises > 0) c.max_raises = p->max_raises;
    if (p->samples > 0) c.samples = p->samples < MAX_SAMPLES ? p->samples : MAX_SAMPLES;
    if (p->foot_mm > 0) c.foot = p->foot_mm;
    if (p->heel_mm > 0) c.heel = p->heel_mm;
    for (int i = 0; i < 2; i++)
        if (p->side_mm[i] > 0) c.side[i] = p->side_mm[i];
    return c;
}

/* The clearance asked at t: full over the middle half, ramping to 0 at
 * the footholds, where the sole must touch [ours]. */
static cub_q16 clearance_at(cub_q16 clear, cub_q16 t)
{
    cub_q16 edge = t < CUB_Q16_HALF ? t : CUB_Q16_ONE - t;
    return cub_fx_mul(clear, cub_fx_clamp(edge * 4, 0, CUB_Q16_ONE));
}

/* The raise is solved for, not stepped to: raising P1..P3 by h moves no
 * point sideways and lifts B(t) by h * w(t), w = b1 + b2 + b3 (> 0 inside
 * the swing). A point of the sole at t that must reach height y then
 * needs h >= (y - B0(t).y) / w(t), B0 the unraised path; the raise is the
 * largest such need, in whole raise_mm steps (as the stepped test gave;
 * their slack keeps the walker's foot, which is not this flat sole, 2 cm
 * over 08_01's log: 18.4 mm with 1 mm steps; docs/gait.md has why the
 * stepped test was replaced). */
typedef struct swing_solve {
    const cub_gait_terrain *t;
    const swing_cfg *c;
    const cub_vec3 *p;  /* the unraised control points: on the line P0P4 */
    cub_q16 t_lo, t_hi; /* the part of the swing tested: the ends are footholds */
    int64_t need;       /* the largest raise needed so far, Q16.16 mm */
} swing_solve;

/* A point at the weights b (offset dy from the path, whose unraised
 * height there is y0) must reach y: fold its need in. */
static void need_with(swing_solve *s, const cub_q16 b[5], cub_q16 y0, cub_q16 y, cub_q16 dy)
{
    cub_q16 w = b[1] + b[2] + b[3];
    if (w <= 0) return;
    int64_t gap = (int64_t)y - dy - y0;
    int64_t h = gap > 0 ? (gap * CUB_Q16_ONE + w - 1) / w : 0;
    if (h > s->need) s->need = h;
}

/* The same at t, the path's height read from the weights at hand. */
static void need_at(swing_solve *s, cub_q16 t, cub_q16 y, cub_q16 dy)
{
    cub_q16 b[5];
    basis(t, b);
    const cub_q16 ys[5] = {s->p[0].y, s->p[1].y, s->p[2].y, s->p[3].y, s->p[4].y};
    need_with(s, b, weigh(ys, b), y, dy);
}

/* The ankle's point over the ground (not the obstacles), at the samples:
 * the ground is smooth, the ramp asks little near the ends. One set of
 * weights per sample gives both the point and its need (the planner
 * tests up to 3 swings per foot-off: the weights were half its time). */
static void need_over_ground(swing_solve *s)
{
    cub_q16 xs[5], ys[5], zs[5];
    for (int k = 0; k < 5; k++) {
        xs[k] = s->p[k].x;
        ys[k] = s->p[k].y;
        zs[k] = s->p[k].z;
    }
    for (int i = 1; i < s->c->samples; i++) {
        cub_q16 tt = (cub_q16)(((int64_t)i << 16) / s->c->samples), b[5];
        basis(tt, b);
        cub_q16 g = cub_gait_ground_height(s->t, weigh(xs, b), weigh(zs, b));
        need_with(s, b, weigh(ys, b), cub_fx_add(g, clearance_at(s->c->clear, tt)), 0);
    }
}

/* A point of the sole: its offset from the ankle's point along the path
 * (y below it for the heel), and whether it is the ankle's point itself. */
typedef struct sole_point {
    cub_vec3 off;
    bool ankle;
} sole_point;

/* The t where a point moving from a by d (per unit t) is inside [lo, hi]
 * on one axis, narrowed into *t0, *t1 (Q16.16). */
static void slab(cub_q16 a, cub_q16 d, cub_q16 lo, cub_q16 hi, int64_t *t0, int64_t *t1)
{
    if (d == 0) {
        if (a < lo || a > hi) *t1 = -1;
        return;
    }
    int64_t u = ((int64_t)lo - a) * CUB_Q16_ONE / d, v = ((int64_t)hi - a) * CUB_Q16_ONE / d;
    if (u > v) {
        int64_t x = u;
        u = v;
        v = x;
    }
    if (u > *t0) *t0 = u;
    if (v < *t1) *t1 = v;
}

/* The height a sole point over box b at t must reach, or false when none:
 * an obstacle whose top is no higher than the foothold of this half of
 * the swing (level) is ground there (a foot leaving or landing on a
 * platform stands on it [ours]; tested as an obstacle, the heel asked
 * 0.95 m for a 12 cm step up): the ankle's point keeps the ramp's
 * clearance over it, the rest of the sole none. Over any other obstacle
 * the full clearance holds, ramp or not (the planner keeps the foot base
 * on its top or 20 mm clear of it). The sole's ends off the ankle's
 * point clear the obstacles only: over the plain ground the walker keeps
 * every foot point above the ground itself (a flat foot's toe held to
 * the path's height on a slope asked a 28-raise path at the swing's
 * start) [ours]. */
static bool box_need(const swing_solve *s, const cub_gait_box *b, const sole_point *sp,
                     cub_q16 t, bool first_half, cub_q16 *y)
{
    cub_q16 level = first_half ? s->p[0].y : s->p[4].y;
    if (b->max_mm.y > level) {
        *y = cub_fx_add(b->max_mm.y, s->c->clear);
        return true;
    }
    *y = cub_fx_add(b->max_mm.y, clearance_at(s->c->clear, t));
    return sp->ankle;
}

/* A sole point over box b between t0 and t1: the need, the height asked
 * less the path's, over w, is linear over a concave w on each piece
 * between the ramp's and the halves' breaks (a quarter, a half, three
 * quarters), so on each piece its largest is at an end: those ends are
 * tested, exactly, and no corner dips between samples. */
static void need_over_box(swing_solve *s, const cub_gait_box *b, const sole_point *sp,
                          int64_t t0, int64_t t1)
{
    static const int64_t cuts[] = {CUB_Q16_ONE / 4, CUB_Q16_HALF, 3 * CUB_Q16_ONE / 4,
                                   CUB_Q16_ONE + 1};
    int64_t a = t0;
    for (int k = 0; k < 4 && a <= t1; k++) {
        if (cuts[k] <= a) continue;
        int64_t e = cuts[k] - 1 < t1 ? cuts[k] - 1 : t1;
        bool first = a < CUB_Q16_HALF;
        cub_q16 y;
        for (int end = 0; end < 2; end++) {
            cub_q16 tt = (cub_q16)(end ? e : a);
            if (box_need(s, b, sp, tt, first, &y)) need_at(s, tt, y, sp->off.y);
        }
        a = cuts[k];
    }
}

/* Every box under a sole point's track: the control points lie evenly on
 * P0P4, so the point moves along it linearly in t. */
static void need_over_boxes(swing_solve *s, const sole_point *sp)
{
    cub_q16 ax = cub_fx_add(s->p[0].x, sp->off.x), az = cub_fx_add(s->p[0].z, sp->off.z);
    cub_q16 dx = cub_fx_sub(s->p[4].x, s->p[0].x), dz = cub_fx_sub(s->p[4].z, s->p[0].z);
    for (int k = 0; k < s->t->obstacle_count; k++) {
        const cub_gait_box *b = &s->t->obstacles[k];
        int64_t t0 = s->t_lo, t1 = s->t_hi;
        slab(ax, dx, b->min_mm.x, b->max_mm.x, &t0, &t1);
        slab(az, dz, b->min_mm.z, b->max_mm.z, &t0, &t1);
        if (t0 <= t1) need_over_box(s, b, sp, t0, t1);
    }
}

/* The offset of a point foot_mm along P0P4 on the ground. */
static cub_vec3 toe_offset(cub_vec3 from, cub_vec3 to, cub_q16 foot)
{
    cub_vec3 d = {cub_fx_sub(to.x, from.x), 0, cub_fx_sub(to.z, from.z)};
    uint32_t len = cub_fx_isqrt64((uint64_t)((int64_t)d.x * d.x + (int64_t)d.z * d.z));
    if (len == 0 || foot == 0) return (cub_vec3){0, 0, 0};
    return (cub_vec3){(cub_q16)((int64_t)d.x * foot / len), 0,
                      (cub_q16)((int64_t)d.z * foot / len)};
}

/* The sole's points: the ankle's, side[0] off the line toward (d.z, 0,
 * -d.x) (d along P0P4) and side[1] the other way; on each of the three
 * lines the toe ahead and the heel behind. The heel is lower than the
 * flat sole the path models: the foot comes down toe up (~15 degrees at
 * the strike), a fifth of the foot at the heel [ours]. */
static int sole_points(const swing_cfg *c, cub_vec3 from, cub_vec3 to, sole_point pts[9])
{
    cub_vec3 l = toe_offset(from, to, c->side[0]), r = toe_offset(from, to, c->side[1]);
    cub_vec3 toe = toe_offset(from, to, c->foot), heel = toe_offset(from, to, c->heel);
    cub_vec3 row[3] = {{0, 0, 0}, {l.z, 0, -l.x}, {-r.z, 0, r.x}};
    heel = (cub_vec3){-heel.x, -(c->foot / 5), -heel.z};
    int n = 0;
    for (int k = 0; k < 3; k++) {
        pts[n++] = (sole_point){row[k], k == 0};
        if (c->foot > 0) pts[n++] = (sole_point){cub_fx_vec3_add(row[k], toe), false};
        if (c->heel > 0) pts[n++] = (sole_point){cub_fx_vec3_add(row[k], heel), false};
    }
    return n;
}

cub_err cub_gait_swing_path(const cub_gait_terrain *t, const cub_gait_swing_params *p,
                            cub_vec3 from_mm, cub_vec3 to_mm, cub_gait_swing *out)
{
    if (!t || !out) return CUB_ERR_ARG;
    swing_cfg c = config(p);
    *out = (cub_gait_swing){{from_mm, cub_fx_vec3_lerp(from_mm, to_mm, CUB_Q16_ONE / 4),
                             cub_fx_vec3_lerp(from_mm, to_mm, CUB_Q16_HALF),
                             cub_fx_vec3_lerp(from_mm, to_mm, 3 * CUB_Q16_ONE / 4), to_mm},
                            0,
                            0};
    /* The first and last samples of the stepped test bound the part tested:
     * the ends are footholds. */
    cub_q16 edge = (cub_q16)(CUB_Q16_ONE / c.samples);
    swing_solve s = {t, &c, out->p, edge, CUB_Q16_ONE - edge, 0};
    sole_point pts[9];
    int n = sole_points(&c, from_mm, to_mm, pts);
    for (int i = 0; i < n; i++)
        need_over_boxes(&s, &pts[i]);
    /* The need is the largest of all: the obstacles' (a few exact tests)
     * first; a swing they already put over the cap fails whatever the
     * ground asks (the path out is the cap's), so the ground's samples,
     * most of the solve's work, are skipped for it. */
    if (s.need <= (int64_t)c.max_raises * c.raise) need_over_ground(&s);
    int64_t raises = (s.need + c.raise - 1) / c.raise;
    bool ok = raises <= c.max_raises;
    out->raises = ok ? (int)raises : c.max_raises;
    for (int k = 1; k <= 3; k++)
        out->p[k].y = cub_fx_add(out->p[k].y, (cub_q16)(out->raises * (int64_t)c.raise));
    out->clear = ok;
    return ok ? CUB_OK : CUB_ERR_RANGE;
}

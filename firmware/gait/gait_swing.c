/* gait — the swing foot's path (SEEDS.md § 003, "Swing foot path"): the
 * quartic Bézier of eq. 4-2 between the current foot and the next
 * foothold, its three inner control points raised together until the
 * path clears the terrain. Q16.16 mm. */
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

cub_vec3 cub_gait_bezier4(const cub_vec3 p[5], cub_q16 t)
{
    t = cub_fx_clamp(t, 0, CUB_Q16_ONE);
    cub_q16 s = CUB_Q16_ONE - t;
    cub_q16 s2 = cub_fx_mul(s, s), t2 = cub_fx_mul(t, t);
    cub_q16 b[5] = {0, 4 * cub_fx_mul(t, cub_fx_mul(s2, s)), 6 * cub_fx_mul(t2, s2),
                    4 * cub_fx_mul(cub_fx_mul(t2, t), s), cub_fx_mul(t2, t2)};
    /* The weights sum to exactly one, so points on a line stay on it. */
    b[0] = CUB_Q16_ONE - b[1] - b[2] - b[3] - b[4];
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

/* Where a swing point needs only the ramp's clearance (and a sole point
 * none): over the ground, or over an obstacle whose top is no higher than
 * the foothold of this half of the swing (level): a foot leaving or landing
 * on a platform's top stands on it [ours]. Tested as an obstacle there,
 * the heel (a fifth of the foot below the path) asked 95 raises (0.95 m)
 * for a step 12 cm up, and the planner, capping the raises, refused it. */
static bool on_ground(const cub_gait_terrain *t, cub_vec3 q, cub_q16 h, cub_q16 level)
{
    return h <= cub_gait_ground_height(t, q.x, q.z) || h <= level;
}

/* Over an obstacle the full clearance holds, ramp or not: no foothold
 * touches an obstacle's side (the planner keeps the foot base on its top
 * or 20 mm clear), so only the ground needs the ramp [ours]. */
static bool point_clears(const cub_gait_terrain *t, cub_vec3 q, cub_q16 need, cub_q16 clear,
                         cub_q16 level)
{
    cub_q16 h = cub_gait_height(t, q.x, q.z);
    if (!on_ground(t, q, h, level) && need < clear) need = clear;
    return cub_fx_sub(q.y, h) >= need;
}

/* A sole point ahead of or behind the path's point clears the obstacles
 * only: over the plain ground the walker keeps every foot point above the
 * ground itself, and a flat foot's toe held to the path's height on a
 * slope asked a 28-raise path at the swing's start (the toe's ground is
 * above the ankle's there) [ours]. */
static bool sole_clears(const cub_gait_terrain *t, cub_vec3 q, cub_q16 clear, cub_q16 level)
{
    cub_q16 h = cub_gait_height(t, q.x, q.z);
    return on_ground(t, q, h, level) || cub_fx_sub(q.y, h) >= clear;
}

/* The sole's points at one sample: the ankle's, the toe ahead and the
 * heel behind it along P0P4, each also side[0] off the line toward
 * (d.z, 0, -d.x) (d along P0P4) and side[1] the other way. */
typedef struct sole_offsets {
    cub_vec3 toe, heel, side[2];
} sole_offsets;

static bool sole_row_clears(const cub_gait_terrain *t, const swing_cfg *c, cub_vec3 q,
                            const sole_offsets *o, cub_q16 level)
{
    for (int k = 0; k < 3; k++) {
        cub_vec3 r = k < 2 ? cub_fx_vec3_add(q, o->side[k]) : q;
        if (k < 2 && !sole_clears(t, r, c->clear, level)) return false;
        if (c->foot > 0 && !sole_clears(t, cub_fx_vec3_add(r, o->toe), c->clear, level))
            return false;
        /* The heel lower than the flat sole the path models: the foot
         * comes down toe up (~15 degrees at the strike), a fifth of the
         * foot at the heel [ours]. */
        cub_vec3 heel = cub_fx_vec3_sub(r, o->heel);
        heel.y -= c->foot / 5;
        if (c->heel > 0 && !sole_clears(t, heel, c->clear, level)) return false;
    }
    return true;
}

/* Every sample of the path (the ankle's point; the sole around it) clears. */
static bool path_clears(const cub_gait_terrain *t, const swing_cfg *c, const cub_vec3 p[5],
                        const sole_offsets *o)
{
    for (int i = 1; i < c->samples; i++) {
        cub_q16 tt = (cub_q16)(((int64_t)i << 16) / c->samples);
        cub_vec3 q = cub_gait_bezier4(p, tt);
        cub_q16 need = clearance_at(c->clear, tt);
        cub_q16 level = tt < CUB_Q16_HALF ? p[0].y : p[4].y;
        if (!point_clears(t, q, need, c->clear, level) || !sole_row_clears(t, c, q, o, level))
            return false;
    }
    return true;
}

/* The toe's offset from the ankle: foot ahead along P0P4 on the ground. */
static cub_vec3 toe_offset(cub_vec3 from, cub_vec3 to, cub_q16 foot)
{
    cub_vec3 d = {cub_fx_sub(to.x, from.x), 0, cub_fx_sub(to.z, from.z)};
    uint32_t len = cub_fx_isqrt64((uint64_t)((int64_t)d.x * d.x + (int64_t)d.z * d.z));
    if (len == 0 || foot == 0) return (cub_vec3){0, 0, 0};
    return (cub_vec3){(cub_q16)((int64_t)d.x * foot / len), 0,
                      (cub_q16)((int64_t)d.z * foot / len)};
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
    cub_vec3 l = toe_offset(from_mm, to_mm, c.side[0]), r = toe_offset(from_mm, to_mm, c.side[1]);
    sole_offsets o = {toe_offset(from_mm, to_mm, c.foot),
                      toe_offset(from_mm, to_mm, c.heel),
                      {{l.z, 0, -l.x}, {-r.z, 0, r.x}}};
    while (!path_clears(t, &c, out->p, &o)) {
        if (out->raises >= c.max_raises) return CUB_ERR_RANGE;
        for (int k = 1; k <= 3; k++)
            out->p[k].y = cub_fx_add(out->p[k].y, c.raise);
        out->raises++;
    }
    out->clear = 1;
    return CUB_OK;
}

/* gait — the footstep planner (SEEDS.md § 003, "Footstep planner"): the
 * next n footholds, sequentially: step i+1 is planned only once step i
 * succeeded; a step with no feasible foothold sends the planner back to
 * its predecessor's next try, then further back; feasible footholds are
 * not ranked, the first one found is taken. Q16.16 mm. */
#include <limits.h>

#include "cub/gait.h"

#define DEFAULT_RISE_MM CUB_Q16_INT(200) /* ours: a knee-high stone is too much */
#define DEFAULT_TILT_MM CUB_Q16_INT(30)  /* ours: ~7 degrees over a 25 cm foot */
#define DEFAULT_GAP_MM CUB_Q16_INT(20)   /* ours: the swing's clearance, sideways */
#define STEPS_FLAT 4                     /* the seed: 4-5 on flat ground */
#define STEPS_ROUGH 3                    /* the seed: 2-3 */

/* ours: the nominal stride first, then shorter and longer ones alternately. */
static const cub_q16 default_factors[] = {CUB_Q16_ONE, 49152, 81920, 32768, 98304};

typedef struct heading {
    cub_q16 ux, uz; /* unit heading on the ground */
} heading;

static heading unit_heading(cub_q16 dx, cub_q16 dz)
{
    uint32_t len = cub_fx_isqrt64((uint64_t)((int64_t)dx * dx + (int64_t)dz * dz));
    if (len == 0) return (heading){0, CUB_Q16_ONE};
    return (heading){(cub_q16)((int64_t)dx * CUB_Q16_ONE / len),
                     (cub_q16)((int64_t)dz * CUB_Q16_ONE / len)};
}

/* The ground point at along_mm ahead of (x, z). */
static cub_vec3 ahead(const cub_gait_terrain *t, heading h, cub_q16 x, cub_q16 z, cub_q16 along)
{
    cub_q16 px = cub_fx_add(x, cub_fx_mul(h.ux, along));
    cub_q16 pz = cub_fx_add(z, cub_fx_mul(h.uz, along));
    return (cub_vec3){px, cub_gait_height(t, px, pz), pz};
}

static cub_q16 rise_limit(const cub_gait_plan_params *p)
{
    return p->max_rise_mm > 0 ? p->max_rise_mm : DEFAULT_RISE_MM;
}

static cub_q16 tilt_limit(const cub_gait_plan_params *p)
{
    return p->max_tilt_mm > 0 ? p->max_tilt_mm : DEFAULT_TILT_MM;
}

/* The foot's base rests on its highest ground point (heel, ankle, middle,
 * toe). The heel, a quarter foot behind the ankle [ours], keeps a foothold
 * from hugging an obstacle's far edge, where no swing can come down. */
static cub_q16 base_range(const cub_gait_terrain *t, const cub_gait_plan_params *p, heading h,
                          cub_q16 x, cub_q16 z, cub_q16 *top)
{
    cub_q16 lo = CUB_Q16_MAX, hi = CUB_Q16_MIN;
    for (int k = -1; k <= 4; k++) {
        cub_q16 y = ahead(t, h, x, z, (cub_q16)(((int64_t)p->foot_mm * k) / 4)).y;
        if (y < lo) lo = y;
        if (y > hi) hi = y;
    }
    *top = hi;
    return cub_fx_sub(hi, lo);
}

/* Inside an obstacle's footprint grown by gap (x, z). */
static bool in_box(const cub_gait_box *b, cub_q16 x, cub_q16 z, cub_q16 gap)
{
    return x > b->min_mm.x - gap && x < b->max_mm.x + gap && z > b->min_mm.z - gap &&
           z < b->max_mm.z + gap;
}

/* A point of the sole next to an obstacle: within gap of its footprint,
 * not on it. */
static bool beside_obstacle(const cub_gait_terrain *t, cub_q16 x, cub_q16 z, cub_q16 gap)
{
    for (int k = 0; k < t->obstacle_count; k++)
        if (in_box(&t->obstacles[k], x, z, gap) && !in_box(&t->obstacles[k], x, z, 0)) return true;
    return false;
}

/* The foot base (the heel a quarter foot behind the ankle to the toe, a
 * fifth of the foot either side; sampled every eighth of its length on
 * its middle and both edges) lands either on an obstacle's top (the tilt
 * test keeps it whole there) or gap clear of it: never just beside, where
 * the swing's last frames come down too low over the edge (CMU 16_11's
 * heel passed 4 mm over a stone) [ours]. */
static bool base_beside_obstacle(const cub_gait_terrain *t, const cub_gait_plan_params *p,
                                 heading h, cub_q16 x, cub_q16 z)
{
    cub_q16 gap = p->obstacle_gap_mm ? p->obstacle_gap_mm : DEFAULT_GAP_MM;
    if (gap < 0 || t->obstacle_count == 0) return false;
    cub_q16 back = p->foot_mm / 4, len = back + p->foot_mm, half = p->foot_mm / 5;
    for (int i = 0; i <= 8; i++) {
        cub_q16 along = cub_fx_sub((cub_q16)(((int64_t)len * i) / 8), back);
        for (int s = -1; s <= 1; s++) {
            cub_q16 px = cub_fx_add(x, cub_fx_sub(cub_fx_mul(h.ux, along), s * cub_fx_mul(h.uz, half)));
            cub_q16 pz = cub_fx_add(z, cub_fx_add(cub_fx_mul(h.uz, along), s * cub_fx_mul(h.ux, half)));
            if (beside_obstacle(t, px, pz, gap)) return true;
        }
    }
    return false;
}

bool cub_gait_foothold_ok(const cub_gait_terrain *t, const cub_gait_plan_params *p,
                          cub_q16 from_y_mm, cub_q16 x_mm, cub_q16 z_mm, cub_q16 dir_x,
                          cub_q16 dir_z)
{
    cub_q16 top;
    heading h = unit_heading(dir_x, dir_z);
    cub_q16 tilt = base_range(t, p, h, x_mm, z_mm, &top);
    return tilt <= tilt_limit(p) && cub_fx_abs(cub_fx_sub(top, from_y_mm)) <= rise_limit(p) &&
           !base_beside_obstacle(t, p, h, x_mm, z_mm);
}

static int step_count(const cub_gait_terrain *t, const cub_gait_plan_params *p)
{
    int n = p->steps > 0 ? p->steps : (cub_gait_terrain_is_flat(t) ? STEPS_FLAT : STEPS_ROUGH);
    return n < CUB_GAIT_MAX_STEPS ? n : CUB_GAIT_MAX_STEPS;
}

static cub_q16 factor(const cub_gait_plan_params *p, int k)
{
    return p->tries > 0 ? p->factors[k] : default_factors[k];
}

/* The swing from the same foot's last foothold clears within the cap.
 * Step i's foot swings from step i-2's foothold (the start's swinging foot
 * for step 0, the start's foothold for step 1); the other foot (odd steps)
 * strays to the other side, its side offsets swapped. Step 0's swing is
 * kept: the walker swings it (a last backtrack to step 0 re-tests and
 * keeps the new one). */
static bool swing_ok(const cub_gait_terrain *t, const cub_gait_plan_params *p, int i,
                     cub_vec3 from, cub_vec3 to, cub_gait_plan *out)
{
    if (!p->swing || cub_gait_terrain_is_flat(t)) return true;
    cub_gait_swing_params sp = *p->swing;
    if (i % 2) {
        sp.side_mm[0] = p->swing->side_mm[1];
        sp.side_mm[1] = p->swing->side_mm[0];
    }
    cub_gait_swing s;
    if (cub_gait_swing_path(t, &sp, from, to, &s) != CUB_OK) return false;
    if (i == 0) {
        out->first_swing = s;
        out->swung = 1;
    }
    return true;
}

/* Try k of step i after prev: the foothold, or false when it is not
 * feasible. The feet alternate; the lateral offset keeps them width apart. */
static bool try_step(const cub_gait_terrain *t, const cub_gait_plan_params *p, heading h,
                     const cub_gait_step *prev, int k, cub_gait_step *out)
{
    int left = !prev->left;
    cub_q16 side = left ? p->width_mm : -p->width_mm; /* left of the heading is (uz, -ux) */
    cub_q16 x = cub_fx_add(prev->foot_mm.x, cub_fx_mul(h.uz, side));
    cub_q16 z = cub_fx_sub(prev->foot_mm.z, cub_fx_mul(h.ux, side));
    cub_vec3 at = ahead(t, h, x, z, cub_fx_mul(p->stride_mm, factor(p, k)));
    if (!cub_gait_foothold_ok(t, p, prev->foot_mm.y, at.x, at.z, h.ux, h.uz)) return false;
    cub_q16 top;
    base_range(t, p, h, at.x, at.z, &top);
    *out = (cub_gait_step){{at.x, top, at.z}, left, k};
    return true;
}

/* Where step i's foot stands before it swings. */
static cub_vec3 swing_from(const cub_gait_start *start, const cub_gait_plan *plan, int i)
{
    if (i >= 2) return plan->steps[i - 2].foot_mm;
    return i == 1 ? start->foot_mm : start->swing_from_mm;
}

static bool params_ok(const cub_gait_plan_params *p)
{
    return p->stride_mm > 0 && p->foot_mm >= 0 && p->width_mm >= 0 && p->tries >= 0 &&
           p->tries <= CUB_GAIT_MAX_TRIES;
}

/* The planner's loop, resumable: at most budget footholds tested per
 * call, the state in pl, so the walker spreads a plan over the frames
 * before its foot-off [ours]. The same tests in the same order as one
 * call: the plan does not depend on the budget. */
cub_err cub_gait_planner_begin(cub_gait_planner *pl, const cub_gait_plan_params *p,
                               const cub_gait_start *start)
{
    if (!pl || !p || !start || !params_ok(p)) return CUB_ERR_ARG;
    *pl = (cub_gait_planner){.p = *p, .start = *start, .has_swing = p->swing != NULL};
    if (p->swing) pl->swing = *p->swing;
    pl->p.swing = NULL; /* pointed at pl->swing per run: the struct may be copied */
    return CUB_OK;
}

/* Test one foothold (try k[i] of step i), or back up when step i has
 * none left: false once the plan is done (pl->err set). */
static bool plan_one(cub_gait_planner *pl, const cub_gait_terrain *t, const cub_gait_plan_params *p,
                     heading h, int n, int tries)
{
    cub_gait_plan *out = &pl->plan;
    int i = pl->i, *k = pl->k;
    if (i >= n) {
        out->count = n;
        pl->done = 1;
        return false;
    }
    if (k[i] >= tries) { /* step i has no foothold left: back up */
        if (i == 0) {
            pl->err = CUB_ERR_EMPTY;
            pl->done = 1;
            return false;
        }
        k[i] = 0;
        k[--pl->i]++;
        out->backtracks++;
        return true;
    }
    cub_gait_step origin = {pl->start.foot_mm, pl->start.left, 0};
    out->tested++;
    if (try_step(t, p, h, i ? &out->steps[i - 1] : &origin, k[i], &out->steps[i]) &&
        swing_ok(t, p, i, swing_from(&pl->start, out, i), out->steps[i].foot_mm, out))
        pl->i++;
    else
        k[i]++;
    return true;
}

bool cub_gait_planner_run(cub_gait_planner *pl, const cub_gait_terrain *t, int budget)
{
    if (pl->done) return true;
    cub_gait_plan_params p = pl->p; /* pl->p keeps swing NULL: begin's inputs, comparable */
    p.swing = pl->has_swing ? &pl->swing : NULL;
    heading h = unit_heading(pl->start.dir_x, pl->start.dir_z);
    int n = step_count(t, &p);
    int tries = p.tries > 0 ? p.tries : (int)(sizeof default_factors / sizeof *default_factors);
    for (;;) {
        /* backing up tests nothing: only a test spends the budget */
        if (pl->i < n && pl->k[pl->i] < tries && budget-- <= 0) return false;
        if (!plan_one(pl, t, &p, h, n, tries)) return true;
    }
}

cub_err cub_gait_plan_steps(const cub_gait_terrain *t, const cub_gait_plan_params *p,
                            const cub_gait_start *start, cub_gait_plan *out)
{
    if (!t || !p || !start || !out || !params_ok(p)) return CUB_ERR_ARG;
    cub_gait_planner pl;
    cub_gait_planner_begin(&pl, p, start);
    cub_gait_planner_run(&pl, t, INT_MAX);
    *out = pl.plan;
    return pl.err;
}

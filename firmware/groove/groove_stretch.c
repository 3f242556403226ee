/* groove — the wrist's clock across a beat (ours, issue 23's beat
 * alignment): the seed's accent runs over the whole stretch from a beat
 * note's key to the next beat note's key; the non-beat keys between are
 * passing points, passed at speed (the seed's "non-beat after non-beat is
 * uniform" applied across the key). The stretch is timed by arc length,
 * so the only speed minima the wrist makes are the accent's: on the beats.
 * Q16.16 throughout. */
#include "groove_internal.h"

#define STEPS 8        /* |B'| sampled at each step's ends and middle (Simpson) */
#define MAX_STRETCH 16 /* notes: a stretch with no beat also breaks at every 16th note */

/* |B'(u)| of the cubic Bézier pt (mm per unit u, Q16). */
static cub_q16 speed_at(const cub_groove_key pt[4], cub_q16 u)
{
    int64_t t = u, s = CUB_Q16_ONE - u;
    int64_t a = 3 * (s * s >> 16), b = 6 * (s * t >> 16), c = 3 * (t * t >> 16);
    int64_t dx = (a * (pt[1].x_mm - pt[0].x_mm) + b * (pt[2].x_mm - pt[1].x_mm) +
                  c * (pt[3].x_mm - pt[2].x_mm)) >> 16;
    int64_t dy = (a * (pt[1].y_mm - pt[0].y_mm) + b * (pt[2].y_mm - pt[1].y_mm) +
                  c * (pt[3].y_mm - pt[2].y_mm)) >> 16;
    return (cub_q16)cub_fx_isqrt64((uint64_t)(dx * dx + dy * dy));
}

/* d[2j], d[2j + 1], d[2j + 2]: step j's start, middle and end. */
static void samples(const cub_groove_key pt[4], int64_t d[2 * STEPS + 1])
{
    for (int j = 0; j <= 2 * STEPS; j++)
        d[j] = speed_at(pt, (cub_q16)(j * CUB_Q16_ONE / (2 * STEPS)));
}

/* Step j's arc length (Simpson: the speed a parabola through its three
 * samples), x = 0..1 of the step, in mm x STEPS (Q16). */
static int64_t step_s(const int64_t *d, int64_t x)
{
    int64_t b = -3 * d[0] + 4 * d[1] - d[2], c = 2 * d[0] - 4 * d[1] + 2 * d[2];
    int64_t x2 = x * x >> 16, x3 = x2 * x >> 16;
    return (d[0] * x + b * x2 / 2 + c * x3 / 3) >> 16;
}

static int64_t step_speed(const int64_t *d, int64_t x)
{
    int64_t b = -3 * d[0] + 4 * d[1] - d[2], c = 2 * d[0] - 4 * d[1] + 2 * d[2];
    return d[0] + (b * x >> 16) + (c * (x * x >> 16) >> 16);
}

cub_q16 cub_groove_path_length(const cub_groove_key pt[4])
{
    int64_t d[2 * STEPS + 1], sum = 0;
    samples(pt, d);
    for (int j = 0; j < STEPS; j++)
        sum += step_s(d + 2 * j, CUB_Q16_ONE);
    return (cub_q16)(sum / STEPS);
}

/* x in [0, 1] of one step where its arc length is c (mm x STEPS): Newton
 * from the middle, kept in the step. */
static int64_t step_x(const int64_t *d, int64_t c, int64_t whole)
{
    int64_t x = whole > 0 ? c * CUB_Q16_ONE / whole : 0;
    for (int it = 0; it < 4; it++) {
        int64_t v = step_speed(d, x);
        if (v <= 0) break;
        x -= (step_s(d, x) - c) * CUB_Q16_ONE / v;
        x = x < 0 ? 0 : x > CUB_Q16_ONE ? CUB_Q16_ONE : x;
    }
    return x;
}

cub_q16 cub_groove_path_u(const cub_groove_key pt[4], cub_q16 s_mm)
{
    int64_t d[2 * STEPS + 1];
    samples(pt, d);
    int64_t left = (int64_t)s_mm * STEPS;
    for (int j = 0; j < STEPS; j++) {
        int64_t whole = step_s(d + 2 * j, CUB_Q16_ONE);
        if (left <= whole || j + 1 == STEPS) {
            int64_t x = step_x(d + 2 * j, left, whole);
            return (cub_q16)((j * (int64_t)CUB_Q16_ONE + x) / STEPS);
        }
        left -= whole;
    }
    return CUB_Q16_ONE;
}

/* A stretch starts on a beat note, and on every 16th note only where the
 * 15 notes before it have no beat (session 35: a break at every 16th note
 * stopped the wrist on a passing key mid-beat, an off-beat motion beat
 * every 16 notes in a reel; the bound stays: a stretch has at most 31
 * notes). */
static bool stretch_starts(const cub_groove_note *notes, int i)
{
    if (i == 0 || notes[i].is_beat) return true;
    if (i % MAX_STRETCH) return false;
    for (int k = i - MAX_STRETCH + 1; k < i; k++)
        if (notes[k].is_beat) return false;
    return true;
}

void cub_groove_stretch_of(const cub_groove_note *notes, int n, int i, int *first, int *last)
{
    int a = i, b = i + 1;
    while (!stretch_starts(notes, a))
        a--;
    while (b < n - 1 && !stretch_starts(notes, b))
        b++;
    *first = a, *last = b < n ? b : n - 1;
}

static void path_points(const cub_groove_plan *plan, int i, cub_groove_key pt[4])
{
    pt[0] = plan->keys[i], pt[1] = plan->handles[i].out_mm;
    pt[2] = plan->handles[i + 1].in_mm, pt[3] = plan->keys[i + 1];
}

cub_groove_key cub_groove_wrist_at(const cub_groove_plan *plan, int64_t t_us)
{
    int n = plan->n, i = groove_note_at(plan->notes, n, t_us), a, b;
    if (i < 0) return plan->keys[0];
    if (i + 1 >= n) return plan->keys[n - 1];
    cub_groove_stretch_of(plan->notes, n, i, &a, &b);
    int64_t total = 0;
    for (int k = a; k < b; k++)
        total += plan->handles[k].len_mm;
    cub_q16 tau = groove_tau(t_us, plan->notes[a].start_us, plan->notes[b].start_us);
    cub_groove_timing kind = plan->notes[a].is_beat ? CUB_GROOVE_ACCENT : CUB_GROOVE_EASE_IN;
    int64_t s = total * cub_groove_timing_at(kind, tau) >> 16;
    int k = a;
    while (k + 1 < b && s > plan->handles[k].len_mm)
        s -= plan->handles[k++].len_mm;
    cub_groove_key pt[4];
    path_points(plan, k, pt);
    return cub_groove_bezier(pt, cub_groove_path_u(pt, (cub_q16)s));
}

/* The wrist's peak speed on a stretch over its mean (arc length / time),
 * Q16: the timing curve's steepest (the accent's start 2.4, the ease-in's
 * 4/3) times the beat stop's level (1 / (1 - (before + after) k / (k + 1)),
 * the clock's fastest), the highest of the stretch's beats (a flat slow
 * beat's hump peaks at twice its mean). An upper bound: the peaks rarely
 * meet. */
static int64_t ramps_of(const groove_beat *b)
{
    return ((int64_t)b->before + b->after) * b->power / (b->power + 1);
}

static int64_t peak_gain(const cub_groove_params *p, const cub_groove_note *notes, int n, int a, int b)
{
    int64_t g = notes[a].is_beat ? CUB_Q16_ONE * 12 / 5 : CUB_Q16_ONE * 4 / 3, ramps = 0;
    groove_beat beat;
    for (int64_t t = notes[a].start_us; t < notes[b].start_us; t = beat.start_us + beat.len_us) {
        if (!groove_beat_at(p, notes, n, t, &beat)) break;
        ramps = ramps_of(&beat) > ramps ? ramps_of(&beat) : ramps;
    }
    if (ramps <= 0 || ramps >= CUB_Q16_ONE) return g;
    return g * CUB_Q16_ONE / (CUB_Q16_ONE - ramps);
}

static cub_groove_key toward(cub_groove_key from, cub_groove_key to, cub_q16 f)
{
    return (cub_groove_key){cub_fx_lerp(from.x_mm, to.x_mm, f), cub_fx_lerp(from.y_mm, to.y_mm, f)};
}

static cub_q16 path_len(const cub_groove_key *keys, const cub_groove_handles *h, int i)
{
    const cub_groove_key pt[4] = {keys[i], h[i].out_mm, h[i + 1].in_mm, keys[i + 1]};
    return cub_groove_path_length(pt);
}

/* Stretch [a, b) drawn in about key a by f: keys, handles and lengths; key
 * b's out handle moves with it, the next path's length is measured again. */
static void shrink(cub_groove_key *keys, cub_groove_handles *h, int n, int a, int b, cub_q16 f)
{
    cub_groove_key o = keys[a], old_b = keys[b];
    h[a].out_mm = toward(o, h[a].out_mm, f);
    for (int k = a + 1; k <= b; k++) {
        keys[k] = toward(o, keys[k], f);
        h[k].in_mm = toward(o, h[k].in_mm, f);
        if (k < b) h[k].out_mm = toward(o, h[k].out_mm, f);
    }
    h[b].out_mm.x_mm += keys[b].x_mm - old_b.x_mm;
    h[b].out_mm.y_mm += keys[b].y_mm - old_b.y_mm;
    for (int k = a; k < b; k++)
        h[k].len_mm = path_len(keys, h, k);
    if (b + 1 < n) h[b].len_mm = path_len(keys, h, b);
}

void cub_groove_stretch_limit(const cub_groove_params *p, const cub_groove_note *notes, int n,
                              cub_groove_key *keys, cub_groove_handles *h)
{
    int64_t most = p->peak_mm_s > 0 ? p->peak_mm_s : CUB_GROOVE_PEAK_MM_S;
    for (int a = 0, first, b; a + 1 < n; a = b) {
        cub_groove_stretch_of(notes, n, a, &first, &b);
        int64_t t = notes[b].start_us - notes[a].start_us, total = 0;
        for (int k = a; k < b; k++)
            total += h[k].len_mm;
        if (t <= 0 || t > INT64_MAX / most || total <= 0) continue;
        /* the peak, mm/s: total x gain / t; over the most, drawn in */
        int64_t allowed = most * t / 1000000 * CUB_Q16_ONE / peak_gain(p, notes, n, a, b);
        if (total > allowed) shrink(keys, h, n, a, b, (cub_q16)(allowed * CUB_Q16_ONE / total));
    }
}

/* groove — the beat stop (ours, issue 23's beat alignment, round 2): the
 * music time as the motion reads it. Every meter beat, inside a long note
 * too, becomes a short stop of the whole body (the wrist on its path, the
 * waist's and head's turns, the left hand): the clock's speed falls to 0
 * on each beat and rises again after it, and runs a little faster
 * between, so each beat stays at its own time. Q16.16. */
#include "groove_internal.h"

/* floor(a / b) for b > 0. */
static int64_t floor_div(int64_t a, int64_t b)
{
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}

/* r^(k + 1) for r in [0, 1] (Q16). */
static int64_t power(int64_t r, int k)
{
    int64_t p = r;
    for (int i = 0; i < k; i++)
        p = p * r >> 16;
    return p;
}

/* The warped share g(x) of a beat at x (both Q16 in [0, 1]): speed 0 at
 * both ends, rising as (x / after)^k from the first beat and falling as
 * ((1 - x) / before)^k into the next, level between; the level keeps
 * g(1) = 1 (each ramp covers 1 / (k + 1) of its width). */
static int64_t warp(int64_t x, int64_t after, int64_t before, int k)
{
    const int64_t one = CUB_Q16_ONE;
    int64_t den = one - (after + before) * k / (k + 1); /* the level is one / den */
    if (x < after) return power(x * one / after, k) * after / ((k + 1) * den);
    if (x > one - before)
        return one - power((one - x) * one / before, k) * before / ((k + 1) * den);
    return (x - after * k / (k + 1)) * one / den;
}

/* A flat beat's longest level (ours, issue 23's round 8): a held move
 * does not cruise at a constant speed for seconds. In a slow beat with few
 * keys (an adagio's 1.5 s beat, one or two notes) the level stretched over
 * most of it, and on so flat a speed every rounding of the path and the
 * pose made a local minimum of the summed speed, several per beat between
 * the beats (docs/groove.md, rounds 7-8). Past this the two ramps take the
 * whole beat: the speed rises and falls again. A beat with more keys
 * inside (a reel's four eighths to a half-note beat) is not flat: its keys
 * already move the speed, and a hump there cost the reels (round 7). */
#define CRUISE_MAX_US INT64_C(500000)
#define FLAT_KEYS 1 /* melody keys strictly inside a beat for it to be flat */

/* Whether the beat [prev, prev + len) holding note i has at most
 * FLAT_KEYS note starts strictly inside it. */
static bool beat_flat(const cub_groove_note *notes, int n, int i, int64_t prev, int64_t len)
{
    int inside = 0;
    for (int k = i; k >= 0 && notes[k].start_us > prev && inside <= FLAT_KEYS; k--)
        inside++;
    for (int k = i + 1; k < n && notes[k].start_us < prev + len && inside <= FLAT_KEYS; k++)
        inside++;
    return inside <= FLAT_KEYS;
}

static bool stop_ok(cub_q16 before, cub_q16 after, int k)
{
    return k >= 1 && k <= 3 && before >= 0 && after >= 0 && before + after > 0 && before < CUB_Q16_ONE &&
           after < CUB_Q16_ONE && (int64_t)before + after <= CUB_Q16_ONE;
}

bool groove_beat_at(const cub_groove_params *p, const cub_groove_note *notes, int n, int64_t t_us,
                    groove_beat *out)
{
    int i = groove_note_at(notes, n, t_us);
    if (i < 0 || !stop_ok(p->stop_before, p->stop_after, p->stop_power)) return false;
    int64_t len = notes[i].beat_us, anchor = notes[i].start_us + notes[i].grid_us;
    if (len <= 0) return false;
    int64_t b = p->stop_before, a = p->stop_after, ramps = a + b;
    *out = (groove_beat){anchor + floor_div(t_us - anchor, len) * len, len, p->stop_before,
                         p->stop_after, p->stop_power};
    if ((CUB_Q16_ONE - ramps) * len <= CRUISE_MAX_US * CUB_Q16_ONE) return true;
    if (!beat_flat(notes, n, i, out->start_us, len)) return true;
    /* a slow flat beat: the ramps take all of it, in their own ratio, straight */
    out->before = (cub_q16)(b * CUB_Q16_ONE / ramps);
    out->after = (cub_q16)(CUB_Q16_ONE - out->before);
    out->power = 1;
    return true;
}

int64_t cub_groove_clock(const cub_groove_plan *plan, int64_t t_us)
{
    groove_beat b;
    if (!groove_beat_at(&plan->params, plan->notes, plan->n, t_us, &b)) return t_us;
    int64_t x = (t_us - b.start_us) * CUB_Q16_ONE / b.len_us;
    return b.start_us + warp(x, b.after, b.before, b.power) * b.len_us / CUB_Q16_ONE;
}

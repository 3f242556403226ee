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

static bool stop_ok(cub_q16 before, cub_q16 after, int k)
{
    return k >= 1 && k <= 3 && before >= 0 && after >= 0 && before + after > 0 && before < CUB_Q16_ONE &&
           after < CUB_Q16_ONE && (int64_t)before + after <= CUB_Q16_ONE;
}

int64_t cub_groove_clock(const cub_groove_plan *plan, int64_t t_us)
{
    const cub_groove_params *p = &plan->params;
    int i = groove_note_at(plan->notes, plan->n, t_us);
    if (i < 0 || !stop_ok(p->stop_before, p->stop_after, p->stop_power)) return t_us;
    const cub_groove_note *note = &plan->notes[i];
    int64_t len = note->beat_us, anchor = note->start_us + note->grid_us;
    if (len <= 0) return t_us;
    int64_t prev = anchor + floor_div(t_us - anchor, len) * len;
    int64_t x = (t_us - prev) * CUB_Q16_ONE / len;
    return prev + warp(x, p->stop_after, p->stop_before, p->stop_power) * len / CUB_Q16_ONE;
}

/* groove — the beat stop (ours, issue 23's beat alignment, round 2): the
 * music time as the motion reads it. Every meter beat, inside a long note
 * too, becomes a short stop of the whole body (the wrist on its path, the
 * waist's and head's turns, the left hand): the clock's speed falls
 * linearly to 0 on each beat and rises again after it, and runs a little
 * faster between, so each beat stays at its own time. Q16.16. */
#include "groove_internal.h"

/* floor(a / b) for b > 0. */
static int64_t floor_div(int64_t a, int64_t b)
{
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}

/* The warped share g(x) of a beat at x (both Q16 in [0, 1]): speed 0 at
 * both ends, ramps over `after` from the first beat and over `before` into
 * the next, level between; the level keeps g(1) = 1. */
static int64_t warp(int64_t x, int64_t after, int64_t before)
{
    const int64_t one = CUB_Q16_ONE;
    int64_t den = one - (after + before) / 2; /* the level is one / den */
    if (x < after) return x * x / (2 * after) * one / den;
    if (x > one - before) {
        int64_t r = one - x;
        return one - r * r / (2 * before) * one / den;
    }
    return (x - after / 2) * one / den;
}

static bool stop_ok(cub_q16 before, cub_q16 after)
{
    return before >= 0 && after >= 0 && before + after > 0 && before < CUB_Q16_ONE &&
           after < CUB_Q16_ONE && (int64_t)before + after <= CUB_Q16_ONE;
}

int64_t cub_groove_clock(const cub_groove_plan *plan, int64_t t_us)
{
    const cub_groove_params *p = &plan->params;
    int i = groove_note_at(plan->notes, plan->n, t_us);
    if (i < 0 || !stop_ok(p->stop_before, p->stop_after)) return t_us;
    const cub_groove_note *note = &plan->notes[i];
    int64_t len = note->beat_us, anchor = note->start_us + note->grid_us;
    if (len <= 0) return t_us;
    int64_t prev = anchor + floor_div(t_us - anchor, len) * len;
    int64_t x = (t_us - prev) * CUB_Q16_ONE / len;
    return prev + warp(x, p->stop_after, p->stop_before) * len / CUB_Q16_ONE;
}

/* Following the music (SEEDS.md § 000 "Music sync"): at a frame whose song
 * time is known (a move's music tag, or the start of a repetition), compare
 * it with the audio clock and set the speed of what plays next so that it
 * reaches its next tag together with the music. The music's own rate
 * against the loop clock is measured too, so that a sound card running 5 %
 * slow is followed from the first move instead of being chased behind. */
#include "coach_internal.h"

#define SYNC_BOUND_DEFAULT ((cub_q16)9830) /* 0.15 */
#define SYNC_BOUND_MAX ((cub_q16)(CUB_Q16_ONE * 9 / 10))
#define RATE_BASELINE_US 1000000 /* measure over at least 1 s */

cub_q16 cub_coach_sync_bound(cub_q16 bound_q16)
{
    if (bound_q16 <= 0) return SYNC_BOUND_DEFAULT;
    return bound_q16 > SYNC_BOUND_MAX ? SYNC_BOUND_MAX : bound_q16; /* never stand still */
}

cub_q16 cub_coach_sync_speed(int32_t tag_ms, int32_t music_ms, int32_t span_ms, cub_q16 rate_q16,
                             cub_q16 bound_q16)
{
    if (rate_q16 <= 0) rate_q16 = CUB_Q16_ONE;
    bound_q16 = cub_coach_sync_bound(bound_q16);
    const int64_t lo = CUB_Q16_ONE - bound_q16, hi = CUB_Q16_ONE + bound_q16;
    if (span_ms <= 0) return CUB_Q16_ONE;
    /* Song time the music still needs to reach the target tag. */
    const int64_t music_left_ms = (int64_t)span_ms + tag_ms - music_ms;
    if (music_left_ms <= 0) return (cub_q16)hi;
    /* span * rate < 2^62: no overflow; rounded to nearest. */
    int64_t s = ((int64_t)span_ms * rate_q16 + music_left_ms / 2) / music_left_ms;
    if (s < lo) s = lo;
    if (s > hi) s = hi;
    return (cub_q16)s;
}

void coach_sync_observe(cub_coach *c, int32_t music_ms)
{
    /* Anchor at the first moving reading: audio starts after a silent
     * buffer or two, and that start-up delay is not a rate. */
    if (c->music_on && c->anchor_ms < 0 && music_ms > 0) {
        c->anchor_ms = music_ms;
        c->anchor_us = c->now_us;
    }
}

/* Music ms per loop ms since the anchor, in [0.5, 2]; the last value while
 * the baseline is still short. */
static cub_q16 measure_rate(const cub_coach *c, int32_t music_ms)
{
    const int64_t dt_us = c->now_us - c->anchor_us;
    if (c->anchor_ms < 0 || dt_us < RATE_BASELINE_US) return c->rate_q16;
    const int64_t dm_ms = (int64_t)music_ms - c->anchor_ms;
    int64_t r = (dm_ms * 1000 * CUB_Q16_ONE + dt_us / 2) / dt_us; /* < 2^58 */
    if (r < CUB_Q16_HALF) r = CUB_Q16_HALF;
    if (r > 2 * CUB_Q16_ONE) r = 2 * CUB_Q16_ONE;
    return (cub_q16)r;
}

cub_q16 coach_sync_at(cub_coach *c, int32_t pos_ms, int32_t target_ms, int32_t lead_ms,
                      int32_t music_ms)
{
    if (music_ms < 0 || !c->music_on) return c->sync_q16;
    c->rate_q16 = measure_rate(c, music_ms);
    /* The dance plays target - pos of song while the music plays that less
     * the lead: the same as a dance lead_ms further behind. */
    c->sync_q16 = cub_coach_sync_speed(pos_ms - lead_ms, music_ms, target_ms - pos_ms,
                                       c->rate_q16, c->desc.sync_bound_q16);
    cub_log_event(c->desc.log, c->now_us, "coach", "sync",
                  "move=%d music_ms=%d tag_ms=%d speed=%q rep=%d rate=%q", c->move, music_ms,
                  pos_ms, c->sync_q16, c->rep, c->rate_q16);
    return c->sync_q16;
}

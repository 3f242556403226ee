/* groove — the seed's parameter sets (table 1) and the right-wrist keys,
 * one per note (SEEDS.md § 001, "Right wrist keyframes"). */
#include "cub/groove.h"

#define DEFAULT_X_SPAN_MM CUB_Q16_INT(400)
/* The beat stop (ours): chosen by docs/groove.md's leave-one-style-out
 * protocol, round 3 (every fold chose these): a short slowing into the
 * beat, a longer, cubic start after it. */
#define STOP_BEFORE ((CUB_Q16_ONE + 5) / 10) /* rounded, as the candidates were run */
#define STOP_AFTER (CUB_Q16_ONE / 5)
#define STOP_POWER 3
#define DEFAULT_Y_REACH_MM CUB_Q16_INT(250)
#define DEFAULT_PACE_MM_S CUB_Q16_INT(1200)

cub_err cub_groove_params_set(char set, cub_groove_params *out)
{
    if (!out || (set != 'a' && set != 'b')) return CUB_ERR_ARG;
    bool a = set == 'a';
    *out = (cub_groove_params){
        .w = {1, 1, 1, 1},
        .v_beats = CUB_Q16_INT(2),
        .swing_deg = CUB_Q16_INT(7),
        .nod_deg = CUB_Q16_INT(10),
        .yscale_mm = a ? CUB_Q16_INT(14) : CUB_Q16_INT(3),
        .smooth_mm = a ? CUB_Q16_INT(100) : CUB_Q16_INT(11),
        /* the table's reflectance is percent; the text's is in [0, 1] */
        .reflectance = (cub_q16)(((a ? 100 : 12) * CUB_Q16_ONE + 50) / 100),
        .l1_mm = a ? CUB_Q16_INT(85) : CUB_Q16_INT(26),
        .l2_mm = CUB_Q16_INT(a ? 50 : 58),
        .x_span_mm = DEFAULT_X_SPAN_MM,
        .y_reach_mm = DEFAULT_Y_REACH_MM,
        .stop_before = STOP_BEFORE,
        .stop_after = STOP_AFTER,
        .stop_power = STOP_POWER,
    };
    return CUB_OK;
}

/* The segment's median pitch in Q16 (the mean of the middle two for an
 * even count: the paper writes "median (mean)"; median is ours). Rests
 * do not count; a segment of rests has median 0 and no y use for it. */
static cub_q16 median_pitch(const cub_groove_note *notes, cub_groove_segment s)
{
    uint16_t hist[128] = {0};
    int count = 0;
    for (int i = s.first; i < s.end; i++)
        if (notes[i].pitch < 128) hist[notes[i].pitch]++, count++;
    if (count == 0) return 0;
    int lo = -1, hi = -1, seen = 0;
    for (int pitch = 0; pitch < 128 && hi < 0; pitch++) {
        seen += hist[pitch];
        if (lo < 0 && seen >= (count + 1) / 2) lo = pitch;
        if (seen >= count / 2 + 1) hi = pitch;
    }
    return (cub_q16)((lo + hi) * (CUB_Q16_ONE / 2));
}

static void segment_y(const cub_groove_params *p, const cub_groove_note *notes,
                      cub_groove_segment s, cub_groove_key *keys, cub_q16 prev_y)
{
    cub_q16 median = median_pitch(notes, s),
            reach = p->y_reach_mm > 0 ? p->y_reach_mm : DEFAULT_Y_REACH_MM;
    cub_q16 peak = 0;
    for (int i = s.first; i < s.end; i++) {
        if (notes[i].pitch == CUB_GROOVE_REST) {
            keys[i].y_mm = i > s.first ? keys[i - 1].y_mm : prev_y;
            continue;
        }
        keys[i].y_mm = cub_fx_mul(cub_fx_sub(CUB_Q16_INT(notes[i].pitch), median), p->yscale_mm);
        if (cub_fx_abs(keys[i].y_mm) > peak) peak = cub_fx_abs(keys[i].y_mm);
    }
    /* Out of reach: the whole segment is scaled in, keeping its shape. */
    if (peak > reach)
        for (int i = s.first; i < s.end; i++)
            keys[i].y_mm = (cub_q16)((int64_t)keys[i].y_mm * reach / peak);
}

static void segment_x(const cub_groove_params *p, const cub_groove_note *notes,
                      cub_groove_segment s, cub_groove_key *keys, cub_q16 x, int dir)
{
    int64_t total = 0;
    for (int i = s.first; i < s.end; i++)
        total += notes[i].length_beats;
    cub_q16 span = p->x_span_mm > 0 ? p->x_span_mm : DEFAULT_X_SPAN_MM;
    for (int i = s.first; i < s.end; i++) {
        int64_t step = total > 0 && i > 0 ? (int64_t)notes[i].length_beats * span / total : 0;
        x = cub_fx_add(x, (cub_q16)(dir * step));
        keys[i].x_mm = x;
    }
}

cub_err cub_groove_keys(const cub_groove_params *p, const cub_groove_note *notes, int n,
                        const cub_groove_segment *segs, int seg_count, cub_groove_key *keys)
{
    if (!p || !notes || !segs || !keys || n < 1 || seg_count < 1) return CUB_ERR_ARG;
    for (int k = 0, at = 0; k < seg_count; at = segs[k++].end)
        if (segs[k].first != at || segs[k].end <= at || segs[k].end > n ||
            (k == seg_count - 1 && segs[k].end != n))
            return CUB_ERR_RANGE;
    cub_q16 x = 0, y = 0;
    for (int k = 0; k < seg_count; k++) {
        segment_x(p, notes, segs[k], keys, x, k % 2 ? -1 : 1);
        segment_y(p, notes, segs[k], keys, y);
        if (k == 0) keys[0].y_mm = 0; /* the melody's first note keeps the wrist */
        x = keys[segs[k].end - 1].x_mm;
        y = keys[segs[k].end - 1].y_mm;
    }
    return CUB_OK;
}

void cub_groove_keys_pace(const cub_groove_params *p, const cub_groove_note *notes, int n,
                          cub_groove_key *keys)
{
    int64_t pace = p->pace_mm_s > 0 ? p->pace_mm_s : DEFAULT_PACE_MM_S;
    for (int i = 1; i < n; i++) {
        int64_t t = notes[i].start_us - notes[i - 1].start_us;
        /* so long a wait (hours, in a damaged tempo map) that no key needs pacing */
        if (t > INT64_MAX / pace) continue;
        int64_t dx = keys[i].x_mm - keys[i - 1].x_mm, dy = keys[i].y_mm - keys[i - 1].y_mm;
        int64_t d = cub_fx_isqrt64((uint64_t)(dx * dx + dy * dy)), most = pace * t / 1000000;
        if (t <= 0 || d <= most) continue;
        keys[i].x_mm = (cub_q16)(keys[i - 1].x_mm + dx * most / d);
        keys[i].y_mm = (cub_q16)(keys[i - 1].y_mm + dy * most / d);
    }
}

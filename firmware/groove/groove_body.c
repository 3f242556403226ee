/* groove — the waist's and head's turns (SEEDS.md § 001, fig. 10) and the
 * left hand's reach and lift; the note sounding at a time. */
#include "groove_internal.h"

int groove_note_at(const cub_groove_note *notes, int n, int64_t t_us)
{
    int lo = 0, hi = n; /* first note starting after t_us, by bisection */
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        if (notes[mid].start_us <= t_us)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo - 1;
}

int64_t groove_note_end(const cub_groove_note *notes, int n, int64_t end_us, int i)
{
    if (i + 1 < n) return notes[i + 1].start_us;
    return end_us > notes[i].start_us ? end_us : notes[i].start_us;
}

cub_q16 groove_tau(int64_t t_us, int64_t t0, int64_t t1)
{
    if (t1 <= t0 || t_us >= t1) return CUB_Q16_ONE;
    if (t_us <= t0) return 0;
    return (cub_q16)((t_us - t0) * CUB_Q16_ONE / (t1 - t0));
}

/* Fig. 11 (back to rest): ease in and out; fig. 12 (the swing): a fast
 * start settling into the end. Both cubic Bézier in value (ours: the
 * figures' shapes, not their numbers, survive in the text). The swing
 * starts from rest (session 33): 1 - (1 - u)^3 left the waist at full
 * speed on the beat and still before it, so the smoothed speed's minimum
 * came before the beat (Bailando's alignment, docs/groove.md). */
static cub_q16 ease_in_out(cub_q16 u)
{
    int64_t t = u;
    return (cub_q16)((3 * CUB_Q16_ONE - 2 * t) * (t * t >> 16) >> 16);
}

static cub_q16 swing_curve(cub_q16 u)
{
    int64_t s = CUB_Q16_ONE - u; /* ease_in_out(1 - (1 - u)^2): 84 % done by half */
    return ease_in_out((cub_q16)(CUB_Q16_ONE - (s * s >> 16)));
}

/* The speed bound for the turns (ours, session 35): no turn faster than
 * TURN_DEG_S at its curve's steepest (the swing's 2.23 x its mean, the
 * return's 1.5 x): a turn with too little time turns less, and a return
 * with too little time lowers the turn it returns from. */
#define TURN_DEG_S 90
#define SWING_GAIN_PCT 224
#define REST_GAIN_PCT 150

/* The farthest a move may go in t_us at per_s (Q16 units a second) at its
 * curve's steepest, which is gain_pct of its mean speed: the turns' and
 * the left hand's bound alike. */
static cub_q16 most_in(cub_q16 per_s, int64_t t_us, int gain_pct)
{
    if (t_us > 1000000000) return INT32_MAX; /* minutes: nothing to bound */
    int64_t d = (int64_t)per_s * 100 / gain_pct * t_us / 1000000;
    return (cub_q16)(d < INT32_MAX ? d : INT32_MAX);
}

static cub_q16 most_deg(int64_t dt_us, int gain_pct)
{
    return most_in(CUB_Q16_INT(TURN_DEG_S), dt_us, gain_pct);
}

static cub_q16 capped(cub_q16 v, cub_q16 from, cub_q16 most)
{
    return cub_fx_clamp(v, cub_fx_sub(from, most), cub_fx_add(from, most));
}

/* The melody's turns after the count-in's (k of them in out already, the
 * last ending on the first note): from where it left the body. */
static int melody_turns(const cub_groove_note *notes, int n, int64_t end_us, cub_q16 amount_deg,
                        cub_groove_turn *out, int k)
{
    cub_q16 current = k ? out[k - 1].to_deg : 0;
    int direct = current > 0 ? -1 : 1;
    int64_t since = notes[0].start_us; /* the seed's accumulate, as a time */
    for (int i = 0; i < n; i++) {
        if (!notes[i].is_beat || notes[i].length_beats < CUB_Q16_ONE) continue;
        cub_q16 to = (cub_q16)((int64_t)amount_deg * notes[i].intensity / 120 * direct);
        int64_t end = groove_note_end(notes, n, end_us, i), turn = notes[i].start_us;
        if (k > 0 && turn > since) { /* the return to rest in time */
            current = capped(current, 0, most_deg(turn - since, REST_GAIN_PCT));
            out[k - 1].to_deg = current;
        }
        to = capped(to, turn > since ? 0 : current, most_deg(end - turn, SWING_GAIN_PCT));
        out[k++] = (cub_groove_turn){since, turn, end, current, to};
        current = to, since = end, direct = -direct;
    }
    return k;
}

#define COUNT_IN_BEATS 64 /* ours: a longer intro is not a count-in */

/* The count-in (ours, issue 23): before the melody's first note nothing
 * of the seed moves (Twinkle's two bars of drums: a still bear). The
 * meter's beats there sway the body as fig. 10 swings it on a beat note:
 * to the full amount on a bar's first beat, half on the others,
 * alternating sides, each swing leaving from rest on its beat (the speed's
 * minimum on the beat) and arriving by the next. The last ends on the
 * first note. At most cap turns and COUNT_IN_BEATS. */
static int count_in(const cub_groove_song *song, int64_t first_us, cub_q16 amount_deg,
                    cub_groove_turn *out, int cap)
{
    int cursor = 0, k = 0, direct = 1;
    int32_t tick = 0;
    cub_q16 current = 0;
    while (k < cap && k < COUNT_IN_BEATS && cub_groove_tick_us(song, tick) < first_us) {
        cub_groove_meter m = groove_meter_at(song, tick, &cursor);
        int32_t beat = groove_beat_ticks(song, m);
        int64_t at = cub_groove_tick_us(song, tick), next = cub_groove_tick_us(song, tick + beat);
        bool downbeat = ((tick - m.tick) / beat) % m.numerator == 0;
        cub_q16 to = (cub_q16)((downbeat ? amount_deg : amount_deg / 2) * direct);
        out[k++] = (cub_groove_turn){at, at, next < first_us ? next : first_us, current, to};
        current = to, direct = -direct, tick += beat;
    }
    return k;
}

cub_err groove_song_turns(const cub_groove_song *song, const cub_groove_note *notes, int n,
                          int64_t end_us, cub_q16 amount_deg, cub_groove_turn *out, int cap,
                          int *count)
{
    if (!song || !notes || !out || !count || n < 1 || cap < n) return CUB_ERR_ARG;
    int k = count_in(song, notes[0].start_us, amount_deg, out, cap - n);
    *count = melody_turns(notes, n, end_us, amount_deg, out, k);
    return CUB_OK;
}

cub_err cub_groove_turns(const cub_groove_note *notes, int n, int64_t end_us, cub_q16 amount_deg,
                         cub_groove_turn *out, int *count)
{
    if (!notes || !out || !count || n < 1) return CUB_ERR_ARG;
    *count = melody_turns(notes, n, end_us, amount_deg, out, 0);
    return CUB_OK;
}

cub_q16 cub_groove_turn_at(const cub_groove_turn *turns, int count, int64_t t_us)
{
    int lo = 0, hi = count; /* the last turn starting at or before t_us */
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        if (turns[mid].start_us <= t_us)
            lo = mid + 1;
        else
            hi = mid;
    }
    if (lo == 0) return 0;
    const cub_groove_turn *t = &turns[lo - 1];
    if (t_us >= t->end_us) return t->to_deg;
    if (t_us < t->turn_us) /* back to rest */
        return cub_fx_lerp(t->from_deg, 0, ease_in_out(groove_tau(t_us, t->start_us, t->turn_us)));
    cub_q16 from = t->start_us == t->turn_us ? t->from_deg : 0;
    return cub_fx_lerp(from, t->to_deg, swing_curve(groove_tau(t_us, t->turn_us, t->end_us)));
}

#define REACH_OUT_MM CUB_Q16_INT(110) /* ours: a full reach, for 2 beats or more */
#define REACH_UP_MM CUB_Q16_INT(40)
#define LIFT_MM CUB_Q16_INT(60)
#define REACH_MM CUB_Q16_INT(117) /* |(110, 40)| */

static bool staccato(const cub_groove_note *notes, int n, int i)
{
    return notes[i].pitch != CUB_GROOVE_REST && notes[i].length_beats < CUB_Q16_ONE && i + 1 < n &&
           notes[i + 1].pitch == CUB_GROOVE_REST;
}

/* The speed bound for the left hand (ours, session 35): a move of mm over
 * t_us at most CUB_GROOVE_PEAK_MM_S at its curve's steepest (gain_pct of
 * its mean: the reach's 300, the lift's 224, the drop's 200), smaller
 * where the note is short. */
static cub_q16 in_time(cub_q16 mm, int64_t t_us, int gain_pct)
{
    cub_q16 most = most_in(CUB_GROOVE_PEAK_MM_S, t_us, gain_pct);
    return most < mm ? most : mm;
}

/* Staccato note i's lift: in time for its lift (swing curve, 2.24 x) and
 * for the drop over the rest after it (1 - tau^2, 2 x). */
static cub_q16 lift_height(const cub_groove_plan *plan, int i)
{
    const cub_groove_note *notes = plan->notes;
    int64_t up = notes[i + 1].start_us - notes[i].start_us,
            down = groove_note_end(notes, plan->n, plan->end_us, i + 1) - notes[i + 1].start_us;
    return in_time(in_time(LIFT_MM, up, 224), down, 200);
}

/* Out and back over the note: eased up to the middle, eased down after. */
static cub_groove_key reach(const cub_groove_note *note, cub_q16 tau, int64_t t_us)
{
    cub_q16 extra = cub_fx_clamp(note->length_beats - CUB_Q16_ONE, 0, CUB_Q16_ONE);
    cub_q16 mm = in_time(cub_fx_mul(extra, REACH_MM), t_us, 300); /* ease 1.5 x 2 ways */
    extra = (cub_q16)((int64_t)mm * CUB_Q16_ONE / REACH_MM);
    cub_q16 u = tau < CUB_Q16_HALF ? ease_in_out(2 * tau) : ease_in_out(2 * (CUB_Q16_ONE - tau));
    cub_q16 amount = cub_fx_mul(u, extra);
    return (cub_groove_key){cub_fx_mul(REACH_OUT_MM, amount), cub_fx_mul(REACH_UP_MM, amount)};
}

cub_groove_key cub_groove_left_at(const cub_groove_plan *plan, int64_t t_us)
{
    const cub_groove_note *notes = plan->notes;
    int n = plan->n, i = groove_note_at(notes, n, t_us);
    cub_groove_key none = {0, 0};
    if (i < 0) return none;
    int64_t end = groove_note_end(notes, n, plan->end_us, i), t = end - notes[i].start_us;
    cub_q16 tau = groove_tau(t_us, notes[i].start_us, end);
    if (notes[i].pitch != CUB_GROOVE_REST && notes[i].length_beats > CUB_Q16_ONE)
        return reach(&notes[i], tau, t);
    if (staccato(notes, n, i)) /* lift, slowing to the top */
        return (cub_groove_key){0, cub_fx_mul(lift_height(plan, i), swing_curve(tau))};
    if (i > 0 && staccato(notes, n, i - 1)) /* drop, accelerating, stop */
        return (cub_groove_key){0, cub_fx_mul(lift_height(plan, i - 1),
                                              CUB_Q16_ONE - cub_fx_mul(tau, tau))};
    return none;
}

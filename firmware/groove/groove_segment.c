/* groove — segmentation of the melody (SEEDS.md § 001, "Segmentation" and
 * "DP", fig. 2): every range [i, j) of notes gets the objective f (lower is
 * better); then, like optimal line breaking, for length 2..n, every start i
 * and every split point mid, the two halves combined (a mean weighted by
 * the segments each holds: ours, the seed's formula is lost) replace the
 * range's value when not worse, so a tie takes the split and the later mid
 * wins. O(n^3), so a long melody is cut into windows first (ours). */
#include "cub/groove.h"

#define DEFAULT_WINDOW 48
#define PITCH_RANGE_GOAL 12 /* f2: a segment spanning an octave is best */

static int weight(const cub_groove_params *p, int k)
{
    int all_zero = !p->w[0] && !p->w[1] && !p->w[2] && !p->w[3];
    return all_zero ? 1 : p->w[k];
}

static cub_q16 preferred_beats(const cub_groove_params *p)
{
    return p->v_beats > 0 ? p->v_beats : CUB_Q16_INT(2);
}

cub_q16 cub_groove_density(const cub_groove_note *notes, int first, int end)
{
    int beat = 0;
    for (int i = first; i < end; i++)
        beat += notes[i].is_beat;
    /* The seed's "notes per beat-note" is inverted (SEEDS.md): beat-notes
     * per note stays in [0, 1] and needs no case for a segment without one. */
    return end > first ? (cub_q16)(((int64_t)beat << 16) / (end - first)) : 0;
}

/* What f needs of a range, grown one note at a time. */
typedef struct range_acc {
    int lo, hi, notes, beats;
    int64_t length; /* Q16 beats */
    bool last_rest_or_beat;
} range_acc;

static void acc_add(range_acc *a, const cub_groove_note *n)
{
    if (n->pitch != CUB_GROOVE_REST) {
        if (a->lo > a->hi) a->lo = a->hi = n->pitch;
        if (n->pitch < a->lo) a->lo = n->pitch;
        if (n->pitch > a->hi) a->hi = n->pitch;
    }
    a->notes++;
    a->beats += n->is_beat;
    a->length += n->length_beats;
    a->last_rest_or_beat = n->pitch == CUB_GROOVE_REST || n->is_beat;
}

/* |x - goal| / scale, saturating at 1 (ours: the seed says only "normalised"). */
static cub_q16 off_by(int64_t x, int64_t goal, int64_t scale)
{
    int64_t d = x > goal ? x - goal : goal - x;
    return d >= scale ? CUB_Q16_ONE : (cub_q16)((d << 16) / scale);
}

static cub_q16 acc_objective(const cub_groove_params *p, const range_acc *a, cub_q16 global)
{
    int range = a->lo > a->hi ? 0 : a->hi - a->lo;
    cub_q16 local = a->notes ? (cub_q16)(((int64_t)a->beats << 16) / a->notes) : 0;
    cub_q16 v = preferred_beats(p);
    cub_q16 f[4] = {a->last_rest_or_beat ? 0 : CUB_Q16_ONE,
                    off_by(range, PITCH_RANGE_GOAL, PITCH_RANGE_GOAL),
                    off_by(local, global, CUB_Q16_ONE), off_by(a->length, v, v)};
    int64_t sum = 0, wsum = 0;
    for (int k = 0; k < 4; k++) {
        sum += (int64_t)weight(p, k) * f[k];
        wsum += weight(p, k);
    }
    return wsum > 0 ? (cub_q16)((sum + wsum / 2) / wsum) : 0;
}

cub_q16 cub_groove_objective(const cub_groove_params *p, const cub_groove_note *notes, int first,
                             int end, cub_q16 global_density)
{
    range_acc a = {1, 0, 0, 0, 0, false};
    for (int i = first; i < end; i++)
        acc_add(&a, &notes[i]);
    return acc_objective(p, &a, global_density);
}

/* T[i][j] = the unsplit objective of every range of the window. */
static void fill_unsplit(const cub_groove_params *p, const cub_groove_note *w, int m,
                         cub_q16 global, cub_groove_work *t)
{
    for (int i = 0; i < m; i++) {
        range_acc a = {1, 0, 0, 0, 0, false};
        for (int j = i + 1; j <= m; j++) {
            acc_add(&a, &w[j - 1]);
            t->value[i][j] = acc_objective(p, &a, global);
            t->split[i][j] = 0;
            t->parts[i][j] = 1;
        }
    }
}

static int64_t run_dp(cub_groove_work *t, int m)
{
    int64_t weighed = 0;
    for (int len = 2; len <= m; len++)
        for (int i = 0; i + len <= m; i++) {
            int j = i + len;
            for (int mid = i + 1; mid < j; mid++) {
                int64_t c1 = t->parts[i][mid], c2 = t->parts[mid][j];
                int64_t v = ((int64_t)t->value[i][mid] * c1 + (int64_t)t->value[mid][j] * c2 +
                             (c1 + c2) / 2) /
                            (c1 + c2);
                weighed++;
                if (v <= t->value[i][j]) {
                    t->value[i][j] = (cub_q16)v;
                    t->split[i][j] = (uint8_t)mid;
                    t->parts[i][j] = (uint8_t)(c1 + c2);
                }
            }
        }
    return weighed;
}

typedef struct emit_ctx {
    const cub_groove_params *p;
    const cub_groove_note *notes;
    cub_q16 global;
    cub_groove_segment *out;
    int cap, count;
    int64_t f_sum;
} emit_ctx;

/* Split T[i][j] recursively while it has a split (depth <= the window). */
static void recover(const cub_groove_work *t, int base, int i, int j, emit_ctx *e)
{
    int mid = t->split[i][j];
    if (mid) {
        recover(t, base, i, mid, e);
        recover(t, base, mid, j, e);
        return;
    }
    if (e->count < e->cap) e->out[e->count] = (cub_groove_segment){base + i, base + j};
    e->f_sum += cub_groove_objective(e->p, e->notes, base + i, base + j, e->global);
    e->count++;
}

/* Where the window from start ends: after the last rest or beat note in
 * its second half, so a cut falls where f1 would put one anyway. */
static int window_end(const cub_groove_note *notes, int n, int start, int window)
{
    if (n - start <= window) return n;
    for (int k = start + window - 1; k >= start + window / 2; k--)
        if (notes[k].pitch == CUB_GROOVE_REST || notes[k].is_beat) return k + 1;
    return start + window;
}

cub_err cub_groove_segment_notes(const cub_groove_params *p, const cub_groove_note *notes, int n,
                                 int window, cub_groove_work *work, cub_groove_segment *out,
                                 int cap, int *count, cub_groove_cost *cost)
{
    if (!p || !notes || n < 1 || !work || !count || cap < 0 || (cap > 0 && !out))
        return CUB_ERR_ARG;
    if (window == 0) window = DEFAULT_WINDOW;
    if (window < 2 || window > CUB_GROOVE_WINDOW_MAX) return CUB_ERR_ARG;
    emit_ctx e = {p, notes, cub_groove_density(notes, 0, n), out, cap, 0, 0};
    cub_groove_cost c = {0, 0, 0};
    for (int start = 0; start < n;) {
        int end = window_end(notes, n, start, window);
        fill_unsplit(p, notes + start, end - start, e.global, work);
        c.splits += run_dp(work, end - start);
        recover(work, start, 0, end - start, &e);
        c.windows++;
        start = end;
    }
    c.mean_f = (cub_q16)(e.f_sum / e.count);
    if (cost) *cost = c;
    *count = e.count;
    return e.count > cap ? CUB_ERR_NOMEM : CUB_OK;
}

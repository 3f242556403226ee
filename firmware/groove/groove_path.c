/* groove — the wrist's paths between keys (SEEDS.md § 001, "Trajectories
 * between keys"): cubic Bézier handles per key, and the timing curves that
 * say how fast the wrist runs along each path ("Speed along a
 * trajectory"). Q16.16 throughout. */
#include "cub/groove.h"

#define L1_MAX_BEATS CUB_Q16_INT(2) /* ours: a 4-beat note would fling L1 x 4 */

static cub_groove_key key_add(cub_groove_key a, cub_groove_key b)
{
    return (cub_groove_key){cub_fx_add(a.x_mm, b.x_mm), cub_fx_add(a.y_mm, b.y_mm)};
}

static cub_groove_key key_sub(cub_groove_key a, cub_groove_key b)
{
    return (cub_groove_key){cub_fx_sub(a.x_mm, b.x_mm), cub_fx_sub(a.y_mm, b.y_mm)};
}

static cub_groove_key key_lerp(cub_groove_key a, cub_groove_key b, cub_q16 t)
{
    return (cub_groove_key){cub_fx_lerp(a.x_mm, b.x_mm, t), cub_fx_lerp(a.y_mm, b.y_mm, t)};
}

/* d scaled to length len; a zero d points along +x. */
static cub_groove_key with_length(cub_groove_key d, cub_q16 len)
{
    int64_t l = cub_fx_isqrt64((uint64_t)((int64_t)d.x_mm * d.x_mm + (int64_t)d.y_mm * d.y_mm));
    if (l == 0) return (cub_groove_key){len, 0};
    return (cub_groove_key){(cub_q16)((int64_t)d.x_mm * len / l),
                            (cub_q16)((int64_t)d.y_mm * len / l)};
}

/* Non-beat key: handles on the line along previous -> next, smooth apart.
 * How the smooth is shared between them is ours: in proportion to the
 * time of the path each starts, so the wrist's speed is the same on both
 * sides of the key (3 smooth / (T_in + T_out)); halves when a time is
 * unknown (the first and last keys). */
static cub_groove_handles smooth_handles(const cub_groove_params *p, const cub_groove_note *notes,
                                         const cub_groove_key *keys, int n, int i)
{
    cub_groove_key prev = keys[i > 0 ? i - 1 : i], next = keys[i + 1 < n ? i + 1 : i];
    int64_t t_in = i > 0 ? notes[i].start_us - notes[i - 1].start_us : 0,
            t_out = i + 1 < n ? notes[i + 1].start_us - notes[i].start_us : 0;
    if (t_in <= 0 || t_out <= 0) t_in = t_out = 1;
    cub_q16 in_len = (cub_q16)((int64_t)p->smooth_mm * t_in / (t_in + t_out));
    cub_groove_key dir = key_sub(next, prev);
    return (cub_groove_handles){key_sub(keys[i], with_length(dir, in_len)),
                                key_add(keys[i], with_length(dir, p->smooth_mm - in_len)), 0};
}

/* Beat key: in from G1 (above) / G2 (back) by intensity, out its mirror. */
static cub_groove_handles beat_handles(const cub_groove_params *p, const cub_groove_note *notes,
                                       const cub_groove_key *keys, int i)
{
    cub_groove_key k = keys[i];
    cub_q16 beats = notes[i].length_beats < L1_MAX_BEATS ? notes[i].length_beats : L1_MAX_BEATS;
    cub_groove_key g1 = {k.x_mm, cub_fx_add(k.y_mm, cub_fx_mul(p->l1_mm, beats))};
    int back = i > 0 && keys[i - 1].x_mm > k.x_mm ? 1 : -1; /* toward the previous key */
    cub_groove_key g2 = {cub_fx_add(k.x_mm, back * p->l2_mm), k.y_mm};
    cub_q16 s = (cub_q16)((int64_t)notes[i].intensity * CUB_Q16_ONE / 120);
    cub_groove_key in = key_lerp(g2, g1, s);
    cub_groove_key reflex = {cub_fx_sub(cub_fx_add(k.x_mm, k.x_mm), in.x_mm), in.y_mm};
    return (cub_groove_handles){in, key_lerp(k, reflex, p->reflectance), 0};
}

/* A handle at most pace x t / 3 from its key (t the time of the path it
 * shapes, 0 unknown): a Bézier leaves its ends at 3 |handle| / t, so no
 * handle asks for more than the pace the keys keep (ours). */
static cub_groove_key pace_handle(const cub_groove_params *p, cub_groove_key key, cub_groove_key h,
                                  int64_t t)
{
    int64_t pace = p->pace_mm_s > 0 ? p->pace_mm_s : CUB_Q16_INT(1200);
    if (t <= 0 || t > INT64_MAX / pace) return h; /* unknown, or hours: no cap */
    cub_groove_key d = key_sub(h, key);
    int64_t len = cub_fx_isqrt64((uint64_t)((int64_t)d.x_mm * d.x_mm + (int64_t)d.y_mm * d.y_mm));
    int64_t most = pace * t / 3000000;
    return len > most ? key_add(key, with_length(d, (cub_q16)most)) : h;
}

static int64_t dist(cub_groove_key a, cub_groove_key b)
{
    cub_groove_key d = key_sub(a, b);
    return cub_fx_isqrt64((uint64_t)((int64_t)d.x_mm * d.x_mm + (int64_t)d.y_mm * d.y_mm));
}

/* A non-beat key's handles scaled together (their time shares kept) so
 * neither is longer than half its path's chord (ours, session 33): busy
 * notes' keys lie closer than the seed's smooth, and handles longer than
 * the chord loop the path, each loop a slowing off the beat (set a's
 * reels and hornpipes). Keys farther apart keep the seed's smooth. */
static void chord_cap(const cub_groove_key *keys, int n, int i, cub_groove_handles *h)
{
    int64_t li = dist(h->in_mm, keys[i]), lo = dist(h->out_mm, keys[i]);
    int64_t ci = i > 0 ? dist(keys[i - 1], keys[i]) / 2 : li,
            co = i + 1 < n ? dist(keys[i + 1], keys[i]) / 2 : lo;
    int64_t num = 1, den = 1; /* the factor, the smaller of ci / li and co / lo */
    if (li > ci) num = ci, den = li;
    if (lo > co && co * den < num * lo) num = co, den = lo;
    if (num >= den) return;
    cub_q16 f = (cub_q16)(num * CUB_Q16_ONE / den);
    h->in_mm = key_lerp(keys[i], h->in_mm, f);
    h->out_mm = key_lerp(keys[i], h->out_mm, f);
}

cub_err cub_groove_handles_make(const cub_groove_params *p, const cub_groove_note *notes, int n,
                                const cub_groove_key *keys, cub_groove_handles *out)
{
    if (!p || !notes || !keys || !out || n < 1) return CUB_ERR_ARG;
    for (int i = 0; i < n; i++) {
        cub_groove_handles h = notes[i].is_beat ? beat_handles(p, notes, keys, i)
                                                : smooth_handles(p, notes, keys, n, i);
        int64_t t_in = i > 0 ? notes[i].start_us - notes[i - 1].start_us : 0,
                t_out = i + 1 < n ? notes[i + 1].start_us - notes[i].start_us : 0;
        out[i].in_mm = pace_handle(p, keys[i], h.in_mm, t_in);
        out[i].out_mm = pace_handle(p, keys[i], h.out_mm, t_out);
        if (!notes[i].is_beat) chord_cap(keys, n, i, &out[i]);
    }
    for (int i = 0; i < n; i++) {
        const cub_groove_key pt[4] = {keys[i], out[i].out_mm, out[i + 1 < n ? i + 1 : i].in_mm,
                                      keys[i + 1 < n ? i + 1 : i]};
        out[i].len_mm = i + 1 < n ? cub_groove_path_length(pt) : 0;
    }
    return CUB_OK;
}

/* One coordinate of a cubic Bézier at u, in 64 bits (Q16 in, Q16 out). */
static cub_q16 cubic(cub_q16 c0, cub_q16 c1, cub_q16 c2, cub_q16 c3, cub_q16 u)
{
    int64_t t = u, s = CUB_Q16_ONE - u;
    int64_t b0 = (s * s >> 16) * s >> 16, b1 = 3 * ((s * s >> 16) * t >> 16),
            b2 = 3 * ((s * t >> 16) * t >> 16), b3 = (t * t >> 16) * t >> 16;
    return (cub_q16)((b0 * c0 + b1 * c1 + b2 * c2 + b3 * c3) >> 16);
}

cub_groove_key cub_groove_bezier(const cub_groove_key pt[4], cub_q16 u)
{
    return (cub_groove_key){cubic(pt[0].x_mm, pt[1].x_mm, pt[2].x_mm, pt[3].x_mm, u),
                            cubic(pt[0].y_mm, pt[1].y_mm, pt[2].y_mm, pt[3].y_mm, u)};
}

cub_groove_timing cub_groove_timing_of(const cub_groove_note *notes, int i)
{
    if (notes[i].is_beat) return CUB_GROOVE_ACCENT;
    return i > 0 && notes[i - 1].is_beat ? CUB_GROOVE_EASE_IN : CUB_GROOVE_UNIFORM;
}

#define Q(x) ((cub_q16)((x) * 65536.0 + 0.5))

/* A piece of a timing curve: tau from the previous piece's end to end,
 * u along the cubic Bézier c[0..3]. Control values are the Hermite form:
 * c1 = c0 + speed_in x length / 3, c2 = c3 - speed_out x length / 3. */
typedef struct piece {
    cub_q16 end, c[4];
} piece;

/* The accent (ours, the seed gives the shape in words): speed 2.4 at the
 * start dropping to 0.7 by tau 0.05 (fast, dropping quickly: the slowest
 * moment after the start stays within a frame or two of the beat), rising
 * steadily to 1.46 by 0.7, then a stop over the last 30 % (the wrist
 * stands still on the next key; its own path starts fast again). Speeds
 * are linear within each piece. The shape was chosen looking at the beat
 * alignment of all 19 songs (docs/groove.md). */
static const piece accent[3] = {
    {Q(0.0500), {0, Q(0.0400), Q(0.0658), Q(0.0775)}},
    {Q(0.7000), {Q(0.0775), Q(0.2292), Q(0.4635), Q(0.7805)}},
    {CUB_Q16_ONE, {Q(0.7805), Q(0.9268), CUB_Q16_ONE, CUB_Q16_ONE}},
};

static const piece ease_in[1] = {{CUB_Q16_ONE, {0, 0, Q(2.0 / 3.0), CUB_Q16_ONE}}};

static cub_q16 pieces_at(const piece *p, int count, cub_q16 tau)
{
    cub_q16 start = 0;
    int i = 0;
    while (i + 1 < count && tau >= p[i].end)
        start = p[i++].end;
    cub_q16 local = cub_fx_div(tau - start, p[i].end - start);
    return cubic(p[i].c[0], p[i].c[1], p[i].c[2], p[i].c[3], local);
}

cub_q16 cub_groove_timing_at(cub_groove_timing kind, cub_q16 tau)
{
    tau = cub_fx_clamp(tau, 0, CUB_Q16_ONE);
    if (kind == CUB_GROOVE_EASE_IN) return pieces_at(ease_in, 1, tau);
    if (kind == CUB_GROOVE_ACCENT) return pieces_at(accent, 3, tau);
    return tau;
}

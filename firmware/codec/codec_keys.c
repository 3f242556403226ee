/* The error-bounded stream (cubkeys): open = check everything once, then
 * decode any one frame by random access. Layout (little-endian):
 *   header  "CUBKEYS" u8 version, u16 joint_count, u8 flags (bit 0: joint
 *           translations), u8 0, u32 frame_count, u32 frame_ns, u32 length
 *   joints  u8 name length, name, u8 parent + 1, u8 end site, offset x y z
 *           (i32 Q16.16 mm each)
 *   tracks  the rotation of every joint but end sites, the root's position,
 *           then (flag bit 0) the translation of every other such joint:
 *           u8 kind; a constant: 3 x i32; keys: 3 x u8 shift, 3 x u8 range
 *           bits, 3 x i32 base, u32 code bytes; the key frames as W =
 *           ceil(n / 64) u64 bit words; per segment (CUB_KEYS_SEGMENT frames) the
 *           u32 bit offset of its first code; per segment a header of 3 x 6
 *           bits (its widths) and 3 x range bits (its minimum), packed;
 *           then the codes, each key's three components LSB first, packed
 *   u32 CRC-32 (IEEE) of everything before it */
#include <string.h>

#include "codec_internal.h"
#include "codec_reader.h"

#define KEYS_MAGIC "CUBKEYS"
#define KEYS_HEADER_BYTES 24
#define KEYS_FLAG_TRANS 1u
#define Q30_ONE (INT32_C(1) << 30)
#define SEG_FRAMES CUB_KEYS_SEGMENT
#define SEG_SHIFT (SEG_FRAMES == 16 ? 4 : SEG_FRAMES == 32 ? 5 : 6)

static uint64_t le64(const uint8_t *p)
{
    uint64_t v;
    memcpy(&v, p, sizeof v);
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
    v = __builtin_bswap64(v);
#endif
    return v;
}

static uint32_t le32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* Set bits of x; by hand, as the firmware links no helper library. */
static int pop64(uint64_t x)
{
    x = x - ((x >> 1) & UINT64_C(0x5555555555555555));
    x = (x & UINT64_C(0x3333333333333333)) + ((x >> 2) & UINT64_C(0x3333333333333333));
    x = (x + (x >> 4)) & UINT64_C(0x0f0f0f0f0f0f0f0f);
    return (int)((x * UINT64_C(0x0101010101010101)) >> 56);
}

/* n (<= 32) bits at bit offset `at` of the codes at p, LSB first; end:
 * the stream's end, which an 8-byte load must not pass. */
static uint32_t bits_at(const uint8_t *p, const uint8_t *end, uint64_t at, int n)
{
    const uint8_t *b = p + (at >> 3);
    int skip = (int)(at & 7);
    uint64_t v = 0;
    if (end - b >= 8) {
        v = le64(b);
    } else {
        for (int i = (int)(end - b) - 1; i >= 0; i--)
            v = v << 8 | b[i];
    }
    return (uint32_t)((v >> skip) & ((UINT64_C(1) << n) - 1));
}

/* ceil(256 sqrt(t + 1)) for t = 64..255: a first guess for keys_sqrt. */
static const uint16_t sqrt_guess[192] = {
    2064, 2080, 2096, 2112, 2127, 2142, 2158, 2173, 2188, 2203, 2218, 2232, 2247, 2261, 2276, 2290,
    2304, 2319, 2333, 2347, 2361, 2375, 2388, 2402, 2416, 2429, 2443, 2456, 2469, 2483, 2496, 2509,
    2522, 2535, 2548, 2560, 2573, 2586, 2599, 2611, 2624, 2636, 2649, 2661, 2673, 2685, 2698, 2710,
    2722, 2734, 2746, 2758, 2770, 2781, 2793, 2805, 2816, 2828, 2840, 2851, 2863, 2874, 2885, 2897,
    2908, 2919, 2931, 2942, 2953, 2964, 2975, 2986, 2997, 3008, 3019, 3030, 3040, 3051, 3062, 3072,
    3083, 3094, 3104, 3115, 3125, 3136, 3146, 3157, 3167, 3177, 3188, 3198, 3208, 3218, 3229, 3239,
    3249, 3259, 3269, 3279, 3289, 3299, 3309, 3319, 3328, 3338, 3348, 3358, 3368, 3377, 3387, 3397,
    3406, 3416, 3426, 3435, 3445, 3454, 3464, 3473, 3482, 3492, 3501, 3511, 3520, 3529, 3538, 3548,
    3557, 3566, 3575, 3584, 3594, 3603, 3612, 3621, 3630, 3639, 3648, 3657, 3666, 3675, 3684, 3693,
    3701, 3710, 3719, 3728, 3737, 3745, 3754, 3763, 3772, 3780, 3789, 3798, 3806, 3815, 3823, 3832,
    3840, 3849, 3858, 3866, 3874, 3883, 3891, 3900, 3908, 3917, 3925, 3933, 3942, 3950, 3958, 3966,
    3975, 3983, 3991, 3999, 4008, 4016, 4024, 4032, 4040, 4048, 4056, 4064, 4072, 4080, 4088, 4096,
};

/* floor(sqrt(x)) for x <= 2^60, exact: a guess from the table (8 bits),
 * two Newton steps from above (16, then over 30 bits), then a fix-up; a
 * few times faster than the digit-by-digit cub_fx_isqrt64. */
static uint32_t keys_sqrt(uint64_t x)
{
    if (x < 64) return cub_fx_isqrt64(x);
    int e = 63 - __builtin_clzll(x), sh = (e & ~1) - 6;
    uint64_t r = (((uint64_t)sqrt_guess[(x >> sh) - 64] << (sh / 2)) >> 8) + 1;
    r = (r + x / r) / 2;
    r = (r + x / r) / 2;
    while (r * r > x)
        r--;
    while ((r + 1) * (r + 1) <= x)
        r++;
    return (uint32_t)r;
}

int32_t cub_keys_lerp(int32_t va, int32_t vb, int a, int b, int f)
{
    uint32_t t = ((uint32_t)(f - a) << 16) / (uint32_t)(b - a);
    int64_t d = (int64_t)((int64_t)vb - va) * t;
    return (int32_t)(va + (d >= 0 ? d >> 16 : -((-d) >> 16)));
}

cub_quat cub_keys_quat(int32_t x, int32_t y, int32_t z)
{
    uint64_t s =
        (uint64_t)((int64_t)x * x) + (uint64_t)((int64_t)y * y) + (uint64_t)((int64_t)z * z);
    uint64_t one = UINT64_C(1) << 60;
    if (s <= one) return (cub_quat){(int32_t)keys_sqrt(one - s), x, y, z};
    return cub_fx_quat_normalize((cub_quat){0, x, y, z});
}

int32_t cub_keys_key(int32_t base, uint64_t code, int shift, int rotation)
{
    int64_t v = base + (int64_t)(code << shift);
    if (rotation) v = v < -Q30_ONE ? -Q30_ONE : v > Q30_ONE ? Q30_ONE : v;
    return (int32_t)v;
}

/* A segment's header: its widths, its minimum, where its codes start. */
typedef struct seg {
    int bits[3], key_bits;
    uint64_t min[3], at;
} seg;

static void seg_read(const cub_keys *k, const cub_keys_track *t, int w, seg *s)
{
    const uint8_t *p = k->data + t->segs, *end = k->data + k->len;
    uint64_t at = (uint64_t)w * t->seg_bits;
    for (int c = 0; c < 3; c++, at += 6)
        s->bits[c] = (int)bits_at(p, end, at, 6);
    for (int c = 0; c < 3; c++) {
        s->min[c] = bits_at(p, end, at, t->range_bits[c]);
        at += t->range_bits[c];
    }
    s->key_bits = s->bits[0] + s->bits[1] + s->bits[2];
    s->at = le32(k->data + t->segoff + 4 * (size_t)w);
}

/* The value of the idx-th key of a segment. */
static void seg_key(const cub_keys *k, const cub_keys_track *t, const seg *s, int idx, int32_t v[3])
{
    const uint8_t *p = k->data + t->codes, *end = k->data + k->len;
    uint64_t at = s->at + (uint64_t)idx * s->key_bits;
    for (int c = 0; c < 3; c++) {
        v[c] = cub_keys_key(t->base[c], s->min[c] + bits_at(p, end, at, s->bits[c]), t->shift[c],
                            t->rotation);
        at += s->bits[c];
    }
}

/* The track's value at frame f. */
static void track_value(const cub_keys *k, const cub_keys_track *t, int f, int32_t v[3])
{
    if (t->kind != CUB_KEYS_ANIMATED) {
        memcpy(v, t->base, sizeof t->base);
        return;
    }
    const uint8_t *set = k->data + t->keyset;
    int w = f >> 6, bit = f & 63, a, b, wa = w, ia;
    uint64_t word = le64(set + 8 * w);
    uint64_t upto = bit == 63 ? ~UINT64_C(0) : (UINT64_C(2) << bit) - 1;
    uint64_t below = word & upto, above = word & ~upto;
    if (below) {
        a = (w << 6) + 63 - __builtin_clzll(below);
        ia = pop64(below) - 1;
    } else { /* keys are at most 64 apart: the previous one is in the word before */
        uint64_t prev = le64(set + 8 * (w - 1));
        wa = w - 1;
        a = (wa << 6) + 63 - __builtin_clzll(prev);
        ia = pop64(prev) - 1;
    }
    /* ia counted a's word up to a: count from its segment's start instead */
    uint64_t word_a = wa == w ? word : le64(set + 8 * wa);
    int start = (a & 63) & ~(SEG_FRAMES - 1);
    ia -= pop64(word_a & ((UINT64_C(1) << start) - 1));
    seg sa, sb;
    seg_read(k, t, a >> SEG_SHIFT, &sa);
    seg_key(k, t, &sa, ia, v);
    if (a == f) return;
    int32_t vb[3];
    b = above ? (w << 6) + __builtin_ctzll(above)
              : ((w + 1) << 6) + __builtin_ctzll(le64(set + 8 * (w + 1)));
    if (b >> SEG_SHIFT == a >> SEG_SHIFT) {
        seg_key(k, t, &sa, ia + 1, vb);
    } else { /* b is the first key of its segment */
        seg_read(k, t, b >> SEG_SHIFT, &sb);
        seg_key(k, t, &sb, 0, vb);
    }
    for (int c = 0; c < 3; c++)
        v[c] = cub_keys_lerp(v[c], vb[c], a, b, f);
}

cub_err cub_keys_pose(const cub_keys *k, int frame, cub_pose *out)
{
    if (!k || !out || frame < 0 || frame >= k->frame_count) return CUB_ERR_ARG;
    out->joint_count = k->joint_count;
    out->has_trans = k->has_trans;
    for (int j = 0; j < k->joint_count; j++) {
        int32_t v[3];
        int r = k->rot_track[j], tr = k->trans_track[j];
        if (r < 0 || k->tracks[r].kind == CUB_KEYS_DEFAULT) {
            out->rot[j] = cub_fx_quat_identity();
        } else {
            track_value(k, &k->tracks[r], frame, v);
            out->rot[j] = cub_keys_quat(v[0], v[1], v[2]);
        }
        if (j > 0 && !k->has_trans) continue;
        cub_vec3 *dst = j == 0 ? &out->root_mm : &out->trans_mm[j];
        if (tr < 0 || k->tracks[tr].kind == CUB_KEYS_DEFAULT) {
            *dst = j == 0 ? (cub_vec3){0, 0, 0} : k->offsets[j];
            continue;
        }
        track_value(k, &k->tracks[tr], frame, v);
        *dst = (cub_vec3){v[0], v[1], v[2]};
    }
    if (k->has_trans) out->trans_mm[0] = (cub_vec3){0, 0, 0};
    return CUB_OK;
}

static cub_err read_header(reader *r, cub_keys *k, cub_codec_problem *why)
{
    if (r->len < KEYS_HEADER_BYTES + CODEC_CRC_BYTES)
        return refuse(why, "too short for a cubkeys header", r->len);
    if (memcmp(r->p, KEYS_MAGIC, CODEC_MAGIC_LEN) != 0)
        return refuse(why, "not a cubkeys stream (no CUBKEYS magic)", 0);
    r->pos = CODEC_MAGIC_LEN;
    if (rd_u8(r) != CUB_KEYS_VERSION) return refuse(why, "unsupported cubkeys version", 7);
    k->joint_count = rd_u16(r);
    unsigned flags = rd_u8(r), zero = rd_u8(r);
    k->frame_count = (int)rd_u32(r);
    k->frame_ns = rd_u32(r);
    uint32_t length = rd_u32(r);
    k->has_trans = (flags & KEYS_FLAG_TRANS) != 0;
    if (k->joint_count < 1 || k->joint_count > CUB_MOTION_MAX_JOINTS)
        return refuse(why, "joint count outside 1..128", 8);
    if ((flags & ~KEYS_FLAG_TRANS) || zero) return refuse(why, "unknown flag bits", 10);
    if (k->frame_count < 1 || k->frame_count > CODEC_MAX_FRAMES)
        return refuse(why, "frame count outside 1..2^20", 12);
    if (k->frame_ns == 0) return refuse(why, "frame period is zero", 16);
    cub_err e = codec_check_crc(r, length, why);
    if (!e) r->len -= CODEC_CRC_BYTES; /* nothing below may read the CRC as data */
    return e;
}

/* The key frames: frame 0 and the last set, none past it, at most
 * CUB_KEYS_MAX_GAP apart. */
static cub_err check_keyset(const reader *r, const cub_keys *k, const cub_keys_track *t,
                            cub_codec_problem *why)
{
    int words = (k->frame_count + 63) >> 6, last = -1;
    for (int w = 0; w < words; w++) {
        size_t at = t->keyset + 8 * (size_t)w;
        uint64_t word = le64(r->p + at);
        for (int b = 0; b < 64; b++) {
            if (!(word >> b & 1)) continue;
            int f = (w << 6) + b;
            if (f >= k->frame_count) return refuse(why, "a key past the last frame", at);
            if ((last < 0 && f != 0) || (last >= 0 && f - last > CUB_KEYS_MAX_GAP))
                return refuse(why, "keys more than 64 frames apart (or none at frame 0)", at);
            last = f;
        }
    }
    if (last != k->frame_count - 1) return refuse(why, "no key at the last frame", t->keyset);
    return CUB_OK;
}

/* Whether base + code * 2^shift stays an int32 for every code up to top. */
static int fits(int32_t base, uint64_t top, int shift)
{
    if (top > (UINT64_C(1) << (63 - shift))) return 0;
    return (top << shift) <= (uint64_t)((int64_t)INT32_MAX - base);
}

/* Every segment: widths within 32 bits, values within int32, its codes
 * within the track's. */
static cub_err check_segments(const reader *r, const cub_keys *k, const cub_keys_track *t,
                              cub_codec_problem *why)
{
    int segs = (k->frame_count + SEG_FRAMES - 1) >> SEG_SHIFT;
    for (int w = 0; w < segs; w++) {
        seg s;
        seg_read(k, t, w, &s);
        size_t at = t->segs + (size_t)w * t->seg_bits / 8;
        for (int c = 0; c < 3; c++)
            if (s.bits[c] > 32 ||
                !fits(t->base[c], s.min[c] + ((UINT64_C(1) << s.bits[c]) - 1), t->shift[c]))
                return refuse(why, "a segment's width or minimum is out of range", at);
        uint64_t word = le64(r->p + t->keyset + 8 * (size_t)(w * SEG_FRAMES >> 6));
        int from = (w * SEG_FRAMES) & 63;
        uint64_t mask = SEG_FRAMES == 64 ? ~UINT64_C(0) : ((UINT64_C(1) << SEG_FRAMES) - 1) << from;
        int keys = pop64(word & mask);
        if (s.at + (uint64_t)keys * s.key_bits > (uint64_t)t->code_bytes * 8)
            return refuse(why, "a segment's codes run past the track's", t->segoff + 4 * (size_t)w);
    }
    return CUB_OK;
}

/* A constant's values within int32 and a rotation's within +-1. */
static int constant_ok(const cub_keys_track *t)
{
    for (int c = 0; c < 3; c++)
        if (t->rotation && (t->base[c] < -Q30_ONE || t->base[c] > Q30_ONE)) return 0;
    return 1;
}

static cub_err read_keys(reader *r, cub_keys *k, cub_keys_track *t, size_t at,
                         cub_codec_problem *why)
{
    t->code_bytes = rd_u32(r);
    if (r->pos > r->len) return refuse(why, "stream ends inside a track", at);
    if (t->shift[0] > 31 || t->shift[1] > 31 || t->shift[2] > 31 || t->range_bits[0] > 32 ||
        t->range_bits[1] > 32 || t->range_bits[2] > 32)
        return refuse(why, "track shift or range width past 31 / 32", at + 1);
    t->seg_bits = (uint8_t)(18 + t->range_bits[0] + t->range_bits[1] + t->range_bits[2]);
    size_t words = (size_t)(k->frame_count + 63) >> 6;
    size_t nseg = (size_t)(k->frame_count + SEG_FRAMES - 1) >> SEG_SHIFT;
    uint64_t keyset = r->pos, segoff = keyset + 8 * words, segs = segoff + 4 * nseg;
    uint64_t codes = segs + (nseg * t->seg_bits + 7) / 8, end = codes + t->code_bytes;
    if (end > r->len) return refuse(why, "stream ends inside a track's keys", r->pos);
    t->keyset = (uint32_t)keyset, t->segoff = (uint32_t)segoff;
    t->segs = (uint32_t)segs, t->codes = (uint32_t)codes;
    cub_err e = check_keyset(r, k, t, why);
    if (!e) e = check_segments(r, k, t, why);
    r->pos = (size_t)end;
    return e;
}

static cub_err read_track(reader *r, cub_keys *k, cub_keys_track *t, int rotation,
                          cub_codec_problem *why)
{
    size_t at = r->pos;
    memset(t, 0, sizeof *t);
    t->kind = rd_u8(r);
    t->rotation = (uint8_t)rotation;
    if (t->kind >= CUB_KEYS_KIND_COUNT_) return refuse(why, "unknown track kind", at);
    if (t->kind == CUB_KEYS_DEFAULT)
        return r->pos > r->len ? refuse(why, "stream ends inside a track", at) : CUB_OK;
    if (t->kind == CUB_KEYS_ANIMATED) {
        for (int c = 0; c < 3; c++)
            t->shift[c] = rd_u8(r);
        for (int c = 0; c < 3; c++)
            t->range_bits[c] = rd_u8(r);
    }
    for (int c = 0; c < 3; c++)
        t->base[c] = (int32_t)rd_u32(r);
    if (r->pos > r->len) return refuse(why, "stream ends inside a track", at);
    if (t->kind == CUB_KEYS_ANIMATED) return read_keys(r, k, t, at, why);
    return constant_ok(t) ? CUB_OK : refuse(why, "a constant rotation outside +-1", at + 1);
}

static cub_err add_track(reader *r, cub_keys *k, int16_t *slot, int rotation,
                         cub_codec_problem *why)
{
    *slot = (int16_t)k->track_count;
    return read_track(r, k, &k->tracks[k->track_count++], rotation, why);
}

static cub_err read_tracks(reader *r, const cub_skeleton *skel, cub_keys *k, cub_codec_problem *why)
{
    cub_err e = CUB_OK;
    for (int j = 0; j < k->joint_count; j++) {
        k->rot_track[j] = k->trans_track[j] = -1;
        k->offsets[j] = skel->joints[j].offset_mm;
    }
    for (int j = 0; j < k->joint_count && !e; j++)
        if (!skel->joints[j].is_end_site) e = add_track(r, k, &k->rot_track[j], 1, why);
    if (!e) e = add_track(r, k, &k->trans_track[0], 0, why);
    for (int j = 1; j < k->joint_count && k->has_trans && !e; j++)
        if (!skel->joints[j].is_end_site) e = add_track(r, k, &k->trans_track[j], 0, why);
    if (!e && r->pos != r->len) return refuse(why, "bytes left over after the last track", r->pos);
    return e;
}

cub_err cub_keys_open(const void *data, size_t len, cub_skeleton *skel, cub_keys *out,
                      cub_codec_problem *why)
{
    if (!data || !skel || !out) return CUB_ERR_ARG;
    memset(out, 0, sizeof *out);
    reader r = {data, len, 0};
    cub_err e = read_header(&r, out, why);
    if (e) return e;
    out->data = data;
    out->len = len;
    cub_motion_skeleton_reset(skel);
    for (int j = 0; j < out->joint_count && !e; j++)
        e = codec_read_joint(&r, skel, j, 1, why);
    if (!e && skel->joints[0].is_end_site)
        e = refuse(why, "the root is an end site", KEYS_HEADER_BYTES);
    return e ? e : read_tracks(&r, skel, out, why);
}

/* The cubkeys encoder (cub/codec_enc.h). Per track: the default, a
 * constant, or keys: the coarsest steps 2^shift (per component) whose
 * rounding holds the track's tolerance, and up to three finer ones, each
 * with greedy key removal (extend a linear run while every frame inside
 * stays within the tolerance), the cheapest in bits kept. A track's error
 * is in mm where it lands: a rotation's, at every bone below its joint and
 * the 3 cm shell; a translation's, its distance. Tolerance: s * bound, then
 * per track loosened while the whole still holds. The scale s is searched
 * on the real decoder's measured error. Doubles only pick candidates; the
 * bound is checked on the integer decode. */
#include "cub/codec_enc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cub/codec.h"
#include "pack_internal.h" /* pack_crc32 */

#define Q30 1073741824.0
#define Q16 65536.0
#define MAX_SHIFT 30
#define SHIFT_TRIES 4
#define GROW_STEPS 8
#define SHRINK_STEPS 24
#define BISECT_STEPS 3

typedef struct src_track {
    int rotation, joint;
    int32_t *v; /* [n * 3]: x y z on w >= 0 (Q2.30), or mm (Q16.16) */
    int32_t def[3];
    int probes;    /* a rotation's: bones below its joint */
    double *probe; /* [n * probes * 3]: where they are in the joint's frame (mm) */
} src_track;

typedef struct enc_track {
    int kind, shift[3], bits[3], keys; /* bits: of every frame's code, at the clip's range */
    int32_t base[3];
    uint8_t *key;   /* [n] 1 where a key is */
    uint32_t *code; /* [n * 3] codes, valid where key */
} enc_track;

typedef struct enc {
    const cub_clip *clip;
    int n, count;
    src_track src[CUB_KEYS_MAX_TRACKS];
    enc_track trk[CUB_KEYS_MAX_TRACKS];
    double scale[CUB_KEYS_MAX_TRACKS]; /* each track's own factor on s, from the refinement */
    enc_track spare;                   /* a track's trial encoding */
    uint32_t *scratch;                 /* [n * 3] */
} enc;

/* ---- per-track error, in doubles ------------------------------------- */

typedef struct xf {
    double q[4], p[3];
} xf;

static void qmul(const double *a, const double *b, double *o)
{
    double r[4] = {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
                   a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
                   a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
                   a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
    memcpy(o, r, sizeof r);
}

static void qrot(const double *q, const double *v, double *o)
{
    double p[4] = {0, v[0], v[1], v[2]}, c[4] = {q[0], -q[1], -q[2], -q[3]}, t[4];
    qmul(q, p, t);
    qmul(t, c, t);
    o[0] = t[1], o[1] = t[2], o[2] = t[3];
}

static void rot_of(const double *x, double *q)
{
    double s = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    q[0] = s < 1 ? sqrt(1 - s) : 0;
    q[1] = x[0], q[2] = x[1], q[3] = x[2];
    if (s > 1) {
        double m = sqrt(s);
        for (int c = 1; c < 4; c++)
            q[c] /= m;
    }
}

/* Error of value x (decoded units as doubles) at frame f: 1 - |dot| for a
 * rotation, squared distance (mm^2) for a translation. */
static double err_at(const src_track *s, int f, const double *x)
{
    const int32_t *v = s->v + 3 * (size_t)f;
    if (s->rotation) {
        /* The rotation error d = b^-1 a moves a point p of the joint's own
         * frame by |2 vec(d) x p| (exactly the chord, for p across the
         * axis); every bone below, and the 30 mm shell around it. */
        double a[4], b[4], d[4], xs[3] = {v[0] / Q30, v[1] / Q30, v[2] / Q30};
        rot_of(x, a);
        rot_of(xs, b);
        b[1] = -b[1], b[2] = -b[2], b[3] = -b[3];
        qmul(b, a, d);
        double sg = d[0] < 0 ? -2 : 2, w[3] = {sg * d[1], sg * d[2], sg * d[3]}, worst = 0;
        const double *p = s->probe + (size_t)f * s->probes * 3;
        for (int k = 0; k < s->probes; k++, p += 3) {
            double cx = w[1] * p[2] - w[2] * p[1], cy = w[2] * p[0] - w[0] * p[2],
                   cz = w[0] * p[1] - w[1] * p[0];
            double m = cx * cx + cy * cy + cz * cz;
            worst = m > worst ? m : worst;
        }
        double e = sqrt(worst) + CUB_KEYS_SHELL_MM * sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
        return e * e;
    }
    double e = 0;
    for (int c = 0; c < 3; c++) {
        double d = x[c] - v[c] / Q16;
        e += d * d;
    }
    return e;
}

static double unit(const src_track *s)
{
    return s->rotation ? Q30 : Q16;
}

static int fits_value(const src_track *s, int n, const int32_t *val, double tol)
{
    double x[3] = {val[0] / unit(s), val[1] / unit(s), val[2] / unit(s)};
    for (int f = 0; f < n; f++)
        if (err_at(s, f, x) > tol) return 0;
    return 1;
}

/* ---- keys at one shift ------------------------------------------------ */

/* Codes of every frame at shifts sh[3] (into code); 0 if rounding alone
 * breaks the tolerance or a value would leave int32. */
static int quantise(const src_track *s, int n, const int *sh3, double tol, enc_track *t,
                    uint32_t *code)
{
    for (int c = 0; c < 3; c++) {
        int sh = sh3[c];
        int64_t half = sh ? (int64_t)1 << (sh - 1) : 0;
        int32_t mn = s->v[c];
        for (int f = 1; f < n; f++)
            mn = s->v[3 * (size_t)f + c] < mn ? s->v[3 * (size_t)f + c] : mn;
        t->base[c] = mn;
        uint32_t top = 0;
        for (int f = 0; f < n; f++) {
            uint32_t k = (uint32_t)(((int64_t)s->v[3 * (size_t)f + c] - mn + half) >> sh);
            code[3 * (size_t)f + c] = k;
            top = k > top ? k : top;
        }
        int b = 0;
        while (b < 32 && (top >> b))
            b++;
        t->bits[c] = b;
        if (mn + ((((int64_t)1 << b) - 1) << sh) > INT32_MAX) return 0;
    }
    memcpy(t->shift, sh3, sizeof t->shift);
    for (int f = 0; f < n; f++) {
        double x[3];
        for (int c = 0; c < 3; c++)
            x[c] = cub_keys_key(t->base[c], code[3 * (size_t)f + c], sh3[c], s->rotation) / unit(s);
        if (err_at(s, f, x) > tol) return 0;
    }
    return 1;
}

static void key_x(const src_track *s, const enc_track *t, const uint32_t *code, int f, double *x)
{
    for (int c = 0; c < 3; c++)
        x[c] =
            cub_keys_key(t->base[c], code[3 * (size_t)f + c], t->shift[c], s->rotation) / unit(s);
}

/* Whether the line from key a to key b holds every frame between. */
static int run_holds(const src_track *s, const enc_track *t, const uint32_t *code, int a, int b,
                     double tol)
{
    double xa[3], xb[3];
    key_x(s, t, code, a, xa);
    key_x(s, t, code, b, xb);
    for (int f = a + 1; f < b; f++) {
        double u = (double)(f - a) / (b - a), x[3];
        for (int c = 0; c < 3; c++)
            x[c] = xa[c] + (xb[c] - xa[c]) * u;
        if (err_at(s, f, x) > tol) return 0;
    }
    return 1;
}

/* Greedy key removal; the number of keys. */
static int place_keys(const src_track *s, int n, const enc_track *t, const uint32_t *code,
                      double tol, uint8_t *key)
{
    memset(key, 0, (size_t)n);
    key[0] = 1;
    int a = 0, keys = 1;
    while (a < n - 1) {
        int best = a + 1;
        for (int b = a + 2; b < n && b - a <= CUB_KEYS_MAX_GAP; b++) {
            if (!run_holds(s, t, code, a, b, tol)) break;
            best = b;
        }
        key[best] = 1;
        keys++;
        a = best;
    }
    return keys;
}

/* ---- segments: range reduction per CUB_KEYS_SEGMENT frames ---------- */

static int bit_len(uint64_t v)
{
    int b = 0;
    while (b < 64 && (v >> b))
        b++;
    return b;
}

/* A segment's minimum code and widths, from the keys in it. */
typedef struct seg_enc {
    uint32_t min[3];
    int bits[3], keys;
} seg_enc;

#define SEG CUB_KEYS_SEGMENT

static void seg_of(const enc_track *t, int n, int w, seg_enc *sg)
{
    uint32_t mx[3] = {0, 0, 0};
    sg->keys = 0;
    for (int c = 0; c < 3; c++)
        sg->min[c] = UINT32_MAX;
    for (int f = w * SEG; f < n && f < w * SEG + SEG; f++) {
        if (!t->key[f]) continue;
        sg->keys++;
        for (int c = 0; c < 3; c++) {
            uint32_t k = t->code[3 * (size_t)f + c];
            sg->min[c] = k < sg->min[c] ? k : sg->min[c];
            mx[c] = k > mx[c] ? k : mx[c];
        }
    }
    for (int c = 0; c < 3; c++) {
        if (!sg->keys) sg->min[c] = mx[c] = 0;
        sg->bits[c] = bit_len(mx[c] - sg->min[c]);
    }
}

/* Widths of the segments' minimums. */
static void range_bits(const enc_track *t, int n, int rb[3])
{
    uint32_t top[3] = {0, 0, 0};
    for (int w = 0; w * SEG < n; w++) {
        seg_enc sg;
        seg_of(t, n, w, &sg);
        for (int c = 0; c < 3; c++)
            top[c] = sg.min[c] > top[c] ? sg.min[c] : top[c];
    }
    for (int c = 0; c < 3; c++)
        rb[c] = bit_len(top[c]);
}

/* Bits the track takes in the stream. */
static long track_cost(const enc_track *t, int n)
{
    if (t->kind == CUB_KEYS_DEFAULT) return 8;
    if (t->kind == CUB_KEYS_CONSTANT) return 8 + 96;
    long bits = 8 * (1 + 6 + 12 + 4), words = (n + 63) / 64, segs = (n + SEG - 1) / SEG;
    int rb[3];
    range_bits(t, n, rb);
    for (int w = 0; w < segs; w++) {
        seg_enc sg;
        seg_of(t, n, w, &sg);
        bits += (long)sg.keys * (sg.bits[0] + sg.bits[1] + sg.bits[2]);
    }
    return bits + words * 64 + segs * (32 + 18 + rb[0] + rb[1] + rb[2]);
}

/* ---- one track ---------------------------------------------------------- */

static void encode_track(enc *e, int i, double tol, enc_track *t)
{
    const src_track *s = &e->src[i];
    int n = e->n;
    t->kind = CUB_KEYS_DEFAULT;
    if (fits_value(s, n, s->def, tol)) return;
    t->kind = CUB_KEYS_CONSTANT;
    for (int c = 0; c < 3; c++) {
        int32_t mn = s->v[c], mx = s->v[c];
        for (int f = 1; f < n; f++) {
            int32_t x = s->v[3 * (size_t)f + c];
            mn = x < mn ? x : mn;
            mx = x > mx ? x : mx;
        }
        t->base[c] = (int32_t)(((int64_t)mn + mx) / 2);
    }
    if (fits_value(s, n, t->base, tol)) return;
    t->kind = CUB_KEYS_ANIMATED;
    /* The coarsest step that holds for all three components alike, then
     * each component as coarse as it can be alone (a twist about the bone
     * moves little but the shell), then finer steps to leave room for key
     * removal; the cheapest. */
    enc_track trial = *t;
    int top[3] = {MAX_SHIFT, MAX_SHIFT, MAX_SHIFT};
    while (top[0] > 0 && !quantise(s, n, top, tol, &trial, e->scratch))
        top[0] = top[1] = --top[2];
    for (int c = 0; c < 3; c++) {
        int up[3] = {top[0], top[1], top[2]};
        while (up[c] < MAX_SHIFT) {
            up[c]++;
            if (!quantise(s, n, up, tol, &trial, e->scratch)) {
                up[c]--;
                break;
            }
        }
        top[c] = up[c];
    }
    long best_cost = -1;
    uint8_t *key = malloc((size_t)n);
    for (int d = 0; d < SHIFT_TRIES && key; d++) {
        int sh[3];
        for (int c = 0; c < 3; c++)
            sh[c] = top[c] - d < 0 ? 0 : top[c] - d;
        if (!quantise(s, n, sh, tol, &trial, e->scratch) && (sh[0] | sh[1] | sh[2])) continue;
        trial.keys = place_keys(s, n, &trial, e->scratch, tol, key);
        trial.key = key, trial.code = e->scratch;
        long cost = track_cost(&trial, n);
        if (best_cost >= 0 && cost >= best_cost) continue;
        best_cost = cost;
        memcpy(t->shift, trial.shift, sizeof t->shift);
        memcpy(t->bits, trial.bits, sizeof t->bits);
        memcpy(t->base, trial.base, sizeof t->base);
        t->keys = trial.keys;
        memcpy(t->key, key, (size_t)n);
        memcpy(t->code, e->scratch, sizeof *t->code * 3 * (size_t)n);
    }
    free(key);
}

/* ---- the stream ---------------------------------------------------------- */

typedef struct writer {
    uint8_t *p;
    size_t len, cap;
    int bad;
} writer;

static void put(writer *w, const void *src, size_t n)
{
    if (w->len + n > w->cap) {
        size_t cap = w->cap ? w->cap * 2 : 4096;
        while (cap < w->len + n)
            cap *= 2;
        uint8_t *p = realloc(w->p, cap);
        if (!p) {
            w->bad = 1;
            return;
        }
        w->p = p, w->cap = cap;
    }
    memcpy(w->p + w->len, src, n);
    w->len += n;
}

static void put_u8(writer *w, unsigned v)
{
    uint8_t b = (uint8_t)v;
    put(w, &b, 1);
}

static void put_u32(writer *w, uint32_t v)
{
    uint8_t b[4] = {(uint8_t)v, (uint8_t)(v >> 8), (uint8_t)(v >> 16), (uint8_t)(v >> 24)};
    put(w, b, 4);
}

static void put_u64(writer *w, uint64_t v)
{
    put_u32(w, (uint32_t)v);
    put_u32(w, (uint32_t)(v >> 32));
}

static void write_joints(writer *w, const cub_skeleton *sk)
{
    for (int j = 0; j < sk->joint_count; j++) {
        const cub_joint *jt = &sk->joints[j];
        size_t len = strlen(jt->name);
        put_u8(w, (unsigned)len);
        put(w, jt->name, len);
        put_u8(w, (unsigned)(jt->parent + 1));
        put_u8(w, jt->is_end_site);
        put_u32(w, (uint32_t)jt->offset_mm.x);
        put_u32(w, (uint32_t)jt->offset_mm.y);
        put_u32(w, (uint32_t)jt->offset_mm.z);
    }
}

/* Bits LSB first into bytes. */
typedef struct bitw {
    writer *w;
    uint64_t acc;
    int have;
} bitw;

static void put_bits(bitw *b, uint64_t v, int n)
{
    for (int i = 0; i < n; i++) {
        b->acc |= ((v >> i) & 1) << b->have;
        if (++b->have == 8) {
            put_u8(b->w, (unsigned)b->acc);
            b->acc = 0, b->have = 0;
        }
    }
}

static void flush_bits(bitw *b)
{
    if (b->have) put_u8(b->w, (unsigned)b->acc);
    b->acc = 0, b->have = 0;
}

static void write_keys(writer *w, const enc_track *t, int n)
{
    int words = (n + 63) / 64, segs = (n + SEG - 1) / SEG, rb[3];
    range_bits(t, n, rb);
    for (int c = 0; c < 3; c++)
        put_u8(w, (unsigned)rb[c]);
    for (int c = 0; c < 3; c++)
        put_u32(w, (uint32_t)t->base[c]);
    uint64_t code_bits = 0;
    for (int wd = 0; wd < segs; wd++) {
        seg_enc sg;
        seg_of(t, n, wd, &sg);
        code_bits += (uint64_t)sg.keys * (sg.bits[0] + sg.bits[1] + sg.bits[2]);
    }
    put_u32(w, (uint32_t)((code_bits + 7) / 8));
    for (int wd = 0; wd < words; wd++) {
        uint64_t bits = 0;
        for (int b = 0; b < 64 && wd * 64 + b < n; b++)
            bits |= (uint64_t)t->key[wd * 64 + b] << b;
        put_u64(w, bits);
    }
    uint32_t at = 0;
    for (int wd = 0; wd < segs; wd++) {
        seg_enc sg;
        seg_of(t, n, wd, &sg);
        put_u32(w, at);
        at += (uint32_t)(sg.keys * (sg.bits[0] + sg.bits[1] + sg.bits[2]));
    }
    bitw b = {w, 0, 0};
    for (int wd = 0; wd < segs; wd++) {
        seg_enc sg;
        seg_of(t, n, wd, &sg);
        for (int c = 0; c < 3; c++)
            put_bits(&b, (uint64_t)sg.bits[c], 6);
        for (int c = 0; c < 3; c++)
            put_bits(&b, sg.min[c], rb[c]);
    }
    flush_bits(&b);
    for (int wd = 0; wd < segs; wd++) {
        seg_enc sg;
        seg_of(t, n, wd, &sg);
        for (int f = wd * SEG; f < n && f < wd * SEG + SEG; f++)
            for (int c = 0; c < 3 && t->key[f]; c++)
                put_bits(&b, t->code[3 * (size_t)f + c] - sg.min[c], sg.bits[c]);
    }
    flush_bits(&b);
}

static void write_track(writer *w, const enc_track *t, int n)
{
    put_u8(w, (unsigned)t->kind);
    if (t->kind == CUB_KEYS_DEFAULT) return;
    if (t->kind == CUB_KEYS_ANIMATED) {
        for (int c = 0; c < 3; c++)
            put_u8(w, (unsigned)t->shift[c]);
        write_keys(w, t, n);
        return;
    }
    for (int c = 0; c < 3; c++)
        put_u32(w, (uint32_t)t->base[c]);
}

static int write_stream(const enc *e, writer *w)
{
    const cub_clip *clip = e->clip;
    w->len = 0;
    put(w, "CUBKEYS", 7);
    put_u8(w, CUB_KEYS_VERSION);
    put_u8(w, (unsigned)clip->skel->joint_count & 0xFF);
    put_u8(w, (unsigned)clip->skel->joint_count >> 8);
    put_u8(w, clip->trans_mm ? 1 : 0);
    put_u8(w, 0);
    put_u32(w, (uint32_t)clip->frame_count);
    put_u32(w, clip->frame_ns);
    put_u32(w, 0); /* the length, below */
    write_joints(w, clip->skel);
    for (int i = 0; i < e->count; i++)
        write_track(w, &e->trk[i], e->n);
    if (w->bad) return -1;
    uint32_t total = (uint32_t)(w->len + 4);
    for (int b = 0; b < 4; b++)
        w->p[20 + b] = (uint8_t)(total >> (8 * b));
    put_u32(w, pack_crc32(w->p, w->len) /* the same CRC-32 (IEEE) */);
    return w->bad ? -1 : 0;
}

/* ---- measuring the decoded stream ----------------------------------------- */

/* Object-space transforms of a pose, in doubles (mm). */
static void forward(const cub_skeleton *sk, const cub_pose *ps, xf *w)
{
    for (int j = 0; j < sk->joint_count; j++) {
        cub_quat r = ps->rot[j];
        double lq[4] = {r.w / Q30, r.x / Q30, r.y / Q30, r.z / Q30};
        int par = sk->joints[j].parent;
        if (par < 0) {
            memcpy(w[j].q, lq, sizeof lq);
            w[j].p[0] = ps->root_mm.x / Q16, w[j].p[1] = ps->root_mm.y / Q16,
            w[j].p[2] = ps->root_mm.z / Q16;
            continue;
        }
        cub_vec3 o = ps->has_trans ? ps->trans_mm[j] : sk->joints[j].offset_mm;
        double off[3] = {o.x / Q16, o.y / Q16, o.z / Q16}, d[3];
        qrot(w[par].q, off, d);
        for (int k = 0; k < 3; k++)
            w[j].p[k] = w[par].p[k] + d[k];
        qmul(w[par].q, lq, w[j].q);
    }
}

static int below(const cub_skeleton *sk, int k, int j)
{
    while (k > j)
        k = sk->joints[k].parent;
    return k == j;
}

/* Every rotation track's probes: the bones below its joint, per frame, in
 * the joint's own frame (after its rotation), from the source. */
static int build_probes(enc *e)
{
    static cub_pose ps;
    static xf w[CUB_MOTION_MAX_JOINTS];
    const cub_skeleton *sk = e->clip->skel;
    for (int i = 0; i < e->count; i++) {
        src_track *s = &e->src[i];
        if (!s->rotation) continue;
        for (int k = s->joint + 1; k < sk->joint_count; k++)
            s->probes += !sk->joints[k].is_end_site && below(sk, k, s->joint);
        s->probe =
            malloc(sizeof *s->probe * 3 * (size_t)e->n * (size_t)(s->probes ? s->probes : 1));
        if (!s->probe) return -1;
    }
    for (int f = 0; f < e->n; f++) {
        if (cub_motion_clip_get_frame(e->clip, f, &ps)) return -1;
        forward(sk, &ps, w);
        for (int i = 0; i < e->count; i++) {
            src_track *s = &e->src[i];
            if (!s->rotation) continue;
            const xf *o = &w[s->joint];
            double inv[4] = {o->q[0], -o->q[1], -o->q[2], -o->q[3]};
            double *p = s->probe + (size_t)f * s->probes * 3;
            for (int k = s->joint + 1; k < sk->joint_count; k++) {
                if (sk->joints[k].is_end_site || !below(sk, k, s->joint)) continue;
                double d[3] = {w[k].p[0] - o->p[0], w[k].p[1] - o->p[1], w[k].p[2] - o->p[2]};
                qrot(inv, d, p);
                p += 3;
            }
        }
    }
    return 0;
}

/* Squared distance of the farthest of the three virtual vertices. */
static double vertex_err2(const xf *a, const xf *b)
{
    double worst = 0;
    for (int axis = 0; axis < 3; axis++) {
        double v[3] = {0, 0, 0}, va[3], vb[3], d2 = 0;
        v[axis] = CUB_KEYS_SHELL_MM;
        qrot(a->q, v, va);
        qrot(b->q, v, vb);
        for (int k = 0; k < 3; k++) {
            double d = (a->p[k] + va[k]) - (b->p[k] + vb[k]);
            d2 += d * d;
        }
        worst = d2 > worst ? d2 : worst;
    }
    return worst;
}

double cub_keys_max_error(const cub_clip *clip, const void *data, size_t len)
{
    static cub_skeleton skel;
    static cub_keys k;
    static cub_pose src, dec;
    static xf ws[CUB_MOTION_MAX_JOINTS], wd[CUB_MOTION_MAX_JOINTS];
    if (cub_keys_open(data, len, &skel, &k, NULL) || k.frame_count != clip->frame_count)
        return INFINITY;
    double worst = 0;
    for (int f = 0; f < clip->frame_count; f++) {
        if (cub_motion_clip_get_frame(clip, f, &src) || cub_keys_pose(&k, f, &dec)) return INFINITY;
        forward(clip->skel, &src, ws);
        forward(&skel, &dec, wd);
        for (int j = 0; j < skel.joint_count; j++) {
            if (skel.joints[j].is_end_site) continue;
            double e = vertex_err2(&ws[j], &wd[j]);
            worst = e > worst ? e : worst;
        }
    }
    return sqrt(worst);
}

/* ---- the source's tracks ----------------------------------------- */

static int add_src(enc *e, int joint, int rotation)
{
    const cub_clip *clip = e->clip;
    int jn = clip->skel->joint_count, n = e->n;
    src_track *s = &e->src[e->count];
    enc_track *t = &e->trk[e->count];
    s->rotation = rotation, s->joint = joint;
    s->v = malloc(sizeof *s->v * 3 * (size_t)n);
    t->key = malloc((size_t)n);
    t->code = malloc(sizeof *t->code * 3 * (size_t)n);
    if (!s->v || !t->key || !t->code) return -1;
    e->count++;
    cub_vec3 def = joint == 0 ? (cub_vec3){0, 0, 0} : clip->skel->joints[joint].offset_mm;
    s->def[0] = def.x, s->def[1] = def.y, s->def[2] = def.z;
    if (rotation) memset(s->def, 0, sizeof s->def);
    for (int f = 0; f < n; f++) {
        int32_t *v = s->v + 3 * (size_t)f;
        if (rotation) {
            cub_quat q = clip->rot[(size_t)f * jn + joint];
            int flip = q.w < 0;
            v[0] = flip ? -q.x : q.x, v[1] = flip ? -q.y : q.y, v[2] = flip ? -q.z : q.z;
        } else {
            cub_vec3 p = joint == 0 ? clip->root_mm[f] : clip->trans_mm[(size_t)f * jn + joint];
            v[0] = p.x, v[1] = p.y, v[2] = p.z;
        }
    }
    return 0;
}

static int build_sources(enc *e)
{
    const cub_skeleton *sk = e->clip->skel;
    int rc = 0;
    for (int j = 0; j < sk->joint_count && !rc; j++)
        if (!sk->joints[j].is_end_site) rc = add_src(e, j, 1);
    if (!rc) rc = add_src(e, 0, 0);
    for (int j = 1; j < sk->joint_count && e->clip->trans_mm && !rc; j++)
        if (!sk->joints[j].is_end_site) rc = add_src(e, j, 0);
    return rc;
}

static void enc_free(enc *e)
{
    for (int i = 0; i < e->count; i++) {
        free(e->src[i].v);
        free(e->src[i].probe);
        free(e->trk[i].key);
        free(e->trk[i].code);
    }
    free(e->scratch);
    free(e->spare.key);
    free(e->spare.code);
}

/* ---- the search -------------------------------------------------------------- */

/* Track i's tolerance at scale s: a rotation's 1 - cos(theta / 2) for an
 * angle that swings its farthest vertex by s * bound, a translation's
 * squared distance. */
static double tolerance(const enc *e, int i, double s, double bound)
{
    double d = s * e->scale[i] * bound;
    return d * d;
}

/* Encode every track at scale s and measure; the error (mm), or INFINITY. */
static double attempt(enc *e, double s, double bound, writer *w)
{
    for (int i = 0; i < e->count; i++)
        encode_track(e, i, tolerance(e, i, s, bound), &e->trk[i]);
    if (write_stream(e, w)) return INFINITY;
    return cub_keys_max_error(e->clip, w->p, w->len);
}

/* Loosen one track at a time by `factor` while the measured error holds:
 * the equal split is conservative (errors down a chain rarely add up). */
/* The tracks, the costliest first: the slack goes where it saves most. */
static void by_cost(const enc *e, int *order)
{
    for (int i = 0; i < e->count; i++) {
        long c = track_cost(&e->trk[i], e->n);
        int at = i;
        while (at > 0 && track_cost(&e->trk[order[at - 1]], e->n) < c) {
            order[at] = order[at - 1];
            at--;
        }
        order[at] = i;
    }
}

static void refine(enc *e, double s, double bound, double factor, writer *w, double *err)
{
    int order[CUB_KEYS_MAX_TRACKS];
    by_cost(e, order);
    for (int o = 0; o < e->count; o++) {
        int i = order[o];
        if (e->trk[i].kind != CUB_KEYS_ANIMATED) continue;
        e->scale[i] *= factor;
        encode_track(e, i, tolerance(e, i, s, bound), &e->spare);
        if (track_cost(&e->spare, e->n) >= track_cost(&e->trk[i], e->n)) {
            e->scale[i] /= factor;
            continue;
        }
        enc_track old = e->trk[i];
        e->trk[i] = e->spare;
        e->spare = old;
        double m = write_stream(e, w) ? INFINITY : cub_keys_max_error(e->clip, w->p, w->len);
        if (m <= bound) {
            *err = m;
            continue;
        }
        e->scale[i] /= factor; /* back to the one that held */
        e->spare = e->trk[i];
        e->trk[i] = old;
    }
}

static int clip_ok(const cub_clip *clip)
{
    return clip && clip->skel && clip->frame_count >= 1 && clip->frame_count <= (1 << 20) &&
           clip->frame_ns > 0 && clip->skel->joint_count >= 1 && !clip->skel->joints[0].is_end_site;
}

cub_err cub_keys_encode(const cub_clip *clip, double bound_mm, cub_keys_result *out)
{
    if (!out) return CUB_ERR_ARG;
    memset(out, 0, sizeof *out);
    if (!clip_ok(clip) || !(bound_mm > 0)) return CUB_ERR_ARG;
    enc *e = calloc(1, sizeof *e);
    if (!e) return CUB_ERR_NOMEM;
    e->clip = clip, e->n = clip->frame_count;
    e->scratch = malloc(sizeof *e->scratch * 3 * (size_t)e->n);
    writer w = {0}, best = {0};
    for (int i = 0; i < CUB_KEYS_MAX_TRACKS; i++)
        e->scale[i] = 1;
    e->spare.key = malloc((size_t)e->n);
    e->spare.code = malloc(sizeof *e->spare.code * 3 * (size_t)e->n);
    cub_err rc =
        !e->scratch || !e->spare.key || !e->spare.code || build_sources(e) || build_probes(e)
            ? CUB_ERR_NOMEM
            : CUB_OK;
    double lo = 0, hi = INFINITY, s = 1, best_err = INFINITY;
    for (int step = 0; !rc && step < GROW_STEPS + SHRINK_STEPS + BISECT_STEPS; step++) {
        double err = attempt(e, s, bound_mm, &w);
        out->trials++;
        if (w.bad) rc = CUB_ERR_NOMEM;
        if (err <= bound_mm) { /* holds: keep it, try coarser */
            lo = s, best_err = err;
            writer t = best;
            best = w, w = t;
        } else {
            hi = s;
        }
        if (lo > 0 && hi < INFINITY && hi / lo < 1.1) break;
        s = lo == 0 ? s * 0.6 : hi == INFINITY ? s * 1.5 : sqrt(lo * hi);
        if (lo == 0 && s < 1e-6) break;
    }
    if (!rc && best_err <= bound_mm) {
        static const double factors[] = {2.0, 1.41, 1.19, 1.41, 1.19, 1.09};
        attempt(e, lo, bound_mm, &w); /* the tracks as they held */
        for (size_t f = 0; f < sizeof factors / sizeof *factors; f++)
            refine(e, lo, bound_mm, factors[f], &w, &best_err);
        if (write_stream(e, &best)) rc = CUB_ERR_NOMEM;
        best_err = cub_keys_max_error(clip, best.p, best.len);
    }
    free(w.p);
    enc_free(e);
    free(e);
    if (!rc && best_err == INFINITY) rc = CUB_ERR_ARG; /* nothing held: no bound reachable */
    if (rc) {
        free(best.p);
        return rc;
    }
    out->data = best.p, out->len = best.len, out->max_err_mm = best_err;
    return CUB_OK;
}

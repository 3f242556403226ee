/* Keyframe clips written by hand (format in cub/keys.h): parse the lines
 * into key poses of Euler angles, fill in held values, then sample a cubic
 * Hermite curve (Catmull-Rom tangents) per number at every frame. Key times
 * are snapped to frames, so the curves run in whole frames and every key's
 * frame gets exactly that key's pose. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/keys.h"
#include "io_internal.h"

#define KEYS_MAX_DEG 10000.0
#define KEYS_MAX_ROOT_MM 10000.0
#define KEYS_CHANNELS(joints) (3 * (joints) + 3) /* Euler x y z per joint, then root */

typedef struct keys_parse {
    io_lex lx;
    const cub_skeleton *skel;
    cub_keys_clip *out;
    int have_clip, clip_line, have_loop, loop_line;
    double fps, loop_s;
    double key_s[CUB_KEYS_MAX_KEYS];
    double *value;        /* [key][channel] */
    unsigned char *given; /* [key][joint + 1]: written in this key (last slot: root) */
    int channels;
} keys_parse;

static double *key_values(keys_parse *p, int k)
{
    return p->value + (size_t)k * (size_t)p->channels;
}

static unsigned char *key_given(keys_parse *p, int k)
{
    return p->given + (size_t)k * (size_t)(p->skel->joint_count + 1);
}

/* "kind=dance" -> value "dance" if tok starts with key "kind=". */
static int tok_option(const io_tok *t, const char *key, io_tok *value)
{
    size_t n = strlen(key);
    if (t->n <= n || memcmp(t->s, key, n) != 0) return 0;
    *value = *t;
    value->s += n;
    value->n -= n;
    return 1;
}

static cub_err read_clip_line(keys_parse *p, const io_tok *kw)
{
    io_tok t, v;
    char shown[40];
    if (p->have_clip) return io_fail(&p->lx, kw->line, "a second clip line (one clip per file)");
    if (!io_lex_next_same_line(&p->lx, &t) || strchr("=#", t.s[0]) || memchr(t.s, '=', t.n))
        return io_fail(&p->lx, kw->line, "clip needs a name: clip NAME [kind=KIND] [fps=N]");
    if (!io_tok_copy(&t, p->out->name, sizeof(p->out->name)))
        return io_fail(&p->lx, t.line, "clip name %s is longer than %d",
                       io_tok_show(&t, shown, sizeof(shown)), CUB_MOTION_NAME_LEN - 1);
    while (io_lex_next_same_line(&p->lx, &t)) {
        long fps = 0;
        if (tok_option(&t, "kind=", &v)) {
            if (!io_tok_copy(&v, p->out->kind, sizeof(p->out->kind)))
                return io_fail(&p->lx, t.line, "kind %s is longer than %d",
                               io_tok_show(&v, shown, sizeof(shown)), CUB_KEYS_KIND_LEN - 1);
        } else if (tok_option(&t, "fps=", &v)) {
            cub_err err = io_tok_long(&p->lx, &v, "fps", &fps);
            if (err) return err;
            if (fps < 1 || fps > 240)
                return io_fail(&p->lx, t.line, "fps %ld is not in 1..240", fps);
            p->fps = (double)fps;
        } else {
            return io_fail(&p->lx, t.line, "unknown clip option %s (kind=, fps=)",
                           io_tok_show(&t, shown, sizeof(shown)));
        }
    }
    p->have_clip = 1;
    p->clip_line = kw->line;
    return CUB_OK;
}

static cub_err read_root(keys_parse *p, const io_tok *t, const io_tok *v, int k)
{
    double *root = key_values(p, k) + 3 * p->skel->joint_count;
    const char *s = v->s, *end = v->s + v->n;
    unsigned char *given = key_given(p, k);
    if (given[p->skel->joint_count])
        return io_fail(&p->lx, t->line, "root= given twice in one key");
    for (int i = 0; i < 3; i++) {
        const char *c = s;
        while (c < end && *c != ',')
            c++;
        io_tok part = {s, (size_t)(c - s), t->line, 0};
        if ((i < 2) != (c < end) || !io_parse_double(&part, &root[i]) ||
            fabs(root[i]) > KEYS_MAX_ROOT_MM) {
            char shown[40];
            return io_fail(&p->lx, t->line, "bad root %s (want root=X,Y,Z in mm, within %g)",
                           io_tok_show(t, shown, sizeof(shown)), KEYS_MAX_ROOT_MM);
        }
        s = c + 1;
    }
    given[p->skel->joint_count] = 1;
    return CUB_OK;
}

/* One "JOINT [x=DEG] [y=DEG] [z=DEG]" entry; *t is the joint name and on
 * return holds the token after the entry (*more = 0 at the line's end). */
static cub_err read_joint(keys_parse *p, io_tok *t, int k, int *more)
{
    char name[CUB_MOTION_NAME_LEN], shown[40];
    int j = io_tok_copy(t, name, sizeof(name)) ? cub_motion_skeleton_find(p->skel, name) : -1;
    if (j < 0)
        return io_fail(&p->lx, t->line, "unknown joint %s", io_tok_show(t, shown, sizeof(shown)));
    if (p->skel->joints[j].is_end_site)
        return io_fail(&p->lx, t->line, "joint '%s' is an end site; rotating it moves nothing",
                       name);
    unsigned char *given = key_given(p, k);
    if (given[j]) return io_fail(&p->lx, t->line, "joint '%s' appears twice in this key", name);
    given[j] = 1;
    double *v = key_values(p, k) + 3 * j;
    int seen[3] = {0, 0, 0};
    v[0] = v[1] = v[2] = 0;
    while ((*more = io_lex_next_same_line(&p->lx, t)) && t->n >= 2 && t->s[1] == '=') {
        int axis = t->s[0] - 'x';
        if (axis < 0 || axis > 2)
            return io_fail(&p->lx, t->line, "unknown axis in %s (x, y or z)",
                           io_tok_show(t, shown, sizeof(shown)));
        if (seen[axis]) return io_fail(&p->lx, t->line, "%s: axis %c given twice", name, t->s[0]);
        seen[axis] = 1;
        io_tok num = {t->s + 2, t->n - 2, t->line, 0};
        char what[64];
        snprintf(what, sizeof(what), "%s %c (degrees)", name, t->s[0]);
        cub_err err = io_tok_double(&p->lx, &num, what, &v[axis]);
        if (err) return err;
        if (fabs(v[axis]) > KEYS_MAX_DEG)
            return io_fail(&p->lx, t->line, "%s: %g degrees is beyond +-%g", what, v[axis],
                           KEYS_MAX_DEG);
    }
    return CUB_OK;
}

/* The rest of a line of joint entries (and root=) for key k. */
static cub_err read_entries(keys_parse *p, io_tok *t, int more, int k)
{
    cub_err err = CUB_OK;
    io_tok v;
    while (!err && more) {
        if (tok_option(t, "root=", &v)) {
            err = read_root(p, t, &v, k);
            more = io_lex_next_same_line(&p->lx, t);
        } else if (memchr(t->s, '=', t->n)) {
            char shown[40];
            return io_fail(&p->lx, t->line, "%s does not follow a joint name",
                           io_tok_show(t, shown, sizeof(shown)));
        } else {
            err = read_joint(p, t, k, &more);
        }
    }
    return err;
}

static cub_err read_key_line(keys_parse *p, const io_tok *kw)
{
    cub_keys_clip *out = p->out;
    io_tok t;
    double s = 0;
    if (out->key_count >= CUB_KEYS_MAX_KEYS)
        return io_fail(&p->lx, kw->line, "more than %d keys", CUB_KEYS_MAX_KEYS);
    if (!io_lex_next_same_line(&p->lx, &t))
        return io_fail(&p->lx, kw->line, "key needs a time in seconds: key T ...");
    cub_err err = io_tok_double(&p->lx, &t, "the key time (seconds)", &s);
    if (err) return err;
    int k = out->key_count;
    if (k == 0 && s != 0)
        return io_fail(&p->lx, t.line, "the first key must be at time 0, not %g", s);
    if (k > 0 && !(s > p->key_s[k - 1]))
        return io_fail(&p->lx, t.line, "key time %g is not after the previous key's %g (line %d)",
                       s, p->key_s[k - 1], out->key_line[k - 1]);
    if (s > CUB_KEYS_MAX_SECONDS)
        return io_fail(&p->lx, t.line, "key time %g is past %d s", s, CUB_KEYS_MAX_SECONDS);
    int frame = (int)lround(s * p->fps);
    if (k > 0 && frame == out->key_frame[k - 1])
        return io_fail(&p->lx, t.line,
                       "key at %g s falls on the same frame as the key at %g s "
                       "(line %d) at %g fps",
                       s, p->key_s[k - 1], out->key_line[k - 1], p->fps);
    p->key_s[k] = s;
    out->key_frame[k] = frame;
    out->key_line[k] = t.line;
    out->key_count++;
    int more = io_lex_next_same_line(&p->lx, &t);
    return read_entries(p, &t, more, k);
}

static cub_err read_loop_line(keys_parse *p, const io_tok *kw)
{
    io_tok t;
    p->have_loop = 1;
    p->loop_line = kw->line;
    p->loop_s = 0;
    if (io_lex_next_same_line(&p->lx, &t)) {
        cub_err err = io_tok_double(&p->lx, &t, "the loop time (seconds)", &p->loop_s);
        if (err) return err;
        /* Checked here: a time <= 0 would read as a bare loop, a huge one
         * overflows the period in frames. */
        if (!(p->loop_s > 0 && p->loop_s <= CUB_KEYS_MAX_SECONDS)) {
            char shown[40];
            return io_fail(&p->lx, t.line,
                           "the loop time %s must be a number of seconds above 0 and at most %g",
                           io_tok_show(&t, shown, sizeof(shown)), (double)CUB_KEYS_MAX_SECONDS);
        }
        if (io_lex_next_same_line(&p->lx, &t))
            return io_fail(&p->lx, t.line, "loop takes at most one time");
    }
    return CUB_OK;
}

static cub_err read_lines(keys_parse *p)
{
    io_tok t;
    char shown[40];
    while (io_lex_next(&p->lx, &t)) {
        cub_err err;
        if (p->have_loop)
            return io_fail(&p->lx, t.line, "nothing may follow loop (line %d)", p->loop_line);
        if (!p->have_clip && !io_tok_is(&t, "clip"))
            return io_fail(&p->lx, t.line, "expected 'clip NAME ...' first, got %s",
                           io_tok_show(&t, shown, sizeof(shown)));
        if (io_tok_is(&t, "clip"))
            err = read_clip_line(p, &t);
        else if (io_tok_is(&t, "key"))
            err = read_key_line(p, &t);
        else if (io_tok_is(&t, "loop"))
            err = read_loop_line(p, &t);
        else if (p->out->key_count == 0)
            err = io_fail(&p->lx, t.line, "expected clip, key or loop, got %s",
                          io_tok_show(&t, shown, sizeof(shown)));
        else
            err = read_entries(p, &t, 1, p->out->key_count - 1);
        if (err) return err;
    }
    if (!p->have_clip)
        return io_fail(&p->lx, p->lx.line, "no clip line (clip NAME kind=... fps=...)");
    if (p->out->key_count == 0) return io_fail(&p->lx, p->clip_line, "no keys");
    return CUB_OK;
}

/* ---- from keys to frames ------------------------------------------------- */

/* Values a key does not write are held from the key before it. */
static void fill_held(keys_parse *p)
{
    int jn = p->skel->joint_count;
    for (int k = 1; k < p->out->key_count; k++) {
        double *v = key_values(p, k), *prev = key_values(p, k - 1);
        unsigned char *given = key_given(p, k);
        for (int j = 0; j <= jn; j++)
            if (!given[j]) memcpy(v + 3 * j, prev + 3 * j, 3 * sizeof(double));
    }
}

/* The number of frames, and for a loop its period in frames. */
static cub_err frame_count(keys_parse *p, int *frames)
{
    cub_keys_clip *out = p->out;
    int last = out->key_frame[out->key_count - 1];
    if (!p->have_loop) {
        *frames = last + 1;
        return CUB_OK;
    }
    if (p->loop_s == 0 && out->key_count < 2)
        return io_fail(&p->lx, p->loop_line, "a bare 'loop' needs two keys; write loop T");
    int period = p->loop_s > 0 ? (int)lround(p->loop_s * p->fps)
                               : last + out->key_frame[1] - out->key_frame[0];
    if (period <= last || p->loop_s > CUB_KEYS_MAX_SECONDS)
        return io_fail(&p->lx, p->loop_line,
                       "the loop time %g s must come after the last key "
                       "(%g s) by at least a frame",
                       (double)period / p->fps, p->key_s[out->key_count - 1]);
    *frames = period;
    return CUB_OK;
}

/* Key i of the (for a loop, periodically extended) key sequence: its frame
 * and values; i may run from -1 to key_count. */
static const double *key_at(keys_parse *p, int i, int period, double *frame)
{
    int n = p->out->key_count, wrap = 0;
    if (p->have_loop) {
        wrap = (i < 0 ? i - (n - 1) : i) / n; /* floor(i / n) */
        i -= wrap * n;
    } else {
        i = i < 0 ? 0 : i >= n ? n - 1 : i;
    }
    *frame = p->out->key_frame[i] + (double)wrap * period;
    return key_values(p, i);
}

/* Hermite curve through keys i and i+1 at frame f, every channel. */
static void sample_segment(keys_parse *p, int i, int period, double f, double *v)
{
    double f0, f1, fa, fb;
    const double *p0 = key_at(p, i, period, &f0), *p1 = key_at(p, i + 1, period, &f1);
    const double *pa = key_at(p, i - 1, period, &fa), *pb = key_at(p, i + 2, period, &fb);
    int n = p->out->key_count;
    /* Ends of a clip that does not loop ease in and out (zero tangent). */
    int ease_in = !p->have_loop && i == 0, ease_out = !p->have_loop && i + 1 >= n - 1;
    double h = f1 - f0, s = h > 0 ? (f - f0) / h : 0;
    double s2 = s * s, s3 = s2 * s;
    double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
    for (int c = 0; c < p->channels; c++) {
        double m0 = ease_in ? 0 : (p1[c] - pa[c]) / (f1 - fa);
        double m1 = ease_out ? 0 : (pb[c] - p0[c]) / (fb - f0);
        v[c] = s == 0 ? p0[c] : h00 * p0[c] + h10 * h * m0 + h01 * p1[c] + h11 * h * m1;
    }
}

static void set_frame(keys_parse *p, int f, const double *v)
{
    const cub_skeleton *skel = p->skel;
    int jn = skel->joint_count;
    cub_clip *clip = &p->out->clip;
    const int axes[3] = {2, 1, 0}; /* q = Rz * Ry * Rx: x acts first */
    for (int j = 0; j < jn; j++) {
        const double deg = CUB_VEC_PI / 180.0;
        double a[3] = {v[3 * j + 2] * deg, v[3 * j + 1] * deg, v[3 * j] * deg};
        clip->rot[(size_t)f * (size_t)jn + (size_t)j] = io_quat_to_fx(cub_dq_euler(axes, a, 3));
    }
    const double *r = v + 3 * jn;
    cub_vec3 rest = skel->joints[0].offset_mm;
    clip->root_mm[f] = (cub_vec3){rest.x + io_mm_to_q16(r[0]), rest.y + io_mm_to_q16(r[1]),
                                  rest.z + io_mm_to_q16(r[2])};
}

static cub_err make_frames(keys_parse *p)
{
    cub_keys_clip *out = p->out;
    int frames = 0, jn = p->skel->joint_count;
    cub_err err = frame_count(p, &frames);
    if (err) return err;
    size_t size = cub_motion_clip_mem_size(jn, frames, 0);
    double *v = malloc(sizeof(double) * (size_t)p->channels);
    out->mem = malloc(size);
    if (!v || !out->mem) {
        free(v);
        return cub_diag_fail(p->lx.diag, CUB_ERR_NOMEM, p->lx.name, 0, "out of memory");
    }
    uint32_t frame_ns = (uint32_t)lround(1e9 / p->fps);
    err = cub_motion_clip_init(&out->clip, p->skel, frames, frame_ns, 0, out->mem, size);
    for (int f = 0, i = 0; !err && f < frames; f++) {
        while (i + 1 < out->key_count && out->key_frame[i + 1] <= f)
            i++;
        sample_segment(p, i, frames, (double)f, v);
        set_frame(p, f, v);
    }
    free(v);
    if (err) return cub_diag_fail(p->lx.diag, err, p->lx.name, 0, "cannot lay out %d frames", frames);
    return CUB_OK;
}

cub_err cub_keys_parse(const char *text, size_t len, const char *name, const cub_skeleton *skel,
                       cub_keys_clip *out, cub_diag *diag)
{
    const char *file = name ? name : "(memory)";
    if (!out || !skel || (!text && len) || skel->joint_count < 1 ||
        skel->joint_count > CUB_MOTION_MAX_JOINTS)
        return cub_diag_fail(diag, CUB_ERR_ARG, file, 0, "no text, skeleton or output");
    memset(out, 0, sizeof(*out));
    keys_parse *p = calloc(1, sizeof(*p));
    if (!p) return cub_diag_fail(diag, CUB_ERR_NOMEM, file, 0, "out of memory");
    io_lex_init(&p->lx, text ? text : "", len, file, diag);
    p->lx.hash_comments = 1;
    p->skel = skel;
    p->out = out;
    p->fps = 30;
    p->channels = KEYS_CHANNELS(skel->joint_count);
    snprintf(out->kind, sizeof(out->kind), "coach");
    p->value = calloc((size_t)CUB_KEYS_MAX_KEYS * (size_t)p->channels, sizeof(double));
    p->given = calloc((size_t)CUB_KEYS_MAX_KEYS * (size_t)(skel->joint_count + 1), 1);
    cub_err err = (!p->value || !p->given)
                      ? cub_diag_fail(diag, CUB_ERR_NOMEM, file, 0, "out of memory")
                      : read_lines(p);
    if (!err) {
        fill_held(p);
        out->loop = p->have_loop;
        out->fps = (int)p->fps;
        err = make_frames(p);
    }
    free(p->value);
    free(p->given);
    free(p);
    if (err) cub_keys_free(out);
    return err;
}

static cub_err parse_text(const cub_text *t, const void *skel, void *out)
{
    return cub_keys_parse(t->s, t->len, t->name, skel, out, t->diag);
}

cub_err cub_keys_load(const char *path, const cub_skeleton *skel, cub_keys_clip *out,
                      cub_diag *diag)
{
    return cub_text_load(&(cub_text_src){path, "keyframe file", CUB_TEXT_MAX_SMALL}, parse_text, skel, out, diag);
}

void cub_keys_free(cub_keys_clip *k)
{
    if (!k) return;
    free(k->mem);
    memset(k, 0, sizeof(*k));
}

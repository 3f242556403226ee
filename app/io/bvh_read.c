/* BVH import: HIERARCHY (ROOT / JOINT / End Site, OFFSET, CHANNELS) then
 * MOTION (Frames:, Frame Time:, one line of values per frame).
 *
 * Conventions, as the files in the wild use them:
 * - rotation channels are degrees, applied in the order listed: for
 *   "Zrotation Xrotation Yrotation" the local rotation is Rz * Rx * Ry;
 * - position channels replace the joint's OFFSET (Bandai animates every
 *   joint's translation, Rokoko's root OFFSET is not added to its motion);
 * - End Sites become joints named "<parent>_end" with is_end_site = 1;
 * - CR, tabs, ".0333" and "2.9e-15" are all fine. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io_internal.h"

#define MAXJ CUB_MOTION_MAX_JOINTS

typedef struct bvh_joint {
    char name[CUB_MOTION_NAME_LEN];
    int parent;
    int end_site;
    int has_offset;
    int has_channels;
    int line;         /* where the joint starts, for messages */
    double off[3];    /* file units */
    char seq[6];      /* channels as listed: 'x'..'z' positions, 'X'..'Z' rotations */
    int nseq;
} bvh_joint;

typedef struct bvh_state {
    io_lex lx;
    bvh_joint j[MAXJ];
    int count;
    int total_channels;
} bvh_state;

static cub_err parse_channels(bvh_state *st, bvh_joint *jt)
{
    io_lex *lx = &st->lx;
    io_tok t;
    long n;
    char shown[40];
    if (jt->has_channels)
        return io_fail(lx, lx->line, "second CHANNELS in joint '%s'", jt->name);
    jt->has_channels = 1;
    if (!io_lex_next(lx, &t))
        return io_fail(lx, lx->line, "file ends after CHANNELS");
    cub_err err = io_tok_long(lx, &t, "the CHANNELS count", &n);
    if (err)
        return err;
    if (n < 0 || n > 6)
        return io_fail(lx, t.line, "CHANNELS count %ld is not 0..6", n);
    for (int i = 0; i < n; i++) {
        if (!io_lex_next(lx, &t))
            return io_fail(lx, lx->line, "file ends in the CHANNELS list");
        int axis = -1;
        char c = t.n > 0 ? t.s[0] : 0;
        if (c == 'X' || c == 'x')
            axis = 0;
        else if (c == 'Y' || c == 'y')
            axis = 1;
        else if (c == 'Z' || c == 'z')
            axis = 2;
        io_tok rest = {t.s + 1, t.n > 0 ? t.n - 1 : 0, t.line, 0};
        char code = 0;
        if (axis >= 0 && io_tok_is_nocase(&rest, "position"))
            code = (char)('x' + axis);
        else if (axis >= 0 && io_tok_is_nocase(&rest, "rotation"))
            code = (char)('X' + axis);
        if (!code)
            return io_fail(lx, t.line, "unknown channel %s", io_tok_show(&t, shown, sizeof(shown)));
        if (memchr(jt->seq, code, (size_t)jt->nseq))
            return io_fail(lx, t.line, "channel %s listed twice", io_tok_show(&t, shown, sizeof(shown)));
        jt->seq[jt->nseq++] = code;
    }
    st->total_channels += (int)n;
    return CUB_OK;
}

static cub_err parse_offset(bvh_state *st, bvh_joint *jt)
{
    io_lex *lx = &st->lx;
    io_tok t;
    if (jt->has_offset)
        return io_fail(lx, lx->line, "second OFFSET in joint '%s'", jt->name);
    jt->has_offset = 1;
    for (int k = 0; k < 3; k++) {
        if (!io_lex_next(lx, &t))
            return io_fail(lx, lx->line, "file ends in OFFSET");
        cub_err err = io_tok_double(lx, &t, "OFFSET", &jt->off[k]);
        if (err)
            return err;
    }
    return CUB_OK;
}

/* One ROOT / JOINT / End Site block, its keyword already read. */
static cub_err parse_node(bvh_state *st, int parent, int end_site, const char *kind, int line)
{
    io_lex *lx = &st->lx;
    io_tok t;
    char shown[40];
    if (st->count >= MAXJ)
        return io_fail(lx, line, "more than %d joints", MAXJ);
    bvh_joint *jt = &st->j[st->count++];
    int self = (int)(jt - st->j);
    jt->parent = parent;
    jt->end_site = end_site;
    jt->line = line;
    if (!io_lex_next(lx, &t))
        return io_fail(lx, lx->line, "file ends after %s", kind);
    if (end_site) {
        if (!io_tok_is(&t, "Site"))
            return io_fail(lx, t.line, "expected 'Site' after 'End', got %s",
                           io_tok_show(&t, shown, sizeof(shown)));
        char pname[CUB_MOTION_NAME_LEN];
        memcpy(pname, st->j[parent].name, sizeof(pname));
        snprintf(jt->name, sizeof(jt->name), "%.27s_end", pname);
    } else if (io_tok_is(&t, "{") || io_tok_is(&t, "}")) {
        return io_fail(lx, t.line, "expected a name after %s", kind);
    } else if (!io_tok_copy(&t, jt->name, sizeof(jt->name))) {
        return io_fail(lx, t.line, "joint name %s is longer than %d characters",
                       io_tok_show(&t, shown, sizeof(shown)), CUB_MOTION_NAME_LEN - 1);
    }
    int got = io_lex_next(lx, &t);
    if (!got || !io_tok_is(&t, "{"))
        return io_fail(lx, got ? t.line : lx->line, "expected '{' after %s%s", kind,
                       end_site ? "" : " name");
    for (;;) {
        cub_err err = CUB_OK;
        if (!io_lex_next(lx, &t))
            return io_fail(lx, lx->line, "file ends inside joint '%s' (missing '}')", jt->name);
        if (io_tok_is(&t, "}"))
            break;
        if (io_tok_is(&t, "OFFSET")) {
            err = parse_offset(st, jt);
        } else if (io_tok_is(&t, "CHANNELS")) {
            if (end_site)
                return io_fail(lx, t.line, "End Site cannot have CHANNELS");
            err = parse_channels(st, jt);
        } else if (io_tok_is(&t, "JOINT") || io_tok_is(&t, "End")) {
            if (end_site)
                return io_fail(lx, t.line, "End Site cannot have children");
            int is_end = io_tok_is(&t, "End");
            err = parse_node(st, self, is_end, is_end ? "End Site" : "JOINT", t.line);
        } else {
            return io_fail(lx, t.line, "unexpected %s in joint '%s'%s",
                           io_tok_show(&t, shown, sizeof(shown)), jt->name,
                           io_tok_is(&t, "MOTION") ? " (missing '}')" : "");
        }
        if (err)
            return err;
    }
    if (!jt->has_offset)
        return io_fail(lx, line, "joint '%s' has no OFFSET", jt->name);
    return CUB_OK;
}

static cub_err expect_word(io_lex *lx, const char *word, const char *context, io_tok *t)
{
    char shown[40];
    if (!io_lex_next(lx, t))
        return io_fail(lx, lx->line, "file ends: expected '%s' %s", word, context);
    if (!io_tok_is(t, word))
        return io_fail(lx, t->line, "expected '%s' %s, got %s", word, context,
                       io_tok_show(t, shown, sizeof(shown)));
    return CUB_OK;
}

/* Largest extent of the rest pose (offsets only), in file units. */
static double rest_size(const bvh_state *st)
{
    double pos[MAXJ][3], lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, size = 0;
    for (int i = 0; i < st->count; i++) {
        for (int k = 0; k < 3; k++) {
            pos[i][k] = i == 0 ? 0 : pos[st->j[i].parent][k] + st->j[i].off[k];
            lo[k] = fmin(lo[k], pos[i][k]);
            hi[k] = fmax(hi[k], pos[i][k]);
        }
    }
    for (int k = 0; k < 3; k++)
        size = fmax(size, hi[k] - lo[k]);
    return size;
}

static cub_err to_mm(io_lex *lx, int line, double v, double unit_mm, const char *what,
                     int32_t *out)
{
    double mm = v * unit_mm;
    if (!(fabs(mm) <= IO_MM_LIMIT))
        return io_fail(lx, line, "%s %g is %.0f mm, beyond the +-32 m of Q16.16", what, v, mm);
    *out = io_mm_to_q16(mm);
    return CUB_OK;
}

static cub_err build_skeleton(bvh_state *st, cub_io_motion *m)
{
    io_lex *lx = &st->lx;
    cub_motion_skeleton_reset(&m->skel);
    for (int i = 0; i < st->count; i++) {
        const bvh_joint *jt = &st->j[i];
        cub_vec3 off;
        cub_err err = to_mm(lx, jt->line, jt->off[0], m->unit_mm, "OFFSET x", &off.x);
        if (!err)
            err = to_mm(lx, jt->line, jt->off[1], m->unit_mm, "OFFSET y", &off.y);
        if (!err)
            err = to_mm(lx, jt->line, jt->off[2], m->unit_mm, "OFFSET z", &off.z);
        if (err)
            return err;
        int idx = -1;
        if (cub_motion_skeleton_find(&m->skel, jt->name) >= 0)
            return io_fail(lx, jt->line, "joint name '%s' is used twice", jt->name);
        err = cub_motion_skeleton_add(&m->skel, jt->name, jt->parent, off, &idx);
        if (err || idx != i)
            return io_fail(lx, jt->line, "joint '%s' refused by the skeleton: %s", jt->name,
                           cub_err_str(err ? err : CUB_ERR_ARG));
        m->skel.joints[i].is_end_site = (uint8_t)jt->end_site;
        cub_io_channels *ch = &m->channels[i];
        memset(ch, 0, sizeof(*ch));
        ch->count = (unsigned char)jt->nseq;
        for (int c = 0, r = 0, p = 0; c < jt->nseq; c++) {
            char code = jt->seq[c];
            if (code >= 'X' && code <= 'Z')
                ch->rot_order[r++] = code;
            else
                ch->pos_order[p++] = (char)(code - 'x' + 'X');
            ch->has_pos = p > 0;
        }
    }
    return CUB_OK;
}

/* Store one frame's values (file units, degrees) into the clip. */
static cub_err store_frame(bvh_state *st, cub_io_motion *m, int f, const double *v, int line)
{
    io_lex *lx = &st->lx;
    cub_clip *clip = &m->clip;
    int jn = m->skel.joint_count;
    for (int i = 0; i < jn; i++) {
        const bvh_joint *jt = &st->j[i];
        cub_vec3 pos = m->skel.joints[i].offset_mm;
        int32_t *pos_k[3] = {&pos.x, &pos.y, &pos.z};
        int axes[3];
        double ang[3];
        int nrot = 0;
        for (int c = 0; c < jt->nseq; c++, v++) {
            char code = jt->seq[c];
            if (code >= 'X' && code <= 'Z') {
                axes[nrot] = code - 'X';
                ang[nrot++] = *v * (CUB_VEC_PI / 180.0);
                continue;
            }
            double mm = *v * m->unit_mm;
            if (!(fabs(mm) <= IO_MM_LIMIT))
                return io_fail(lx, line, "frame %d: %s %cposition %g is %.0f mm, beyond the +-32 m of Q16.16",
                               f + 1, jt->name, code - 'x' + 'X', *v, mm);
            *pos_k[code - 'x'] = io_mm_to_q16(mm);
        }
        clip->rot[(size_t)f * jn + i] = io_quat_to_fx(cub_dq_euler(axes, ang, nrot));
        if (i == 0)
            clip->root_mm[f] = pos;
        if (clip->trans_mm)
            clip->trans_mm[(size_t)f * jn + i] = pos;
    }
    return CUB_OK;
}

static cub_err parse_frames(bvh_state *st, cub_io_motion *m, long frames)
{
    io_lex *lx = &st->lx;
    io_tok t;
    char shown[40], what[64];
    int n_ch = st->total_channels;
    double *vals = malloc(sizeof(double) * (size_t)n_ch);
    if (!vals)
        return cub_diag_fail(lx->diag, CUB_ERR_NOMEM, lx->name, 0, "out of memory");
    cub_err err = CUB_OK;
    for (long f = 0; f < frames && !err; f++) {
        if (!io_lex_next(lx, &t)) {
            err = io_fail(lx, lx->line, "file ends after %ld frames, Frames: says %ld", f, frames);
            break;
        }
        if (!t.first_on_line) {
            err = io_fail(lx, t.line, "expected frame data on a new line, got %s",
                          io_tok_show(&t, shown, sizeof(shown)));
            break;
        }
        int line = t.line, count = 0;
        do {
            if (count < n_ch && !io_parse_double(&t, &vals[count])) {
                snprintf(what, sizeof(what), "frame %ld value %d", f + 1, count + 1);
                err = io_tok_double(lx, &t, what, &vals[count]);
            }
            count++;
        } while (!err && io_lex_next_same_line(lx, &t));
        if (!err && count != n_ch)
            err = io_fail(lx, line, "frame %ld has %d values, expected %d", f + 1, count, n_ch);
        if (!err)
            err = store_frame(st, m, (int)f, vals, line);
    }
    free(vals);
    if (!err && io_lex_next(lx, &t))
        err = io_fail(lx, t.line, "more frame data than Frames: %ld", frames);
    return err;
}

static cub_err parse_motion_header(bvh_state *st, long *frames, uint32_t *frame_ns, int *line)
{
    io_lex *lx = &st->lx;
    io_tok t;
    double sec;
    cub_err err = expect_word(lx, "Frames:", "after MOTION", &t);
    if (err)
        return err;
    if (!io_lex_next(lx, &t))
        return io_fail(lx, lx->line, "file ends after 'Frames:'");
    *line = t.line;
    if ((err = io_tok_long(lx, &t, "Frames:", frames)))
        return err;
    if (*frames < 0)
        return io_fail(lx, t.line, "Frames: count is negative");
    if (*frames == 0)
        return io_fail(lx, t.line, "Frames: count is zero");
    if (*frames > INT32_MAX / 2)
        return io_fail(lx, t.line, "Frames: count %ld is too large", *frames);
    if ((err = expect_word(lx, "Frame", "after the frame count", &t)) ||
        (err = expect_word(lx, "Time:", "after 'Frame'", &t)))
        return err;
    if (!io_lex_next(lx, &t))
        return io_fail(lx, lx->line, "file ends after 'Frame Time:'");
    if ((err = io_tok_double(lx, &t, "Frame Time", &sec)))
        return err;
    double ns = floor(sec * 1e9 + 0.5);
    if (!(ns >= 1.0 && ns <= (double)UINT32_MAX))
        return io_fail(lx, t.line, "Frame Time %g s is not in (0, 4.29] s", sec);
    *frame_ns = (uint32_t)ns;
    return CUB_OK;
}

static cub_err parse_bvh(bvh_state *st, const cub_io_desc *desc, cub_io_motion *m)
{
    io_lex *lx = &st->lx;
    io_tok t;
    char shown[40];
    long frames = 0;
    uint32_t frame_ns = 0;
    int frames_line = 0;
    if (!io_lex_peek(lx, &t))
        return io_fail(lx, 1, "empty file");
    cub_err err = expect_word(lx, "HIERARCHY", "at the start", &t);
    if (!err)
        err = expect_word(lx, "ROOT", "after HIERARCHY", &t);
    if (!err)
        err = parse_node(st, -1, 0, "ROOT", t.line);
    if (err)
        return err;
    if (!io_lex_next(lx, &t))
        return io_fail(lx, lx->line, "file ends: expected 'MOTION' after the hierarchy");
    if (io_tok_is(&t, "ROOT"))
        return io_fail(lx, t.line, "a second ROOT is not supported");
    if (!io_tok_is(&t, "MOTION"))
        return io_fail(lx, t.line, "expected 'MOTION' after the hierarchy, got %s",
                       io_tok_show(&t, shown, sizeof(shown)));
    if ((err = parse_motion_header(st, &frames, &frame_ns, &frames_line)))
        return err;
    if (st->total_channels == 0)
        return io_fail(lx, frames_line, "no joint has CHANNELS: nothing to animate");
    /* Every value takes at least a digit and a separator. */
    if ((double)frames * st->total_channels * 2.0 > (double)io_lex_left(lx) + 2.0)
        return io_fail(lx, frames_line, "Frames: %ld frames of %d values cannot fit in the %zu bytes that follow",
                       frames, st->total_channels, io_lex_left(lx));
    m->unit_mm = (desc && desc->unit_mm > 0) ? desc->unit_mm : cub_io_guess_unit_mm(rest_size(st));
    if (!isfinite(m->unit_mm))
        return cub_diag_fail(lx->diag, CUB_ERR_ARG, lx->name, 0, "unit_mm is not finite");
    if ((err = build_skeleton(st, m)))
        return err;
    int with_trans = 0;
    for (int i = 1; i < st->count; i++)
        with_trans |= m->channels[i].has_pos;
    err = io_clip_alloc(m, (int)frames, frame_ns, with_trans, lx->name, frames_line, lx->diag);
    if (!err)
        err = parse_frames(st, m, frames);
    return err;
}

static cub_err parse_text(const cub_text *t, const void *desc, void *out)
{
    cub_io_motion *m = out;
    memset(m, 0, sizeof(*m));
    bvh_state *st = calloc(1, sizeof(*st));
    if (!st)
        return cub_diag_fail(t->diag, CUB_ERR_NOMEM, t->name, 0, "out of memory");
    io_lex_init(&st->lx, t->s ? t->s : "", t->len, t->name, t->diag);
    st->lx.split_braces = 1;
    cub_err err = parse_bvh(st, desc, m);
    free(st);
    if (err) {
        cub_io_motion_free(m);
        memset(m, 0, sizeof(*m));
    }
    return err;
}

cub_err cub_io_parse_bvh(const char *text, size_t len, const char *name, const cub_io_desc *desc,
                         cub_io_motion *out, cub_diag *diag)
{
    cub_diag scratch;
    if (!diag)
        diag = &scratch;
    memset(diag, 0, sizeof(*diag));
    cub_text t = {text, len, name ? name : "(memory)", diag};
    return cub_text_parse(&t, parse_text, desc, out);
}

cub_err cub_io_load_bvh(const char *path, const cub_io_desc *desc, cub_io_motion *out,
                        cub_diag *diag)
{
    return cub_text_load(&(cub_text_src){path, "BVH file", CUB_TEXT_MAX_MOCAP}, parse_text, desc, out, diag);
}

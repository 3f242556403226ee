/* truth.txt reader (format in cub/synth.h). Strict: every problem is
 * reported with the file and line; the reader never reads past its input. */
#include <stdlib.h>
#include <string.h>

#include "synth_internal.h"

#define TRUTH_MAGIC "# cub-synth truth v1"
#define TRUTH_FIELDS (3 + 4 * CUB_KJ_COUNT)
#define TRUTH_MAX_FRAMES 1000000
#define COORD_LIMIT_MM 1e6

static cub_err parse_frame(const synth_fields *f, const char *name, int line,
                           cub_synth_truth_frame *t, cub_diag *diag)
{
    double v;
    if (f->n != TRUTH_FIELDS || f->too_many)
        return synth_fail(diag, name, line,
                          "expected %d fields (frame t_s ts, 20 x 'x y z v'), got %d%s",
                          TRUTH_FIELDS, f->n, f->too_many ? " or more" : "");
    if (!synth_parse_num(f->f[0], 1e9, &v) || v != (int)v || v < 0)
        return synth_fail(diag, name, line, "bad frame number '%.40s'", f->f[0]);
    t->frame = (int)v;
    if (!synth_parse_num(f->f[1], 1e12, &t->t_s) || t->t_s < 0)
        return synth_fail(diag, name, line, "bad time '%.40s'", f->f[1]);
    if (!synth_parse_num(f->f[2], 4294967295.0, &v) || v < 0 || v != (double)(uint32_t)v)
        return synth_fail(diag, name, line, "bad timestamp '%.40s'", f->f[2]);
    t->ts = (uint32_t)v;
    for (int j = 0; j < CUB_KJ_COUNT; j++) {
        for (int k = 0; k < 3; k++) {
            const char *s = f->f[3 + 4 * j + k];
            if (!synth_parse_num(s, COORD_LIMIT_MM, &v))
                return synth_fail(diag, name, line, "bad %c of %s: '%.40s'", "xyz"[k],
                                  cub_kinect_joint_name(j), s);
            t->joint_mm[j][k] = (float)v;
        }
        const char *s = f->f[3 + 4 * j + 3];
        if (strcmp(s, "0") != 0 && strcmp(s, "1") != 0)
            return synth_fail(diag, name, line, "visibility of %s must be 0 or 1, got '%.40s'",
                              cub_kinect_joint_name(j), s);
        t->visible[j] = (uint8_t)(s[0] - '0');
    }
    return CUB_OK;
}

static cub_err parse_gravity(const synth_fields *f, const char *name, int line, float g[3],
                             cub_diag *diag)
{
    if (f->n != 4 || strcmp(f->f[0], "gravity") != 0)
        return synth_fail(diag, name, line, "expected 'gravity gx gy gz' on line 2");
    double v, len2 = 0;
    for (int k = 0; k < 3; k++) {
        if (!synth_parse_num(f->f[1 + k], 1e6, &v))
            return synth_fail(diag, name, line, "bad gravity component '%.40s'", f->f[1 + k]);
        g[k] = (float)v;
        len2 += v * v;
    }
    if (len2 < 1e-6) return synth_fail(diag, name, line, "gravity is the zero vector");
    return CUB_OK;
}

static cub_err add_frame(cub_synth_truth *out, int *cap, const cub_synth_truth_frame *t)
{
    if (out->frame_count == *cap) {
        int n = *cap ? *cap * 2 : 64;
        cub_synth_truth_frame *p = realloc(out->frames, (size_t)n * sizeof(*p));
        if (!p) return CUB_ERR_NOMEM;
        out->frames = p;
        *cap = n;
    }
    out->frames[out->frame_count++] = *t;
    return CUB_OK;
}

cub_err cub_synth_truth_parse(const char *text, size_t len, const char *name, cub_synth_truth *out,
                              cub_diag *diag)
{
    if (!text || !out) return CUB_ERR_ARG;
    memset(out, 0, sizeof(*out));
    name = name ? name : "(memory)";
    synth_lines l = {text, text + len, name, 0};
    synth_fields *f = malloc(sizeof(*f));
    if (!f) return CUB_ERR_NOMEM;
    cub_err err = CUB_OK;
    int cap = 0, have_gravity = 0;
    size_t magic = strlen(TRUTH_MAGIC);
    if (len < magic || memcmp(text, TRUTH_MAGIC, magic) != 0)
        err = synth_fail(diag, name, 1, "not a truth file (line 1 must start '%s')", TRUTH_MAGIC);
    if (!err) synth_lines_next(&l, f); /* the description */
    while (!err && synth_lines_next(&l, f)) {
        if (f->nul) {
            err = synth_fail(diag, name, l.line, "a NUL byte in the line (not a text file?)");
            break;
        }
        if (f->n == 0 || f->f[0][0] == '#') continue;
        if (!have_gravity) {
            err = parse_gravity(f, name, l.line, out->gravity, diag);
            have_gravity = 1;
            continue;
        }
        cub_synth_truth_frame t;
        err = parse_frame(f, name, l.line, &t, diag);
        if (!err && out->frame_count > 0 && t.frame <= out->frames[out->frame_count - 1].frame)
            err = synth_fail(diag, name, l.line, "frame %d does not follow frame %d", t.frame,
                             out->frames[out->frame_count - 1].frame);
        if (!err && out->frame_count >= TRUTH_MAX_FRAMES)
            err = synth_fail(diag, name, l.line, "more than %d frames", TRUTH_MAX_FRAMES);
        if (!err) err = add_frame(out, &cap, &t);
    }
    if (!err && !have_gravity) err = synth_fail(diag, name, l.line, "no 'gravity' line");
    free(f);
    if (err) cub_synth_truth_free(out);
    return err;
}

static cub_err parse_text(const cub_text *t, const void *in, void *out)
{
    return cub_synth_truth_parse(t->s, t->len, t->name, out, t->diag);
}

cub_err cub_synth_truth_read(const char *path, cub_synth_truth *out, cub_diag *diag)
{
    if (!path || !out) return CUB_ERR_ARG;
    return cub_text_load(&(cub_text_src){path, "truth file", CUB_TEXT_MAX_MOCAP}, parse_text, NULL, out, diag);
}

void cub_synth_truth_free(cub_synth_truth *t)
{
    if (!t) return;
    free(t->frames);
    t->frames = NULL;
    t->frame_count = 0;
}

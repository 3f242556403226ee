/* Joint tracks (cub/synth.h): a performance kept as the player's points per
 * frame, so that a demo can render its child without the mocap it was cut
 * from. Each coordinate is a whole number of units, written as what is left
 * after predicting it from its last two frames (constant velocity): a child
 * moves smoothly, so that is almost always within +-31 units, one printable
 * character; anything larger is spelt out in brackets. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/text.h"
#include "synth_internal.h"

#define JT_VALUES (CUB_SYNTH_JTRACK_POINTS * 3)
#define JT_SMALL 31           /* residuals in [-31, 31] are one character */
#define JT_ZERO ('@' + JT_SMALL) /* '@'..'~': never '#', a blank or a bracket */
#define JT_MAX_Q 100000000L   /* |units| allowed: 100 m at 1 um */
#define JT_MAX_FRAMES 1000000 /* 9 hours at 30 fps */

typedef struct jt_parse {
    cub_synth_jtrack *t;
    int header;    /* header lines read (4: frames follow) */
    int frame;     /* frames read */
    int cap;       /* frames t->points_mm holds: grown as they come, so that a
                    * short file claiming many frames costs nothing */
    long q[2][JT_VALUES]; /* the last two frames, in units */
} jt_parse;

static long predict(const jt_parse *p, int k)
{
    if (p->frame == 0) return 0;
    if (p->frame == 1) return p->q[(p->frame - 1) & 1][k];
    return 2 * p->q[(p->frame - 1) & 1][k] - p->q[p->frame & 1][k];
}

static cub_err header_line(jt_parse *p, cub_text_line *ln)
{
    static const char *keys[] = {"cub-jtrack", "fps", "unit_mm", "frames"};
    static const double lo[] = {1, 1, 1e-3, 1}, hi[] = {1, 240, 100, JT_MAX_FRAMES};
    char *w[3];
    int n = cub_text_words(ln->s, w, 2);
    if (n != 2 || strcmp(w[0], keys[p->header]) != 0)
        return cub_text_fail(&ln->at, "expected '%s VALUE' (the header: cub-jtrack 1, fps, "
                                      "unit_mm, frames)", keys[p->header]);
    char *end;
    double v = strtod(w[1], &end);
    if (*end || !(v >= lo[p->header] && v <= hi[p->header]))
        return cub_text_fail(&ln->at, "%s '%.40s' is not a number in [%g, %g]", keys[p->header],
                             w[1], lo[p->header], hi[p->header]);
    if (p->header == 1) p->t->fps = (float)v;
    if (p->header == 2) p->t->unit_mm = (float)v;
    if (p->header == 3) {
        p->t->frame_count = (int)v;
        if (v != (int)v) return cub_text_fail(&ln->at, "frames '%.40s' is not whole", w[1]);
    }
    p->header++;
    return CUB_OK;
}

/* One residual at *s: a character, or "(-123)"; advances *s. */
static int residual(const char **s, long *r)
{
    const char *c = *s;
    if (*c >= '@' && *c <= '~') {
        *r = *c - JT_ZERO;
        *s = c + 1;
        return 1;
    }
    if (*c != '(') return 0;
    char *end;
    long v = strtol(c + 1, &end, 10);
    if (end == c + 1 || *end != ')' || end - c > 12) return 0;
    *r = v;
    *s = end + 1;
    return 1;
}

static cub_err frame_line(jt_parse *p, cub_text_line *ln)
{
    if (p->frame >= p->t->frame_count)
        return cub_text_fail(&ln->at, "more frame lines than 'frames %d'", p->t->frame_count);
    const char *s = ln->s;
    while (*s == ' ' || *s == '\t')
        s++;
    long *q = p->q[p->frame & 1]; /* overwrites the frame before last */
    long now[JT_VALUES];
    for (int k = 0; k < JT_VALUES; k++) {
        long r;
        if (!residual(&s, &r))
            return cub_text_fail(&ln->at, "value %d of %d: expected a character '@'..'~' or "
                                          "'(N)', got '%.12s'", k + 1, JT_VALUES, *s ? s : "(end)");
        now[k] = predict(p, k) + r;
        if (labs(now[k]) > JT_MAX_Q)
            return cub_text_fail(&ln->at, "value %d is %ld units, beyond +-%ld", k + 1, now[k],
                                 JT_MAX_Q);
    }
    while (*s == ' ' || *s == '\t')
        s++;
    if (*s) return cub_text_fail(&ln->at, "more than %d values: '%.12s'", JT_VALUES, s);
    if (p->frame == p->cap) {
        int cap = p->cap ? 2 * p->cap : 256;
        cap = cap > p->t->frame_count ? p->t->frame_count : cap;
        float *m = realloc(p->t->points_mm, (size_t)cap * JT_VALUES * sizeof(float));
        if (!m) return CUB_ERR_NOMEM;
        p->t->points_mm = m;
        p->cap = cap;
    }
    float *out = p->t->points_mm + (size_t)p->frame * JT_VALUES;
    for (int k = 0; k < JT_VALUES; k++) {
        q[k] = now[k];
        out[k] = (float)((double)now[k] * p->t->unit_mm);
    }
    p->frame++;
    return CUB_OK;
}

static cub_err jt_line(void *ctx, cub_text_line *ln)
{
    jt_parse *p = ctx;
    return p->header < 4 ? header_line(p, ln) : frame_line(p, ln);
}

static cub_err jt_whole(const cub_text *t, const void *in, void *out)
{
    (void)in;
    jt_parse *p = calloc(1, sizeof(*p));
    if (!p) return CUB_ERR_NOMEM;
    p->t = out;
    cub_err err = cub_text_lines(t, jt_line, p);
    cub_text_at at = {t->name, 0, t->diag};
    if (!err && p->header < 4) err = cub_text_fail(&at, "the header ends early (no 'frames N')");
    if (!err && p->frame < p->t->frame_count)
        err = cub_text_fail(&at, "%d frame lines, the header says %d", p->frame,
                            p->t->frame_count);
    free(p);
    return err;
}

cub_err cub_synth_jtrack_parse(const char *text, size_t len, const char *name,
                               cub_synth_jtrack *out, cub_diag *diag)
{
    if (!out) return CUB_ERR_ARG;
    memset(out, 0, sizeof(*out));
    cub_text t = {text, len, name ? name : "(memory)", diag};
    cub_err err = cub_text_parse(&t, jt_whole, NULL, out);
    if (err) cub_synth_jtrack_free(out);
    return err;
}

cub_err cub_synth_jtrack_read(const char *path, cub_synth_jtrack *out, cub_diag *diag)
{
    if (!out) return CUB_ERR_ARG;
    memset(out, 0, sizeof(*out));
    cub_text_src src = {path, "joint track", CUB_TEXT_MAX_MOCAP};
    cub_err err = cub_text_load(&src, jt_whole, NULL, out, diag);
    if (err) cub_synth_jtrack_free(out);
    return err;
}

void cub_synth_jtrack_free(cub_synth_jtrack *t)
{
    if (!t) return;
    free(t->points_mm);
    memset(t, 0, sizeof(*t));
}

static void put_residual(FILE *f, long r)
{
    if (r >= -JT_SMALL && r <= JT_SMALL)
        fputc((int)(JT_ZERO + r), f);
    else
        fprintf(f, "(%ld)", r);
}

cub_err cub_synth_write_jtrack(const cub_synth *s, const char *path, float unit_mm,
                               const char *comment, cub_diag *diag)
{
    if (!s || !path || !(unit_mm >= 1e-3f && unit_mm <= 100)) return CUB_ERR_ARG;
    FILE *f = fopen(path, "w");
    if (!f) return cub_diag_fail(diag, CUB_ERR_IO, path, 0, "cannot write it");
    int frames = cub_synth_frame_count(s);
    if (comment) fputs(comment, f);
    fprintf(f, "cub-jtrack 1\nfps %g\nunit_mm %g\nframes %d\n", synth_fps(s), unit_mm, frames);
    jt_parse p = {0};
    for (int i = 0; i < frames; i++) {
        cub_fv3 pts[SP_COUNT];
        synth_performance_points(s, i / (double)synth_fps(s), pts);
        long *q = p.q[i & 1];
        long now[JT_VALUES];
        for (int k = 0; k < JT_VALUES; k++) {
            cub_fv3 v = pts[k / 3];
            float c = k % 3 == 0 ? v.x : k % 3 == 1 ? v.y : v.z;
            now[k] = lround(c / (double)unit_mm);
            p.frame = i;
            put_residual(f, now[k] - predict(&p, k));
        }
        memcpy(q, now, sizeof(now));
        fputc('\n', f);
    }
    if (fclose(f) != 0) return cub_diag_fail(diag, CUB_ERR_IO, path, 0, "write failed");
    return CUB_OK;
}

/* render_text — text as textured quads from a glyph atlas baked once at
 * create time with stb_truetype (Debian's libstb, linked, not compiled in).
 *
 * The atlas holds codepoints 32..255 (ASCII and Latin-1: the songs' hints
 * are English, and names like "Zoë" still draw) at a pixel height of
 * h / 8 of the viewport (baked at most 270 px high, drawn scaled up past
 * that), so 1280x720 bakes 90 px glyphs and 1920x1080 135 px:
 * the title is drawn a little larger, the hint and cues smaller, and
 * bilinear filtering of a big atlas reads better than blowing up a small
 * one. Each label is drawn first eight times offset in a dark colour (an
 * outline) and then in its own colour, so it reads on sky, grass and bear
 * alike. A label is laid out (glyph quads relative to its pen) only when
 * its string changes; drawing it only offsets those quads. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_truetype.h>

#include "cub/text.h"
#include "render_internal.h"

#define ATLAS_SHARE 8  /* glyph pixel height = viewport height / this */
/* The glyphs are baked at most this high (a 4K screen's h / 8) and drawn
 * scaled up past it: at 7680x4320 the 540 px glyphs do not fit a 4096
 * atlas (they stop fitting near h = 3300), and an 8K screen seen from a
 * sofa shows no difference. */
#define BAKE_MAX_PX 270.0f
#define MAX_FONT_BYTES CUB_TEXT_MAX_FONT

static const char TEXT_VS[] =
    "attribute vec2 a_pos;\n"
    "attribute vec2 a_uv;\n"
    "attribute vec4 a_col;\n"
    "varying mediump vec2 v_uv;\n"
    "varying mediump vec4 v_col;\n"
    "void main() { v_uv = a_uv; v_col = a_col; gl_Position = vec4(a_pos, 0.0, 1.0); }\n";
static const char TEXT_FS[] =
    "precision mediump float;\n"
    "uniform sampler2D u_tex;\n"
    "varying vec2 v_uv;\n"
    "varying vec4 v_col;\n"
    "void main() { gl_FragColor = vec4(v_col.rgb, v_col.a * texture2D(u_tex, v_uv).a); }\n";

static void say(char *err, size_t size, const char *fmt, const char *path, const char *why)
{
    if (err && size)
        snprintf(err, size, fmt, path, why);
}

/* The whole font file, or NULL with the reason in err; *len its size. */
static unsigned char *read_font(const char *path, size_t *len, char *err, size_t size)
{
    FILE *f = NULL;
    size_t n = 0;
    cub_diag d = {0};
    cub_text_src src = {path, "font", MAX_FONT_BYTES};
    if (cub_text_fopen(&src, &f, &n, &d)) {
        /* "cannot read the font: why" -> "cannot load font PATH: why" */
        const char *why = strstr(d.msg, "font: ");
        say(err, size, "cannot load font %s: %s", path, why ? why + 6 : d.msg);
        return NULL;
    }
    unsigned char *data = NULL;
    if (n == 0) {
        say(err, size, "cannot load font %s: %s", path, "the file is empty");
    } else if (!(data = malloc(n))) {
        say(err, size, "cannot load font %s: %s", path, "out of memory");
    } else if (fread(data, 1, n, f) != n) {
        say(err, size, "cannot load font %s: %s", path, "read error");
        free(data);
        data = NULL;
    }
    fclose(f);
    *len = data ? n : 0;
    return data;
}

/* Bake into the smallest square atlas (512..4096) that holds every glyph. */
static unsigned char *bake(cub_render_text *t, const unsigned char *font)
{
    for (int side = 512; side <= 4096; side *= 2) {
        unsigned char *px = calloc((size_t)side * side, 1);
        if (!px)
            return NULL;
        int r = stbtt_BakeFontBitmap(font, 0, t->baked_px, px, side, side, CUB_RENDER_GLYPH_FIRST,
                                     CUB_RENDER_GLYPH_COUNT, t->glyphs);
        if (r > 0) {
            t->atlas_side = side;
            return px;
        }
        free(px);
    }
    return NULL;
}

static cub_err make_gl(cub_render_text *t, const unsigned char *px)
{
    t->prog = cub_render_gl_program(TEXT_VS, TEXT_FS, "text");
    if (!t->prog)
        return CUB_ERR_DEVICE;
    t->a_pos = glGetAttribLocation(t->prog, "a_pos");
    t->a_uv = glGetAttribLocation(t->prog, "a_uv");
    t->a_col = glGetAttribLocation(t->prog, "a_col");
    t->u_tex = glGetUniformLocation(t->prog, "u_tex");
    t->tex = cub_render_gl_texture(GL_ALPHA, t->atlas_side, t->atlas_side, px);
    return CUB_OK;
}

cub_err cub_render_text_init(cub_render *r, const char *path, char *err, size_t size)
{
    cub_render_text *t = &r->text;
    size_t len = 0;
    unsigned char *font = read_font(path, &len, err, size);
    if (!font)
        return CUB_ERR_IO;
    /* stb_truetype checks no offset: a damaged font must be refused here. */
    char why[160];
    int usable = cub_render_font_check(font, len, why, sizeof why);
    stbtt_fontinfo info;
    int offset = usable > 0 ? stbtt_GetFontOffsetForIndex(font, 0) : -1;
    if (usable > 0 && (offset < 0 || !stbtt_InitFont(&info, font, offset)))
        usable = -1;
    if (usable <= 0) {
        char msg[200];
        snprintf(msg, sizeof msg, "not a usable TrueType font (%s)", why);
        say(err, size, "cannot load font %s: %s", path, usable < 0 ? "not a TrueType font" : msg);
        free(font);
        return CUB_ERR_FORMAT;
    }
    t->px = (float)(r->h / ATLAS_SHARE > 8 ? r->h / ATLAS_SHARE : 8);
    t->baked_px = t->px < BAKE_MAX_PX ? t->px : BAKE_MAX_PX;
    int ascent = 0, descent = 0, gap = 0;
    stbtt_GetFontVMetrics(&info, &ascent, &descent, &gap);
    float scale = stbtt_ScaleForPixelHeight(&info, t->px);
    t->ascent_px = (float)ascent * scale;
    t->descent_px = (float)-descent * scale;
    unsigned char *px = bake(t, font);
    free(font);
    if (!px) {
        say(err, size, "cannot load font %s: %s", path, "its glyphs do not fit a 4096 atlas");
        return CUB_ERR_FORMAT;
    }
    cub_err e = make_gl(t, px);
    free(px);
    t->cap = CUB_RENDER_TEXT_VERTS;
    t->v = malloc((size_t)t->cap * sizeof t->v[0]);
    return e ? e : t->v ? CUB_OK : CUB_ERR_NOMEM;
}

void cub_render_text_free(cub_render_text *t)
{
    glDeleteProgram(t->prog);
    glDeleteTextures(1, &t->tex);
    free(t->v);
    t->v = NULL;
}

/* The next codepoint of UTF-8 s, advancing *i; malformed bytes -> '?'. */
static int next_codepoint(const char *s, size_t *i)
{
    unsigned char c = (unsigned char)s[*i];
    (*i)++;
    if (c < 0x80)
        return c;
    int extra = c >= 0xF0 ? 3 : c >= 0xE0 ? 2 : c >= 0xC0 ? 1 : -1;
    if (extra < 0)
        return '?';
    int cp = c & (0x3F >> extra);
    for (int k = 0; k < extra; k++) {
        unsigned char d = (unsigned char)s[*i];
        if ((d & 0xC0) != 0x80)
            return '?';
        cp = (cp << 6) | (d & 0x3F);
        (*i)++;
    }
    return cp;
}

void cub_render_text_layout(const cub_render *r, cub_render_label *l, const char *s)
{
    if (!s)
        s = "";
    if (l->laid_out && strcmp(l->text, s) == 0)
        return;
    snprintf(l->text, sizeof l->text, "%s", s);
    l->laid_out = 1;
    l->quads = 0;
    float pen = 0.0f;
    const cub_render_text *t = &r->text;
    float side = (float)t->atlas_side, up = t->px / t->baked_px; /* atlas px -> screen px */
    for (size_t i = 0; l->text[i] && l->quads < CUB_RENDER_LABEL_LEN;) {
        int cp = next_codepoint(l->text, &i);
        if (cp < CUB_RENDER_GLYPH_FIRST || cp >= CUB_RENDER_GLYPH_FIRST + CUB_RENDER_GLYPH_COUNT ||
            (cp >= 0x7F && cp < 0xA0))
            cp = '?';
        const stbtt_bakedchar *g = &t->glyphs[cp - CUB_RENDER_GLYPH_FIRST];
        float *q = l->q[l->quads];
        /* y up from the baseline; the atlas' rows run down. */
        q[0] = pen + g->xoff * up, q[1] = (-g->yoff - (float)(g->y1 - g->y0)) * up;
        q[2] = q[0] + (float)(g->x1 - g->x0) * up, q[3] = -g->yoff * up;
        q[4] = g->x0 / side, q[5] = g->y1 / side, q[6] = g->x1 / side, q[7] = g->y0 / side;
        if (g->x1 > g->x0)
            l->quads++;
        pen += g->xadvance * up;
    }
    l->width_px = pen;
}

static void push(cub_render_text *t, const cub_render *r, float x, float y, float u, float v,
                 const float rgba[4])
{
    cub_render_text_vtx *p = &t->v[t->count++];
    p->x = 2.0f * x / (float)r->w - 1.0f, p->y = 2.0f * y / (float)r->h - 1.0f;
    p->u = u, p->v = v;
    memcpy(p->rgba, rgba, sizeof p->rgba);
}

static void label_quads(cub_render *r, const cub_render_label *l, float x, float y, float scale,
                        const float rgba[4])
{
    cub_render_text *t = &r->text;
    for (int i = 0; i < l->quads && t->count + 6 <= t->cap; i++) {
        const float *q = l->q[i];
        float x0 = x + q[0] * scale, y0 = y + q[1] * scale;
        float x1 = x + q[2] * scale, y1 = y + q[3] * scale;
        push(t, r, x0, y0, q[4], q[5], rgba);
        push(t, r, x1, y0, q[6], q[5], rgba);
        push(t, r, x1, y1, q[6], q[7], rgba);
        push(t, r, x0, y0, q[4], q[5], rgba);
        push(t, r, x1, y1, q[6], q[7], rgba);
        push(t, r, x0, y1, q[4], q[7], rgba);
    }
}

void cub_render_text_draw(cub_render *r, const cub_render_label *l, float x, float y,
                          float scale, const float rgb[3])
{
    static const float OUTLINE[4] = {0.10f, 0.07f, 0.16f, 0.85f};
    static const float DIRS[8][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1},
                                     {0.7f, 0.7f}, {-0.7f, 0.7f}, {0.7f, -0.7f}, {-0.7f, -0.7f}};
    float o = 0.045f * r->text.px * scale;
    o = o < 1.0f ? 1.0f : o;
    for (int d = 0; d < 8; d++)
        label_quads(r, l, x + DIRS[d][0] * o, y + DIRS[d][1] * o, scale, OUTLINE);
    const float fill[4] = {rgb[0], rgb[1], rgb[2], 1.0f};
    label_quads(r, l, x, y, scale, fill);
}

void cub_render_text_flush(cub_render *r)
{
    cub_render_text *t = &r->text;
    if (t->count == 0)
        return;
    glUseProgram(t->prog);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, t->tex);
    glUniform1i(t->u_tex, 0);
    glBindBuffer(GL_ARRAY_BUFFER, r->vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(t->count * sizeof t->v[0]), t->v,
                 GL_STREAM_DRAW);
    GLsizei stride = sizeof t->v[0];
    glEnableVertexAttribArray((GLuint)t->a_pos);
    glEnableVertexAttribArray((GLuint)t->a_uv);
    glEnableVertexAttribArray((GLuint)t->a_col);
    glVertexAttribPointer((GLuint)t->a_pos, 2, GL_FLOAT, GL_FALSE, stride, (const void *)0);
    glVertexAttribPointer((GLuint)t->a_uv, 2, GL_FLOAT, GL_FALSE, stride,
                          (const void *)(2 * sizeof(float)));
    glVertexAttribPointer((GLuint)t->a_col, 4, GL_FLOAT, GL_FALSE, stride,
                          (const void *)(4 * sizeof(float)));
    glDrawArrays(GL_TRIANGLES, 0, t->count);
    glDisableVertexAttribArray((GLuint)t->a_pos);
    glDisableVertexAttribArray((GLuint)t->a_uv);
    glDisableVertexAttribArray((GLuint)t->a_col);
    t->count = 0;
}

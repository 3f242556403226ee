/* render_gl — shader building and the flat-colour triangle batch. */
#include <stdio.h>

#include "render_internal.h"

static GLuint compile(GLenum type, const char *src, const char *name)
{
    GLuint sh = glCreateShader(type);
    glShaderSource(sh, 1, &src, NULL);
    glCompileShader(sh);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[512] = "";
        glGetShaderInfoLog(sh, sizeof log, NULL, log);
        fprintf(stderr, "render: %s %s shader does not compile: %s\n", name,
                type == GL_VERTEX_SHADER ? "vertex" : "fragment", log);
        glDeleteShader(sh);
        return 0;
    }
    return sh;
}

GLuint cub_render_gl_program(const char *vs, const char *fs, const char *name)
{
    GLuint v = compile(GL_VERTEX_SHADER, vs, name);
    GLuint f = compile(GL_FRAGMENT_SHADER, fs, name);
    if (!v || !f) {
        glDeleteShader(v);
        glDeleteShader(f);
        return 0;
    }
    GLuint p = glCreateProgram();
    glAttachShader(p, v);
    glAttachShader(p, f);
    glLinkProgram(p);
    glDeleteShader(v); /* flagged; freed with the program */
    glDeleteShader(f);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[512] = "";
        glGetProgramInfoLog(p, sizeof log, NULL, log);
        fprintf(stderr, "render: %s program does not link: %s\n", name, log);
        glDeleteProgram(p);
        return 0;
    }
    return p;
}

void cub_render_batch_tri(cub_render_batch *b, const cub_render_vtx v[3])
{
    if (b->count + 3 > b->cap)
        return;
    for (int i = 0; i < 3; i++)
        b->v[b->count++] = v[i];
}

cub_render_vtx cub_render_px_vtx(const cub_render *r, float x, float y, const float rgb[3],
                                 float alpha)
{
    return (cub_render_vtx){2.0f * x / (float)r->w - 1.0f, 2.0f * y / (float)r->h - 1.0f, 0.0f,
                            rgb[0], rgb[1], rgb[2], alpha};
}

void cub_render_batch_rect_px(cub_render *r, float x0, float y0, float x1, float y1,
                              const float top_rgb[3], const float bottom_rgb[3])
{
    cub_render_vtx a = cub_render_px_vtx(r, x0, y0, bottom_rgb, 1.0f);
    cub_render_vtx b = cub_render_px_vtx(r, x1, y0, bottom_rgb, 1.0f);
    cub_render_vtx c = cub_render_px_vtx(r, x1, y1, top_rgb, 1.0f);
    cub_render_vtx d = cub_render_px_vtx(r, x0, y1, top_rgb, 1.0f);
    cub_render_batch_tri(&r->batch, (cub_render_vtx[3]){a, b, c});
    cub_render_batch_tri(&r->batch, (cub_render_vtx[3]){a, c, d});
}

void cub_render_batch_draw(cub_render *r)
{
    cub_render_batch *b = &r->batch;
    if (b->count == 0)
        return;
    glUseProgram(r->flat_prog);
    glBindBuffer(GL_ARRAY_BUFFER, r->vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(b->count * sizeof b->v[0]), b->v,
                 GL_STREAM_DRAW);
    glEnableVertexAttribArray((GLuint)r->flat_pos);
    glEnableVertexAttribArray((GLuint)r->flat_col);
    glVertexAttribPointer((GLuint)r->flat_pos, 3, GL_FLOAT, GL_FALSE, sizeof b->v[0],
                          (const void *)0);
    glVertexAttribPointer((GLuint)r->flat_col, 4, GL_FLOAT, GL_FALSE, sizeof b->v[0],
                          (const void *)(3 * sizeof(float)));
    glDrawArrays(GL_TRIANGLES, 0, b->count);
    glDisableVertexAttribArray((GLuint)r->flat_pos);
    glDisableVertexAttribArray((GLuint)r->flat_col);
    b->count = 0;
}

GLuint cub_render_gl_texture(GLenum format, int w, int h, const void *px)
{
    GLuint tex = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1); /* rows of any width, byte-packed */
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)format, w, h, 0, format, GL_UNSIGNED_BYTE, px);
    return tex;
}

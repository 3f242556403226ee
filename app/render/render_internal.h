/* render_internal — what the renderer's files share: the cub_render state,
 * the vertex batch every flat-coloured shape goes through, and the GL
 * helpers. Private to app/render. */
#ifndef CUB_RENDER_INTERNAL_H
#define CUB_RENDER_INTERNAL_H

#include <GLES2/gl2.h>
#include <stdint.h>

#include "cub/render.h"

#define CUB_RENDER_DEPTH_W 640
#define CUB_RENDER_DEPTH_H 480

/* One vertex of a flat-coloured triangle: position in normalised device
 * coordinates, colour RGBA. */
typedef struct cub_render_vtx {
    float x, y, z;
    float r, g, b, a;
} cub_render_vtx;

/* Triangles collected on the CPU and drawn with one call. Pushing past cap
 * drops the triangle (a skeleton has at most CUB_MOTION_MAX_JOINTS joints,
 * and cap is sized for that, so this never happens in practice). */
typedef struct cub_render_batch {
    cub_render_vtx *v;
    int count, cap;
} cub_render_batch;

struct cub_render {
    int w, h;
    float figure_height_mm;
    GLuint flat_prog, tex_prog;
    GLint flat_pos, flat_col;
    GLint tex_pos, tex_uv, tex_sampler;
    GLuint vbo;
    GLuint depth_tex;
    uint8_t depth_lut[2048];  /* raw 11-bit -> 8-bit shade */
    uint8_t *depth_lum;       /* CUB_RENDER_DEPTH_W * _H shades */
    cub_render_batch batch;
};

/* render_gl.c */
GLuint cub_render_gl_program(const char *vs, const char *fs, const char *name);
void cub_render_batch_tri(cub_render_batch *b, const cub_render_vtx v[3]);
/* An axis-aligned rectangle in pixels (origin bottom-left), flat colours
 * at the top and the bottom edge (a vertical gradient). */
void cub_render_batch_rect_px(cub_render *r, float x0, float y0, float x1, float y1,
                              const float top_rgb[3], const float bottom_rgb[3]);
void cub_render_batch_draw(cub_render *r);

/* render_figure.c: CUB_ERR_ARG for a skeleton without positions or with a
 * parent after its child; then append the figure's triangles to r->batch. */
cub_err cub_render_figure_check(const cub_render_scene *scene);
void cub_render_figure(cub_render *r, const cub_render_scene *scene);

/* render_inset.c */
void cub_render_inset_init_lut(uint8_t lut[2048]);
void cub_render_inset_draw(cub_render *r, const uint16_t *depth_raw);
/* The inset's rectangle in pixels, origin bottom-left. */
void cub_render_inset_rect(int w, int h, int *x0, int *y0, int *iw, int *ih);

#endif

/* render_internal — what the renderer's files share: the cub_render state,
 * the vertex batch every flat-coloured shape goes through, and the GL
 * helpers. Private to app/render. */
#ifndef CUB_RENDER_INTERNAL_H
#define CUB_RENDER_INTERNAL_H

#include <GLES2/gl2.h>
#include <stb_truetype.h>
#include <stdint.h>

#include "cub/render.h"
#include "render_floor.h"
#include "render_mesh.h"

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

/* Bone slots the lit shader holds (two vec4 uniforms each; GLES2 promises
 * 128 vertex uniform vectors). Slot 0 is the stage; joint j is slot j + 1. */
#define CUB_RENDER_MAX_SLOTS 48

/* A mesh in GL buffers: indices [first, first + count) of one draw. */
typedef struct cub_render_range {
    int first, count;
} cub_render_range;

/* The lit, skinned shader and the per-frame bone transforms it reads. */
typedef struct cub_render_lit {
    GLuint prog;
    GLint a_pos, a_nrm, a_col, a_skin;
    GLint u_vp, u_rot, u_pos, u_eye;
    float vp[16], eye[3];                 /* this frame's camera */
    float rot[4 * CUB_RENDER_MAX_SLOTS];  /* x y z w per slot */
    float pos[4 * CUB_RENDER_MAX_SLOTS];  /* translation per slot (w unused) */
} cub_render_lit;

/* The character's meshes, built once for the character shown, and how its
 * joints map onto the scene skeleton's. */
typedef struct cub_render_bear {
    const cub_character *shown; /* NULL: none built */
    GLuint vbo, ibo;
    cub_render_range body;      /* every part but the eyes and the optional ones */
    cub_render_range optional;  /* the parts on optional joints (the wings) */
    cub_render_range face[CUB_RENDER_FACE_COUNT];
    float rest_mm[CUB_MOTION_MAX_JOINTS][3]; /* joint positions, rest pose */
    const cub_skeleton *mapped_skel;
    int mapped_count;           /* joint_count of mapped_skel when mapped */
    int map[CUB_MOTION_MAX_JOINTS]; /* character joint -> scene joint or -1 */
    int mapped_any;
    int mapped_optional;        /* every optional joint with parts is in the scene */
} cub_render_bear;

/* Text (render_text.c): the baked glyphs and this frame's quads. */
#define CUB_RENDER_GLYPH_FIRST 32
#define CUB_RENDER_GLYPH_COUNT 224 /* 32..255: ASCII and Latin-1 */
#define CUB_RENDER_LABEL_LEN 128   /* glyphs a label holds */
#define CUB_RENDER_TEXT_VERTS (9 * 6 * 4 * CUB_RENDER_LABEL_LEN) /* four labels a frame */

typedef struct cub_render_text_vtx {
    float x, y, u, v;
    float rgba[4];
} cub_render_text_vtx;

typedef struct cub_render_text {
    GLuint prog, tex;
    GLint a_pos, a_uv, a_col, u_tex;
    float px;                   /* glyph height on the screen in pixels */
    float baked_px;             /* glyph height in the atlas (px, capped) */
    float ascent_px, descent_px;
    int atlas_side;
    stbtt_bakedchar glyphs[CUB_RENDER_GLYPH_COUNT];
    cub_render_text_vtx *v;
    int count, cap;
} cub_render_text;

/* A string laid out once: glyph quads (x0 y0 x1 y1 in pixels from the pen
 * at the baseline, y up; then u0 v0 u1 v1), at the atlas' size. */
typedef struct cub_render_label {
    char text[CUB_RENDER_LABEL_LEN * 2];
    int laid_out, quads;
    float width_px;
    float q[CUB_RENDER_LABEL_LEN][8];
} cub_render_label;

struct cub_render {
    int w, h;
    float figure_height_mm;
    int x0, y0;            /* viewport origin (cub_render_desc x, y) */
    cub_render_view view;  /* clamped; zoom 1 = the default camera */
    GLuint flat_prog, tex_prog;
    GLint flat_pos, flat_col;
    GLint tex_pos, tex_uv, tex_sampler;
    GLuint vbo;
    GLuint depth_tex;
    uint8_t depth_lut[2048];  /* raw 11-bit -> 8-bit shade */
    uint8_t *depth_lum;       /* CUB_RENDER_DEPTH_W * _H shades */
    cub_render_batch batch;
    cub_render_lit lit;
    cub_render_bear bear;
    GLuint stage_vbo, stage_ibo;
    cub_render_range stage;
    /* The forest floor (cub_render_set_floor; NULL: the flat meadow) and
     * the terrain made of it, pointing into it. */
    cub_floor *floor;
    cub_gait_terrain terrain;
    cub_render_text text;
    cub_render_label hint_label, title_label, cue_label;
};

/* render_gl.c */
GLuint cub_render_gl_program(const char *vs, const char *fs, const char *name);
/* A w x h texture of one-byte texels (format: GL_ALPHA, GL_LUMINANCE),
 * linear and clamped to its edge (what ES2 allows for any size without
 * mipmaps), filled from px (NULL: left for glTexSubImage2D); it stays bound. */
GLuint cub_render_gl_texture(GLenum format, int w, int h, const void *px);
void cub_render_batch_tri(cub_render_batch *b, const cub_render_vtx v[3]);
/* A batch vertex at pixel (x, y) of the viewport (origin bottom-left). */
cub_render_vtx cub_render_px_vtx(const cub_render *r, float x, float y, const float rgb[3],
                                 float alpha);
/* An axis-aligned rectangle in pixels (origin bottom-left), flat colours
 * at the top and the bottom edge (a vertical gradient). */
void cub_render_batch_rect_px(cub_render *r, float x0, float y0, float x1, float y1,
                              const float top_rgb[3], const float bottom_rgb[3]);
void cub_render_batch_draw(cub_render *r);

/* render_figure.c: CUB_ERR_ARG for a skeleton without positions or with a
 * parent after its child; then append the figure's triangles to r->batch. */
cub_err cub_render_figure_check(const cub_render_scene *scene);
void cub_render_figure(cub_render *r, const cub_render_scene *scene);

/* render_lit.c: the lit shader, the camera that frames the character, and
 * drawing an index range of a mesh with the bone slots as they are. */
cub_err cub_render_lit_init(cub_render_lit *lit);
void cub_render_lit_free(cub_render_lit *lit);
/* The camera for this frame: perspective, level, framing a figure of
 * figure_height_mm standing at root (x, z) whole at the viewport's aspect. */
void cub_render_lit_camera(cub_render *r, const float root_mm[3]);
/* Upload the slots' transforms once per frame, then draw ranges. */
void cub_render_lit_begin(cub_render *r);
void cub_render_lit_draw(cub_render *r, GLuint vbo, GLuint ibo, cub_render_range range);
/* Fill GL buffers from a mesh; 0 on success. */
int cub_render_lit_upload(const cub_render_mesh *m, GLuint *vbo, GLuint *ibo);

/* render_bear.c: CUB_ERR_ARG when the scene's character cannot be shown
 * (too many joints, or a part that does not fit); otherwise builds its
 * meshes if they are not built yet. *drawn says whether the bear is drawn
 * this frame (else the stick figure stands in). */
cub_err cub_render_bear_prepare(cub_render *r, const cub_render_scene *scene, int *drawn);
void cub_render_bear_draw(cub_render *r, const cub_render_scene *scene);
void cub_render_bear_free(cub_render_bear *b);

/* render_stage.c: the forest, built at create and again when the floor
 * is set (on r->floor when there is one); the old buffers are freed. */
cub_err cub_render_stage_init(cub_render *r);
/* The ground's height under (x, z): the floor's, else the meadow's 0. */
float cub_render_stage_ground_y(const cub_render *r, float x_mm, float z_mm);
void cub_render_stage_draw(cub_render *r);

/* render_inset.c */
void cub_render_inset_init_lut(uint8_t lut[2048]);
void cub_render_inset_draw(cub_render *r, const uint16_t *depth_raw);
/* The inset's rectangle in pixels, origin bottom-left. */
void cub_render_inset_rect(int w, int h, int *x0, int *y0, int *iw, int *ih);

/* render_font_check.c: whether n bytes of a font file are safe for
 * stb_truetype's atlas bake: 1 yes; 0 no, with the reason in why; -1 not
 * a TrueType file at all. */
int cub_render_font_check(const unsigned char *data, size_t n, char *why, size_t size);

/* render_text.c: bake the font's atlas (CUB_ERR_IO / CUB_ERR_FORMAT with
 * "cannot load font PATH: why" in err), lay out a label when its string
 * changed, queue it at pen (x, y) px (baseline, origin bottom-left) times
 * scale with its outline, and draw what is queued. */
cub_err cub_render_text_init(cub_render *r, const char *path, char *err, size_t size);
void cub_render_text_free(cub_render_text *t);
void cub_render_text_layout(const cub_render *r, cub_render_label *l, const char *s);
void cub_render_text_draw(cub_render *r, const cub_render_label *l, float x, float y,
                          float scale, const float rgb[3]);
void cub_render_text_flush(cub_render *r);

/* render_shapes.c: translucent 2D shapes in pixels (origin bottom-left)
 * into r->batch. */
void cub_render_shape_rect(cub_render *r, float x0, float y0, float x1, float y1,
                           const float rgba[4]);
void cub_render_shape_disc(cub_render *r, float cx, float cy, float radius, const float rgba[4]);
void cub_render_shape_round_rect(cub_render *r, float x0, float y0, float x1, float y1,
                                 float radius, const float rgba[4]);
/* A thick segment with round ends (half-width hw). */
void cub_render_shape_limb(cub_render *r, float x0, float y0, float x1, float y1, float hw,
                           const float rgba[4]);

/* render_hud.c: hint and icon, progress, the idle screen. */
void cub_render_hud_draw(cub_render *r, const cub_render_scene *scene);
/* render_child.c: the child's skeleton over the inset (the bones of the
 * joints in mark drawn marked) and the cue text (NULL or "": none) above it. */
void cub_render_child_draw(cub_render *r, const cub_track_skeleton *child, const char *cue_text,
                           uint32_t mark, int have_depth);

#endif

/* render — set-up and the frame: background, then the coach (the lit
 * character on the forest stage, or the stick figure), then over it what
 * the child reads (the idle screen, or progress, hint and icon), then the
 * depth inset with the child's skeleton and cue, into whatever framebuffer
 * is current. Output depends only on the
 * scene (no clocks, no animation), so frames can be golden-tested. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render_internal.h"

#define BATCH_CAP 16384 /* vertices; a 128-joint figure needs about 7000 */

static const char FLAT_VS[] =
    "attribute vec3 a_pos;\n"
    "attribute vec4 a_col;\n"
    "varying mediump vec4 v_col;\n"
    "void main() { v_col = a_col; gl_Position = vec4(a_pos, 1.0); }\n";
static const char FLAT_FS[] =
    "precision mediump float;\n"
    "varying vec4 v_col;\n"
    "void main() { gl_FragColor = v_col; }\n";
static const char TEX_VS[] =
    "attribute vec2 a_pos;\n"
    "attribute vec2 a_uv;\n"
    "varying mediump vec2 v_uv;\n"
    "void main() { v_uv = a_uv; gl_Position = vec4(a_pos, 0.0, 1.0); }\n";
static const char TEX_FS[] =
    "precision mediump float;\n"
    "uniform sampler2D u_tex;\n"
    "varying vec2 v_uv;\n"
    "void main() { gl_FragColor = vec4(vec3(texture2D(u_tex, v_uv).r), 1.0); }\n";

/* The default sky: deeper blue at the top, pale at the horizon, and grass
 * below the floor line. */
static const float SKY_TOP[3] = {0.38f, 0.62f, 0.92f};
static const float SKY_HORIZON[3] = {0.82f, 0.91f, 0.99f};
static const float GRASS_TOP[3] = {0.47f, 0.70f, 0.36f};
static const float GRASS_BOTTOM[3] = {0.34f, 0.56f, 0.26f};
#define FLOOR_ROW_SHARE 0.07f /* matches the figure camera's floor line */

static cub_err make_gl_objects(cub_render *r)
{
    r->flat_prog = cub_render_gl_program(FLAT_VS, FLAT_FS, "flat");
    r->tex_prog = cub_render_gl_program(TEX_VS, TEX_FS, "depth inset");
    if (!r->flat_prog || !r->tex_prog)
        return CUB_ERR_DEVICE;
    r->flat_pos = glGetAttribLocation(r->flat_prog, "a_pos");
    r->flat_col = glGetAttribLocation(r->flat_prog, "a_col");
    r->tex_pos = glGetAttribLocation(r->tex_prog, "a_pos");
    r->tex_uv = glGetAttribLocation(r->tex_prog, "a_uv");
    r->tex_sampler = glGetUniformLocation(r->tex_prog, "u_tex");
    glGenBuffers(1, &r->vbo);
    r->depth_tex = cub_render_gl_texture(GL_LUMINANCE, CUB_RENDER_DEPTH_W, CUB_RENDER_DEPTH_H, NULL);
    if (cub_render_lit_init(&r->lit))
        return CUB_ERR_DEVICE;
    if (cub_render_stage_init(r))
        return CUB_ERR_DEVICE;
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) {
        fprintf(stderr, "render: setting up GL objects failed: GL error 0x%04x\n", e);
        return CUB_ERR_DEVICE;
    }
    return CUB_OK;
}

cub_err cub_render_create(const cub_render_desc *desc, cub_render **out)
{
    if (!desc || !out || desc->width <= 0 || desc->height <= 0 || desc->figure_height_mm < 0.0f)
        return CUB_ERR_ARG;
    *out = NULL;
    cub_render *r = calloc(1, sizeof *r);
    if (!r)
        return CUB_ERR_NOMEM;
    r->w = desc->width;
    r->h = desc->height;
    r->x0 = desc->x;
    r->y0 = desc->y;
    cub_render_set_view(r, NULL);
    r->figure_height_mm = desc->figure_height_mm > 0.0f ? desc->figure_height_mm : 1800.0f;
    r->batch.cap = BATCH_CAP;
    r->batch.v = malloc(BATCH_CAP * sizeof r->batch.v[0]);
    r->depth_lum = malloc(CUB_RENDER_DEPTH_W * CUB_RENDER_DEPTH_H);
    if (!r->batch.v || !r->depth_lum) {
        cub_render_destroy(r);
        return CUB_ERR_NOMEM;
    }
    cub_render_inset_init_lut(r->depth_lut);
    if (desc->error && desc->error_size)
        desc->error[0] = '\0';
    cub_err e = make_gl_objects(r);
    if (!e)
        e = cub_render_text_init(r, desc->font_path ? desc->font_path : CUB_RENDER_DEFAULT_FONT,
                                 desc->error, desc->error_size);
    if (e) {
        cub_render_destroy(r);
        return e;
    }
    *out = r;
    return CUB_OK;
}

void cub_render_destroy(cub_render *r)
{
    if (!r)
        return;
    /* Deleting name 0 is a no-op, so a half-made renderer is fine here. */
    glDeleteProgram(r->flat_prog);
    glDeleteProgram(r->tex_prog);
    glDeleteBuffers(1, &r->vbo);
    glDeleteTextures(1, &r->depth_tex);
    cub_render_lit_free(&r->lit);
    cub_render_bear_free(&r->bear);
    cub_render_text_free(&r->text);
    glDeleteBuffers(1, &r->stage_vbo);
    glDeleteBuffers(1, &r->stage_ibo);
    free(r->floor);
    free(r->batch.v);
    free(r->depth_lum);
    free(r);
}

/* The stage's sky: the level camera puts the horizon at mid-height. */
static const float STAGE_SKY_TOP[3] = {0.30f, 0.58f, 0.93f};
static const float STAGE_SKY_HORIZON[3] = {0.86f, 0.94f, 1.00f};

static void background(cub_render *r, const float rgb[3], int stage)
{
    float w = (float)r->w, h = (float)r->h;
    if (rgb[0] != 0.0f || rgb[1] != 0.0f || rgb[2] != 0.0f) {
        cub_render_batch_rect_px(r, 0, 0, w, h, rgb, rgb);
    } else if (stage) {
        cub_render_batch_rect_px(r, 0, 0.5f * h, w, h, STAGE_SKY_TOP, STAGE_SKY_HORIZON);
        cub_render_batch_rect_px(r, 0, 0, w, 0.5f * h, STAGE_SKY_HORIZON, STAGE_SKY_HORIZON);
    } else {
        float floor_y = FLOOR_ROW_SHARE * h;
        cub_render_batch_rect_px(r, 0, floor_y, w, h, SKY_TOP, SKY_HORIZON);
        cub_render_batch_rect_px(r, 0, 0, w, floor_y, GRASS_TOP, GRASS_BOTTOM);
    }
    cub_render_batch_draw(r);
}

void cub_render_set_view(cub_render *r, const cub_render_view *view)
{
    cub_render_view v = view ? *view : (cub_render_view){0};
    if (!(v.zoom > 0.0f)) /* also NaN */
        v.zoom = 1.0f;
    v.zoom = fminf(fmaxf(v.zoom, 0.1f), 10.0f);
    v.pitch_deg = isfinite(v.pitch_deg) ? fminf(fmaxf(v.pitch_deg, -80.0f), 80.0f) : 0.0f;
    v.yaw_deg = isfinite(v.yaw_deg) ? fmodf(v.yaw_deg, 360.0f) : 0.0f;
    r->view = v;
}

/* The view as a turn and a scale of the world about a pivot (column-major
 * 3x3 m = zoom * Rx(pitch) * Ry(-yaw)): the same picture as orbiting and
 * dollying the camera, and it leaves both cameras (the lit perspective one
 * and the stick figure's orthographic one) untouched. */
static void view_matrix(const cub_render_view *v, float m[9])
{
    const float rad = 3.14159265f / 180.0f;
    float cy = cosf(v->yaw_deg * rad), sy = sinf(v->yaw_deg * rad);
    float cp = cosf(v->pitch_deg * rad), sp = sinf(v->pitch_deg * rad), s = v->zoom;
    const float rm[9] = {cy, -sp * sy, cp * sy, 0.0f, cp, sp, -sy, -sp * cy, cp * cy};
    for (int i = 0; i < 9; i++)
        m[i] = s * rm[i];
}

static void view_point(const float m[9], const float pivot[3], const float in[3], float out[3])
{
    float d[3] = {in[0] - pivot[0], in[1] - pivot[1], in[2] - pivot[2]};
    for (int i = 0; i < 3; i++)
        out[i] = pivot[i] + m[i] * d[0] + m[3 + i] * d[1] + m[6 + i] * d[2];
}

/* vp = vp * M with M = T(pivot) m T(-pivot); the eye (for the shading)
 * moves by M's inverse, where it stands relative to the turned world. */
static void view_on_lit(cub_render *r, const float pivot[3])
{
    float m[9], t[3], e[3], *vp = r->lit.vp, out[16];
    view_matrix(&r->view, m);
    view_point(m, pivot, (const float[3]){0.0f, 0.0f, 0.0f}, t);
    const float mm[16] = {m[0], m[1], m[2], 0, m[3], m[4], m[5], 0,
                          m[6], m[7], m[8], 0, t[0], t[1], t[2], 1};
    for (int c = 0; c < 4; c++)
        for (int row = 0; row < 4; row++)
            out[4 * c + row] = vp[row] * mm[4 * c] + vp[4 + row] * mm[4 * c + 1] +
                               vp[8 + row] * mm[4 * c + 2] + vp[12 + row] * mm[4 * c + 3];
    memcpy(vp, out, sizeof out);
    float s2 = r->view.zoom * r->view.zoom, *eye = r->lit.eye;
    for (int i = 0; i < 3; i++) /* m^-1 = m^T / zoom^2 */
        e[i] = (m[3 * i] * (eye[0] - pivot[0]) + m[3 * i + 1] * (eye[1] - pivot[1]) +
                m[3 * i + 2] * (eye[2] - pivot[2])) / s2 + pivot[i];
    memcpy(eye, e, sizeof e);
}

static int default_view(const cub_render *r)
{
    return r->view.yaw_deg == 0.0f && r->view.pitch_deg == 0.0f && r->view.zoom == 1.0f;
}

/* The stick figure's camera is fixed; the view turns a copy of the joints
 * about the middle of the frame above the root instead. */
static void figure_in_view(cub_render *r, const cub_render_scene *scene)
{
    const cub_skeleton *skel = scene->skel;
    if (default_view(r) || !skel || skel->joint_count <= 0) {
        cub_render_figure(r, scene);
        return;
    }
    float xyz[3 * CUB_MOTION_MAX_JOINTS], m[9];
    const float *root = scene->world_xyz_mm;
    /* mid-height of the view: (1/2 - floor share) of fh / fill share */
    float pivot[3] = {root[0], 0.43f * r->figure_height_mm / 0.8f, root[2]};
    view_matrix(&r->view, m);
    for (int j = 0; j < skel->joint_count; j++)
        view_point(m, pivot, scene->world_xyz_mm + 3 * j, xyz + 3 * j);
    cub_render_scene turned = *scene;
    turned.world_xyz_mm = xyz;
    cub_render_figure(r, &turned);
}

/* The camera follows the root (and on a floor the ground under it), so
 * the bear stays in the middle of the frame. The meadow follows it too, so
 * it stands still on screen; a floor stays where it is, so the bear walks
 * over it. */
static void coach_on_stage(cub_render *r, const cub_render_scene *scene)
{
    const float *root = scene->world_xyz_mm;
    float at[3] = {0.0f, 0.0f, 0.0f};
    if (isfinite(root[0]) && isfinite(root[2]))
        at[0] = root[0], at[2] = root[2];
    at[1] = cub_render_stage_ground_y(r, at[0], at[2]);
    cub_render_lit_camera(r, at);
    if (!default_view(r))
        view_on_lit(r, (const float[3]){at[0], r->lit.eye[1], at[2]});
    float *q = r->lit.rot, *t = r->lit.pos; /* slot 0: the stage */
    q[0] = q[1] = q[2] = 0.0f, q[3] = 1.0f;
    t[0] = r->floor ? 0.0f : at[0], t[1] = 0.0f, t[2] = r->floor ? 0.0f : at[2];
    cub_render_bear_draw(r, scene);
    cub_render_stage_draw(r);
}

cub_err cub_render_set_floor(cub_render *r, const cub_floor *floor)
{
    if (!r) return CUB_ERR_ARG;
    cub_floor *copy = NULL;
    cub_gait_terrain t;
    if (floor) {
        if (cub_floor_check(floor)) return CUB_ERR_ARG;
        copy = malloc(sizeof *copy);
        if (!copy) return CUB_ERR_NOMEM;
        *copy = *floor;
        cub_floor_terrain(copy, &t); /* checked above */
    }
    free(r->floor);
    r->floor = copy;
    if (copy) r->terrain = t;
    return cub_render_stage_init(r);
}

cub_err cub_render_frame(cub_render *r, const cub_render_scene *scene)
{
    if (!r || !scene)
        return CUB_ERR_ARG;
    cub_err e = cub_render_figure_check(scene);
    int bear = 0;
    if (!e)
        e = cub_render_bear_prepare(r, scene, &bear);
    if (e)
        return e; /* before drawing anything: no half frame */
    /* The scissor keeps the clear inside this renderer's viewport. */
    glViewport(r->x0, r->y0, r->w, r->h);
    glScissor(r->x0, r->y0, r->w, r->h);
    glEnable(GL_SCISSOR_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDepthMask(GL_TRUE);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClearDepthf(1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

    glDisable(GL_DEPTH_TEST);
    background(r, scene->background_rgb, bear);

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    if (bear)
        coach_on_stage(r, scene);
    else
        figure_in_view(r, scene);
    cub_render_batch_draw(r);
    glDisable(GL_DEPTH_TEST);

    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    cub_render_hud_draw(r, scene);
    glDisable(GL_BLEND);
    if (scene->depth_raw)
        cub_render_inset_draw(r, scene->depth_raw);
    if (scene->child) {
        glEnable(GL_BLEND);
        cub_render_child_draw(r, scene->child, scene->child_cue, scene->child_mark,
                              scene->depth_raw != NULL);
        glDisable(GL_BLEND);
    }
    glDisable(GL_SCISSOR_TEST);

    GLenum gl_err = glGetError();
    if (gl_err != GL_NO_ERROR) {
        fprintf(stderr, "render: frame failed: GL error 0x%04x\n", gl_err);
        return CUB_ERR_DEVICE;
    }
    return CUB_OK;
}

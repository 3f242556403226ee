/* render_lit — the lit, skinned shader and the camera.
 *
 * Skinning runs in the vertex shader: each vertex names two bone slots and
 * a weight; a slot is a rotation (quaternion) and a translation taking the
 * bind pose to this frame's pose. The CPU only fills 48 x 2 vec4 per frame.
 *
 * Lighting is a cartoon one: a key light from the upper left front, cut
 * into three bands (lit, half, shade) instead of a smooth falloff, a fill
 * so the shade is never dark, and a warm rim where the surface turns away
 * from the viewer, which rounds the silhouettes.
 *
 * The direction to the eye is found per vertex, in the vertex shader's
 * full precision. Done in the mediump fragment shader, normalize(u_eye -
 * v_world) of a vector thousands of millimetres long gave a rim on every
 * pixel under x86-64 llvmpipe and a right one under aarch64 llvmpipe; our
 * guess, not proven: mediump run as 16-bit floats there, where the squared
 * length overflows (a GPU such as the Pi's may do the same). */
#include <math.h>
#include <stddef.h>
#include <stdio.h>

#include "render_internal.h"

#define FOV_Y_DEG 30.0f
#define FILL_SHARE 0.80f  /* share of the view height the figure fills */
#define FLOOR_SHARE 0.07f /* floor above the bottom edge, share of the view */
#define WIDTH_PER_HEIGHT 1.1f /* the widest a figure gets (arms out), x its height */

#define STR_(x) #x
#define STR(x) STR_(x)

static const char LIT_VS[] =
    "uniform mat4 u_vp;\n"
    "uniform vec4 u_rot[" STR(CUB_RENDER_MAX_SLOTS) "];\n"
    "uniform vec4 u_pos[" STR(CUB_RENDER_MAX_SLOTS) "];\n"
    "attribute vec3 a_pos;\n"
    "attribute vec3 a_nrm;\n"
    "attribute vec3 a_col;\n"
    "attribute vec3 a_skin;\n" /* slot a, slot b, weight of b */
    "varying vec3 v_nrm;\n"
    "varying vec3 v_col;\n"
    "varying vec3 v_to_eye;\n"
    "uniform vec3 u_eye;\n"
    "vec3 qrot(vec4 q, vec3 v) { return v + 2.0 * cross(q.xyz, cross(q.xyz, v) + q.w * v); }\n"
    "void main() {\n"
    "  int a = int(a_skin.x + 0.5), b = int(a_skin.y + 0.5);\n"
    "  vec3 pa = qrot(u_rot[a], a_pos) + u_pos[a].xyz;\n"
    "  vec3 pb = qrot(u_rot[b], a_pos) + u_pos[b].xyz;\n"
    "  vec3 na = qrot(u_rot[a], a_nrm), nb = qrot(u_rot[b], a_nrm);\n"
    "  vec3 p = mix(pa, pb, a_skin.z);\n"
    "  v_nrm = mix(na, nb, a_skin.z);\n"
    "  v_col = a_col;\n"
    "  v_to_eye = normalize(u_eye - p);\n"
    "  gl_Position = u_vp * vec4(p, 1.0);\n"
    "}\n";
static const char LIT_FS[] =
    "precision mediump float;\n"
    "varying vec3 v_nrm;\n"
    "varying vec3 v_col;\n"
    "varying vec3 v_to_eye;\n"
    "void main() {\n"
    "  vec3 n = normalize(v_nrm);\n"
    "  vec3 key = normalize(vec3(-0.45, 0.75, 0.5));\n"
    "  float d = dot(n, key);\n"
    "  float band = d > 0.5 ? 1.0 : d > 0.05 ? 0.84 : 0.68;\n"
    "  vec3 to_eye = normalize(v_to_eye);\n"
    "  float rim = 1.0 - max(dot(n, to_eye), 0.0);\n"
    "  rim = rim * rim * rim;\n"
    "  vec3 c = v_col * (band * 0.92 + 0.08) + rim * 0.22 * vec3(1.0, 0.93, 0.8);\n"
    "  gl_FragColor = vec4(min(c, vec3(1.0)), 1.0);\n"
    "}\n";

cub_err cub_render_lit_init(cub_render_lit *lit)
{
    lit->prog = cub_render_gl_program(LIT_VS, LIT_FS, "lit");
    if (!lit->prog)
        return CUB_ERR_DEVICE;
    lit->a_pos = glGetAttribLocation(lit->prog, "a_pos");
    lit->a_nrm = glGetAttribLocation(lit->prog, "a_nrm");
    lit->a_col = glGetAttribLocation(lit->prog, "a_col");
    lit->a_skin = glGetAttribLocation(lit->prog, "a_skin");
    lit->u_vp = glGetUniformLocation(lit->prog, "u_vp");
    lit->u_rot = glGetUniformLocation(lit->prog, "u_rot");
    lit->u_pos = glGetUniformLocation(lit->prog, "u_pos");
    lit->u_eye = glGetUniformLocation(lit->prog, "u_eye");
    for (int s = 0; s < CUB_RENDER_MAX_SLOTS; s++)
        lit->rot[4 * s + 3] = 1.0f; /* identity until a frame says otherwise */
    return CUB_OK;
}

void cub_render_lit_free(cub_render_lit *lit)
{
    glDeleteProgram(lit->prog);
    lit->prog = 0;
}

void cub_render_lit_camera(cub_render *r, const float root_mm[3])
{
    float fh = r->figure_height_mm, aspect = (float)r->w / (float)r->h;
    float view_h = fh / FILL_SHARE;
    if (view_h * aspect < WIDTH_PER_HEIGHT * view_h)
        view_h = WIDTH_PER_HEIGHT * fh / FILL_SHARE / aspect; /* narrower than 1.1:1 */
    float f = 1.0f / tanf(0.5f * FOV_Y_DEG * 3.14159265f / 180.0f);
    float dist = 0.5f * view_h * f;
    float eye[3] = {root_mm[0], root_mm[1] - FLOOR_SHARE * view_h + 0.5f * view_h,
                    root_mm[2] + dist};
    float near_mm = 0.25f * dist, far_mm = dist + 12000.0f;
    float *m = r->lit.vp;
    for (int i = 0; i < 16; i++)
        m[i] = 0.0f;
    /* Perspective (column-major) times a translation by -eye: a level
     * camera looking down -z, so the figure's plane is framed exactly. */
    m[0] = f / aspect;
    m[5] = f;
    m[10] = (far_mm + near_mm) / (near_mm - far_mm);
    m[11] = -1.0f;
    float p14 = 2.0f * far_mm * near_mm / (near_mm - far_mm);
    m[12] = -m[0] * eye[0];
    m[13] = -m[5] * eye[1];
    m[14] = -m[10] * eye[2] + p14;
    m[15] = eye[2];
    for (int i = 0; i < 3; i++)
        r->lit.eye[i] = eye[i];
}

void cub_render_lit_begin(cub_render *r)
{
    cub_render_lit *lit = &r->lit;
    glUseProgram(lit->prog);
    glUniformMatrix4fv(lit->u_vp, 1, GL_FALSE, lit->vp);
    glUniform4fv(lit->u_rot, CUB_RENDER_MAX_SLOTS, lit->rot);
    glUniform4fv(lit->u_pos, CUB_RENDER_MAX_SLOTS, lit->pos);
    glUniform3fv(lit->u_eye, 1, lit->eye);
}

static void attrib(GLint loc, size_t offset)
{
    if (loc < 0)
        return; /* optimised away by the compiler */
    glEnableVertexAttribArray((GLuint)loc);
    glVertexAttribPointer((GLuint)loc, 3, GL_FLOAT, GL_FALSE, sizeof(cub_render_lvtx),
                          (const void *)offset);
}

static void unattrib(GLint loc)
{
    if (loc >= 0)
        glDisableVertexAttribArray((GLuint)loc);
}

void cub_render_lit_draw(cub_render *r, GLuint vbo, GLuint ibo, cub_render_range range)
{
    cub_render_lit *lit = &r->lit;
    if (range.count <= 0)
        return;
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo);
    attrib(lit->a_pos, offsetof(cub_render_lvtx, pos));
    attrib(lit->a_nrm, offsetof(cub_render_lvtx, nrm));
    attrib(lit->a_col, offsetof(cub_render_lvtx, rgb));
    attrib(lit->a_skin, offsetof(cub_render_lvtx, skin));
    glDrawElements(GL_TRIANGLES, range.count, GL_UNSIGNED_SHORT,
                   (const void *)((size_t)range.first * sizeof(GLushort)));
    unattrib(lit->a_pos);
    unattrib(lit->a_nrm);
    unattrib(lit->a_col);
    unattrib(lit->a_skin);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
}

int cub_render_lit_upload(const cub_render_mesh *m, GLuint *vbo, GLuint *ibo)
{
    glGenBuffers(1, vbo);
    glGenBuffers(1, ibo);
    glBindBuffer(GL_ARRAY_BUFFER, *vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)((size_t)m->nv * sizeof m->v[0]), m->v,
                 GL_STATIC_DRAW);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, *ibo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)((size_t)m->ni * sizeof m->idx[0]),
                 m->idx, GL_STATIC_DRAW);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) {
        fprintf(stderr, "render: uploading a mesh failed: GL error 0x%04x\n", e);
        return -1;
    }
    return 0;
}

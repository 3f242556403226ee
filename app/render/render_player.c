/* render_player — the motion player's scene (see cub_render_player_frame):
 * a perspective camera orbiting a target, a grid floor, stick figures or
 * numbered points, everything through the flat batch and the text. */
#include <math.h>
#include <stdio.h>

#include "render_internal.h"

#define FOV_Y_DEG 40.0f
#define NEAR_MM 10.0f
#define FAR_MM 200000.0f
#define FLOOR_CELLS 10
#define RING_SEGMENTS 32
#define LABELS_PER_FLUSH 24 /* the text queue holds four long labels' glyphs */

static const float SKY_TOP[3] = {0.06f, 0.08f, 0.20f};
static const float SKY_LOW[3] = {0.16f, 0.20f, 0.34f};
static const float FLOOR_RGB[3] = {0.26f, 0.31f, 0.27f};
static const float GRID_RGB[3] = {0.42f, 0.50f, 0.44f};
static const float RING_RGB[3] = {1.00f, 0.86f, 0.10f};
static const float LABEL_RGB[3] = {1.00f, 1.00f, 1.00f};

typedef struct cam {
    float eye[3], right[3], up[3], fwd[3];
    float tan_y, aspect;
    float w, h;
} cam;

static float dot3(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void norm3(float v[3])
{
    float n = sqrtf(dot3(v, v));
    if (n > 0.0f) v[0] /= n, v[1] /= n, v[2] /= n;
}

static cam make_cam(const cub_render *r, const cub_render_player_scene *s)
{
    const float rad = 3.14159265f / 180.0f;
    float yaw = s->yaw_deg * rad, pitch = s->pitch_deg * rad, d = s->distance_mm;
    cam c = {.tan_y = tanf(0.5f * FOV_Y_DEG * rad),
             .aspect = (float)r->w / (float)r->h,
             .w = (float)r->w,
             .h = (float)r->h};
    const float *t = s->target_mm;
    c.eye[0] = t[0] + d * cosf(pitch) * sinf(yaw);
    c.eye[1] = t[1] + d * sinf(pitch);
    c.eye[2] = t[2] + d * cosf(pitch) * cosf(yaw);
    for (int i = 0; i < 3; i++)
        c.fwd[i] = t[i] - c.eye[i];
    norm3(c.fwd);
    /* right = fwd x (0, 1, 0), up = right x fwd */
    c.right[0] = -c.fwd[2], c.right[1] = 0.0f, c.right[2] = c.fwd[0];
    norm3(c.right);
    c.up[0] = c.right[1] * c.fwd[2] - c.right[2] * c.fwd[1];
    c.up[1] = c.right[2] * c.fwd[0] - c.right[0] * c.fwd[2];
    c.up[2] = c.right[0] * c.fwd[1] - c.right[1] * c.fwd[0];
    return c;
}

/* World mm to pixels (origin bottom-left) and a depth in -1..1; 0 when the
 * point is behind the near plane or not a number. */
static int project(const cam *c, const float p[3], float out[3])
{
    float v[3] = {p[0] - c->eye[0], p[1] - c->eye[1], p[2] - c->eye[2]};
    float z = dot3(v, c->fwd);
    if (!(z > NEAR_MM) || !isfinite(p[0])) return 0;
    float x = dot3(v, c->right) / (z * c->tan_y * c->aspect), y = dot3(v, c->up) / (z * c->tan_y);
    out[0] = 0.5f * (x + 1.0f) * c->w;
    out[1] = 0.5f * (y + 1.0f) * c->h;
    /* a + b / z, as a perspective projection's depth: affine on the
     * screen, so GL's interpolation along a long bone stays true */
    out[2] = (FAR_MM + NEAR_MM) / (FAR_MM - NEAR_MM) -
             2.0f * FAR_MM * NEAR_MM / ((FAR_MM - NEAR_MM) * z);
    return out[2] < 1.0f;
}

static cub_render_vtx px_vtx(const cub_render *r, const float p[3], const float rgb[3])
{
    cub_render_vtx v = cub_render_px_vtx(r, p[0], p[1], rgb, 1.0f);
    v.z = p[2];
    return v;
}

/* A screen-space band of half-width hw px between two projected points. */
static void band(cub_render *r, const float a[3], const float b[3], float hw, const float rgb[3])
{
    float dx = b[0] - a[0], dy = b[1] - a[1], len = sqrtf(dx * dx + dy * dy);
    if (len < 1e-3f) return;
    float nx = -dy / len * hw, ny = dx / len * hw;
    float q[4][3] = {{a[0] + nx, a[1] + ny, a[2]},
                     {a[0] - nx, a[1] - ny, a[2]},
                     {b[0] - nx, b[1] - ny, b[2]},
                     {b[0] + nx, b[1] + ny, b[2]}};
    cub_render_batch_tri(&r->batch, (cub_render_vtx[3]){px_vtx(r, q[0], rgb), px_vtx(r, q[1], rgb),
                                                        px_vtx(r, q[2], rgb)});
    cub_render_batch_tri(&r->batch, (cub_render_vtx[3]){px_vtx(r, q[0], rgb), px_vtx(r, q[2], rgb),
                                                        px_vtx(r, q[3], rgb)});
}

static float depth_of(const cam *c, const float p[3])
{
    float v[3] = {p[0] - c->eye[0], p[1] - c->eye[1], p[2] - c->eye[2]};
    return dot3(v, c->fwd);
}

/* A world segment as a band, the part in front of the camera (a floor
 * line runs past it). */
static void segment(cub_render *r, const cam *c, const float a[3], const float b[3], float hw,
                    const float rgb[3])
{
    float za = depth_of(c, a), zb = depth_of(c, b), near = 2.0f * NEAR_MM, ca[3], cb[3];
    if (!(za > near) && !(zb > near)) return;
    for (int i = 0; i < 3; i++)
        ca[i] = a[i], cb[i] = b[i];
    float *behind = za > near ? (zb > near ? NULL : cb) : ca;
    if (behind) { /* move the end behind onto the near plane */
        float t = (near - za) / (zb - za);
        for (int i = 0; i < 3; i++)
            behind[i] = a[i] + t * (b[i] - a[i]);
    }
    float pa[3], pb[3];
    if (project(c, ca, pa) && project(c, cb, pb)) band(r, pa, pb, hw, rgb);
}

/* A disc facing the camera at a projected point, pulled a hair nearer. */
static void dot(cub_render *r, const float p[3], float radius, const float rgb[3])
{
    float centre[3] = {p[0], p[1], p[2] - 1e-4f};
    for (int i = 0; i < 16; i++) {
        float a0 = 6.2831853f * (float)i / 16, a1 = 6.2831853f * (float)(i + 1) / 16;
        float p0[3] = {p[0] + radius * cosf(a0), p[1] + radius * sinf(a0), centre[2]};
        float p1[3] = {p[0] + radius * cosf(a1), p[1] + radius * sinf(a1), centre[2]};
        cub_render_batch_tri(
            &r->batch,
            (cub_render_vtx[3]){px_vtx(r, centre, rgb), px_vtx(r, p0, rgb), px_vtx(r, p1, rgb)});
    }
}

static void floor_grid(cub_render *r, const cam *c, float side)
{
    float h = 0.5f * side, step = side / FLOOR_CELLS;
    for (int i = 0; i < FLOOR_CELLS; i++)
        for (int k = 0; k < FLOOR_CELLS; k++) {
            float x0 = -h + i * step, z0 = -h + k * step;
            float w[4][3] = {
                {x0, -2, z0}, {x0 + step, -2, z0}, {x0 + step, -2, z0 + step}, {x0, -2, z0 + step}};
            float p[4][3];
            if (!project(c, w[0], p[0]) || !project(c, w[1], p[1]) || !project(c, w[2], p[2]) ||
                !project(c, w[3], p[3]))
                continue;
            cub_render_batch_tri(&r->batch, (cub_render_vtx[3]){px_vtx(r, p[0], FLOOR_RGB),
                                                                px_vtx(r, p[1], FLOOR_RGB),
                                                                px_vtx(r, p[2], FLOOR_RGB)});
            cub_render_batch_tri(&r->batch, (cub_render_vtx[3]){px_vtx(r, p[0], FLOOR_RGB),
                                                                px_vtx(r, p[2], FLOOR_RGB),
                                                                px_vtx(r, p[3], FLOOR_RGB)});
        }
    for (int i = 0; i <= FLOOR_CELLS; i++) {
        float u = -h + i * step;
        segment(r, c, (const float[3]){u, 0, -h}, (const float[3]){u, 0, h}, 1.0f, GRID_RGB);
        segment(r, c, (const float[3]){-h, 0, u}, (const float[3]){h, 0, u}, 1.0f, GRID_RGB);
    }
}

static void ring(cub_render *r, const cam *c, const float at[2], float radius)
{
    for (int i = 0; i < RING_SEGMENTS; i++) {
        float a0 = 6.2831853f * (float)i / RING_SEGMENTS;
        float a1 = 6.2831853f * (float)(i + 1) / RING_SEGMENTS;
        segment(r, c, (const float[3]){at[0] + radius * cosf(a0), 1, at[1] + radius * sinf(a0)},
                (const float[3]){at[0] + radius * cosf(a1), 1, at[1] + radius * sinf(a1)},
                0.004f * c->h, RING_RGB);
    }
}

static void labels(cub_render *r, const cam *c, const cub_render_player_figure *f)
{
    static cub_render_label label; /* laid out again per number: a few glyphs */
    char num[16];
    int queued = 0;
    for (int j = 0; j < f->joint_count; j++) {
        float p[3];
        if (!project(c, f->world_xyz_mm + 3 * j, p)) continue;
        snprintf(num, sizeof num, "%d", j);
        cub_render_text_layout(r, &label, num);
        cub_render_text_draw(r, &label, p[0] + 0.008f * c->h, p[1] + 0.004f * c->h, 0.22f,
                             LABEL_RGB);
        if (++queued % LABELS_PER_FLUSH == 0) cub_render_text_flush(r);
    }
    cub_render_text_flush(r);
}

static void figure(cub_render *r, const cam *c, const cub_render_player_figure *f, int points)
{
    points |= !f->parent;
    const float *xyz = f->world_xyz_mm;
    if (f->parent && !points)
        for (int j = 0; j < f->joint_count; j++)
            if (f->parent[j] >= 0)
                segment(r, c, xyz + 3 * f->parent[j], xyz + 3 * j, 0.005f * c->h, f->rgb);
    float radius = (points ? 0.007f : 0.006f) * c->h;
    radius = radius < 2.5f ? 2.5f : radius; /* visible on a small frame too */
    for (int j = 0; j < f->joint_count; j++) {
        float p[3];
        if (project(c, xyz + 3 * j, p)) dot(r, p, radius, f->rgb);
    }
}

static int scene_ok(const cub_render_player_scene *s)
{
    if (!s || s->figure_count < 0 || (s->figure_count && !s->figures) || !(s->distance_mm > 0.0f) ||
        !isfinite(s->yaw_deg) || !(fabsf(s->pitch_deg) < 89.5f) || !(s->floor_mm >= 0.0f) ||
        !isfinite(s->target_mm[0] + s->target_mm[1] + s->target_mm[2]))
        return 0;
    for (int i = 0; i < s->figure_count; i++) {
        const cub_render_player_figure *f = &s->figures[i];
        if (f->joint_count < 0 || f->joint_count > CUB_RENDER_PLAYER_MAX_POINTS ||
            (f->joint_count && !f->world_xyz_mm))
            return 0;
        for (int j = 0; f->parent && j < f->joint_count; j++)
            if (f->parent[j] >= j || f->parent[j] < -1) return 0;
    }
    return 1;
}

cub_err cub_render_player_frame(cub_render *r, const cub_render_player_scene *s)
{
    if (!r || !scene_ok(s)) return CUB_ERR_ARG;
    glViewport(r->x0, r->y0, r->w, r->h);
    glScissor(r->x0, r->y0, r->w, r->h);
    glEnable(GL_SCISSOR_TEST);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClearDepthf(1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDisable(GL_DEPTH_TEST);
    cub_render_batch_rect_px(r, 0, 0, (float)r->w, (float)r->h, SKY_TOP, SKY_LOW);
    cub_render_batch_draw(r);
    cam c = make_cam(r, s);
    if (s->floor_mm > 0.0f) /* under everything: drawn first, no depth */
        floor_grid(r, &c, s->floor_mm);
    cub_render_batch_draw(r);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    for (int i = 0; i < s->figure_count; i++) {
        if (s->figures[i].selected) ring(r, &c, s->figures[i].ground_mm, 350.0f);
        figure(r, &c, &s->figures[i], s->points);
        cub_render_batch_draw(r); /* one figure fills most of the batch */
    }
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    for (int i = 0; i < s->figure_count; i++)
        if (s->points || !s->figures[i].parent) /* markers are always numbered points */
            labels(r, &c, &s->figures[i]);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) {
        fprintf(stderr, "render: player frame failed: GL error 0x%04x\n", e);
        return CUB_ERR_DEVICE;
    }
    return CUB_OK;
}

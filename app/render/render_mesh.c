/* render_mesh — the shape builders. Every shape is a grid of rings by
 * SEGMENTS around; smooth normals come from the shape's own formula rather
 * than from averaging faces, which keeps the builders short. */
#include "render_mesh.h"

#include <math.h>
#include <stdlib.h>

#define SEGMENTS 20   /* around each ring */
#define LAT_RINGS 12  /* pole to pole on an ellipsoid */
#define CAP_RINGS 6   /* pole to equator on each end of a capsule */
#define BLEND_SHARE 0.3f /* share of a capsule's bone that blends at each end */
#define PI_F 3.14159265f

int cub_render_mesh_init(cub_render_mesh *m, int cap_v, int cap_i)
{
    *m = (cub_render_mesh){.cap_v = cap_v, .cap_i = cap_i};
    m->v = malloc((size_t)cap_v * sizeof m->v[0]);
    m->idx = malloc((size_t)cap_i * sizeof m->idx[0]);
    return m->v && m->idx;
}

void cub_render_mesh_free(cub_render_mesh *m)
{
    free(m->v);
    free(m->idx);
    *m = (cub_render_mesh){0};
}

static void normalize3(float v[3])
{
    float n = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (n < 1e-9f) {
        v[0] = 0, v[1] = 1, v[2] = 0;
        return;
    }
    v[0] /= n, v[1] /= n, v[2] /= n;
}

/* Room for a grid of rings x SEGMENTS vertices; its first vertex index, or
 * -1 when the mesh is full (16-bit indices cap the vertex count too). */
static int grid_begin(cub_render_mesh *m, int rings)
{
    int nv = rings * SEGMENTS, ni = (rings - 1) * SEGMENTS * 6;
    if (m->full || m->nv + nv > m->cap_v || m->nv + nv > 65535 || m->ni + ni > m->cap_i) {
        m->full = 1;
        return -1;
    }
    int first = m->nv;
    for (int k = 0; k + 1 < rings; k++) {
        for (int s = 0; s < SEGMENTS; s++) {
            int s1 = (s + 1) % SEGMENTS;
            int a = first + k * SEGMENTS + s, b = first + k * SEGMENTS + s1;
            int c = a + SEGMENTS, d = b + SEGMENTS;
            GLushort q[6] = {(GLushort)a, (GLushort)b, (GLushort)d,
                             (GLushort)a, (GLushort)d, (GLushort)c};
            for (int i = 0; i < 6; i++)
                m->idx[m->ni++] = q[i];
        }
    }
    return first;
}

static void put(cub_render_mesh *m, const float p[3], const float n[3], const float rgb[3],
                int slot_b, float w_b)
{
    cub_render_lvtx *v = &m->v[m->nv++];
    for (int i = 0; i < 3; i++) {
        v->pos[i] = m->origin[i] + p[i];
        v->nrm[i] = n[i];
        v->rgb[i] = rgb[i];
    }
    normalize3(v->nrm);
    v->skin[0] = (float)m->slot;
    v->skin[1] = (float)(slot_b >= 0 ? slot_b : m->slot);
    v->skin[2] = slot_b >= 0 ? w_b : 0.0f;
}

int cub_render_mesh_room(cub_render_mesh *m, int nv, int ni)
{
    if (m->full || m->nv + nv > m->cap_v || m->nv + nv > 65535 || m->ni + ni > m->cap_i) {
        m->full = 1;
        return -1;
    }
    return m->nv;
}

void cub_render_mesh_vertex(cub_render_mesh *m, const float p[3], const float n[3],
                            const float rgb[3])
{
    put(m, p, n, rgb, -1, 0.0f);
}

void cub_render_mesh_tri(cub_render_mesh *m, int a, int b, int c)
{
    m->idx[m->ni++] = (GLushort)a;
    m->idx[m->ni++] = (GLushort)b;
    m->idx[m->ni++] = (GLushort)c;
}

void cub_render_mesh_ellipsoid(cub_render_mesh *m, const float c[3], const float radii[3],
                               const float rgb[3])
{
    if (grid_begin(m, LAT_RINGS + 1) < 0)
        return;
    for (int k = 0; k <= LAT_RINGS; k++) {
        float phi = -0.5f * PI_F + PI_F * (float)k / LAT_RINGS;
        for (int s = 0; s < SEGMENTS; s++) {
            float th = 2.0f * PI_F * (float)s / SEGMENTS;
            float u[3] = {cosf(phi) * cosf(th), sinf(phi), cosf(phi) * sinf(th)};
            float p[3], n[3];
            for (int i = 0; i < 3; i++) {
                p[i] = c[i] + radii[i] * u[i];
                n[i] = u[i] / radii[i]; /* the gradient of the implicit form */
            }
            put(m, p, n, rgb, -1, 0.0f);
        }
    }
}

/* Two unit vectors perpendicular to the unit vector a and to each other. */
static void basis(const float a[3], float u[3], float v[3])
{
    float t[3] = {0, 0, 1};
    if (fabsf(a[2]) > 0.9f)
        t[0] = 1, t[2] = 0;
    u[0] = a[1] * t[2] - a[2] * t[1];
    u[1] = a[2] * t[0] - a[0] * t[2];
    u[2] = a[0] * t[1] - a[1] * t[0];
    normalize3(u);
    v[0] = a[1] * u[2] - a[2] * u[1];
    v[1] = a[2] * u[0] - a[0] * u[2];
    v[2] = a[0] * u[1] - a[1] * u[0];
}

/* Blend weight toward the neighbour at parameter s along the bone (0 at the
 * joint, 1 at the child; the caps go past both ends): one half at the
 * joint itself, fading to nothing BLEND_SHARE along the bone. */
static float blend_weight(float s)
{
    float w = 0.5f * (1.0f - s / BLEND_SHARE);
    return w < 0.0f ? 0.0f : w > 0.5f ? 0.5f : w;
}

void cub_render_mesh_capsule(cub_render_mesh *m, const float axis[3], float r0, float r1,
                             const float rgb[3], int parent_slot, int child_slot)
{
    float len = sqrtf(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    if (len < 1e-3f || grid_begin(m, 2 * (CAP_RINGS + 1)) < 0)
        return;
    float a[3] = {axis[0] / len, axis[1] / len, axis[2] / len}, u[3], v[3];
    basis(a, u, v);
    for (int k = 0; k < 2 * (CAP_RINGS + 1); k++) {
        int end = k > CAP_RINGS; /* the second half: the end cap */
        int kk = end ? k - CAP_RINGS - 1 : k;
        float phi = 0.5f * PI_F * ((float)kk / CAP_RINGS - (end ? 0.0f : 1.0f));
        float r = end ? r1 : r0, along = end ? len : 0.0f;
        for (int s = 0; s < SEGMENTS; s++) {
            float th = 2.0f * PI_F * (float)s / SEGMENTS;
            float n[3], p[3];
            for (int i = 0; i < 3; i++) {
                n[i] = cosf(phi) * (cosf(th) * u[i] + sinf(th) * v[i]) + sinf(phi) * a[i];
                p[i] = a[i] * along + r * n[i];
            }
            float t = (p[0] * a[0] + p[1] * a[1] + p[2] * a[2]) / len;
            float wp = parent_slot >= 0 ? blend_weight(t) : 0.0f;
            float wc = child_slot >= 0 ? blend_weight(1.0f - t) : 0.0f;
            if (wp > 0.0f)
                put(m, p, n, rgb, parent_slot, wp);
            else
                put(m, p, n, rgb, wc > 0.0f ? child_slot : -1, wc);
        }
    }
}

void cub_render_mesh_tube(cub_render_mesh *m, const float (*pts)[3], int n, float r,
                          const float rgb[3])
{
    if (n < 2 || grid_begin(m, n) < 0)
        return;
    for (int k = 0; k < n; k++) {
        const float *p0 = pts[k > 0 ? k - 1 : 0], *p1 = pts[k + 1 < n ? k + 1 : n - 1];
        float a[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}, u[3], v[3];
        normalize3(a);
        basis(a, u, v);
        for (int s = 0; s < SEGMENTS; s++) {
            float th = 2.0f * PI_F * (float)s / SEGMENTS;
            float nn[3], p[3];
            for (int i = 0; i < 3; i++) {
                nn[i] = cosf(th) * u[i] + sinf(th) * v[i];
                p[i] = pts[k][i] + r * nn[i];
            }
            put(m, p, nn, rgb, -1, 0.0f);
        }
    }
    const float radii[3] = {r, r, r};
    cub_render_mesh_ellipsoid(m, pts[0], radii, rgb);
    cub_render_mesh_ellipsoid(m, pts[n - 1], radii, rgb);
}

void cub_render_mesh_lathe(cub_render_mesh *m, const float base[3], const float (*prof)[2],
                           int n, const float rgb[3])
{
    if (n < 2 || grid_begin(m, n) < 0)
        return;
    for (int k = 0; k < n; k++) {
        /* The normal is the profile's slope turned outward. */
        const float *q0 = prof[k > 0 ? k - 1 : 0], *q1 = prof[k + 1 < n ? k + 1 : n - 1];
        float dr = q1[0] - q0[0], dy = q1[1] - q0[1];
        for (int s = 0; s < SEGMENTS; s++) {
            float th = 2.0f * PI_F * (float)s / SEGMENTS;
            float c = cosf(th), sn = sinf(th);
            float p[3] = {base[0] + prof[k][0] * c, base[1] + prof[k][1], base[2] + prof[k][0] * sn};
            float nn[3] = {dy * c, -dr, dy * sn};
            put(m, p, nn, rgb, -1, 0.0f);
        }
    }
}

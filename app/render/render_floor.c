/* render_floor — the forest floor's meshes (render_floor.h). */
#include "render_floor.h"

#include <math.h>

#define PI_F 3.14159265f
#define LOG_SEGMENTS 16
#define ROCK_SEGMENTS 7

static const float BARK_RGB[3] = {0.45f, 0.30f, 0.18f};
static const float CUT_RGB[3] = {0.82f, 0.66f, 0.44f};  /* the sawn ends */
static const float STONE_RGB[3] = {0.58f, 0.58f, 0.56f};

static float mm(cub_q16 q)
{
    return (float)q / 65536.0f;
}

static cub_q16 q16(float v)
{
    return (cub_q16)lroundf(v * 65536.0f);
}

float cub_render_floor_y(const cub_gait_terrain *t, float x_mm, float z_mm)
{
    return mm(cub_gait_ground_height(t, q16(x_mm), q16(z_mm)));
}

/* Where the vertex lines run along one axis: the grid's samples and
 * CUB_RENDER_FLOOR_SUB steps between them, and one line past each end. */
static int lines(int32_t origin, int32_t cell, int n, float *out)
{
    int k = 0;
    out[k++] = (float)origin - CUB_RENDER_FLOOR_BEYOND_MM;
    for (int i = 0; i < (n - 1) * CUB_RENDER_FLOOR_SUB; i++)
        out[k++] = (float)origin + (float)cell * (float)i / CUB_RENDER_FLOOR_SUB;
    float last = (float)origin + (float)cell * (float)(n - 1);
    out[k++] = last;
    out[k++] = last + CUB_RENDER_FLOOR_BEYOND_MM;
    return k;
}

/* The ground's normal at (x, z) from the heights a quarter cell around. */
static void ground_normal(const cub_gait_terrain *t, float d, float x, float z, float n[3])
{
    n[0] = (cub_render_floor_y(t, x - d, z) - cub_render_floor_y(t, x + d, z)) / (2.0f * d);
    n[1] = 1.0f;
    n[2] = (cub_render_floor_y(t, x, z - d) - cub_render_floor_y(t, x, z + d)) / (2.0f * d);
}

void cub_render_floor_ground(cub_render_mesh *m, const cub_floor *f, const cub_gait_terrain *t,
                             const float rgb[3])
{
    float xs[CUB_RENDER_FLOOR_MAX_LINES], zs[CUB_RENDER_FLOOR_MAX_LINES];
    int nx = lines(f->origin_x_mm, f->cell_mm, f->nx, xs);
    int nz = lines(f->origin_z_mm, f->cell_mm, f->nz, zs);
    int first = cub_render_mesh_room(m, nx * nz, (nx - 1) * (nz - 1) * 6);
    if (first < 0) return;
    const float d = 0.25f * (float)f->cell_mm;
    for (int j = 0; j < nz; j++)
        for (int i = 0; i < nx; i++) {
            float p[3] = {xs[i], cub_render_floor_y(t, xs[i], zs[j]) - CUB_RENDER_FLOOR_DROP_MM,
                          zs[j]}, n[3];
            ground_normal(t, d, xs[i], zs[j], n);
            cub_render_mesh_vertex(m, p, n, rgb);
        }
    for (int j = 0; j + 1 < nz; j++)
        for (int i = 0; i + 1 < nx; i++) {
            int a = first + j * nx + i, b = a + 1, c = a + nx, e = c + 1;
            cub_render_mesh_tri(m, a, c, e);
            cub_render_mesh_tri(m, a, e, b);
        }
}

/* A point of a log's surface: ring s of LOG_SEGMENTS around its axis at
 * `along` (-1 or +1 end), centre c, half length hl, radius r. */
static void log_point(const float c[3], int along_x, float hl, float r, float along, int s,
                      float p[3], float n[3])
{
    float th = 2.0f * PI_F * (float)s / LOG_SEGMENTS, cy = cosf(th), sy = sinf(th);
    n[0] = along_x ? 0.0f : cy;
    n[1] = sy;
    n[2] = along_x ? cy : 0.0f;
    p[0] = c[0] + (along_x ? along * hl : r * cy);
    p[1] = c[1] + r * sy;
    p[2] = c[2] + (along_x ? r * cy : along * hl);
}

/* A cylinder lying along x or z: the bark, and the two sawn ends as fans. */
static void log_mesh(cub_render_mesh *m, const cub_floor_thing *th, float base)
{
    int along_x = th->half_x_mm >= th->half_z_mm;
    float hl = (float)(along_x ? th->half_x_mm : th->half_z_mm), r = 0.5f * (float)th->height_mm;
    float c[3] = {(float)th->x_mm, base + r, (float)th->z_mm};
    const int S = LOG_SEGMENTS;
    int first = cub_render_mesh_room(m, 4 * S + 2, 12 * S);
    if (first < 0) return;
    for (int e = 0; e < 2; e++) /* bark rings at both ends */
        for (int s = 0; s < S; s++) {
            float p[3], n[3];
            log_point(c, along_x, hl, r, e ? 1.0f : -1.0f, s, p, n);
            cub_render_mesh_vertex(m, p, n, BARK_RGB);
        }
    for (int e = 0; e < 2; e++) { /* the ends: a centre and a ring facing out */
        float sign = e ? 1.0f : -1.0f, n[3] = {along_x ? sign : 0.0f, 0.0f, along_x ? 0.0f : sign};
        float p[3] = {c[0] + n[0] * hl, c[1], c[2] + n[2] * hl}, q[3], unused[3];
        cub_render_mesh_vertex(m, p, n, CUT_RGB);
        for (int s = 0; s < S; s++) {
            log_point(c, along_x, hl, r, sign, s, q, unused);
            cub_render_mesh_vertex(m, q, n, CUT_RGB);
        }
    }
    for (int s = 0; s < S; s++) {
        int s1 = (s + 1) % S, a = first + s, b = first + s1;
        cub_render_mesh_tri(m, a, b, b + S);
        cub_render_mesh_tri(m, a, b + S, a + S);
        for (int e = 0; e < 2; e++) {
            int centre = first + 2 * S + e * (S + 1);
            cub_render_mesh_tri(m, centre, centre + 1 + s, centre + 1 + s1);
        }
    }
}

/* A fixed lumpiness per corner (0.74 .. 1 of the half side): every stone
 * looks hewn, the same on every frame and machine, and stays within the
 * footprint the planner steps around. */
static float lump(int k, int s)
{
    static const float L[] = {0.91f, 0.78f, 0.98f, 0.85f, 0.74f, 0.95f, 0.82f, 1.0f, 0.76f, 0.88f};
    return L[(3 * k + 7 * s) % 10];
}

/* One flat-shaded triangle: its own three vertices with the face normal,
 * turned away from the stone's heart. */
static void facet(cub_render_mesh *m, const float heart[3], const float a[3], const float b[3],
                  const float c[3])
{
    float u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    float v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    float n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    float out = 0.0f;
    for (int i = 0; i < 3; i++)
        out += n[i] * ((a[i] + b[i] + c[i]) / 3.0f - heart[i]);
    if (out < 0.0f) n[0] = -n[0], n[1] = -n[1], n[2] = -n[2];
    int first = cub_render_mesh_room(m, 3, 3);
    if (first < 0) return;
    cub_render_mesh_vertex(m, a, n, STONE_RGB);
    cub_render_mesh_vertex(m, b, n, STONE_RGB);
    cub_render_mesh_vertex(m, c, n, STONE_RGB);
    cub_render_mesh_tri(m, first, first + 1, first + 2);
}

/* A low-poly rock: a sunken base ring, a shoulder ring turned half a step,
 * and its top exactly at the terrain box's top. */
static void rock_mesh(cub_render_mesh *m, const cub_floor_thing *th, float base)
{
    const int S = ROCK_SEGMENTS;
    float h = (float)th->height_mm, rx = (float)th->half_x_mm, rz = (float)th->half_z_mm;
    float ring[2][ROCK_SEGMENTS][3], top[3] = {(float)th->x_mm, base + h, (float)th->z_mm};
    const float heart[3] = {top[0], base + 0.3f * h, top[2]};
    const float share[2] = {1.0f, 0.75f}, lift[2] = {-0.15f, 0.6f};
    for (int k = 0; k < 2; k++)
        for (int s = 0; s < S; s++) {
            float th_s = 2.0f * PI_F * ((float)s + 0.5f * (float)k) / S, l = lump(k, s) * share[k];
            ring[k][s][0] = top[0] + l * rx * cosf(th_s);
            ring[k][s][1] = base + lift[k] * h;
            ring[k][s][2] = top[2] + l * rz * sinf(th_s);
        }
    for (int s = 0; s < S; s++) {
        int s1 = (s + 1) % S;
        facet(m, heart, ring[0][s], ring[1][s], ring[0][s1]);
        facet(m, heart, ring[0][s1], ring[1][s], ring[1][s1]);
        facet(m, heart, ring[1][s], top, ring[1][s1]);
    }
}

void cub_render_floor_thing(cub_render_mesh *m, const cub_floor *f, int k,
                            const cub_gait_terrain *t)
{
    const cub_floor_thing *th = &f->things[k];
    if (k >= t->obstacle_count) return;
    float base = mm(t->obstacles[k].min_mm.y);
    if (th->kind == CUB_FLOOR_LOG) log_mesh(m, th, base);
    else rock_mesh(m, th, base);
}

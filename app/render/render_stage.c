/* render_stage — the forest the bear dances in: a meadow, round and pointed
 * cartoon trees behind the bear and a few bushes, all static and built once
 * at create (one index range, one draw a frame). The sky is the flat
 * gradient drawn before it. Coordinates: mm, the bear's spot at the origin,
 * the camera on +z looking at it. On the flat meadow the stage follows the
 * figure's root the way the camera does, so it stands still on screen; on
 * a forest floor (cub_render_set_floor) the ground has its place, so the
 * stage stays put, the rolling ground with its log and stones is drawn
 * instead of the disc, and the trees and bushes stand on it. */
#include "render_internal.h"

#define GROUND_RADIUS_MM 30000.0f
#define STAGE_VERTS 12000
#define STAGE_INDICES 66000
/* With a floor: its heightfield and the things on it (at most 12 x 63
 * vertices and 12 x 192 indices). */
#define FLOOR_LINES CUB_RENDER_FLOOR_MAX_LINES
#define FLOOR_VERTS (STAGE_VERTS + FLOOR_LINES * FLOOR_LINES + 1000)
#define FLOOR_INDICES (STAGE_INDICES + (FLOOR_LINES - 1) * (FLOOR_LINES - 1) * 6 + 3000)

static const float GRASS_RGB[3] = {0.50f, 0.76f, 0.35f};
static const float TRUNK_RGB[3] = {0.55f, 0.36f, 0.20f};
static const float PINE_RGB[3] = {0.16f, 0.52f, 0.30f};
static const float LEAF_RGB[3] = {0.36f, 0.70f, 0.25f};
static const float BUSH_RGB[3] = {0.28f, 0.62f, 0.28f};

/* A tree: where it stands (x, z mm), how tall, and round (0) or pine (1). */
static const struct {
    float x, z, height;
    int pine;
} TREES[] = {
    {-1700, -1600, 1900, 0}, {1800, -2000, 2300, 1}, {-3000, -3200, 2600, 1},
    {3200, -3400, 2200, 0},  {-600, -4800, 2500, 0}, {1100, -5200, 2900, 1},
    {-4400, -1800, 2100, 0}, {4600, -1500, 2400, 1}, {-2300, -6200, 3000, 1},
    {3000, -6600, 2700, 0},
};
#define TREE_COUNT ((int)(sizeof TREES / sizeof TREES[0]))

float cub_render_stage_ground_y(const cub_render *r, float x_mm, float z_mm)
{
    return r->floor ? cub_render_floor_y(&r->terrain, x_mm, z_mm) : 0.0f;
}

static void ground(cub_render *r, cub_render_mesh *m)
{
    if (r->floor) {
        cub_render_floor_ground(m, r->floor, &r->terrain, GRASS_RGB);
        for (int k = 0; k < r->floor->thing_count; k++)
            cub_render_floor_thing(m, r->floor, k, &r->terrain);
        return;
    }
    /* A wide flat disc a hair below the feet, so soles never flicker. */
    const float prof[2][2] = {{GROUND_RADIUS_MM, 0.0f}, {0.0f, 0.0f}};
    const float base[3] = {0.0f, -CUB_RENDER_FLOOR_DROP_MM, 0.0f};
    cub_render_mesh_lathe(m, base, prof, 2, GRASS_RGB);
}

/* A tree standing on the ground at (x, y, z). */
static void tree(cub_render_mesh *m, float x, float y, float z, float h, int pine)
{
    const float base[3] = {x, y, z};
    const float trunk[3][2] = {{0.06f * h, 0.0f}, {0.05f * h, 0.40f * h}, {0.0f, 0.40f * h}};
    cub_render_mesh_lathe(m, base, trunk, 3, TRUNK_RGB);
    if (pine) {
        /* Two stacked cones, the upper one smaller: a cartoon fir. */
        const float low[3][2] = {{0.30f * h, 0.28f * h}, {0.0f, 0.78f * h}, {0.0f, 0.78f * h}};
        const float high[3][2] = {{0.22f * h, 0.55f * h}, {0.0f, 1.0f * h}, {0.0f, 1.0f * h}};
        const float flat_low[2][2] = {{0.0f, 0.28f * h}, {0.30f * h, 0.28f * h}};
        cub_render_mesh_lathe(m, base, flat_low, 2, PINE_RGB);
        cub_render_mesh_lathe(m, base, low, 3, PINE_RGB);
        cub_render_mesh_lathe(m, base, high, 3, PINE_RGB);
    } else {
        /* A cluster of three balls: a round leafy crown. */
        const float c0[3] = {x, y + 0.66f * h, z}, r0[3] = {0.30f * h, 0.26f * h, 0.30f * h};
        const float c1[3] = {x - 0.18f * h, y + 0.52f * h, z + 0.05f * h};
        const float c2[3] = {x + 0.19f * h, y + 0.55f * h, z + 0.03f * h};
        const float r1[3] = {0.19f * h, 0.17f * h, 0.19f * h};
        cub_render_mesh_ellipsoid(m, c0, r0, LEAF_RGB);
        cub_render_mesh_ellipsoid(m, c1, r1, LEAF_RGB);
        cub_render_mesh_ellipsoid(m, c2, r1, LEAF_RGB);
    }
}

static void bushes(const cub_render *r, cub_render_mesh *m)
{
    const float spots[][2] = {{-1100, -700}, {1250, -900}, {-2300, -300}};
    for (int i = 0; i < 3; i++) {
        const float rad[3] = {260.0f, 190.0f, 220.0f};
        float c[3] = {spots[i][0], cub_render_stage_ground_y(r, spots[i][0], spots[i][1]),
                      spots[i][1]};
        cub_render_mesh_ellipsoid(m, c, rad, BUSH_RGB);
    }
}

cub_err cub_render_stage_init(cub_render *r)
{
    cub_render_mesh m;
    int floor = r->floor != NULL;
    glDeleteBuffers(1, &r->stage_vbo); /* name 0 (none yet) is a no-op */
    glDeleteBuffers(1, &r->stage_ibo);
    r->stage_vbo = r->stage_ibo = 0;
    r->stage = (cub_render_range){0, 0};
    if (!cub_render_mesh_init(&m, floor ? FLOOR_VERTS : STAGE_VERTS,
                              floor ? FLOOR_INDICES : STAGE_INDICES)) {
        cub_render_mesh_free(&m);
        return CUB_ERR_NOMEM;
    }
    m.slot = 0;
    ground(r, &m);
    for (int i = 0; i < TREE_COUNT; i++) {
        float y = cub_render_stage_ground_y(r, TREES[i].x, TREES[i].z);
        tree(&m, TREES[i].x, y, TREES[i].z, TREES[i].height, TREES[i].pine);
    }
    bushes(r, &m);
    int bad = m.full || cub_render_lit_upload(&m, &r->stage_vbo, &r->stage_ibo);
    r->stage = (cub_render_range){0, m.ni};
    cub_render_mesh_free(&m);
    return bad ? CUB_ERR_DEVICE : CUB_OK; /* full: the sizes above are too small */
}

void cub_render_stage_draw(cub_render *r)
{
    cub_render_lit_draw(r, r->stage_vbo, r->stage_ibo, r->stage);
}

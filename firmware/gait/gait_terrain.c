/* gait — the terrain (SEEDS.md § 003, "Terrain"): flat, sloped, rolling
 * (a heightfield), and box obstacles added at run time. Q16.16 mm. */
#include "cub/gait.h"

static void reset(cub_gait_terrain *t, cub_gait_ground g, cub_q16 base_mm)
{
    *t = (cub_gait_terrain){0};
    t->ground = g;
    t->base_mm = base_mm;
}

void cub_gait_terrain_flat(cub_gait_terrain *t, cub_q16 base_mm)
{
    reset(t, CUB_GAIT_FLAT, base_mm);
}

void cub_gait_terrain_slope(cub_gait_terrain *t, cub_q16 base_mm, cub_q16 grad_x, cub_q16 grad_z)
{
    reset(t, CUB_GAIT_SLOPE, base_mm);
    t->grad_x = grad_x;
    t->grad_z = grad_z;
}

cub_err cub_gait_terrain_rolling(cub_gait_terrain *t, cub_q16 *heights_mm, int nx, int nz,
                                 cub_q16 cell_mm, cub_q16 amp_mm, cub_q16 wave_mm)
{
    if (!t || !heights_mm || nx < 2 || nz < 2 || cell_mm <= 0 || wave_mm <= 0) return CUB_ERR_ARG;
    reset(t, CUB_GAIT_ROLLING, 0);
    t->heights_mm = heights_mm;
    t->nx = nx;
    t->nz = nz;
    t->cell_mm = cell_mm;
    for (int j = 0; j < nz; j++) {
        cub_q16 az =
            cub_fx_mul(CUB_Q16_TWO_PI, cub_fx_div(cub_fx_mul(CUB_Q16_INT(j), cell_mm), wave_mm));
        for (int i = 0; i < nx; i++) {
            cub_q16 ax = cub_fx_mul(CUB_Q16_TWO_PI,
                                    cub_fx_div(cub_fx_mul(CUB_Q16_INT(i), cell_mm), wave_mm));
            heights_mm[j * nx + i] = cub_fx_mul(amp_mm, cub_fx_mul(cub_fx_sin(ax), cub_fx_cos(az)));
        }
    }
    return CUB_OK;
}

cub_err cub_gait_terrain_add(cub_gait_terrain *t, cub_gait_box box)
{
    if (!t || box.max_mm.x <= box.min_mm.x || box.max_mm.z <= box.min_mm.z ||
        box.max_mm.y <= box.min_mm.y)
        return CUB_ERR_ARG;
    if (t->obstacle_count >= CUB_GAIT_MAX_OBSTACLES) return CUB_ERR_FULL;
    t->obstacles[t->obstacle_count++] = box;
    return CUB_OK;
}

/* Grid coordinate of a position along one axis: the cell index in *i and
 * the fraction across it, clamped to the grid. */
static cub_q16 grid_coord(cub_q16 pos, cub_q16 origin, cub_q16 cell, int n, int *i)
{
    cub_q16 u = cub_fx_clamp(cub_fx_div(cub_fx_sub(pos, origin), cell), 0, CUB_Q16_INT(n - 1));
    *i = u >> 16;
    if (*i >= n - 1) {
        *i = n - 2;
        return CUB_Q16_ONE;
    }
    return u & 0xffff;
}

static cub_q16 rolling_height(const cub_gait_terrain *t, cub_q16 x, cub_q16 z)
{
    int i, j;
    cub_q16 fx = grid_coord(x, t->origin_x_mm, t->cell_mm, t->nx, &i);
    cub_q16 fz = grid_coord(z, t->origin_z_mm, t->cell_mm, t->nz, &j);
    const cub_q16 *row0 = t->heights_mm + j * t->nx, *row1 = row0 + t->nx;
    cub_q16 h0 = cub_fx_lerp(row0[i], row0[i + 1], fx);
    cub_q16 h1 = cub_fx_lerp(row1[i], row1[i + 1], fx);
    return cub_fx_lerp(h0, h1, fz);
}

cub_q16 cub_gait_ground_height(const cub_gait_terrain *t, cub_q16 x_mm, cub_q16 z_mm)
{
    switch (t->ground) {
    case CUB_GAIT_SLOPE:
        return cub_fx_add(t->base_mm,
                          cub_fx_add(cub_fx_mul(t->grad_x, x_mm), cub_fx_mul(t->grad_z, z_mm)));
    case CUB_GAIT_ROLLING: return t->heights_mm ? rolling_height(t, x_mm, z_mm) : 0;
    case CUB_GAIT_FLAT:
    default: return t->base_mm;
    }
}

cub_q16 cub_gait_height(const cub_gait_terrain *t, cub_q16 x_mm, cub_q16 z_mm)
{
    cub_q16 h = cub_gait_ground_height(t, x_mm, z_mm);
    for (int k = 0; k < t->obstacle_count; k++) {
        const cub_gait_box *b = &t->obstacles[k];
        bool over = x_mm >= b->min_mm.x && x_mm <= b->max_mm.x && z_mm >= b->min_mm.z &&
                    z_mm <= b->max_mm.z;
        if (over && b->max_mm.y > h) h = b->max_mm.y;
    }
    return h;
}

bool cub_gait_terrain_is_flat(const cub_gait_terrain *t)
{
    return t->ground == CUB_GAIT_FLAT && t->obstacle_count == 0;
}

/* floor — the checks on a floor and the one terrain made of it. */
#include "cub/floor.h"

static int within(int32_t v, int32_t lo, int32_t hi)
{
    return v >= lo && v <= hi;
}

static int grid_ok(const cub_floor *f)
{
    const int32_t e = CUB_FLOOR_EXTENT_MM;
    if (!within(f->nx, 2, CUB_FLOOR_MAX_SIDE) || !within(f->nz, 2, CUB_FLOOR_MAX_SIDE)) return 0;
    if (!within(f->cell_mm, CUB_FLOOR_MIN_CELL_MM, CUB_FLOOR_MAX_CELL_MM)) return 0;
    if (!within(f->origin_x_mm, -e, e) || !within(f->origin_z_mm, -e, e)) return 0;
    /* 64 bits: 47 cells of 5 m is past the extent but not past int32 */
    int64_t far_x = (int64_t)f->origin_x_mm + (int64_t)(f->nx - 1) * f->cell_mm;
    int64_t far_z = (int64_t)f->origin_z_mm + (int64_t)(f->nz - 1) * f->cell_mm;
    return far_x <= e && far_z <= e;
}

static int heights_ok(const cub_floor *f)
{
    const cub_q16 top = CUB_Q16_INT(CUB_FLOOR_MAX_RISE_MM);
    for (int i = 0; i < f->nx * f->nz; i++)
        if (!within(f->heights_mm[i], -top, top)) return 0;
    return 1;
}

static int thing_ok(const cub_floor_thing *t)
{
    const int32_t lo = CUB_FLOOR_MIN_SIZE_MM, hi = CUB_FLOOR_MAX_SIZE_MM;
    const int32_t e = CUB_FLOOR_EXTENT_MM;
    if (t->kind != CUB_FLOOR_LOG && t->kind != CUB_FLOOR_STONE) return 0;
    if (!within(t->x_mm, -e, e) || !within(t->z_mm, -e, e)) return 0;
    if (!within(t->half_x_mm, lo, hi) || !within(t->half_z_mm, lo, hi)) return 0;
    if (!within(t->height_mm, lo, hi)) return 0;
    return within(t->x_mm - t->half_x_mm, -e, e) && within(t->x_mm + t->half_x_mm, -e, e) &&
           within(t->z_mm - t->half_z_mm, -e, e) && within(t->z_mm + t->half_z_mm, -e, e);
}

cub_err cub_floor_check(const cub_floor *f)
{
    if (!f || !grid_ok(f) || !heights_ok(f)) return CUB_ERR_ARG;
    if (!within(f->thing_count, 0, CUB_FLOOR_MAX_THINGS)) return CUB_ERR_ARG;
    for (int k = 0; k < f->thing_count; k++)
        if (!thing_ok(&f->things[k])) return CUB_ERR_ARG;
    return CUB_OK;
}

/* The rolling ground alone: the gait module's ROLLING terrain over the
 * floor's own samples (cub_gait_terrain_rolling would fill them with its
 * hills; these come from the asset). */
static void ground(const cub_floor *f, cub_gait_terrain *t)
{
    *t = (cub_gait_terrain){0};
    t->ground = CUB_GAIT_ROLLING;
    t->heights_mm = f->heights_mm;
    t->nx = f->nx;
    t->nz = f->nz;
    t->cell_mm = CUB_Q16_INT(f->cell_mm);
    t->origin_x_mm = CUB_Q16_INT(f->origin_x_mm);
    t->origin_z_mm = CUB_Q16_INT(f->origin_z_mm);
}

/* The lowest ground under a footprint (a 5 x 5 lattice over it): a thing
 * rests there, sunk into higher ground rather than floating over lower. */
static cub_q16 rest_height(const cub_gait_terrain *t, cub_q16 x, cub_q16 z, cub_q16 hx,
                           cub_q16 hz)
{
    cub_q16 low = cub_gait_ground_height(t, x, z);
    for (int i = -2; i <= 2; i++)
        for (int j = -2; j <= 2; j++) {
            cub_q16 h = cub_gait_ground_height(t, x + i * (hx / 2), z + j * (hz / 2));
            low = h < low ? h : low;
        }
    return low;
}

static cub_gait_box thing_box(const cub_gait_terrain *t, const cub_floor_thing *th)
{
    cub_q16 x = CUB_Q16_INT(th->x_mm), z = CUB_Q16_INT(th->z_mm);
    cub_q16 hx = CUB_Q16_INT(th->half_x_mm), hz = CUB_Q16_INT(th->half_z_mm);
    cub_q16 base = rest_height(t, x, z, hx, hz);
    return (cub_gait_box){.min_mm = {x - hx, base, z - hz},
                          .max_mm = {x + hx, base + CUB_Q16_INT(th->height_mm), z + hz}};
}

cub_err cub_floor_terrain(const cub_floor *f, cub_gait_terrain *t)
{
    if (!t || cub_floor_check(f)) return CUB_ERR_ARG;
    ground(f, t);
    for (int k = 0; k < f->thing_count; k++) {
        cub_err e = cub_gait_terrain_add(t, thing_box(t, &f->things[k]));
        if (e) return e;
    }
    return CUB_OK;
}

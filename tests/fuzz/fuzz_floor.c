/* libFuzzer target: the forest floor reader (cub/floor_file.h) and what
 * the box makes of an accepted floor. The input is the file. A refusal
 * must name the file with a message; an accepted floor must pass
 * cub_floor_check, make a terrain (cub_floor_terrain) whose things stand
 * where the floor says, and a ground mesh (render_floor.c, no GL) whose
 * indices stay within its vertices and whose heights are the terrain's.
 * Seeds: seeds_floor/ (make_seeds.py) and assets/floor. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cub/floor_file.h"
#include "fuzz_tally.h"
#include "render_floor.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check_terrain(const cub_floor *f, const cub_gait_terrain *t)
{
    if (t->obstacle_count != f->thing_count) abort();
    for (int k = 0; k < f->thing_count; k++) {
        const cub_floor_thing *th = &f->things[k];
        const cub_gait_box *b = &t->obstacles[k];
        cub_q16 top = cub_gait_height(t, CUB_Q16_INT(th->x_mm), CUB_Q16_INT(th->z_mm));
        if (b->max_mm.y - b->min_mm.y != CUB_Q16_INT(th->height_mm) || top < b->max_mm.y) abort();
    }
}

static void check_mesh(const cub_floor *f, const cub_gait_terrain *t)
{
    static cub_render_mesh m;
    if (!cub_render_mesh_init(&m, 25000, 130000)) abort();
    cub_render_floor_ground(&m, f, t, (const float[3]){0.5f, 0.7f, 0.3f});
    int ground = m.nv;
    for (int k = 0; k < f->thing_count; k++)
        cub_render_floor_thing(&m, f, k, t);
    if (m.full) abort(); /* the largest floor fits these sizes */
    for (int i = 0; i < m.ni; i++)
        if (m.idx[i] >= m.nv) abort();
    for (int i = 0; i < ground; i++) {
        const float *p = m.v[i].pos;
        float want = cub_render_floor_y(t, p[0], p[2]) - CUB_RENDER_FLOOR_DROP_MM;
        if (!isfinite(p[1]) || fabsf(p[1] - want) > 0.01f) abort();
    }
    cub_render_mesh_free(&m);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static cub_floor f;
    cub_diag d;
    cub_err e = cub_floor_parse((const char *)data, size, "fuzz.floor", &f, &d);
    cub_fuzz_tally("fuzz_floor", !e);
    if (e) {
        if (e != CUB_ERR_FORMAT || strcmp(d.file, "fuzz.floor") != 0 || !d.msg[0]) abort();
        return 0;
    }
    cub_gait_terrain t;
    if (cub_floor_check(&f) || cub_floor_terrain(&f, &t)) abort();
    check_terrain(&f, &t);
    check_mesh(&f, &t);
    return 0;
}

/* libFuzzer target: cubtool gait's terrain file (app/cubtool/
 * gait_terrain_file.c). The input is the file. A refusal names the file
 * with a message; an accepted terrain gives finite heights anywhere, its
 * grid within the storage, its obstacles non-empty. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "../../app/cubtool/gait_tool.h"
#include "fuzz_tally.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check_accepted(const gait_ground *g)
{
    const cub_gait_terrain *t = &g->t;
    if (t->ground == CUB_GAIT_ROLLING &&
        (t->nx < 2 || t->nz < 2 || t->nx > GAIT_GRID || t->nz > GAIT_GRID || t->cell_mm <= 0))
        abort();
    if (t->obstacle_count < 0 || t->obstacle_count > CUB_GAIT_MAX_OBSTACLES) abort();
    for (int i = 0; i < t->obstacle_count; i++)
        if (t->obstacles[i].min_mm.y >= t->obstacles[i].max_mm.y) abort();
    /* Heights are read anywhere without a fault (the sanitizers watch). */
    static const cub_q16 probe[] = {0, CUB_Q16_INT(1234), -CUB_Q16_INT(30000), CUB_Q16_INT(30000)};
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            (void)cub_gait_height(t, probe[i], probe[j]);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static gait_ground g;
    cub_diag d = {0};
    cub_err e = gait_terrain_parse((const char *)data, size, "fuzz.terrain", &g, &d);
    cub_fuzz_tally("fuzz_gait_terrain", !e);
    if (!e) check_accepted(&g);
    else if (e != CUB_ERR_FORMAT || strcmp(d.file, "fuzz.terrain") != 0 || !d.msg[0]) abort();
    return 0;
}

/* libFuzzer target: cubtool evolve's map file (app/evolve/map.c) read from
 * a file as cubtool reads it (cub_evolve_map_load: the bounded reader too),
 * then bound by the correspondence between the bear's skeleton and itself
 * (assets/clips/hello.bvh) and crossed. A map that binds gives pairs inside
 * both skeletons and a meta skeleton that validates. Seeds: seeds_evolve/. */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdlib.h>

#include "cub/evolve.h"
#include "fuzz_bear.h"
#include "fuzz_file.h"
#include "fuzz_tally.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check_pairs(const cub_evolve_corr *c)
{
    for (int i = 0; i < c->pair_count; i++)
        if (c->pair[i].a < 0 || c->pair[i].a >= c->a_count || c->pair[i].b < 0 ||
            c->pair[i].b >= c->b_count)
            abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = cub_fuzz_file("fuzz_evolve_map", "evmap", data, size);
    const cub_io_motion *bear = cub_fuzz_bear();
    static cub_evolve_map map;
    static cub_evolve_corr corr;
    static cub_evolve_meta meta;
    cub_diag d = {0};
    if (cub_evolve_map_load(path, &map, &d) != CUB_OK) {
        cub_fuzz_tally("fuzz_evolve_map", 0);
        if (!d.msg[0]) abort();
        return 0;
    }
    int bound = cub_evolve_correspond(&bear->skel, &bear->skel, &map, &corr, &d) == CUB_OK;
    cub_fuzz_tally("fuzz_evolve_map", bound);
    if (!bound) {
        if (!d.msg[0]) abort();
        return 0;
    }
    check_pairs(&corr);
    if (cub_evolve_crossover(&bear->skel, &bear->skel, &corr, &meta, &d) != CUB_OK) abort();
    if (cub_motion_skeleton_validate(&meta.skel) != CUB_OK) abort();
    return 0;
}

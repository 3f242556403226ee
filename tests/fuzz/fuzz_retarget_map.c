/* libFuzzer target: the retarget mapping table (app/retarget/map.c) read
 * from a file as cubtool reads it (cub_retarget_map_load, so the bounded
 * file reader runs too), then bound to the bear's skeleton on both sides
 * (assets/clips/hello.bvh is a bear BVH). Seeds: the maps in assets/retarget/ and
 * seeds_map/. A table that parses has finite positive weights; one that
 * binds has each link's weights summing to 1 (what the retarget divides
 * by: a sum that overflowed to inf would make them all 0). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "cub/io.h"
#include "cub/retarget.h"
#include "fuzz_bear.h"
#include "fuzz_file.h"
#include "fuzz_tally.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = cub_fuzz_file("fuzz_retarget_map", "map", data, size);
    const cub_io_motion *bear = cub_fuzz_bear();
    static cub_retarget_map map;
    cub_diag d;
    if (cub_retarget_map_load(path, &map, &d) != CUB_OK) {
        cub_fuzz_tally("fuzz_retarget_map", 0);
        if (!d.msg[0]) abort();
        return 0;
    }
    for (int i = 0; i < map.link_count; i++)
        for (int k = 0; k < map.link[i].source_count; k++)
            if (!isfinite(map.link[i].source[k].weight) || !(map.link[i].source[k].weight > 0)) abort();
    int bound = cub_retarget_map_bind(&map, &bear->skel, &bear->skel, &d) == CUB_OK;
    cub_fuzz_tally("fuzz_retarget_map", bound);
    if (!bound) {
        if (!d.msg[0]) abort();
        return 0;
    }
    for (int i = 0; i < map.link_count; i++) {
        double sum = 0;
        for (int k = 0; k < map.link[i].source_count; k++) sum += map.link[i].source[k].weight;
        if (!(fabs(sum - 1) < 1e-6)) abort();
    }
    return 0;
}

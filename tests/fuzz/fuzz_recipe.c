/* libFuzzer target: the clip library's recipe (app/retarget/recipe.c, what
 * `cubtool build` reads) from a file through cub_recipe_load. Seeds:
 * assets/library/recipe.txt. A recipe that parses holds named clips of a
 * known kind with finite times and a speed in 0.1..10. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cub/retarget.h"
#include "fuzz_file.h"
#include "fuzz_tally.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = cub_fuzz_file("fuzz_recipe", "txt", data, size);
    static cub_recipe r;
    cub_diag d;
    int ok = cub_recipe_load(path, &r, &d) == CUB_OK;
    cub_fuzz_tally("fuzz_recipe", ok && r.clip_count > 0);
    if (!ok) {
        if (!d.msg[0] || strcmp(d.file, path) != 0) abort();
        return 0;
    }
    if (r.clip_count < 0 || r.clip_count > CUB_RECIPE_MAX_CLIPS) abort();
    for (int i = 0; i < r.clip_count; i++) {
        const cub_recipe_clip *c = &r.clip[i];
        if (!c->name[0] || (strcmp(c->kind, "dance") && strcmp(c->kind, "coach"))) abort();
        if (!isfinite(c->start_s) || !isfinite(c->end_s) || !isfinite(c->turn_deg)) abort();
        if (!(c->speed >= 0.1 && c->speed <= 10)) abort();
    }
    return 0;
}

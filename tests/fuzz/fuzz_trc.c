/* libFuzzer target: the TRC marker reader (cub/trc.h). The input is the
 * file. A refusal must name the file with a message; an accepted file must
 * hold what its header says: 1..CUB_TRC_MAX_MARKERS named markers, frames
 * within the limit, finite positions, and exactly 0,0,0 where a marker is
 * missing. Seeds: seeds_trc/ (make_seeds.py). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cub/trc.h"
#include "fuzz_tally.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check_accepted(const cub_trc *t)
{
    if (t->markers < 1 || t->markers > CUB_TRC_MAX_MARKERS) abort();
    if (t->frames < 1 || t->frames > CUB_TRC_MAX_FRAMES || !(t->rate > 0)) abort();
    for (int m = 0; m < t->markers; m++)
        if (!t->names[m][0] || strlen(t->names[m]) >= CUB_TRC_NAME_LEN) abort();
    for (size_t i = 0; i < (size_t)t->frames * (size_t)t->markers; i++)
        for (int k = 0; k < 3; k++) {
            float v = t->pos[3 * i + (size_t)k];
            if (!isfinite(t->time[i / (size_t)t->markers]) || (t->present[i] ? 0 : v != 0.0f))
                abort();
        }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    cub_trc t;
    cub_diag d;
    cub_err e = cub_trc_parse((const char *)data, size, "fuzz.trc", &t, &d);
    cub_fuzz_tally("fuzz_trc", !e);
    if (!e) check_accepted(&t);
    else if (e != CUB_ERR_FORMAT || strcmp(d.file, "fuzz.trc") != 0 || !d.msg[0]) abort();
    cub_trc_free(&t);
    return 0;
}

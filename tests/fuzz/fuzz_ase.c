/* libFuzzer target: the ASE reader (cub/ase.h). The input is the file. A
 * refusal must name the file with a message and leave no clip; an accepted
 * file must give a valid skeleton of 1..CUB_MOTION_MAX_JOINTS joints and a
 * clip of at least one frame with a period, unit rotations and the clip
 * pointing at its skeleton. Seeds: seeds_ase/ (make_seeds.py). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cub/ase.h"
#include "fuzz_tally.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check_accepted(const cub_io_motion *m)
{
    const cub_clip *c = &m->clip;
    int jn = m->skel.joint_count;
    if (jn < 1 || jn > CUB_MOTION_MAX_JOINTS || cub_motion_skeleton_validate(&m->skel)) abort();
    if (c->skel != &m->skel || c->frame_count < 1 || c->frame_ns == 0 || !c->rot) abort();
    for (size_t i = 0; i < (size_t)c->frame_count * (size_t)jn; i++) {
        cub_quat q = c->rot[i];
        int64_t n2 = 0;
        const int64_t v[4] = {q.w >> 8, q.x >> 8, q.y >> 8, q.z >> 8};
        for (int k = 0; k < 4; k++)
            n2 += v[k] * v[k];
        if (q.w < 0 || n2 < ((int64_t)1 << 44) * 49 / 50 || n2 > ((int64_t)1 << 44) * 51 / 50)
            abort();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static cub_io_motion m;
    cub_diag d;
    cub_io_desc mm = {1.0};
    cub_err e = cub_ase_parse((const char *)data, size, "fuzz.ase", &mm, &m, &d);
    cub_fuzz_tally("fuzz_ase", !e);
    if (!e) check_accepted(&m);
    else if (e != CUB_ERR_FORMAT || strcmp(d.file, "fuzz.ase") != 0 || !d.msg[0] ||
             m.clip.frame_count)
        abort();
    cub_io_motion_free(&m);
    return 0;
}

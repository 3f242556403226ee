/* The importers' conversions to the firmware's Q2.30 / Q16.16 types, clip
 * allocation and the unit guess. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "io_internal.h"

cub_quat io_quat_to_fx(cub_dq q)
{
    double n = sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    if (!(n > 0) || !isfinite(n)) {
        cub_quat id = {CUB_QUAT_ONE, 0, 0, 0};
        return id;
    }
    /* One sign for q and -q: w >= 0 keeps clips free of needless flips. */
    double k = (q.w < 0 ? -1.0 : 1.0) * (double)CUB_QUAT_ONE / n;
    cub_quat r = {(int32_t)lrint(q.w * k), (int32_t)lrint(q.x * k), (int32_t)lrint(q.y * k),
                  (int32_t)lrint(q.z * k)};
    return r;
}

int32_t io_mm_to_q16(double mm)
{
    double v = mm * 65536.0;
    if (v >= 2147483647.0)
        return INT32_MAX;
    if (v <= -2147483648.0)
        return INT32_MIN;
    return (int32_t)lrint(v);
}

double io_q16_to_mm(int32_t q)
{
    return q / 65536.0;
}

cub_err io_clip_alloc(cub_io_motion *m, int frame_count, uint32_t frame_ns, int with_trans,
                      const char *file, int line, cub_diag *diag)
{
    int joints = m->skel.joint_count;
    /* Check the size in doubles first: the product may not fit a size_t. */
    double per_frame = (double)joints * (sizeof(cub_quat) + (with_trans ? sizeof(cub_vec3) : 0)) +
                       sizeof(cub_vec3);
    double need = per_frame * frame_count;
    if (frame_count < 1 || need > (double)IO_MEM_CAP_BYTES)
        return cub_diag_fail(diag, CUB_ERR_FORMAT, file, line,
                          "%d frames of %d joints need %.0f MB, over the %zu MB cap", frame_count,
                          joints, need / 1048576.0, IO_MEM_CAP_BYTES >> 20);
    size_t size = cub_motion_clip_mem_size(joints, frame_count, with_trans);
    void *mem = malloc(size ? size : 1);
    if (!mem)
        return cub_diag_fail(diag, CUB_ERR_NOMEM, file, line, "out of memory for %d frames",
                          frame_count);
    cub_err err = cub_motion_clip_init(&m->clip, &m->skel, frame_count, frame_ns, with_trans,
                                       mem, size);
    if (err) {
        free(mem);
        return cub_diag_fail(diag, err, file, line, "cannot lay out the clip: %s",
                          cub_err_str(err));
    }
    m->frame_mem = mem;
    return CUB_OK;
}

void cub_io_motion_free(cub_io_motion *m)
{
    if (!m)
        return;
    free(m->frame_mem);
    m->frame_mem = NULL;
    memset(&m->clip, 0, sizeof(m->clip));
}

/* Known conventions by the size of the rest skeleton (its largest extent,
 * in file units), checked on the shared data:
 *   size <= 4        metres (a 1.7 m human is 1.7 units)
 *   15 .. 35         CMU's inches/0.45 (cgspeed BVH: ~25 units, 56.4 mm each)
 *   60 .. 600        centimetres (Bandai, Daz, Rokoko, the MANN dog)
 *   over 600         millimetres
 * Sizes between bands match no convention: scale so the skeleton is a
 * 1.7 m human (AnimatedDrawings' fair1 rigs, ~45 units, come out 1.7 m).
 * A non-human in an unusual unit needs desc.unit_mm. */
double cub_io_guess_unit_mm(double rest_size_units)
{
    if (!(rest_size_units > 0) || !isfinite(rest_size_units))
        return 10.0;
    if (rest_size_units <= 4.0)
        return 1000.0;
    if (rest_size_units >= 15.0 && rest_size_units <= 35.0)
        return 25.4 / 0.45;
    if (rest_size_units >= 60.0 && rest_size_units <= 600.0)
        return 10.0;
    if (rest_size_units > 600.0)
        return 1.0;
    return 1700.0 / rest_size_units;
}

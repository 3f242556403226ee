/* Rotations in doubles (Euler <-> quaternion), the conversions to the
 * firmware's Q2.30 / Q16.16 types, clip allocation and the unit guess. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "io_internal.h"

io_dquat io_dquat_mul(io_dquat a, io_dquat b)
{
    io_dquat r = {
        a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z,
        a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
        a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
        a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w,
    };
    return r;
}

io_dquat io_dquat_conj(io_dquat q)
{
    io_dquat r = {q.w, -q.x, -q.y, -q.z};
    return r;
}

io_dquat io_dquat_axis(int axis, double angle_rad)
{
    double s = sin(angle_rad * 0.5);
    io_dquat r = {cos(angle_rad * 0.5), 0, 0, 0};
    if (axis == 0)
        r.x = s;
    else if (axis == 1)
        r.y = s;
    else
        r.z = s;
    return r;
}

io_dquat io_dquat_euler(const int *axes, const double *angle_rad, int count)
{
    io_dquat q = {1, 0, 0, 0};
    for (int i = 0; i < count; i++)
        q = io_dquat_mul(q, io_dquat_axis(axes[i], angle_rad[i]));
    return q;
}

static void dquat_to_matrix(io_dquat q, double m[3][3])
{
    double n = q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;
    double s = n > 0 ? 2.0 / n : 0;
    double xx = q.x * q.x * s, yy = q.y * q.y * s, zz = q.z * q.z * s;
    double xy = q.x * q.y * s, xz = q.x * q.z * s, yz = q.y * q.z * s;
    double wx = q.w * q.x * s, wy = q.w * q.y * s, wz = q.w * q.z * s;
    m[0][0] = 1 - yy - zz, m[0][1] = xy - wz, m[0][2] = xz + wy;
    m[1][0] = xy + wz, m[1][1] = 1 - xx - zz, m[1][2] = yz - wx;
    m[2][0] = xz - wy, m[2][1] = yz + wx, m[2][2] = 1 - xx - yy;
}

/* Tait-Bryan angles of R = Ra(al) Rb(be) Rc(ga) for distinct a, b, c;
 * s is +1 when (a, b, c) is a cyclic order of (x, y, z), else -1. */
static void matrix_to_abc(double m[3][3], int a, int b, int c, double out[3])
{
    double s = ((b - a + 3) % 3 == 1) ? 1.0 : -1.0;
    double sb = s * m[a][c];
    double cb = sqrt(m[a][a] * m[a][a] + m[a][b] * m[a][b]);
    out[1] = atan2(sb, cb);
    if (cb > 1e-9) {
        out[0] = atan2(-s * m[b][c], m[c][c]);
        out[2] = atan2(-s * m[a][b], m[a][a]);
    } else { /* gimbal lock: put the whole twist in the last angle */
        out[0] = 0;
        out[2] = atan2(s * m[b][a], m[b][b]);
    }
}

void io_dquat_to_euler(io_dquat q, const int *axes, int count, double *angle_rad)
{
    int full[3];
    double m[3][3], abc[3];
    int used[3] = {0, 0, 0}, n = 0;
    for (int i = 0; i < count && i < 3; i++) {
        full[n++] = axes[i];
        used[axes[i]] = 1;
    }
    /* Fewer than three axes: complete the order with the missing ones
     * (their angles come out near zero for rotations those axes made). */
    for (int k = 0; k < 3 && n < 3; k++)
        if (!used[k])
            full[n++] = k;
    dquat_to_matrix(q, m);
    matrix_to_abc(m, full[0], full[1], full[2], abc);
    for (int i = 0; i < count && i < 3; i++)
        angle_rad[i] = abc[i];
}

cub_quat io_quat_to_fx(io_dquat q)
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

io_dquat io_quat_from_fx(cub_quat q)
{
    const double k = 1.0 / (double)CUB_QUAT_ONE;
    io_dquat r = {q.w * k, q.x * k, q.y * k, q.z * k};
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

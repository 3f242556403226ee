/* Quaternions in doubles, Euler angles, and the conversions to the
 * firmware's fixed-point types (cub/vec.h). */
#include "cub/vec.h"

#include <math.h>

double cub_dv3_angle(cub_dv3 a, cub_dv3 b)
{
    /* atan2 of |a x b| and a.b stays accurate near 0 and pi, unlike acos. */
    return atan2(cub_dv3_len(cub_dv3_cross(a, b)), cub_dv3_dot(a, b));
}

cub_dq cub_dq_identity(void)
{
    cub_dq q = {1, 0, 0, 0};
    return q;
}

cub_dq cub_dq_mul(cub_dq a, cub_dq b)
{
    cub_dq r = {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z,
                a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
                a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
                a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
    return r;
}

cub_dq cub_dq_conj(cub_dq q)
{
    cub_dq r = {q.w, -q.x, -q.y, -q.z};
    return r;
}

double cub_dq_dot(cub_dq a, cub_dq b)
{
    return a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z;
}

cub_dq cub_dq_norm(cub_dq q)
{
    double n = sqrt(cub_dq_dot(q, q));
    if (n < 1e-12)
        return cub_dq_identity();
    cub_dq r = {q.w / n, q.x / n, q.y / n, q.z / n};
    return r;
}

cub_dv3 cub_dq_rotate(cub_dq q, cub_dv3 v)
{
    /* v + 2w(u x v) + 2 u x (u x v), u the vector part. */
    cub_dv3 u = {q.x, q.y, q.z};
    cub_dv3 t = cub_dv3_scale(cub_dv3_cross(u, v), 2.0);
    return cub_dv3_add(cub_dv3_add(v, cub_dv3_scale(t, q.w)), cub_dv3_cross(u, t));
}

cub_dq cub_dq_axis_angle(cub_dv3 a, double angle_rad)
{
    double s = sin(angle_rad / 2);
    cub_dq q = {cos(angle_rad / 2), a.x * s, a.y * s, a.z * s};
    return q;
}

cub_dq cub_dq_about(int axis, double angle_rad)
{
    double s = sin(angle_rad * 0.5);
    cub_dq r = {cos(angle_rad * 0.5), 0, 0, 0};
    if (axis == 0)
        r.x = s;
    else if (axis == 1)
        r.y = s;
    else
        r.z = s;
    return r;
}

cub_dq cub_dq_arc(cub_dv3 a, cub_dv3 b)
{
    cub_dv3 up = cub_dv3_make(0, 1, 0);
    a = cub_dv3_norm(a, up);
    b = cub_dv3_norm(b, up);
    double d = cub_dv3_dot(a, b);
    if (d < -0.999999) {
        /* Opposite: any axis perpendicular to a will do; pick a stable one. */
        cub_dv3 axis = cub_dv3_cross(cub_dv3_make(1, 0, 0), a);
        if (cub_dv3_len(axis) < 1e-6)
            axis = cub_dv3_cross(up, a);
        return cub_dq_axis_angle(cub_dv3_norm(axis, cub_dv3_make(0, 0, 1)), CUB_VEC_PI);
    }
    cub_dv3 c = cub_dv3_cross(a, b);
    cub_dq q = {1 + d, c.x, c.y, c.z};
    return cub_dq_norm(q);
}

cub_dq cub_dq_frames(cub_dv3 a0, cub_dv3 a1, cub_dv3 b0, cub_dv3 b1)
{
    cub_dq q1 = cub_dq_arc(a0, b0);
    cub_dv3 a1r = cub_dq_rotate(q1, a1);
    cub_dv3 n = cub_dv3_norm(b0, cub_dv3_make(0, 1, 0));
    cub_dv3 pa = cub_dv3_sub(a1r, cub_dv3_scale(n, cub_dv3_dot(a1r, n)));
    cub_dv3 pb = cub_dv3_sub(b1, cub_dv3_scale(n, cub_dv3_dot(b1, n)));
    double ang = atan2(cub_dv3_dot(cub_dv3_cross(pa, pb), n), cub_dv3_dot(pa, pb));
    return cub_dq_norm(cub_dq_mul(cub_dq_axis_angle(n, ang), q1));
}

cub_dq cub_dq_slerp(cub_dq a, cub_dq b, double t)
{
    double d = cub_dq_dot(a, b);
    if (d < 0) {
        b.w = -b.w, b.x = -b.x, b.y = -b.y, b.z = -b.z;
        d = -d;
    }
    double wa = 1 - t, wb = t;
    if (d < 0.9995) {
        double th = acos(d), s = sin(th);
        wa = sin((1 - t) * th) / s;
        wb = sin(t * th) / s;
    }
    cub_dq r = {wa * a.w + wb * b.w, wa * a.x + wb * b.x, wa * a.y + wb * b.y, wa * a.z + wb * b.z};
    return cub_dq_norm(r);
}

double cub_dq_angle_between(cub_dq a, cub_dq b)
{
    double d = fabs(cub_dq_dot(cub_dq_norm(a), cub_dq_norm(b)));
    return 2 * acos(d > 1 ? 1 : d);
}

cub_dq cub_dq_euler(const int *axes, const double *angle_rad, int count)
{
    cub_dq q = {1, 0, 0, 0};
    for (int i = 0; i < count; i++)
        q = cub_dq_mul(q, cub_dq_about(axes[i], angle_rad[i]));
    return q;
}

static void dq_to_matrix(cub_dq q, double m[3][3])
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

void cub_dq_to_euler(cub_dq q, const int *axes, int count, double *angle_rad)
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
    dq_to_matrix(q, m);
    matrix_to_abc(m, full[0], full[1], full[2], abc);
    for (int i = 0; i < count && i < 3; i++)
        angle_rad[i] = abc[i];
}

cub_dq cub_dq_from_fx(cub_quat q)
{
    const double k = 1.0 / (double)CUB_QUAT_ONE;
    cub_dq r = {q.w * k, q.x * k, q.y * k, q.z * k};
    return r;
}

static int32_t round_i32(double v)
{
    return (int32_t)lround(v);
}

cub_quat cub_dq_to_fx(cub_dq q)
{
    q = cub_dq_norm(q);
    const double s = (double)CUB_QUAT_ONE;
    cub_quat r = {round_i32(q.w * s), round_i32(q.x * s), round_i32(q.y * s), round_i32(q.z * s)};
    return r;
}

cub_dv3 cub_dv3_from_fx(cub_vec3 v)
{
    return cub_dv3_make(v.x / 65536.0, v.y / 65536.0, v.z / 65536.0);
}

cub_vec3 cub_dv3_to_fx(cub_dv3 v)
{
    cub_vec3 r = {round_i32(v.x * 65536.0), round_i32(v.y * 65536.0), round_i32(v.z * 65536.0)};
    return r;
}

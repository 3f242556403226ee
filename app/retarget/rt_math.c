/* Double-precision vectors and quaternions for the offline retargeter. */
#include <math.h>
#include <string.h>

#include "rt_internal.h"

rt_v3 rt_v3_make(double x, double y, double z)
{
    rt_v3 v = {x, y, z};
    return v;
}

rt_v3 rt_v3_add(rt_v3 a, rt_v3 b) { return rt_v3_make(a.x + b.x, a.y + b.y, a.z + b.z); }
rt_v3 rt_v3_sub(rt_v3 a, rt_v3 b) { return rt_v3_make(a.x - b.x, a.y - b.y, a.z - b.z); }
rt_v3 rt_v3_scale(rt_v3 a, double s) { return rt_v3_make(a.x * s, a.y * s, a.z * s); }
double rt_v3_dot(rt_v3 a, rt_v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double rt_v3_len(rt_v3 a) { return sqrt(rt_v3_dot(a, a)); }

rt_v3 rt_v3_cross(rt_v3 a, rt_v3 b)
{
    return rt_v3_make(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

rt_v3 rt_v3_norm(rt_v3 a, rt_v3 fallback)
{
    double n = rt_v3_len(a);
    return n > 1e-12 ? rt_v3_scale(a, 1.0 / n) : fallback;
}

double rt_v3_angle(rt_v3 a, rt_v3 b)
{
    /* atan2 of |a x b| and a.b stays accurate near 0 and pi, unlike acos. */
    return atan2(rt_v3_len(rt_v3_cross(a, b)), rt_v3_dot(a, b));
}

rt_q rt_q_identity(void)
{
    rt_q q = {1, 0, 0, 0};
    return q;
}

rt_q rt_q_mul(rt_q a, rt_q b)
{
    rt_q r = {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z,
              a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
              a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
              a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
    return r;
}

rt_q rt_q_conj(rt_q q)
{
    rt_q r = {q.w, -q.x, -q.y, -q.z};
    return r;
}

double rt_q_dot(rt_q a, rt_q b) { return a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z; }

rt_q rt_q_norm(rt_q q)
{
    double n = sqrt(rt_q_dot(q, q));
    if (n < 1e-12)
        return rt_q_identity();
    rt_q r = {q.w / n, q.x / n, q.y / n, q.z / n};
    return r;
}

rt_v3 rt_q_rotate(rt_q q, rt_v3 v)
{
    /* v + 2w(u x v) + 2 u x (u x v), u the vector part. */
    rt_v3 u = {q.x, q.y, q.z};
    rt_v3 t = rt_v3_scale(rt_v3_cross(u, v), 2.0);
    return rt_v3_add(rt_v3_add(v, rt_v3_scale(t, q.w)), rt_v3_cross(u, t));
}

rt_q rt_q_axis_angle(rt_v3 a, double angle_rad)
{
    double s = sin(angle_rad / 2);
    rt_q q = {cos(angle_rad / 2), a.x * s, a.y * s, a.z * s};
    return q;
}

rt_q rt_q_arc(rt_v3 a, rt_v3 b)
{
    a = rt_v3_norm(a, rt_v3_make(0, 1, 0));
    b = rt_v3_norm(b, rt_v3_make(0, 1, 0));
    double d = rt_v3_dot(a, b);
    if (d < -0.999999) {
        /* Opposite: any axis perpendicular to a will do; pick a stable one. */
        rt_v3 axis = rt_v3_cross(rt_v3_make(1, 0, 0), a);
        if (rt_v3_len(axis) < 1e-6)
            axis = rt_v3_cross(rt_v3_make(0, 1, 0), a);
        return rt_q_axis_angle(rt_v3_norm(axis, rt_v3_make(0, 0, 1)), RT_PI);
    }
    rt_v3 c = rt_v3_cross(a, b);
    rt_q q = {1 + d, c.x, c.y, c.z};
    return rt_q_norm(q);
}

rt_q rt_q_frames(rt_v3 a0, rt_v3 a1, rt_v3 b0, rt_v3 b1)
{
    /* First turn a0 onto b0, then turn about b0 so that a1 lands on b1. */
    rt_q q1 = rt_q_arc(a0, b0);
    rt_v3 a1r = rt_q_rotate(q1, a1);
    rt_v3 n = rt_v3_norm(b0, rt_v3_make(0, 1, 0));
    rt_v3 pa = rt_v3_sub(a1r, rt_v3_scale(n, rt_v3_dot(a1r, n)));
    rt_v3 pb = rt_v3_sub(b1, rt_v3_scale(n, rt_v3_dot(b1, n)));
    double ang = atan2(rt_v3_dot(rt_v3_cross(pa, pb), n), rt_v3_dot(pa, pb));
    return rt_q_norm(rt_q_mul(rt_q_axis_angle(n, ang), q1));
}

rt_q rt_q_slerp(rt_q a, rt_q b, double t)
{
    double d = rt_q_dot(a, b);
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
    rt_q r = {wa * a.w + wb * b.w, wa * a.x + wb * b.x, wa * a.y + wb * b.y, wa * a.z + wb * b.z};
    return rt_q_norm(r);
}

double rt_q_angle_between(rt_q a, rt_q b)
{
    double d = fabs(rt_q_dot(rt_q_norm(a), rt_q_norm(b)));
    return 2 * acos(d > 1 ? 1 : d);
}

rt_q rt_q_from_fx(cub_quat q)
{
    const double s = 1.0 / (double)CUB_QUAT_ONE;
    rt_q r = {q.w * s, q.x * s, q.y * s, q.z * s};
    return rt_q_norm(r);
}

static int32_t round_i32(double v)
{
    return (int32_t)lround(v);
}

cub_quat rt_q_to_fx(rt_q q)
{
    q = rt_q_norm(q);
    const double s = (double)CUB_QUAT_ONE;
    cub_quat r = {round_i32(q.w * s), round_i32(q.x * s), round_i32(q.y * s), round_i32(q.z * s)};
    return r;
}

rt_v3 rt_v3_from_fx(cub_vec3 v)
{
    return rt_v3_make(v.x / 65536.0, v.y / 65536.0, v.z / 65536.0);
}

cub_vec3 rt_v3_to_fx(rt_v3 v)
{
    cub_vec3 r = {round_i32(v.x * 65536.0), round_i32(v.y * 65536.0), round_i32(v.z * 65536.0)};
    return r;
}

void rt_forward(const cub_skeleton *skel, rt_v3 root, const rt_q *rot, const rt_v3 *trans,
                rt_v3 *world_pos, rt_q *world_rot)
{
    for (int j = 0; j < skel->joint_count; j++) {
        int p = skel->joints[j].parent;
        if (p < 0) {
            world_pos[j] = root;
            world_rot[j] = rot[j];
            continue;
        }
        rt_v3 off = trans ? trans[j] : rt_v3_from_fx(skel->joints[j].offset_mm);
        world_pos[j] = rt_v3_add(world_pos[p], rt_q_rotate(world_rot[p], off));
        world_rot[j] = rt_q_norm(rt_q_mul(world_rot[p], rot[j]));
    }
}


/* The ray caster: every pixel's ray against rounded primitives, nearest hit
 * wins (a z-buffer). Rays are built so that their camera-z component is 1:
 * the ray parameter t is the camera depth in mm. Each primitive only visits
 * the pixels its bounding sphere can cover. */
#include <float.h>

#include "synth_internal.h"

#define NEAR_MM 50.0f
#define W CUB_KINECT_WIDTH
#define H CUB_KINECT_HEIGHT
#define F ((float)CUB_KINECT_FOCAL_PX)

void synth_prim_bound(synth_prim *p)
{
    switch (p->kind) {
    case PRIM_CAPSULE:
    case PRIM_CYLINDER:
        p->bs_c = cub_fv3_lerp(p->a, p->b, 0.5f);
        p->bs_r = cub_fv3_len(cub_fv3_sub(p->b, p->a)) * 0.5f + p->r;
        break;
    case PRIM_ELLIPSOID:
        p->bs_c = p->a;
        p->bs_r = fmaxf(p->radii[0], fmaxf(p->radii[1], p->radii[2]));
        break;
    case PRIM_BOX:
        p->bs_c = cub_fv3_lerp(p->a, p->b, 0.5f);
        p->bs_r = cub_fv3_len(cub_fv3_sub(p->b, p->a)) * 0.5f;
        break;
    default: p->bs_r = -1.0f; break;
    }
}

/* Smallest root t of A t^2 + 2 B t + C = 0, or -1. */
static float near_root(float A, float B, float C)
{
    float h = B * B - A * C;
    if (h < 0 || A <= 0) return -1.0f;
    return (-B - sqrtf(h)) / A;
}

static float hit_sphere(cub_fv3 o, cub_fv3 d, float dd, cub_fv3 c, float r)
{
    cub_fv3 oc = cub_fv3_sub(o, c);
    return near_root(dd, cub_fv3_dot(oc, d), cub_fv3_dot(oc, oc) - r * r);
}

/* A ray o + t d against the infinite cylinder of radius r around the line
 * through a and b: A t^2 + 2 B t + C = 0. A hit at t lies at baoa + t bard
 * along b - a, scaled by baba: inside the segment when 0 < that < baba. */
typedef struct axis_quad {
    float baba, bard, baoa, A, B, C;
} axis_quad;

static axis_quad axis_quadratic(const synth_prim *p, cub_fv3 o, cub_fv3 d, float dd)
{
    cub_fv3 ba = cub_fv3_sub(p->b, p->a), oa = cub_fv3_sub(o, p->a);
    axis_quad q;
    q.baba = cub_fv3_dot(ba, ba);
    q.bard = cub_fv3_dot(ba, d);
    q.baoa = cub_fv3_dot(ba, oa);
    q.A = q.baba * dd - q.bard * q.bard;
    q.B = q.baba * cub_fv3_dot(oa, d) - q.baoa * q.bard;
    q.C = q.baba * cub_fv3_dot(oa, oa) - q.baoa * q.baoa - p->r * p->r * q.baba;
    return q;
}

static float hit_capsule(const synth_prim *p, cub_fv3 o, cub_fv3 d, float dd)
{
    axis_quad q = axis_quadratic(p, o, d, dd);
    if (q.A > 0 && q.B * q.B - q.A * q.C < 0)
        return -1.0f; /* misses the infinite cylinder, so the end spheres too */
    float t = near_root(q.A, q.B, q.C);
    if (t > 0) {
        float y = q.baoa + t * q.bard;
        if (y > 0 && y < q.baba) return t;
    }
    /* An end sphere; both when the camera lies inside the infinite
     * cylinder (a limb pointing at the camera). */
    float ta = hit_sphere(o, d, dd, p->a, p->r), tb = hit_sphere(o, d, dd, p->b, p->r);
    if (ta <= 0) return tb;
    return (tb > 0 && tb < ta) ? tb : ta;
}

static float hit_cylinder(const synth_prim *p, cub_fv3 o, cub_fv3 d, float dd)
{
    axis_quad q = axis_quadratic(p, o, d, dd);
    float h = q.B * q.B - q.A * q.C;
    if (h < 0 || q.A <= 0) return -1.0f;
    h = sqrtf(h);
    float t = (-q.B - h) / q.A;
    float y = q.baoa + t * q.bard;
    if (y > 0 && y < q.baba) return t;
    if (fabsf(q.bard) < 1e-6f) return -1.0f;
    t = ((y < 0 ? 0 : q.baba) - q.baoa) / q.bard; /* the cap facing the ray */
    return fabsf(q.B + q.A * t) < h ? t : -1.0f;
}

static float hit_ellipsoid(const synth_prim *p, cub_fv3 o, cub_fv3 d)
{
    cub_fv3 oc = cub_fv3_sub(o, p->a);
    float lo[3], ld[3];
    for (int i = 0; i < 3; i++) {
        lo[i] = cub_fv3_dot(oc, p->axis[i]) / p->radii[i];
        ld[i] = cub_fv3_dot(d, p->axis[i]) / p->radii[i];
    }
    float A = ld[0] * ld[0] + ld[1] * ld[1] + ld[2] * ld[2];
    float B = lo[0] * ld[0] + lo[1] * ld[1] + lo[2] * ld[2];
    float C = lo[0] * lo[0] + lo[1] * lo[1] + lo[2] * lo[2] - 1.0f;
    return near_root(A, B, C);
}

static float slab(float o, float d, float lo, float hi, float *tmin, float *tmax)
{
    if (fabsf(d) < 1e-9f) return (o >= lo && o <= hi) ? 1.0f : -1.0f;
    float t0 = (lo - o) / d, t1 = (hi - o) / d;
    if (t0 > t1) {
        float s = t0;
        t0 = t1;
        t1 = s;
    }
    *tmin = fmaxf(*tmin, t0);
    *tmax = fminf(*tmax, t1);
    return 1.0f;
}

static float hit_box(const synth_prim *p, cub_fv3 o, cub_fv3 d)
{
    float tmin = -FLT_MAX, tmax = FLT_MAX;
    if (slab(o.x, d.x, p->a.x, p->b.x, &tmin, &tmax) < 0 ||
        slab(o.y, d.y, p->a.y, p->b.y, &tmin, &tmax) < 0 ||
        slab(o.z, d.z, p->a.z, p->b.z, &tmin, &tmax) < 0 || tmin > tmax)
        return -1.0f;
    return tmin;
}

/* The floor: y = 0 within the x and z ranges of a and b. */
static float hit_floor(const synth_prim *p, cub_fv3 o, cub_fv3 d)
{
    if (d.y >= -1e-9f || o.y <= 0) return -1.0f;
    float t = -o.y / d.y;
    float x = o.x + t * d.x, z = o.z + t * d.z;
    return (x >= p->a.x && x <= p->b.x && z >= p->a.z && z <= p->b.z) ? t : -1.0f;
}

static float hit(const synth_prim *p, cub_fv3 o, cub_fv3 d, float dd)
{
    switch (p->kind) {
    case PRIM_CAPSULE: return hit_capsule(p, o, d, dd);
    case PRIM_CYLINDER: return hit_cylinder(p, o, d, dd);
    case PRIM_ELLIPSOID: return hit_ellipsoid(p, o, d);
    case PRIM_BOX: return hit_box(p, o, d);
    default: return hit_floor(p, o, d);
    }
}

static int clampi(int v, int lo, int hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

/* The pixel rectangle a bounding sphere can cover; 0 if none. */
static int screen_rect(const synth_camera *cam, const synth_prim *p, int r[4])
{
    r[0] = 0, r[1] = 0, r[2] = W - 1, r[3] = H - 1;
    if (p->bs_r < 0) return 1;
    cub_fv3 c = cub_fv3_sub(p->bs_c, cam->origin);
    float x = cub_fv3_dot(c, cam->x), y = cub_fv3_dot(c, cam->y), z = cub_fv3_dot(c, cam->z);
    float rad = p->bs_r;
    if (z + rad < NEAR_MM) return 0;
    if (z - rad < NEAR_MM) return 1;
    float zn = z - rad, zf = z + rad;
    float u0 = CUB_KINECT_CX + F * fminf((x - rad) / zn, (x - rad) / zf);
    float u1 = CUB_KINECT_CX + F * fmaxf((x + rad) / zn, (x + rad) / zf);
    float v0 = CUB_KINECT_CY - F * fmaxf((y + rad) / zn, (y + rad) / zf);
    float v1 = CUB_KINECT_CY - F * fminf((y - rad) / zn, (y - rad) / zf);
    if (u1 < 0 || u0 > W - 1 || v1 < 0 || v0 > H - 1) return 0;
    r[0] = clampi((int)floorf(u0), 0, W - 1);
    r[1] = clampi((int)floorf(v0), 0, H - 1);
    r[2] = clampi((int)ceilf(u1), 0, W - 1);
    r[3] = clampi((int)ceilf(v1), 0, H - 1);
    return 1;
}

/* Where a cast writes: depth always, owner and part when not NULL. */
typedef struct cast_out {
    float *depth_mm;
    uint8_t *owner, *part;
} cast_out;

static void cast(const synth_camera *cam, const synth_prim *prims, int n, const cast_out *o)
{
    for (int k = 0; k < n; k++) {
        const synth_prim *p = &prims[k];
        int r[4];
        if (!screen_rect(cam, p, r)) continue;
        for (int v = r[1]; v <= r[3]; v++) {
            cub_fv3 row = cub_fv3_add(cam->z, cub_fv3_scale(cam->y, (CUB_KINECT_CY - v) / F));
            for (int u = r[0]; u <= r[2]; u++) {
                cub_fv3 d = cub_fv3_add(row, cub_fv3_scale(cam->x, (u - CUB_KINECT_CX) / F));
                float t = hit(p, cam->origin, d, cub_fv3_dot(d, d));
                int i = v * W + u;
                float *z = &o->depth_mm[i];
                if (t > NEAR_MM && (*z == 0 || t < *z)) {
                    *z = t;
                    if (o->owner) o->owner[i] = p->owner;
                    if (o->part) o->part[i] = p->part;
                }
            }
        }
    }
}

void synth_raycast(const synth_camera *cam, const synth_prim *prims, int n, float *depth_mm,
                   uint8_t *owner, int clear)
{
    for (int i = 0; i < W * H && clear; i++) {
        depth_mm[i] = 0;
        if (owner) owner[i] = OWNER_NONE;
    }
    cast_out o = {depth_mm, owner, NULL};
    cast(cam, prims, n, &o);
}

void synth_raycast_parts(const synth_camera *cam, const synth_prim *prims, int n, float *depth_mm,
                         uint8_t *owner, uint8_t *part)
{
    cast_out o = {depth_mm, owner, part};
    cast(cam, prims, n, &o);
}

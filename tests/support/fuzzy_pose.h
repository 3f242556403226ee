/* fuzzy_pose — test helpers for the fuzzy features: the firmware's fuzzy
 * body over the Kinect's 20 joints (kinect.h) with the floor and height in
 * mm, a standing adult template in that layout, simple pose edits (bend,
 * sit), a fixed random stream, and conversion to the double reference's
 * types (fuzzy_ref.h). Header-only (static inline), so cub_test_support
 * itself needs no firmware headers. Test code only. */
#ifndef CUB_FUZZY_POSE_H
#define CUB_FUZZY_POSE_H

#include <math.h>
#include <stdint.h>

#include "cub/fuzzy.h"
#include "cub/kinect.h"
#include "fuzzy_ref.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static inline cub_q16 fz_q16(double v)
{
    return (cub_q16)lround(v * 65536.0);
}

/* The firmware's fuzzy body over the Kinect's joints (kinect.h), floor and
 * standing height in mm. */
static inline cub_fuzzy_body fz_kinect_body(double floor_y_mm, double stand_cog_mm)
{
    return cub_kinect_fuzzy_body(fz_q16(floor_y_mm), fz_q16(stand_cog_mm));
}

static inline cub_vec3 fz_mm(double x, double y, double z)
{
    return (cub_vec3){fz_q16(x), fz_q16(y), fz_q16(z)};
}

static inline cub_vec3 fz_add(cub_vec3 p, double dx, double dy, double dz)
{
    return (cub_vec3){p.x + fz_q16(dx), p.y + fz_q16(dy), p.z + fz_q16(dz)};
}

/* An adult standing straight, arms hanging, facing +z, floor at y = 0, so
 * the left side is +x. */
static inline void fz_template(cub_vec3 *w)
{
    static const double t[CUB_KJ_COUNT][3] = {
        {0, 1000, 0},   {0, 1100, 0},   {0, 1450, 0},   {0, 1650, 0},    {180, 1420, 0},
        {200, 1130, 0}, {210, 880, 0},  {215, 800, 0},  {-180, 1420, 0}, {-200, 1130, 0},
        {-210, 880, 0}, {-215, 800, 0}, {100, 950, 0},  {100, 520, 0},   {100, 80, 0},
        {100, 30, 80},  {-100, 950, 0}, {-100, 520, 0}, {-100, 80, 0},   {-100, 30, 80},
    };
    for (int j = 0; j < CUB_KJ_COUNT; j++)
        w[j] = fz_mm(t[j][0], t[j][1], t[j][2]);
}

/* Rotate the upper body (spine, shoulders, head, arms) forward by deg about
 * the hip centre. */
static inline void fz_bend_forward(cub_vec3 *w, double deg)
{
    const int upper[] = {CUB_KJ_SPINE,   CUB_KJ_SHOULDER_CENTRE, CUB_KJ_HEAD,   CUB_KJ_SHOULDER_L,
                         CUB_KJ_ELBOW_L, CUB_KJ_WRIST_L,         CUB_KJ_HAND_L, CUB_KJ_SHOULDER_R,
                         CUB_KJ_ELBOW_R, CUB_KJ_WRIST_R,         CUB_KJ_HAND_R};
    double c = cos(deg * M_PI / 180), s = sin(deg * M_PI / 180);
    for (unsigned i = 0; i < sizeof upper / sizeof upper[0]; i++) {
        cub_vec3 *p = &w[upper[i]];
        double y = (p->y - w[CUB_KJ_HIP_CENTRE].y) / 65536.0;
        double z = (p->z - w[CUB_KJ_HIP_CENTRE].z) / 65536.0;
        p->y = w[CUB_KJ_HIP_CENTRE].y + fz_q16(y * c - z * s);
        p->z = w[CUB_KJ_HIP_CENTRE].z + fz_q16(y * s + z * c);
    }
}

/* Seated on a chair (seat 480 mm high): trunk upright, thighs forward, shins
 * vertical. Starts from the template. */
static inline void fz_sit(cub_vec3 *w)
{
    for (int j = CUB_KJ_HIP_CENTRE; j <= CUB_KJ_HAND_R; j++)
        w[j].y -= fz_q16(470);
    w[CUB_KJ_HIP_L].y -= fz_q16(470);
    w[CUB_KJ_HIP_R].y -= fz_q16(470);
    for (int side = 0; side < 2; side++) {
        int k = side ? CUB_KJ_KNEE_R : CUB_KJ_KNEE_L;
        w[k] = fz_mm(w[k].x / 65536.0, 480, 430);
        w[k + 1] = fz_mm(w[k].x / 65536.0, 80, 430);
        w[k + 2] = fz_mm(w[k].x / 65536.0, 30, 510);
    }
}

/* splitmix64: a fixed pseudo-random stream. */
static inline uint64_t fz_rng(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

/* Uniform in [lo, hi). */
static inline double fz_uniform(uint64_t *state, double lo, double hi)
{
    return lo + (hi - lo) * (double)(fz_rng(state) >> 11) / 9007199254740992.0;
}

/* The same body for the double reference, and positions as doubles. */
static inline cub_fuzzy_ref_body fz_ref_body(const cub_fuzzy_body *b)
{
    cub_fuzzy_ref_body r = {
        .hip_centre = b->hip_centre,
        .spine = b->spine,
        .shoulder_centre = b->shoulder_centre,
        .head = b->head,
        .floor_y_mm = b->floor_y_mm / 65536.0,
        .stand_cog_mm = b->stand_cog_mm / 65536.0,
    };
    for (int s = 0; s < 2; s++) {
        r.shoulder[s] = b->shoulder[s];
        r.elbow[s] = b->elbow[s];
        r.wrist[s] = b->wrist[s];
        r.hip[s] = b->hip[s];
        r.knee[s] = b->knee[s];
        r.ankle[s] = b->ankle[s];
    }
    return r;
}

static inline void fz_to_double(const cub_vec3 *w, int n, double *xyz)
{
    for (int j = 0; j < n; j++) {
        xyz[3 * j] = w[j].x / 65536.0;
        xyz[3 * j + 1] = w[j].y / 65536.0;
        xyz[3 * j + 2] = w[j].z / 65536.0;
    }
}

/* Largest |fixed - double| over every membership of a frame. */
static inline double fz_max_mu_err(const cub_fuzzy_frame *f, const cub_fuzzy_ref_frame *r)
{
    double e = 0;
    for (int k = 0; k < CUB_FUZZY_FEATURE_COUNT; k++)
        for (int s = 0; s < CUB_FUZZY_MAX_SETS; s++) {
            double d = fabs(f->mu[k][s] / 32768.0 - r->mu[k][s]);
            if (d > e) e = d;
        }
    return e;
}

#endif

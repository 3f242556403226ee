/* fuzzy_ref — the double reference of the fuzzy features; see fuzzy_ref.h.
 * Definitions as documented at the top of firmware/fuzzy/fuzzy_features.c;
 * membership functions typed in from SEEDS.md § 000 piece by piece. */
#include "fuzzy_ref.h"

#include <math.h>
#include <stddef.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static const int set_count[CUB_FUZZY_REF_FEATURES] = {3, 2, 3, 2, 4, 2, 2, 2, 2, 2};

static double clamp01(double v)
{
    return v < 0 ? 0 : v > 1 ? 1 : v;
}

void cub_fuzzy_ref_membership(int k, double x, double mu[CUB_FUZZY_REF_MAX_SETS])
{
    for (int s = 0; s < CUB_FUZZY_REF_MAX_SETS; s++)
        mu[s] = 0;
    switch (k) {
    case 0: /* RH, LH */
    case 2:
        mu[0] = clamp01((90 - x) / 70);
        mu[1] = x <= 90 ? clamp01((x - 20) / 70) : clamp01((180 - x) / 90);
        mu[2] = clamp01((x - 90) / 90);
        break;
    case 1: /* RHE, LHE */
    case 3:
        mu[0] = clamp01((90 - x) / 90);
        mu[1] = clamp01((x - 20) / 70);
        break;
    case 4: /* Posture */
        mu[0] = clamp01((40 - x) / 40);
        mu[1] = x <= 40 ? clamp01(x / 40) : clamp01((80 - x) / 40);
        mu[2] = x <= 80 ? clamp01((x - 40) / 40) : clamp01((120 - x) / 40);
        mu[3] = clamp01((x - 80) / 40);
        break;
    case 5: /* Trunk */
        mu[0] = clamp01((180 - x) / 70);
        mu[1] = clamp01((x - 125) / 55);
        break;
    case 6: /* RF, LF */
    case 8:
        mu[0] = clamp01((40 - x) / 40);
        mu[1] = clamp01(x / 40);
        break;
    case 7: /* RFK, LFK */
    case 9:
        mu[0] = clamp01((180 - x) / 90);
        mu[1] = clamp01((x - 100) / 80);
        break;
    default: break;
    }
}

typedef struct dv {
    double x, y, z;
} dv;

static dv joint(const double *xyz, int i)
{
    return (dv){xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
}

static dv dsub(dv a, dv b)
{
    return (dv){a.x - b.x, a.y - b.y, a.z - b.z};
}

static dv from_to(const double *xyz, int a, int b)
{
    return dsub(joint(xyz, b), joint(xyz, a));
}

static double angle_deg(dv a, dv b)
{
    double dot = a.x * b.x + a.y * b.y + a.z * b.z;
    double cx = a.y * b.z - a.z * b.y, cy = a.z * b.x - a.x * b.z, cz = a.x * b.y - a.y * b.x;
    double cross = sqrt(cx * cx + cy * cy + cz * cz);
    if (dot == 0 && cross == 0) return 0;
    return atan2(cross, dot) * 180.0 / M_PI;
}

double cub_fuzzy_ref_cog_height_mm(const cub_fuzzy_ref_body *b, const double *xyz)
{
    /* Percent masses at segment midpoints: see fuzzy_features.c. */
    int head = b->head >= 0 ? b->head : b->shoulder_centre;
    struct {
        double m;
        int a, c;
    } seg[] = {
        {50, b->hip_centre, b->shoulder_centre},
        {8, head, head},
        {3, b->shoulder[0], b->elbow[0]},
        {3, b->shoulder[1], b->elbow[1]},
        {2, b->elbow[0], b->wrist[0]},
        {2, b->elbow[1], b->wrist[1]},
        {10, b->hip[0], b->knee[0]},
        {10, b->hip[1], b->knee[1]},
        {6, b->knee[0], b->ankle[0]},
        {6, b->knee[1], b->ankle[1]},
    };
    double sum = 0, mass = 0;
    for (size_t i = 0; i < sizeof seg / sizeof seg[0]; i++) {
        sum += seg[i].m * (xyz[3 * seg[i].a + 1] + xyz[3 * seg[i].c + 1]) / 2;
        mass += seg[i].m;
    }
    return sum / mass - b->floor_y_mm;
}

static int ok(int i, int n)
{
    return i >= 0 && i < n;
}

static double abduction(const cub_fuzzy_ref_body *b, const double *xyz, int side)
{
    dv out = from_to(xyz, b->hip[1 - side], b->hip[side]);
    if (out.x == 0 && out.y == 0 && out.z == 0) return 0;
    return 90 - angle_deg(from_to(xyz, b->hip[side], b->knee[side]), out);
}

int cub_fuzzy_ref_features(const cub_fuzzy_ref_body *b, const double *xyz, int n,
                           cub_fuzzy_ref_frame *out)
{
    const int need[] = {b->hip_centre, b->shoulder_centre, b->shoulder[0], b->shoulder[1],
                        b->elbow[0],   b->elbow[1],        b->wrist[0],    b->wrist[1],
                        b->hip[0],     b->hip[1],          b->knee[0],     b->knee[1],
                        b->ankle[0],   b->ankle[1]};
    for (size_t i = 0; i < sizeof need / sizeof need[0]; i++)
        if (!ok(need[i], n)) return -1;
    if ((b->spine != -1 && !ok(b->spine, n)) || (b->head != -1 && !ok(b->head, n))) return -1;
    if (!(b->stand_cog_mm > 0)) return -1;

    dv down = from_to(xyz, b->shoulder_centre, b->hip_centre);
    for (int side = 0; side < 2; side++) {
        int base = side == 1 ? 0 : 2; /* RH.. at 0, LH.. at 2 */
        int leg = side == 1 ? 6 : 8;  /* RF, RFK at 6; LF, LFK at 8 */
        dv upper = from_to(xyz, b->shoulder[side], b->elbow[side]);
        out->input[base] = angle_deg(upper, down);
        out->input[base + 1] = angle_deg(upper, from_to(xyz, b->elbow[side], b->wrist[side]));
        out->input[leg] = abduction(b, xyz, side);
        out->input[leg + 1] = angle_deg(from_to(xyz, b->knee[side], b->hip[side]),
                                        from_to(xyz, b->knee[side], b->ankle[side]));
    }
    out->input[4] = 80 * cub_fuzzy_ref_cog_height_mm(b, xyz) / b->stand_cog_mm;
    dv t0 = from_to(xyz, b->hip[0], b->knee[0]), t1 = from_to(xyz, b->hip[1], b->knee[1]);
    dv thighs = {t0.x + t1.x, t0.y + t1.y, t0.z + t1.z};
    out->input[5] = angle_deg(from_to(xyz, b->hip_centre, b->shoulder_centre), thighs);
    for (int k = 0; k < CUB_FUZZY_REF_FEATURES; k++)
        cub_fuzzy_ref_membership(k, out->input[k], out->mu[k]);
    return 0;
}

double cub_fuzzy_ref_distance(const cub_fuzzy_ref_frame *a, const cub_fuzzy_ref_frame *b,
                              const double *weight)
{
    static const double def[CUB_FUZZY_REF_FEATURES] = {3, 3, 3, 3, 3, 2, 1, 1, 1, 1};
    double w[CUB_FUZZY_REF_FEATURES], sum = 0;
    for (int k = 0; k < CUB_FUZZY_REF_FEATURES; k++) {
        w[k] = weight && weight[k] > 0 ? weight[k] : 0;
        sum += w[k];
    }
    if (sum == 0) {
        for (int k = 0; k < CUB_FUZZY_REF_FEATURES; k++)
            sum += w[k] = def[k];
    }
    double d2 = 0;
    for (int k = 0; k < CUB_FUZZY_REF_FEATURES; k++) {
        double sq = 0;
        for (int s = 0; s < set_count[k]; s++)
            sq += (a->mu[k][s] - b->mu[k][s]) * (a->mu[k][s] - b->mu[k][s]);
        d2 += w[k] / sum * sq / 2;
    }
    return sqrt(d2);
}

unsigned cub_fuzzy_ref_crisp_class(const cub_fuzzy_ref_frame *f)
{
    unsigned cls = 0;
    for (int k = 0; k < CUB_FUZZY_REF_FEATURES; k++) {
        int best = 0;
        for (int s = 1; s < set_count[k]; s++)
            if (f->mu[k][s] > f->mu[k][best]) best = s;
        cls |= (unsigned)best << (2 * k);
    }
    return cls;
}

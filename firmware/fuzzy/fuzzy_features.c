/* fuzzy: the ten feature inputs of one frame, from world joint positions
 * (SEEDS.md § 000, step 2, and "Recognising the child's move").
 *
 * Definitions (the float reference tests/support/fuzzy_ref.c repeats them):
 * - trunk-down: the direction shoulder_centre -> hip_centre. The spine
 *   joint is not used: this is the longest and stablest line through the
 *   trunk (a Kinect's spine joint sits a few cm above the hip centre).
 * - RH/LH: angle between the upper arm (shoulder -> elbow) and trunk-down:
 *   0 arm hanging, 90 arm out, 180 arm straight up.
 * - RHE/LHE: angle between shoulder -> elbow and elbow -> wrist, 0 straight.
 * - Posture: 80 * CoG height above the floor / stand_cog_mm (see cog below).
 * - Trunk: angle between hip_centre -> shoulder_centre and the summed thigh
 *   vectors (hip -> knee, both sides), 180 standing straight, ~90 bent over
 *   or seated.
 * - RF/LF: abduction, the angle of the thigh (hip -> knee) out of the
 *   pelvis' sagittal plane, i.e. 90 - angle(thigh, lateral axis), the
 *   lateral axis running from the other hip to this one. 0 standing, the
 *   side step's angle when stepped out, negative when crossed inward; a
 *   forward kick stays near 0 (it is not a side move), and unlike an angle
 *   measured inside the frontal plane it stays well-defined when the thigh
 *   points forward. Coincident hips read 0.
 * - RFK/LFK: knee angle, angle between knee -> hip and knee -> ankle, 180
 *   straight. */
#include <stddef.h>
#include <stdint.h>

#include "cub/fuzzy.h"

/* A difference of two Q16.16 positions needs 33 bits. */
typedef struct v64 {
    int64_t x, y, z;
} v64;

static v64 sub(cub_vec3 a, cub_vec3 b)
{
    return (v64){(int64_t)a.x - b.x, (int64_t)a.y - b.y, (int64_t)a.z - b.z};
}

static v64 add(v64 a, v64 b)
{
    return (v64){a.x + b.x, a.y + b.y, a.z + b.z};
}

static int64_t abs64(int64_t v)
{
    return v < 0 ? -v : v;
}

/* Halve until every component fits a Q16.16 vector: the direction, which is
 * all an angle needs, survives. */
static cub_vec3 fit(v64 v)
{
    while (abs64(v.x) > INT32_MAX || abs64(v.y) > INT32_MAX || abs64(v.z) > INT32_MAX) {
        v.x /= 2;
        v.y /= 2;
        v.z /= 2;
    }
    return (cub_vec3){(cub_q16)v.x, (cub_q16)v.y, (cub_q16)v.z};
}

/* 180/pi in Q32. */
#define DEG_PER_RAD_Q32 ((int64_t)246083499208)

/* Angle between two vectors in Q16.16 degrees, [0, 180]; 0 if either is 0. */
static cub_q16 angle_deg(v64 a, v64 b)
{
    int64_t rad = cub_fx_vec3_angle(fit(a), fit(b)); /* [0, pi] in Q16.16 */
    return (cub_q16)((rad * DEG_PER_RAD_Q32 + ((int64_t)1 << 31)) >> 32);
}

static int in_range(int idx, int n)
{
    return idx >= 0 && idx < n;
}

/* Required joints in range; optional ones (spine, head) -1 or in range. */
static int body_ok(const cub_fuzzy_body *b, const cub_vec3 *world, int n)
{
    if (!b || !world || n <= 0) return 0;
    const int16_t required[] = {
        b->hip_centre, b->shoulder_centre, b->shoulder[0], b->shoulder[1], b->elbow[0],
        b->elbow[1],   b->wrist[0],        b->wrist[1],    b->hip[0],      b->hip[1],
        b->knee[0],    b->knee[1],         b->ankle[0],    b->ankle[1],
    };
    for (size_t i = 0; i < sizeof required / sizeof required[0]; i++)
        if (!in_range(required[i], n)) return 0;
    if (b->spine != -1 && !in_range(b->spine, n)) return 0;
    if (b->head != -1 && !in_range(b->head, n)) return 0;
    return 1;
}

/* The CoG as a mass-weighted mean of segment midpoints, masses in percent
 * after adult tables (de Leva 1996, rounded): trunk with pelvis 50 at the
 * middle of hip_centre..shoulder_centre, head and neck 8 at the head (at the
 * shoulder centre if the skeleton has no head), upper arms 3, forearms with
 * hands 2, thighs 10, shanks with feet 6. Sitting drops the trunk and
 * thighs to seat height, so it reads low; a jump lifts everything. Only the
 * height is needed. */
typedef struct segment {
    int weight;
    int a, b; /* joint indices: the segment's midpoint */
} segment;

static int64_t cog_y_q16(const cub_fuzzy_body *bd, const cub_vec3 *w)
{
    int head = bd->head >= 0 ? bd->head : bd->shoulder_centre;
    const segment seg[] = {
        {50, bd->hip_centre, bd->shoulder_centre},
        {8, head, head},
        {3, bd->shoulder[0], bd->elbow[0]},
        {3, bd->shoulder[1], bd->elbow[1]},
        {2, bd->elbow[0], bd->wrist[0]},
        {2, bd->elbow[1], bd->wrist[1]},
        {10, bd->hip[0], bd->knee[0]},
        {10, bd->hip[1], bd->knee[1]},
        {6, bd->knee[0], bd->ankle[0]},
        {6, bd->knee[1], bd->ankle[1]},
    };
    int64_t sum = 0, mass = 0;
    for (size_t i = 0; i < sizeof seg / sizeof seg[0]; i++) {
        sum += (int64_t)seg[i].weight * ((int64_t)w[seg[i].a].y + w[seg[i].b].y);
        mass += 2 * seg[i].weight;
    }
    return sum / mass;
}

cub_q16 cub_fuzzy_cog_height_mm(const cub_fuzzy_body *body, const cub_vec3 *world_mm,
                                int joint_count)
{
    if (!body_ok(body, world_mm, joint_count)) return 0;
    int64_t h = cog_y_q16(body, world_mm) - body->floor_y_mm;
    return h > INT32_MAX ? INT32_MAX : h < INT32_MIN ? INT32_MIN : (cub_q16)h;
}

/* num/den rounded to nearest (den > 0), saturated to int32. */
static cub_q16 div_round(int64_t num, int64_t den)
{
    int64_t q = (num >= 0 ? num + den / 2 : num - den / 2) / den;
    return q > INT32_MAX ? INT32_MAX : q < INT32_MIN ? INT32_MIN : (cub_q16)q;
}

/* Abduction of one leg (side 0 left, 1 right), see the top of the file. */
static cub_q16 abduction_deg(const cub_fuzzy_body *b, const cub_vec3 *w, int side)
{
    v64 out = sub(w[b->hip[side]], w[b->hip[1 - side]]);
    if (out.x == 0 && out.y == 0 && out.z == 0) return 0;
    v64 thigh = sub(w[b->knee[side]], w[b->hip[side]]);
    return CUB_Q16_INT(90) - angle_deg(thigh, out);
}

/* One side's four inputs into the right slots of in[]. */
static void limb_inputs(const cub_fuzzy_body *b, const cub_vec3 *w, int side, v64 down,
                        cub_q16 in[])
{
    int right = side == 1;
    v64 upper = sub(w[b->elbow[side]], w[b->shoulder[side]]);
    v64 fore = sub(w[b->wrist[side]], w[b->elbow[side]]);
    in[right ? CUB_FUZZY_RH : CUB_FUZZY_LH] = angle_deg(upper, down);
    in[right ? CUB_FUZZY_RHE : CUB_FUZZY_LHE] = angle_deg(upper, fore);
    in[right ? CUB_FUZZY_RF : CUB_FUZZY_LF] = abduction_deg(b, w, side);
    v64 to_hip = sub(w[b->hip[side]], w[b->knee[side]]);
    v64 to_ankle = sub(w[b->ankle[side]], w[b->knee[side]]);
    in[right ? CUB_FUZZY_RFK : CUB_FUZZY_LFK] = angle_deg(to_hip, to_ankle);
}

cub_err cub_fuzzy_features(const cub_fuzzy_body *body, const cub_vec3 *world_mm, int joint_count,
                           cub_fuzzy_frame *out)
{
    if (!out) return CUB_ERR_ARG;
    *out = (cub_fuzzy_frame){0};
    if (!body_ok(body, world_mm, joint_count) || body->stand_cog_mm <= 0) return CUB_ERR_ARG;
    const cub_fuzzy_body *b = body;
    const cub_vec3 *w = world_mm;
    cub_q16 *in = out->input;

    v64 down = sub(w[b->hip_centre], w[b->shoulder_centre]);
    limb_inputs(b, w, 0, down, in);
    limb_inputs(b, w, 1, down, in);

    int64_t h = cog_y_q16(b, w) - b->floor_y_mm;
    in[CUB_FUZZY_POSTURE] = div_round(h * 80 * CUB_Q16_ONE, b->stand_cog_mm);

    v64 up = sub(w[b->shoulder_centre], w[b->hip_centre]);
    v64 thighs = add(sub(w[b->knee[0]], w[b->hip[0]]), sub(w[b->knee[1]], w[b->hip[1]]));
    in[CUB_FUZZY_TRUNK] = angle_deg(up, thighs);

    for (int k = 0; k < CUB_FUZZY_FEATURE_COUNT; k++)
        cub_fuzzy_membership((cub_fuzzy_feature)k, in[k], out->mu[k]);
    return CUB_OK;
}

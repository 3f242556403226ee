/* The body: rounded primitives placed by the 20 joints, in child
 * proportions. Radii are fractions of the height H (a 1150 mm child: upper
 * arm 35 mm, thigh 58 mm, head 74 x 104 x 90 mm), times the build factor;
 * loose clothes widen the torso and thighs and add a skirt-like hem; at
 * level 2 also a loose shirt over the chest, wide sleeves and baggy legs
 * (fixed fractions: deterministic). */
#include "synth_internal.h"

#define NECK_F 0.03f    /* neck length / H */
#define HEAD_UP_F 0.09f /* head half-height / H */
#define FOOT_R_F 0.028f

float synth_body_above_shoulders_mm(const synth_body_shape *s)
{
    return s->height_mm * (NECK_F + 2 * HEAD_UP_F);
}

float synth_body_hand_mm(const synth_body_shape *s)
{
    return s->height_mm * 0.045f;
}

void synth_body_foot_ends(cub_fv3 ankle, cub_fv3 foot, cub_fv3 *heel, cub_fv3 *toe)
{
    *heel = cub_fv3_lerp(ankle, foot, -0.25f);
    *toe = cub_fv3_lerp(ankle, foot, 1.25f);
}

float synth_body_sole_mm(const synth_body_shape *s)
{
    return s->height_mm * FOOT_R_F;
}

void synth_body_head(const synth_body_shape *s, cub_fv3 sc, cub_fv3 head_dir_point, cub_fv3 *centre,
                     cub_fv3 *top)
{
    cub_fv3 u = cub_fv3_norm(cub_fv3_sub(head_dir_point, sc), cub_fv3_make(0, 1, 0));
    float h = s->height_mm;
    *centre = cub_fv3_add(sc, cub_fv3_scale(u, h * (NECK_F + HEAD_UP_F)));
    *top = cub_fv3_add(*centre, cub_fv3_scale(u, h * HEAD_UP_F));
}

static float loose_add(const synth_body_shape *s, float f)
{
    return s->loose ? f * s->height_mm : 0;
}

/* Level 2 only: the shirt, sleeves and trouser legs. */
static float baggy_add(const synth_body_shape *s, float f)
{
    return s->loose >= 2 ? f * s->height_mm : 0;
}

float synth_body_joint_radius(const synth_body_shape *s, int j)
{
    float h = s->height_mm, b = s->build;
    switch (j) {
    case CUB_KJ_HIP_CENTRE:
    case CUB_KJ_SPINE:
    case CUB_KJ_SHOULDER_CENTRE: return 0.06f * h * b + loose_add(s, 0.02f) + baggy_add(s, 0.015f);
    case CUB_KJ_HEAD: return 0.078f * h;
    case CUB_KJ_HIP_L:
    case CUB_KJ_HIP_R: return 0.05f * h * b + loose_add(s, 0.015f);
    case CUB_KJ_KNEE_L:
    case CUB_KJ_KNEE_R: return 0.036f * h * b + baggy_add(s, 0.012f);
    case CUB_KJ_SHOULDER_L:
    case CUB_KJ_SHOULDER_R: return 0.038f * h * b + baggy_add(s, 0.015f);
    case CUB_KJ_ELBOW_L:
    case CUB_KJ_ELBOW_R: return 0.028f * h * b + baggy_add(s, 0.015f);
    default: return 0.025f * h;
    }
}

static synth_prim capsule(cub_fv3 a, cub_fv3 b, float r, uint8_t owner)
{
    synth_prim p = {.kind = PRIM_CAPSULE, .owner = owner, .a = a, .b = b, .r = r};
    return p;
}

static synth_prim ellipsoid(cub_fv3 c, const cub_fv3 axis[3], float rx, float ry, float rz,
                            uint8_t owner)
{
    synth_prim p = {.kind = PRIM_ELLIPSOID, .owner = owner, .a = c};
    for (int i = 0; i < 3; i++)
        p.axis[i] = axis[i];
    p.radii[0] = rx;
    p.radii[1] = ry;
    p.radii[2] = rz;
    return p;
}

/* side (x), up (y), forward (z): an orthonormal frame from up and a rough
 * side direction. */
static void frame_of(cub_fv3 up, cub_fv3 side, cub_fv3 axis[3])
{
    axis[1] = cub_fv3_norm(up, cub_fv3_make(0, 1, 0));
    cub_fv3 across = cub_fv3_sub(side, cub_fv3_scale(axis[1], cub_fv3_dot(side, axis[1])));
    axis[0] = cub_fv3_norm(across, cub_fv3_make(0, 1, 0));
    axis[2] = cub_fv3_cross(axis[0], axis[1]);
}

int synth_body_prims(const synth_body_shape *s, const cub_fv3 p[SP_COUNT], uint8_t owner,
                     synth_prim *out)
{
    float h = s->height_mm, b = s->build;
    int n = 0;
    cub_fv3 ax[3];
    frame_of(cub_fv3_sub(p[CUB_KJ_HEAD], p[CUB_KJ_SHOULDER_CENTRE]),
             cub_fv3_sub(p[CUB_KJ_SHOULDER_L], p[CUB_KJ_SHOULDER_R]), ax);
    out[n++] = ellipsoid(p[CUB_KJ_HEAD], ax, 0.064f * h, HEAD_UP_F * h, 0.078f * h, owner);
    out[n - 1].part = CUB_PART_HEAD;
    out[n++] = capsule(p[CUB_KJ_SHOULDER_CENTRE], p[CUB_KJ_HEAD], 0.03f * h * b, owner);
    out[n - 1].part = CUB_PART_TORSO_UPPER;

    frame_of(cub_fv3_sub(p[CUB_KJ_SHOULDER_CENTRE], p[CUB_KJ_HIP_CENTRE]),
             cub_fv3_sub(p[CUB_KJ_SHOULDER_L], p[CUB_KJ_SHOULDER_R]), ax);
    float wide = loose_add(s, 0.02f) + baggy_add(s, 0.015f);
    out[n++] = ellipsoid(cub_fv3_lerp(p[CUB_KJ_SPINE], p[CUB_KJ_SHOULDER_CENTRE], 0.35f), ax,
                         0.095f * h * b + wide, 0.15f * h, 0.06f * h * b + wide, owner);
    out[n - 1].part = CUB_PART_TORSO_UPPER;
    out[n++] = ellipsoid(cub_fv3_lerp(p[CUB_KJ_HIP_CENTRE], p[CUB_KJ_SPINE], 0.2f), ax,
                         0.09f * h * b + wide, 0.12f * h, 0.058f * h * b + wide, owner);
    out[n - 1].part = CUB_PART_TORSO_LOWER;
    out[n++] = capsule(p[CUB_KJ_SHOULDER_L], p[CUB_KJ_SHOULDER_R], 0.038f * h * b, owner);
    out[n - 1].part = CUB_PART_TORSO_UPPER;
    out[n++] = capsule(p[CUB_KJ_HIP_L], p[CUB_KJ_HIP_R], 0.05f * h * b, owner);
    out[n - 1].part = CUB_PART_TORSO_LOWER;
    for (int side = 0; side < 2; side++) {
        int sh = side ? CUB_KJ_SHOULDER_R : CUB_KJ_SHOULDER_L;
        int arm = side ? CUB_PART_UPPER_ARM_R : CUB_PART_UPPER_ARM_L;
        out[n++] = capsule(p[sh], p[sh + 1], 0.03f * h * b + baggy_add(s, 0.015f), owner);
        out[n++] = capsule(p[sh + 1], p[sh + 2], 0.025f * h * b + baggy_add(s, 0.012f), owner);
        cub_fv3 tip = cub_fv3_lerp(p[sh + 2], p[sh + 3], 2.0f);
        out[n++] = capsule(p[sh + 2], tip, 0.021f * h, owner);
        for (int k = 0; k < 3; k++)
            out[n - 3 + k].part = (uint8_t)(arm + k);
        int hip = side ? CUB_KJ_HIP_R : CUB_KJ_HIP_L;
        int leg = side ? CUB_PART_THIGH_R : CUB_PART_THIGH_L;
        out[n++] = capsule(p[hip], p[hip + 1], 0.05f * h * b + loose_add(s, 0.015f), owner);
        out[n++] = capsule(p[hip + 1], p[hip + 2], 0.036f * h * b + baggy_add(s, 0.012f), owner);
        cub_fv3 heel, toe;
        synth_body_foot_ends(p[hip + 2], p[hip + 3], &heel, &toe);
        out[n++] = capsule(heel, toe, FOOT_R_F * h, owner);
        for (int k = 0; k < 3; k++)
            out[n - 3 + k].part = (uint8_t)(leg + k);
    }
    if (s->loose) {
        cub_fv3 hips = cub_fv3_lerp(p[CUB_KJ_HIP_L], p[CUB_KJ_HIP_R], 0.5f);
        cub_fv3 knees = cub_fv3_lerp(p[CUB_KJ_KNEE_L], p[CUB_KJ_KNEE_R], 0.5f);
        synth_prim c = {.kind = PRIM_CYLINDER,
                        .owner = owner,
                        .a = cub_fv3_lerp(p[CUB_KJ_HIP_CENTRE], p[CUB_KJ_SPINE], 0.3f),
                        .b = cub_fv3_lerp(hips, knees, 0.55f),
                        .r = 0.115f * h * b,
                        .part = CUB_PART_TORSO_LOWER};
        out[n++] = c;
    }
    for (int i = 0; i < n; i++)
        synth_prim_bound(&out[i]);
    return n;
}

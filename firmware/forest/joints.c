/* Joints from the part proposals (cub/forest.h): every part proposed,
 * then the joints the parts give, with whether the forest is confident of
 * each. Integers only. */
#include <string.h>

#include "cub/forest.h"

#define HALF_Q16 32768

/* Per part: kernel radius, the joint's depth behind the mode (about 0.7 of
 * the part's radius in synth's body, child of 1.15 m), and the surface a
 * proposal needs to be confident. Set from the body's sizes before any
 * measurement; the probability floor is Shotton et al.'s 0.14. */
static const struct {
    int32_t radius_mm, push_mm, min_area_mm2;
} PART[CUB_PART_COUNT] = {
    [CUB_PART_HEAD] = {100, 60, 6000},       [CUB_PART_TORSO_UPPER] = {150, 45, 10000},
    [CUB_PART_TORSO_LOWER] = {150, 45, 10000}, [CUB_PART_UPPER_ARM_L] = {80, 25, 1500},
    [CUB_PART_FOREARM_L] = {70, 20, 1500},   [CUB_PART_HAND_L] = {60, 15, 1500},
    [CUB_PART_UPPER_ARM_R] = {80, 25, 1500}, [CUB_PART_FOREARM_R] = {70, 20, 1500},
    [CUB_PART_HAND_R] = {60, 15, 1500},      [CUB_PART_THIGH_L] = {100, 40, 2500},
    [CUB_PART_SHIN_L] = {80, 30, 2000},      [CUB_PART_FOOT_L] = {70, 20, 1500},
    [CUB_PART_THIGH_R] = {100, 40, 2500},    [CUB_PART_SHIN_R] = {80, 30, 2000},
    [CUB_PART_FOOT_R] = {70, 20, 1500},
};
#define MIN_PROB 9175 /* 0.14, Q0.16 */

void cub_forest_propose_all(const cub_forest_points *pts, cub_forest_proposal prop[CUB_PART_COUNT])
{
    memset(prop, 0, sizeof(*prop) * CUB_PART_COUNT);
    for (int p = 1; p < CUB_PART_COUNT && p < pts->classes; p++) {
        cub_forest_shift sh = {PART[p].radius_mm, MIN_PROB, PART[p].push_mm};
        cub_forest_propose(pts, p, &sh, &prop[p]);
    }
}

static int confident(const cub_forest_proposal *p, int part)
{
    return p->found && p->share >= HALF_Q16 && p->area_mm2 >= PART[part].min_area_mm2;
}

/* A joint that is a part's own centre (head, hands, feet). */
static void own(const cub_forest_proposal *prop, int part, int joint, cub_forest_joints *out)
{
    const cub_forest_proposal *p = &prop[part];
    if (!p->found) return;
    memcpy(out->mm[joint], p->mm, sizeof(p->mm));
    out->have[joint] = 1;
    out->confident[joint] = (uint8_t)confident(p, part);
}

/* A joint between two segments (elbow, knee): the midpoint of their
 * centres (exact for a straight limb, a quarter of the bend off). */
static void between(const cub_forest_proposal *prop, int a, int b, int joint, cub_forest_joints *out)
{
    if (!prop[a].found || !prop[b].found) return;
    for (int k = 0; k < 3; k++)
        out->mm[joint][k] = (prop[a].mm[k] + prop[b].mm[k]) / 2;
    out->have[joint] = 1;
    out->confident[joint] = (uint8_t)(confident(&prop[a], a) && confident(&prop[b], b));
}

void cub_forest_joints_of(const cub_forest_proposal prop[CUB_PART_COUNT], cub_forest_joints *out)
{
    memset(out, 0, sizeof(*out));
    own(prop, CUB_PART_HEAD, CUB_KJ_HEAD, out);
    own(prop, CUB_PART_HAND_L, CUB_KJ_HAND_L, out);
    own(prop, CUB_PART_HAND_R, CUB_KJ_HAND_R, out);
    own(prop, CUB_PART_FOOT_L, CUB_KJ_FOOT_L, out);
    own(prop, CUB_PART_FOOT_R, CUB_KJ_FOOT_R, out);
    between(prop, CUB_PART_UPPER_ARM_L, CUB_PART_FOREARM_L, CUB_KJ_ELBOW_L, out);
    between(prop, CUB_PART_UPPER_ARM_R, CUB_PART_FOREARM_R, CUB_KJ_ELBOW_R, out);
    between(prop, CUB_PART_THIGH_L, CUB_PART_SHIN_L, CUB_KJ_KNEE_L, out);
    between(prop, CUB_PART_THIGH_R, CUB_PART_SHIN_R, CUB_KJ_KNEE_R, out);
}


/* judge: what a wrong verdict says to fix (cub/judge.h, "A wrong
 * verdict's fault"): the fault as one number for the loop event, the limb
 * it is about and that limb's tracker joints. */
#include <stdint.h>

#include "cub/judge.h"
#include "cub/kinect.h"

#define ALL_LIMBS ((1u << (CUB_JUDGE_LIMB_COUNT - 1)) - 1u)

static int fault_ok(cub_judge_fault f)
{
    return f.how > CUB_JUDGE_HOW_NONE && f.how < CUB_JUDGE_HOW_COUNT && f.feature >= 0 &&
           f.feature < CUB_FUZZY_FEATURE_COUNT && f.set >= 0 &&
           f.set < cub_fuzzy_set_count((cub_fuzzy_feature)f.feature) && f.limbs <= ALL_LIMBS;
}

int32_t cub_judge_fault_code(cub_judge_fault f)
{
    return fault_ok(f) ? (int32_t)f.limbs * 1000 + f.how * 100 + f.feature * 10 + f.set : 0;
}

cub_judge_fault cub_judge_fault_of(int32_t code)
{
    cub_judge_fault none = {CUB_JUDGE_HOW_NONE, -1, -1, 0};
    if (code <= 0 || code / 1000 > (int32_t)ALL_LIMBS) return none;
    cub_judge_fault f = {code / 100 % 10, code / 10 % 10, code % 10, (uint32_t)(code / 1000)};
    return fault_ok(f) ? f : none;
}

int32_t cub_judge_fault_limb(cub_judge_fault f)
{
    if (!fault_ok(f)) return CUB_JUDGE_LIMB_NONE;
    switch (f.feature) {
    case CUB_FUZZY_RH:
    case CUB_FUZZY_RHE: return CUB_JUDGE_LIMB_RIGHT_ARM;
    case CUB_FUZZY_LH:
    case CUB_FUZZY_LHE: return CUB_JUDGE_LIMB_LEFT_ARM;
    case CUB_FUZZY_RF:
    case CUB_FUZZY_RFK: return CUB_JUDGE_LIMB_RIGHT_LEG;
    case CUB_FUZZY_LF:
    case CUB_FUZZY_LFK: return CUB_JUDGE_LIMB_LEFT_LEG;
    case CUB_FUZZY_POSTURE: return CUB_JUDGE_LIMB_LEGS;
    default: return CUB_JUDGE_LIMB_TRUNK;
    }
}

uint32_t cub_judge_fault_joints(cub_judge_fault f)
{
    if (!fault_ok(f)) return 0;
    if (!f.limbs) return cub_judge_limb_joints(cub_judge_fault_limb(f));
    uint32_t joints = 0;
    for (int32_t limb = 1; limb < CUB_JUDGE_LIMB_COUNT; limb++)
        if (f.limbs >> (limb - 1) & 1u) joints |= cub_judge_limb_joints(limb);
    return joints;
}

#define BIT(j) (1u << (j))

uint32_t cub_judge_limb_joints(int32_t limb)
{
    /* A joint stands for its bone to its parent: an arm from the shoulder
     * (the collar bone) to the hand, a leg from the hip to the foot. */
    const uint32_t arm_l = BIT(CUB_KJ_SHOULDER_L) | BIT(CUB_KJ_ELBOW_L) | BIT(CUB_KJ_WRIST_L) |
                           BIT(CUB_KJ_HAND_L);
    const uint32_t arm_r = BIT(CUB_KJ_SHOULDER_R) | BIT(CUB_KJ_ELBOW_R) | BIT(CUB_KJ_WRIST_R) |
                           BIT(CUB_KJ_HAND_R);
    const uint32_t leg_l =
        BIT(CUB_KJ_HIP_L) | BIT(CUB_KJ_KNEE_L) | BIT(CUB_KJ_ANKLE_L) | BIT(CUB_KJ_FOOT_L);
    const uint32_t leg_r =
        BIT(CUB_KJ_HIP_R) | BIT(CUB_KJ_KNEE_R) | BIT(CUB_KJ_ANKLE_R) | BIT(CUB_KJ_FOOT_R);
    switch (limb) {
    case CUB_JUDGE_LIMB_RIGHT_ARM: return arm_r;
    case CUB_JUDGE_LIMB_LEFT_ARM: return arm_l;
    case CUB_JUDGE_LIMB_RIGHT_LEG: return leg_r;
    case CUB_JUDGE_LIMB_LEFT_LEG: return leg_l;
    case CUB_JUDGE_LIMB_LEGS: return leg_l | leg_r;
    case CUB_JUDGE_LIMB_TRUNK: return BIT(CUB_KJ_SPINE) | BIT(CUB_KJ_SHOULDER_CENTRE);
    default: return 0;
    }
}

const char *cub_judge_how_name(int32_t how)
{
    static const char *const names[CUB_JUDGE_HOW_COUNT] = {"none", "missed", "mirror"};
    return how >= 0 && how < CUB_JUDGE_HOW_COUNT ? names[how] : "?";
}

const char *cub_judge_limb_name(int32_t limb)
{
    static const char *const names[CUB_JUDGE_LIMB_COUNT] = {
        "none", "right_arm", "left_arm", "right_leg", "left_leg", "legs", "trunk"};
    return limb >= 0 && limb < CUB_JUDGE_LIMB_COUNT ? names[limb] : "?";
}

/* kinect — the 20 joints' names and parents, and the fuzzy body over them
 * (see kinect.h). */
#include "cub/kinect.h"

const char *cub_kinect_joint_name(int32_t joint)
{
    static const char *const names[CUB_KJ_COUNT] = {
        "hip_centre", "spine",      "shoulder_centre", "head",    "shoulder_l",
        "elbow_l",    "wrist_l",    "hand_l",          "shoulder_r", "elbow_r",
        "wrist_r",    "hand_r",     "hip_l",           "knee_l",  "ankle_l",
        "foot_l",     "hip_r",      "knee_r",          "ankle_r", "foot_r"};
    return joint >= 0 && joint < CUB_KJ_COUNT ? names[joint] : "?";
}

int32_t cub_kinect_joint_parent(int32_t joint)
{
    static const int8_t parents[CUB_KJ_COUNT] = {
        [CUB_KJ_HIP_CENTRE] = -1,
        [CUB_KJ_SPINE] = CUB_KJ_HIP_CENTRE,
        [CUB_KJ_SHOULDER_CENTRE] = CUB_KJ_SPINE,
        [CUB_KJ_HEAD] = CUB_KJ_SHOULDER_CENTRE,
        [CUB_KJ_SHOULDER_L] = CUB_KJ_SHOULDER_CENTRE,
        [CUB_KJ_ELBOW_L] = CUB_KJ_SHOULDER_L,
        [CUB_KJ_WRIST_L] = CUB_KJ_ELBOW_L,
        [CUB_KJ_HAND_L] = CUB_KJ_WRIST_L,
        [CUB_KJ_SHOULDER_R] = CUB_KJ_SHOULDER_CENTRE,
        [CUB_KJ_ELBOW_R] = CUB_KJ_SHOULDER_R,
        [CUB_KJ_WRIST_R] = CUB_KJ_ELBOW_R,
        [CUB_KJ_HAND_R] = CUB_KJ_WRIST_R,
        [CUB_KJ_HIP_L] = CUB_KJ_HIP_CENTRE,
        [CUB_KJ_KNEE_L] = CUB_KJ_HIP_L,
        [CUB_KJ_ANKLE_L] = CUB_KJ_KNEE_L,
        [CUB_KJ_FOOT_L] = CUB_KJ_ANKLE_L,
        [CUB_KJ_HIP_R] = CUB_KJ_HIP_CENTRE,
        [CUB_KJ_KNEE_R] = CUB_KJ_HIP_R,
        [CUB_KJ_ANKLE_R] = CUB_KJ_KNEE_R,
        [CUB_KJ_FOOT_R] = CUB_KJ_ANKLE_R,
    };
    return joint >= 0 && joint < CUB_KJ_COUNT ? parents[joint] : -1;
}

cub_fuzzy_body cub_kinect_fuzzy_body(cub_q16 floor_y_mm, cub_q16 stand_cog_mm)
{
    cub_fuzzy_body b = {
        .hip_centre = CUB_KJ_HIP_CENTRE,
        .spine = CUB_KJ_SPINE,
        .shoulder_centre = CUB_KJ_SHOULDER_CENTRE,
        .head = CUB_KJ_HEAD,
        .shoulder = {CUB_KJ_SHOULDER_L, CUB_KJ_SHOULDER_R},
        .elbow = {CUB_KJ_ELBOW_L, CUB_KJ_ELBOW_R},
        .wrist = {CUB_KJ_WRIST_L, CUB_KJ_WRIST_R},
        .hip = {CUB_KJ_HIP_L, CUB_KJ_HIP_R},
        .knee = {CUB_KJ_KNEE_L, CUB_KJ_KNEE_R},
        .ankle = {CUB_KJ_ANKLE_L, CUB_KJ_ANKLE_R},
        .floor_y_mm = floor_y_mm,
        .stand_cog_mm = stand_cog_mm,
    };
    return b;
}

/* The skeleton's joint names (Kinect SDK order, track.h). */
#include "cub/track.h"

const char *cub_track_joint_name(int32_t joint)
{
    static const char *const names[CUB_TJ_COUNT] = {
        "hip_centre", "spine",      "shoulder_centre", "head",    "shoulder_l",
        "elbow_l",    "wrist_l",    "hand_l",          "shoulder_r", "elbow_r",
        "wrist_r",    "hand_r",     "hip_l",           "knee_l",  "ankle_l",
        "foot_l",     "hip_r",      "knee_r",          "ankle_r", "foot_r"};
    return joint >= 0 && joint < CUB_TJ_COUNT ? names[joint] : "?";
}

/* kinect — the Kinect v1's conventions that every module shares (the
 * tracker, the judge, the depth synthesizer, the renderer's inset, the
 * tools and the tests): the depth image and its raw units, the camera model
 * that takes a pixel to camera space (mm), the accelerometer's units, and
 * the 20-joint skeleton (order, names, parents) with the fuzzy body that
 * reads it. Constants and lookups; no state, no allocation. */
#ifndef CUB_KINECT_H
#define CUB_KINECT_H

#include <stdint.h>

#include "cub/fuzzy.h"

/* ---- the depth image ---------------------------------------------------- */

/* 640x480, row-major, raw 11-bit disparity; 2047 means no reading. */
#define CUB_KINECT_WIDTH 640
#define CUB_KINECT_HEIGHT 480
#define CUB_KINECT_NO_READING 2047

/* Raw to millimetres, mm = 123.6 * tan(raw / 2842.5 + 1.1863) (the data
 * README): MM_SCALE * tan(raw / RAW_PER_RAD + RAW_OFFSET_RAD). For host
 * tools and tables made offline; the firmware looks it up in a table
 * (cub_track_raw_to_mm). */
#define CUB_KINECT_MM_SCALE 123.6
#define CUB_KINECT_RAW_PER_RAD 2842.5
#define CUB_KINECT_RAW_OFFSET_RAD 1.1863

/* ---- the camera ------------------------------------------------------------ */

/* Camera space, millimetres: x to the right in the depth image, y up, z
 * away from the camera (the reading's depth). A pixel (u, v) at depth z
 * sits at x = (u - CX) * z / F, y = (CY - v) * z / F. F is the depth
 * camera's focal length in pixels; the principal point is the image centre. */
#define CUB_KINECT_FOCAL_PX 580
#define CUB_KINECT_CX 320
#define CUB_KINECT_CY 240

/* The accelerometer (libfreenect's freenect_raw_tilt_state, as a-*.dump
 * files hold it): int16 counts per axis in camera space, 819 counts a g.
 * It reads the push that holds the camera up, the opposite of gravity: a
 * level Kinect reads (0, +819, 0). */
#define CUB_KINECT_ACCEL_COUNTS_PER_G 819

/* ---- the skeleton ---------------------------------------------------------- */

/* The 20 joints in the Kinect SDK order (UTKinect files use it; see
 * ../shared/data/README.md). Left and right are the player's own. */
typedef enum cub_kinect_joint {
    CUB_KJ_HIP_CENTRE = 0,
    CUB_KJ_SPINE,
    CUB_KJ_SHOULDER_CENTRE,
    CUB_KJ_HEAD,
    CUB_KJ_SHOULDER_L,
    CUB_KJ_ELBOW_L,
    CUB_KJ_WRIST_L,
    CUB_KJ_HAND_L,
    CUB_KJ_SHOULDER_R,
    CUB_KJ_ELBOW_R,
    CUB_KJ_WRIST_R,
    CUB_KJ_HAND_R,
    CUB_KJ_HIP_L,
    CUB_KJ_KNEE_L,
    CUB_KJ_ANKLE_L,
    CUB_KJ_FOOT_L,
    CUB_KJ_HIP_R,
    CUB_KJ_KNEE_R,
    CUB_KJ_ANKLE_R,
    CUB_KJ_FOOT_R,
    CUB_KJ_COUNT
} cub_kinect_joint;

/* "hip_centre", "spine", ..., "foot_r"; "?" out of range. */
const char *cub_kinect_joint_name(int32_t joint);
/* The joint's parent in the tree rooted at the hip centre; -1 for the root
 * and out of range. */
int32_t cub_kinect_joint_parent(int32_t joint);
/* The fuzzy features' view of these joints, floor_y_mm and stand_cog_mm
 * as given (the caller knows its floor and the player's height). */
cub_fuzzy_body cub_kinect_fuzzy_body(cub_q16 floor_y_mm, cub_q16 stand_cog_mm);

#endif

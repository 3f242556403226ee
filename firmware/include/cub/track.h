/* track — from Kinect depth to the player's skeleton (seed card): the
 * depth units, the camera and skeleton conventions every module shares,
 * and the tracker.
 *
 * The Kinect v1 reports raw 11-bit disparity; 2047 means no reading. Depth
 * in millimetres is mm = 123.6 * tan(raw / 2842.5 + 1.1863) (the data
 * README), looked up in a table computed offline, so no libm is needed and
 * every CPU gets the same numbers.
 */
#ifndef CUB_TRACK_H
#define CUB_TRACK_H

#include <stddef.h>
#include <stdint.h>

#include "cub/err.h"
#include "cub/fx.h"

#define CUB_TRACK_RAW_NO_READING 2047
#define CUB_TRACK_WIDTH 640
#define CUB_TRACK_HEIGHT 480

/* ---- the camera and the skeleton (shared by the tracker, the judge, the
 * depth synthesizer and the evaluation tools) ---------------------------- */

/* Camera space, millimetres: x to the right in the depth image, y up, z
 * away from the camera (the reading's depth). A pixel (u, v) of the 640x480
 * image at depth z sits at x = (u - CX) * z / F, y = (CY - v) * z / F.
 * F is the Kinect v1 depth camera's focal length in pixels; the principal
 * point is the image centre. */
#define CUB_TRACK_FOCAL_PX 580
#define CUB_TRACK_CX 320
#define CUB_TRACK_CY 240

/* The 20 joints in the Kinect SDK order (UTKinect files use it; see
 * ../shared/data/README.md). Left and right are the player's own. */
typedef enum cub_track_joint {
    CUB_TJ_HIP_CENTRE = 0,
    CUB_TJ_SPINE,
    CUB_TJ_SHOULDER_CENTRE,
    CUB_TJ_HEAD,
    CUB_TJ_SHOULDER_L,
    CUB_TJ_ELBOW_L,
    CUB_TJ_WRIST_L,
    CUB_TJ_HAND_L,
    CUB_TJ_SHOULDER_R,
    CUB_TJ_ELBOW_R,
    CUB_TJ_WRIST_R,
    CUB_TJ_HAND_R,
    CUB_TJ_HIP_L,
    CUB_TJ_KNEE_L,
    CUB_TJ_ANKLE_L,
    CUB_TJ_FOOT_L,
    CUB_TJ_HIP_R,
    CUB_TJ_KNEE_R,
    CUB_TJ_ANKLE_R,
    CUB_TJ_FOOT_R,
    CUB_TJ_COUNT
} cub_track_joint;

/* What the tracker can say about the player in a frame. */
typedef enum cub_track_status {
    CUB_TRACK_OK = 0,        /* a player, whole in view */
    CUB_TRACK_NO_PLAYER,     /* nobody (or no usable frame) */
    CUB_TRACK_TOO_CLOSE,     /* nearer than the range the body fits in */
    CUB_TRACK_TOO_FAR,       /* beyond the range the Kinect reads well */
    CUB_TRACK_PARTLY_OUT,    /* part of the body leaves the image */
} cub_track_status;

/* One frame's player. joint_mm in camera space (above); confidence in
 * [0, 1] Q16.16 per joint, 0 = not seen (its position is a guess). */
typedef struct cub_track_skeleton {
    int32_t status; /* cub_track_status */
    int32_t player_id; /* stays the same while the same person is tracked */
    cub_vec3 joint_mm[CUB_TJ_COUNT];
    cub_q16 confidence[CUB_TJ_COUNT];
} cub_track_skeleton;

/* "hip_centre", "spine", ..., "foot_r"; "?" out of range. */
const char *cub_track_joint_name(int32_t joint);

/* ---- the tracker --------------------------------------------------------- */

/* Zero-initialised fields take defaults (the implementation documents
 * them). */
typedef struct cub_track_desc {
    int32_t min_mm, max_mm; /* the range a player is looked for in; 0 = defaults */
} cub_track_desc;

/* The tracker's state lives in caller memory (no heap). */
typedef struct cub_tracker cub_tracker;

/* Bytes of memory cub_track_init needs for this desc. */
size_t cub_track_mem_size(const cub_track_desc *desc);
/* Set up a tracker in mem (aligned to 16). CUB_ERR_ARG, CUB_ERR_NOMEM. */
cub_err cub_track_init(const cub_track_desc *desc, void *mem, size_t mem_size, cub_tracker **out);
/* One 640x480 raw 11-bit frame (row-major, 2047 = no reading) taken at
 * t_us; gravity_mm: the accelerometer's down direction in camera space
 * (any length), or NULL when unknown. Always fills *out: a frame without
 * a usable player gives status NO_PLAYER (or TOO_CLOSE, ...), never an
 * error. CUB_ERR_ARG only for NULL pointers. */
cub_err cub_track_frame(cub_tracker *t, const uint16_t *raw, int64_t t_us,
                        const cub_vec3 *gravity_mm, cub_track_skeleton *out);

/* Depth of a raw value in Q16.16 mm (step 1/8 mm); 0 = no usable reading
 * (2047, values above 2047, or farther than 8191 mm). */
cub_q16 cub_track_raw_to_mm(uint16_t raw);
/* The same, rounded to whole millimetres; 0 = no reading. */
uint16_t cub_track_raw_to_mm_int(uint16_t raw);

#endif

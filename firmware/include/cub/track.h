/* track — from Kinect depth to the player's skeleton (seed card). The
 * image, the camera space and the 20 joints are the Kinect's (kinect.h).
 *
 * Raw depth to millimetres is looked up in a table computed offline from
 * the Kinect's formula, so no libm is needed and every CPU gets the same
 * numbers.
 */
#ifndef CUB_TRACK_H
#define CUB_TRACK_H

#include <stddef.h>
#include <stdint.h>

#include "cub/err.h"
#include "cub/fx.h"
#include "cub/kinect.h"

/* What the tracker can say about the player in a frame. */
typedef enum cub_track_status {
    CUB_TRACK_OK = 0,        /* a player, whole in view */
    CUB_TRACK_NO_PLAYER,     /* nobody (or no usable frame) */
    CUB_TRACK_TOO_CLOSE,     /* nearer than the range the body fits in */
    CUB_TRACK_TOO_FAR,       /* beyond the range the Kinect reads well */
    CUB_TRACK_PARTLY_OUT,    /* part of the body leaves the image */
} cub_track_status;

/* One frame's player. joint_mm in camera space (kinect.h); confidence in
 * [0, 1] Q16.16 per joint: 0 = not seen (its position is a guess), above
 * 0 = found, CUB_TRACK_CONFIDENT and above = confident: the depth backs it
 * (track/trk_conf.c), what `cubtool eval-track` checks is honest
 * (docs/tracker_eval.md, "the confidence": of the confident joints, the share
 * within 10 cm). The judge reads both (cub/judge.h): a wrong pose (the
 * other arm, another move) only where confident, and a move glimpsed only
 * where not confident is unsure, never corrected; "found" still decides
 * standing still and a right verdict (README, "the judge and the
 * tracker's confidence"). */
#define CUB_TRACK_CONFIDENT (CUB_Q16_ONE / 2)
typedef struct cub_track_skeleton {
    int32_t status; /* cub_track_status */
    int32_t player_id; /* stays the same while the same person is tracked */
    cub_vec3 joint_mm[CUB_KJ_COUNT];
    cub_q16 confidence[CUB_KJ_COUNT];
} cub_track_skeleton;

/* Zero-initialised fields take defaults (the implementation documents
 * them). */
struct cub_forest;
typedef struct cub_track_desc {
    int32_t min_mm, max_mm; /* the range a player is looked for in; 0 = defaults */
    /* NULL: the heuristic tracker alone. Else an opened body-part forest
     * (cub/forest.h; it must outlive the tracker): a joint it is confident
     * of replaces the tracker's in the output (docs/forest.md, "In the
     * box"); cub_track_mem_size grows by its scratch (about 1 MB). */
    const struct cub_forest *forest;
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
/* START: the next frame chooses the player afresh, as a box that has just
 * started does (the nearest, most central person: the child who pressed
 * or clapped stands before the box), not whoever the track followed in
 * attract mode (a parent standing there, a plant). The track then follows
 * that player as before. CUB_ERR_ARG for NULL. */
cub_err cub_track_choose_afresh(cub_tracker *t);

/* Depth of a raw value in Q16.16 mm (step 1/8 mm); 0 = no usable reading
 * (2047, values above 2047, or farther than 8191 mm). */
cub_q16 cub_track_raw_to_mm(uint16_t raw);
/* The same, rounded to whole millimetres; 0 = no reading. */
uint16_t cub_track_raw_to_mm_int(uint16_t raw);

#endif

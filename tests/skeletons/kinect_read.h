/* kinect_read — real Kinect v1 skeleton sequences for the tests: UTKinect
 * (joints_sSS_eEE.txt + actionLabel.txt) and MSR Action3D
 * (aAA_sSS_eEE_skeleton3D.txt), read into the Kinect SDK's 20-joint order
 * (kinect.h's CUB_KJ_* order), Q16.16 millimetres, y up. Both files hold
 * metres in the sensor's frame: x to the sensor's left (the right of a
 * person facing it), y up, z away from the sensor.
 * Test code: allocates, reports problems as "file:line: message". */
#ifndef CUB_KINECT_READ_H
#define CUB_KINECT_READ_H

#include <stddef.h>

#include "cub/fuzzy.h"
#include "fuzzy_pose.h"

typedef struct kinect_seq {
    int count;                           /* frames */
    int *frame_no;                       /* UTKinect's frame numbers; MSR: 0.. */
    cub_vec3 (*joint)[CUB_KJ_COUNT]; /* [count] */
} kinect_seq;

/* UTKinect: one line per frame, "frame x y z ... (20 joints)". A frame
 * number repeated on the next line (the files hold near-identical re-saves)
 * keeps its first line only. 0 on success, -1 with a message in err. */
int kinect_read_utkinect(const char *path, kinect_seq *out, char *err, size_t err_size);

/* MSR Action3D: 20 lines "x y z confidence" per frame in the dataset's
 * joint numbering, mapped to the Kinect order. All-zero frames (the sensor
 * lost the person) are dropped; a file with none left fails. Which side is left is
 * decided from the geometry: the person faces the sensor, so the right
 * shoulder has the larger x (on a01 the waving arm comes out right, as the
 * dataset's protocol has it: tests/skeletons checks this). */
int kinect_read_msr(const char *path, kinect_seq *out, char *err, size_t err_size);

void kinect_free(kinect_seq *s);

/* $CUB_DATA_DIR/skeletons/<sub> into buf: 1 when that folder exists, 0
 * when it (or CUB_DATA_DIR) does not (the tests then skip). */
int kinect_data_dir(const char *sub, char *buf, size_t size);

/* One labelled interval of a UTKinect run, inclusive frame numbers. */
typedef struct utk_interval {
    char run[16];    /* "s01_e01" */
    char action[32]; /* "walk", "sitDown", ... */
    int first, last;
} utk_interval;

/* All intervals of actionLabel.txt; returns the count (<= max) or -1. An
 * action marked "NaN NaN" (the real file's way of saying a run lacks it)
 * is missing: no interval; one NaN with a number is refused. */
int kinect_read_utk_labels(const char *path, utk_interval *out, int max, char *err,
                           size_t err_size);

/* A body for a sequence: floor = the 5th percentile over frames of the
 * lower foot joint's y (robust against a stray low foot); stand_cog_mm =
 * the median CoG height above that floor over the given frames [from, to)
 * (callers pass the standing part: UTKinect's walk interval), or over all
 * frames' 90th percentile when from < 0. */
cub_fuzzy_body kinect_body_for(const kinect_seq *s, int from, int to);

#endif

/* fuzzy — the ten fuzzy pose features of seed 000 and the distance d
 * between two poses (SEEDS.md § 000, "Bridge-frame tagging", step 2 and 3).
 *
 * Input: world joint positions of one frame (Q16.16 mm, y up, floor at
 * floor_y_mm), and a cub_fuzzy_body naming which joints are the shoulders,
 * elbows, hips... of that skeleton (the bear's, a human mocap skeleton's, or
 * the Kinect's 20 joints). Output: each feature's input angle or height
 * (Q16.16 degrees / Posture units), and the degree of membership of every
 * fuzzy set in Q1.15 (0..32768 = 0..1). d is Q16.16 in [0, 1] when the
 * weights sum to 1. All integer: identical on every CPU. No allocation.
 */
#ifndef CUB_FUZZY_H
#define CUB_FUZZY_H

#include <stdint.h>

#include "cub/err.h"
#include "cub/fx.h"

/* The ten features, in the seed's order. */
typedef enum cub_fuzzy_feature {
    CUB_FUZZY_RH = 0, /* right arm raise: down, mid, up */
    CUB_FUZZY_RHE,    /* right elbow bent: false, true */
    CUB_FUZZY_LH,     /* left arm raise: down, mid, up */
    CUB_FUZZY_LHE,    /* left elbow bent: false, true */
    CUB_FUZZY_POSTURE,/* body height: lie, sit, stand, jump */
    CUB_FUZZY_TRUNK,  /* trunk bent: true, false */
    CUB_FUZZY_RF,     /* right leg out: inward, outward */
    CUB_FUZZY_RFK,    /* right knee bent: true, false */
    CUB_FUZZY_LF,     /* left leg out: inward, outward */
    CUB_FUZZY_LFK,    /* left knee bent: true, false */
    CUB_FUZZY_FEATURE_COUNT
} cub_fuzzy_feature;

#define CUB_FUZZY_MAX_SETS 4   /* Posture has four */
#define CUB_FUZZY_ONE 32768    /* membership 1.0 in Q1.15 */

/* Which joints of a skeleton the features read; -1 = absent. Index 0 of
 * each pair is the LEFT side, 1 the RIGHT. */
typedef struct cub_fuzzy_body {
    int16_t hip_centre;       /* pelvis / root */
    int16_t spine;            /* mid-trunk; may be -1 */
    int16_t shoulder_centre;  /* neck base */
    int16_t head;
    int16_t shoulder[2], elbow[2], wrist[2];
    int16_t hip[2], knee[2], ankle[2];
    cub_q16 floor_y_mm;       /* the floor's height in world y */
    cub_q16 stand_cog_mm;     /* centre-of-gravity height when standing
                                 (Posture is normalised so this reads 80) */
} cub_fuzzy_body;

/* One frame's features. */
typedef struct cub_fuzzy_frame {
    cub_q16 input[CUB_FUZZY_FEATURE_COUNT];  /* angle in degrees, or Posture x */
    uint16_t mu[CUB_FUZZY_FEATURE_COUNT][CUB_FUZZY_MAX_SETS]; /* Q1.15 */
} cub_fuzzy_frame;

/* Weights S_k of the distance and the switch threshold. Zero-initialised =
 * defaults: arms and Posture largest, Trunk between (the seed, with its
 * fix, has it equal to the arms: measured, README "Trunk's weight"), legs
 * smallest, normalised to sum 1; threshold 0.4. */
typedef struct cub_fuzzy_config {
    cub_q16 weight[CUB_FUZZY_FEATURE_COUNT]; /* all zero = defaults */
    cub_q16 threshold;                       /* 0 = default 0.4 */
} cub_fuzzy_config;

/* The config with defaults filled in, weights normalised to sum 1. */
cub_fuzzy_config cub_fuzzy_config_defaults(const cub_fuzzy_config *cfg);

/* How many fuzzy sets feature f has (2, 3 or 4) and the name of set s
 * ("down", "true", ...); the feature's short name ("RH", "Posture"). */
int cub_fuzzy_set_count(cub_fuzzy_feature f);
const char *cub_fuzzy_set_name(cub_fuzzy_feature f, int s);
const char *cub_fuzzy_feature_name(cub_fuzzy_feature f);

/* Membership of input x (Q16.16 degrees, or Posture units) in each set of
 * feature f, exactly as SEEDS.md gives them. */
void cub_fuzzy_membership(cub_fuzzy_feature f, cub_q16 x, uint16_t mu[CUB_FUZZY_MAX_SETS]);

/* All ten features of one frame. CUB_ERR_ARG if the body lacks a joint a
 * feature needs or an index is out of [0, joint_count). */
cub_err cub_fuzzy_features(const cub_fuzzy_body *body, const cub_vec3 *world_mm,
                           int joint_count, cub_fuzzy_frame *out);

/* The centre-of-gravity height above the floor that Posture reads (mm);
 * run it on a skeleton's standing rest pose to get stand_cog_mm. 0 if the
 * body lacks a joint or an index is out of range (stand_cog_mm is not
 * needed here). */
cub_q16 cub_fuzzy_cog_height_mm(const cub_fuzzy_body *body, const cub_vec3 *world_mm,
                                int joint_count);

/* d = sqrt( sum_k S_k * sum_sets (mu1 - mu2)^2 / 2 ), Q16.16; symmetric,
 * d(a, a) = 0, within [0, 1]. The /2: a feature's sum of squares is at
 * most 2 (e.g. down vs up), so each feature contributes at most S_k. cfg's
 * weights are normalised to sum 1 here (cfg NULL or all zero = defaults).
 * NULL a or b gives 1. */
cub_q16 cub_fuzzy_distance(const cub_fuzzy_frame *a, const cub_fuzzy_frame *b,
                           const cub_fuzzy_config *cfg);

/* The crisp pose class of a frame: for each feature the set with the
 * highest membership (ties to the lower index), packed 2 bits per feature.
 * Frames of one class are "the same pose" when counting how often a pose
 * occurs (tagging step 1). */
uint32_t cub_fuzzy_crisp_class(const cub_fuzzy_frame *f);

#endif

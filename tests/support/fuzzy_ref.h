/* fuzzy_ref — a double-precision reference of firmware/fuzzy: the same ten
 * features, membership functions and distance d (SEEDS.md § 000), written
 * straight from the seed's formulas with libm, to check the fixed-point
 * module against. Self-contained (no cub headers): feature k and set s
 * mean the same as in cub/fuzzy.h (RH, RHE, LH, LHE, Posture, Trunk, RF,
 * RFK, LF, LFK). Test code only. */
#ifndef CUB_FUZZY_REF_H
#define CUB_FUZZY_REF_H

#define CUB_FUZZY_REF_FEATURES 10
#define CUB_FUZZY_REF_MAX_SETS 4

/* Joint indices as in cub_fuzzy_body (index 0 of a pair = left); -1 absent
 * (allowed for spine and head only). */
typedef struct cub_fuzzy_ref_body {
    int hip_centre, spine, shoulder_centre, head;
    int shoulder[2], elbow[2], wrist[2], hip[2], knee[2], ankle[2];
    double floor_y_mm, stand_cog_mm;
} cub_fuzzy_ref_body;

typedef struct cub_fuzzy_ref_frame {
    double input[CUB_FUZZY_REF_FEATURES];                      /* degrees, or Posture x */
    double mu[CUB_FUZZY_REF_FEATURES][CUB_FUZZY_REF_MAX_SETS]; /* 0..1 */
} cub_fuzzy_ref_frame;

/* Membership of x in every set of feature k (unused sets 0). */
void cub_fuzzy_ref_membership(int k, double x, double mu[CUB_FUZZY_REF_MAX_SETS]);
/* CoG height above the floor, mm; xyz_mm holds 3 doubles per joint. */
double cub_fuzzy_ref_cog_height_mm(const cub_fuzzy_ref_body *b, const double *xyz_mm);
/* All ten features; 0 on success, -1 on a missing / out-of-range joint or a
 * non-positive stand_cog_mm. */
int cub_fuzzy_ref_features(const cub_fuzzy_ref_body *b, const double *xyz_mm, int joint_count,
                           cub_fuzzy_ref_frame *out);
/* d = sqrt(sum_k S_k * sum_sets (mu1-mu2)^2 / 2) with S normalised to sum 1;
 * weight NULL (or all <= 0) = the defaults 3,3,3,3, 3, 2, 1,1,1,1. */
double cub_fuzzy_ref_distance(const cub_fuzzy_ref_frame *a, const cub_fuzzy_ref_frame *b,
                              const double *weight);
/* Argmax per feature (ties to the lower set), 2 bits per feature. */
unsigned cub_fuzzy_ref_crisp_class(const cub_fuzzy_ref_frame *f);

#endif

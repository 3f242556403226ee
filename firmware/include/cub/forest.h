/* forest — a randomized decision forest that names the body part under a
 * depth pixel (Shotton et al., CVPR 2011: the Kinect's own method), in
 * integers. docs/forest.md: the training (cubtool train-forest), the
 * figures, what is next.
 *
 * A split node compares two probes around pixel p = (x, y) of depth d(p)
 * in mm: f = d(p + u / d(p)) - d(p + v / d(p)). The offsets u, v are in
 * pixel·mm, so they shrink with distance and touch the same spot of a body
 * whether it stands near or far; u / d(p) divides each coordinate in C's
 * integer division (truncating towards zero). A probe off the image or on
 * no reading (0) reads CUB_FOREST_FAR_MM (p on no reading: f = 0). f < threshold
 * (mm) goes to the left child. A leaf holds the probability of every
 * class, Q0.16 (65535 ~ 1); a pixel's score per class is the sum over the
 * trees, its class the highest score (the lowest class on a tie).
 *
 * The asset (little-endian; docs/forest.md shows it):
 *   header, 24 bytes: "CUBFRST1", u16 version (1), u16 classes (1..64),
 *     u16 trees (1..64), u16 reserved (0), u32 nodes, u32 leaves
 *   u32 root[trees]      a child reference each
 *   node[nodes], 28 bytes each: i32 ux uy vx vy (pixel·mm, |.| <= 2^24),
 *     i32 threshold (mm), u32 left, right (child references)
 *   u16 leaf[leaves][classes]
 *   and nothing after.
 * A child reference below 2^31 is a node index, one with bit 31 set a leaf
 * index (the low bits). A node's children come after it (left, right >
 * its own index), so every path ends at a leaf: no cycle, depth <= nodes.
 *
 * The forest is a view of the caller's bytes: no copy, no heap; the bytes
 * must outlive it. Integer only: bit-identical on every CPU.
 */
#ifndef CUB_FOREST_H
#define CUB_FOREST_H

#include <stddef.h>
#include <stdint.h>

#include "cub/err.h"
#include "cub/fx.h"
#include "cub/kinect.h"

/* The body parts, the forest's classes (docs/forest.md); the renders of
 * app/synth paint them per pixel. By the body's own side (the player's
 * left arm is ARM_L whichever way the player faces; a mirrored segment
 * swaps them, as it swaps the joints). 0: not a body (room, floor). */
typedef enum cub_synth_part {
    CUB_PART_NONE = 0,
    CUB_PART_HEAD,
    CUB_PART_TORSO_UPPER, /* chest, the shoulder bar and the neck (the head and
                           * chest hide it: alone it is almost never seen) */
    CUB_PART_TORSO_LOWER, /* belly, the hip bar, a skirt hem */
    CUB_PART_UPPER_ARM_L,
    CUB_PART_FOREARM_L,
    CUB_PART_HAND_L,
    CUB_PART_UPPER_ARM_R,
    CUB_PART_FOREARM_R,
    CUB_PART_HAND_R,
    CUB_PART_THIGH_L,
    CUB_PART_SHIN_L,
    CUB_PART_FOOT_L,
    CUB_PART_THIGH_R,
    CUB_PART_SHIN_R,
    CUB_PART_FOOT_R,
    CUB_PART_COUNT
} cub_synth_part;

#define CUB_FOREST_VERSION 1
#define CUB_FOREST_MAX_CLASSES 64
#define CUB_FOREST_MAX_TREES 64
#define CUB_FOREST_MAX_OFFSET (1 << 24)       /* |u|, |v| in pixel·mm */
#define CUB_FOREST_FAR_MM 10000               /* what a probe off the body reads */
#define CUB_FOREST_LEAF_BIT 0x80000000u
#define CUB_FOREST_HEADER_BYTES 24
#define CUB_FOREST_NODE_BYTES 28

typedef struct cub_forest {
    const uint8_t *roots, *nodes, *leaves;
    int classes, trees;
    uint32_t node_count, leaf_count;
} cub_forest;

/* One split node, decoded. */
typedef struct cub_forest_node {
    int32_t u[2], v[2]; /* probe offsets (x right, y down), pixel·mm */
    int32_t threshold_mm;
    uint32_t left, right; /* child references */
} cub_forest_node;

/* Why an asset was refused: what, and the byte offset where. */
typedef struct cub_forest_problem {
    const char *what;
    size_t offset;
} cub_forest_problem;

/* A depth image in mm (0 = no reading), row-major, w x h. */
typedef struct cub_forest_image {
    const uint16_t *mm;
    int w, h;
} cub_forest_image;

/* Check the whole asset and make f a view of it. CUB_ERR_FORMAT with why
 * filled when the bytes are not a forest; CUB_ERR_ARG on NULL. */
cub_err cub_forest_open(const void *data, size_t len, cub_forest *f, cub_forest_problem *why);
/* Node i (< node_count) of an opened forest. */
cub_forest_node cub_forest_node_at(const cub_forest *f, uint32_t i);

/* The depth a probe at p + off / d(p) reads (CUB_FOREST_FAR_MM off the
 * image or on no reading); d_mm is d(p), > 0. */
int32_t cub_forest_probe(const cub_forest_image *im, int x, int y, int32_t d_mm,
                         const int32_t off[2]);
/* The split feature f of a node at p (p on no reading: both probes read far). */
int32_t cub_forest_feature(const cub_forest_image *im, int x, int y, const cub_forest_node *n);
/* The leaf reference tree t reaches from p. */
uint32_t cub_forest_descend(const cub_forest *f, int t, const cub_forest_image *im, int x, int y);
/* Scores of every class at p (score[classes]: sums of Q0.16 leaf
 * probabilities over the trees); returns the class with the highest. */
int cub_forest_classify(const cub_forest *f, const cub_forest_image *im, int x, int y,
                        uint32_t *score);

/* ---- part proposals (Shotton et al. 2011, section 4: joint proposals) ----
 *
 * The classified pixels become 3D points in camera space (cub/kinect.h:
 * x = (u - CX) z / F, y = (CY - v) z / F, C's integer division), each with
 * every class's probability (the trees' mean, Q0.16). A part's proposal is
 * the strongest mode of a weighted mean shift over the points: a point
 * weighs its probability times z^2 (the surface a pixel covers grows with
 * the square of its depth, so a near hand does not outvote a far one by
 * its pixel count), the kernel is (1 - d^2/r^2) within radius r. Starts:
 * the heaviest point, then the heaviest point farther than r from every
 * mode found so far, up to CUB_FOREST_STARTS. The mode found is on the
 * body's surface; the proposal is pushed back along z by the part's push
 * (the joint lies inside the body). Integers only: bit-identical on every
 * CPU. */
#define CUB_FOREST_STARTS 4
#define CUB_FOREST_SHIFT_STEPS 12

/* Caller-owned scratch: up to capacity points, prob[capacity * classes]. */
typedef struct cub_forest_points {
    int32_t (*mm)[3];
    uint16_t *prob; /* Q0.16, point i's class c at [i * classes + c] */
    int n, capacity, classes;
    int stride; /* the pixel step the points were sampled at (for areas) */
    int32_t *part_pts; /* capacity entries, or NULL: a part's points listed once, so the
                        * mean shift visits only them (the same result, faster) */
} cub_forest_points;

/* How one part is proposed. */
typedef struct cub_forest_shift {
    int32_t radius_mm; /* the kernel's radius, > 0 */
    uint16_t min_prob; /* points below this probability (Q0.16) are left out */
    int32_t push_mm;   /* the joint's depth behind the mode */
} cub_forest_shift;

typedef struct cub_forest_proposal {
    int32_t found;     /* 0: no point of the part */
    int32_t mm[3];     /* camera space, pushed back */
    int32_t area_mm2;  /* the surface voting within r of the mode: sum of prob x pixel area */
    cub_q16 share;     /* the part's weight within r of the mode over its whole weight, Q16.16 */
} cub_forest_proposal;

/* Pixel (u, v) at z mm (> 0) in camera space, mm. */
void cub_forest_point_at(int u, int v, int32_t z_mm, int32_t out[3]);
/* Classify every stride-th pixel (in x and y) with a reading and keep it in
 * pts (up to its capacity; pts->classes must equal f's). Returns pts->n. */
int cub_forest_gather(const cub_forest *f, const cub_forest_image *im, int stride,
                      cub_forest_points *pts);
/* The proposal of class `part` from the points. */
void cub_forest_propose(const cub_forest_points *pts, int part, const cub_forest_shift *sh,
                        cub_forest_proposal *out);

/* ---- joints from the proposals (docs/forest.md, step 2) ---- */

/* Every part's proposal, with the per-part radius, push and probability
 * floor of forest/joints.c. */
void cub_forest_propose_all(const cub_forest_points *pts, cub_forest_proposal prop[CUB_PART_COUNT]);

/* The joints the proposals give: head, hands and feet are their parts'
 * centres; elbows and knees the midpoint of the two segments' centres.
 * confident: share >= 1/2 and enough surface (both segments for a joint
 * between two). */
typedef struct cub_forest_joints {
    int32_t mm[CUB_KJ_COUNT][3];
    uint8_t have[CUB_KJ_COUNT], confident[CUB_KJ_COUNT];
} cub_forest_joints;
void cub_forest_joints_of(const cub_forest_proposal prop[CUB_PART_COUNT], cub_forest_joints *out);

#endif

/* motion — skeletons, poses, clips, forward kinematics and sampling.
 *
 * A skeleton is a tree of named joints; each joint has a parent (-1 for the
 * root, and parents always come before their children) and a rest offset
 * from its parent in millimetres. A pose is the root's translation plus one
 * local rotation per joint (and, for skeletons whose files animate joint
 * translations too, one local translation per joint). A clip is a run of
 * poses at a fixed frame period.
 *
 * Units: positions Q16.16 millimetres (`cub_vec3`), rotations Q2.30 unit
 * quaternions (`cub_quat`), time in microseconds. All integer: the same clip
 * gives bit-identical world positions on x86-64 and aarch64. Float views
 * (`cub_motion_world_to_float`) are for the renderer only.
 *
 * Memory: skeletons and poses are fixed-size structs; a clip's frame data
 * lives in a buffer the caller provides (`cub_motion_clip_mem_size`).
 */
#ifndef CUB_MOTION_H
#define CUB_MOTION_H

#include <stddef.h>
#include <stdint.h>

#include "cub/err.h"
#include "cub/fx.h"

#define CUB_MOTION_MAX_JOINTS 128
#define CUB_MOTION_NAME_LEN 32 /* including the terminating NUL */

/* ---- skeleton ---------------------------------------------------------- */

typedef struct cub_joint {
    char name[CUB_MOTION_NAME_LEN];
    int16_t parent;      /* index of the parent joint, -1 for the root */
    uint8_t is_end_site; /* 1 for a BVH "End Site": a leaf with no channels */
    uint8_t reserved_;
    cub_vec3 offset_mm; /* rest offset from the parent */
} cub_joint;

typedef struct cub_skeleton {
    int joint_count;
    cub_joint joints[CUB_MOTION_MAX_JOINTS];
} cub_skeleton;

/* Empty the skeleton. */
void cub_motion_skeleton_reset(cub_skeleton *skel);
/* Append a joint; parent must be an existing index or -1 (only for the
 * first joint). Returns its index in *out_index. Fails with CUB_ERR_FULL,
 * CUB_ERR_ARG (bad parent, empty, too long or already used name). */
cub_err cub_motion_skeleton_add(cub_skeleton *skel, const char *name, int parent,
                                cub_vec3 offset_mm, int *out_index);
/* Index of the joint with this exact name, or -1. */
int cub_motion_skeleton_find(const cub_skeleton *skel, const char *name);
/* Check the invariants above (parents before children, one root, names
 * non-empty). CUB_OK or CUB_ERR_FORMAT. */
cub_err cub_motion_skeleton_validate(const cub_skeleton *skel);

/* ---- pose -------------------------------------------------------------- */

typedef struct cub_pose {
    int joint_count;
    cub_vec3 root_mm;                          /* root translation */
    cub_quat rot[CUB_MOTION_MAX_JOINTS];       /* local rotation of each joint */
    cub_vec3 trans_mm[CUB_MOTION_MAX_JOINTS];  /* local translations, if has_trans */
    int has_trans; /* 0: joints sit at their skeleton rest offsets */
} cub_pose;

/* The rest pose: identity rotations, root at the origin, no translations. */
void cub_motion_pose_rest(const cub_skeleton *skel, cub_pose *out);

/* Forward kinematics: world position of every joint (Q16.16 mm) and,
 * optionally, its world rotation (world_rot may be NULL). The root is placed
 * at root_mm and its own offset (and trans_mm[0]) is ignored: as in common
 * BVH practice, the root's position channels replace its OFFSET. Every
 * other joint sits at its parent + parent's world rotation applied to its
 * offset (or trans_mm when has_trans). */
cub_err cub_motion_forward(const cub_skeleton *skel, const cub_pose *pose,
                           cub_vec3 *world_mm, cub_quat *world_rot);

/* One joint's world position and rotation: what cub_motion_forward gives
 * for it, bit for bit, walking only its ancestors. */
cub_err cub_motion_joint_world(const cub_skeleton *skel, const cub_pose *pose, int joint,
                               cub_vec3 *world_mm, cub_quat *world_rot);

/* Blend two poses of the same skeleton: t = 0 gives a, 1 gives b. */
cub_err cub_motion_pose_blend(const cub_pose *a, const cub_pose *b, cub_q16 t,
                              cub_pose *out);

/* ---- clip -------------------------------------------------------------- */

typedef struct cub_clip {
    const cub_skeleton *skel;
    int frame_count;
    uint32_t frame_ns;   /* frame period in nanoseconds (8333333 at 120 fps) */
    cub_vec3 *root_mm;   /* [frame_count] root translation per frame */
    cub_quat *rot;       /* [frame_count * joint_count] local rotations */
    cub_vec3 *trans_mm;  /* [frame_count * joint_count] or NULL */
} cub_clip;

/* Bytes of frame data a clip of this shape needs. */
size_t cub_motion_clip_mem_size(int joint_count, int frame_count, int with_trans);
/* Lay a clip out in mem (aligned to 8). Frames start as the rest pose. */
cub_err cub_motion_clip_init(cub_clip *clip, const cub_skeleton *skel, int frame_count,
                             uint32_t frame_ns, int with_trans, void *mem, size_t mem_size);
/* Copy one frame into a pose / a pose into one frame. */
cub_err cub_motion_clip_get_frame(const cub_clip *clip, int frame, cub_pose *out);
cub_err cub_motion_clip_set_frame(cub_clip *clip, int frame, const cub_pose *pose);
/* Length from the first to the last frame, in microseconds, rounded up (so
 * sampling at it with CLAMP gives the last frame exactly). */
int64_t cub_motion_clip_duration_us(const cub_clip *clip);

typedef enum cub_motion_wrap {
    CUB_MOTION_CLAMP = 0, /* hold the first/last frame outside the clip */
    CUB_MOTION_LOOP,      /* wrap around (the last frame joins the first: a loop
                             of n frames lasts n frame periods) */
} cub_motion_wrap;

/* The pose at time t_us, interpolated between the two nearest frames
 * (nlerp for rotations, lerp for translations). */
cub_err cub_motion_sample(const cub_clip *clip, int64_t t_us, cub_motion_wrap wrap,
                          cub_pose *out);

/* ---- two-bone analytic IK (arms, legs) ----------------------------------- */

/* How far a two-bone chain may fold and open: the inner angle at the
 * middle joint (pi: straight) stays in [min_rad, max_rad]. Both 0: the
 * defaults, 20 and 175 degrees (a straight elbow flips its bend). */
typedef struct cub_ik_limits {
    cub_q16 min_rad, max_rad;
} cub_ik_limits;

/* The solved chain, world positions (Q16.16 mm). */
typedef struct cub_ik_solution {
    cub_vec3 mid_mm, end_mm;
    int clamped; /* 1: the target was out of reach (or too near): end_mm is
                    the nearest point the limits allow, on the target's ray */
} cub_ik_solution;

/* Geometry only: a chain rooted at root_mm with bones upper_mm and
 * lower_mm reaching for target_mm, the middle joint bent toward pole_mm
 * (a point: the middle joint lies in the plane of root, target and pole,
 * on the pole's side). limits may be NULL. CUB_ERR_ARG for a bone <= 0. */
cub_err cub_motion_ik_solve(cub_vec3 root_mm, cub_q16 upper_mm, cub_q16 lower_mm,
                            cub_vec3 target_mm, cub_vec3 pole_mm, const cub_ik_limits *limits,
                            cub_ik_solution *out);

/* The same on a skeleton: upper is the chain's first joint (a shoulder),
 * its first child the middle (elbow), the middle's first child the end
 * (wrist). Rewrites pose->rot of upper and middle with the smallest turn
 * from their current rotations that puts the middle and end joints where
 * the solution says (the end joint's own rotation is kept). out may be
 * NULL. CUB_ERR_ARG / CUB_ERR_RANGE for a bad chain. */
cub_err cub_motion_ik_apply(const cub_skeleton *skel, cub_pose *pose, int upper,
                            cub_vec3 target_mm, cub_vec3 pole_mm, const cub_ik_limits *limits,
                            cub_ik_solution *out);

/* The smallest rotation taking direction from to direction to (any
 * lengths; a zero vector gives identity; opposite directions turn pi
 * about an axis perpendicular to from). */
cub_quat cub_motion_quat_between(cub_vec3 from, cub_vec3 to);

/* ---- float views, for rendering only ----------------------------------- */

/* World positions to floats (millimetres), 3 floats per joint. */
void cub_motion_world_to_float(const cub_vec3 *world_mm, int joint_count, float *out_xyz);

#endif

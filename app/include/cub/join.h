/* join — joining two clips without sliding feet (seed 002, § 5; SEEDS.md
 * § 002): support points, the point-cloud distance of Kovar et al. 2002,
 * the search for a transition clip C, the one-foot-at-a-time blend, and
 * the figures that say how a join looks (docs/join.md).
 *
 * Host code, doubles, millimetres, frames of the clips' own period; the
 * heap is the caller's through cub_join_db and cub_join_result. Y is up,
 * the floor is the plane y = floor_mm of each clip (its lowest foot point).
 *
 * The pieces, each usable alone:
 *   contacts     a point touches the floor when it is low and slow, in runs
 *                of a few frames (retargeting pins feet with it too);
 *   support      which body parts touch the floor per frame (a bit mask):
 *                the pose classes of the dance's motion graph;
 *   leg IK       analytic two-bone IK putting an ankle on a target;
 *   kovar        min over θ, x0, z0 of Σ w_i ‖p_i − T p'_i‖², closed form;
 *   search       C whose start matches A's end and whose end B's start;
 *   build        A|C|B (or A|B) with blends whose length the distance sets,
 *                the legs moved one at a time while the other stays put;
 *   measure      stance-foot slide and joint-speed jump across the joins. */
#ifndef CUB_JOIN_H
#define CUB_JOIN_H

#include <stddef.h>

#include "cub/err.h"
#include "cub/motion.h"
#include "cub/text.h" /* cub_diag */
#include "cub/vec.h"

/* ---- contacts ------------------------------------------------------------- */

/* A point's track: pos[f * stride] for f < frames, times scale (0 = 1). */
typedef struct cub_join_track {
    const cub_dv3 *pos;
    size_t stride;
    double scale;
    int frames;
    double dt_s;
} cub_join_track;

/* Zero-initialised = the defaults in brackets. */
typedef struct cub_join_contact_cfg {
    double height_mm;  /* above the floor [30] */
    double speed_mm_s; /* [180] */
    int min_frames;    /* shorter runs are a point passing low [3] */
} cub_join_contact_cfg;

/* out[f] = 1 where the point is within height_mm of floor_mm and slower
 * than speed_mm_s (central difference), in runs of at least min_frames. */
void cub_join_contacts(const cub_join_track *t, const cub_join_contact_cfg *cfg, double floor_mm,
                       unsigned char *out);
/* The lowest (scaled) height of the track. */
double cub_join_track_lowest(const cub_join_track *t);

/* ---- the body: legs and support parts --------------------------------------- */

typedef enum cub_join_part {
    CUB_JOIN_LFOOT = 0,
    CUB_JOIN_RFOOT,
    CUB_JOIN_LHAND,
    CUB_JOIN_RHAND,
    CUB_JOIN_LKNEE,
    CUB_JOIN_RKNEE,
    CUB_JOIN_HIP,
    CUB_JOIN_PARTS
} cub_join_part;

typedef struct cub_join_leg {
    int hip, knee, ankle; /* joint indices: thigh root, knee, ankle */
} cub_join_leg;

#define CUB_JOIN_PART_JOINTS 4
typedef struct cub_join_body {
    int hips;                                       /* the pelvis ("Hips", else the root) */
    cub_join_leg leg[2];                            /* left, right */
    int part[CUB_JOIN_PARTS][CUB_JOIN_PART_JOINTS]; /* joints of a part, -1 ends */
    double pad_mm[CUB_JOIN_PARTS];                  /* the part's surface below its lowest joint */
} cub_join_body;

/* Find the parts by joint names (Hips; Left/Right UpLeg, Leg, Foot, Hand and
 * what hangs below a foot or hand). CUB_ERR_FORMAT when the legs or the
 * hands are missing, with the missing joint's name in diag. */
cub_err cub_join_body_find(const cub_skeleton *skel, cub_join_body *out, cub_diag *diag);

/* A support mask's name: "LF+RF", "LH+LF", "HIP+LF+RF", "air" (no support).
 * Parts: LF RF (feet) LH RH (hands) LK RK (knees) HIP. */
const char *cub_join_support_name(unsigned mask, char *buf, size_t size);

/* ---- leg IK ------------------------------------------------------------------ */

typedef struct cub_join_goal {
    cub_dv3 ankle;   /* where the ankle goes (world) */
    cub_dq foot;     /* the foot's world rotation there */
    cub_dv3 forward; /* the body's forward: the knee bends toward it when straight */
} cub_join_goal;

/* Two-bone IK: new local rotations for the leg's hip, knee and ankle in
 * local[] so the ankle reaches goal->ankle (or as near as the leg's length
 * allows) with the foot at goal->foot, the knee in its current bend plane.
 * pos/rot: the frame's world joint positions and rotations now. */
void cub_join_leg_ik(const cub_skeleton *skel, const cub_join_leg *leg, const cub_dv3 *pos,
                     const cub_dq *rot, const cub_join_goal *goal, cub_dq *local);

/* ---- Kovar's point-cloud distance -------------------------------------------- */

/* T_{θ,x0,z0} q = R_y(θ) q + (x0, 0, z0), R_y(θ) taking +z toward +x. */
typedef struct cub_join_align {
    double theta_rad, x0_mm, z0_mm;
    double d_mm2; /* Σ w_i ‖p_i − T q_i‖² / Σ w_i at the optimum */
} cub_join_align;

/* The rotation about the vertical and floor translation taking the cloud q
 * closest to p (n points, weights w or NULL for equal ones). */
cub_join_align cub_join_kovar(const cub_dv3 *p, const cub_dv3 *q, const double *w, int n);
/* The weighted mean squared distance after a given T (for checks). */
double cub_join_kovar_cost(const cub_dv3 *p, const cub_dv3 *q, const double *w, int n,
                           const cub_join_align *t);
cub_dv3 cub_join_apply(const cub_join_align *t, cub_dv3 q);
/* The rotation of T as a quaternion about +y. */
cub_dq cub_join_align_rot(const cub_join_align *t);

/* ---- the motion database ------------------------------------------------------ */

/* Zero-initialised = the defaults in brackets. */
typedef struct cub_join_cfg {
    cub_join_contact_cfg contact;
    int window_frames;         /* frames in a compared point cloud [5] */
    int min_frames;            /* shortest C [3 windows] */
    int max_frames;            /* longest C [90] */
    double blend_mm_per_frame; /* a blend spreads the residual at this [10] */
    int min_blend, max_blend;  /* blend frames [3, 20] */
} cub_join_cfg;

typedef struct cub_join_clip {
    char name[CUB_MOTION_NAME_LEN];
    const cub_clip *clip;   /* the caller's; must outlive the db */
    cub_dv3 *pos;           /* [frames * joints] world positions */
    unsigned char *support; /* [frames] masks of cub_join_part bits */
    unsigned char *foot[2]; /* [frames] contacts of each foot */
    double floor_mm;
} cub_join_clip;

typedef struct cub_join_db {
    const cub_skeleton *skel;
    cub_join_body body;
    cub_join_cfg cfg; /* with the defaults filled in */
    int count, cap;
    cub_join_clip *clips;
} cub_join_db;

/* An empty database of clips on skel. Fails (CUB_ERR_FORMAT, diag) when
 * cub_join_body_find does. */
cub_err cub_join_db_init(cub_join_db *db, const cub_skeleton *skel, const cub_join_cfg *cfg,
                         cub_diag *diag);
/* Add a clip on the db's skeleton (its index in *index, may be NULL):
 * world positions, contacts, supports. CUB_ERR_ARG: another skeleton or
 * fewer than 2 windows of frames; CUB_ERR_NOMEM. */
cub_err cub_join_db_add(cub_join_db *db, const char *name, const cub_clip *clip, int *index);
void cub_join_db_free(cub_join_db *db);

/* ---- search ---------------------------------------------------------------- */

typedef struct cub_join_pick {
    int clip, first, last; /* C = clip's frames first..last */
    cub_join_align in;     /* C onto A's end (d: D at A|C) */
    cub_join_align out;    /* B onto C's end, C already moved (d: D at C|B) */
    cub_join_align direct; /* B onto A's end (d: D of the direct join) */
} cub_join_pick;

/* The C minimising D(A's end, C's start) + D(C's end, B's start) over every
 * clip and window of the db. CUB_ERR_EMPTY when no clip is long enough. */
cub_err cub_join_search(const cub_join_db *db, int a, int b, cub_join_pick *out);
/* Only the direct alignment of B onto A's end (out->clip = -1). */
void cub_join_direct(const cub_join_db *db, int a, int b, cub_join_pick *out);

/* ---- build and measure ----------------------------------------------------------- */

typedef struct cub_join_result {
    cub_clip clip; /* A, [C,] B joined; frames owned (mem) */
    void *mem;
    int windows;                     /* blend windows: 1 (direct) or 2 */
    int win_first[2], win_frames[2]; /* each window's first output frame, length */
    double floor_mm;                 /* A's floor */
    unsigned char *stance;           /* [frames] bit s: foot s stands in the clip(s) a frame comes
                                        from (in a blend: in both); owned */
} cub_join_result;

/* Join A to B: through the pick's C when pick->clip >= 0, directly
 * otherwise. feet = 1 moves the legs one at a time, the other planted
 * (leg IK); feet = 0 blends every joint at once. With CUB_JOIN_CUT or'ed
 * in, the same frames and windows without the blend: each seam shows the
 * outgoing clip to its middle, then the incoming one (each moved as in the
 * join), no foot standing across that cut - the clips' own motion there,
 * which the measure of the join collects too. */
#define CUB_JOIN_CUT 2
cub_err cub_join_build(const cub_join_db *db, int a, int b, const cub_join_pick *pick, int feet,
                       cub_join_result *out);
void cub_join_result_free(cub_join_result *r);

typedef struct cub_join_figures {
    double slide_cm; /* the most a stance foot moves on the floor across the windows */
    double jump_cm;  /* peak change of a joint's velocity there, cm/frame per frame */
} cub_join_figures;

/* The figures of a built join (positions by forward kinematics). */
cub_join_figures cub_join_measure(const cub_join_db *db, const cub_join_result *r);
/* The same measure of the velocity change, per frame over a whole clip of
 * the db (its own motion), into out[frames] (out[0] = out[1] = 0). */
void cub_join_clip_jumps(const cub_join_db *db, int c, double *out);

/* ---- the motion graph by support points -------------------------------------- */

/* A run of frames of one clip with one support mask. */
typedef struct cub_join_segment {
    int first, last;
    unsigned mask;
} cub_join_segment;

#define CUB_JOIN_CLASSES (1 << CUB_JOIN_PARTS)

/* Up to max segments of clip c (runs shorter than min_frames are taken
 * into the run before them: a foot landing a frame after the other is one
 * change, not two). Returns how many there are (may exceed max). */
int cub_join_segments(const cub_join_db *db, int c, int min_frames, cub_join_segment *out, int max);

/* The graph: per class (a support mask) its frames and segments, and per
 * ordered pair of classes how often a clip goes from one to the other. */
typedef struct cub_join_graph {
    int frames[CUB_JOIN_CLASSES];
    int segments[CUB_JOIN_CLASSES];
    int edges[CUB_JOIN_CLASSES][CUB_JOIN_CLASSES];
} cub_join_graph;

/* Build it over every clip of db. CUB_ERR_NOMEM. */
cub_err cub_join_graph_build(const cub_join_db *db, int min_frames, cub_join_graph *g);
/* Draw it: classes on a circle (area by frames), edges as arrows (width
 * by count, the count beside). CUB_ERR_IO / CUB_ERR_NOMEM. */
cub_err cub_join_graph_png(const cub_join_graph *g, const char *path);

#endif

/* evolve — skeletons crossed by hierarchical evolution (SEEDS.md § 004):
 * motion moved between *different* skeletons (a human and a dog, a bear
 * and a bird) by crossing them. Offline, in doubles; used by `cubtool
 * evolve` and the tests, never by the box.
 *
 * A skeleton C_s is a cub_skeleton: joint 0 the root R (6 DOF: position
 * and rotation), every other joint 3 DOF (a local rotation); BVH End Sites
 * are leaves with no DOF. A motion C_m(t), t = 0..k, is a cub_evolve_motion:
 * the root's position (mm) and every joint's local rotation per frame.
 * The pipeline, each step its own function:
 *   correspond  which joints of parent 1 and parent 2 are the same joint:
 *               one-to-one, many-to-one (two legs -> one tail), none;
 *               from names and structure, overridden by a map file;
 *   crossover   the meta skeleton M_s = C_s1 ∪ C_s2: parent 1's joints,
 *               then parent 2's joints that have no partner, appended;
 *   mutate      the least active joints of M_s removed (activity: the
 *               standard deviation of a joint's per-frame rotation angle,
 *               made comparable across the parents by PCA) -> the
 *               population skeleton C_p, re-linked to kept ancestors;
 *   survivor    the child's motion C_mp(t) = C_m1(t) + x·d(t), d the
 *               difference to parent 2 over its best-matching window;
 *   floor       no joint below y = 0, fixed by a Jacobian IK step.
 * Where the seed's pages are lost (the PCA step, d(t), how weights and
 * re-linking work) the choices are ours and said so below.
 */
#ifndef CUB_EVOLVE_H
#define CUB_EVOLVE_H

#include <stddef.h>

#include "cub/err.h"
#include "cub/io.h"
#include "cub/motion.h"
#include "cub/vec.h"

#define CUB_EVOLVE_MAX_JOINTS CUB_MOTION_MAX_JOINTS
#define CUB_EVOLVE_MAP_SIDE 4          /* joints on one side of a map row */
#define CUB_EVOLVE_MUTATIONS_DEFAULT 5 /* the seed's default mutation count */
#define CUB_EVOLVE_SAMPLE_STEP 5       /* the survivor samples parent 1 every 5 frames */

/* ---- motion --------------------------------------------------------------- */

typedef struct cub_evolve_motion {
    cub_skeleton skel; /* C_s */
    int frames;        /* k + 1 */
    double fps;
    cub_dv3 *root_mm; /* [frames] the root's position */
    cub_dq *rot;      /* [frames * skel.joint_count] local rotations */
} cub_evolve_motion;

/* A clip resampled at fps (0: its own rate) into doubles; joint
 * translations, if the clip has any, are dropped. Heap: free with
 * cub_evolve_motion_free. CUB_ERR_ARG on an empty clip, CUB_ERR_NOMEM. */
cub_err cub_evolve_from_clip(const cub_clip *clip, double fps, cub_evolve_motion *out);
/* An empty motion of skel, frames long, every frame the rest pose. */
cub_err cub_evolve_motion_alloc(const cub_skeleton *skel, int frames, double fps,
                                cub_evolve_motion *out);
void cub_evolve_motion_free(cub_evolve_motion *m);
/* Local rotation of joint j at frame f. */
static inline cub_dq *cub_evolve_rot(const cub_evolve_motion *m, int f, int j)
{
    return &m->rot[(size_t)f * (size_t)m->skel.joint_count + (size_t)j];
}
/* World positions (mm) of every joint at frame f (world: joint_count). */
void cub_evolve_forward(const cub_evolve_motion *m, int f, cub_dv3 *world);
/* m as a BVH-ready cub_io_motion (root XYZ + ZXY, joints ZXY, unit_mm per
 * file unit); free with cub_io_motion_free. */
cub_err cub_evolve_to_io(const cub_evolve_motion *m, double unit_mm, cub_io_motion *out);

/* ---- correspondence -------------------------------------------------------- */

/* A map file overrides the automatic matching, one row a line:
 *     # parent-1 joint(s) = parent-2 joint(s)
 *     Head = Head                      one-to-one
 *     LeftUpLeg RightUpLeg = Tail      many-to-one (one side has one joint)
 *     Horn = -                         none: Horn has no partner
 * Up to CUB_EVOLVE_MAP_SIDE names a side; a joint appears in one row. */
typedef struct cub_evolve_map_row {
    char a[CUB_EVOLVE_MAP_SIDE][CUB_MOTION_NAME_LEN]; /* parent 1's side */
    char b[CUB_EVOLVE_MAP_SIDE][CUB_MOTION_NAME_LEN]; /* parent 2's side */
    int a_count, b_count;                             /* 0 on a side written "-" */
    int line;
} cub_evolve_map_row;

typedef struct cub_evolve_map {
    char file[256];
    int row_count;
    cub_evolve_map_row row[CUB_EVOLVE_MAX_JOINTS];
} cub_evolve_map;

/* Parse / read a map file; errors name file:line. */
cub_err cub_evolve_map_parse(const char *text, size_t len, const char *name, cub_evolve_map *out,
                             cub_diag *diag);
cub_err cub_evolve_map_load(const char *path, cub_evolve_map *out, cub_diag *diag);

typedef struct cub_evolve_pair {
    int a, b; /* joint of parent 1, joint of parent 2 */
} cub_evolve_pair;

typedef enum cub_evolve_kind {
    CUB_EVOLVE_NONE = 0, /* no partner */
    CUB_EVOLVE_ONE_TO_ONE,
    CUB_EVOLVE_MANY_TO_ONE, /* this joint shares its one partner with others */
    CUB_EVOLVE_ONE_TO_MANY, /* this joint has several partners */
} cub_evolve_kind;

typedef struct cub_evolve_corr {
    int pair_count;
    cub_evolve_pair pair[2 * CUB_EVOLVE_MAX_JOINTS];
    int a_count, b_count; /* the parents' joint counts */
} cub_evolve_corr;

/* Pairs the joints of a (parent 1) and b (parent 2). The map (NULL: none)
 * decides for the joints it names; its unknown names fail with its
 * file:line. The others: by name (case and "L"/"Left", "R"/"Right" aside),
 * then by structure (the only unmatched child of two matched parents, each
 * side, is the same joint), roots always paired. End sites pair only by
 * name or with their parent's partner's end site. */
cub_err cub_evolve_correspond(const cub_skeleton *a, const cub_skeleton *b,
                              const cub_evolve_map *map, cub_evolve_corr *out, cub_diag *diag);
/* The first partner in b of joint ja of a, or -1. */
int cub_evolve_partner_of_a(const cub_evolve_corr *c, int ja);
/* How joint ja of a (side 1) or jb of b (side 2) corresponds. */
cub_evolve_kind cub_evolve_kind_of(const cub_evolve_corr *c, int side, int joint);
const char *cub_evolve_kind_str(cub_evolve_kind k);

/* ---- crossover ------------------------------------------------------------- */

typedef struct cub_evolve_meta {
    cub_skeleton skel;                  /* M_s: parent 1's joints first, in order */
    int from[CUB_EVOLVE_MAX_JOINTS];    /* 1 or 2: the parent a joint comes from */
    int src[CUB_EVOLVE_MAX_JOINTS];     /* its index in that parent */
    int partner[CUB_EVOLVE_MAX_JOINTS]; /* parent 1's joints: the partner in b, or -1 */
    /* parent 1's joints: all their partners in b, in the map's order
     * (one-to-many: the bear's Spine Chest for one Torso) */
    int partner_count[CUB_EVOLVE_MAX_JOINTS];
    int partners[CUB_EVOLVE_MAX_JOINTS][CUB_EVOLVE_MAP_SIDE];
    int appended;                       /* joints from parent 2 */
} cub_evolve_meta;

/* M_s = C_s1 ∪ C_s2. An appended joint whose name parent 1 already uses
 * gets "_2". CUB_ERR_FULL past CUB_EVOLVE_MAX_JOINTS (said in diag). */
cub_err cub_evolve_crossover(const cub_skeleton *a, const cub_skeleton *b,
                             const cub_evolve_corr *corr, cub_evolve_meta *out, cub_diag *diag);

/* ---- mutation -------------------------------------------------------------- */

/* Activity of every joint of m (eq. 3-2, fixed): the joint's bone (the mean
 * of its children's rest offsets; a leaf: its own) turned by the joint's
 * local rotation at t and t-1; θ(t) the angle between the two, degrees;
 * activity = the standard deviation of θ over the clip. act_deg: joint_count. */
void cub_evolve_activity(const cub_evolve_motion *m, double *act_deg);

typedef struct cub_evolve_mutation {
    int count; /* joints to remove (CUB_EVOLVE_MUTATIONS_DEFAULT is the seed's); 0: none */
    double weight[CUB_EVOLVE_MAX_JOINTS]; /* per meta joint, added to its score; 0 = unchanged */
} cub_evolve_mutation;

typedef struct cub_evolve_pop {
    cub_skeleton skel;                   /* C_p */
    int meta[CUB_EVOLVE_MAX_JOINTS];     /* child joint -> meta joint */
    int child[CUB_EVOLVE_MAX_JOINTS];    /* meta joint -> child joint, -1 if removed */
    int removed[CUB_EVOLVE_MAX_JOINTS];  /* per meta joint: 1 in the mutation set Mu_s */
    double score[CUB_EVOLVE_MAX_JOINTS]; /* per meta joint: 0..1 + weight; lower goes first */
    int removed_count;
    int relinked; /* kept joints whose parent was removed */
} cub_evolve_pop;

/* The mutation (algorithm 3.15). Scores (PCA, ours): each parent's
 * activities are standardised (z-scores over its non-root joints); a meta
 * joint is the point (z1, z2) - its own z twice when it has no partner;
 * the point's projection on the first principal axis (turned towards the
 * first quadrant) is its PCA value; the values are rescaled to 0..1 and
 * the user weight added, so a weight <= -1 puts a joint before every
 * unweighted one (a horn at -2 with count 1 is the one removed) and >= +1
 * keeps it. The root and end sites are never chosen; a removed joint's end
 * sites go with it. A kept joint whose parent was removed is re-linked to
 * its nearest kept ancestor, its rest offset the sum of the skipped ones. */
cub_err cub_evolve_mutate(const cub_evolve_meta *meta, const cub_evolve_motion *p1,
                          const cub_evolve_motion *p2, const cub_evolve_mutation *cfg,
                          cub_evolve_pop *out, cub_diag *diag);

/* ---- survivor ------------------------------------------------------------- */

typedef struct cub_evolve_survivor_cfg {
    double blend; /* x: 0 = parent 1's motion; 1 = parent 2's; negative allowed */
    int step;     /* parent 1 sampled every step frames; 0 = CUB_EVOLVE_SAMPLE_STEP */
    int in_time;  /* 1: no window search, parent 2 laid from its frame 0 (parents already in
                   * time, e.g. a coach clip timed to the music; the energy still reported) */
} cub_evolve_survivor_cfg;

typedef struct cub_evolve_survivor_report {
    int offset;        /* parent 2's window starts at this frame */
    double energy;     /* its energy loss: mean sin²(θ/2), θ the partners' angle, at the samples */
    double mean_d_deg; /* mean |d(t)| over the child's joints and frames */
} cub_evolve_survivor_report;

/* The child's motion on C_p (ours where the seed is lost). Each parent's
 * rotations are taken relative to its own mean pose, D_j(t) = q̄_j^-1 q_j(t)
 * (the parents' rest poses differ; their movements compare). Parent 2 is
 * laid against parent 1 at every start frame o (looping); the energy loss
 * of o is the mean sin²(θ/2), θ the angle between partners' D, at parent
 * 1's samples; the least wins (the first of equals). For a joint with a
 * partner (several: cub_evolve_partner_rot's combination, D2 relative to
 * its mean) d_j(t) = log(D1_j(t)^-1 D2_j(t + o)) and q_j(t) = q1_j(t)
 * exp(x d_j(t)): x = 0 is parent 1 exactly, x = 1 parent 1's mean pose
 * moving as parent 2 does. The root's position and rotation stay parent
 * 1's (its path). Appended joints take parent 2's rotation at t + o. The
 * child is as long as the longer parent (the shorter loops; parent 1's
 * root carries on along the floor from where each loop ended). A joint
 * re-linked past removed ones takes their rotations too. Both parents at
 * the same fps. */
/* Every joint's mean rotation over m (mean: joint_count), as the survivor
 * takes it: the normalised sum, each frame turned into the first frame's
 * hemisphere. */
void cub_evolve_mean_pose(const cub_evolve_motion *m, cub_dq *mean);

/* What parent 2 does at a meta joint j of parent 1 at frame f of p2 (ours):
 * its one partner's local rotation; several partners that are a chain in
 * parent 2 (each the parent of the next: Spine, Chest for one Torso) give
 * the product of theirs, down the chain; others (two legs for one tail)
 * their mean (the normalised sum, the first's hemisphere). Identity when j
 * has no partner. */
cub_dq cub_evolve_partner_rot(const cub_evolve_meta *meta, const cub_evolve_motion *p2, int f,
                              int j);
/* The mean over p2's frames of cub_evolve_partner_rot for every meta joint
 * of parent 1 (mean: the meta skeleton's joint_count; identity where none). */
void cub_evolve_partner_means(const cub_evolve_meta *meta, const cub_evolve_motion *p2,
                              cub_dq *mean);

cub_err cub_evolve_survivor(const cub_evolve_meta *meta, const cub_evolve_pop *pop,
                            const cub_evolve_motion *p1, const cub_evolve_motion *p2,
                            const cub_evolve_survivor_cfg *cfg, cub_evolve_motion *child,
                            cub_evolve_survivor_report *rep, cub_diag *diag);

/* ---- the floor constraint ------------------------------------------------- */

typedef struct cub_evolve_floor_report {
    int below_before;  /* joint-frames below y = 0 before */
    int below_after;   /* ... after (0 by design) */
    int frames_ik;     /* frames the IK step changed */
    int frames_lifted; /* frames where IK fell short and the root was raised */
    double deepest_mm; /* the lowest joint before, below 0 */
} cub_evolve_floor_report;

/* No joint below y = 0: per frame, each joint below is pulled up onto the
 * floor (its projection on the X-Z plane) by damped least-squares steps of
 * its ancestors' rotations (the Jacobian ∂y/∂(rx, ry, rz), three parents
 * up, never the root); what is still below after the steps is lifted by
 * raising the root. Rotations only: bone lengths are untouched. */
void cub_evolve_floor(cub_evolve_motion *m, cub_evolve_floor_report *rep);

/* The largest |world bone length - rest length| (mm) over m's frames for
 * the joints of pop whose parent link is the meta skeleton's (not
 * re-linked); rest lengths from the parents the joints come from. */
double cub_evolve_bone_error_mm(const cub_evolve_motion *m, const cub_evolve_pop *pop,
                                const cub_evolve_meta *meta);

/* Foot slide of one joint over m: its contacts (low and slow, app/join's
 * rule, the floor its lowest point), and its horizontal travel per frame
 * between two contact frames. */
typedef struct cub_evolve_slide_report {
    int contact_frames; /* frame pairs both in contact */
    double mean_mm;     /* travel per frame, mean over those */
    double max_mm;
} cub_evolve_slide_report;

/* CUB_ERR_ARG: no such joint or fewer than 2 frames; CUB_ERR_NOMEM. */
cub_err cub_evolve_slide(const cub_evolve_motion *m, int joint, cub_evolve_slide_report *out);

#endif

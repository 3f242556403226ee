/* retarget — a human motion clip onto the bear (or any target skeleton),
 * offline, in doubles. Also the recipe the clip library is built from.
 *
 * Correspondence model. A map is a list of links; each link says which
 * source joint(s) drive one target joint:
 *     target joint  <-  source joints s_1..s_n with weights w_1..w_n
 * The link's source position is the weighted mean of the sources' world
 * positions; its source rotation is that of s_1. Today's tables are the
 * one-to-one case (n = 1, w = 1): assets/retarget/<kind>.map, one line
 * `BearJoint SourceJoint [aim|rot]`. Several links may name the same source
 * joint (one-to-many) and a link may list several sources
 * (`Chest Spine1:0.5 Spine2:0.5`, many-to-one), which is where skeleton
 * crossover (SEEDS.md § 004) plugs in: it builds a map, this file runs it.
 *
 * Transfer, per output frame (30 fps):
 * - Frames. Q0 turns the source's rest frame (its up = hips->head, its
 *   left = right hip->left hip, each snapped to the nearest file axis, since
 *   files are y up or z up) into the target's (y up, facing +z, left
 *   +x); a yaw turns the clip's mean facing to +z (plus desc.turn_deg).
 *   G_j = Yaw * W_s * Q0^-1 is the link's source world rotation, relative
 *   to the source rest, in target coordinates.
 * - aim links (the default when the target joint has a linked child): the
 *   target bone j->child points exactly along the source's world bone
 *   direction (between the two links' source positions). Twist comes from
 *   G_j corrected by the rest alignment A_j (the rotation taking the
 *   source's rest bone direction to the target's): start from G_j * A_j^-1,
 *   then swing it onto the source direction. World-direction transfer is
 *   robust to different rest poses (CMU's legs splay 20 degrees at rest).
 * - rot links: the target joint's world rotation is G_j (rotation change
 *   from the rest pose, transferred as is): clavicles, hands, feet.
 * - unlinked joints keep their rest local rotation.
 * Proportions: the root translation is scaled by k = target hip height /
 * source hip height (rest poses, hips above the lowest foot joint), so the
 * stride matches the short legs; the clip is centred on its mean ground
 * position; the lowest foot joint over the clip is put on y = 0.
 * Feet (app/retarget/feet.c): contacts are detected in the (scaled) source -
 * ankle low and slow, runs of 3 frames or more. The floor is where the
 * contacts stand: the root is shifted so the ankles in contact are, on
 * average, at the bear's rest ankle height. Each contact run is pinned at
 * one point (the run's mean ground position, at the rest ankle height) and
 * the foot is turned flat on the floor, keeping only its mean heading (a
 * human foot is rarely flat in the data; the bear's is a stiff paw). Where a
 * pinned leg cannot reach its pin the root is lowered just enough, per
 * frame (smoothed). The ankle is then put on its pin by an analytic two-bone
 * IK (hip-knee-ankle; the knee stays in its plane, forward when the leg is
 * straight), eased in and out over 4 frames around each run. Out of contact
 * a swinging foot that dips below the floor is lifted just out of it.
 * Rotations are kept in one quaternion hemisphere frame to frame.
 */
#ifndef CUB_RETARGET_H
#define CUB_RETARGET_H

#include <stddef.h>

#include "cub/err.h"
#include "cub/io.h"
#include "cub/motion.h"

#define CUB_RETARGET_MAX_SOURCES 4 /* sources per link (many-to-one) */

typedef enum cub_retarget_policy {
    CUB_RETARGET_AUTO = 0, /* aim if the target joint has a linked child, else rot */
    CUB_RETARGET_AIM,
    CUB_RETARGET_ROT,
} cub_retarget_policy;

typedef struct cub_retarget_source {
    char name[CUB_MOTION_NAME_LEN];
    int joint;     /* index in the source skeleton, after bind */
    double weight; /* > 0; a link's weights are normalised to sum 1 */
} cub_retarget_source;

typedef struct cub_retarget_link {
    char target_name[CUB_MOTION_NAME_LEN];
    int target; /* index in the target skeleton, after bind */
    int source_count;
    cub_retarget_source source[CUB_RETARGET_MAX_SOURCES];
    cub_retarget_policy policy;
    int line; /* where the link was written, for messages */
} cub_retarget_link;

typedef struct cub_retarget_map {
    char file[256];
    int link_count;
    cub_retarget_link link[CUB_MOTION_MAX_JOINTS];
    int bound; /* 1 after a successful bind */
} cub_retarget_map;

/* Parse a mapping table: '#' comments, one link per line
 * `Target Source[:weight] [Source[:weight]...] [aim|rot]`. Fails on
 * duplicate targets, bad weights, too many links or sources (file:line). */
cub_err cub_retarget_map_parse(const char *text, size_t len, const char *name,
                               cub_retarget_map *out, cub_diag *diag);
cub_err cub_retarget_map_load(const char *path, cub_retarget_map *out, cub_diag *diag);
/* Resolve the names in both skeletons; an unknown joint name fails with
 * the table's file and line, e.g. `cmu31.map:12: no source joint "LeftFot"`. */
cub_err cub_retarget_map_bind(cub_retarget_map *map, const cub_skeleton *target,
                              const cub_skeleton *source, cub_diag *diag);
/* Index of the link driving target joint t, or -1. */
int cub_retarget_map_find(const cub_retarget_map *map, int target);

/* The target's key joints, by name (NULL = the bear's names: Hips, Head,
 * LeftUpLeg/LeftLeg/LeftFoot, Right...). Each must be linked. */
typedef struct cub_retarget_joints {
    const char *hips, *head;
    const char *up_leg[2], *leg[2], *foot[2]; /* [0] left, [1] right */
} cub_retarget_joints;

typedef struct cub_retarget_desc {
    double fps;                  /* output rate; 0 = 30 */
    double start_s, end_s;       /* source range; end_s <= 0 = to the end */
    double speed;                /* playback speed; 0 = 1 */
    int mirror;                  /* swap left and right */
    double turn_deg;             /* extra yaw after facing +z */
    int keep_facing;             /* 1 = do not turn the clip to face +z */
    int no_contacts;             /* 1 = no foot pinning (for tests) */
    double contact_height_mm;    /* ankle above its lowest, target scale; 0 = 30 */
    double contact_speed_mm_s;   /* ankle speed, target scale; 0 = 180 */
    cub_retarget_joints joints;
    const char *name; /* for messages; NULL = "clip" */
} cub_retarget_desc;

/* What a retarget did, for reports and tests. */
typedef struct cub_retarget_report {
    double leg_ratio;          /* k: target hip height / source hip height */
    double yaw_deg;            /* turn applied about y (after Q0) */
    double offset_mm[3];       /* target root = k * Yaw * Q0 * src_root + offset */
    int frames;
    int contact_frames[2];     /* per foot (left, right) */
    double min_foot_mm;        /* lowest foot joint over the clip (0 by design) */
    double contact_ankle_mm;   /* mean ankle height during contacts */
    double slide_mean_mm;      /* ankle travel per frame during contacts */
    double slide_max_mm;
    double max_ang_deg;        /* largest local rotation change per frame */
} cub_retarget_report;

/* Retarget src (any rate) onto target through a bound map. out receives a
 * copy of target, the new clip (heap, free with cub_io_motion_free) and a
 * BVH channel layout (root XYZ + ZXY, joints ZXY, millimetres). */
cub_err cub_retarget_clip(const cub_retarget_map *map, const cub_skeleton *target,
                          const cub_clip *src, const cub_retarget_desc *desc, cub_io_motion *out,
                          cub_retarget_report *report, cub_diag *diag);

/* Load a source clip: a .bvh, or an .asf with its .amc (amc_path given).
 * Picks nothing else; a plain wrapper over cub_io for the tool and tests. */
cub_err cub_retarget_load_source(const char *path, const char *amc_path, cub_io_motion *out,
                                 cub_diag *diag);

/* A PNG contact sheet of a clip for a person to look at: `columns` evenly
 * spaced frames, front view above, side view below, floor line at y = 0. */
cub_err cub_retarget_sheet_png(const char *path, const cub_clip *clip, int columns);
/* Several clips side by side on one sheet (n <= 8; e.g. evolve's parents
 * and child): each a block of `columns` frames as above, titles[i] (NULL:
 * no title strip) written above its block. Size: 200 * columns * n by
 * 480 (+ CUB_SHEET_TITLE_H with titles) pixels. */
#define CUB_SHEET_TITLE_H 24
cub_err cub_retarget_sheet_multi_png(const char *path, const cub_clip *const *clips,
                                     const char *const *titles, int n, int columns);

/* ---- the library recipe (assets/library/recipe.txt) -------------------- */

#define CUB_RECIPE_MAX_CLIPS 64

typedef struct cub_recipe_clip {
    char name[CUB_MOTION_NAME_LEN];
    char kind[16];     /* "dance" or "coach" */
    char source[256];  /* data-dir relative path, or keys:assets/keys/x.keys */
    char map[256];     /* mapping table, relative to the source tree; "-" for keys */
    double start_s, end_s;
    double speed;      /* 1 unless speed=... */
    int mirror;
    double turn_deg;
    int line;
} cub_recipe_clip;

typedef struct cub_recipe {
    int clip_count;
    cub_recipe_clip clip[CUB_RECIPE_MAX_CLIPS];
} cub_recipe;

cub_err cub_recipe_parse(const char *text, size_t len, const char *name, cub_recipe *out,
                         cub_diag *diag);
cub_err cub_recipe_load(const char *path, cub_recipe *out, cub_diag *diag);

#endif

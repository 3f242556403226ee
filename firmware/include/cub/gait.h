/* gait — seed 003 (SEEDS.md § 003): one captured walk cycle adapted to any
 * ground. This slice: the phase analysis of a walk (per foot, from the
 * ankle and toe heights and the foot's pitch: the foot length and the five
 * key phases of each leg cycle), the terrain (flat, sloped, a rolling
 * heightfield, box obstacles added at run time), the footstep planner
 * (sequential, backtracking, first feasible step taken) and the swing
 * path (the quartic Bézier raised until it clears the terrain).
 *
 * World frame as in cub/motion.h: Q16.16 millimetres, y up; the ground is
 * a height y over the (x, z) plane. Fixed point, no allocation: the caller
 * owns every array. Choices the seed leaves open are marked [ours] here and
 * in docs/gait.md.
 */
#ifndef CUB_GAIT_H
#define CUB_GAIT_H

#include <stdbool.h>
#include <stdint.h>

#include "cub/err.h"
#include "cub/fx.h"
#include "cub/motion.h"

/* ---- phase analysis ------------------------------------------------------ */

/* The seed's five key phases, in the order a leg cycle runs them. */
typedef enum cub_gait_phase {
    CUB_GAIT_STANCE = 0, /* ankle and toe on the ground */
    CUB_GAIT_LIFT,       /* ankle up, toe still down */
    CUB_GAIT_OFF,        /* both up: the swing */
    CUB_GAIT_STRIKE,     /* first contact again, one of the two down */
    CUB_GAIT_LAND,       /* both down, the foot still settling to flat */
    CUB_GAIT_PHASE_COUNT_
} cub_gait_phase;

/* A short lowercase name ("stance", "lift", ...); never NULL. */
const char *cub_gait_phase_name(cub_gait_phase p);

/* Thresholds the seed does not give [ours]. All 0: the defaults.
 * A point (ankle or toe) is down at a frame when it is within down_mm of
 * its ground there and moves slower than still_mm_s. Its ground is its
 * lowest height within half a second either side: a captured floor is not
 * level (CMU 02_01's footfalls differ by 5 cm), one lowest height for the
 * whole clip would leave later steps in the air. */
typedef struct cub_gait_phase_params {
    int fps;              /* frames per second of the tracks (0: 120) */
    cub_q16 down_mm;      /* (0: 25 mm) */
    cub_q16 still_mm_s;   /* (0: 1000 mm/s) */
    cub_q16 settle_rad_s; /* land ends when the pitch turns slower (0: 30 deg/s) */
    int min_frames;       /* a point's contact change shorter than this is noise (0: fps / 24) */
} cub_gait_phase_params;

/* What the analysis learnt of one foot. */
typedef struct cub_gait_foot {
    cub_q16 length_mm; /* ankle -> toe, mean over the clip (the foot base) */
    /* Over the frames with both points down (most are stance) [ours]: */
    cub_q16 ankle_lift_mm;                   /* the ankle's mean height over the toe's */
    cub_q16 flat_pitch_rad;                  /* the foot's mean pitch: its pitch when flat */
    int cycles;                              /* complete lift..land cycles seen */
    int phase_frames[CUB_GAIT_PHASE_COUNT_]; /* frames spent in each phase */
} cub_gait_foot;

/* The foot's pitch: the angle of ankle -> toe below the horizontal
 * (positive: the ankle is above the toe). */
cub_q16 cub_gait_foot_pitch(cub_vec3 ankle_mm, cub_vec3 toe_mm);

/* Per frame world positions of an ankle and a toe joint of a clip (FK on
 * every frame). ankle_out and toe_out hold clip->frame_count entries. */
cub_err cub_gait_track_clip(const cub_clip *clip, int ankle, int toe, cub_vec3 *ankle_out,
                            cub_vec3 *toe_out);

/* One foot's phases: phase_out[frames] gets one cub_gait_phase per frame,
 * foot the lengths and counts. p may be NULL. Frames before the foot's
 * first stance are labelled by what they look like (a clip may start mid
 * swing). CUB_ERR_ARG for NULL arrays or fewer than 2 frames. */
cub_err cub_gait_analyse(const cub_vec3 *ankle_mm, const cub_vec3 *toe_mm, int frames,
                         const cub_gait_phase_params *p, uint8_t *phase_out, cub_gait_foot *foot);

/* ---- terrain ------------------------------------------------------------- */

typedef enum cub_gait_ground {
    CUB_GAIT_FLAT = 0, /* y = base */
    CUB_GAIT_SLOPE,    /* y = base + grad_x * x + grad_z * z */
    CUB_GAIT_ROLLING   /* a heightfield, bilinear between its samples */
} cub_gait_ground;

/* An obstacle: an axis-aligned box (a log lying across, a stone). The
 * ground under its footprint is its top, max_mm.y, where that is higher. */
typedef struct cub_gait_box {
    cub_vec3 min_mm, max_mm;
} cub_gait_box;

#define CUB_GAIT_MAX_OBSTACLES 16

typedef struct cub_gait_terrain {
    cub_gait_ground ground;
    cub_q16 base_mm;        /* FLAT and SLOPE: the height at x = z = 0 */
    cub_q16 grad_x, grad_z; /* SLOPE: rise per unit run (Q16.16, 1 = 45 degrees) */
    /* ROLLING: nx * nz heights, row major (x fastest), sample (i, j) at
     * origin + (i, j) * cell_mm; outside, the nearest edge sample holds. */
    const cub_q16 *heights_mm;
    int nx, nz;
    cub_q16 cell_mm;
    cub_q16 origin_x_mm, origin_z_mm;
    cub_gait_box obstacles[CUB_GAIT_MAX_OBSTACLES];
    int obstacle_count;
} cub_gait_terrain;

void cub_gait_terrain_flat(cub_gait_terrain *t, cub_q16 base_mm);
void cub_gait_terrain_slope(cub_gait_terrain *t, cub_q16 base_mm, cub_q16 grad_x, cub_q16 grad_z);
/* A rolling heightfield over heights_mm[nx * nz] (the caller's), filled
 * here with gentle hills: amp_mm * sin(2 pi x / wave) * cos(2 pi z / wave), x
 * and z from the grid's origin (origin_*_mm, 0 here; the caller may move it)
 * [ours: one smooth family, enough for a forest floor]. CUB_ERR_ARG for a
 * grid under 2 x 2, cell or wave <= 0. */
cub_err cub_gait_terrain_rolling(cub_gait_terrain *t, cub_q16 *heights_mm, int nx, int nz,
                                 cub_q16 cell_mm, cub_q16 amp_mm, cub_q16 wave_mm);
/* Add an obstacle at run time. CUB_ERR_FULL past CUB_GAIT_MAX_OBSTACLES,
 * CUB_ERR_ARG for an empty box. */
cub_err cub_gait_terrain_add(cub_gait_terrain *t, cub_gait_box box);
/* The ground alone, and the ground with the obstacles on it. */
cub_q16 cub_gait_ground_height(const cub_gait_terrain *t, cub_q16 x_mm, cub_q16 z_mm);
cub_q16 cub_gait_height(const cub_gait_terrain *t, cub_q16 x_mm, cub_q16 z_mm);
/* true for a terrain the planner may treat as flat: FLAT, no obstacles. */
bool cub_gait_terrain_is_flat(const cub_gait_terrain *t);

/* ---- footstep planner ----------------------------------------------------- */

#define CUB_GAIT_MAX_STEPS 5
#define CUB_GAIT_MAX_TRIES 8

/* The seed's quartic Bézier (eq. 4-2): P0 the foot's current point, P4 the
 * next foothold, P1..P3 start at the quartile, middle and third quartile
 * of P0P4 and are raised together until the sole clears the terrain: the
 * least raise (in raise_mm steps) is solved for, not stepped to. */
typedef struct cub_gait_swing {
    cub_vec3 p[5];
    int raises; /* times P1..P3 were raised */
    int clear;  /* 1: the path clears the terrain by clearance_mm */
} cub_gait_swing;

struct cub_gait_swing_params {
    cub_q16 clearance_mm; /* the sole stays this far above (0: 20 mm) */
    cub_q16 raise_mm;     /* each raise (0: 10 mm) [ours] */
    int max_raises;       /* give up after (0: 100) [ours] */
    int samples;          /* points of the path tested over the ground (0: 64); the obstacles
                             are tested exactly, between the first and last of them [ours] */
    cub_q16 foot_mm;      /* the toe, this far ahead of the ankle along P0P4, is tested too */
    cub_q16 heel_mm;      /* the heel, this far behind the ankle along P0P4, is tested too */
    cub_q16 side_mm[2];   /* ... and ankle, toe and heel this far off the line: [0] toward
                             (d.z, 0, -d.x), d the direction P0 -> P4; [1] the other way */
};
typedef struct cub_gait_swing_params cub_gait_swing_params;

typedef struct cub_gait_plan_params {
    int steps;           /* n; 0: by terrain, 4 on flat ground, 3 on rough */
    cub_q16 stride_mm;   /* one step's nominal length (from the walk) */
    cub_q16 width_mm;    /* lateral distance between the feet's lines */
    cub_q16 foot_mm;     /* the foot base: ankle -> toe */
    cub_q16 max_rise_mm; /* step up or down at most this (0: 200 mm) */
    cub_q16 max_tilt_mm; /* the foot base's ground may differ by this (0: 30 mm) */
    cub_q16 obstacle_gap_mm; /* the foot base is on an obstacle's top or this far off its
                                footprint, never just beside (0: 20 mm; < 0: no test) [ours] */
    /* The step lengths tried, in order, as fractions of stride_mm; the
     * first feasible is taken (the seed ranks none). tries 0: the default
     * 1, 0.75, 1.25, 0.5, 1.5 [ours]. */
    int tries;
    cub_q16 factors[CUB_GAIT_MAX_TRIES];
    /* Not NULL (and the terrain not flat): a foothold is feasible only if
     * the swing to it from the same foot's last foothold clears within
     * swing->max_raises (cub_gait_swing_path), so a step planted too near
     * an obstacle, from where no low swing can clear it, is refused and
     * the look-ahead backtracks [ours: the seed tests footholds only].
     * The other foot's swings take side_mm mirrored ([0] and [1] swapped). */
    const struct cub_gait_swing_params *swing;
} cub_gait_plan_params;

/* Where the walk stands: the last foothold (the ankle's ground point), its
 * side, and the heading (x, z; any length but zero). */
typedef struct cub_gait_start {
    cub_vec3 foot_mm;
    int left; /* 1: the last foot down is the left one */
    cub_q16 dir_x, dir_z;
    cub_vec3 swing_from_mm; /* with params->swing: where the first step's foot stands now */
} cub_gait_start;

typedef struct cub_gait_step {
    cub_vec3 foot_mm; /* the ankle's point on the ground */
    int left;
    int try_index; /* which of the factors placed it */
} cub_gait_step;

typedef struct cub_gait_plan {
    int count; /* steps planned (== n when it succeeded) */
    cub_gait_step steps[CUB_GAIT_MAX_STEPS];
    int tested;     /* footholds tested */
    int backtracks; /* times a step was given up and its predecessor retried */
    /* With params->swing (the terrain not flat): the swing tested to
     * steps[0] (swung 1), so the walker need not solve it again. */
    cub_gait_swing first_swing;
    int swung;
} cub_gait_plan;

/* true if a foot may stand at foot_mm (ankle ground point) heading along
 * (dir_x, dir_z), coming from a foothold at from_y_mm: its base is level
 * (ankle, middle and toe ground within max_tilt), the rise from the last
 * foothold is within max_rise, and its base is on an obstacle's top or
 * obstacle_gap clear of it (heel a quarter foot behind the ankle, a fifth
 * of the foot either side). */
bool cub_gait_foothold_ok(const cub_gait_terrain *t, const cub_gait_plan_params *p,
                          cub_q16 from_y_mm, cub_q16 x_mm, cub_q16 z_mm, cub_q16 dir_x,
                          cub_q16 dir_z);

/* The next n footholds, sequentially (step i+1 only once i succeeded; on
 * a failure back up to i-1, then i-2, ...; the first feasible step found
 * is taken). When backtracking runs out: CUB_ERR_EMPTY with out->count 0
 * [ours: the walk stops where it is]. CUB_ERR_ARG for bad parameters. */
cub_err cub_gait_plan_steps(const cub_gait_terrain *t, const cub_gait_plan_params *p,
                            const cub_gait_start *start, cub_gait_plan *out);

/* The planner resumable [ours]: begin, then run until it returns true
 * (done; err CUB_OK with the plan, or CUB_ERR_EMPTY as above), testing
 * at most budget footholds per run; the tests and the plan are those of
 * cub_gait_plan_steps whatever the budgets. The walker spreads a plan
 * over the frames before its foot-off this way. A plain struct (it may
 * be copied); the terrain must not change between runs. */
typedef struct cub_gait_planner {
    cub_gait_plan_params p;
    cub_gait_swing_params swing; /* *p.swing, kept */
    int has_swing;
    cub_gait_start start;
    int k[CUB_GAIT_MAX_STEPS]; /* the try each step is at */
    int i;                     /* the step being planned */
    int done;
    cub_err err;
    cub_gait_plan plan;
} cub_gait_planner;

/* CUB_ERR_ARG for NULLs or bad parameters (as cub_gait_plan_steps). */
cub_err cub_gait_planner_begin(cub_gait_planner *pl, const cub_gait_plan_params *p,
                               const cub_gait_start *start);
bool cub_gait_planner_run(cub_gait_planner *pl, const cub_gait_terrain *t, int budget);

/* ---- swing path ------------------------------------------------------------ */


/* B(t), t in [0, 1] Q16.16. */
cub_vec3 cub_gait_bezier4(const cub_vec3 p[5], cub_q16 t);

/* The swing from from_mm to to_mm over t. The end points themselves are
 * not tested (they are footholds). p may be NULL. CUB_ERR_RANGE when
 * max_raises did not clear it (out holds the highest path tried). */
cub_err cub_gait_swing_path(const cub_gait_terrain *t, const cub_gait_swing_params *p,
                            cub_vec3 from_mm, cub_vec3 to_mm, cub_gait_swing *out);

/* ---- leg IK with limits ----------------------------------------------------- */

/* The seed's IK formula is missing: ours is cub/motion.h's two-bone
 * solve (hip, knee, ankle) plus the ankle, with the seed's three
 * corrections: the foot to a reachable position (the ankle target pulled
 * in along the hip's ray), thigh and knee to reasonable angles (the knee's
 * inner angle kept in its range), the ankle to a reasonable angle (the
 * foot turned, in the shin's plane, back into its range). */
typedef struct cub_gait_leg_limits {
    cub_q16 knee_min_rad, knee_max_rad;   /* inner angle, pi straight (0, 0: 25..175 deg) */
    cub_q16 ankle_min_rad, ankle_max_rad; /* shin to foot (0, 0: 35..150 deg) [ours] */
} cub_gait_leg_limits;

typedef struct cub_gait_leg {
    cub_vec3 hip_mm;           /* the thigh's root */
    cub_q16 thigh_mm, shin_mm; /* > 0 */
    cub_vec3 pole_mm;          /* a point the knee bends toward (ahead of the leg) */
} cub_gait_leg;

#define CUB_GAIT_LEG_REACH 1 /* the ankle target was out of reach (or too near) */
#define CUB_GAIT_LEG_ANKLE 2 /* the foot was turned back into the ankle's range */

typedef struct cub_gait_leg_pose {
    cub_vec3 knee_mm, ankle_mm, toe_mm;
    cub_q16 knee_rad;  /* inner angle at the knee */
    cub_q16 ankle_rad; /* between the shin (knee -> ankle) and the foot (ankle -> toe) */
    int corrected;     /* CUB_GAIT_LEG_* flags */
} cub_gait_leg_pose;

/* The angle between the shin and the foot. */
cub_q16 cub_gait_ankle_angle(cub_vec3 knee_mm, cub_vec3 ankle_mm, cub_vec3 toe_mm);

/* Put the ankle at ankle_target and the toe toward toe_target (the foot
 * keeps its length |toe_target - ankle_target|). lim may be NULL.
 * CUB_ERR_ARG for a bone <= 0 or a zero-length foot. */
cub_err cub_gait_leg_solve(const cub_gait_leg *leg, const cub_gait_leg_limits *lim,
                           cub_vec3 ankle_target, cub_vec3 toe_target, cub_gait_leg_pose *out);

/* The leg of a skeleton's pose: the ankle joint's grandparent is the hip
 * (thigh root), its parent the knee; the pole is the knee 10 cm along
 * ahead (a unit heading). CUB_ERR_ARG for a chain too short. */
cub_err cub_gait_pose_leg(const cub_skeleton *sk, const cub_pose *pose, int ankle, cub_vec3 ahead,
                          cub_gait_leg *leg);

typedef struct cub_gait_leg_target {
    int ankle, toe;             /* joint indices */
    cub_vec3 ankle_mm, toe_mm;  /* world targets */
    cub_vec3 ahead;             /* unit heading (the knee's pole side) */
} cub_gait_leg_target;

/* cub_gait_leg_solve on a pose: rewrites the hip's and knee's rotations
 * (cub_motion_ik_apply) and turns the ankle so the toe joint points at
 * the solved toe. out: the solved geometry. */
cub_err cub_gait_leg_apply(const cub_skeleton *sk, cub_pose *pose, const cub_gait_leg_target *t,
                           const cub_gait_leg_limits *lim, cub_gait_leg_pose *out);

/* How far the pelvis must lower (>= 0, mm) so that both hips reach their
 * ankle targets with the knees inside their range: the seed's "the pelvis
 * lowers so both feet reach". */
cub_q16 cub_gait_pelvis_drop(const cub_gait_leg legs[2], const cub_gait_leg_limits *lim,
                             const cub_vec3 ankle_targets[2]);

/* ---- walker: a captured walk cycle driven over a terrain -------------------- */

/* The key configuration at a foot-strike by the step's height difference
 * (the seed: "the key configuration may be set differently by the feet's
 * height difference, uphill or downhill"; the rule is ours): the pelvis
 * sits a quarter of |dh_mm| below the mean of the two footholds, so at
 * the strike of a step up the leading knee bends more (the body is still
 * over the lower foot), and at a step down the supporting knee bends more
 * (the body lowers toward the lower foot before it takes the weight).
 * dh_mm: the landing foothold's height minus the supporting one's; |dh|
 * counts up to 200 mm. Returns the pelvis offset (<= 0, mm). The walker
 * goes from one strike's key to the next with a cubic Bezier in time
 * (smoothstep: no speed at the keys). */
cub_q16 cub_gait_key_pelvis(cub_q16 dh_mm);


/* Use: per foot, cub_gait_track_clip then cub_gait_analyse on the clip
 * (once); fill a cub_gait_walk_clip; cub_gait_walker_init; then one
 * cub_gait_walker_step per clip frame (1/fps s), the pose out of it. The
 * clip, its arrays and the terrain must outlive the walker (it keeps
 * pointers); obstacles added to the terrain meanwhile count from the next
 * plan (the next foot-off: a plan made ahead under fewer obstacles is
 * dropped); nothing else of the terrain may change. Events come from
 * inside step. The walker is a
 * plain struct (5.3 kB on x86-64, most of it the pose); no allocation; a step
 * copies it once per foot-off on the stack (planning ahead). */

/* Footstep events, for the box's event log. */
typedef enum cub_gait_event_kind {
    CUB_GAIT_EV_PLANNED = 0, /* one foothold of a new plan (index = its place in the plan) */
    CUB_GAIT_EV_BACKTRACKED, /* the plan just made backed up count times */
    CUB_GAIT_EV_TAKEN,       /* a foot came down on its foothold */
    CUB_GAIT_EV_BLOCKED      /* no plan: the walker stops on both feet [ours] */
} cub_gait_event_kind;

typedef struct cub_gait_event {
    cub_gait_event_kind kind;
    int left;         /* 1: the left foot (the clip's, not the planner's side label) */
    int step;         /* the walker's step number (one per swing, from 0) */
    int index, count; /* PLANNED: place in the plan; BACKTRACKED: backtracks */
    cub_vec3 foot_mm; /* the foothold (ankle's ground point), world */
} cub_gait_event;

typedef void (*cub_gait_event_fn)(void *ctx, const cub_gait_event *e);

/* The walk the walker plays: the caller's clip and its analysis (arrays
 * from cub_gait_track_clip and cub_gait_analyse, frame_count entries each;
 * [0] the left foot, [1] the right). The leg chain is ankle's parent
 * (knee) and grandparent (hip). The walker keeps these pointers. */
typedef struct cub_gait_walk_clip {
    const cub_clip *clip;
    int ankle[2], toe[2];
    const cub_vec3 *ankle_mm[2], *toe_mm[2];
    const uint8_t *phase[2];
    cub_gait_foot foot[2];
} cub_gait_walk_clip;

/* Fill *out for clip: per foot (ankle[i], toe[i] joint indices; [0] the
 * left) its tracks and phases into the caller's arrays (frame_count
 * entries each), analysed at the clip's own frame rate with the default
 * thresholds. Errors as cub_gait_track_clip and cub_gait_analyse. */
cub_err cub_gait_walk_clip_make(const cub_clip *clip, const int ankle[2], const int toe[2],
                                cub_vec3 *const ankle_mm[2], cub_vec3 *const toe_mm[2],
                                uint8_t *const phase[2], cub_gait_walk_clip *out);

/* The walker's parts that cub_gait_walk_params.without may leave out
 * (measurement only: the walk then slides, pops or floats). */
enum {
    CUB_GAIT_NO_PIN = 1,   /* stance feet follow the clip's own slide */
    CUB_GAIT_NO_CLOSE = 2, /* the cycle's mismatch is not spread (it pops at the wrap) */
    CUB_GAIT_NO_DROP = 4,  /* the pelvis does not lower */
    CUB_GAIT_NO_FLOOR = 8, /* one floor for the clip (its lowest foot point), not one per step */
    CUB_GAIT_NO_KEYS = 16, /* the key configurations do not depend on the height difference */
    CUB_GAIT_NO_AHEAD = 32, /* each plan made whole at its foot-off, not spread over the
                               frames before it (the same walk, one slow frame per step) */
    CUB_GAIT_NO_FOLLOW = 64 /* the root does not follow the pinned feet (the body moves
                               against them by the capture's slide) */
};

typedef struct cub_gait_walk_params {
    cub_vec3 start_mm;            /* where the root starts (x, z; y from the terrain) */
    cub_q16 dir_x, dir_z;         /* the first heading (0, 0: the clip's own) */
    cub_q16 max_turn_rad;         /* heading change per step (0: 10 degrees) [ours] */
    cub_gait_leg_limits limits;   /* 0: cub_gait_leg_solve's defaults */
    cub_gait_swing_params swing;  /* 0: cub_gait_swing_path's defaults */
    int steps;                    /* footholds planned ahead (0: 4 flat, 3 rough) */
    int key_swing;                /* 1: on flat ground the swing made from its key frames
                                     (a Bezier through them), not the captured one (a comparison) */
    int straight_swing;           /* 1: on flat ground the seed's straight segments between
                                     the key frames (a comparison) */
    int without;                  /* CUB_GAIT_NO_* bits: parts left out, to price each
                                     one's share of the error (cubtool gait-eval --without) */
    cub_gait_event_fn on_event;   /* may be NULL */
    void *ctx;
    /* 1: the walk ends on these footholds (x, z of the ankles; [0] the left
     * foot), e.g. where the next clip has its feet: a foot's step whose
     * foothold comes within half a step of its end foothold (along the
     * heading) lands so that its ankle stands on it once flat, the other
     * foot's next step on its own, and the walker stops at the foot-off
     * after, both feet on them and flat (not at half a step from the
     * target) [ours] */
    int has_end;
    cub_vec3 end_mm[2];
    /* has_end: the pose to arrive in, or NULL: on the clip's skeleton, local
     * rotations and the root's world place (e.g. the next clip's first
     * frame where it will play). With has_end the end feet land turned to
     * the end's facing (square to the line from the right end foothold to
     * the left) and the body turns to it over the two end swings; with
     * end_pose too every joint's rotation eases from the walk's to it over
     * both swings, the root's place over the second (the legs then solved
     * onto the feet), all of it once the second end foot is down. Read
     * every frame: the caller may move it [ours] */
    const cub_pose *end_pose;
} cub_gait_walk_params;

/* One foot of the walker (read only for the caller). */
typedef struct cub_gait_walk_foot {
    int swinging;                 /* 1: between foot-off and the next strike */
    cub_vec3 hold_mm;             /* the foothold it stands on / swings from */
    cub_vec3 next_mm;             /* swinging: the foothold it swings to */
    cub_vec3 ankle_mm, toe_mm;    /* this frame's targets (after the sole guard) */
    cub_gait_leg_pose leg;        /* this frame's IK result */
    /* internal */
    cub_vec3 plant_u, next_u;     /* the clip's ankle where it planted (unwrapped) */
    cub_q16 floor_u, next_floor;  /* the clip's floor there */
    cub_q16 yaw_c, yaw_s;         /* the heading when it planted */
    cub_vec3 pin_u[2], skate_u[2];/* ankle, toe: where stance began; the clip's slide so far */
    cub_vec3 slid_mm;             /* pinned: the clip's ankle slide since stance began (world) */
    cub_vec3 follow_at_mm;        /* the walker's follow_mm when it struck (predicted) */
    cub_vec3 stride_shift_mm;     /* swinging: the root's shift over this swing by the plan's
                                     stride changes (stride_shift) */
    int swing_at, swing_len, step;
    cub_vec3 key_u[3];            /* flat ground: the ankle at foot-off, apex, strike */
    cub_vec3 key_v[3];            /* ... its captured velocity there, mm per frame (clip axes) */
    int key_at[3];                /* their frames into the swing */
    uint8_t last_phase;
    cub_gait_swing path;
    cub_q16 path_u0, path_lift0;  /* the ankle's progress on the path at foot-off, the path's rise there */
    int rough;
    cub_q16 key_mm;               /* swinging: the pelvis key at this step's strike (<= 0) */
    cub_q16 sway_mm[2];           /* swinging: the captured ankle's stray off its line, each way */
    cub_vec3 rest_mm[2];          /* ankle, toe targets of its last stance frame (flat down) */
    int has_rest;                 /* rest_mm is set */
    int at_end;                   /* has_end: its foothold (or the one it swings to) is its end */
    cub_vec3 stand_u;             /* swinging: the clip's ankle once flat after the strike */
    cub_vec3 end_shift_mm;        /* swinging: its end foothold less the planned one */
} cub_gait_walk_foot;

typedef struct cub_gait_walker {
    const cub_gait_walk_clip *c;
    const cub_gait_terrain *t;
    cub_gait_walk_params p;
    int a, b;                     /* the cycle played: frames [a, b) */
    int frame, loops, ticks, steps;
    cub_vec3 cycle_u;             /* the root's travel over one cycle */
    cub_vec3 travel_u;            /* ... less the pinned feet's slide: the walk's direction */
    cub_vec3 origin_mm, ref_u;    /* world = origin + yaw (u - ref), horizontal */
    cub_q16 yaw_c, yaw_s;         /* the clip's heading turned to the walker's */
    cub_q16 dir_x, dir_z;         /* the walker's heading (unit) */
    cub_q16 drop_mm;              /* this frame's pelvis drop */
    cub_q16 key_mm;               /* the pelvis key of the last strike (<= 0, mm) */
    cub_vec3 end_shift_mm;        /* the root's shift by the end steps landed (half each) */
    cub_vec3 end_face;            /* has_end: the end's facing (unit), from the first end step on */
    cub_q16 end_yaw_c, end_yaw_s; /* ... the clip's heading turned to it */
    cub_vec3 follow_mm;           /* the root held back by the pinned feet's removed slide */
    cub_vec3 stride_shift_mm;     /* the root's shift by the strides the plan changed, landed */
    cub_vec3 stride_due_mm;       /* ... and the half still due at the other foot's next step */
    cub_gait_plan plan;           /* the last plan */
    /* The next foot-off's plan, made ahead a foothold test per frame while
     * both feet are down; taken at the foot-off only if its inputs are
     * the foot-off's own, byte for byte (else planned there whole). */
    cub_gait_planner ahead;
    int ahead_on;                 /* ahead holds the plan of foot ahead_foot's foot-off ... */
    int ahead_foot, ahead_frame, ahead_loops; /* ... at this frame and loop */
    int ahead_obstacles;          /* the terrain's obstacle count when it began */
    int ahead_taken;              /* foot-offs that took their plan made ahead */
    cub_gait_walk_foot feet[2];
    int arrived;                  /* 1: the root is within half a step of the target */
    int stopped;                  /* 1: at rest on both feet (arrived, or BLOCKED) */
    int blocked;                  /* 1: stopped by a BLOCKED step */
    int stop_foot, settle;        /* the foot that would have lifted; frames into its settling */
    cub_vec3 stop_target;         /* the target when it stopped */
    cub_pose pose;                /* this frame's pose of the clip's skeleton */
} cub_gait_walker;

/* Start at params->start_mm on t (both kept). CUB_ERR_ARG for NULLs,
 * CUB_ERR_FORMAT when the clip has no full left-foot cycle. */
cub_err cub_gait_walker_init(cub_gait_walker *w, const cub_gait_walk_clip *c,
                             const cub_gait_terrain *t, const cub_gait_walk_params *p);
/* One frame (the clip's frame period) toward target_mm (x, z): *out is
 * the pose (root translation, mm; local rotations, Q2.30), valid until the
 * next call. Turns at each foot-off by at most max_turn_rad. At a foot-off
 * within half a step of the target, or when the step is BLOCKED, it stops
 * instead: the frame before the foot-off is held and the lifting foot
 * settles flat on its foothold (stopped = 1). It walks on when the target
 * is again farther than half a step (after BLOCKED: when the target moved),
 * the foot lifted again first. */
cub_err cub_gait_walker_step(cub_gait_walker *w, cub_vec3 target_mm, const cub_pose **out);
/* The sole box of a foot [ours]: 6 points (heel, toe tip, and their
 * corners a fifth of the foot length either side), from the ankle and toe
 * joints, the foot length and the ankle's standing height over the sole. */
void cub_gait_sole_points(cub_vec3 ankle_mm, cub_vec3 toe_mm, cub_q16 foot_mm, cub_q16 ankle_h_mm,
                          cub_vec3 out[6]);

#endif

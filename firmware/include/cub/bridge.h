/* bridge — switching the coach from one clip to another at once, unnoticed
 * (SEEDS.md § 000, "Switching"; issue 4).
 *
 *   table    every clip of the library with its per-frame fuzzy features,
 *            its bridge frames and, for each ordered clip pair, the tagged
 *            links (a, b, d, half). Built once at init in caller memory.
 *   planner  given where the current clip is and the clip wanted next:
 *            look at the current clip's upcoming frames (any frame, not only
 *            tagged ones: that is what makes the reaction fast) against the
 *            wanted clip's bridge frames, FRONT HALF FIRST, then the back
 *            half, and take a frame within the threshold (d < 0.4) that
 *            the current clip reaches soon (see below). None: a TWEEN,
 *            the quickest chain of tagged links through other clips
 *            (Dijkstra on play time over the bridge frames; fixed memory),
 *            or, with via_tween, a route through the seed's tween clip
 *            (below; measured in the README, not used by the box).
 *            The search looks 6 frames (200 ms) ahead first and widens the
 *            window (x2) up to one whole clip only when nothing is found.
 *   player   plays the coach: advances time, switches exactly at the
 *            planned frame, reports switches and clip ends, and gives the
 *            pose with the cut smoothed, planted feet held (the leg phase,
 *            cub_bridge_legs below).
 *
 * Choosing the frame: the soonest upcoming frame within the threshold;
 * at that frame, the bridge frame whose body (joint positions, the root's
 * x and z taken off) is closest. wait_cost_mm can trade waiting for a
 * closer body (cost = distance + wait_cost_mm per frame), but measured it
 * does not pay: at 30 mm/frame the p95 reaction grows from 67 to 100 ms
 * while the naive cut's median shrinks only 33.3 -> 32.2 cm and the
 * smoothed jump stays the same (p95 8.1 cm/frame both): the adaptive blend
 * below absorbs the distance anyway.
 *
 * Smoothing: INERTIALIZATION (a decaying offset), the default. At every
 * cut (a switch, or a looping clip starting its next pass) the offset
 * between the pose on screen and the new frame (a local rotation per joint
 * and the root translation) is taken, added to the new clip, and faded out
 * by w = 1 - smoothstep: no step in position. The offset also carries the
 * velocity the body had (the old clip's last frame step less the new
 * clip's first, per joint), faded by t (1 - t/T)^2 over at most 10 frames:
 * at the cut the body goes on moving as it moved, then takes up the new
 * clip's motion — no step in speed either. Each blend lasts as long as
 * its distance needs for the fade to add at most blend_speed_mm (2.5 cm)
 * per frame, at least 6 frames, at most 60; the distance is the larger of
 * the joints' straight-line gap and the arcs the rotation offsets swing
 * them along their chains. The root's drift over the floor (capture clips
 * walk up to 90 cm) fades on its own, longer clock. Measured by `cubtool
 * bench-bridge` over the shipped library (all 529 ordered pairs, every 5th
 * frame, 10511 switches): the largest joint jump at the switch is 11.3
 * cm/frame for ours (p95 5.3, median 1.9; above the p99 of both clips it
 * joins in 0.3 % of switches, less often than the clips' own frames: 1 %),
 * 107.0 for a naive cut (p95 65.7, median 29.7), 86.9 for a crossfade of
 * the same length (p95 6.6); the clips' own fastest joint moves up to 15.6
 * cm/frame (p99 10.1). Without the carried velocity ours was p95 7.8,
 * median 3.7, 6.9 % above both p99s. The crossfade keeps playing the old
 * clip, so it blends two motions and, when the clips stand apart, drags
 * the body between them (up to 89.9 cm/frame added while it runs; ours
 * adds at most 15.3, p95 5.3, counting the carried-over velocity); the
 * offset needs only the poses around the cut and two quaternion
 * multiplies per joint and frame.
 *
 * Units: positions in clips are frames, Q16.16 (`pos_q16`), measured on
 * the clip's unwrapped time line (a looping clip keeps counting past its
 * end); speed is Q16.16 (1.0 = the clip's own rate), d Q16.16 in [0, 1],
 * times microseconds. Fixed point, deterministic, no allocation: the table
 * and the player take caller memory sized by their mem_size functions.
 */
#ifndef CUB_BRIDGE_H
#define CUB_BRIDGE_H

#include <stddef.h>
#include <stdint.h>

#include "cub/err.h"
#include "cub/fuzzy.h"
#include "cub/fx.h"
#include "cub/motion.h"

#define CUB_BRIDGE_MAX_STEPS 8                     /* longest plan: 1 direct or a tween */
#define CUB_BRIDGE_SPEED_MIN_Q16 (CUB_Q16_ONE / 4)  /* 0.25: slowest demonstration */
#define CUB_BRIDGE_SPEED_MAX_Q16 (2 * CUB_Q16_ONE)  /* 2.0 */
#define CUB_BRIDGE_WINDOW_FRAMES 6                 /* first look-ahead: 200 ms at 30 fps */
#define CUB_BRIDGE_BLEND_FRAMES 6                  /* shortest smoothing */
#define CUB_BRIDGE_BLEND_SPEED_MM CUB_Q16_INT(25)   /* 2.5 cm/frame at most added by a blend */
#define CUB_BRIDGE_MAX_BLEND_FRAMES 60
#define CUB_BRIDGE_WAIT_COST_MM CUB_Q16_MAX /* waiting outweighs any body distance */

/* ---- the table --------------------------------------------------------- */

/* "From frame a of clip A, switch to frame b of clip B" (a tag link). */
typedef struct cub_bridge_link {
    int16_t a, b;
    uint8_t back; /* b lies in B's back half (2*b >= frames) */
    uint8_t reserved_[3];
    cub_q16 d;
} cub_bridge_link;

typedef struct cub_bridge_table_desc {
    const cub_skeleton *skel; /* every clip's skeleton */
    cub_fuzzy_body body;      /* joints the features read, indices into skel */
    cub_fuzzy_config fuzzy;   /* weights and threshold; zero = seed defaults */
    int clip_count;
    int frame_total;  /* sum of all clips' frame counts */
    int bridge_total; /* sum of all clips' bridge frame counts */
    int link_total;   /* sum of all pairs' link counts */
} cub_bridge_table_desc;

typedef struct cub_bridge_clip {
    cub_clip clip;    /* frame data stays in the caller's memory */
    int first_frame;  /* its frame 0 in the table's fuzzy[] */
    int first_bridge; /* its first bridge frame in bridges[] */
    int bridge_count;
} cub_bridge_clip;

typedef struct cub_bridge_pair {
    int32_t first, count; /* into links[]; count -1: not set yet */
} cub_bridge_pair;

/* A searched route (docs/join.md, "Routes"; issue 21 § 3): from frame a
 * of clip `from`, into frame `in` of clip `via`, play it on to frame `out`,
 * then into frame b of clip `to`. Found offline (`cubtool join --all
 * --routes-out`) where the seed's searched transition through C = via
 * beats the box's own switch; loaded beside the tags (cub/routes.h). The
 * player plays via where it stands: the inertial offset, not the search's
 * rigid move, takes the body onto it. */
typedef struct cub_bridge_route {
    int16_t from, to, via;
    int16_t a, in, out, b;
    int16_t reserved_;
} cub_bridge_route;

typedef struct cub_bridge_table {
    cub_bridge_table_desc desc; /* fuzzy filled with defaults, normalised */
    cub_bridge_clip *clips;     /* [clip_count] */
    cub_fuzzy_frame *fuzzy;     /* [frame_total] features of every frame */
    int16_t *bridges;           /* [bridge_total] ascending per clip */
    cub_bridge_pair *pairs;     /* [from * clip_count + to] */
    cub_bridge_link *links;     /* [link_total] */
    cub_vec3 *bridge_body_mm;   /* [bridge_total * joints] each bridge frame's
                                   joint positions, root x and z taken off */
    int clips_added, frames_used, bridges_used, links_used;
    int finished;
    int tween_clip; /* the seed's tween (cub_bridge_table_set_tween), -1: none */
    int tween_pass; /* its loop's length in frames (the clip holds two passes) */
    const cub_bridge_route *routes; /* [route_count] caller memory, see set_routes */
    int route_count;
} cub_bridge_table;

/* Bytes the table needs; 0 if the desc is impossible (counts < 0, no clip). */
size_t cub_bridge_table_mem_size(const cub_bridge_table_desc *desc);
/* CUB_ERR_ARG (NULL, bad counts, bad body), CUB_ERR_NOMEM (mem too small). */
cub_err cub_bridge_table_init(cub_bridge_table *t, const cub_bridge_table_desc *desc, void *mem,
                              size_t mem_size);
/* Add the next clip, in library order. bridge_frames ascending, in range.
 * fuzzy: the clip's per-frame features, or NULL to compute them here by
 * forward kinematics (cub_fuzzy_features on world positions). The table
 * keeps a copy of the cub_clip struct; its frame data must outlive it.
 * CUB_ERR_ARG (bad frames, other skeleton), CUB_ERR_FULL (too many). */
cub_err cub_bridge_table_add_clip(cub_bridge_table *t, const cub_clip *clip,
                                  const int *bridge_frames, int bridge_count,
                                  const cub_fuzzy_frame *fuzzy);
/* The links of one ordered pair, once per pair, after both clips were
 * added. Every a must be a bridge frame of `from`, every b one of `to`.
 * CUB_ERR_ARG (bad link), CUB_ERR_FULL (link_total exceeded). */
cub_err cub_bridge_table_set_links(cub_bridge_table *t, int from, int to,
                                   const cub_bridge_link *links, int count);
/* Is frame f of clip c one of its bridge frames? (0 for a bad c or f.) */
int cub_bridge_is_bridge(const cub_bridge_table *t, int c, int f);
/* Clip c (already added, every frame a bridge frame) is the seed's tween
 * (see "the tween clip" below), its loop unrolled: two passes of
 * pass_frames each, so a route enters it in the first pass and leaves it
 * within one pass without wrapping. Routes through it are planned with
 * cub_bridge_query.via_tween; chains through other clips never pass it.
 * CUB_ERR_ARG (bad c, not two passes, a frame that is not a bridge frame,
 * set twice). */
cub_err cub_bridge_table_set_tween(cub_bridge_table *t, int c, int pass_frames);
/* The searched routes the planner takes (cub_bridge_route), at most one
 * per ordered pair; the array stays in the caller's memory. Every clip and
 * frame in range, in < out, from != to. CUB_ERR_ARG (a bad route, a pair
 * twice, set twice, unfinished table). */
cub_err cub_bridge_table_set_routes(cub_bridge_table *t, const cub_bridge_route *routes,
                                    int count);
/* All clips added? Pairs never set have no links. CUB_ERR_RANGE if not. */
cub_err cub_bridge_table_finish(cub_bridge_table *t);

/* ---- the planner ------------------------------------------------------- */

typedef enum cub_bridge_via {
    CUB_BRIDGE_DIRECT = 0, /* one switch, into the wanted clip */
    CUB_BRIDGE_TWEEN = 1,  /* a step of a chain through other clips */
    CUB_BRIDGE_ROUTE = 2,  /* a step of a searched route (cub_bridge_route) */
} cub_bridge_via;

/* One switch: play `from_clip` until its unwrapped position at_q16 (a
 * whole frame; from_frame = that frame modulo the clip), then continue
 * `to_clip` at to_frame. */
typedef struct cub_bridge_step {
    int from_clip, from_frame;
    int to_clip, to_frame;
    cub_q16 d;
    cub_bridge_via via;
    int64_t at_q16;
} cub_bridge_step;

typedef struct cub_bridge_plan {
    int step_count;
    cub_bridge_step step[CUB_BRIDGE_MAX_STEPS];
    int wait_frames;  /* frames of the current clip still played before step 0 */
    int total_frames; /* frames until the wanted clip starts (via a tween: longer) */
    int window_frames; /* the look-ahead window the plan was found in */
} cub_bridge_plan;

typedef struct cub_bridge_query {
    int from_clip;
    int64_t pos_q16; /* where from_clip is now (unwrapped, >= 0) */
    int from_loops;  /* from_clip wraps around (look-ahead wraps too) */
    int to_clip;     /* the same clip: a jump of at least a quarter of it */
    int window_frames; /* first look-ahead window; 0 = CUB_BRIDGE_WINDOW_FRAMES */
    cub_q16 wait_cost_mm; /* what a frame of waiting costs against body distance
                             (mm); 0 = CUB_BRIDGE_WAIT_COST_MM: the soonest frame */
    int start_frames;  /* > 0: first try to enter the wanted clip at one of its
                          first start_frames frames (tagged or not, by d), the
                          soonest within the first window: a move then begins
                          at its beginning and keeps its music time. 0 = off */
    int reach_frames;  /* > 0: when no plan within the threshold enters the
                          wanted clip within reach_frames, enter it anyway at
                          the closest (by d) of its first start_frames frames
                          (or all) from one of the next reach_frames frames:
                          a reaction that must not wait (the blend covers the
                          distance). 0 = off */
    int strict;        /* 1: the seed's rule, both ends of every switch are
                          bridge frames (leave the current clip only at one
                          of its own, enter only at one of the wanted
                          clip's, start and reach entries included). 0:
                          leave at any upcoming frame (the default) */
    int via_tween;     /* 1: when no direct switch is found, route through the
                          table's tween clip (enter it at its frame closest
                          to an upcoming one, play it on, leave it for the
                          wanted clip: two steps). 0: chains of tagged links
                          through other clips (the default) */
    int no_routes;     /* 1: ignore the table's searched routes (for measuring).
                          0: when the table has a route for this pair and the
                          current clip reaches its frame a within the first
                          window (200 ms), take it before any search */
    int direct_only;   /* 1: one direct switch, never a chain or tween through
                          other clips' frames: within the threshold into one
                          of the start frames when that comes within
                          reach_frames, else the reach (needs reach_frames >
                          0). For a clip no chain belongs to (a groove): two
                          frames of an unrelated move on the way in read as a
                          twitch, a blend does not. 0: the searches above */
    int on_clock;      /* 1 (with direct_only): the wanted clip runs on a clock
                          (a groove on the music's): a switch after waiting
                          until upcoming frame k enters it at the frame its
                          clock reaches then, clock_q16 + (that frame - pos),
                          rounded; the soonest k within the threshold, else
                          the smallest d. start_frames is not used. 0: off */
    int64_t clock_q16; /* on_clock: the wanted clip's frame on its clock now
                          (Q16.16 frames; before its start: entered at 0) */
} cub_bridge_query;

/* Scratch memory the planner needs for this table (the tween search). */
size_t cub_bridge_plan_work_size(const cub_bridge_table *t);
/* Plan the switch. CUB_ERR_ARG (bad query, unfinished table), CUB_ERR_NOMEM
 * (work too small), CUB_ERR_RANGE: the wanted clip cannot be reached from
 * here by any chain of links (out->step_count is 0). */
cub_err cub_bridge_plan_switch(const cub_bridge_table *t, const cub_bridge_query *q,
                               cub_bridge_plan *out, void *work, size_t work_size);

/* ---- the tween clip ---------------------------------------------------- */

/* The seed's tween (SEEDS.md § 000, "Switching"): one looping clip made of
 * the library's bridge frames, so that it can join any two clips. Built
 * from a finished table without a tween:
 *   keys   the bridge frames, in table order, each kept unless a kept one
 *          is within cover_d of it (fuzzy d): every bridge frame is then
 *          within cover_d of a key;
 *   order  a closed tour of the keys, shortest in frames (nearest neighbour,
 *          then 2-opt; cost = the in-between frames of each leg);
 *   legs   from each key to the next, every joint's local rotation by slerp
 *          and the root's height by lerp, eased (smoothstep: the body
 *          settles on each key), over as many frames as keep the fastest
 *          joint within speed_mm per frame (bound: each ancestor's turn
 *          times the bone chain below it). The root stands at x = z = 0.
 * The last frame leads into the first: played as a loop it never stops.
 * Fixed point, deterministic; the same table gives the same clip on every
 * CPU. */
#define CUB_BRIDGE_TWEEN_MAX_KEYS 256
#define CUB_BRIDGE_TWEEN_SPEED_MM CUB_Q16_INT(30) /* 3 cm/frame: the library's median is 2.2 */
#define CUB_BRIDGE_TWEEN_MAX_LEG 120              /* frames between two keys at most */

typedef struct cub_bridge_tween_config {
    cub_q16 cover_d;  /* 0 = half the table's threshold (a frame within that
                         of a bridge frame is within the threshold of a key) */
    cub_q16 speed_mm; /* 0 = CUB_BRIDGE_TWEEN_SPEED_MM */
} cub_bridge_tween_config;

typedef struct cub_bridge_tween {
    int key_count;
    int frame_count; /* one pass of the loop */
    int16_t key_clip[CUB_BRIDGE_TWEEN_MAX_KEYS];  /* the bridge frames passed, in play order */
    int16_t key_frame[CUB_BRIDGE_TWEEN_MAX_KEYS];
    int16_t key_at[CUB_BRIDGE_TWEEN_MAX_KEYS];    /* the tween frame that shows it exactly */
} cub_bridge_tween;

/* Scratch memory cub_bridge_tween_plan needs for this table. */
size_t cub_bridge_tween_work_size(const cub_bridge_table *t);
/* Choose the keys, their order and each leg's length. CUB_ERR_ARG
 * (unfinished table, or one with a tween), CUB_ERR_NOMEM, CUB_ERR_RANGE (no
 * bridge frame), CUB_ERR_FULL (more keys than CUB_BRIDGE_TWEEN_MAX_KEYS). */
cub_err cub_bridge_tween_plan(const cub_bridge_table *t, const cub_bridge_tween_config *cfg,
                              cub_bridge_tween *out, void *work, size_t work_size);
/* Write the tween's frames into clip (on the table's skeleton, laid out by
 * cub_motion_clip_init): frame i is the tween's frame i modulo its
 * frame_count, so a clip of two passes holds the loop unrolled. */
cub_err cub_bridge_tween_fill(const cub_bridge_table *t, const cub_bridge_tween *tw,
                              cub_clip *clip);

/* ---- the player -------------------------------------------------------- */

typedef enum cub_bridge_smooth {
    CUB_BRIDGE_SMOOTH_INERTIAL = 0, /* decaying offset (the default, see above) */
    CUB_BRIDGE_SMOOTH_NONE,         /* a naive cut (for measuring) */
    CUB_BRIDGE_SMOOTH_CROSSFADE,    /* nlerp old -> new clip (for measuring) */
} cub_bridge_smooth;

/* The player's leg phase (firmware/bridge/bridge_legs.c; docs/join.md): at
 * an inertial cut where a foot stands (on the shown side, or in the new
 * clip within its first blend_frames frames), a foot that stands on the
 * shown side - low on the screen, within 30 mm of the clip's floor - is
 * held where it stands by a two-bone leg IK while the offset fades, and
 * the legs go over to where the new clip puts them one at a time (the free
 * one first) while the other stays planted; a foot with more than 20 mm to
 * go steps (is lifted). Standing in the new clip is app/join's contact
 * rule (within 30 mm of the clip's floor, slower than 180 mm/s, in runs of
 * at least 3 frames), marked for every frame at init. Each leg gets as
 * many frames as keep its step within blend_speed_mm a frame, at least
 * blend_frames. A looping clip whose last frame runs into its first (both
 * ankles within 20 mm) wraps without a cut for the feet; any other wrap's
 * phase ends blend_frames before the next pass. */
#define CUB_BRIDGE_FOOT_JOINTS 4

typedef struct cub_bridge_legs {
    int ok;                         /* legs found (the fuzzy body's hip, knee, ankle) */
    int enabled;                    /* the leg phase runs (inertial, not no_legs) */
    int16_t hip[2], knee[2], ankle[2];
    int16_t foot[2][CUB_BRIDGE_FOOT_JOINTS]; /* the ankle and what hangs below, -1 ends */
    const uint8_t *contact;         /* [frame_total] bit s: foot s stands; bit 2 of a clip's
                                     * first frame: its loop is seamless (player memory) */
    const cub_q16 *floor_mm;        /* [clip_count] each clip's floor: its lowest foot point */
    cub_q16 speed_mm;               /* a step moves at most this a frame (the blend's) */
    int min_frames;                 /* each leg gets at least this (the shortest blend) */
    /* this blend */
    int on;                         /* a foot is held: the leg phase runs */
    int first, len;                 /* the leg that goes first; frames each leg gets */
    int64_t from_q16;               /* the position (the clip's unwrapped time) it began at */
    uint8_t planted;                /* bit s: foot s stands on both sides of the cut */
    cub_vec3 hold_mm[2];            /* where a planted ankle stood at the cut */
    cub_quat hold_rot[2];           /* and its world rotation */
    /* scratch */
    cub_pose raw;
    cub_vec3 world[2][CUB_MOTION_MAX_JOINTS];
    cub_quat wrot[2][CUB_MOTION_MAX_JOINTS];
} cub_bridge_legs;

typedef struct cub_bridge_player_desc {
    const cub_bridge_table *table; /* finished */
    cub_bridge_smooth smooth;
    int blend_frames;  /* shortest blend; 0 = CUB_BRIDGE_BLEND_FRAMES; <= MAX_BLEND_FRAMES */
    cub_q16 blend_speed_mm; /* most joint speed the fading offset may add, mm per
                               frame; 0 = CUB_BRIDGE_BLEND_SPEED_MM. Sets each
                               blend's length from the distance it must cover */
    int window_frames; /* 0 = CUB_BRIDGE_WINDOW_FRAMES */
    cub_q16 wait_cost_mm; /* the planner's, see cub_bridge_query; 0 = default */
    int start_frames;     /* the planner's, see cub_bridge_query; 0 = off */
    int reach_frames;     /* the planner's, see cub_bridge_query; 0 = off */
    int strict;           /* the planner's, see cub_bridge_query; 0 = off */
    int via_tween;        /* the planner's, see cub_bridge_query; 0 = off */
    int no_legs;          /* 1: no leg phase (for measuring); 0: inertial cuts hold
                             planted feet (cub_bridge_legs) */
    int no_routes;        /* the planner's, see cub_bridge_query; 0 = take routes */
    int direct_only;      /* the planner's, see cub_bridge_query; 0 = off */
    int on_clock;         /* the planner's, see cub_bridge_query; 0 = off */
    int64_t clock_q16;
} cub_bridge_player_desc;

typedef enum cub_bridge_event_type {
    CUB_BRIDGE_EV_SWITCH = 1, /* step: a switch happened */
    CUB_BRIDGE_EV_DONE = 2,   /* clip reached its end (looping: one more pass) */
} cub_bridge_event_type;

typedef struct cub_bridge_event {
    int type;
    int64_t t_us;          /* when, from the start of the advance call */
    cub_bridge_step step;  /* SWITCH */
    int clip;              /* DONE: the clip; SWITCH: the clip now playing */
    int looped;            /* DONE: the clip loops and goes on */
} cub_bridge_event;

typedef struct cub_bridge_player {
    cub_bridge_player_desc desc;
    void *work;
    size_t work_size;
    int clip, loop;
    int64_t pos_q16;  /* unwrapped position in clip */
    cub_q16 speed_q16;
    uint64_t rem;     /* sub-Q16 time remainder (exact, no drift) */
    int done_sent;
    /* the pending plan */
    cub_bridge_plan plan;
    int next_step;
    cub_q16 want_speed_q16;
    int want_loop;
    /* smoothing: inertialization offset, or the crossfade's old clip */
    int blending;
    int64_t blend_from_q16; /* where the blend began in the current clip */
    int blend_len, root_len; /* frames: the joints', the root's drift's */
    cub_vec3 body[2][CUB_MOTION_MAX_JOINTS];
    cub_quat off_rot[CUB_MOTION_MAX_JOINTS];
    cub_vec3 off_root_mm;
    /* ... and the velocity it carries over (the old motion's, less the
     * new's), per frame of the new clip: an axis (any length) and an angle
     * per joint, the root's in mm, faded over vel_len frames */
    cub_vec3 vel_axis[CUB_MOTION_MAX_JOINTS];
    cub_q16 vel_angle[CUB_MOTION_MAX_JOINTS];
    cub_vec3 vel_root_mm;
    int vel_len;
    int old_clip, old_loop;
    int64_t old_pos_q16;
    cub_q16 old_speed_q16;
    cub_pose scratch[5];
    cub_bridge_legs legs;
} cub_bridge_player;

/* Bytes of memory the player needs (the planner's work, the feet's contacts). */
size_t cub_bridge_player_mem_size(const cub_bridge_player_desc *desc);
/* CUB_ERR_ARG (no table, unfinished, bad blend), CUB_ERR_NOMEM. */
cub_err cub_bridge_player_init(cub_bridge_player *p, const cub_bridge_player_desc *desc,
                               void *mem, size_t mem_size);
/* Start playing a clip at a frame, at once and without smoothing (boot,
 * or after STOP). CUB_ERR_ARG for a bad clip, frame or speed. speed_q16 0
 * = 1.0; otherwise within [SPEED_MIN, SPEED_MAX]. */
cub_err cub_bridge_player_start(cub_bridge_player *p, int clip, int frame, cub_q16 speed_q16,
                                int loop);
/* Ask for another clip: plans the switch (replacing any pending plan) and
 * copies the plan to out (may be NULL). The clip plays at speed_q16 (0 =
 * 1.0) once entered; tween clips play at that speed too. CUB_ERR_ARG (bad
 * clip or speed), CUB_ERR_RANGE (no way there; playback goes on as it was). */
cub_err cub_bridge_player_request(cub_bridge_player *p, int clip, cub_q16 speed_q16, int loop,
                                  cub_bridge_plan *out);
/* Plan without carrying anything out (how soon could the player be in
 * that clip?): q as for cub_bridge_plan_switch, in the player's scratch
 * memory; q->from_clip < 0 means from where the player is now, and zero
 * window/wait cost take the player's. Errors as cub_bridge_plan_switch. */
cub_err cub_bridge_player_preview(cub_bridge_player *p, const cub_bridge_query *q,
                                  cub_bridge_plan *out);
/* Change the speed of what plays now (music sync). CUB_ERR_ARG if out of bounds. */
cub_err cub_bridge_player_set_speed(cub_bridge_player *p, cub_q16 speed_q16);
/* How later requests enter their clip (cub_bridge_query.start_frames): the
 * app asks for a move's beginning when it starts a move, and for the
 * quickest entry when it must react (a correction). CUB_ERR_ARG if < 0. */
cub_err cub_bridge_player_set_start_frames(cub_bridge_player *p, int start_frames);
/* How soon later requests must enter their clip (cub_bridge_query.
 * reach_frames; 0 = when the threshold allows). CUB_ERR_ARG if < 0. */
cub_err cub_bridge_player_set_reach_frames(cub_bridge_player *p, int reach_frames);
/* Whether later requests may take the table's searched routes
 * (cub_bridge_query.no_routes): the director allows them only where the
 * music has time for the route's frames. CUB_ERR_ARG unless 0 or 1. */
cub_err cub_bridge_player_set_no_routes(cub_bridge_player *p, int no_routes);
/* Whether later requests take one direct switch only (cub_bridge_query.
 * direct_only). CUB_ERR_ARG unless 0 or 1. */
cub_err cub_bridge_player_set_direct_only(cub_bridge_player *p, int direct_only);
/* Whether later requests enter their clip on a clock, and where that clock
 * stands now (cub_bridge_query.on_clock, clock_q16). CUB_ERR_ARG unless
 * on_clock is 0 or 1 and clock_q16 is within 2^46. */
cub_err cub_bridge_player_set_clock(cub_bridge_player *p, int on_clock, int64_t clock_q16);
/* Move time on by dt_us (>= 0): switch exactly at the planned frames,
 * report events into ev[max_ev] (count in *n_ev; events past max_ev are
 * dropped, the playback is not). */
cub_err cub_bridge_player_advance(cub_bridge_player *p, int64_t dt_us, cub_bridge_event *ev,
                                  int max_ev, int *n_ev);
/* The pose to show now, with the cut smoothed. */
cub_err cub_bridge_player_pose(cub_bridge_player *p, cub_pose *out);
/* The pose the current clip alone gives now (no smoothing). */
cub_err cub_bridge_player_raw_pose(const cub_bridge_player *p, cub_pose *out);
/* A switch is still planned (a request not yet carried out). */
int cub_bridge_player_pending(const cub_bridge_player *p);

#endif

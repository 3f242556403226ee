/* The tracker's private state and the stages it runs (tracker.c explains
 * the method). Everything works on a 160x120 grid of 4x4-pixel cells. */
#ifndef CUB_TRK_INTERNAL_H
#define CUB_TRK_INTERNAL_H

#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "cub/forest.h"
#include "cub/track.h"

#define TRK_CELL_PX 4
#define TRK_GW (CUB_KINECT_WIDTH / TRK_CELL_PX)
#define TRK_GH (CUB_KINECT_HEIGHT / TRK_CELL_PX)
#define TRK_CELLS (TRK_GW * TRK_GH)
#define TRK_BW (TRK_GW / 2) /* the coarse grid of 2x2 blocks */
#define TRK_BH (TRK_GH / 2)
#define TRK_BLOCKS (TRK_BW * TRK_BH)
#define TRK_MAX_EXTREMA 7
#define TRK_INF INT32_MAX
#define TRK_PATH_STEPS 800 /* the most cells walked along a path (a guard, paths are shorter) */
#define TRK_HEAP_CAP (TRK_CELLS * 4)
#define TRK_EDGE_PAD (TRK_GW + 1)
#define TRK_COARSE_PAD (TRK_BW + 1)
#define TRK_EDGE_NONE 0xFFFF
/* grid cell (gx, gy) lies on the grid */
static inline bool on_grid(int32_t gx, int32_t gy) { return gx >= 0 && gy >= 0 && gx < TRK_GW && gy < TRK_GH; }
/* who_prev: the player's cell, another person-like blob's standing apart
 * from the player, or one's beside it (not apart: maybe the player's own
 * cut-off part, so never split off; see trk_pick_player) */
enum { TRK_WHO_PLAYER = 1, TRK_WHO_OTHER = 2, TRK_WHO_NEAR = 3 };
#define TRK_PITCHES 21 /* floor search without gravity: -20..+20 degrees */
#define TRK_LOW_CELLS (TRK_CELLS / 4 + 1) /* the floor search's cells: the lower half's first, then every odd one */
#define TRK_CLOSE_MM 1000 /* the play range: the player's centre nearer is TOO_CLOSE, */
#define TRK_FAR_MM 3500   /* farther TOO_FAR */

/* A point in camera space, whole millimetres. */
typedef struct trk_p3 {
    int32_t x, y, z;
} trk_p3;

/* One connected blob of the grid. */
typedef struct trk_comp {
    int32_t n;
    int64_t sx, sy, sz, area_mm2;
    int32_t hmin, hmax, xmin, xmax;
    int32_t gx0, gx1, gy0, gy1; /* grid bounding box */
    int32_t border;             /* cells on the image's edge */
    int32_t interior;           /* cells whose 4 neighbours are all in the blob */
} trk_comp;

#define TRK_MAX_COMPS 256
#define TRK_PAST 4 /* frames of joints kept for the confidence's motion (100 ms at 30 fps) */

struct cub_tracker {
    int32_t min_mm, max_mm;
    /* per frame */
    int16_t z[TRK_CELLS]; /* mm, 0 = nothing there (or removed) */
    int32_t x[TRK_CELLS], y[TRK_CELLS];
    int16_t label[TRK_CELLS]; /* component, -1 none */
    uint8_t mask[TRK_CELLS];  /* 1 = the player's */
    uint8_t who_prev[TRK_CELLS]; /* last frame's: TRK_WHO_PLAYER, _OTHER, _NEAR or 0 */
    int16_t label_prev[TRK_CELLS]; /* last frame's blob of a person-like blob's cell, else -1 */
    int16_t z_prev[TRK_CELLS];   /* last frame's depth after the floor and background went (mm, 0 none) */
    /* the room's background (trk_bg.c): per cell the farthest depth that
     * stayed still (mm, 0 unknown), the depth being followed and how long
     * it has stayed, and how long since a person covered the cell (10 ms
     * units) */
    int16_t bg_mm[TRK_CELLS], bg_cand_mm[TRK_CELLS];
    uint16_t bg_age[TRK_CELLS], bg_person_age[TRK_CELLS];
    uint16_t bg_player_age[TRK_CELLS]; /* since the player covered the cell */
    int32_t bg_resets, bg_run_us; /* times forgotten; time learnt since */
    uint8_t room_known; /* 0 not yet, 1 known and the player not chosen afresh yet, 2 chosen */
    bool start_afresh;  /* cub_track_choose_afresh: the next frame chooses the player afresh */
    int32_t dist0[TRK_CELLS], parent0[TRK_CELLS];
    int32_t distx[TRK_CELLS];
    int32_t dist_sh[2][TRK_BLOCKS]; /* coarse, along the surface from each shoulder (left, right) */
    int32_t stack[TRK_CELLS];
    uint64_t heap[TRK_HEAP_CAP];
    /* the geodesics' edge lengths, once a frame (trk_geo.c): per cell, to
     * its right, lower, lower right and lower left neighbour; a row of
     * TRK_EDGE_NONE before the first so a cell reads its upper ones at
     * i - offset without a bounds check */
    uint16_t edge_w[4][TRK_EDGE_PAD + TRK_CELLS];
    uint16_t coarse_w[4][TRK_COARSE_PAD + TRK_BLOCKS]; /* the same on the coarse grid of 2x2 blocks */
    /* the floor search's cells (trk_grid.c): the lower image's readings, in
     * mm (|x|, |y| < 4500, z < 8192: 16 bits), gathered once a frame for
     * the 21 pitches */
    int16_t low_x[TRK_LOW_CELLS], low_y[TRK_LOW_CELLS], low_z[TRK_LOW_CELLS];
    trk_comp comps[TRK_MAX_COMPS];
    int32_t ncomps;
    /* the ground: unit up vector (Q16.16) and the floor's height along it */
    cub_vec3 pitch_up[TRK_PITCHES];
    cub_vec3 up;
    int32_t floor_h_mm;
    bool have_floor;
    int32_t frame_no;
    /* the player across frames */
    bool tracked;
    int32_t player_id, next_id, lost_frames;
    bool in_play; /* the player has come nearer than TRK_FAR_MM */
    trk_p3 centre, vel; /* where the player was last seen (mm) and its velocity (mm/s) */
    int64_t seen_us;    /* when */
    int32_t seen_gx0, seen_gx1; /* and its blob's columns on the grid */
    int32_t top_mm; /* the player's highest point of late (mm along up): merged_with_taller */
    /* the other person nearest the player (trk_grid.c, other_motion): its
     * centre (mm), velocity along the floor (mm/s), measured only while it
     * is a blob of its own, and its blob last frame (-1 none) */
    trk_p3 other_c, other_vel;
    int32_t other_edge; /* its blob's side away from the player (x, mm) */
    int16_t other_label;
    int8_t other_side; /* which side that is: -1 left (xmin), 1 right (xmax) */
    bool parted, parted_before; /* this frame (last frame) split a blob between the player and someone else */
    int32_t stature_mm;
    int32_t neck_drop_mm; /* head top to the neck base (smoothed), 0 unknown */
    int32_t head_cell, stature_seen_mm; /* this frame's, for tools */
    /* root joint to end joint when stretched (shoulder-wrist, hip-ankle;
     * left arm, right arm, left leg, right leg), 0 unknown: learnt per
     * player, as bodies differ from the proportions */
    int32_t reach_mm[4];
    int32_t shoulder_half_mm; /* the shoulder joints' half width, learnt per player, 0 unknown */
    int64_t side_on_us;       /* when the player (side_on_id) was last seen side-on (trk_conf.c) */
    /* the last frames' joints, to measure motion over 100 ms whatever the
     * frame rate (trk_conf.c) */
    struct {
        trk_p3 j[CUB_KJ_COUNT];
        int64_t t_us;
        int32_t id;
        bool used;
    } past[TRK_PAST];
    int32_t past_next;
    int32_t side_on_id;
    bool side_on_seen;
    cub_track_skeleton prev;
    bool have_prev;
    int64_t prev_t_us; /* last frame's time, and the time since it as the */
    int32_t dt_us;     /* smoothing takes it (10-200 ms, 33 ms unknown) */
    /* the forest's seam (trk_forest.c), in the memory after this struct;
     * forest NULL: the heuristic tracker alone */
    const cub_forest *forest;
    uint16_t *forest_mm;
    cub_forest_points forest_pts;
};

/* Dot product of a mm point with a Q16.16 unit vector: mm. */
static inline int32_t trk_along(int32_t x, int32_t y, int32_t z, cub_vec3 u)
{
    return (int32_t)(((int64_t)x * u.x + (int64_t)y * u.y + (int64_t)z * u.z) >> 16);
}

static inline int32_t trk_abs(int32_t a) { return a < 0 ? -a : a; }

/* Exact Euclidean length in mm. */
int32_t trk_len(int32_t dx, int32_t dy, int32_t dz);

/* trk_bg.c: the room's background. Learn from this frame's grid (before
 * the floor goes; dt_us the time since the last frame, 0 learns nothing),
 * forget it all, remove the cells at their background's depth, and the
 * margin by which a cell must stand before its background. */
void trk_bg_learn(cub_tracker *t, int32_t dt_us);
void trk_bg_reset(cub_tracker *t);
void trk_bg_remove(cub_tracker *t);
int32_t trk_bg_margin(int32_t z);
/* The room's background is known (most cells have one) and the player
 * has not been chosen afresh since (trk_pick_player sets room_known 2). */
bool trk_bg_room_new(const cub_tracker *t);
/* This frame's people keep their cells out of the background a while:
 * the player's cells (mask), and person-like blobs that move (person[k]). */
void trk_bg_mark_people(cub_tracker *t, const bool *person);

/* trk_grid.c */
void trk_grid_fill(cub_tracker *t, const uint16_t *raw);
void trk_floor_update(cub_tracker *t, const cub_vec3 *gravity_mm);
void trk_floor_remove(cub_tracker *t);
void trk_components(cub_tracker *t);
/* Index of the player's component (and merges limbs in front into mask), -1 none. */
int32_t trk_pick_player(cub_tracker *t);
/* The player's blob pid's pieces a depth step behind it that join
 * another person-like blob with a smaller step become that person's
 * (trk_grid.c says why). */
void trk_give_back_pieces(cub_tracker *t, int32_t pid);

/* trk_geo.c */
int32_t trk_root_cell(cub_tracker *t);
/* Plain surface lengths (no extra cost for depth jumps) from cell src on
 * the coarse grid of 2x2 blocks into dist_b (TRK_BLOCKS), a quarter of the
 * work: for rough decisions (how far a hand is from a shoulder). Over the
 * coarse edges trk_coarse_edges filled from the player's mask. */
void trk_coarse_edges(cub_tracker *t);
void trk_geodesic_coarse(cub_tracker *t, int32_t *dist_b, int32_t src);
/* A cell's distance from such a map, TRK_INF when unreached. */
int32_t trk_coarse_at(const cub_tracker *t, const int32_t *dist_b, int32_t cell);
int32_t trk_extrema(cub_tracker *t, int32_t root, int32_t min_mm, int32_t *out, int32_t max_out);

/* trk_head.c: picks the head among the extremities (or adds the column's
 * top to ext, so *next may grow), updates stature_mm and neck_drop_mm;
 * the head's index in ext, -1 none. */
int32_t trk_fit_head(cub_tracker *t, int32_t root, int32_t *ext, int32_t *next, bool *on_floor);

/* trk_fit.c */
void trk_fit_skeleton(cub_tracker *t, int32_t root, int32_t *ext, int32_t next,
                      cub_track_skeleton *out);
void trk_smooth(cub_tracker *t, cub_track_skeleton *out);

/* trk_forest.c: the bytes the forest's seam needs after the tracker (0
 * without a forest), set it up there, and override the output's joints
 * the forest is confident of (raw: this frame). */
size_t trk_forest_mem(const cub_forest *f);
void trk_forest_setup(cub_tracker *t, const cub_forest *f, uint8_t *mem);
void trk_forest_override(cub_tracker *t, const uint16_t *raw, cub_track_skeleton *out);

/* trk_conf.c */
void trk_confidence(cub_tracker *t, int64_t t_us, cub_track_skeleton *s);

#endif

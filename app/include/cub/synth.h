/* synth — a synthetic Kinect v1: a child-sized body driven by mocap clips,
 * rendered to raw 11-bit depth, with the true joints per frame.
 *
 * Camera: exactly the conventions of cub/kinect.h (640x480, focal 580 px,
 * centre 320,240; x right in the image, y up, z away; mm). The camera sits
 * camera_height_mm above a floor, level or pitched by tilt_deg (positive
 * = looking up, as the Kinect's motor). The player stands distance_mm in
 * front of it, facing it; a player's left hand shows on the image's left
 * (the Kinect's images are mirrored; camera space is right-handed).
 *
 * Kinect effects: depth -> raw by the inverse of
 * mm = 123.6 * tan(raw / 2842.5 + 1.1863), rounded (so the step grows with
 * distance); the IR projector 75 mm to the camera's +x: surface the
 * projector cannot see gives no reading (2047) - a band on the -x side of
 * near edges; jitter and dropout at depth edges; small holes; 2047 outside
 * 500..4000 mm. Noise is deterministic for a given seed on one machine.
 *
 * Host-side tool code: floats, libm and the heap are fine here.
 */
#ifndef CUB_SYNTH_H
#define CUB_SYNTH_H

#include <stddef.h>
#include <stdint.h>

#include "cub/err.h"
#include "cub/forest.h"
#include "cub/io.h"
#include "cub/track.h"

#define CUB_SYNTH_PROJECTOR_X_MM 75.0f
#define CUB_SYNTH_MIN_MM 500.0f
#define CUB_SYNTH_MAX_MM 4000.0f

typedef enum cub_synth_build {
    CUB_SYNTH_AVERAGE = 0,
    CUB_SYNTH_SLIM,
    CUB_SYNTH_STURDY,
} cub_synth_build;

/* One piece of a performance: clip seconds [from_s, to_s) (to_s <= 0:
 * to the clip's end), mirrored (left <-> right: "the wrong arm") or not.
 * clip: a path (.bvh, or .amc with its subject's .asf beside it) or a short
 * name looked up under data_dir/mocap (e.g. "13_29", "jumping_jacks"). */
typedef struct cub_synth_segment {
    char clip[256];
    double from_s, to_s;
    int mirror;
} cub_synth_segment;

/* Where the second person is (cub_synth_desc.second_mode). */
typedef enum cub_synth_second_mode {
    CUB_SYNTH_SECOND_BEHIND = 0, /* stands at second_x, second_dz the whole time */
    CUB_SYNTH_SECOND_WALK_IN,    /* walks in from the right (second_speed, from 1 s) to that spot */
    CUB_SYNTH_SECOND_CROSS,      /* crosses in front of the child, right to left, mid-way */
    CUB_SYNTH_SECOND_SIBLING,    /* a child of similar height beside the child where it starts */
} cub_synth_second_mode;

/* Zero-initialised fields take the defaults in brackets. */
typedef struct cub_synth_jtrack cub_synth_jtrack;

typedef struct cub_synth_desc {
    const struct cub_synth_jtrack *track; /* the performance as a joint track (then no
                                      * segments; it is not copied: keep it open) */
    const char *data_dir;            /* for short clip names [$CUB_DATA_DIR or none] */
    float height_mm;                 /* the child's height [1150] */
    int build;                       /* cub_synth_build [AVERAGE] */
    int loose_clothes;               /* 1: wider torso and thighs, a skirt hem;
                                      * 2: also a loose shirt and sleeves, baggy legs */
    float distance_mm;               /* player's ground position from the camera [2200] */
    float camera_height_mm;          /* [800] */
    float tilt_deg;                  /* camera pitch, + = up [0] */
    float fps;                       /* [30] */
    float blend_s;                   /* between segments [0.3] */
    uint64_t seed;                   /* noise seed [0 is a seed like any other] */
    int clean;                       /* 1: quantisation only (no shadow, noise, holes) */
    int room;                        /* 1: back wall, sofa, table, plant */
    /* Facing: the body's yaw about its own vertical axis, + = turned towards
     * its left (anticlockwise seen from above), 0 = facing the camera. */
    float yaw_deg;                   /* turns the whole performance about its centre [0] */
    float spin_deg_s;                /* and keeps turning about the hips [0] */
    float yaw_segment_s;             /* > 0: every this many seconds a new yaw drawn in
                                      * [-180, 180) from the seed, turned to in 0.5 s */
    float start_yaw_max_deg;         /* > 0: the first segment's yaw drawn in [-this,
                                      * this) instead (a child who pressed START
                                      * looking at the TV); the later yaws are the
                                      * same draws as without it [0: off] */
    /* Travel: the clip's own root travel about its mean position is kept
     * (a walk walks); max_travel_mm > 0 clamps it softly (tanh) to +-that
     * on each floor axis, pin = 1 holds the hips over one spot. */
    float max_travel_mm;             /* [0: not clamped] */
    int pin;
    const char *second_clip;         /* another person (NULL: none) */
    int second_mode;                 /* cub_synth_second_mode [BEHIND] */
    float second_height_mm;          /* [1650; SIBLING: the child's height + 8 %] */
    /* beside / behind the player's spot [700, 900; CROSS: 0, -700 (in
     * front); SIBLING: from where the child starts, 650 mm to the side away
     * from the image's centre, 100]; WALK_IN walks to this spot */
    float second_x_mm, second_dz_mm;
    float second_speed_mm_s;         /* WALK_IN and CROSS walk this fast [1000] */
    /* The room before the child: this many seconds of frames first with
     * the child not there (the furniture, and the second person as its
     * mode has it: standing, or yet to walk in or cross), as the box sees
     * the room in attract mode before START; then the child is at its start
     * spot and the performance begins. The performance's clock (turning,
     * walk-in, crossing) starts after it; the second person's own clip
     * plays through it. The truths have no line for its frames. [0] */
    float prelude_s;
} cub_synth_desc;

typedef struct cub_synth cub_synth;

/* The true skeleton of one frame (the player only). */
typedef struct cub_synth_truth_frame {
    int frame;
    double t_s;                      /* the time in the dump's file name */
    uint32_t ts;                     /* the timestamp in the dump's file name */
    float joint_mm[CUB_KJ_COUNT][3]; /* camera space */
    uint8_t visible[CUB_KJ_COUNT];   /* 1: the joint's spot is seen by the camera */
} cub_synth_truth_frame;

/* Load the clips and build the scene. segments may be empty (n = 0: an
 * empty room, for tests). Errors name the clip (and the missing joint). */
cub_err cub_synth_open(const cub_synth_desc *desc, const cub_synth_segment *segs, int n,
                       cub_synth **out, cub_diag *diag);
void cub_synth_close(cub_synth *s);
/* Frames the performance lasts at desc->fps (segments back to back). */
int cub_synth_frame_count(const cub_synth *s);
/* Of those, the prelude's (desc.prelude_s): the first frames, the child not
 * in them; cub_synth_write_dump writes no truth for them. */
int cub_synth_prelude_frames(const cub_synth *s);
/* Gravity (down) in camera space, length 1000. */
void cub_synth_gravity(const cub_synth *s, float g[3]);
/* Render frame i: raw[640*480] (2047 = no reading). Optional outputs
 * (NULL to skip): the truth; the clean depth in mm before any Kinect
 * effect (0 = nothing); the owner of each pixel (0 none, 1 player,
 * 2 second person, 3 room or floor). */
cub_err cub_synth_render(cub_synth *s, int frame, uint16_t *raw, cub_synth_truth_frame *truth,
                         float *depth_mm, uint8_t *owner);

/* 1 when the scene has a second person. Its true skeleton in the frame
 * last rendered (visibility against its own pixels), for telling the
 * player from the other person. */
int cub_synth_has_second(const cub_synth *s);
cub_err cub_synth_second_truth(const cub_synth *s, cub_synth_truth_frame *truth);

/* Body parts painted per pixel: cub_synth_part, in cub/forest.h (the
 * firmware's forest names the same classes). */

/* The part of every pixel in the frame last rendered (w*h bytes), on
 * either person; tell them apart by cub_synth_render's owner. */
cub_err cub_synth_parts(const cub_synth *s, uint8_t *part);
const char *cub_synth_part_name(int part);

/* The Kinect's mapping, both ways (raw 0..2046; out of range -> 2047). */
uint16_t cub_synth_mm_to_raw(double mm);
double cub_synth_raw_to_mm(uint16_t raw);

/* The fakenect file name of frame i ("d-1300000000.033333-3000000.pgm"),
 * its time and timestamp. */
void cub_synth_frame_name(int frame, float fps, char *buf, size_t size, double *t_s, uint32_t *ts);
/* Write frames [0, frames) (frames <= 0: all) as a fakenect dump in dir
 * (created if needed): INDEX.txt, d-*.pgm, truth.txt, and with a second
 * person truth_second.txt (its joints, same format); flags below. */
#define CUB_SYNTH_DUMP_VERBOSE 1 /* progress to stderr */
#define CUB_SYNTH_DUMP_PARTS 2   /* also p-<time>-<timestamp>.pgm beside each depth
                                  * frame: "P5 640 480 255", one cub_synth_part a byte */
cub_err cub_synth_write_dump(cub_synth *s, const char *dir, int frames, int flags,
                             cub_diag *diag);

/* ---- segments file: `clip from_s to_s [mirror]` per line, # comments --- */
cub_err cub_synth_sequence_parse(const char *text, size_t len, const char *name,
                                 cub_synth_segment **out, int *n, cub_diag *diag);

/* ---- joint tracks: a performance without its mocap ----------------------
 * The player's points per frame as the segments make them (blended, placed
 * on the floor facing the camera, before any turning or travel limit), so
 * that a scene can be rendered without the clips (scripts/demo.sh ships its
 * child this way). Text:
 *   cub-jtrack 1
 *   fps F
 *   unit_mm U        every coordinate is a whole number of U mm
 *   frames N
 * then N lines, one a frame, of the 21 points (the 20 joints of kinect.h,
 * then the top of the head) x y z in units: each the residual from the
 * constant-velocity guess 2 a[f-1] - a[f-2] (a[f-1] for frame 1, 0 for frame
 * 0), written as one character '@'..'~' for -31..31 ('_' = 0) or as "(N)".
 * '#' starts a comment. */
#define CUB_SYNTH_JTRACK_POINTS 21
struct cub_synth_jtrack {
    float fps, unit_mm;
    int frame_count;
    float *points_mm; /* frame_count x 21 x 3, heap; cub_synth_jtrack_free */
};
cub_err cub_synth_jtrack_parse(const char *text, size_t len, const char *name,
                               cub_synth_jtrack *out, cub_diag *diag);
cub_err cub_synth_jtrack_read(const char *path, cub_synth_jtrack *out, cub_diag *diag);
void cub_synth_jtrack_free(cub_synth_jtrack *t);
/* Write s's performance (all its frames at its fps) as a joint track in
 * units of unit_mm (0.001..100), comment (# lines, may be NULL) first. */
cub_err cub_synth_write_jtrack(const cub_synth *s, const char *path, float unit_mm,
                               const char *comment, cub_diag *diag);

/* ---- truth.txt ----------------------------------------------------------
 * Line 1: "# cub-synth truth v1: ..." (a description of the format).
 * Line 2: "gravity gx gy gz" (camera space, down, length 1000).
 * Then one line per frame: "frame t_s ts" then for each of the 20 joints
 * in kinect.h order "x y z v" (mm, camera space; v 1 visible, 0 not).
 * Other lines starting with '#' are comments. */
typedef struct cub_synth_truth {
    float gravity[3];
    int frame_count;
    cub_synth_truth_frame *frames; /* heap; cub_synth_truth_free */
} cub_synth_truth;

cub_err cub_synth_truth_read(const char *path, cub_synth_truth *out, cub_diag *diag);
cub_err cub_synth_truth_parse(const char *text, size_t len, const char *name, cub_synth_truth *out,
                              cub_diag *diag);
void cub_synth_truth_free(cub_synth_truth *t);

#endif

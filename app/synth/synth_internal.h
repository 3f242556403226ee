/* synth internals: the actor (a clip mapped to the 20 Kinect joints), the
 * body's primitives and the ray caster (vectors: cub_fv3 of cub/vec.h). */
#ifndef CUB_SYNTH_INTERNAL_H
#define CUB_SYNTH_INTERNAL_H

#include <math.h>
#include <stdint.h>

#include "cub/synth.h"
#include "cub/vec.h"

/* The 20 joints of kinect.h, then extra points the body needs. */
enum { SP_HEAD_TOP = CUB_KJ_COUNT, SP_COUNT };

/* ---- actor: one loaded clip (actor.c) ---------------------------------- */
typedef struct synth_actor synth_actor;

/* Load a clip by path or short name; height_mm scales it. */
cub_err synth_actor_load(const char *clip, const char *data_dir, float height_mm, synth_actor **out,
                         cub_diag *diag);
void synth_actor_free(synth_actor *a);
double synth_actor_duration_s(const synth_actor *a);
/* Points at t_s in the actor's frame: y up, scaled, left +x, facing +z
 * (not yet placed). */
void synth_actor_points(const synth_actor *a, double t_s, cub_fv3 out[SP_COUNT]);

/* ---- primitives and the ray caster (raycast.c) -------------------------- */
enum { PRIM_CAPSULE, PRIM_ELLIPSOID, PRIM_BOX, PRIM_CYLINDER, PRIM_FLOOR };
enum { OWNER_NONE = 0, OWNER_PLAYER = 1, OWNER_SECOND = 2, OWNER_ROOM = 3 };

typedef struct synth_prim {
    uint8_t kind, owner;
    uint8_t part;       /* cub_synth_part of a body's primitive; 0 for the room */
    cub_fv3 a, b;       /* capsule/cylinder ends; ellipsoid centre (a); box min/max */
    float r;        /* capsule/cylinder radius */
    cub_fv3 axis[3];    /* ellipsoid: unit axes */
    float radii[3]; /* ellipsoid: radius along each axis */
    cub_fv3 bs_c;       /* bounding sphere (culling) */
    float bs_r;     /* < 0: covers the whole image */
} synth_prim;

typedef struct synth_camera {
    cub_fv3 origin, x, y, z; /* world position and unit axes */
} synth_camera;

/* Nearest hit of every pixel's ray with the primitives: depth_mm (camera
 * z, 0 = nothing) and owner (may be NULL). clear = 0 keeps what the
 * buffers hold (the static room) and draws over it. */
void synth_raycast(const synth_camera *cam, const synth_prim *prims, int n, float *depth_mm,
                   uint8_t *owner, int clear);
/* The same over what the buffers hold, also writing each hit's part. */
void synth_raycast_parts(const synth_camera *cam, const synth_prim *prims, int n, float *depth_mm,
                         uint8_t *owner, uint8_t *part);
void synth_prim_bound(synth_prim *p);

/* ---- body (body.c) ---------------------------------------------------- */
typedef struct synth_body_shape {
    float height_mm;
    float build; /* radius factor: slim 0.82, average 1, sturdy 1.22 */
    int loose;
} synth_body_shape;

#define SYNTH_BODY_MAX_PRIMS 24
/* Primitives of a body posed by its points (world space); returns count. */
int synth_body_prims(const synth_body_shape *shape, const cub_fv3 pts[SP_COUNT], uint8_t owner,
                     synth_prim *out);
/* Radius of the body around joint j (for visibility margins). */
float synth_body_joint_radius(const synth_body_shape *shape, int j);
/* Neck plus head above the shoulder centre; the sole under the feet. */
float synth_body_above_shoulders_mm(const synth_body_shape *shape);
float synth_body_sole_mm(const synth_body_shape *shape);
/* The foot capsule's ends (its axis; the sole is its radius below). */
void synth_body_foot_ends(cub_fv3 ankle, cub_fv3 foot, cub_fv3 *heel, cub_fv3 *toe);
/* Wrist to the palm's centre (the hand joint). */
float synth_body_hand_mm(const synth_body_shape *shape);
/* Head centre and head top from the shoulder centre and the source's head
 * direction (child proportions, see body.c). */
void synth_body_head(const synth_body_shape *shape, cub_fv3 shoulder_centre, cub_fv3 head_dir_point,
                     cub_fv3 *centre, cub_fv3 *top);

/* The frame rate of a synth (synth.c). */
float synth_fps(const cub_synth *s);
/* The performance at t in the player frame (floor y = 0, facing -z), before
 * any turning or travel limit: the segments blended, or the joint track. */
void synth_performance_points(const cub_synth *s, double t_s, cub_fv3 out[SP_COUNT]);

/* ---- text lines for the parsers (lines.c) ------------------------------- */
#define SYNTH_MAX_FIELDS 96
#define SYNTH_FIELD_LEN 256
typedef struct synth_lines {
    const char *p, *end, *name;
    int line; /* 1-based number of the line last read */
} synth_lines;
typedef struct synth_fields {
    int n;
    char f[SYNTH_MAX_FIELDS][SYNTH_FIELD_LEN];
    int too_many, too_long;
    int nul; /* the line holds a NUL byte: no text format has one */
} synth_fields;
/* Next line split at blanks; 0 at the end. */
int synth_lines_next(synth_lines *l, synth_fields *out);
/* A finite number in [-limit, limit]; 0 if the field is not one. */
int synth_parse_num(const char *s, double limit, double *out);
cub_err synth_fail(cub_diag *diag, const char *file, int line, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* ---- the room (room.c): the floor, and furniture when furnished ------- */
void synth_room_build(float distance_mm, int furnished, synth_prim *out, int *n);

/* ---- Kinect effects (kinect.c) ----------------------------------------- */
typedef struct synth_rng {
    uint64_t s;
} synth_rng;
uint64_t synth_rng_next(synth_rng *r);
float synth_rng_unit(synth_rng *r); /* [0, 1) */
float synth_rng_gauss(synth_rng *r);

/* depth (clean, mm) -> raw, with the projector's shadow (proj_depth is the
 * scene seen from the projector), edge noise and holes unless clean. */
void synth_kinect_apply(const float *depth_mm, const float *proj_depth_mm, int clean,
                        synth_rng *rng, uint16_t *raw);

#endif

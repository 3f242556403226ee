/* The scene and the performance: segments of clips played back to back
 * (blended), the player placed facing the camera then turned and its
 * travel clamped as asked, the optional room and second person (standing,
 * walking in, crossing, a sibling), and one frame's render with its truth. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "synth_internal.h"

#define PI_F 3.14159265f
#define MAX_PRIMS 96
#define YAW_TURN_S 0.5f   /* a new segment yaw is turned to in this time */
#define WALK_MM_S 1000.0f /* the second person's walking speed */
#define WALK_IN_FROM_S 1.0
#define WALK_IN_MM 2400.0f /* from this far right of its spot: out of view */
#define CROSS_HALF_MM 2000.0f
#define NPIX (CUB_KINECT_WIDTH * CUB_KINECT_HEIGHT)

_Static_assert(SP_COUNT == CUB_SYNTH_JTRACK_POINTS, "a joint track holds every point");

typedef struct seg {
    synth_actor *actor;
    double from_s, dur_s, start_s; /* clip time, length, start in the performance */
    int mirror;
    float cos_b, sin_b; /* yaw that turns the clip's mean facing to the camera */
    cub_fv3 centre;         /* the clip's mean ground position (actor frame) */
    float floor_y;      /* the lowest sole over the segment (actor frame) */
} seg;

struct cub_synth {
    cub_synth_desc d;
    seg *segs;
    int nseg;
    double total_s;
    int prelude;                  /* frames before the child's (desc.prelude_s) */
    seg second;
    int has_second;
    float start_x, start_z;   /* the child's hips at the start (player frame): a sibling's spot */
    float sib_own_x, sib_own_z; /* the sibling's own clip's hips at the start, about its spot */
    cub_fv3 second_pts[SP_COUNT]; /* of the frame last rendered */
    int last_frame;
    float *yaws;                  /* per yaw segment, degrees */
    int nyaw;
    synth_body_shape shape, second_shape;
    synth_camera cam, proj;
    synth_prim room[32];
    int nroom;
    float *depth, *proj_depth;
    uint8_t *owner, *part;
    /* the room does not move: rendered once, copied under every frame */
    float *room_depth, *room_proj_depth;
    uint8_t *room_owner;
};

static void defaults(cub_synth_desc *d)
{
    if (!d->data_dir) d->data_dir = getenv("CUB_DATA_DIR");
    if (d->height_mm <= 0) d->height_mm = 1150;
    if (d->distance_mm <= 0) d->distance_mm = 2200;
    if (d->camera_height_mm <= 0) d->camera_height_mm = 800;
    if (d->fps <= 0) d->fps = 30;
    if (d->blend_s <= 0) d->blend_s = 0.3f;
    int sib = d->second_mode == CUB_SYNTH_SECOND_SIBLING;
    int cross = d->second_mode == CUB_SYNTH_SECOND_CROSS;
    if (d->second_height_mm <= 0) d->second_height_mm = sib ? d->height_mm * 1.08f : 1650;
    if (d->second_speed_mm_s <= 0) d->second_speed_mm_s = WALK_MM_S;
    /* a sibling's x stays 0 here: its side is chosen where the child starts */
    if (d->second_x_mm == 0 && !sib) d->second_x_mm = cross ? 0 : 700;
    if (d->second_dz_mm == 0) d->second_dz_mm = sib ? 100 : cross ? -700 : 900;
}

static float build_factor(int build)
{
    return build == CUB_SYNTH_SLIM ? 0.82f : build == CUB_SYNTH_STURDY ? 1.22f : 1.0f;
}

/* Mean facing, mean ground position and lowest sole over the segment. */
static void fit_segment(seg *s, float sole_mm)
{
    cub_fv3 p[SP_COUNT], left = cub_fv3_make(0, 0, 0), centre = cub_fv3_make(0, 0, 0);
    float low = 1e30f;
    const int K = 24;
    for (int k = 0; k < K; k++) {
        synth_actor_points(s->actor, s->from_s + s->dur_s * k / (K - 1), p);
        left = cub_fv3_add(left, cub_fv3_sub(p[CUB_KJ_HIP_L], p[CUB_KJ_HIP_R]));
        left = cub_fv3_add(left, cub_fv3_sub(p[CUB_KJ_SHOULDER_L], p[CUB_KJ_SHOULDER_R]));
        centre = cub_fv3_add(centre, cub_fv3_scale(p[CUB_KJ_HIP_CENTRE], 1.0f / K));
        for (int a = CUB_KJ_ANKLE_L; a <= CUB_KJ_ANKLE_R; a += CUB_KJ_ANKLE_R - CUB_KJ_ANKLE_L) {
            cub_fv3 heel, toe;
            synth_body_foot_ends(p[a], p[a + 1], &heel, &toe);
            low = fminf(low, fminf(heel.y, toe.y));
        }
    }
    /* Turn the mean left direction to -x: the player faces -z, the camera. */
    float beta = PI_F - atan2f(left.z, left.x);
    s->cos_b = cosf(beta);
    s->sin_b = sinf(beta);
    s->centre = centre;
    s->floor_y = low - sole_mm;
}

/* The segment's points at clip time t, in the player frame (floor y = 0,
 * facing -z, centred on x = z = 0). */
static void segment_points(const seg *s, double t_s, cub_fv3 out[SP_COUNT])
{
    cub_fv3 p[SP_COUNT];
    synth_actor_points(s->actor, t_s, p);
    for (int j = 0; j < SP_COUNT; j++) {
        float x = p[j].x - s->centre.x, z = p[j].z - s->centre.z;
        out[j] = cub_fv3_make(x * s->cos_b - z * s->sin_b, p[j].y - s->floor_y,
                              x * s->sin_b + z * s->cos_b);
    }
    if (!s->mirror) return;
    for (int j = 0; j < SP_COUNT; j++)
        out[j].x = -out[j].x;
    for (int k = 0; k < 4; k++) { /* shoulder..hand, hip..foot: L and R swap */
        cub_fv3 t = out[CUB_KJ_SHOULDER_L + k];
        out[CUB_KJ_SHOULDER_L + k] = out[CUB_KJ_SHOULDER_R + k];
        out[CUB_KJ_SHOULDER_R + k] = t;
        t = out[CUB_KJ_HIP_L + k];
        out[CUB_KJ_HIP_L + k] = out[CUB_KJ_HIP_R + k];
        out[CUB_KJ_HIP_R + k] = t;
    }
}

static cub_fv3 to_world(cub_fv3 p, float dx, float dz)
{
    return cub_fv3_make(p.x + dx, p.y, p.z + dz);
}

static float smooth01(float w)
{
    w = w < 0 ? 0 : w > 1 ? 1 : w;
    return w * w * (3 - 2 * w);
}

/* Turn the points by deg about the vertical line through (cx, cz). */
static void turn_about(cub_fv3 p[SP_COUNT], float cx, float cz, float deg)
{
    float th = deg * PI_F / 180.0f, c = cosf(th), n = sinf(th);
    for (int j = 0; j < SP_COUNT; j++) {
        float x = p[j].x - cx, z = p[j].z - cz;
        p[j].x = cx + x * c + z * n;
        p[j].z = cz - x * n + z * c;
    }
}

/* The clip's own travel (the hips about the origin of the player frame):
 * kept, softly clamped to +-max_mm on each floor axis, or pinned. */
static void limit_travel(cub_fv3 p[SP_COUNT], float max_mm, int pin)
{
    cub_fv3 h = p[CUB_KJ_HIP_CENTRE];
    float dx = 0, dz = 0;
    if (pin) {
        dx = -h.x, dz = -h.z;
    } else if (max_mm > 0) {
        dx = max_mm * tanhf(h.x / max_mm) - h.x;
        dz = max_mm * tanhf(h.z / max_mm) - h.z;
    }
    for (int j = 0; j < SP_COUNT; j++)
        p[j].x += dx, p[j].z += dz;
}

static float wrap180(float deg)
{
    return deg - 360.0f * floorf((deg + 180.0f) / 360.0f);
}

/* The turning about the hips at t: the spin plus the segment yaw. */
static float turning_deg(const cub_synth *s, double t_s)
{
    float yaw = (float)(s->d.spin_deg_s * t_s);
    if (s->nyaw == 0) return yaw;
    int k = (int)(t_s / s->d.yaw_segment_s);
    k = k < 0 ? 0 : k >= s->nyaw ? s->nyaw - 1 : k;
    float w = smooth01((float)(t_s - k * s->d.yaw_segment_s) / YAW_TURN_S);
    float prev = k > 0 ? s->yaws[k - 1] : s->yaws[0];
    return yaw + prev + wrap180(s->yaws[k] - prev) * w;
}

/* Segment yaws uniform in [-180, 180), from their own stream of the seed;
 * the first one in [-start_yaw_max, start_yaw_max) when that is set, from
 * the same draw, so every later yaw is the one the seed gave before. */
static int draw_yaws(cub_synth *s)
{
    if (s->d.yaw_segment_s <= 0) return 0;
    s->nyaw = (int)(s->total_s / s->d.yaw_segment_s) + 1;
    s->yaws = malloc((size_t)s->nyaw * sizeof(float));
    if (!s->yaws) return -1;
    /* not seed x splitmix's own step: seeds n and n + 1 would be one stream */
    synth_rng rng = {s->d.seed * 0xD1B54A32D192ED03ull + 0x5EEDull};
    for (int k = 0; k < s->nyaw; k++)
        s->yaws[k] = synth_rng_unit(&rng) * 360.0f - 180.0f;
    if (s->d.start_yaw_max_deg > 0) s->yaws[0] *= s->d.start_yaw_max_deg / 180.0f;
    return 0;
}

/* The joint track's frame nearest t (the track fixes the performance). */
static void track_points(const cub_synth_jtrack *t, double t_s, cub_fv3 out[SP_COUNT])
{
    long i = lround(t_s * t->fps);
    i = i < 0 ? 0 : i >= t->frame_count ? t->frame_count - 1 : i;
    const float *v = t->points_mm + (size_t)i * CUB_SYNTH_JTRACK_POINTS * 3;
    for (int j = 0; j < SP_COUNT; j++)
        out[j] = cub_fv3_make(v[3 * j], v[3 * j + 1], v[3 * j + 2]);
}

void synth_performance_points(const cub_synth *s, double t_s, cub_fv3 out[SP_COUNT])
{
    if (s->d.track) {
        track_points(s->d.track, t_s, out);
        return;
    }
    int k = 0;
    while (k + 1 < s->nseg && t_s >= s->segs[k + 1].start_s)
        k++;
    const seg *g = &s->segs[k];
    double local = t_s - g->start_s;
    if (local > g->dur_s) local = g->dur_s;
    segment_points(g, g->from_s + local, out);
    if (k > 0 && local < s->d.blend_s) {
        cub_fv3 prev[SP_COUNT];
        const seg *q = &s->segs[k - 1];
        segment_points(q, q->from_s + q->dur_s, prev);
        float w = (float)(local / s->d.blend_s);
        w = w * w * (3 - 2 * w);
        for (int j = 0; j < SP_COUNT; j++)
            out[j] = cub_fv3_lerp(prev[j], out[j], w);
    }
}

/* The player at t in the player frame: the whole performance turned by
 * yaw_deg, the body turning about its hips, its travel limited. */
static void player_points(const cub_synth *s, double t_s, cub_fv3 out[SP_COUNT])
{
    synth_performance_points(s, t_s, out);
    if (s->d.yaw_deg != 0) turn_about(out, 0, 0, s->d.yaw_deg);
    float turn = turning_deg(s, t_s);
    if (turn != 0) turn_about(out, out[CUB_KJ_HIP_CENTRE].x, out[CUB_KJ_HIP_CENTRE].z, turn);
    limit_travel(out, s->d.max_travel_mm, s->d.pin);
}

/* The second person's spot (offset from the player's) and yaw at t; 1 when
 * its motion is driven here (its own travel is then pinned). */
static int second_spot(const cub_synth *s, double t_s, float *x, float *dz, float *yaw)
{
    *x = s->d.second_x_mm, *dz = s->d.second_dz_mm, *yaw = 0;
    double speed = s->d.second_speed_mm_s;
    if (s->d.second_mode == CUB_SYNTH_SECOND_SIBLING) {
        /* beside the child where it starts (a clip that travels starts
         * off the spot), on the side away from the image's centre unless
         * told: the child, in the middle, is the one the box plays with */
        float side = s->start_x > 0 ? 650.0f : -650.0f;
        *x = s->start_x - s->sib_own_x + (s->d.second_x_mm != 0 ? s->d.second_x_mm : side);
        *dz += s->start_z - s->sib_own_z;
        return 0;
    }
    if (s->d.second_mode == CUB_SYNTH_SECOND_WALK_IN) {
        double walked = (t_s - WALK_IN_FROM_S) * speed;
        walked = walked < 0 ? 0 : walked > WALK_IN_MM ? WALK_IN_MM : walked;
        *x += WALK_IN_MM - (float)walked;
        double arrived_s = t_s - WALK_IN_FROM_S - WALK_IN_MM / speed;
        /* walking to -x: facing its left (+90), then turning to the camera */
        *yaw = 90.0f * (1 - smooth01((float)arrived_s / YAW_TURN_S));
        return 1;
    }
    if (s->d.second_mode == CUB_SYNTH_SECOND_CROSS) {
        /* mid-way, but from out of view: the child is there first */
        double mid_s = s->total_s / 2 > CROSS_HALF_MM / speed ? s->total_s / 2 : CROSS_HALF_MM / speed;
        double x_mm = -(t_s - mid_s) * speed;
        *x += (float)(x_mm < -CROSS_HALF_MM ? -CROSS_HALF_MM : x_mm > CROSS_HALF_MM ? CROSS_HALF_MM : x_mm);
        *yaw = 90.0f;
        return 1;
    }
    return 0;
}

/* At t_s on the performance's clock; its own clip at clip_s (>= 0: it
 * plays through the prelude too, where t_s < 0). */
static void second_points(const cub_synth *s, double t_s, double clip_s, cub_fv3 q[SP_COUNT])
{
    const seg *g = &s->second;
    segment_points(g, g->from_s + fmod(clip_s, g->dur_s), q);
    float x, dz, yaw;
    int driven = second_spot(s, t_s, &x, &dz, &yaw);
    if (yaw != 0) turn_about(q, q[CUB_KJ_HIP_CENTRE].x, q[CUB_KJ_HIP_CENTRE].z, yaw);
    limit_travel(q, s->d.max_travel_mm, driven || s->d.pin);
    for (int j = 0; j < SP_COUNT; j++)
        q[j] = to_world(q[j], x, s->d.distance_mm + dz);
}

static void set_cameras(cub_synth *s)
{
    float th = s->d.tilt_deg * PI_F / 180.0f, c = cosf(th), n = sinf(th);
    s->cam.origin = cub_fv3_make(0, s->d.camera_height_mm, 0);
    s->cam.x = cub_fv3_make(1, 0, 0);
    s->cam.y = cub_fv3_make(0, c, -n);
    s->cam.z = cub_fv3_make(0, n, c);
    s->proj = s->cam;
    s->proj.origin = cub_fv3_add(s->cam.origin, cub_fv3_scale(s->cam.x, CUB_SYNTH_PROJECTOR_X_MM));
}

void cub_synth_gravity(const cub_synth *s, float g[3])
{
    cub_fv3 down = cub_fv3_make(0, -1000.0f, 0);
    g[0] = cub_fv3_dot(down, s->cam.x);
    g[1] = cub_fv3_dot(down, s->cam.y);
    g[2] = cub_fv3_dot(down, s->cam.z);
}

static cub_err load_segment(cub_synth *s, seg *g, const char *clip, float height_mm, double from_s,
                            double to_s, int mirror, cub_diag *diag)
{
    cub_err err = synth_actor_load(clip, s->d.data_dir, height_mm, &g->actor, diag);
    if (err) return err;
    double len = synth_actor_duration_s(g->actor);
    if (from_s < 0 || from_s >= len) {
        synth_actor_free(g->actor);
        g->actor = NULL;
        if (diag) {
            memset(diag, 0, sizeof(*diag));
            snprintf(diag->file, sizeof(diag->file), "%.250s", clip);
            snprintf(diag->msg, sizeof(diag->msg), "from %.2f s is outside the clip (%.2f s)",
                     from_s, len);
        }
        return CUB_ERR_RANGE;
    }
    g->from_s = from_s;
    g->dur_s = (to_s <= 0 || to_s > len ? len : to_s) - from_s;
    if (g->dur_s <= 0) g->dur_s = 1.0 / s->d.fps;
    g->mirror = mirror;
    synth_body_shape shape = {.height_mm = height_mm, .build = 1};
    fit_segment(g, synth_body_sole_mm(&shape));
    return CUB_OK;
}

cub_err cub_synth_open(const cub_synth_desc *desc, const cub_synth_segment *segs, int n,
                       cub_synth **out, cub_diag *diag)
{
    if (!desc || !out || n < 0 || (n > 0 && !segs)) return CUB_ERR_ARG;
    if (desc->track && (n > 0 || desc->track->frame_count < 1 || !(desc->track->fps > 0) ||
                        !desc->track->points_mm))
        return CUB_ERR_ARG;
    cub_synth *s = calloc(1, sizeof(*s));
    if (!s) return CUB_ERR_NOMEM;
    s->d = *desc;
    defaults(&s->d);
    s->shape = (synth_body_shape){s->d.height_mm, build_factor(s->d.build), s->d.loose_clothes};
    s->second_shape = (synth_body_shape){s->d.second_height_mm, 1.0f, 0};
    if (s->d.yaw_segment_s > 0 && s->d.yaw_segment_s < 0.1f) s->d.yaw_segment_s = 0.1f;
    set_cameras(s);
    synth_room_build(s->d.distance_mm, s->d.room, s->room, &s->nroom);
    s->segs = calloc((size_t)(n ? n : 1), sizeof(seg));
    s->depth = malloc(NPIX * sizeof(float));
    s->proj_depth = malloc(NPIX * sizeof(float));
    s->owner = malloc(NPIX);
    s->part = calloc(NPIX, 1);
    s->room_depth = malloc(NPIX * sizeof(float));
    s->room_proj_depth = malloc(NPIX * sizeof(float));
    s->room_owner = malloc(NPIX);
    cub_err err = (s->segs && s->depth && s->proj_depth && s->owner && s->part && s->room_depth &&
                   s->room_proj_depth && s->room_owner)
                      ? CUB_OK
                      : CUB_ERR_NOMEM;
    if (!err) {
        synth_raycast(&s->cam, s->room, s->nroom, s->room_depth, s->room_owner, 1);
        synth_raycast(&s->proj, s->room, s->nroom, s->room_proj_depth, NULL, 1);
    }
    for (int i = 0; i < n && !err; i++) {
        err = load_segment(s, &s->segs[i], segs[i].clip, s->d.height_mm, segs[i].from_s,
                           segs[i].to_s, segs[i].mirror, diag);
        s->nseg = err ? i : i + 1;
        s->segs[i].start_s = s->total_s;
        s->total_s += s->segs[i].dur_s;
    }
    if (s->d.track) s->total_s = s->d.track->frame_count / (double)s->d.track->fps;
    if (s->d.prelude_s > 0) s->prelude = (int)lround(s->d.prelude_s * s->d.fps);
    if (!err && draw_yaws(s)) err = CUB_ERR_NOMEM;
    if (!err && (s->nseg > 0 || s->d.track)) {
        cub_fv3 p[SP_COUNT];
        player_points(s, 0, p);
        s->start_x = p[CUB_KJ_HIP_CENTRE].x, s->start_z = p[CUB_KJ_HIP_CENTRE].z;
    }
    if (!err && s->d.second_clip) {
        err = load_segment(s, &s->second, s->d.second_clip, s->d.second_height_mm, 0, 0, 0, diag);
        s->has_second = !err;
    }
    if (!err && s->has_second) {
        cub_fv3 q[SP_COUNT];
        segment_points(&s->second, s->second.from_s, q);
        limit_travel(q, s->d.max_travel_mm, s->d.pin);
        s->sib_own_x = q[CUB_KJ_HIP_CENTRE].x, s->sib_own_z = q[CUB_KJ_HIP_CENTRE].z;
    }
    if (err) {
        cub_synth_close(s);
        return err;
    }
    *out = s;
    return CUB_OK;
}

void cub_synth_close(cub_synth *s)
{
    if (!s) return;
    for (int i = 0; i < s->nseg; i++)
        synth_actor_free(s->segs[i].actor);
    if (s->has_second) synth_actor_free(s->second.actor);
    free(s->segs);
    free(s->yaws);
    free(s->depth);
    free(s->proj_depth);
    free(s->owner);
    free(s->part);
    free(s->room_depth);
    free(s->room_proj_depth);
    free(s->room_owner);
    free(s);
}

float synth_fps(const cub_synth *s)
{
    return s->d.fps;
}

int cub_synth_frame_count(const cub_synth *s)
{
    return s->prelude + (int)(s->total_s * s->d.fps + 1e-6);
}

int cub_synth_prelude_frames(const cub_synth *s)
{
    return s ? s->prelude : 0;
}

/* The truth of a body (shape, owner) posed by pts, seen in the frame last
 * rendered. */
static void truth_of(const cub_synth *s, const cub_fv3 pts[SP_COUNT], const synth_body_shape *shape,
                     uint8_t owner, cub_synth_truth_frame *t)
{
    for (int j = 0; j < CUB_KJ_COUNT; j++) {
        cub_fv3 c = cub_fv3_sub(pts[j], s->cam.origin);
        float x = cub_fv3_dot(c, s->cam.x), y = cub_fv3_dot(c, s->cam.y);
        float z = cub_fv3_dot(c, s->cam.z);
        t->joint_mm[j][0] = x;
        t->joint_mm[j][1] = y;
        t->joint_mm[j][2] = z;
        t->visible[j] = 0;
        if (z < 100) continue;
        int u = (int)lroundf(CUB_KINECT_CX + CUB_KINECT_FOCAL_PX * x / z);
        int v = (int)lroundf(CUB_KINECT_CY - CUB_KINECT_FOCAL_PX * y / z);
        if (u < 0 || v < 0 || u >= CUB_KINECT_WIDTH || v >= CUB_KINECT_HEIGHT) continue;
        /* Seen when the surface at its pixel is this body's, not something
         * in front of it (an arm across the chest). */
        float margin = synth_body_joint_radius(shape, j) + 50.0f;
        int i = v * CUB_KINECT_WIDTH + u;
        t->visible[j] = s->owner[i] == owner && s->depth[i] >= z - margin;
    }
}

cub_err cub_synth_render(cub_synth *s, int frame, uint16_t *raw, cub_synth_truth_frame *truth,
                         float *depth_mm, uint8_t *owner)
{
    if (!s || !raw || frame < 0) return CUB_ERR_ARG;
    synth_prim prims[MAX_PRIMS];
    int n = 0;
    double t_s = (frame - s->prelude) / (double)s->d.fps;
    cub_fv3 pts[SP_COUNT];
    s->last_frame = frame;
    int child = (s->nseg > 0 || s->d.track) && frame >= s->prelude;
    if (child) {
        player_points(s, t_s, pts);
        for (int j = 0; j < SP_COUNT; j++)
            pts[j] = to_world(pts[j], 0, s->d.distance_mm);
        n += synth_body_prims(&s->shape, pts, OWNER_PLAYER, prims + n);
    }
    if (s->has_second) {
        second_points(s, t_s, frame / (double)s->d.fps, s->second_pts);
        n += synth_body_prims(&s->second_shape, s->second_pts, OWNER_SECOND, prims + n);
    }
    memcpy(s->depth, s->room_depth, NPIX * sizeof(float));
    memcpy(s->owner, s->room_owner, NPIX);
    memset(s->part, CUB_PART_NONE, NPIX);
    synth_raycast_parts(&s->cam, prims, n, s->depth, s->owner, s->part);
    if (!s->d.clean) {
        memcpy(s->proj_depth, s->room_proj_depth, NPIX * sizeof(float));
        synth_raycast(&s->proj, prims, n, s->proj_depth, NULL, 0);
    }
    synth_rng rng = {s->d.seed * 0x2545F4914F6CDD1Dull + (uint64_t)frame * 0x9E3779B97F4A7C15ull};
    synth_kinect_apply(s->depth, s->proj_depth, s->d.clean, &rng, raw);
    if (truth) {
        memset(truth, 0, sizeof(*truth));
        truth->frame = frame;
        cub_synth_frame_name(frame, s->d.fps, NULL, 0, &truth->t_s, &truth->ts);
        if (child) truth_of(s, pts, &s->shape, OWNER_PLAYER, truth);
    }
    if (depth_mm) memcpy(depth_mm, s->depth, NPIX * sizeof(float));
    if (owner) memcpy(owner, s->owner, NPIX);
    return CUB_OK;
}

int cub_synth_has_second(const cub_synth *s)
{
    return s && s->has_second;
}

cub_err cub_synth_second_truth(const cub_synth *s, cub_synth_truth_frame *truth)
{
    if (!s || !truth || !s->has_second) return CUB_ERR_ARG;
    memset(truth, 0, sizeof(*truth));
    truth->frame = s->last_frame;
    cub_synth_frame_name(s->last_frame, s->d.fps, NULL, 0, &truth->t_s, &truth->ts);
    truth_of(s, s->second_pts, &s->second_shape, OWNER_SECOND, truth);
    return CUB_OK;
}

cub_err cub_synth_parts(const cub_synth *s, uint8_t *part)
{
    if (!s || !part) return CUB_ERR_ARG;
    memcpy(part, s->part, NPIX);
    return CUB_OK;
}

const char *cub_synth_part_name(int part)
{
    static const char *names[CUB_PART_COUNT] = {
        "none",   "head",   "torso_upper", "torso_lower", "upper_arm_l", "forearm_l",
        "hand_l", "upper_arm_r", "forearm_r", "hand_r", "thigh_l",     "shin_l",
        "foot_l", "thigh_r",     "shin_r",    "foot_r"};
    return part >= 0 && part < CUB_PART_COUNT ? names[part] : "?";
}

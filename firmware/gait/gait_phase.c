/* gait — the phase analysis (SEEDS.md § 003, "Analysis"): per foot, the
 * foot length and the five key phases of each leg cycle, from the ankle's
 * and toe's heights and the foot's pitch. There is no heel node: every
 * test compares the ankle and the toe. Q16.16 throughout. */
#include "cub/gait.h"

#define DEFAULT_DOWN_MM CUB_Q16_INT(25) /* ours: CMU walks' ankles jitter ~1 cm at rest */
#define DEFAULT_SETTLE_RAD_S 34315      /* ours: 30 degrees per second */
#define DEFAULT_FPS 120
#define DEFAULT_MIN_RUN_DIV 24 /* ours: 1/24 s, 5 frames at 120 fps (see docs/gait.md) */
#define DEFAULT_STILL_MM_S CUB_Q16_INT(1000) /* ours: a swinging foot moves 3-4 m/s */

const char *cub_gait_phase_name(cub_gait_phase p)
{
    static const char *const names[CUB_GAIT_PHASE_COUNT_] = {"stance", "lift", "off", "strike",
                                                             "land"};
    return (unsigned)p < CUB_GAIT_PHASE_COUNT_ ? names[p] : "?";
}

cub_q16 cub_gait_foot_pitch(cub_vec3 ankle_mm, cub_vec3 toe_mm)
{
    cub_vec3 d = cub_fx_vec3_sub(toe_mm, ankle_mm);
    cub_q16 run = cub_fx_vec3_length((cub_vec3){d.x, 0, d.z});
    return cub_fx_atan2(cub_fx_sub(ankle_mm.y, toe_mm.y), run);
}

cub_err cub_gait_track_clip(const cub_clip *clip, int ankle, int toe, cub_vec3 *ankle_out,
                            cub_vec3 *toe_out)
{
    if (!clip || !clip->skel || !ankle_out || !toe_out) return CUB_ERR_ARG;
    if (ankle < 0 || toe < 0 || ankle >= clip->skel->joint_count || toe >= clip->skel->joint_count)
        return CUB_ERR_RANGE;
    cub_pose pose;
    cub_quat rot; /* unused, but joint_world fills it */
    for (int f = 0; f < clip->frame_count; f++) {
        cub_err e = cub_motion_clip_get_frame(clip, f, &pose);
        if (!e) e = cub_motion_joint_world(clip->skel, &pose, ankle, &ankle_out[f], &rot);
        if (!e) e = cub_motion_joint_world(clip->skel, &pose, toe, &toe_out[f], &rot);
        if (e) return e;
    }
    return CUB_OK;
}

typedef struct phase_cfg {
    int half;            /* frames either side for the local ground */
    cub_q16 down, still; /* mm; mm per frame */
    cub_q16 settle;      /* radians per frame */
    int min_run;         /* shortest contact change counted, frames */
} phase_cfg;

static phase_cfg config(const cub_gait_phase_params *p)
{
    int fps = p && p->fps > 0 ? p->fps : DEFAULT_FPS;
    cub_q16 still = p && p->still_mm_s > 0 ? p->still_mm_s : DEFAULT_STILL_MM_S;
    cub_q16 settle = p && p->settle_rad_s > 0 ? p->settle_rad_s : DEFAULT_SETTLE_RAD_S;
    int min_run = p && p->min_frames > 0 ? p->min_frames : fps / DEFAULT_MIN_RUN_DIV;
    return (phase_cfg){fps / 2 > 0 ? fps / 2 : 1,
                       p && p->down_mm > 0 ? p->down_mm : DEFAULT_DOWN_MM, still / fps,
                       settle / fps, min_run > 1 ? min_run : 1};
}

/* The lowest height of a point within half frames of f. */
static cub_q16 local_ground(const cub_vec3 *pt, int frames, int f, int half)
{
    int a = f - half > 0 ? f - half : 0, b = f + half < frames ? f + half : frames - 1;
    cub_q16 lo = pt[a].y;
    for (int i = a + 1; i <= b; i++)
        if (pt[i].y < lo) lo = pt[i].y;
    return lo;
}

/* The point's speed at f, mm per frame (central difference). */
static cub_q16 frame_speed(const cub_vec3 *pt, int frames, int f)
{
    int a = f > 0 ? f - 1 : 0, b = f < frames - 1 ? f + 1 : frames - 1;
    return cub_fx_vec3_length(cub_fx_vec3_sub(pt[b], pt[a])) / (b - a);
}

static bool is_down(const cub_vec3 *pt, int frames, int f, const phase_cfg *c)
{
    cub_q16 h = cub_fx_sub(pt[f].y, local_ground(pt, frames, f, c->half));
    return h <= c->down && frame_speed(pt, frames, f) <= c->still;
}

/* How fast the foot's pitch turns at f, radians per frame. */
static cub_q16 pitch_rate(const cub_vec3 *ankle, const cub_vec3 *toe, int frames, int f)
{
    int a = f > 0 ? f - 1 : 0, b = f < frames - 1 ? f + 1 : frames - 1;
    cub_q16 d =
        cub_fx_sub(cub_gait_foot_pitch(ankle[b], toe[b]), cub_gait_foot_pitch(ankle[a], toe[a]));
    return cub_fx_abs(d) / (b - a);
}

/* Length and flat pitch of the foot over the clip: the mean ankle -> toe
 * distance; the mean pitch and ankle-over-toe height of the frames with
 * both points down [ours: most of those are stance, so the mean is flat]. */
static void measure_foot(const cub_vec3 *ankle, const cub_vec3 *toe, int frames, const phase_cfg *c,
                         cub_gait_foot *foot)
{
    int64_t len = 0, lift = 0, pitch = 0;
    int down = 0;
    for (int f = 0; f < frames; f++) {
        len += cub_fx_vec3_length(cub_fx_vec3_sub(toe[f], ankle[f]));
        if (!is_down(ankle, frames, f, c) || !is_down(toe, frames, f, c)) continue;
        lift += cub_fx_sub(ankle[f].y, toe[f].y);
        pitch += cub_gait_foot_pitch(ankle[f], toe[f]);
        down++;
    }
    foot->length_mm = (cub_q16)(len / frames);
    foot->ankle_lift_mm = down ? (cub_q16)(lift / down) : 0;
    foot->flat_pitch_rad = down ? (cub_q16)(pitch / down) : 0;
}

/* The phase of a frame from which points are down and the phase before
 * (-1 for the first frame: judged by the frame alone). */
static cub_gait_phase next_phase(int prev, bool ankle_down, bool toe_down, bool settled)
{
    if (ankle_down && toe_down) {
        /* Both touch again: at least one frame of land (the key frame),
         * more while the foot still rolls down to flat. */
        if (prev == CUB_GAIT_OFF || prev == CUB_GAIT_STRIKE) return CUB_GAIT_LAND;
        return prev == CUB_GAIT_LAND && !settled ? CUB_GAIT_LAND : CUB_GAIT_STANCE;
    }
    if (!ankle_down && !toe_down) return CUB_GAIT_OFF;
    if (prev == CUB_GAIT_OFF || prev == CUB_GAIT_STRIKE) return CUB_GAIT_STRIKE;
    if (prev < 0) return toe_down ? CUB_GAIT_LIFT : CUB_GAIT_STRIKE;
    /* From stance, lift or land: one point leaves the ground first. */
    return CUB_GAIT_LIFT;
}

#define ANKLE_BIT 1
#define TOE_BIT 2

/* Runs of one contact bit shorter than min frames, with the other state
 * on both sides, take the state around them: a toe brushing the ground
 * mid-swing, or a planted point jittering past down_mm for a frame, is
 * noise, not a phase [ours]. Runs at the clip's ends are kept (their
 * other side is unknown). A flipped run joins the run before it and the
 * one after, and the scan goes on from the joined run's start: a train
 * of one-frame flickers (CMU 07_01's toe at foot-off: up, down, up) is
 * merged, not passed along one frame at a time. */
static void debounce(uint8_t *bits, int frames, uint8_t bit, int min)
{
    int start = 0, prev = 0;
    while (start < frames) {
        int end = start;
        while (end < frames && (bits[end] & bit) == (bits[start] & bit))
            end++;
        if (start > 0 && end < frames && end - start < min) {
            for (int f = start; f < end; f++)
                bits[f] ^= bit;
            start = prev;
            continue;
        }
        prev = start;
        start = end;
    }
}

/* Each frame's contact bits, debounced, into out (the phase array, reused
 * as scratch: no allocation). */
static void contacts(const cub_vec3 *ankle, const cub_vec3 *toe, int frames, const phase_cfg *c,
                     uint8_t *out)
{
    for (int f = 0; f < frames; f++)
        out[f] = (uint8_t)((is_down(ankle, frames, f, c) ? ANKLE_BIT : 0) |
                           (is_down(toe, frames, f, c) ? TOE_BIT : 0));
    debounce(out, frames, ANKLE_BIT, c->min_run);
    debounce(out, frames, TOE_BIT, c->min_run);
}

cub_err cub_gait_analyse(const cub_vec3 *ankle_mm, const cub_vec3 *toe_mm, int frames,
                         const cub_gait_phase_params *p, uint8_t *phase_out, cub_gait_foot *foot)
{
    if (!ankle_mm || !toe_mm || !phase_out || !foot || frames < 2) return CUB_ERR_ARG;
    phase_cfg c = config(p);
    *foot = (cub_gait_foot){0};
    measure_foot(ankle_mm, toe_mm, frames, &c, foot);
    contacts(ankle_mm, toe_mm, frames, &c, phase_out);
    int prev = -1;
    bool seen_lift = false, seen_off = false;
    for (int f = 0; f < frames; f++) {
        bool a = phase_out[f] & ANKLE_BIT, t = phase_out[f] & TOE_BIT;
        bool settled = pitch_rate(ankle_mm, toe_mm, frames, f) <= c.settle;
        cub_gait_phase ph = next_phase(prev, a, t, settled);
        seen_lift |= ph == CUB_GAIT_LIFT;
        seen_off |= seen_lift && ph == CUB_GAIT_OFF;
        if (ph == CUB_GAIT_LAND && prev != CUB_GAIT_LAND && seen_off) {
            foot->cycles++;
            seen_lift = seen_off = false;
        }
        foot->phase_frames[ph]++;
        phase_out[f] = (uint8_t)ph;
        prev = (int)ph;
    }
    return CUB_OK;
}

cub_err cub_gait_walk_clip_make(const cub_clip *clip, const int ankle[2], const int toe[2],
                                cub_vec3 *const ankle_mm[2], cub_vec3 *const toe_mm[2],
                                uint8_t *const phase[2], cub_gait_walk_clip *out)
{
    if (!clip || !clip->frame_ns || !out) return CUB_ERR_ARG;
    /* the clip's own rate: the bear's clips are 30 fps, CMU's 120 */
    cub_gait_phase_params pp = {.fps = (int)((1000000000u + clip->frame_ns / 2) / clip->frame_ns)};
    *out = (cub_gait_walk_clip){.clip = clip};
    for (int i = 0; i < 2; i++) {
        cub_err e = cub_gait_track_clip(clip, ankle[i], toe[i], ankle_mm[i], toe_mm[i]);
        if (!e)
            e = cub_gait_analyse(ankle_mm[i], toe_mm[i], clip->frame_count, &pp, phase[i],
                                 &out->foot[i]);
        if (e) return e;
        out->ankle[i] = ankle[i], out->toe[i] = toe[i];
        out->ankle_mm[i] = ankle_mm[i], out->toe_mm[i] = toe_mm[i], out->phase[i] = phase[i];
    }
    return CUB_OK;
}

/* judge: set-up, the per-frame driver, presence, the posture calibration
 * and the event lines. See cub/judge.h for the rules. */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "cub/judge.h"
#include "cub/kinect.h"
#include "judge_internal.h"

#define PCT(n) ((cub_q16)((n) * 65536 / 100)) /* n hundredths in Q16.16 */

static void fill_defaults(cub_judge_desc *d)
{
    if (!d->key_mu) d->key_mu = CUB_FUZZY_ONE / 2;
    if (!d->hold_ms) d->hold_ms = 100;
    if (!d->pose_d_max) d->pose_d_max = PCT(45);
    if (!d->present_frames) d->present_frames = 5;
    if (!d->absent_frames) d->absent_frames = 30;
    if (!d->clap_meet) d->clap_meet = PCT(55);
    if (!d->clap_open) d->clap_open = PCT(100);
    if (!d->clap_approach_ms) d->clap_approach_ms = 400;
    if (!d->clap_speed) d->clap_speed = CUB_Q16_INT(3);
    if (!d->clap_part) d->clap_part = PCT(25);
    if (!d->clap_part_ms) d->clap_part_ms = 600;
    if (!d->clap_refractory_ms) d->clap_refractory_ms = 200;
    if (!d->clap_slack) d->clap_slack = PCT(50);
    if (d->clap_slack == CUB_JUDGE_NO_SLACK) d->clap_slack = 0;
    if (!d->wave_swing) d->wave_swing = PCT(25);
    if (!d->wave_reversals) d->wave_reversals = 2;
    if (!d->wave_gap_ms) d->wave_gap_ms = 2000;
    if (!d->wave_pair_ms) d->wave_pair_ms = 250;
    if (!d->clap_side) d->clap_side = PCT(50);
    if (!d->lag_ms) d->lag_ms = 500;
    if (!d->sign_ms) d->sign_ms = 250;
    if (!d->kick_lift) d->kick_lift = PCT(10);
}

static int desc_ok(const cub_judge_desc *d)
{
    const int32_t ms[] = {d->hold_ms, d->clap_approach_ms, d->clap_part_ms,
                          d->clap_refractory_ms, d->wave_gap_ms, d->wave_pair_ms};
    for (size_t i = 0; i < sizeof ms / sizeof ms[0]; i++)
        if (ms[i] < 0 || ms[i] > 60000) return 0;
    const cub_q16 ratio[] = {d->pose_d_max, d->clap_meet, d->clap_open, d->clap_part,
                             d->wave_swing, d->clap_speed, d->clap_slack, d->kick_lift,
                             d->clap_side};
    for (size_t i = 0; i < sizeof ratio / sizeof ratio[0]; i++)
        if (ratio[i] < 0 || ratio[i] > CUB_Q16_INT(8)) return 0;
    return d->key_mu <= CUB_FUZZY_ONE && d->present_frames > 0 && d->present_frames <= 1000 &&
           d->absent_frames > 0 && d->absent_frames <= 1000 && d->wave_reversals > 0 &&
           d->wave_reversals <= 100 && d->stand_cog_mm >= 0 && d->lag_ms >= 0 &&
           d->lag_ms <= 60000 && d->sign_ms >= 0 && d->sign_ms <= 60000;
}

size_t cub_judge_mem_size(const cub_judge_desc *desc)
{
    (void)desc;
    return sizeof(cub_judge);
}

cub_err cub_judge_init(const cub_judge_desc *desc, void *mem, size_t mem_size, cub_judge **out)
{
    if (!mem || !out) return CUB_ERR_ARG;
    *out = NULL;
    if ((uintptr_t)mem % 8 != 0) return CUB_ERR_ARG;
    if (mem_size < sizeof(cub_judge)) return CUB_ERR_NOMEM;
    cub_judge_desc d = desc ? *desc : (cub_judge_desc){0};
    fill_defaults(&d);
    if (!desc_ok(&d)) return CUB_ERR_ARG;
    cub_judge *j = mem;
    memset(j, 0, sizeof *j);
    j->d = d;
    j->body = cub_kinect_fuzzy_body(0, 0);
    if (d.stand_cog_mm > 0) {
        j->body.floor_y_mm = d.floor_y_mm;
        j->body.stand_cog_mm = d.stand_cog_mm;
        j->calibrated = 1;
    }
    *out = j;
    return CUB_OK;
}

int32_t judge_dist_mm(cub_vec3 a, cub_vec3 b)
{
    int64_t dx = judge_mm(a.x) - (int64_t)judge_mm(b.x);
    int64_t dy = judge_mm(a.y) - (int64_t)judge_mm(b.y);
    int64_t dz = judge_mm(a.z) - (int64_t)judge_mm(b.z);
    return (int32_t)cub_fx_isqrt64((uint64_t)(dx * dx + dy * dy + dz * dz));
}

void judge_emit(cub_judge *j, cub_judge_out *out, const cub_judge_event *e)
{
    if (out->count < CUB_JUDGE_MAX_EVENTS) out->events[out->count++] = *e;
    if (j->d.log) {
        char line[192];
        cub_judge_describe(e, line, sizeof line);
        cub_log_event(j->d.log, e->ev.t_us, "judge", line, NULL);
    }
}

/* Presence with hysteresis over frames. */
static void presence(cub_judge *j, int64_t t_us, int32_t status, cub_judge_out *out)
{
    int ok = status == CUB_TRACK_OK;
    j->ok_run = ok ? j->ok_run + 1 : 0;
    j->bad_run = ok ? 0 : j->bad_run + 1;
    /* other statuses between too-close frames (the child nearer than
     * the Kinect reads) do not end the episode; an OK frame does */
    j->close_run = ok ? 0 : j->close_run + (status == CUB_TRACK_TOO_CLOSE);
    int close = j->close_run == j->d.present_frames && status == CUB_TRACK_TOO_CLOSE;
    int flip = close || (j->in_view ? j->bad_run >= j->d.absent_frames : j->ok_run >= j->d.present_frames);
    if (!flip) return;
    j->in_view = close ? 0 : !j->in_view;
    cub_judge_event e = {
        .ev = {.t_us = t_us, .type = CUB_EV_PLAYER, .a = j->in_view, .b = close},
        .kind = CUB_JUDGE_PLAYER,
        .why = close ? CUB_JUDGE_WHY_TOO_CLOSE : j->in_view ? CUB_JUDGE_WHY_IN_VIEW : CUB_JUDGE_WHY_OUT_OF_VIEW,
        .move = -1, .rep = -1, .feature = -1, .set = -1, .side = -1,
        .value = j->in_view ? CUB_Q16_ONE : 0,
    };
    judge_emit(j, out, &e);
}

/* Floor and standing CoG, when the desc did not fix them: the floor
 * follows the lower foot (down at once, up slowly: a jump lifts the feet
 * for a few frames only), the standing CoG height follows the CoG at 1/64
 * per frame from the first frame seen (a child enters standing). */
static void calibrate(cub_judge *j, const cub_track_skeleton *s)
{
    if (j->d.stand_cog_mm > 0) return;
    cub_q16 fl = s->joint_mm[CUB_KJ_FOOT_L].y, fr = s->joint_mm[CUB_KJ_FOOT_R].y;
    cub_q16 low = fl < fr ? fl : fr;
    if (!j->calibrated || low < j->body.floor_y_mm)
        j->body.floor_y_mm = low;
    else
        j->body.floor_y_mm += (cub_q16)(((int64_t)low - j->body.floor_y_mm) / 128);
    cub_q16 cog = cub_fuzzy_cog_height_mm(&j->body, s->joint_mm, CUB_KJ_COUNT);
    if (cog < CUB_Q16_INT(100)) cog = CUB_Q16_INT(100); /* a degenerate frame */
    if (!j->calibrated)
        j->body.stand_cog_mm = cog;
    else
        j->body.stand_cog_mm += (cub_q16)(((int64_t)cog - j->body.stand_cog_mm) / 64);
    j->calibrated = 1;
}

/* The fuzzy features of the child's pose, but the arm raise (RH, LH) read
 * along the whole arm, shoulder to wrist: the tracker places elbows least
 * well of all joints (a raised arm lost half its raise when the elbow was
 * put low), and an arm is raised as far as its wrist is, bent or not. */
static cub_err arm_aware_features(cub_judge *j, const cub_track_skeleton *skel)
{
    cub_err e = cub_fuzzy_features(&j->body, skel->joint_mm, CUB_KJ_COUNT, &j->last);
    if (e) return e;
    cub_fuzzy_body whole_arm = j->body;
    whole_arm.elbow[0] = j->body.wrist[0];
    whole_arm.elbow[1] = j->body.wrist[1];
    cub_fuzzy_frame raise;
    if (cub_fuzzy_features(&whole_arm, skel->joint_mm, CUB_KJ_COUNT, &raise) == CUB_OK) {
        memcpy(j->last.mu[CUB_FUZZY_RH], raise.mu[CUB_FUZZY_RH], sizeof raise.mu[0]);
        memcpy(j->last.mu[CUB_FUZZY_LH], raise.mu[CUB_FUZZY_LH], sizeof raise.mu[0]);
    }
    return CUB_OK;
}

/* Both legs' length, hip-knee-ankle (twice the mean leg), in mm. */
static int64_t legs_mm(const cub_fuzzy_body *b, const cub_vec3 *w)
{
    int64_t legs = 0;
    for (int k = 0; k < 2; k++)
        legs += judge_dist_mm(w[b->hip[k]], w[b->knee[k]]) +
                judge_dist_mm(w[b->knee[k]], w[b->ankle[k]]);
    return legs;
}

/* mm in lengths of the legs (their mean; Q16) against a ramp: 0 at lo, 1
 * (CUB_FUZZY_ONE) at lo + span. */
static uint16_t leg_ramp(int64_t mm, int64_t legs, int64_t lo, int64_t span)
{
    if (legs <= 0 || span <= 0) return 0;
    int64_t share = mm * 2 * CUB_Q16_ONE / legs;
    if (share <= lo) return 0;
    if (share >= lo + span) return CUB_FUZZY_ONE;
    return (uint16_t)(((share - lo) * CUB_FUZZY_ONE + span / 2) / span);
}

/* How far a foot is lifted, 0..CUB_FUZZY_ONE: its ankle's height above the
 * other ankle in lengths of the legs (their mean, hip-knee-ankle), 0 at
 * kick_lift / 2 (a foot on the floor reads less: the Kinect's jitter and a
 * raised heel), 1 at 3/2 kick_lift (a kick: a straight leg swung out 30
 * degrees lifts its foot 0.13 of its length, 45 degrees 0.29). The other
 * ankle is the body's lowest point while the foot is off the floor, so the
 * floor need not be known, and a jump, which lifts both, lifts neither. */
static uint16_t foot_lift(const cub_judge *j, const cub_vec3 *w, int side)
{
    const cub_fuzzy_body *b = &j->body;
    int64_t lift = (int64_t)judge_mm(w[b->ankle[side]].y) - judge_mm(w[b->ankle[1 - side]].y);
    return leg_ramp(lift, legs_mm(b, w), j->d.kick_lift / 2, j->d.kick_lift);
}

/* Is the body over the foot it stands on while the other is out,
 * 0..CUB_FUZZY_ONE: the hip centre's offset from the standing ankle along
 * the hips' line, toward the lifted leg, in lengths of the legs; 0 at
 * -kick_lift / 2, 1 at +kick_lift / 2 (the Kinect's jitter either side
 * of the ankle). A leg held out is balanced on the other: its weight
 * shifts the pelvis toward it, never past the standing foot. A pelvis
 * beyond that foot, away from the lifted one, is on its way over it: a
 * step onto it, a throw's weight shift, the legs of a bend or a swing
 * misplaced by the Kinect. */
static uint16_t foot_balanced(const cub_judge *j, const cub_vec3 *w, int side)
{
    const cub_fuzzy_body *b = &j->body;
    cub_vec3 hs = w[b->hip[side]], ho = w[b->hip[1 - side]], ao = w[b->ankle[1 - side]];
    cub_vec3 hc = w[b->hip_centre];
    int64_t hips = judge_dist_mm(hs, ho);
    if (hips <= 0) return 0;
    int64_t along = ((int64_t)judge_mm(hs.x) - judge_mm(ho.x)) * (judge_mm(hc.x) - judge_mm(ao.x)) +
                    ((int64_t)judge_mm(hs.y) - judge_mm(ho.y)) * (judge_mm(hc.y) - judge_mm(ao.y)) +
                    ((int64_t)judge_mm(hs.z) - judge_mm(ho.z)) * (judge_mm(hc.z) - judge_mm(ao.z));
    return leg_ramp(along / hips, legs_mm(b, w), -j->d.kick_lift / 2, j->d.kick_lift);
}

/* A leg is out only as far as its foot is lifted and the body balanced
 * on the other (cub/judge.h): the outward membership capped by both.
 * Inward is left as it is. */
static void lifted_legs(cub_judge *j, const cub_track_skeleton *skel)
{
    static const int32_t feature[2] = {CUB_FUZZY_LF, CUB_FUZZY_RF}; /* body side 0 left */
    for (int side = 0; side < 2; side++) {
        uint16_t lift = foot_lift(j, skel->joint_mm, side);
        uint16_t balanced = foot_balanced(j, skel->joint_mm, side);
        uint16_t *out = &j->last.mu[feature[side]][1];
        if (lift < *out) *out = lift;
        if (balanced < *out) *out = balanced;
    }
}

/* The joints each feature reads (the fuzzy body's, Kinect indices). */
static uint32_t feature_joints(const cub_fuzzy_body *b, int32_t f)
{
    int side = f == CUB_FUZZY_RH || f == CUB_FUZZY_RHE || f == CUB_FUZZY_RF || f == CUB_FUZZY_RFK;
    uint32_t m = 0;
    switch (f) {
    case CUB_FUZZY_RH:
    case CUB_FUZZY_RHE:
    case CUB_FUZZY_LH:
    case CUB_FUZZY_LHE:
        return 1u << b->shoulder[side] | 1u << b->elbow[side] | 1u << b->wrist[side];
    case CUB_FUZZY_RF:
    case CUB_FUZZY_LF: /* and the other leg's hip and ankle, the hip centre:
                          the lift and the balance are measured from them */
        return 1u << b->hip[side] | 1u << b->knee[side] | 1u << b->ankle[side] |
               1u << b->hip[1 - side] | 1u << b->ankle[1 - side] | 1u << b->hip_centre;
    case CUB_FUZZY_RFK:
    case CUB_FUZZY_LFK: return 1u << b->hip[side] | 1u << b->knee[side] | 1u << b->ankle[side];
    case CUB_FUZZY_TRUNK:
        return 1u << b->shoulder_centre | 1u << b->hip_centre | 1u << b->knee[0] | 1u << b->knee[1];
    default: /* Posture: the centre of gravity, most of it trunk and legs */
        m = 1u << b->shoulder_centre | 1u << b->hip_centre;
        for (int k = 0; k < 2; k++)
            m |= 1u << b->hip[k] | 1u << b->knee[k] | 1u << b->ankle[k];
        return m;
    }
}

/* Per feature: were all the joints it reads found (confidence > 0: the
 * tracker did not guess them), and were all confident? */
static judge_sure sure_features(const cub_judge *j, const cub_track_skeleton *skel)
{
    uint32_t found = 0, confident = 0;
    judge_sure sure = {0, 0};
    for (int k = 0; k < CUB_KJ_COUNT; k++) {
        if (skel->confidence[k] > 0) found |= 1u << k;
        if (skel->confidence[k] >= CUB_TRACK_CONFIDENT) confident |= 1u << k;
    }
    for (int32_t f = 0; f < CUB_FUZZY_FEATURE_COUNT; f++) {
        uint32_t need = feature_joints(&j->body, f);
        if ((found & need) == need) sure.found |= 1u << f;
        if ((confident & need) == need) sure.confident |= 1u << f;
    }
    return sure;
}

cub_err cub_judge_frame(cub_judge *j, int64_t t_us, const cub_track_skeleton *skel,
                        cub_judge_out *out)
{
    if (!out) return CUB_ERR_ARG;
    out->count = 0;
    if (!j || !skel) return CUB_ERR_ARG;
    if (j->have_t && t_us <= j->last_t_us) return CUB_OK;
    j->have_t = 1;
    j->last_t_us = t_us;
    int ok = skel->status == CUB_TRACK_OK;
    presence(j, t_us, skel->status, out);
    const cub_fuzzy_frame *f = NULL;
    judge_sure sure = {0, 0};
    if (ok) {
        sure = sure_features(j, skel);
        calibrate(j, skel);
        if (arm_aware_features(j, skel) == CUB_OK) {
            lifted_legs(j, skel);
            f = &j->last;
        }
        judge_gestures(j, t_us, skel, out);
    } else {
        judge_gestures_reset(j);
    }
    judge_reps_frame(j, t_us, f, &sure, skel->status == CUB_TRACK_TOO_CLOSE, out);
    return CUB_OK;
}

const cub_fuzzy_frame *cub_judge_last_features(const cub_judge *j)
{
    return j ? &j->last : NULL;
}

static const char *const why_names[] = {
    "?", "keys", "missed", "pose", "no_player", "clap", "wave", "in_view", "out_of_view", "mirror",
    "unsure", "other", "too_close",
};

const char *cub_judge_why_name(int32_t why)
{
    if (why < 1 || why >= (int32_t)(sizeof why_names / sizeof why_names[0])) return "?";
    return why_names[why];
}

/* " fix=right_arm,left_arm": the limbs a fault asks to move; "" without. */
static size_t describe_fix(cub_judge_fault f, char *buf, size_t size)
{
    uint32_t limbs = f.limbs;
    int32_t own = cub_judge_fault_limb(f);
    if (!limbs && own > CUB_JUDGE_LIMB_NONE) limbs = 1u << (own - 1);
    size_t n = 0;
    for (int32_t limb = 1; limb < CUB_JUDGE_LIMB_COUNT && n + 1 < size; limb++)
        if (limbs >> (limb - 1) & 1u)
            n += cub_log_format(buf + n, size - n, "%s%s", n ? "," : " fix=",
                                cub_judge_limb_name(limb));
    return n;
}

size_t cub_judge_describe(const cub_judge_event *e, char *buf, size_t size)
{
    if (!e || !buf || size == 0) return 0;
    const char *why = cub_judge_why_name(e->why);
    switch (e->kind) {
    case CUB_JUDGE_VERDICT: {
        const char *key = e->feature >= 0 ? cub_fuzzy_feature_name(e->feature) : "-";
        const char *set = e->feature >= 0 ? cub_fuzzy_set_name(e->feature, e->set) : "-";
        const char *what = e->why == CUB_JUDGE_WHY_POSE ? "d" : "best";
        size_t n = cub_log_format(buf, size,
                                  "verdict move=%d rep=%d result=%s why=%s key=%s=%s %s=%q",
                                  e->move, e->rep, e->ev.b ? "right" : "wrong", why, key, set,
                                  what, e->value);
        if (e->why == CUB_JUDGE_WHY_UNSURE) /* no result the coach acts on */
            return cub_log_format(buf, size,
                                  "verdict move=%d rep=%d result=unsure why=unsure key=%s=%s "
                                  "sure=%q",
                                  e->move, e->rep, key, set, e->value);
        return e->ev.b ? n : n + describe_fix(cub_judge_fault_of(e->ev.c), buf + n, size - n);
    }
    case CUB_JUDGE_CLAP:
        return cub_log_format(buf, size, "clap gap_mm=%d", (int)(e->value >> 16));
    case CUB_JUDGE_WAVE:
        return cub_log_format(buf, size, "wave hand=%s reversals=%d", e->side ? "right" : "left",
                              (int)(e->value >> 16));
    case CUB_JUDGE_PLAYER:
        return cub_log_format(buf, size, "player in_view=%d why=%s", e->ev.a, why);
    default: return cub_log_format(buf, size, "unknown kind=%d", e->kind);
    }
}

/* test_judge — the judge on synthetic skeleton sequences with exact
 * expected events: bad input first, then verdicts (on time, late by a
 * beat, too late, wrong arm, standing still, no player, one run for one
 * repetition, the expected pose), claps, waves, presence, determinism.
 * A child of 1.3 m stands 2.5 m from the camera, facing it (kinect.h camera
 * space: x right, y up, z away; the player's right at +x), 30 fps. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <stdio.h>
#include <string.h>

#include "cub/judge.h"
#include "cub/kinect.h"

#define FRAME_US 33333

static cub_vec3 mm(int x, int y, int z)
{
    return (cub_vec3){CUB_Q16_INT(x), CUB_Q16_INT(y), CUB_Q16_INT(z)};
}

/* What the child does in a frame. */
typedef struct pose {
    int bend[2];      /* elbow bent 90 degrees, forearm forward: 0 left, 1 right */
    int clap_gap;     /* > 0: hands in front of the chest, this far apart (mm) */
    int one_hand;     /* with clap_gap: the left hand still at x -300, the right moves */
    int wave_dx;      /* right hand raised above the head, shifted sideways (mm) */
    int wave_dy;      /* and up (mm) */
    int waving;       /* use wave_dx */
    int arms_up;      /* both arms straight up */
    int status;       /* cub_track_status */
    int guess_right;  /* the tracker guessed the right arm (confidence 0) */
    int right_leg;    /* the right leg out: LEG_STANCE (foot on the floor) or LEG_KICK */
    int unconfident[2]; /* the arm found, not confident (a quarter): 0 left, 1 right */
    int mirror;       /* with waving: the left hand raised too, mirrored */
    int clap_up;      /* with clap_gap: the hands one above the other at x 0 */
    int in_step;      /* with waving: the left hand raised too, moving the same way,
                         STEP_APART (520 mm from the right) or STEP_TOGETHER (100) */
    int wave_dz;      /* with waving: the right hand moved back, away from the camera
                         (mm; 0: level with the shoulder) */
} pose;

enum { LEG_DOWN, LEG_STANCE, LEG_KICK, LEG_KICK_OFF_BALANCE };
enum { STEP_NONE, STEP_APART, STEP_TOGETHER };

static cub_track_skeleton child(pose p)
{
    cub_track_skeleton s = {.status = p.status, .player_id = 1};
    cub_vec3 *j = s.joint_mm;
    const int z = 2500;
    j[CUB_KJ_HIP_CENTRE] = mm(0, 800, z);
    j[CUB_KJ_SPINE] = mm(0, 900, z);
    j[CUB_KJ_SHOULDER_CENTRE] = mm(0, 1150, z);
    j[CUB_KJ_HEAD] = mm(0, 1300, z);
    for (int side = 0; side < 2; side++) {
        int sx = side ? 1 : -1; /* the right side at +x */
        int sh = side ? CUB_KJ_SHOULDER_R : CUB_KJ_SHOULDER_L;
        int hip = side ? CUB_KJ_HIP_R : CUB_KJ_HIP_L;
        j[sh] = mm(170 * sx, 1100, z);
        j[sh + 1] = mm(190 * sx, 850, z);       /* elbow: arm hanging */
        j[sh + 2] = mm(200 * sx, 620, z);       /* wrist */
        j[sh + 3] = mm(200 * sx, 560, z);       /* hand */
        if (p.bend[side]) {
            j[sh + 2] = mm(190 * sx, 850, z - 230);
            j[sh + 3] = mm(190 * sx, 850, z - 290);
        }
        if (p.arms_up) {
            j[sh + 1] = mm(175 * sx, 1350, z);
            j[sh + 2] = mm(180 * sx, 1580, z);
            j[sh + 3] = mm(180 * sx, 1640, z);
        }
        if (p.clap_gap > 0) {
            int hx = p.one_hand ? (side ? p.clap_gap - 300 : -300) : p.clap_gap / 2 * sx;
            j[sh + 1] = mm(190 * sx, 880, z - 50);
            j[sh + 2] = mm((190 * sx + hx) / 2, 930, z - 250);
            j[sh + 3] = mm(hx, 950, z - 300);
            if (p.clap_up) j[sh + 3] = mm(0, 950 + p.clap_gap / 2 * sx, z - 300);
        }
        if (p.waving && (side == 1 || p.mirror)) {
            j[sh + 1] = mm(260 * sx, 1150, z);
            j[sh + 2] = mm((260 + p.wave_dx) * sx, 1380 + p.wave_dy, z + p.wave_dz);
            j[sh + 3] = mm((260 + p.wave_dx) * sx, 1450 + p.wave_dy, z + p.wave_dz);
        }
        if (p.waving && side == 0 && p.in_step) {
            int hx = p.wave_dx + (p.in_step == STEP_APART ? -260 : 160);
            j[sh + 1] = mm(-260, 1150, z);
            j[sh + 2] = mm(hx, 1380 + p.wave_dy, z);
            j[sh + 3] = mm(hx, 1450 + p.wave_dy, z);
        }
        j[hip] = mm(80 * sx, 780, z);
        j[hip + 1] = mm(85 * sx, 450, z);
        j[hip + 2] = mm(85 * sx, 100, z);
        j[hip + 3] = mm(85 * sx, 30, z - 80);
        if (side == 1 && p.right_leg == LEG_STANCE) { /* 24 degrees out, foot on the floor */
            j[hip + 1] = mm(232, 440, z);
            j[hip + 2] = mm(385, 100, z);
            j[hip + 3] = mm(385, 30, z - 80);
        }
        if (side == 1 && p.right_leg >= LEG_KICK) { /* 35 degrees out, straight: lifted */
            j[hip + 1] = mm(269, 510, z);
            j[hip + 2] = mm(470, 223, z);
            j[hip + 3] = mm(490, 160, z - 80);
        }
        if (side == 0 && p.right_leg == LEG_KICK_OFF_BALANCE) {
            /* the standing left foot 90 mm right of the hip centre: the
             * pelvis beyond it, away from the kick (a step across) */
            j[hip + 1] = mm(10, 450, z);
            j[hip + 2] = mm(90, 100, z);
            j[hip + 3] = mm(90, 30, z - 80);
        }
    }
    for (int k = 0; k < CUB_KJ_COUNT; k++)
        s.confidence[k] = CUB_Q16_ONE;
    for (int side = 0; side < 2; side++)
        for (int k = 1; p.unconfident[side] && k <= 3; k++)
            s.confidence[(side ? CUB_KJ_SHOULDER_R : CUB_KJ_SHOULDER_L) + k] = CUB_Q16_ONE / 4;
    for (int k = CUB_KJ_ELBOW_R; p.guess_right && k <= CUB_KJ_HAND_R; k++)
        s.confidence[k] = 0;
    return s;
}

/* ---- a judge and a recorder ------------------------------------------- */

#define MAX_REC 64

typedef struct rec {
    _Alignas(16) unsigned char mem[8192];
    cub_judge *j;
    int n;
    cub_judge_event ev[MAX_REC];
} rec;

static void rec_init(rec *r, const cub_judge_desc *d)
{
    memset(r, 0, sizeof *r);
    assert_true(cub_judge_mem_size(d) <= sizeof r->mem);
    assert_int_equal(cub_judge_init(d, r->mem, sizeof r->mem, &r->j), CUB_OK);
}

static void feed(rec *r, int frame, pose p)
{
    cub_track_skeleton s = child(p);
    cub_judge_out out;
    assert_int_equal(cub_judge_frame(r->j, (int64_t)frame * FRAME_US, &s, &out), CUB_OK);
    for (int i = 0; i < out.count; i++) {
        assert_true(r->n < MAX_REC);
        r->ev[r->n++] = out.events[i];
    }
}

static int count(const rec *r, int kind)
{
    int n = 0;
    for (int i = 0; i < r->n; i++)
        n += r->ev[i].kind == kind;
    return n;
}

static const cub_judge_event *first(const rec *r, int kind)
{
    for (int i = 0; i < r->n; i++)
        if (r->ev[i].kind == kind) return &r->ev[i];
    fail_msg("no event of kind %d", kind);
    return NULL;
}

/* The k-th event of a kind. */
static const cub_judge_event *nth(const rec *r, int kind, int k)
{
    for (int i = 0; i < r->n; i++)
        if (r->ev[i].kind == kind && k-- == 0) return &r->ev[i];
    fail_msg("no event %d of kind %d", k, kind);
    return NULL;
}

/* The k-th verdict is about repetition rep, right or not, given at frame
 * at_frame (the assertions stay on the caller's line in a failure). */
#define assert_verdict(r, k, rep_no, right, at_frame)                                                                  \
    do {                                                                                                               \
        const cub_judge_event *v_ = nth((r), CUB_JUDGE_VERDICT, (k));                                                  \
        assert_int_equal(v_->rep, (rep_no));                                                                           \
        assert_int_equal(v_->ev.b, (right));                                                                           \
        assert_int_equal(v_->ev.t_us, (int64_t)(at_frame) * FRAME_US);                                                 \
    } while (0)

/* A repetition of move 3 with key RHE=true, frames [from, to), one beat
 * of 15 frames (500 ms at 120 bpm). */
static cub_judge_rep rep_rhe(int rep, int from, int to)
{
    cub_judge_rep r = {
        .move = 3,
        .rep = rep,
        .key_count = 1,
        .keys = {{CUB_FUZZY_RHE, 1}},
        .start_us = (int64_t)from * FRAME_US,
        .end_us = (int64_t)to * FRAME_US,
        .beat_us = 15LL * FRAME_US,
    };
    return r;
}

static const pose STILL = {{0, 0}, 0, 0, 0, 0, 0, 0, CUB_TRACK_OK, 0, LEG_DOWN, {0, 0}, 0, 0, STEP_NONE, 0};

static pose bent_right(void)
{
    pose p = STILL;
    p.bend[1] = 1;
    return p;
}

/* Frames [0, n) standing still except `pose_p` in [from, to). */
static void play(rec *r, int n, int from, int to, pose pose_p)
{
    for (int f = 0; f < n; f++)
        feed(r, f, f >= from && f < to ? pose_p : STILL);
}

/* Frames [0, n): repetition a open from the start, b begun at its start
 * frame; the child's right elbow bent in the n_spans frame spans [from, to)
 * of `bent`, standing still otherwise. */
static void play_two(rec *r, cub_judge_rep a, cub_judge_rep b, int n, const int bent[][2],
                     int n_spans)
{
    assert_int_equal(cub_judge_begin_rep(r->j, &a), CUB_OK);
    for (int f = 0; f < n; f++) {
        if ((int64_t)f * FRAME_US == b.start_us)
            assert_int_equal(cub_judge_begin_rep(r->j, &b), CUB_OK);
        int in = 0;
        for (int k = 0; k < n_spans; k++)
            in |= f >= bent[k][0] && f < bent[k][1];
        feed(r, f, in ? bent_right() : STILL);
    }
}

/* ---- bad input ---------------------------------------------------------- */

static void test_bad_input_is_refused(void **state)
{
    (void)state;
    _Alignas(16) unsigned char mem[8192];
    cub_judge *j;
    assert_int_equal(cub_judge_init(NULL, NULL, sizeof mem, &j), CUB_ERR_ARG);
    assert_int_equal(cub_judge_init(NULL, mem, sizeof mem, NULL), CUB_ERR_ARG);
    assert_int_equal(cub_judge_init(NULL, mem + 1, sizeof mem - 1, &j), CUB_ERR_ARG);
    assert_int_equal(cub_judge_init(NULL, mem, 16, &j), CUB_ERR_NOMEM);
    cub_judge_desc bad = {.hold_ms = -1};
    assert_int_equal(cub_judge_init(&bad, mem, sizeof mem, &j), CUB_ERR_ARG);
    assert_int_equal(cub_judge_init(NULL, mem, sizeof mem, &j), CUB_OK);

    cub_judge_rep r = rep_rhe(0, 0, 30);
    r.keys[0].set = 2; /* RHE has two sets */
    assert_int_equal(cub_judge_begin_rep(j, &r), CUB_ERR_ARG);
    r = rep_rhe(0, 0, 30);
    r.keys[0].feature = CUB_FUZZY_FEATURE_COUNT;
    assert_int_equal(cub_judge_begin_rep(j, &r), CUB_ERR_ARG);
    r = rep_rhe(0, 0, 30);
    r.key_count = 0;
    assert_int_equal(cub_judge_begin_rep(j, &r), CUB_ERR_ARG);
    r = rep_rhe(0, 30, 30);
    assert_int_equal(cub_judge_begin_rep(j, &r), CUB_ERR_ARG);
    r = rep_rhe(0, 0, 30);
    r.beat_us = -1;
    assert_int_equal(cub_judge_begin_rep(j, &r), CUB_ERR_ARG);
    assert_int_equal(cub_judge_begin_rep(NULL, &r), CUB_ERR_ARG);
    for (int i = 0; i < CUB_JUDGE_MAX_OPEN; i++)
        assert_int_equal(cub_judge_begin_rep(j, &(cub_judge_rep){.key_count = 1, .start_us = 0,
                                                                   .end_us = 1}),
                         CUB_OK);
    r = rep_rhe(0, 0, 30);
    assert_int_equal(cub_judge_begin_rep(j, &r), CUB_ERR_FULL);
    assert_int_equal(cub_judge_cancel_reps(j), CUB_JUDGE_MAX_OPEN);

    cub_judge_out out = {.count = 5};
    cub_track_skeleton s = child(STILL);
    assert_int_equal(cub_judge_frame(j, 0, NULL, &out), CUB_ERR_ARG);
    assert_int_equal(out.count, 0);
    assert_int_equal(cub_judge_frame(NULL, 0, &s, &out), CUB_ERR_ARG);
    assert_int_equal(cub_judge_frame(j, 0, &s, NULL), CUB_ERR_ARG);
    /* A garbage skeleton (huge coordinates, unknown status) is no crash. */
    memset(&s, 0x7f, sizeof s);
    assert_int_equal(cub_judge_frame(j, 1, &s, &out), CUB_OK);
    s.status = CUB_TRACK_OK;
    assert_int_equal(cub_judge_frame(j, 2, &s, &out), CUB_OK);
    memset(&s, 0x80, sizeof s);
    s.status = CUB_TRACK_OK;
    assert_int_equal(cub_judge_frame(j, 3, &s, &out), CUB_OK);
    /* Time not moving forward: ignored. */
    assert_int_equal(cub_judge_frame(j, 3, &s, &out), CUB_OK);
    assert_int_equal(out.count, 0);
    assert_string_equal(cub_judge_why_name(99), "?");
}

/* ---- verdicts ----------------------------------------------------------- */

static void test_key_reached_on_time_is_right_at_once(void **state)
{
    (void)state;
    rec r;
    rec_init(&r, NULL);
    cub_judge_rep rep = rep_rhe(0, 0, 60);
    assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
    play(&r, 100, 20, 30, bent_right());
    assert_int_equal(count(&r, CUB_JUDGE_VERDICT), 1);
    const cub_judge_event *v = first(&r, CUB_JUDGE_VERDICT);
    assert_int_equal(v->ev.type, CUB_EV_VERDICT);
    assert_int_equal(v->ev.a, 3);
    assert_int_equal(v->ev.b, 1);
    assert_int_equal(v->why, CUB_JUDGE_WHY_KEYS);
    /* Held from frame 20; 100 ms later is frame 24 (frame 23 is 99.999 ms). */
    assert_int_equal(v->ev.t_us, 24LL * FRAME_US);
    char line[160];
    cub_judge_describe(v, line, sizeof line);
    assert_string_equal(line, "verdict move=3 rep=0 result=right why=keys key=RHE=true best=1.000");
}

static void test_child_late_by_a_beat_is_right(void **state)
{
    (void)state;
    rec r;
    rec_init(&r, NULL);
    cub_judge_rep rep = rep_rhe(0, 0, 60); /* closes at frame 75 */
    assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
    play(&r, 100, 65, 72, bent_right());
    assert_int_equal(count(&r, CUB_JUDGE_VERDICT), 1);
    const cub_judge_event *v = first(&r, CUB_JUDGE_VERDICT);
    assert_int_equal(v->ev.b, 1);
    assert_int_equal(v->ev.t_us, 69LL * FRAME_US);
}

static void test_child_later_than_a_beat_is_wrong_at_the_close(void **state)
{
    (void)state;
    rec r;
    rec_init(&r, NULL);
    cub_judge_rep rep = rep_rhe(0, 0, 60);
    assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
    play(&r, 100, 73, 90, bent_right()); /* would be held at 77 */
    assert_int_equal(count(&r, CUB_JUDGE_VERDICT), 1);
    const cub_judge_event *v = first(&r, CUB_JUDGE_VERDICT);
    assert_int_equal(v->ev.b, 0);
    assert_int_equal(v->why, CUB_JUDGE_WHY_MISSED);
    /* The window closes at 60 + 15 frames: the first frame at or past it. */
    assert_true(v->ev.t_us >= (int64_t)rep.end_us + rep.beat_us);
    assert_int_equal(v->ev.t_us, 75LL * FRAME_US);
}

static void test_wrong_arm_is_wrong_naming_the_key(void **state)
{
    (void)state;
    rec r;
    rec_init(&r, NULL);
    cub_judge_rep rep = rep_rhe(1, 0, 60);
    assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
    pose left = STILL;
    left.bend[0] = 1;
    play(&r, 100, 10, 50, left);
    assert_int_equal(count(&r, CUB_JUDGE_VERDICT), 1);
    const cub_judge_event *v = first(&r, CUB_JUDGE_VERDICT);
    assert_int_equal(v->ev.b, 0);
    assert_int_equal(v->why, CUB_JUDGE_WHY_MISSED);
    assert_int_equal(v->feature, CUB_FUZZY_RHE);
    assert_int_equal(v->set, 1);
    assert_true(v->value < CUB_Q16_HALF);
    char line[160];
    cub_judge_describe(v, line, sizeof line);
    assert_non_null(strstr(line, "verdict move=3 rep=1 result=wrong why=missed key=RHE=true"));
}

static void test_standing_still_is_wrong(void **state)
{
    (void)state;
    rec r;
    rec_init(&r, NULL);
    cub_judge_rep rep = rep_rhe(0, 0, 60);
    assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
    play(&r, 100, 0, 0, STILL);
    assert_int_equal(count(&r, CUB_JUDGE_VERDICT), 1);
    assert_int_equal(first(&r, CUB_JUDGE_VERDICT)->ev.b, 0);
    assert_int_equal(first(&r, CUB_JUDGE_VERDICT)->why, CUB_JUDGE_WHY_MISSED);
}

/* A fresh judge (d, or the defaults) with a repetition keyed RF = outward
 * over frames [0, 60), the child's right leg as `leg` in frames [20, 40):
 * the repetition's one verdict (1 right, 0 wrong), at frame *at. */
static int leg_out_verdict(const cub_judge_desc *d, int leg, int *at)
{
    cub_judge_rep rep = rep_rhe(0, 0, 60);
    rep.keys[0] = (cub_judge_key){CUB_FUZZY_RF, 1};
    pose p = STILL;
    p.right_leg = leg;
    rec r;
    rec_init(&r, d);
    assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
    play(&r, 100, 20, 40, p);
    assert_int_equal(count(&r, CUB_JUDGE_VERDICT), 1);
    *at = (int)(first(&r, CUB_JUDGE_VERDICT)->ev.t_us / FRAME_US);
    return first(&r, CUB_JUDGE_VERDICT)->ev.b;
}

/* The leg-out key needs the foot lifted: a foot out on the floor (a wide
 * stance) reads out by its angle alone, but is no kick. */
static void test_leg_out_needs_the_foot_lifted(void **state)
{
    (void)state;
    int at;
    assert_int_equal(leg_out_verdict(NULL, LEG_STANCE, &at), 0);
    assert_int_equal(leg_out_verdict(NULL, LEG_KICK, &at), 1);
    assert_int_equal(at, 24);
    /* the lift is what decides: the same kick (its foot 0.18 of the leg up)
     * is no kick when a kick must lift it 0.35 */
    cub_judge_desc d = {.kick_lift = CUB_Q16_ONE * 35 / 100};
    assert_int_equal(leg_out_verdict(&d, LEG_KICK, &at), 0);
}

/* The right leg's outward membership in the last of 30 frames, `leg` from
 * frame 10 on. */
static uint16_t leg_out_mu(int leg)
{
    pose p = STILL;
    p.right_leg = leg;
    rec r;
    rec_init(&r, NULL);
    play(&r, 30, 10, 30, p);
    return cub_judge_last_features(r.j)->mu[CUB_FUZZY_RF][1];
}

/* A leg held out is balanced on the other foot: the same kick with the
 * pelvis past the standing foot, away from the kick (a step across onto
 * it, a throw's weight shift), is no kick, and its feature reads 0. */
static void test_leg_out_is_balanced_on_the_other_foot(void **state)
{
    (void)state;
    int at;
    assert_int_equal(leg_out_verdict(NULL, LEG_KICK_OFF_BALANCE, &at), 0);
    assert_true(leg_out_mu(LEG_KICK) >= CUB_FUZZY_ONE / 2);
    assert_int_equal(leg_out_mu(LEG_KICK_OFF_BALANCE), 0);
}

/* ---- early verdicts, from the coach's key moment ------------------------ */

/* rep_rhe with the bear's key moment key_frames after the start. */
static cub_judge_rep rep_rhe_keyed(int rep, int from, int to, int key_frames, int mirror)
{
    cub_judge_rep r = rep_rhe(rep, from, to);
    r.has_key = 1;
    r.key_us = (int64_t)key_frames * FRAME_US;
    r.mirror_wrong = mirror;
    return r;
}

/* A fresh judge (defaults) with rep_rhe_keyed(0, 0, 60, key_frames, 0) open. */
static void start_keyed(rec *r, int key_frames)
{
    rec_init(r, NULL);
    cub_judge_rep rep = rep_rhe_keyed(0, 0, 60, key_frames, 0);
    assert_int_equal(cub_judge_begin_rep(r->j, &rep), CUB_OK);
}

static void test_standing_still_is_wrong_a_lag_after_the_key(void **state)
{
    (void)state;
    rec r;
    rec_init(&r, NULL);
    cub_judge_rep rep = rep_rhe_keyed(0, 0, 60, 20, 0);
    assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
    play(&r, 100, 0, 0, STILL);
    assert_int_equal(count(&r, CUB_JUDGE_VERDICT), 1);
    /* key at 20 frames + the lag's 500 ms: wrong in frame 36 (the first at
     * or past 1.1667 s), not at the close (75) */
    assert_verdict(&r, 0, 0, 0, 36);
    assert_int_equal(first(&r, CUB_JUDGE_VERDICT)->why, CUB_JUDGE_WHY_MISSED);
}

static void test_child_a_beat_late_is_still_right(void **state)
{
    (void)state;
    rec r;
    rec_init(&r, NULL);
    cub_judge_rep rep = rep_rhe_keyed(0, 0, 60, 20, 0);
    assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
    /* reached at 34 (14 frames late), held at 38: the sign before the
     * deadline (36) leaves it the window's whole time */
    play(&r, 100, 34, 45, bent_right());
    assert_int_equal(count(&r, CUB_JUDGE_VERDICT), 1);
    assert_verdict(&r, 0, 0, 1, 38);
}

static void test_lag_is_a_tunable(void **state)
{
    (void)state;
    rec r;
    cub_judge_desc d = {.lag_ms = 1000}; /* 30 frames */
    rec_init(&r, &d);
    cub_judge_rep rep = rep_rhe_keyed(0, 0, 60, 20, 0);
    assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
    play(&r, 100, 0, 0, STILL);
    assert_verdict(&r, 0, 0, 0, 51); /* 20 frames + 1 s is past frame 50 (frames of 33333 us) */
    d.lag_ms = -1;
    _Alignas(16) unsigned char mem[8192];
    cub_judge *j;
    assert_int_equal(cub_judge_init(&d, mem, sizeof mem, &j), CUB_ERR_ARG);
}

/* A key the bear shows from its clip's start: the deadline is the lag plus
 * sign_ms (250 ms), the child's time to show it; a sign in that time (the
 * elbow bent again after a punch) is enough. */
static void test_early_deadline_leaves_time_for_a_sign(void **state)
{
    (void)state;
    for (int signed_ = 0; signed_ < 2; signed_++) {
        rec r;
        start_keyed(&r, 0);
        /* bent in the lag (the previous repetition's tail: no sign), and
         * for the signed child again at frames 20-21, past the lag */
        for (int f = 0; f < 100; f++)
            feed(&r, f, f < 10 || (signed_ && f >= 20 && f < 22) ? bent_right() : STILL);
        /* 500 + 250 ms: frame 23; the signed child gets the close (75) */
        assert_verdict(&r, 0, 0, 0, signed_ ? 75 : 23);
    }
    cub_judge_desc d = {.lag_ms = 33, .sign_ms = 100};
    rec r;
    rec_init(&r, &d);
    cub_judge_rep rep = rep_rhe_keyed(0, 0, 60, 0, 0);
    assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
    play(&r, 100, 0, 0, STILL);
    assert_verdict(&r, 0, 0, 0, 4); /* 33 + 100 ms: frame 4 (133.3 ms) */
}

static void test_mirrored_key_is_wrong_at_once(void **state)
{
    (void)state;
    rec r;
    rec_init(&r, NULL);
    cub_judge_rep rep = rep_rhe_keyed(0, 0, 60, 40, 1);
    assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
    pose left = STILL;
    left.bend[0] = 1;
    play(&r, 100, 5, 60, left);
    assert_int_equal(count(&r, CUB_JUDGE_VERDICT), 1);
    /* held from 5, but not in the child's lag (500 ms): wrong at 16, long
     * before the key's deadline (56) */
    assert_verdict(&r, 0, 0, 0, 16);
    const cub_judge_event *v = first(&r, CUB_JUDGE_VERDICT);
    assert_int_equal(v->why, CUB_JUDGE_WHY_MIRROR);
    char line[160];
    cub_judge_describe(v, line, sizeof line);
    assert_non_null(strstr(line, "result=wrong why=mirror key=RHE=true"));
    /* without mirror_wrong (a clip that shows both sides) it waits for the deadline */
    rec_init(&r, NULL);
    rep = rep_rhe_keyed(0, 0, 60, 40, 0);
    assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
    play(&r, 100, 5, 60, left);
    assert_verdict(&r, 0, 0, 0, 56);
}

/* ---- what a wrong verdict says to fix ------------------------------------ */

static void assert_fault(const cub_judge_event *v, int32_t how, int32_t feature, int32_t set)
{
    cub_judge_fault f = cub_judge_fault_of(v->ev.c);
    assert_int_equal(f.how, how);
    assert_int_equal(f.feature, feature);
    assert_int_equal(f.set, set);
}

/* Another move's keys (both arms up) held instead of this one's (the right
 * elbow bent), which the bear's clip never shows: wrong once they have
 * been held sign_ms past the lag, long before the key's deadline; not when
 * the child showed this move's keys first, nor when nobody said they are
 * another move's. */
static void test_another_moves_keys_held_are_wrong_at_once(void **state)
{
    (void)state;
    pose up = STILL;
    up.arms_up = 1;
    for (int c = 0; c < 3; c++) {
        rec r;
        rec_init(&r, NULL);
        cub_judge_rep rep = rep_rhe_keyed(0, 0, 60, 40, 0);
        if (c != 2) {
            rep.other_count = 1;
            rep.other[0] = (cub_judge_keyset){2, {{CUB_FUZZY_RH, 2}, {CUB_FUZZY_LH, 2}}};
        }
        assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
        for (int f = 0; f < 100; f++)
            feed(&r, f, c == 1 && f >= 16 && f < 18 ? bent_right() : f < 60 ? up : STILL);
        assert_int_equal(count(&r, CUB_JUDGE_VERDICT), 1);
        const cub_judge_event *v = first(&r, CUB_JUDGE_VERDICT);
        /* 500 + 250 ms: frame 23; the key's deadline 1333 + 500 ms: 56;
         * the signed child waits for the close (75) */
        assert_verdict(&r, 0, 0, 0, c == 0 ? 23 : c == 1 ? 75 : 56);
        assert_int_equal(v->why, c == 0 ? CUB_JUDGE_WHY_OTHER : CUB_JUDGE_WHY_MISSED);
        if (c == 0) {
            assert_fault(v, CUB_JUDGE_HOW_MISSED, CUB_FUZZY_RHE, 1);
            char line[192];
            cub_judge_describe(v, line, sizeof line);
            assert_non_null(strstr(line, "result=wrong why=other key=RHE=true"));
        }
    }
    /* a bad set among the others is refused */
    rec r;
    rec_init(&r, NULL);
    cub_judge_rep bad = rep_rhe_keyed(0, 0, 60, 40, 0);
    bad.other_count = 1;
    bad.other[0] = (cub_judge_keyset){1, {{CUB_FUZZY_RH, 7}}};
    assert_int_equal(cub_judge_begin_rep(r.j, &bad), CUB_ERR_ARG);
    bad.other_count = CUB_JUDGE_MAX_OTHER + 1;
    assert_int_equal(cub_judge_begin_rep(r.j, &bad), CUB_ERR_ARG);
}

/* Standing still past the key's moment: missed RHE=true, the right arm to
 * move; the line says so by one field added at its end. */
static void test_missed_key_is_the_fault(void **state)
{
    (void)state;
    rec r;
    rec_init(&r, NULL);
    cub_judge_rep rep = rep_rhe_keyed(0, 0, 60, 20, 1);
    assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
    play(&r, 100, 0, 0, STILL);
    const cub_judge_event *v = first(&r, CUB_JUDGE_VERDICT);
    assert_int_equal(v->ev.c, 1111); /* the right arm (1), missed (1), RHE (1), true (1) */
    assert_fault(v, CUB_JUDGE_HOW_MISSED, CUB_FUZZY_RHE, 1);
    assert_int_equal(cub_judge_fault_limb(cub_judge_fault_of(v->ev.c)), CUB_JUDGE_LIMB_RIGHT_ARM);
    char line[192];
    cub_judge_describe(v, line, sizeof line);
    assert_string_equal(line,
                        "verdict move=3 rep=0 result=wrong why=missed key=RHE=true best=0.000 "
                        "fix=right_arm");
}

/* Both elbows to bend (a clap): the limbs to move are the arms whose key
 * never came; when each came alone but never together, both. */
static void test_missed_fault_marks_the_limbs_that_never_came(void **state)
{
    (void)state;
    static const struct {
        int right_from, right_to, left_from, left_to;
        uint32_t limbs;
        const char *fix;
    } cases[] = {
        {0, 0, 0, 0, 3u, " fix=right_arm,left_arm"},    /* standing still */
        {5, 60, 0, 0, 2u, " fix=left_arm"},             /* the right arm only */
        {5, 15, 20, 30, 3u, " fix=right_arm,left_arm"}, /* one after the other */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        rec r;
        rec_init(&r, NULL);
        cub_judge_rep rep = rep_rhe_keyed(0, 0, 60, 20, 0);
        rep.key_count = 2;
        rep.keys[1] = (cub_judge_key){CUB_FUZZY_LHE, 1};
        assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
        for (int f = 0; f < 100; f++) {
            pose p = STILL;
            p.bend[1] = f >= cases[i].right_from && f < cases[i].right_to;
            p.bend[0] = f >= cases[i].left_from && f < cases[i].left_to;
            feed(&r, f, p);
        }
        const cub_judge_event *v = first(&r, CUB_JUDGE_VERDICT);
        assert_int_equal(v->ev.b, 0);
        cub_judge_fault fault = cub_judge_fault_of(v->ev.c);
        assert_int_equal(fault.how, CUB_JUDGE_HOW_MISSED);
        assert_int_equal(fault.limbs, cases[i].limbs);
        char line[192];
        cub_judge_describe(v, line, sizeof line);
        printf("judge: case %zu: %s\n", i, line);
        const char *fix = strstr(line, " fix=");
        assert_non_null(fix);
        assert_string_equal(fix, cases[i].fix);
        uint32_t joints = cub_judge_fault_joints(fault);
        assert_int_equal((joints >> CUB_KJ_ELBOW_L) & 1u, (cases[i].limbs >> 1) & 1u);
        assert_int_equal((joints >> CUB_KJ_ELBOW_R) & 1u, cases[i].limbs & 1u);
    }
}

/* The left arm did the right arm's key: mirror RHE=true, the right arm
 * (the side that should have moved) to mark; a key with no other side
 * (Posture) is never the one named for a mirror. */
static void test_mirror_fault_names_the_side_to_move(void **state)
{
    (void)state;
    rec r;
    rec_init(&r, NULL);
    cub_judge_rep rep = rep_rhe_keyed(0, 0, 60, 40, 1);
    rep.key_count = 2;
    rep.keys[0] = (cub_judge_key){CUB_FUZZY_POSTURE, 2}; /* stand: held throughout */
    rep.keys[1] = (cub_judge_key){CUB_FUZZY_RHE, 1};
    assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
    pose left = STILL;
    left.bend[0] = 1;
    play(&r, 100, 5, 60, left);
    const cub_judge_event *v = first(&r, CUB_JUDGE_VERDICT);
    assert_int_equal(v->why, CUB_JUDGE_WHY_MIRROR);
    assert_fault(v, CUB_JUDGE_HOW_MIRROR, CUB_FUZZY_RHE, 1);
    char line[192];
    cub_judge_describe(v, line, sizeof line);
    assert_non_null(strstr(line, "why=mirror key=RHE=true best="));
    assert_non_null(strstr(line, " fix=right_arm"));
    assert_null(strstr(line, "left_arm"));
    assert_int_equal(cub_judge_fault_of(v->ev.c).limbs, 1u);
}

/* Nothing one limb can fix: no fault for nobody seen, none for a right
 * verdict, and no fix= field on their lines. */
static void test_no_fault_without_a_key_to_fix(void **state)
{
    (void)state;
    rec r;
    rec_init(&r, NULL);
    cub_judge_rep rep = rep_rhe(0, 0, 60);
    assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
    pose gone = STILL;
    gone.status = CUB_TRACK_NO_PLAYER;
    play(&r, 100, 0, 100, gone);
    const cub_judge_event *v = first(&r, CUB_JUDGE_VERDICT);
    assert_int_equal(v->why, CUB_JUDGE_WHY_NO_PLAYER);
    assert_int_equal(v->ev.c, 0);
    char line[192];
    cub_judge_describe(v, line, sizeof line);
    assert_null(strstr(line, "fix="));
    rec_init(&r, NULL);
    assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
    play(&r, 100, 20, 40, bent_right());
    v = first(&r, CUB_JUDGE_VERDICT);
    assert_int_equal(v->ev.b, 1);
    assert_int_equal(v->ev.c, 0);
    cub_judge_describe(v, line, sizeof line);
    assert_null(strstr(line, "fix="));
}

/* Every valid fault survives its code; anything else is no fault. */
static void test_fault_codes_round_trip(void **state)
{
    (void)state;
    int valid = 0;
    for (uint32_t limbs = 0; limbs <= 64; limbs += 7)
        for (int32_t how = 0; how <= CUB_JUDGE_HOW_COUNT; how++)
            for (int32_t f = -1; f <= CUB_FUZZY_FEATURE_COUNT; f++)
                for (int32_t set = -1; set <= CUB_FUZZY_MAX_SETS; set++) {
                    cub_judge_fault in = {how, f, set, limbs};
                    int32_t code = cub_judge_fault_code(in);
                    int ok = how > 0 && how < CUB_JUDGE_HOW_COUNT && f >= 0 &&
                             f < CUB_FUZZY_FEATURE_COUNT && set >= 0 &&
                             set < cub_fuzzy_set_count((cub_fuzzy_feature)f) && limbs < 64;
                    assert_int_equal(code != 0, ok);
                    if (!ok) continue;
                    valid++;
                    cub_judge_fault out = cub_judge_fault_of(code);
                    assert_memory_equal(&in, &out, sizeof in);
                }
    assert_int_equal(valid, 10 * 2 * 24); /* 10 limb sets below 64, two hows of the 24 sets */
    const int32_t bad[] = {0, -211, 99, 153, 104, 300, 64111, 199, 1099};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        assert_int_equal(cub_judge_fault_of(bad[i]).how, CUB_JUDGE_HOW_NONE);
}

/* Each limb's joints are its own side's, arms and legs apart. */
static void test_limb_joints(void **state)
{
    (void)state;
    uint32_t ra = cub_judge_limb_joints(CUB_JUDGE_LIMB_RIGHT_ARM);
    uint32_t la = cub_judge_limb_joints(CUB_JUDGE_LIMB_LEFT_ARM);
    uint32_t rl = cub_judge_limb_joints(CUB_JUDGE_LIMB_RIGHT_LEG);
    uint32_t ll = cub_judge_limb_joints(CUB_JUDGE_LIMB_LEFT_LEG);
    assert_true(ra & (1u << CUB_KJ_ELBOW_R));
    assert_true(ra & (1u << CUB_KJ_HAND_R));
    assert_false(ra & (1u << CUB_KJ_ELBOW_L));
    assert_true(la & (1u << CUB_KJ_WRIST_L));
    assert_true(rl & (1u << CUB_KJ_KNEE_R));
    assert_false(rl & (1u << CUB_KJ_KNEE_L));
    assert_int_equal(ra & la, 0);
    assert_int_equal(rl & ll, 0);
    assert_int_equal((ra | la) & (rl | ll), 0);
    assert_int_equal(cub_judge_limb_joints(CUB_JUDGE_LIMB_LEGS), rl | ll);
    assert_int_equal(cub_judge_limb_joints(CUB_JUDGE_LIMB_NONE), 0);
    assert_int_equal(cub_judge_limb_joints(99), 0);
    cub_judge_fault knees = {CUB_JUDGE_HOW_MISSED, CUB_FUZZY_LFK, 0, 0};
    assert_int_equal(cub_judge_fault_limb(knees), CUB_JUDGE_LIMB_LEFT_LEG);
    cub_judge_fault jump = {CUB_JUDGE_HOW_MISSED, CUB_FUZZY_POSTURE, 3, 0};
    assert_int_equal(cub_judge_fault_limb(jump), CUB_JUDGE_LIMB_LEGS);
    assert_string_equal(cub_judge_limb_name(CUB_JUDGE_LIMB_LEFT_LEG), "left_leg");
    assert_string_equal(cub_judge_how_name(CUB_JUDGE_HOW_MIRROR), "mirror");
    assert_string_equal(cub_judge_how_name(7), "?");
}

static void test_the_previous_repetitions_tail_is_no_sign(void **state)
{
    (void)state;
    rec r;
    rec_init(&r, NULL);
    cub_judge_rep rep = rep_rhe_keyed(0, 0, 60, 20, 0);
    assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
    play(&r, 100, 0, 10, bent_right()); /* a late child ending the one before */
    assert_verdict(&r, 0, 0, 0, 36);
}

static void test_no_early_verdict_without_the_tracker(void **state)
{
    (void)state;
    rec r;
    rec_init(&r, NULL);
    cub_judge_rep rep = rep_rhe_keyed(0, 0, 60, 20, 0);
    assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
    pose lost = STILL;
    lost.status = CUB_TRACK_PARTLY_OUT;
    play(&r, 100, 30, 45, lost); /* not sure of the child around the deadline */
    assert_verdict(&r, 0, 0, 0, 45); /* the first sure frame after it */
}

/* The right arm guessed by the tracker (confidence 0) while the key is its
 * elbow: no early verdict and, at the close, unsure: logged, never posted
 * to the coach. The same arm seen is wrong early. */
static void test_guessed_keys_are_unsure(void **state)
{
    (void)state;
    for (int guessed = 0; guessed < 2; guessed++) {
        rec r;
        start_keyed(&r, 20);
        pose p = STILL;
        p.guess_right = guessed;
        play(&r, 100, 0, 100, p);
        assert_int_equal(count(&r, CUB_JUDGE_VERDICT), 1);
        const cub_judge_event *v = first(&r, CUB_JUDGE_VERDICT);
        assert_verdict(&r, 0, 0, 0, guessed ? 75 : 36);
        assert_int_equal(v->why, guessed ? CUB_JUDGE_WHY_UNSURE : CUB_JUDGE_WHY_MISSED);
        assert_int_equal(v->ev.type, guessed ? CUB_EV_NONE : CUB_EV_VERDICT);
        char line[192];
        cub_judge_describe(v, line, sizeof line);
        if (guessed)
            assert_string_equal(line, "verdict move=3 rep=0 result=unsure why=unsure "
                                      "key=RHE=true sure=0.000");
    }
    /* guessed in a few frames only (a hanging arm the tracker loses now
     * and then): the seen frames decide */
    rec r;
    start_keyed(&r, 20);
    pose p = STILL;
    p.guess_right = 1;
    for (int f = 0; f < 100; f++)
        feed(&r, f, f % 3 == 0 ? p : STILL);
    assert_verdict(&r, 0, 0, 0, 36);
    assert_int_equal(first(&r, CUB_JUDGE_VERDICT)->why, CUB_JUDGE_WHY_MISSED);
}

/* A key glimpsed (reached past the lag, not held) only where its joints
 * were not confident is no evidence either way: the close is unsure,
 * logged and never posted to the coach (a fast kick's foot the tracker
 * cannot place). Glimpsed with the joints confident, the close is wrong
 * as before. A child standing still shows no sign at all: wrong early,
 * confident or not (nothing glimpsed to be unsure of). */
static void test_unsure_repetition_is_not_corrected(void **state)
{
    (void)state;
    for (int unconfident = 0; unconfident < 2; unconfident++) {
        rec r;
        start_keyed(&r, 0);
        pose glimpse = bent_right();
        glimpse.unconfident[1] = unconfident;
        play(&r, 100, 20, 22, glimpse); /* 2 frames: a sign, not held 100 ms */
        assert_int_equal(count(&r, CUB_JUDGE_VERDICT), 1);
        assert_verdict(&r, 0, 0, 0, 75);
        const cub_judge_event *v = first(&r, CUB_JUDGE_VERDICT);
        assert_int_equal(v->why, unconfident ? CUB_JUDGE_WHY_UNSURE : CUB_JUDGE_WHY_MISSED);
        assert_int_equal(v->ev.type, unconfident ? CUB_EV_NONE : CUB_EV_VERDICT);
        assert_int_equal(v->ev.c != 0, !unconfident); /* no fault to fix when unsure */
        char line[192];
        cub_judge_describe(v, line, sizeof line);
        /* 73 of the window's 75 frames had the right arm confident */
        if (unconfident)
            assert_string_equal(line, "verdict move=3 rep=0 result=unsure why=unsure "
                                      "key=RHE=true sure=0.973");
        /* standing still, the arm found but not confident: wrong early */
        start_keyed(&r, 0);
        pose still = STILL;
        still.unconfident[1] = unconfident;
        play(&r, 100, 0, 100, still);
        assert_verdict(&r, 0, 0, 0, 23);
        assert_int_equal(first(&r, CUB_JUDGE_VERDICT)->ev.type, CUB_EV_VERDICT);
    }
}

/* Joints that are not confident decide nothing: the other arm bent (the
 * mirrored keys), or another move's keys (both arms up), held with those
 * arms not confident, are no wrong verdict at once; the key's deadline
 * (the right arm confident and still: no sign of the key) decides. */
static void test_unconfident_joints_decide_nothing(void **state)
{
    (void)state;
    for (int unconfident = 0; unconfident < 2; unconfident++) {
        rec r;
        rec_init(&r, NULL);
        cub_judge_rep rep = rep_rhe_keyed(0, 0, 60, 40, 1);
        assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
        pose left = STILL;
        left.bend[0] = 1;
        left.unconfident[0] = unconfident;
        play(&r, 100, 5, 60, left);
        assert_int_equal(count(&r, CUB_JUDGE_VERDICT), 1);
        assert_verdict(&r, 0, 0, 0, unconfident ? 56 : 16);
        assert_int_equal(first(&r, CUB_JUDGE_VERDICT)->why,
                         unconfident ? CUB_JUDGE_WHY_MISSED : CUB_JUDGE_WHY_MIRROR);

        rec_init(&r, NULL);
        rep = rep_rhe_keyed(0, 0, 60, 40, 0);
        rep.other_count = 1;
        rep.other[0] = (cub_judge_keyset){2, {{CUB_FUZZY_RH, 2}, {CUB_FUZZY_LH, 2}}};
        assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
        pose up = STILL;
        up.arms_up = 1;
        up.unconfident[0] = unconfident;
        play(&r, 100, 0, 60, up);
        assert_int_equal(count(&r, CUB_JUDGE_VERDICT), 1);
        assert_verdict(&r, 0, 0, 0, unconfident ? 56 : 23);
        assert_int_equal(first(&r, CUB_JUDGE_VERDICT)->why,
                         unconfident ? CUB_JUDGE_WHY_MISSED : CUB_JUDGE_WHY_OTHER);
    }
}

static void test_mirror_keys(void **state)
{
    (void)state;
    cub_judge_key k[2] = {{CUB_FUZZY_RH, 2}, {CUB_FUZZY_LH, 2}}, m[2];
    assert_int_equal(cub_judge_mirror_keys(k, 2, m), 0); /* both arms up: its own mirror */
    cub_judge_key lean[3] = {{CUB_FUZZY_TRUNK, 0}, {CUB_FUZZY_RH, 1}, {CUB_FUZZY_LH, 0}}, ml[3];
    assert_int_equal(cub_judge_mirror_keys(lean, 3, ml), 1);
    assert_int_equal(ml[0].feature, CUB_FUZZY_TRUNK);
    assert_int_equal(ml[1].feature, CUB_FUZZY_LH);
    assert_int_equal(ml[1].set, 1);
    assert_int_equal(ml[2].feature, CUB_FUZZY_RH);
    assert_int_equal(ml[2].set, 0);
}

static void test_no_player_is_wrong_and_not_in_view(void **state)
{
    (void)state;
    rec r;
    rec_init(&r, NULL);
    cub_judge_rep rep = rep_rhe(0, 0, 60);
    assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
    pose gone = bent_right(); /* a skeleton the tracker does not vouch for */
    gone.status = CUB_TRACK_NO_PLAYER;
    for (int f = 0; f < 100; f++)
        feed(&r, f, gone);
    assert_int_equal(r.n, 1);
    const cub_judge_event *v = first(&r, CUB_JUDGE_VERDICT);
    assert_int_equal(v->ev.b, 0);
    assert_int_equal(v->why, CUB_JUDGE_WHY_NO_PLAYER);
    assert_int_equal(count(&r, CUB_JUDGE_PLAYER), 0);
}

/* A late child's pose in the next repetition's first beat counts for the
 * late one only; the next needs the keys reached again. */
static void test_one_run_credits_one_repetition(void **state)
{
    (void)state;
    for (int again = 0; again < 2; again++) {
        rec r;
        rec_init(&r, NULL);
        const int bent[][2] = {{62, 80}, {100, 110}};
        play_two(&r, rep_rhe(0, 0, 60), rep_rhe(1, 60, 120), 160, bent, again ? 2 : 1);
        assert_int_equal(count(&r, CUB_JUDGE_VERDICT), 2);
        assert_verdict(&r, 0, 0, 1, 66);
        assert_verdict(&r, 1, 1, again, again ? 104 : 135);
    }
}

/* A pose held on (a sway, a stance) counts for every repetition it is
 * held through: a beat into the next repetition the credit is renewed. */
static void test_a_pose_held_on_counts_for_each_repetition(void **state)
{
    (void)state;
    rec r;
    rec_init(&r, NULL);
    cub_judge_rep a = rep_rhe(0, 0, 60), b = rep_rhe(1, 60, 120), c = rep_rhe(2, 120, 180);
    assert_int_equal(cub_judge_begin_rep(r.j, &a), CUB_OK);
    for (int f = 0; f < 220; f++) {
        if (f == 60) assert_int_equal(cub_judge_begin_rep(r.j, &b), CUB_OK);
        if (f == 120) assert_int_equal(cub_judge_begin_rep(r.j, &c), CUB_OK);
        feed(&r, f, f >= 10 ? bent_right() : STILL);
    }
    assert_int_equal(count(&r, CUB_JUDGE_VERDICT), 3);
    for (int k = 0; k < 3; k++) {
        const cub_judge_event *v = nth(&r, CUB_JUDGE_VERDICT, k);
        assert_int_equal(v->rep, k);
        assert_int_equal(v->ev.b, 1);
    }
    /* Not before a beat (15 frames here) of the next repetition has passed. */
    assert_true(nth(&r, CUB_JUDGE_VERDICT, 1)->ev.t_us >= 75LL * FRAME_US);
    assert_true(nth(&r, CUB_JUDGE_VERDICT, 2)->ev.t_us >= 135LL * FRAME_US);
}

/* In a repetition's first beat a late child is still finishing the
 * previous one: a pose there that ends within the beat credits nothing new
 * (the previous repetition was right already); held on past it, it does. */
static void test_pose_in_the_first_beat_belongs_to_the_previous(void **state)
{
    (void)state;
    for (int held_on = 0; held_on < 2; held_on++) {
        rec r;
        rec_init(&r, NULL);
        const int bent[][2] = {{20, 30}, {62, held_on ? 80 : 72}};
        play_two(&r, rep_rhe(0, 0, 60), rep_rhe(1, 60, 120), 160, bent, 2);
        assert_int_equal(count(&r, CUB_JUDGE_VERDICT), 2);
        /* right once the beat (15 frames) has passed; else wrong at the close */
        assert_verdict(&r, 1, 1, held_on, held_on ? 75 : 135);
    }
}

/* A repetition ends when the next begins (the coach re-timed the clip):
 * its window closes a beat later, not a beat after its clip's length. */
static void test_next_repetition_ends_the_open_one(void **state)
{
    (void)state;
    rec r;
    rec_init(&r, NULL);
    const int bent[][2] = {{80, 90}};
    play_two(&r, rep_rhe(0, 0, 90), rep_rhe(1, 60, 120), 160, bent, 1);
    assert_int_equal(count(&r, CUB_JUDGE_VERDICT), 2);
    assert_verdict(&r, 0, 0, 0, 75); /* not 105 */
    assert_verdict(&r, 1, 1, 1, 84);
}

static void test_expected_pose_must_be_near(void **state)
{
    (void)state;
    rec r;
    rec_init(&r, NULL);
    /* The coach's pose: right elbow bent, left arm hanging. */
    play(&r, 5, 0, 5, bent_right());
    cub_fuzzy_frame expected = *cub_judge_last_features(r.j);
    cub_judge_rep rep = rep_rhe(0, 10, 70);
    rep.expected = &expected;
    assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
    /* The child bends the right elbow but with both arms raised high, both
     * forearms bent forward (the arm raise is read shoulder to wrist). */
    pose p = STILL;
    p.arms_up = 1;
    for (int f = 5; f < 100; f++) {
        cub_track_skeleton s = child(f >= 20 && f < 50 ? p : STILL);
        if (f >= 20 && f < 50) { /* bend the raised right forearm forward */
            s.joint_mm[CUB_KJ_WRIST_R] = mm(175, 1350, 2270);
            s.joint_mm[CUB_KJ_HAND_R] = mm(175, 1350, 2210);
            s.joint_mm[CUB_KJ_WRIST_L] = mm(-175, 1350, 2270);
            s.joint_mm[CUB_KJ_HAND_L] = mm(-175, 1350, 2210);
        }
        cub_judge_out out;
        assert_int_equal(cub_judge_frame(r.j, (int64_t)f * FRAME_US, &s, &out), CUB_OK);
        for (int i = 0; i < out.count; i++)
            r.ev[r.n++] = out.events[i];
    }
    const cub_judge_event *v = first(&r, CUB_JUDGE_VERDICT);
    assert_int_equal(v->ev.b, 0);
    assert_int_equal(v->why, CUB_JUDGE_WHY_POSE);
    assert_true(v->value > CUB_Q16_INT(45) / 100);

    /* The same child doing the coach's pose is right. */
    rec_init(&r, NULL);
    play(&r, 5, 0, 5, bent_right());
    assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
    for (int f = 5; f < 100; f++)
        feed(&r, f, f >= 20 && f < 50 ? bent_right() : STILL);
    assert_int_equal(first(&r, CUB_JUDGE_VERDICT)->ev.b, 1);
}

/* ---- claps, waves, presence --------------------------------------------- */

/* One clap: hands 600 mm apart, together in 4 frames, apart again. */
static int clap_gap_at(int f)
{
    static const int gap[] = {600, 450, 300, 150, 40, 30, 60, 200, 400, 600};
    return f >= 0 && f < 10 ? gap[f] : 600;
}

/* Events of one kind over 60 frames of a fresh judge, the child doing
 * at(f, variant) in frame f. */
static int events_over(int kind, pose (*at)(int f, int variant), int variant)
{
    rec r;
    rec_init(&r, NULL);
    for (int f = 0; f < 60; f++)
        feed(&r, f, at(f, variant));
    return count(&r, kind);
}

static void test_one_clap_one_event(void **state)
{
    (void)state;
    rec r;
    rec_init(&r, NULL);
    for (int f = 0; f < 40; f++) {
        pose p = STILL;
        p.clap_gap = clap_gap_at(f - 20);
        feed(&r, f, p);
    }
    assert_int_equal(count(&r, CUB_JUDGE_CLAP), 1);
    const cub_judge_event *c = first(&r, CUB_JUDGE_CLAP);
    assert_int_equal(c->ev.type, CUB_EV_CLAP);
    /* Met at 23 (150 mm < 0.55 x 340), min 30 mm at 25, apart by 85 mm at 27. */
    assert_int_equal(c->ev.t_us, 27LL * FRAME_US);
    assert_int_equal(c->value, CUB_Q16_INT(30));
    assert_int_equal(count(&r, CUB_JUDGE_WAVE), 0);
}

static void test_claps_in_a_row_and_held_hands(void **state)
{
    (void)state;
    rec r;
    rec_init(&r, NULL);
    /* Three claps 12 frames (400 ms) apart, then hands brought together and
     * held (carrying a box): no fourth. */
    for (int f = 0; f < 120; f++) {
        pose p = STILL;
        p.clap_gap = f < 36 ? clap_gap_at(f % 12) : f < 80 ? 600 : f < 84 ? 600 - (f - 80) * 150 : 40;
        feed(&r, f, p);
    }
    assert_int_equal(count(&r, CUB_JUDGE_CLAP), 3);
}

/* The clap of clap_gap_at from frame 20; one_hand: the left hand still,
 * the right brought to it. */
static pose clap_at(int f, int one_hand)
{
    pose p = STILL;
    p.clap_gap = clap_gap_at(f - 20);
    p.one_hand = one_hand;
    return p;
}

/* A hand brought to a still one (a punch across the body, a hand to a
 * held box) closes the gap as fast as a clap, but only one hand moves. */
static void test_clap_needs_both_hands(void **state)
{
    (void)state;
    assert_int_equal(events_over(CUB_JUDGE_CLAP, clap_at, 1), 0);
    assert_int_equal(events_over(CUB_JUDGE_CLAP, clap_at, 0), 1);
}

/* Hands closing from 400 mm to 30 in 12 frames (400 ms, slow = 1) or 9
 * (300 ms), from frame 10, held 4 frames, then open. */
static pose closing_at(int f, int slow)
{
    pose p = STILL;
    int k = f - 10, frames = slow ? 12 : 9;
    p.clap_gap = k < 0 ? 400 : k <= frames ? 400 - 370 * k / frames : k < frames + 4 ? 30 : 400;
    return p;
}

/* Hands that meet slowly are no clap: 400 mm closed to 30 in 400 ms is
 * 0.93 m/s, 2.7 shoulder widths (340 mm) a second, under clap_speed (3);
 * the same closing in 300 ms (3.6 widths a second) is one. */
static void test_clap_needs_a_fast_approach(void **state)
{
    (void)state;
    assert_int_equal(events_over(CUB_JUDGE_CLAP, closing_at, 1), 0);
    assert_int_equal(events_over(CUB_JUDGE_CLAP, closing_at, 0), 1);
}

/* The clap of clap_gap_at from frame 20, the hands closing sideways, or
 * (up = 1) one brought down onto the other, as on a ball to throw. */
static pose clap_up_at(int f, int up)
{
    pose p = STILL;
    p.clap_gap = clap_gap_at(f - 20);
    p.clap_up = up;
    return p;
}

/* Palms clap across the body: hands closing up and down are no clap. */
static void test_clap_closes_sideways(void **state)
{
    (void)state;
    assert_int_equal(events_over(CUB_JUDGE_CLAP, clap_up_at, 1), 0);
    assert_int_equal(events_over(CUB_JUDGE_CLAP, clap_up_at, 0), 1);
}

/* One swing out and back over the head (one reversal, 7 frames), with
 * the right hand alone (both = 0) or both hands in mirror (1), or both
 * rising twice as far as they swing out (2: arms swept up from the sides). */
static pose one_swing_at(int f, int both)
{
    static const int dx[] = {0, 60, 120, 150, 120, 60, 0};
    pose p = STILL;
    p.waving = f < 7;
    p.wave_dx = f < 7 ? dx[f] : 0;
    p.wave_dy = both == 2 ? 2 * p.wave_dx : 0;
    p.mirror = both > 0;
    return p;
}

/* A two-hand wave is one arc of both arms in mirror; one arm's single
 * swing is not a wave. */
static void test_two_hand_wave_one_arc(void **state)
{
    (void)state;
    assert_int_equal(events_over(CUB_JUDGE_WAVE, one_swing_at, 0), 0);
    assert_int_equal(events_over(CUB_JUDGE_WAVE, one_swing_at, 1), 1);
    /* the two hands' arc need not be sideways: arms swept up from the
     * sides rise as they go out, and no one-armed movement turns both */
    assert_int_equal(events_over(CUB_JUDGE_WAVE, one_swing_at, 2), 1);
}

/* Both hands over the head in one swing out and back together, the same
 * way (one reversal each): apart (variant STEP_APART), or 100 mm apart as
 * if holding one thing (STEP_TOGETHER). */
static pose in_step_at(int f, int variant)
{
    pose p = one_swing_at(f, 0);
    p.in_step = variant;
    return p;
}

/* A two-hand wave may swing both arms the same way: one arc of both hands
 * in step is one wave when they are apart, none when they move together
 * (a club, a ball held overhead). One arm alone is none (above). */
static void test_two_hand_wave_in_step(void **state)
{
    (void)state;
    assert_int_equal(events_over(CUB_JUDGE_WAVE, in_step_at, STEP_APART), 1);
    assert_int_equal(events_over(CUB_JUDGE_WAVE, in_step_at, STEP_TOGETHER), 0);
}

/* One sweep of the right arm over the head: the hand from outside its
 * shoulder across the body's midline to 190 mm left of it and back out
 * (13 frames), 200 mm in front of the shoulder (behind = 0), or first drawn
 * 100 mm behind it for 3 frames (1: a throw's wind-up). */
static pose sweep_at(int f, int behind)
{
    static const int dx[] = {0, -75, -150, -225, -300, -375, -450, -375, -300, -225, -150, -75, 0};
    pose p = STILL;
    p.waving = f < 13;
    p.wave_dx = f < 13 ? dx[f] : 0;
    p.wave_dz = behind && f < 3 ? 100 : -200;
    return p;
}

/* One arm swept out, across over the head and back out, in front of the
 * body, is a wave (a single arc; one reversal); the same sweep after
 * drawing the hand behind the shoulder is a throw's, no wave. A swing
 * that stays on its own side is none (test_wave_needs_two_reversals). */
static void test_one_arm_sweep_across_is_a_wave(void **state)
{
    (void)state;
    rec r;
    rec_init(&r, NULL);
    for (int f = 0; f < 60; f++)
        feed(&r, f, sweep_at(f, 0));
    assert_int_equal(count(&r, CUB_JUDGE_WAVE), 1);
    const cub_judge_event *w = first(&r, CUB_JUDGE_WAVE);
    assert_int_equal(w->side, 1);
    /* turned at -450 + 85 (frame 8), back outside the shoulder (hand x
     * 260 - 75 >= 170) at frame 11 */
    assert_int_equal(w->ev.t_us, 11LL * FRAME_US);
    assert_int_equal(events_over(CUB_JUDGE_WAVE, sweep_at, 1), 0);
}

/* The right hand back and forth over the head for 48 frames, 150 mm
 * across: each swing 2 frames (67 ms, variant 1: a flutter no arm makes,
 * the recoil of a hit) or 4 frames (133 ms: waving 3.75 times a second). */
static pose flutter_at(int f, int fast)
{
    static const int slow_dx[] = {0, 40, 75, 110, 150, 110, 75, 40};
    static const int fast_dx[] = {0, 75, 150, 75};
    pose p = STILL;
    p.waving = f < 48;
    p.wave_dx = fast ? fast_dx[f % 4] : slow_dx[f % 8];
    return p;
}

/* A wave's swing takes at least 80 ms (no arm waves 6 times a second). */
static void test_wave_swings_are_not_a_flutter(void **state)
{
    (void)state;
    assert_int_equal(events_over(CUB_JUDGE_WAVE, flutter_at, 1), 0);
    assert_int_equal(events_over(CUB_JUDGE_WAVE, flutter_at, 0), 1);
}

/* The right hand drawing a circle 600 mm wide for 48 frames whose lower
 * part dips below the elbow (dip = 1, as in drawing a big circle), or the
 * same circle lifted 450 mm, above the elbow all the way round. */
static pose circle_at(int f, int dip)
{
    static const int dx[] = {0, 75, 130, 150, 130, 75, 0, -75, -130, -150, -130, -75};
    pose p = STILL;
    p.waving = f < 48;
    p.wave_dx = 2 * dx[f % 12];
    p.wave_dy = 2 * dx[(f + 3) % 12] - (dip ? 150 : -300);
    return p;
}

/* A wave swings with the hand up: a hand that comes back up from below
 * starts its swings afresh, so a big circle is no wave. */
static void test_wave_restarts_after_a_dip(void **state)
{
    (void)state;
    assert_int_equal(events_over(CUB_JUDGE_WAVE, circle_at, 1), 0);
    assert_int_equal(events_over(CUB_JUDGE_WAVE, circle_at, 0), 1);
}

/* The right hand looping above the head for 36 frames: three times as far
 * up and down as across (tall = 1), or a third as far. */
static pose loop_at(int f, int tall)
{
    static const int dx[] = {0, 75, 130, 150, 130, 75, 0, -75, -130, -150, -130, -75};
    pose p = STILL;
    p.waving = f < 36;
    p.wave_dx = dx[f % 12];
    p.wave_dy = (tall ? dx[(f + 3) % 12] * 3 : dx[(f + 3) % 12] / 3) + 460;
    return p;
}

/* A tall loop (as in drawing or a throw) is no wave; the same loop
 * flattened is one. */
static void test_wave_swings_sideways(void **state)
{
    (void)state;
    assert_int_equal(events_over(CUB_JUDGE_WAVE, loop_at, 1), 0);
    assert_int_equal(events_over(CUB_JUDGE_WAVE, loop_at, 0), 1);
}

static void test_wave_needs_two_reversals(void **state)
{
    (void)state;
    static const int dx[] = {0, 60, 120, 150, 120, 60, 0, -60, -120, -150, -120, -60};
    for (int cycles = 0; cycles < 2; cycles++) {
        rec r;
        rec_init(&r, NULL);
        /* cycles 0: one swing out and back (one reversal); 1: back and forth. */
        int n = cycles ? 36 : 7;
        for (int f = 0; f < 60; f++) {
            pose p = STILL;
            p.waving = f < n;
            p.wave_dx = dx[f % 12];
            feed(&r, f, p);
        }
        assert_int_equal(count(&r, CUB_JUDGE_WAVE), cycles);
        if (cycles) {
            const cub_judge_event *w = first(&r, CUB_JUDGE_WAVE);
            assert_int_equal(w->side, 1);
            assert_int_equal(w->ev.type, CUB_EV_NONE);
            /* Out from 0 to +150, back past 150 - 85 at frame 5, out again
             * past -150 + 85 at frame 11. */
            assert_int_equal(w->ev.t_us, 11LL * FRAME_US);
        }
        assert_int_equal(count(&r, CUB_JUDGE_CLAP), 0);
    }
}

static void test_presence_hysteresis(void **state)
{
    (void)state;
    rec r;
    rec_init(&r, NULL);
    pose gone = STILL;
    gone.status = CUB_TRACK_PARTLY_OUT;
    int f = 0;
    for (; f < 4; f++)
        feed(&r, f, STILL); /* 4 OK frames: not yet */
    feed(&r, f++, gone);
    for (int k = 0; k < 5; k++)
        feed(&r, f++, STILL); /* frames 5..9: in view at the 5th */
    assert_int_equal(r.n, 1);
    assert_int_equal(r.ev[0].ev.type, CUB_EV_PLAYER);
    assert_int_equal(r.ev[0].ev.a, 1);
    assert_int_equal(r.ev[0].ev.t_us, 9LL * FRAME_US);
    for (int k = 0; k < 29; k++)
        feed(&r, f++, gone); /* a glitch shorter than 30 frames */
    feed(&r, f++, STILL);
    assert_int_equal(r.n, 1);
    for (int k = 0; k < 30; k++)
        feed(&r, f++, gone);
    assert_int_equal(r.n, 2);
    assert_int_equal(r.ev[1].ev.a, 0);
    assert_int_equal(r.ev[1].why, CUB_JUDGE_WHY_OUT_OF_VIEW);
    assert_int_equal(r.ev[1].ev.t_us, (int64_t)(f - 1) * FRAME_US);
}

/* A child too close (issue 20 point 9): out of view at once with b = 1
 * (the coach says "Step back"), and a repetition whose window saw it too
 * close gets no verdict, wrong or right (the same window without the
 * tracker is wrong: test_no_player_is_wrong_and_not_in_view). Frames the
 * tracker cannot read at all between the too-close ones do not end it. */
static void test_too_close_is_step_back_never_a_verdict(void **state)
{
    (void)state;
    rec r;
    rec_init(&r, NULL);
    pose close = bent_right(), blank = STILL;
    close.status = CUB_TRACK_TOO_CLOSE;
    blank.status = CUB_TRACK_NO_PLAYER;
    int f = 0;
    for (; f < 10; f++)
        feed(&r, f, STILL); /* in view at frame 4 */
    cub_judge_rep rep = rep_rhe(0, 10, 70);
    assert_int_equal(cub_judge_begin_rep(r.j, &rep), CUB_OK);
    for (; f < 120; f++)
        feed(&r, f, f % 4 == 3 ? blank : close);
    assert_int_equal(count(&r, CUB_JUDGE_VERDICT), 0);
    assert_int_equal(count(&r, CUB_JUDGE_PLAYER), 2);
    const cub_judge_event *e = nth(&r, CUB_JUDGE_PLAYER, 1);
    assert_int_equal(e->ev.a, 0);
    assert_int_equal(e->ev.b, 1);
    assert_int_equal(e->why, CUB_JUDGE_WHY_TOO_CLOSE);
    /* the 5th too-close frame: 10, 12, 13, 14, 16 (11 and 15 read nothing) */
    assert_int_equal(e->ev.t_us, 16LL * FRAME_US);
    /* stepping back: in view again, and judged again */
    cub_judge_rep next = rep_rhe(1, 130, 190);
    for (; f < 130; f++)
        feed(&r, f, STILL);
    assert_int_equal(cub_judge_begin_rep(r.j, &next), CUB_OK);
    for (; f < 260; f++)
        feed(&r, f, STILL);
    assert_int_equal(count(&r, CUB_JUDGE_VERDICT), 1);
    assert_int_equal(nth(&r, CUB_JUDGE_PLAYER, 2)->ev.a, 1);
}

/* ---- determinism -------------------------------------------------------- */

static void log_sink(void *user, const char *line, size_t len)
{
    char *buf = user;
    size_t have = strlen(buf);
    if (have + len + 2 < 4096) {
        memcpy(buf + have, line, len);
        buf[have + len] = '\n';
        buf[have + len + 1] = '\0';
    }
}

static void run_mixed(rec *r, char *log_text)
{
    static cub_log log;
    log = (cub_log){.sink = log_sink, .user = log_text};
    cub_judge_desc d = {.log = &log};
    rec_init(r, &d);
    for (int f = 0; f < 400; f++) {
        if (f % 60 == 0) {
            cub_judge_rep rep = rep_rhe(f / 60, f, f + 60);
            assert_int_equal(cub_judge_begin_rep(r->j, &rep), CUB_OK);
        }
        pose p = STILL;
        int phase = f % 60;
        if ((f / 60) % 2 == 0 && phase >= 30 && phase < 40) p.bend[1] = 1;
        if (f >= 200 && f < 240) p.clap_gap = clap_gap_at(f % 12);
        if (f >= 300 && f < 340) p.status = CUB_TRACK_NO_PLAYER;
        feed(r, f, p);
    }
}

static void test_same_input_same_events(void **state)
{
    (void)state;
    static rec a, b;
    static char la[4096], lb[4096];
    la[0] = lb[0] = '\0';
    run_mixed(&a, la);
    run_mixed(&b, lb);
    assert_int_equal(a.n, b.n);
    assert_true(a.n >= 8);
    assert_memory_equal(a.ev, b.ev, (size_t)a.n * sizeof a.ev[0]);
    assert_string_equal(la, lb);
    assert_non_null(strstr(la, " judge verdict move=3 rep=0 result=right why=keys"));
    assert_non_null(strstr(la, " judge verdict move=3 rep=1 result=wrong why=missed key=RHE=true"));
    assert_non_null(strstr(la, " judge clap gap_mm="));
    assert_non_null(strstr(la, " judge player in_view=1"));
    printf("judge: mixed run log (%d events):\n%s", a.n, la);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_input_is_refused),
        cmocka_unit_test(test_key_reached_on_time_is_right_at_once),
        cmocka_unit_test(test_child_late_by_a_beat_is_right),
        cmocka_unit_test(test_child_later_than_a_beat_is_wrong_at_the_close),
        cmocka_unit_test(test_wrong_arm_is_wrong_naming_the_key),
        cmocka_unit_test(test_standing_still_is_wrong),
        cmocka_unit_test(test_leg_out_needs_the_foot_lifted),
        cmocka_unit_test(test_leg_out_is_balanced_on_the_other_foot),
        cmocka_unit_test(test_two_hand_wave_in_step),
        cmocka_unit_test(test_wave_swings_are_not_a_flutter),
        cmocka_unit_test(test_one_arm_sweep_across_is_a_wave),
        cmocka_unit_test(test_standing_still_is_wrong_a_lag_after_the_key),
        cmocka_unit_test(test_child_a_beat_late_is_still_right),
        cmocka_unit_test(test_lag_is_a_tunable),
        cmocka_unit_test(test_early_deadline_leaves_time_for_a_sign),
        cmocka_unit_test(test_mirrored_key_is_wrong_at_once),
        cmocka_unit_test(test_the_previous_repetitions_tail_is_no_sign),
        cmocka_unit_test(test_no_early_verdict_without_the_tracker),
        cmocka_unit_test(test_guessed_keys_are_unsure),
        cmocka_unit_test(test_unsure_repetition_is_not_corrected),
        cmocka_unit_test(test_unconfident_joints_decide_nothing),
        cmocka_unit_test(test_another_moves_keys_held_are_wrong_at_once),
        cmocka_unit_test(test_mirror_keys),
        cmocka_unit_test(test_missed_key_is_the_fault),
        cmocka_unit_test(test_missed_fault_marks_the_limbs_that_never_came),
        cmocka_unit_test(test_mirror_fault_names_the_side_to_move),
        cmocka_unit_test(test_no_fault_without_a_key_to_fix),
        cmocka_unit_test(test_fault_codes_round_trip),
        cmocka_unit_test(test_limb_joints),
        cmocka_unit_test(test_no_player_is_wrong_and_not_in_view),
        cmocka_unit_test(test_one_run_credits_one_repetition),
        cmocka_unit_test(test_a_pose_held_on_counts_for_each_repetition),
        cmocka_unit_test(test_pose_in_the_first_beat_belongs_to_the_previous),
        cmocka_unit_test(test_next_repetition_ends_the_open_one),
        cmocka_unit_test(test_expected_pose_must_be_near),
        cmocka_unit_test(test_one_clap_one_event),
        cmocka_unit_test(test_claps_in_a_row_and_held_hands),
        cmocka_unit_test(test_clap_needs_both_hands),
        cmocka_unit_test(test_clap_needs_a_fast_approach),
        cmocka_unit_test(test_wave_swings_sideways),
        cmocka_unit_test(test_clap_closes_sideways),
        cmocka_unit_test(test_two_hand_wave_one_arc),
        cmocka_unit_test(test_wave_restarts_after_a_dip),
        cmocka_unit_test(test_wave_needs_two_reversals),
        cmocka_unit_test(test_presence_hysteresis),
        cmocka_unit_test(test_too_close_is_step_back_never_a_verdict),
        cmocka_unit_test(test_same_input_same_events),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

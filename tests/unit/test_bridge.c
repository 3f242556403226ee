/* bridge: the switch planner and the clip player on a synthetic table.
 *
 * Every synthetic frame is one number v in [0, 1]: its fuzzy features are
 * (1 - v, v) in two sets of every feature, so d(v1, v2) = |v1 - v2| exactly
 * (the weights sum to 1), and its pose turns every joint by v radians and
 * moves the root by 200 v mm, so the pose follows v smoothly. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "cub/bridge.h"

#define JOINTS 16
#define MAX_CLIPS 4
#define MAX_FRAMES 64
#define Q(x) ((cub_q16)((x) * 65536.0 + 0.5))

typedef struct synth {
    cub_skeleton skel;
    cub_clip clips[MAX_CLIPS];
    uint8_t clip_mem[MAX_CLIPS][MAX_FRAMES * (JOINTS * 16 + 16) + 64];
    cub_fuzzy_frame fuzzy[MAX_CLIPS][MAX_FRAMES];
    cub_bridge_table table;
    uint8_t table_mem[1 << 16];
    uint8_t work[1 << 14];
} synth;

static synth S;

static void make_skeleton(cub_skeleton *sk)
{
    cub_motion_skeleton_reset(sk);
    int parent = -1;
    for (int j = 0; j < JOINTS; j++) {
        char name[8] = {'j', (char)('a' + j), 0};
        cub_vec3 off = {0, CUB_Q16_INT(100), 0};
        assert_int_equal(cub_motion_skeleton_add(sk, name, parent, off, &parent), CUB_OK);
    }
}

static cub_fuzzy_body body(void)
{
    cub_fuzzy_body b = {.hip_centre = 0, .spine = -1, .shoulder_centre = 1, .head = -1,
                        .shoulder = {2, 3}, .elbow = {4, 5}, .wrist = {6, 7}, .hip = {8, 9},
                        .knee = {10, 11}, .ankle = {12, 13}, .stand_cog_mm = CUB_Q16_INT(500)};
    return b;
}

/* Frame f of clip c shows the value v. */
static void set_frame(int c, int f, double v)
{
    cub_pose pose;
    cub_motion_pose_rest(&S.skel, &pose);
    cub_vec3 axis = {0, 0, CUB_Q16_ONE};
    for (int j = 0; j < JOINTS; j++)
        pose.rot[j] = cub_fx_quat_from_axis_angle(axis, Q(v));
    pose.root_mm = (cub_vec3){Q(200 * v), 0, 0};
    assert_int_equal(cub_motion_clip_set_frame(&S.clips[c], f, &pose), CUB_OK);
    cub_fuzzy_frame *fz = &S.fuzzy[c][f];
    memset(fz, 0, sizeof *fz);
    for (int k = 0; k < CUB_FUZZY_FEATURE_COUNT; k++) {
        fz->mu[k][0] = (uint16_t)(32768 * (1 - v) + 0.5);
        fz->mu[k][1] = (uint16_t)(32768 * v + 0.5);
    }
}

typedef double (*value_fn)(int frame, int frames);

static void make_clip(int c, int frames, value_fn fn)
{
    assert_int_equal(cub_motion_clip_init(&S.clips[c], &S.skel, frames, 33333333, 0,
                                          S.clip_mem[c], sizeof S.clip_mem[c]),
                     CUB_OK);
    for (int f = 0; f < frames; f++)
        set_frame(c, f, fn(f, frames));
}

static cub_bridge_table_desc table_desc(int clips, int bridges, int links)
{
    int frames = 0;
    for (int c = 0; c < clips; c++)
        frames += S.clips[c].frame_count;
    cub_bridge_table_desc d = {.skel = &S.skel, .body = body(), .clip_count = clips,
                               .frame_total = frames, .bridge_total = bridges,
                               .link_total = links};
    return d;
}

static void init_table(int clips, int bridges, int links)
{
    cub_bridge_table_desc d = table_desc(clips, bridges, links);
    assert_true(cub_bridge_table_mem_size(&d) <= sizeof S.table_mem);
    assert_int_equal(cub_bridge_table_init(&S.table, &d, S.table_mem, sizeof S.table_mem), CUB_OK);
}

static void add(int c, const int *bridges, int count)
{
    assert_int_equal(cub_bridge_table_add_clip(&S.table, &S.clips[c], bridges, count, S.fuzzy[c]),
                     CUB_OK);
}

static double v_half(int f, int n) { return (void)f, (void)n, 0.5; }
static double v_zero(int f, int n) { return (void)f, (void)n, 0.0; }
static double v_ramp(int f, int n) { return (double)f / n; }
/* Near 0.7 around frame 10, near 0.5 in the back half, far elsewhere. */
static double v_front_back(int f, int n) { return f == 10 ? 0.7 : 2 * f >= n ? 0.5 : 1.0; }
/* Far (1) but for frame 5 (0.9) and a smooth valley down to 0.3 at 12. */
static double v_soon(int f, int n)
{
    int k = f > 12 ? f - 12 : 12 - f;
    return (void)n, f == 5 ? 0.9 : k <= 10 ? 0.3 + 0.07 * k : 1.0;
}
/* 0.3 for five frames, then 1: only its start is near 0.3. */
static double v_late(int f, int n) { return (void)n, f < 5 ? 0.3 : 1.0; }
static double v_03(int f, int n) { return (void)f, (void)n, 0.3; }
/* A way between 0 and 1: 0.2 early on, 0.8 from frame 20. */
static double v_step(int f, int n) { return (void)n, f < 20 ? 0.2 : 0.8; }
static double v_one(int f, int n) { return (void)f, (void)n, 1.0; }

/* ---- bad input --------------------------------------------------------- */

static void test_table_rejects_bad_input(void **s)
{
    (void)s;
    make_skeleton(&S.skel);
    make_clip(0, 40, v_half);
    cub_bridge_table_desc d = table_desc(1, 2, 0);
    assert_int_equal(cub_bridge_table_mem_size(NULL), 0);
    cub_bridge_table_desc bad = d;
    bad.clip_count = 0;
    assert_int_equal(cub_bridge_table_mem_size(&bad), 0);
    assert_int_equal(cub_bridge_table_init(&S.table, &bad, S.table_mem, sizeof S.table_mem),
                     CUB_ERR_ARG);
    bad = d;
    bad.body.elbow[1] = JOINTS; /* out of the skeleton */
    assert_int_equal(cub_bridge_table_init(&S.table, &bad, S.table_mem, sizeof S.table_mem),
                     CUB_ERR_ARG);
    assert_int_equal(cub_bridge_table_init(&S.table, &d, S.table_mem, 16), CUB_ERR_NOMEM);
    assert_int_equal(cub_bridge_table_init(NULL, &d, S.table_mem, sizeof S.table_mem),
                     CUB_ERR_ARG);
    assert_int_equal(cub_bridge_table_init(&S.table, &d, S.table_mem, sizeof S.table_mem), CUB_OK);

    const int unordered[] = {12, 3}, out_of_range[] = {40}, ok[] = {3, 30};
    assert_int_equal(cub_bridge_table_add_clip(&S.table, &S.clips[0], unordered, 2, NULL),
                     CUB_ERR_ARG);
    assert_int_equal(cub_bridge_table_add_clip(&S.table, &S.clips[0], out_of_range, 1, NULL),
                     CUB_ERR_ARG);
    assert_int_equal(cub_bridge_table_add_clip(&S.table, NULL, ok, 2, NULL), CUB_ERR_ARG);
    /* Not finished: the planner refuses the table. */
    cub_bridge_plan plan;
    cub_bridge_query q = {0};
    assert_int_equal(cub_bridge_plan_switch(&S.table, &q, &plan, S.work, sizeof S.work),
                     CUB_ERR_ARG);
    assert_int_equal(cub_bridge_table_finish(&S.table), CUB_ERR_RANGE);
    /* Fuzzy features computed by forward kinematics (fuzzy = NULL). */
    assert_int_equal(cub_bridge_table_add_clip(&S.table, &S.clips[0], ok, 2, NULL), CUB_OK);
    assert_int_equal(cub_bridge_table_add_clip(&S.table, &S.clips[0], ok, 2, NULL), CUB_ERR_FULL);
    cub_bridge_link not_bridge = {.a = 4, .b = 30, .back = 1, .d = Q(0.1)};
    cub_bridge_link wrong_half = {.a = 3, .b = 30, .back = 0, .d = Q(0.1)};
    cub_bridge_link good = {.a = 3, .b = 30, .back = 1, .d = Q(0.1)};
    assert_int_equal(cub_bridge_table_set_links(&S.table, 0, 0, &not_bridge, 1), CUB_ERR_ARG);
    assert_int_equal(cub_bridge_table_set_links(&S.table, 0, 0, &wrong_half, 1), CUB_ERR_ARG);
    assert_int_equal(cub_bridge_table_set_links(&S.table, 0, 1, &good, 1), CUB_ERR_ARG);
    assert_int_equal(cub_bridge_table_set_links(&S.table, 0, 0, &good, 1), CUB_ERR_FULL);
    assert_int_equal(cub_bridge_table_finish(&S.table), CUB_OK);

    q = (cub_bridge_query){.from_clip = 0, .to_clip = 1};
    assert_int_equal(cub_bridge_plan_switch(&S.table, &q, &plan, S.work, sizeof S.work),
                     CUB_ERR_ARG);
    q.to_clip = 0;
    q.pos_q16 = -1;
    assert_int_equal(cub_bridge_plan_switch(&S.table, &q, &plan, S.work, sizeof S.work),
                     CUB_ERR_ARG);
    q.pos_q16 = 0;
    assert_int_equal(cub_bridge_plan_switch(&S.table, &q, &plan, S.work, 0), CUB_ERR_NOMEM);
    assert_int_equal(cub_bridge_plan_switch(&S.table, &q, NULL, S.work, sizeof S.work),
                     CUB_ERR_ARG);

    cub_bridge_player p;
    cub_bridge_player_desc pd = {.table = &S.table, .blend_frames = 1000};
    assert_int_equal(cub_bridge_player_init(&p, &pd, S.work, sizeof S.work), CUB_ERR_ARG);
    pd.blend_frames = 0;
    assert_int_equal(cub_bridge_player_init(&p, &pd, S.work, 1), CUB_ERR_NOMEM);
    assert_int_equal(cub_bridge_player_init(&p, &pd, S.work, sizeof S.work), CUB_OK);
    int n;
    /* Nothing started yet. */
    assert_int_equal(cub_bridge_player_request(&p, 0, 0, 0, NULL), CUB_ERR_ARG);
    assert_int_equal(cub_bridge_player_advance(&p, 1000, NULL, 0, &n), CUB_ERR_ARG);
    assert_int_equal(cub_bridge_player_start(&p, 1, 0, 0, 0), CUB_ERR_ARG);
    assert_int_equal(cub_bridge_player_start(&p, 0, 40, 0, 0), CUB_ERR_ARG);
    assert_int_equal(cub_bridge_player_start(&p, 0, 0, 0, 0), CUB_OK);
    assert_int_equal(cub_bridge_player_advance(&p, -1, NULL, 0, &n), CUB_ERR_ARG);
    assert_int_equal(cub_bridge_player_advance(&p, 10, NULL, 0, NULL), CUB_ERR_ARG);
}

/* ---- the planner ------------------------------------------------------- */

/* Plans with the "soonest frame" rule, spelt out. */
static cub_bridge_plan plan_from(int from, int64_t pos_q16, int loops, int to)
{
    cub_bridge_query q = {.from_clip = from, .pos_q16 = pos_q16, .from_loops = loops, .to_clip = to,
                          .wait_cost_mm = CUB_Q16_MAX};
    cub_bridge_plan plan;
    assert_int_equal(cub_bridge_plan_switch(&S.table, &q, &plan, S.work, sizeof S.work), CUB_OK);
    return plan;
}

static void test_switch_prefers_front_half(void **s)
{
    (void)s;
    make_clip(0, 40, v_half);
    make_clip(1, 40, v_front_back);
    init_table(2, 4, 0);
    const int none[] = {0}, b[] = {10, 25, 30};
    add(0, none, 1);
    add(1, b, 3);
    assert_int_equal(cub_bridge_table_finish(&S.table), CUB_OK);
    /* Back-half frames 25 and 30 match exactly (d = 0); front frame 10 at
     * d = 0.2 still wins. */
    cub_bridge_plan plan = plan_from(0, 0, 1, 1);
    assert_int_equal(plan.step_count, 1);
    assert_int_equal(plan.step[0].via, CUB_BRIDGE_DIRECT);
    assert_int_equal(plan.step[0].to_frame, 10);
    assert_true(plan.step[0].d > Q(0.19) && plan.step[0].d < Q(0.21));
    assert_int_equal(plan.wait_frames, 0);
}

/* 0: a ramp; 1: far but for frames 5 (0.9) and 12 (0.3), both bridges;
 * 2: near 0.3 only in frames 0..4; 3: 0.3 throughout, bridge frame 10. */
static void build_soon_table(void)
{
    make_clip(0, 40, v_ramp);
    make_clip(1, 40, v_soon);
    make_clip(2, 40, v_late);
    make_clip(3, 40, v_03);
    init_table(4, 5, 0);
    const int none[] = {0}, b[] = {5, 12}, ten[] = {10};
    add(0, none, 1);
    add(1, b, 2);
    add(2, none, 1);
    add(3, ten, 1);
    assert_int_equal(cub_bridge_table_finish(&S.table), CUB_OK);
}

static void test_switch_takes_the_soonest_frame(void **s)
{
    (void)s;
    build_soon_table();
    /* From frame 2 (v = 0.05): frame 12 (v = 0.3) is within 0.4 at once;
     * the current clip would match it exactly only at frame 12. */
    cub_bridge_plan plan = plan_from(0, (int64_t)2 << 16, 1, 1);
    assert_int_equal(plan.step[0].from_frame, 2);
    assert_int_equal(plan.step[0].to_frame, 12);
    /* The default is the same rule. */
    cub_bridge_query dq = {.from_clip = 0, .pos_q16 = (int64_t)2 << 16, .from_loops = 1,
                           .to_clip = 1};
    cub_bridge_plan dp;
    assert_int_equal(cub_bridge_plan_switch(&S.table, &dq, &dp, S.work, sizeof S.work), CUB_OK);
    assert_int_equal(dp.step[0].from_frame, 2);
    /* Waiting priced at 30 mm a frame: the much closer body of frame 7
     * (v 0.175) within the 6-frame window is worth it. */
    dq.wait_cost_mm = CUB_Q16_INT(30);
    assert_int_equal(cub_bridge_plan_switch(&S.table, &dq, &dp, S.work, sizeof S.work), CUB_OK);
    assert_int_equal(dp.step[0].from_frame, 7);
    assert_int_equal(dp.step[0].to_frame, 12);
    assert_int_equal(dp.wait_frames, 5);
    /* Between frames: the next whole frame. */
    plan = plan_from(0, ((int64_t)2 << 16) + 100, 1, 1);
    assert_int_equal(plan.step[0].from_frame, 3);
    assert_int_equal(plan.step[0].at_q16, (int64_t)3 << 16);
    assert_int_equal(plan.wait_frames, 0);
    /* From frame 30 of clip 2 (v = 1) nothing is close in the 6-frame
     * window; the window widens and wraps (the clip loops) to frame 0. */
    plan = plan_from(2, (int64_t)30 << 16, 1, 3);
    assert_int_equal(plan.step_count, 1);
    assert_int_equal(plan.step[0].to_frame, 10);
    /* Frame 1 of the next pass (frame 0 starts the pass's blend). */
    assert_int_equal(plan.step[0].at_q16, (int64_t)41 << 16);
    assert_int_equal(plan.step[0].from_frame, 1);
    assert_int_equal(plan.wait_frames, 11);
    assert_true(plan.window_frames > CUB_BRIDGE_WINDOW_FRAMES);
    /* A clip that does not loop cannot wrap: no way there. */
    cub_bridge_query q = {.from_clip = 2, .pos_q16 = (int64_t)30 << 16, .to_clip = 3};
    assert_int_equal(cub_bridge_plan_switch(&S.table, &q, &plan, S.work, sizeof S.work),
                     CUB_ERR_RANGE);
}

static void build_tween_table(int with_links)
{
    make_clip(0, 40, v_zero);
    make_clip(1, 40, v_one);
    make_clip(2, 40, v_step);
    init_table(3, 4, 2);
    const int a[] = {0}, b[] = {4}, c[] = {2, 20};
    add(0, a, 1);
    add(1, b, 1);
    add(2, c, 2);
    if (with_links) {
        cub_bridge_link l = {.a = 20, .b = 4, .back = 0, .d = Q(0.2)};
        assert_int_equal(cub_bridge_table_set_links(&S.table, 2, 1, &l, 1), CUB_OK);
    }
    assert_int_equal(cub_bridge_table_finish(&S.table), CUB_OK);
}

static void test_tween_when_no_direct_link(void **s)
{
    (void)s;
    build_tween_table(1);
    cub_bridge_plan plan = plan_from(0, (int64_t)7 << 16, 1, 1);
    assert_int_equal(plan.step_count, 2);
    const cub_bridge_step *s0 = &plan.step[0], *s1 = &plan.step[1];
    assert_int_equal(s0->via, CUB_BRIDGE_TWEEN);
    assert_int_equal(s0->from_clip, 0);
    assert_int_equal(s0->from_frame, 7); /* at once: into clip 2 at frame 2 */
    assert_int_equal(s0->to_clip, 2);
    assert_int_equal(s0->to_frame, 2);
    assert_int_equal(s1->from_clip, 2);
    assert_int_equal(s1->from_frame, 20);
    assert_int_equal(s1->to_clip, 1);
    assert_int_equal(s1->to_frame, 4);
    assert_int_equal(plan.wait_frames, 0);
    assert_int_equal(plan.total_frames, 18);
}

static void test_no_link_is_a_clear_error(void **s)
{
    (void)s;
    build_tween_table(0);
    cub_bridge_query q = {.from_clip = 0, .from_loops = 1, .to_clip = 1};
    cub_bridge_plan plan;
    assert_int_equal(cub_bridge_plan_switch(&S.table, &q, &plan, S.work, sizeof S.work),
                     CUB_ERR_RANGE);
    assert_int_equal(plan.step_count, 0);
    cub_bridge_player p;
    cub_bridge_player_desc pd = {.table = &S.table};
    assert_int_equal(cub_bridge_player_init(&p, &pd, S.work, sizeof S.work), CUB_OK);
    assert_int_equal(cub_bridge_player_start(&p, 0, 3, 0, 1), CUB_OK);
    assert_int_equal(cub_bridge_player_request(&p, 1, 0, 1, NULL), CUB_ERR_RANGE);
    assert_false(cub_bridge_player_pending(&p));
    int n;
    assert_int_equal(cub_bridge_player_advance(&p, 33334, NULL, 0, &n), CUB_OK);
    assert_int_equal(p.clip, 0); /* playback went on */
}

/* A reaction that must not wait: the tween (18 frames) or no route at all
 * gives way to a direct switch beyond the threshold within reach_frames;
 * a plan that is soon enough is kept. */
static void test_reach_enters_within_its_frames(void **s)
{
    (void)s;
    for (int with_links = 1; with_links >= 0; with_links--) {
        build_tween_table(with_links);
        cub_bridge_query q = {.from_clip = 0, .pos_q16 = (int64_t)7 << 16, .from_loops = 1,
                              .to_clip = 1, .reach_frames = 5};
        cub_bridge_plan plan;
        assert_int_equal(cub_bridge_plan_switch(&S.table, &q, &plan, S.work, sizeof S.work),
                         CUB_OK);
        assert_int_equal(plan.step_count, 1);
        assert_int_equal(plan.step[0].via, CUB_BRIDGE_DIRECT);
        assert_int_equal(plan.step[0].to_clip, 1);
        assert_int_equal(plan.step[0].from_frame, 7); /* every pair is as far: the soonest */
        assert_true(plan.step[0].d >= Q(0.4));
        assert_true(plan.total_frames < 5);
    }
    build_tween_table(1);
    cub_bridge_query q = {.from_clip = 0, .pos_q16 = (int64_t)7 << 16, .from_loops = 1,
                          .to_clip = 2, .reach_frames = 5};
    cub_bridge_plan plan;
    assert_int_equal(cub_bridge_plan_switch(&S.table, &q, &plan, S.work, sizeof S.work), CUB_OK);
    assert_int_equal(plan.step[0].to_frame, 2); /* the tagged frame within the threshold */
    assert_true(plan.step[0].d < Q(0.4));
    q.reach_frames = -1;
    assert_int_equal(cub_bridge_plan_switch(&S.table, &q, &plan, S.work, sizeof S.work),
                     CUB_ERR_ARG);
}

/* Into a clip no chain belongs to (a groove): direct_only makes one
 * direct switch where the planner would tween through another clip, even
 * when the tween (18 frames) comes within reach_frames; it needs a reach. */
static void test_direct_only_never_tweens(void **s)
{
    (void)s;
    build_tween_table(1);
    cub_bridge_query q = {.from_clip = 0, .pos_q16 = (int64_t)7 << 16, .from_loops = 1,
                          .to_clip = 1, .reach_frames = 20};
    cub_bridge_plan plan;
    assert_int_equal(cub_bridge_plan_switch(&S.table, &q, &plan, S.work, sizeof S.work), CUB_OK);
    assert_int_equal(plan.step_count, 2); /* the tween is soon enough */
    q.direct_only = 1;
    assert_int_equal(cub_bridge_plan_switch(&S.table, &q, &plan, S.work, sizeof S.work), CUB_OK);
    assert_int_equal(plan.step_count, 1);
    assert_int_equal(plan.step[0].via, CUB_BRIDGE_DIRECT);
    assert_int_equal(plan.step[0].to_clip, 1);
    assert_true(plan.total_frames < 20);
    q.reach_frames = 0;
    assert_int_equal(cub_bridge_plan_switch(&S.table, &q, &plan, S.work, sizeof S.work),
                     CUB_ERR_ARG);
}

/* A clip on a clock (a groove on the music's): the switch after waiting
 * until upcoming frame k enters it at the clock's frame then, whatever
 * frame is closest by d; half a frame into the clock rounds up. */
static void test_on_clock_enters_at_the_clock_frame(void **s)
{
    (void)s;
    build_tween_table(1);
    cub_bridge_query q = {.from_clip = 0, .pos_q16 = ((int64_t)7 << 16) + 0x4000, .from_loops = 1,
                          .to_clip = 1, .reach_frames = 5, .direct_only = 1, .on_clock = 1,
                          .clock_q16 = ((int64_t)3 << 16) + 0x8000};
    cub_bridge_plan plan;
    assert_int_equal(cub_bridge_plan_switch(&S.table, &q, &plan, S.work, sizeof S.work), CUB_OK);
    assert_int_equal(plan.step_count, 1);
    assert_true(plan.wait_frames < 5);
    /* leaving at upcoming frame 8 + wait: the clock has run 0.75 + wait frames */
    const int64_t ahead_q16 = ((int64_t)(8 + plan.wait_frames) << 16) - q.pos_q16;
    assert_int_equal(plan.step[0].to_frame, (int)((q.clock_q16 + ahead_q16 + 0x8000) >> 16));
    q.clock_q16 = -((int64_t)40 << 16); /* before the clip's start: its frame 0 */
    assert_int_equal(cub_bridge_plan_switch(&S.table, &q, &plan, S.work, sizeof S.work), CUB_OK);
    assert_int_equal(plan.step[0].to_frame, 0);
    q.direct_only = 0; /* a clock needs the one direct switch */
    assert_int_equal(cub_bridge_plan_switch(&S.table, &q, &plan, S.work, sizeof S.work),
                     CUB_ERR_ARG);
}

/* ---- the player -------------------------------------------------------- */

static void test_speed_bounds(void **s)
{
    (void)s;
    build_tween_table(1);
    cub_bridge_player p;
    cub_bridge_player_desc pd = {.table = &S.table};
    assert_int_equal(cub_bridge_player_init(&p, &pd, S.work, sizeof S.work), CUB_OK);
    assert_int_equal(cub_bridge_player_start(&p, 0, 0, Q(0.2), 1), CUB_ERR_ARG);
    assert_int_equal(cub_bridge_player_start(&p, 0, 0, Q(2.5), 1), CUB_ERR_ARG);
    assert_int_equal(cub_bridge_player_start(&p, 0, 0, -CUB_Q16_ONE, 1), CUB_ERR_ARG);
    assert_int_equal(cub_bridge_player_start(&p, 0, 0, 0, 1), CUB_OK);
    assert_int_equal(p.speed_q16, CUB_Q16_ONE);
    assert_int_equal(cub_bridge_player_request(&p, 1, CUB_BRIDGE_SPEED_MAX_Q16 + 1, 1, NULL),
                     CUB_ERR_ARG);
    assert_int_equal(cub_bridge_player_set_speed(&p, CUB_BRIDGE_SPEED_MIN_Q16 - 1), CUB_ERR_ARG);
    assert_int_equal(cub_bridge_player_set_speed(&p, Q(0.7)), CUB_OK);
    /* 0.7 x: one second of time is 21 frames of clip. */
    int n;
    assert_int_equal(cub_bridge_player_advance(&p, 1000000, NULL, 0, &n), CUB_OK);
    int64_t expect = (int64_t)1000000 * 1000 * Q(0.7) / 33333333;
    assert_int_equal(p.pos_q16, expect);
}

static void test_player_switches_exactly_at_the_planned_frame(void **s)
{
    (void)s;
    build_soon_table();
    cub_bridge_player p;
    cub_bridge_player_desc pd = {.table = &S.table};
    assert_int_equal(cub_bridge_player_init(&p, &pd, S.work, sizeof S.work), CUB_OK);
    assert_int_equal(cub_bridge_player_start(&p, 2, 30, 0, 1), CUB_OK);
    cub_bridge_plan plan;
    assert_int_equal(cub_bridge_player_request(&p, 3, Q(0.5), 0, &plan), CUB_OK);
    assert_int_equal(plan.step[0].at_q16, (int64_t)41 << 16); /* 11 frames on */
    /* Advance in 7 ms steps: the switch is reported in the step that
     * crosses 366.67 ms, at that time. */
    int64_t t = 0;
    int switched = 0;
    for (int i = 0; i < 100 && !switched; i++) {
        cub_bridge_event ev[4];
        int n;
        assert_int_equal(cub_bridge_player_advance(&p, 7000, ev, 4, &n), CUB_OK);
        for (int k = 0; k < n; k++) {
            if (ev[k].type != CUB_BRIDGE_EV_SWITCH) continue;
            switched = 1;
            int64_t at_us = t + ev[k].t_us;
            assert_true(at_us >= 366665 && at_us <= 366668);
            assert_int_equal(ev[k].step.from_frame, 1);
            assert_int_equal(ev[k].step.to_frame, 10);
            assert_int_equal(ev[k].clip, 3);
            /* The rest of the step went on at the new speed from frame 10. */
            int64_t after_us = t + 7000 - at_us;
            int64_t want = ((int64_t)10 << 16) + after_us * 1000 * Q(0.5) / 33333333;
            assert_true(p.pos_q16 >= want - 2 && p.pos_q16 <= want + 2);
        }
        t += 7000;
    }
    assert_true(switched);
    assert_int_equal(p.speed_q16, Q(0.5));
    assert_false(cub_bridge_player_pending(&p));
    /* The new clip does not loop: it ends once, then holds. */
    int done = 0;
    for (int i = 0; i < 200; i++) {
        cub_bridge_event ev[4];
        int n;
        cub_bridge_player_advance(&p, 33333, ev, 4, &n);
        for (int k = 0; k < n; k++)
            done += ev[k].type == CUB_BRIDGE_EV_DONE && ev[k].clip == 3 && !ev[k].looped;
    }
    assert_int_equal(done, 1);
    assert_int_equal(p.pos_q16, (int64_t)39 << 16);
}

/* Largest joint displacement between two poses, mm. */
static double jump_mm(const cub_pose *a, const cub_pose *b)
{
    static cub_vec3 wa[CUB_MOTION_MAX_JOINTS], wb[CUB_MOTION_MAX_JOINTS];
    cub_motion_forward(&S.skel, a, wa, NULL);
    cub_motion_forward(&S.skel, b, wb, NULL);
    double best = 0;
    for (int j = 0; j < JOINTS; j++) {
        double dx = (wa[j].x - wb[j].x) / 65536.0, dy = (wa[j].y - wb[j].y) / 65536.0;
        double d = dx * dx + dy * dy;
        if (d > best) best = d;
    }
    return best;
}

/* Play a -> b across the switch in 1 ms steps; the largest joint move per
 * step (squared mm) around the switch. */
static double play_switch(cub_bridge_smooth smooth)
{
    static cub_bridge_player p;
    static cub_pose prev, cur;
    cub_bridge_player_desc pd = {.table = &S.table, .smooth = smooth};
    assert_int_equal(cub_bridge_player_init(&p, &pd, S.work, sizeof S.work), CUB_OK);
    assert_int_equal(cub_bridge_player_start(&p, 0, 2, 0, 1), CUB_OK);
    cub_bridge_plan plan;
    assert_int_equal(cub_bridge_player_request(&p, 1, 0, 1, &plan), CUB_OK);
    assert_int_equal(plan.step[0].to_frame, 12);
    assert_int_equal(cub_bridge_player_pose(&p, &prev), CUB_OK);
    double worst = 0;
    for (int i = 0; i < 400; i++) {
        int n;
        cub_bridge_player_advance(&p, 1000, NULL, 0, &n);
        assert_int_equal(cub_bridge_player_pose(&p, &cur), CUB_OK);
        double j = jump_mm(&prev, &cur);
        if (j > worst) worst = j;
        prev = cur;
    }
    return worst;
}

static void test_pose_is_continuous_at_the_switch(void **s)
{
    (void)s;
    build_soon_table();
    /* From frame 2 (v 0.05) to frame 12 (v 0.3): a naive cut turns every
     * joint by 0.25 rad at once; the smoothed ones spread it over frames. */
    double naive = play_switch(CUB_BRIDGE_SMOOTH_NONE);
    double inertial = play_switch(CUB_BRIDGE_SMOOTH_INERTIAL);
    double fade = play_switch(CUB_BRIDGE_SMOOTH_CROSSFADE);
    printf("bridge: synthetic switch largest joint move per ms naive=%.1f inertial=%.2f "
           "crossfade=%.2f mm\n",
           __builtin_sqrt(naive), __builtin_sqrt(inertial), __builtin_sqrt(fade));
    assert_true(naive > 100 * 100);        /* the cut is a real jump */
    assert_true(inertial < naive / 400.0); /* < 1/20 of it in distance */
    assert_true(fade < naive / 400.0);
}

/* The cut keeps the body's speed: clip 0 moves the root 5 mm a frame (v
 * rises 1/40 a frame), clip 1 from frame 12 moves it 14 mm a
 * frame (0.07). Right after the switch the root goes on at 5, then takes
 * up 14 as the carried velocity fades (10 frames). */
static void test_cut_keeps_the_speed_then_takes_up_the_new_one(void **s)
{
    (void)s;
    build_soon_table();
    static cub_bridge_player p;
    static cub_pose pose;
    cub_bridge_player_desc pd = {.table = &S.table};
    assert_int_equal(cub_bridge_player_init(&p, &pd, S.work, sizeof S.work), CUB_OK);
    assert_int_equal(cub_bridge_player_start(&p, 0, 2, 0, 1), CUB_OK);
    double x[1500];
    int cut = -1;
    for (int i = 0; i < 1500; i++) { /* 1 ms steps; the request after 300 */
        if (i == 300) assert_int_equal(cub_bridge_player_request(&p, 1, 0, 1, NULL), CUB_OK);
        cub_bridge_event ev[4];
        int n;
        assert_int_equal(cub_bridge_player_advance(&p, 1000, ev, 4, &n), CUB_OK);
        if (n && ev[0].type == CUB_BRIDGE_EV_SWITCH) cut = i;
        assert_int_equal(cub_bridge_player_pose(&p, &pose), CUB_OK);
        x[i] = pose.root_mm.x / 65536.0;
    }
    assert_true(cut >= 300 && cut < 400);
    const double ms_per_frame = 33.333333;
    double before = (x[cut - 1] - x[cut - 11]) / 10 * ms_per_frame;
    double after = (x[cut + 10] - x[cut]) / 10 * ms_per_frame;
    double later = (x[cut + 320] - x[cut + 280]) / 40 * ms_per_frame;
    printf("bridge: root speed before the cut %.2f, just after %.2f, 9 frames on %.2f mm/frame\n",
           before, after, later);
    assert_true(before > 4.9 && before < 5.1);
    assert_true(after > 4.5 && after < 6.0); /* not 14: the old speed goes on */
    assert_true(later > 12.0 && later < 18.0); /* the new clip's 14, the offsets nearly faded */
}

/* Play the tween 0 -> 2 -> 1 for one second in steps of step_us. */
static void play_tween(cub_bridge_player *p, void *work, size_t size, int64_t step_us,
                       int *switches)
{
    cub_bridge_player_desc pd = {.table = &S.table};
    assert_int_equal(cub_bridge_player_init(p, &pd, work, size), CUB_OK);
    assert_int_equal(cub_bridge_player_start(p, 0, 7, 0, 1), CUB_OK);
    assert_int_equal(cub_bridge_player_request(p, 1, Q(0.7), 1, NULL), CUB_OK);
    *switches = 0;
    for (int64_t t = 0; t < 1000000; t += step_us) {
        cub_bridge_event ev[4];
        int n;
        assert_int_equal(cub_bridge_player_advance(p, step_us, ev, 4, &n), CUB_OK);
        for (int k = 0; k < n; k++)
            *switches += ev[k].type == CUB_BRIDGE_EV_SWITCH;
    }
}

static void test_playback_is_deterministic(void **s)
{
    (void)s;
    build_tween_table(1);
    static cub_bridge_player a, b, c;
    static cub_pose pa, pb;
    static uint8_t work2[1 << 14], work3[1 << 14];
    int sa, sb, sc;
    play_tween(&a, S.work, sizeof S.work, 1000, &sa);
    play_tween(&b, work2, sizeof work2, 1000, &sb);
    play_tween(&c, work3, sizeof work3, 250000, &sc);
    assert_int_equal(sa, 2); /* the tween's two steps */
    assert_int_equal(sb, 2);
    assert_int_equal(sc, 2);
    assert_int_equal(a.clip, 1);
    assert_int_equal(a.pos_q16, b.pos_q16);
    cub_bridge_player_pose(&a, &pa);
    cub_bridge_player_pose(&b, &pb);
    assert_memory_equal(pa.rot, pb.rot, sizeof(cub_quat) * JOINTS);
    /* Other steps: the same place within rounding (a switch converts the
     * time left over into the new speed). */
    assert_int_equal(c.clip, 1);
    int64_t diff = c.pos_q16 - a.pos_q16;
    assert_true(diff >= -2 && diff <= 2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_table_rejects_bad_input),
        cmocka_unit_test(test_switch_prefers_front_half),
        cmocka_unit_test(test_switch_takes_the_soonest_frame),
        cmocka_unit_test(test_tween_when_no_direct_link),
        cmocka_unit_test(test_no_link_is_a_clear_error),
        cmocka_unit_test(test_reach_enters_within_its_frames),
        cmocka_unit_test(test_direct_only_never_tweens),
        cmocka_unit_test(test_on_clock_enters_at_the_clock_frame),
        cmocka_unit_test(test_speed_bounds),
        cmocka_unit_test(test_player_switches_exactly_at_the_planned_frame),
        cmocka_unit_test(test_pose_is_continuous_at_the_switch),
        cmocka_unit_test(test_cut_keeps_the_speed_then_takes_up_the_new_one),
        cmocka_unit_test(test_playback_is_deterministic),
    };
    return cmocka_run_group_tests_name("bridge", tests, NULL, NULL);
}

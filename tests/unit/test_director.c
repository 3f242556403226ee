/* director: the tick's policy on a synthetic clip library. Bad input
 * first, then how requests enter their clips (a move at its first frames,
 * a correction anywhere in its front half, the other correcting clip when
 * it is sooner), the leads, the judge's windows and the other moves they
 * look for, the music tags and clip ends the player posts, and the
 * scripted verdict's move.
 *
 * Every synthetic frame is one number v in [0, 1]: its fuzzy features are
 * (1 - v, v) in two sets of every feature, so d(v1, v2) = |v1 - v2|, and
 * its pose turns every joint by v radians. The idle clip ramps from 0 to 1
 * over its 40 frames, so from its first frame a clip near 0 is reachable
 * at once and one near 0.9 only some 20 frames later. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "cub/director.h"
#include "director_internal.h" /* director_key_moment: a window's other key sets */

#define JOINTS 16
#define FRAMES 40
#define FRAME_NS 33333333u
#define BPM 120
#define Q(x) ((cub_q16)((x) * 65536.0 + 0.5))

enum {
    C_IDLE, C_WAKE, C_WAVE, C_DOZE, C_SHAKE, C_WATCH, C_WORRIED, C_CHEER, C_CLAP, C_SWAY,
    C_COUNT
};
static const char *const names[C_COUNT] = {"idle",     "wake_up",  "wave",    "doze",
                                           "head_shake", "watch_me", "worried", "cheer",
                                           "clap",     "sway"};

/* clap: 2 reps at 0.8 from 0; a gap; sway: 2 reps at 1.0 from 5 s. */
static const cub_coach_move song[2] = {
    {.clip = C_CLAP, .reps = 2, .speed_q16 = Q(0.8), .tag_ms = 0, .span_ms = 3250},
    {.clip = C_SWAY, .reps = 2, .tag_ms = 5000, .span_ms = 4000},
};
static const cub_director_keys keys[2] = {
    {.count = 1, .key = {{.feature = CUB_FUZZY_RH, .set = 1}}},
    {.count = 1, .key = {{.feature = CUB_FUZZY_LH, .set = 1}}},
};

typedef double (*value_fn)(int frame);

static struct {
    cub_skeleton skel;
    cub_clip clips[C_COUNT];
    uint8_t clip_mem[C_COUNT][FRAMES * (JOINTS * 16 + 16) + 64];
    cub_fuzzy_frame fuzzy[C_COUNT][FRAMES];
    cub_bridge_table table;
    uint8_t table_mem[1 << 18];
    uint8_t mem[1 << 16];
    cub_event slots[64];
    cub_loop loop;
    char log[64][160];
    int lines;
    cub_log sink;
} F;

static cub_director dir;
/* Outside F: build_table clears F after the judge is made. */
static uint8_t judge_mem[1 << 16];

/* ---- the fixture ----------------------------------------------------------- */

static double v_ramp(int f) { return (double)f / FRAMES; }
static double v_zero(int f) { return (void)f, 0.0; }
static double v_high(int f) { return (void)f, 0.9; }
/* Near the ramp's start at frames 1 to 3, exactly at bridge frame 10;
 * elsewhere between (0.45: near nothing else either). */
static double v_clap(int f) { return f == 0 ? 0.9 : f < 4 ? 0.2 : f == 10 ? 0.0 : 0.45; }
/* Exactly at untagged frame 12 and at bridge frame 30, far elsewhere. */
static double v_watch(int f) { return f == 12 || f == 30 ? 0.0 : f > 30 ? 0.45 : 1.0; }

static void set_frame(int c, int f, double v)
{
    cub_pose pose;
    cub_motion_pose_rest(&F.skel, &pose);
    cub_vec3 axis = {0, 0, CUB_Q16_ONE};
    for (int j = 0; j < JOINTS; j++) pose.rot[j] = cub_fx_quat_from_axis_angle(axis, Q(v));
    assert_int_equal(cub_motion_clip_set_frame(&F.clips[c], f, &pose), CUB_OK);
    for (int k = 0; k < CUB_FUZZY_FEATURE_COUNT; k++) {
        F.fuzzy[c][f].mu[k][0] = (uint16_t)(32768 * (1 - v) + 0.5);
        F.fuzzy[c][f].mu[k][1] = (uint16_t)(32768 * v + 0.5);
    }
}

static void add_clip(int c, value_fn fn, const int *bridges, int count)
{
    assert_int_equal(cub_motion_clip_init(&F.clips[c], &F.skel, FRAMES, FRAME_NS, 0,
                                          F.clip_mem[c], sizeof F.clip_mem[c]),
                     CUB_OK);
    for (int f = 0; f < FRAMES; f++) set_frame(c, f, fn(f));
    assert_int_equal(cub_bridge_table_add_clip(&F.table, &F.clips[c], bridges, count, F.fuzzy[c]),
                     CUB_OK);
}

static void sink(void *u, const char *line, size_t len)
{
    (void)u;
    if (F.lines < 64) snprintf(F.log[F.lines++], sizeof F.log[0], "%.*s", (int)len, line);
}

static int logged(const char *needle)
{
    for (int i = 0; i < F.lines; i++)
        if (strstr(F.log[i], needle)) return 1;
    return 0;
}

/* The library: the ramp to idle on; head_shake near 0.9 (late) or 0
 * (soon); the other roles and sway far or near as noted. */
static void build_table(value_fn shake)
{
    memset(&F, 0, sizeof F);
    cub_motion_skeleton_reset(&F.skel);
    int parent = -1;
    for (int j = 0; j < JOINTS; j++) {
        char name[8] = {'j', (char)('a' + j), 0};
        assert_int_equal(cub_motion_skeleton_add(&F.skel, name, parent,
                                                 (cub_vec3){0, CUB_Q16_INT(100), 0}, &parent),
                         CUB_OK);
    }
    cub_bridge_table_desc td = {
        .skel = &F.skel, .clip_count = C_COUNT, .frame_total = C_COUNT * FRAMES,
        .bridge_total = 2 * C_COUNT, .link_total = 0,
        .body = {.hip_centre = 0, .spine = -1, .shoulder_centre = 1, .head = -1,
                 .shoulder = {2, 3}, .elbow = {4, 5}, .wrist = {6, 7}, .hip = {8, 9},
                 .knee = {10, 11}, .ankle = {12, 13}, .stand_cog_mm = CUB_Q16_INT(500)}};
    assert_true(cub_bridge_table_mem_size(&td) <= sizeof F.table_mem);
    assert_int_equal(cub_bridge_table_init(&F.table, &td, F.table_mem, sizeof F.table_mem), CUB_OK);
    const int ends[2] = {0, 20}, ten[2] = {10, 30}, thirty[2] = {5, 30};
    const value_fn fns[C_COUNT] = {v_ramp, v_zero, v_zero, v_zero, shake,
                                   v_watch, v_zero, v_zero, v_clap, v_high};
    for (int c = 0; c < C_COUNT; c++)
        add_clip(c, fns[c], c == C_CLAP ? ten : c == C_WATCH || c == C_SHAKE ? thirty : ends, 2);
    assert_int_equal(cub_bridge_table_finish(&F.table), CUB_OK);
    F.sink = (cub_log){.sink = sink};
    cub_loop_desc ld = {.queue_capacity = 64};
    assert_int_equal(cub_loop_init(&F.loop, &ld, F.slots, sizeof F.slots), CUB_OK);
}

static cub_director_desc make_desc(cub_judge *judge)
{
    cub_director_desc d = {.table = &F.table, .keys = keys, .bpm = BPM, .song_name = "test",
                           .song_length_ms = 9000, .judge = judge,
                           .coach = {.moves = song, .move_count = 2, .clip_count = C_COUNT,
                                     .clip_names = names, .log = &F.sink}};
    assert_int_equal(cub_coach_roles_by_name(names, C_COUNT, &d.coach.roles), CUB_OK);
    return d;
}

static void start(value_fn shake, cub_judge *judge)
{
    build_table(shake);
    cub_director_desc d = make_desc(judge);
    assert_true(cub_director_mem_size(&d) <= sizeof F.mem);
    assert_int_equal(cub_director_init(&dir, &d, F.mem, sizeof F.mem, 0), CUB_OK);
}

static void send(int64_t t_ms, int32_t type, int32_t a, int32_t b, int32_t music_ms)
{
    cub_event ev = {.t_us = t_ms * 1000, .type = type, .a = a, .b = b};
    assert_int_equal(cub_director_handle(&dir, &ev, music_ms), CUB_OK);
}

/* START, then the wake_up clip ends at t_ms: the dance begins (move 0). */
static void to_dance(int64_t t_ms)
{
    send(t_ms - 1000, CUB_EV_BUTTON_DOWN, CUB_BUTTON_START, 0, CUB_COACH_NO_MUSIC);
    send(t_ms, CUB_EV_CLIP_DONE, C_WAKE, 0, CUB_COACH_NO_MUSIC);
    assert_int_equal(dir.coach.state, CUB_COACH_DANCE);
}

/* Where the pending plan enters the clip it leads to. */
static const cub_bridge_step *planned_entry(void)
{
    assert_true(cub_bridge_player_pending(&dir.player));
    return &dir.player.plan.step[dir.player.plan.step_count - 1];
}

static int has_out(int32_t what)
{
    for (int i = 0; i < dir.out_count; i++)
        if (dir.out[i].what == what) return 1;
    return 0;
}

/* ---- bad input ------------------------------------------------------------ */

/* Zero tunables take the defaults; given ones are kept. */
static void test_tunables_default(void **s)
{
    (void)s;
    start(v_high, NULL);
    assert_int_equal(dir.desc.start_frames, 4);
    assert_int_equal(dir.desc.react_frames, 5);
    cub_director_desc d = make_desc(NULL);
    d.start_frames = 2;
    d.react_frames = 9;
    assert_int_equal(cub_director_init(&dir, &d, F.mem, sizeof F.mem, 0), CUB_OK);
    assert_int_equal(dir.desc.start_frames, 2);
    assert_int_equal(dir.desc.react_frames, 9);
}

static void test_bad_desc_is_refused(void **s)
{
    (void)s;
    build_table(v_high);
    cub_director_desc d = make_desc(NULL);
    assert_int_equal(cub_director_init(NULL, &d, F.mem, sizeof F.mem, 0), CUB_ERR_ARG);
    assert_int_equal(cub_director_init(&dir, NULL, F.mem, sizeof F.mem, 0), CUB_ERR_ARG);
    assert_int_equal(cub_director_mem_size(NULL), 0);
    cub_director_desc e = d;
    e.table = NULL;
    assert_int_equal(cub_director_mem_size(&e), 0);
    assert_int_equal(cub_director_init(&dir, &e, F.mem, sizeof F.mem, 0), CUB_ERR_ARG);
    e = d;
    e.coach.move_count = CUB_DIRECTOR_MAX_MOVES + 1;
    assert_int_equal(cub_director_init(&dir, &e, F.mem, sizeof F.mem, 0), CUB_ERR_ARG);
    e = d;
    e.coach.move_count = 0; /* the coach refuses a song without moves */
    assert_int_equal(cub_director_init(&dir, &e, F.mem, sizeof F.mem, 0), CUB_ERR_ARG);
    e = d;
    e.start_frames = -1;
    assert_int_equal(cub_director_init(&dir, &e, F.mem, sizeof F.mem, 0), CUB_ERR_ARG);
    e = d;
    e.react_frames = -1;
    assert_int_equal(cub_director_init(&dir, &e, F.mem, sizeof F.mem, 0), CUB_ERR_ARG);
    assert_int_equal(cub_director_init(&dir, &d, F.mem, 8, 0), CUB_ERR_NOMEM);
    assert_int_equal(cub_director_handle(NULL, &(cub_event){0}, 0), CUB_ERR_ARG);
    assert_int_equal(cub_director_tick(NULL, 0, 0), CUB_ERR_ARG);
    assert_int_equal(cub_director_advance(&dir, NULL, 0, 0), CUB_ERR_ARG);
}

/* ---- entering clips ------------------------------------------------------- */

static void test_init_plays_the_idle_clip(void **s)
{
    (void)s;
    start(v_high, NULL);
    assert_int_equal(dir.player.clip, C_IDLE);
    assert_int_equal(dir.coach.state, CUB_COACH_IDLE);
    assert_true(logged("coach request clip=idle"));
}

static void test_move_is_entered_at_its_first_frames(void **s)
{
    (void)s;
    start(v_high, NULL);
    to_dance(1000);
    assert_int_equal(dir.coach.clip, C_CLAP);
    assert_true(has_out(CUB_DIRECTOR_MUSIC_START));
    assert_true(logged("music start song=\"test\" bpm=120 length_ms=9000"));
    assert_true(logged("bridge plan to=clap"));
    const cub_bridge_step *in = planned_entry();
    assert_int_equal(in->to_clip, C_CLAP);
    assert_true(in->to_frame < dir.desc.start_frames);
    /* Left to the planner alone, the exact bridge frame 10 would win. */
    cub_bridge_query q = {.from_clip = -1, .to_clip = C_CLAP};
    cub_bridge_plan plan;
    assert_int_equal(cub_bridge_player_preview(&dir.player, &q, &plan), CUB_OK);
    assert_int_equal(plan.step[plan.step_count - 1].to_frame, 10);
}

/* head_shake (asked for first) is near 0.9: some 20 frames of the ramp
 * away; watch_me is near 0 at once. */
static void test_correction_substitutes_the_sooner_clip(void **s)
{
    (void)s;
    start(v_high, NULL);
    to_dance(1000);
    send(1500, CUB_EV_VERDICT, 0, 0, 500);
    assert_int_equal(dir.coach.state, CUB_COACH_CORRECT);
    assert_int_equal(dir.coach.clip, C_SHAKE);
    assert_true(logged("bridge substitute requested=head_shake played=watch_me reason=sooner"));
    assert_int_equal(planned_entry()->to_clip, C_WATCH);
    assert_true(dir.player.plan.total_frames <= dir.desc.react_frames);
    /* The asked clip alone would have taken longer than the reaction allows. */
    cub_bridge_query q = {.from_clip = -1, .to_clip = C_SHAKE, .start_frames = FRAMES / 2};
    cub_bridge_plan plan;
    assert_int_equal(cub_bridge_player_preview(&dir.player, &q, &plan), CUB_OK);
    assert_true(plan.total_frames > dir.desc.react_frames);
}

/* The coach hears of the substitute's end under the name it asked for. */
static void test_substitute_ends_under_the_asked_name(void **s)
{
    (void)s;
    start(v_high, NULL);
    to_dance(1000);
    send(1500, CUB_EV_VERDICT, 0, 0, 500);
    cub_event ev;
    int done = -1;
    for (int64_t t_ms = 1500; t_ms < 5000 && done < 0; t_ms += 33) {
        assert_int_equal(cub_director_advance(&dir, &F.loop, t_ms * 1000, 500), CUB_OK);
        while (cub_queue_pop(&F.loop.queue, &ev) == CUB_OK)
            if (ev.type == CUB_EV_CLIP_DONE) done = ev.a;
    }
    assert_int_equal(done, C_SHAKE);
    assert_true(logged("bridge done clip=watch_me"));
}

static void test_correction_soon_enough_is_not_substituted(void **s)
{
    (void)s;
    start(v_zero, NULL);
    to_dance(1000);
    send(1500, CUB_EV_VERDICT, 0, 0, 500);
    assert_int_equal(planned_entry()->to_clip, C_SHAKE);
    assert_false(logged("bridge substitute"));
}

/* watch_me is near 0 at untagged frame 12 and at bridge frame 30. */
static void test_correction_enters_anywhere_in_the_front_half(void **s)
{
    (void)s;
    start(v_high, NULL);
    to_dance(1000);
    send(1500, CUB_EV_VERDICT, 0, 0, 500);
    assert_int_equal(planned_entry()->to_clip, C_WATCH);
    assert_int_equal(planned_entry()->to_frame, 12);
    cub_bridge_query q = {.from_clip = -1, .to_clip = C_WATCH};
    cub_bridge_plan plan;
    assert_int_equal(cub_bridge_player_preview(&dir.player, &q, &plan), CUB_OK);
    assert_int_equal(plan.step[plan.step_count - 1].to_frame, 30);
}

/* ---- leads ----------------------------------------------------------------- */

/* The planner's route from a query, as a lead: its frames at the move's
 * speed less the content it skips; 0 without a route. */
static int32_t expected_lead(cub_bridge_query q, int m)
{
    q.to_clip = song[m].clip;
    q.start_frames = dir.desc.start_frames;
    cub_bridge_plan plan;
    if (cub_bridge_player_preview(&dir.player, &q, &plan)) return 0;
    int64_t speed = song[m].speed_q16 ? song[m].speed_q16 : CUB_Q16_ONE;
    int64_t route_ms = (int64_t)plan.total_frames * FRAME_NS / 1000000 * CUB_Q16_ONE / speed;
    int to = plan.step[plan.step_count - 1].to_frame;
    return (int32_t)(route_ms - (int64_t)song[m].span_ms / song[m].reps * to / (FRAMES - 1));
}

static void test_leads_are_the_routes_from_the_last_frame(void **s)
{
    (void)s;
    start(v_high, NULL);
    const cub_bridge_query from_clap_end = {.from_clip = C_CLAP, .pos_q16 = (FRAMES - 1) << 16};
    const cub_bridge_query from_sway_end = {.from_clip = C_SWAY, .pos_q16 = (FRAMES - 1) << 16};
    assert_int_equal(dir.moves[0].lead_ms, 0); /* nothing before the first move */
    /* clap's last frame (0.45) goes on into its frame 1 (0.2) at once: the
     * lead is the frame skipped, 1625 ms a repetition over 39 frames. */
    assert_int_equal(dir.moves[0].rep_lead_ms, -1625 / 39);
    assert_int_equal(dir.moves[0].rep_lead_ms, expected_lead(from_clap_end, 0));
    assert_int_equal(dir.moves[1].lead_ms, expected_lead(from_clap_end, 1));
    assert_int_equal(dir.moves[1].rep_lead_ms, expected_lead(from_sway_end, 1));
    char line[96];
    snprintf(line, sizeof line, "music lead move=1 clip=sway lead_ms=%d rep_lead_ms=%d",
             dir.moves[1].lead_ms, dir.moves[1].rep_lead_ms);
    assert_true(logged(line));
}

/* After the gap, sway (near 0.9) is some 20 frames from the idle clip's
 * first frame: the coach asks for it that much before its tag. */
static void test_move_after_a_gap_begins_early_by_its_entry_lead(void **s)
{
    (void)s;
    start(v_high, NULL);
    to_dance(1000);
    send(2600, CUB_EV_CLIP_DONE, C_CLAP, 0, 1600);
    send(4200, CUB_EV_CLIP_DONE, C_CLAP, 0, 3200);
    assert_int_equal(dir.coach.clip, C_IDLE); /* waiting for sway's tag */
    const int32_t lead = expected_lead((cub_bridge_query){.from_clip = -1}, 1);
    assert_true(lead > 500);
    assert_int_equal(dir.moves[1].entry_lead_ms, lead);
    assert_int_equal(cub_director_tick(&dir, 4300 * 1000, 5000 - lead - 1), CUB_OK);
    assert_int_equal(dir.coach.clip, C_IDLE);
    assert_int_equal(cub_director_tick(&dir, 4333 * 1000, 5000 - lead), CUB_OK);
    assert_int_equal(dir.coach.clip, C_SWAY);
    assert_int_equal(planned_entry()->to_clip, C_SWAY);
}

/* ---- searched routes -------------------------------------------------------- */

/* clap then sway at once, 2 s repetitions (a route's fit: 139 ms), and a
 * searched route clap@39 (0.45) -> idle@18..18+len (the ramp to 0.9) ->
 * sway@0 (0.9): len frames of the idle clip between the two moves. */
static void start_routed(int len)
{
    static cub_coach_move mv[2];
    static cub_bridge_route route;
    mv[0] = (cub_coach_move){.clip = C_CLAP, .reps = 2, .tag_ms = 0, .span_ms = 4000};
    mv[1] = (cub_coach_move){.clip = C_SWAY, .reps = 2, .tag_ms = 4000, .span_ms = 4000};
    build_table(v_high);
    route = (cub_bridge_route){.from = C_CLAP, .to = C_SWAY, .via = C_IDLE, .a = FRAMES - 1,
                               .in = 18, .out = (int16_t)(18 + len), .b = 0};
    assert_int_equal(cub_bridge_table_set_routes(&F.table, &route, 1), CUB_OK);
    cub_director_desc d = make_desc(NULL);
    d.keys = NULL;
    d.coach.moves = mv;
    d.coach.move_count = 2;
    assert_int_equal(cub_director_init(&dir, &d, F.mem, sizeof F.mem, 0), CUB_OK);
}

/* The coach asks for sway when clap's last repetition ends (its last
 * frame): the plan the player makes then, as a lead. */
static int32_t lead_at_the_request(cub_bridge_plan *plan)
{
    assert_int_equal(cub_bridge_player_start(&dir.player, C_CLAP, FRAMES - 1, 0, 0), CUB_OK);
    const cub_coach_action a = {.kind = CUB_COACH_ACT_CLIP, .reason = CUB_COACH_WHY_MOVE,
                                .clip = C_SWAY, .move = 1, .rep = 0};
    director_request(&dir, &a, 0, CUB_COACH_NO_MUSIC);
    *plan = dir.player.plan;
    int to = plan->step[plan->step_count - 1].to_frame;
    return (int32_t)((int64_t)plan->total_frames * FRAME_NS / 1000000 -
                     (int64_t)2000 * to / (FRAMES - 1));
}

/* A short route fits what clap's last repetition can give (1.075 times
 * faster ends it 139 ms early): the lead is planned through it and the
 * request takes it, the same frames. */
static void test_a_route_the_music_has_time_for_is_taken(void **s)
{
    (void)s;
    start_routed(4);
    assert_true(dir.route_in[1]);
    assert_int_equal(dir.moves[1].lead_ms, 4 * FRAME_NS / 1000000);
    assert_true(logged("music route move=1 from=clap lead_ms=133 fit_ms=139"));
    cub_bridge_plan plan;
    assert_int_equal(lead_at_the_request(&plan), dir.moves[1].lead_ms);
    assert_int_equal(plan.step[0].via, CUB_BRIDGE_ROUTE);
    assert_true(logged("via=route"));
}

/* A route of 20 frames (667 ms) would need clap's last repetition 1.5
 * times faster: the lead is planned without it, and so is the request. */
static void test_a_route_too_long_for_the_music_is_not_taken(void **s)
{
    (void)s;
    start_routed(20);
    assert_false(dir.route_in[1]);
    const cub_bridge_query plain = {.from_clip = C_CLAP, .pos_q16 = (FRAMES - 1) << 16,
                                    .no_routes = 1};
    const int32_t lead = expected_lead(plain, 1);
    assert_true(lead < 667);
    assert_int_equal(dir.moves[1].lead_ms, lead);
    cub_bridge_plan plan;
    assert_int_equal(lead_at_the_request(&plan), lead);
    assert_true(plan.step[0].via != CUB_BRIDGE_ROUTE);
    assert_true(logged("taken=0"));
    assert_false(dir.player.desc.no_routes); /* only that request went without */
}

/* ---- the judge's windows ----------------------------------------------------- */

static cub_judge *judge(void)
{
    cub_judge *j = NULL;
    assert_true(cub_judge_mem_size(NULL) <= sizeof judge_mem);
    assert_int_equal(cub_judge_init(NULL, judge_mem, sizeof judge_mem, &j), CUB_OK);
    return j;
}

/* Nobody in view from t0_us on, a frame a millisecond: the time of the
 * first verdict (-1: none before until_us) and its move. */
static int64_t first_verdict_us(cub_judge *j, int64_t t0_us, int64_t until_us, int32_t *move)
{
    cub_track_skeleton nobody = {.status = CUB_TRACK_NO_PLAYER};
    for (int64_t t = t0_us; t < until_us; t += 1000) {
        cub_judge_out out;
        assert_int_equal(cub_judge_frame(j, t, &nobody, &out), CUB_OK);
        for (int i = 0; i < out.count; i++)
            if (out.events[i].kind == CUB_JUDGE_VERDICT) {
                *move = out.events[i].move;
                return t;
            }
    }
    return -1;
}

/* The window of move 0's first repetition: from its request for as long as
 * its clip plays at the move's speed (39 frames at 0.8), and a beat. */
static void test_repetition_window_spans_the_clip_at_its_speed_and_a_beat(void **s)
{
    (void)s;
    cub_judge *j = judge();
    start(v_high, j);
    to_dance(1000);
    assert_int_equal(dir.coach.speed_q16, Q(0.8));
    const int64_t play_us = (int64_t)(FRAMES - 1) * FRAME_NS / 1000 * CUB_Q16_ONE / Q(0.8);
    const int64_t beat_us = 60000000 / BPM;
    int32_t move = -1;
    const int64_t t = first_verdict_us(j, 1000 * 1000 + 1000, 10 * 1000 * 1000, &move);
    assert_int_equal(t, ((1000 * 1000 + play_us + beat_us + 999) / 1000) * 1000);
    assert_int_equal(move, 0);
}

/* Anything but a repetition closes the open windows: no verdict then. */
static void test_other_requests_close_the_windows(void **s)
{
    (void)s;
    cub_judge *j = judge();
    start(v_high, j);
    to_dance(1000);
    send(1100, CUB_EV_BUTTON_DOWN, CUB_BUTTON_STOP, 0, 100);
    assert_int_equal(dir.coach.clip, C_IDLE);
    assert_true(has_out(CUB_DIRECTOR_MUSIC_STOP));
    int32_t move = -1;
    assert_int_equal(first_verdict_us(j, 1100 * 1000, 10 * 1000 * 1000, &move), -1);
}

/* The slower demonstration is watched, not judged (SEEDS.md § 000): its
 * request closes the windows and opens none, and says so; the attempt
 * after it (the dance resumed where the music is) is judged as usual. */
static void test_demonstration_is_watched_the_attempt_judged(void **s)
{
    (void)s;
    cub_judge *j = judge();
    start(v_high, j);
    to_dance(1000);
    send(1200, CUB_EV_VERDICT, 0, 0, 200); /* wrong: the correcting clip */
    assert_int_equal(dir.coach.state, CUB_COACH_CORRECT);
    send(2000, CUB_EV_CLIP_DONE, dir.coach.clip, 0, 1000);
    assert_int_equal(dir.coach.clip, C_CLAP); /* the demonstration */
    assert_true(logged("judge watch move=0 rep=0"));
    int32_t move = -1;
    assert_int_equal(first_verdict_us(j, 2000 * 1000, 6000 * 1000, &move), -1);
    send(6000, CUB_EV_CLIP_DONE, C_CLAP, 0, 1600); /* watched: the attempt, clap's rep 1 */
    assert_int_equal(dir.coach.state, CUB_COACH_DANCE);
    assert_int_equal(dir.coach.rep, 1);
    assert_true(first_verdict_us(j, 6000 * 1000 + 1000, 10 * 1000 * 1000, &move) > 0);
    assert_int_equal(move, 0);
}

/* ---- the other moves a window looks for ----------------------------------- */

/* A song of n moves (2 reps, a second apart) on the given clips and keys,
 * with a judge: the director finds each move's other moves at init. */
static void start_song(const int *clips, const cub_director_keys *k, int n)
{
    static cub_coach_move mv[8];
    assert_true(n <= 8);
    for (int i = 0; i < n; i++)
        mv[i] = (cub_coach_move){.clip = clips[i], .reps = 2, .tag_ms = 1000 * i, .span_ms = 1000};
    cub_judge *j = judge();
    build_table(v_high);
    cub_director_desc d = make_desc(j);
    d.keys = k;
    d.coach.moves = mv;
    d.coach.move_count = n;
    assert_true(cub_director_mem_size(&d) <= sizeof F.mem);
    assert_int_equal(cub_director_init(&dir, &d, F.mem, sizeof F.mem, 0), CUB_OK);
}

#define KEY1(f, s) {.count = 1, .key = {{.feature = (f), .set = (s)}}}
#define KEY2(f, s, g, t) {.count = 2, .key = {{.feature = (f), .set = (s)}, {.feature = (g), .set = (t)}}}

/* Move 1's keys rule move 0's out (the right arm half raised, not down) but
 * move 0's clap clip shows them (its frame 0 is at 0.9): no mistake to look
 * for. Move 1's sway clip (0.9 throughout) never shows move 0's keys, so
 * there the rule lists it. */
static void test_other_move_the_clip_shows_is_not_listed(void **s)
{
    (void)s;
    static const cub_director_keys k[2] = {KEY1(CUB_FUZZY_RH, 0), KEY1(CUB_FUZZY_RH, 1)};
    const int clips[2] = {C_CLAP, C_SWAY};
    start_song(clips, k, 2);
    assert_int_equal(dir.other_moves[0], 0);
    assert_false(logged("judge other move=0"));
    assert_int_equal(dir.other_moves[1], 1u << 0);
    assert_true(logged("judge other move=1 moves=0"));
}

/* Move 1's keys (the left arm down) are never shown in move 0's sway clip
 * either, but move 0 reads the right arm only: a child may do both, so
 * they rule nothing out. Move 2's right arm down does. */
static void test_other_move_on_other_features_is_not_listed(void **s)
{
    (void)s;
    static const cub_director_keys k[3] = {KEY1(CUB_FUZZY_RH, 1), KEY1(CUB_FUZZY_LH, 0),
                                           KEY1(CUB_FUZZY_RH, 0)};
    const int clips[3] = {C_SWAY, C_SWAY, C_SWAY};
    start_song(clips, k, 3);
    assert_int_equal(dir.other_moves[0], 1u << 2);
    assert_true(logged("judge other move=0 moves=2"));
}

/* Keys that share a feature with move 0's in another set (the right arm up,
 * not half raised; the left elbow straight, not bent), never shown in move
 * 0's sway clip (no set 0 or 2 there), are listed, and its window looks for
 * them in song order. */
static void test_other_move_that_rules_out_and_never_shows_is_listed(void **s)
{
    (void)s;
    static const cub_director_keys k[3] = {KEY2(CUB_FUZZY_RH, 1, CUB_FUZZY_LHE, 1),
                                           KEY1(CUB_FUZZY_RH, 2),
                                           KEY2(CUB_FUZZY_LH, 1, CUB_FUZZY_LHE, 0)};
    const int clips[3] = {C_SWAY, C_SWAY, C_SWAY};
    start_song(clips, k, 3);
    assert_int_equal(dir.other_moves[0], (1u << 1) | (1u << 2));
    assert_true(logged("judge other move=0 moves=1,2"));
    cub_judge_rep r = {0};
    director_key_moment(&dir, 0, 0, 0, CUB_Q16_ONE, &r);
    assert_int_equal(r.has_key, 1);
    assert_int_equal(r.other_count, 2);
    assert_int_equal(r.other[0].count, 1);
    assert_int_equal(r.other[0].key[0].feature, CUB_FUZZY_RH);
    assert_int_equal(r.other[0].key[0].set, 2);
    assert_int_equal(r.other[1].count, 2);
    assert_int_equal(r.other[1].key[1].feature, CUB_FUZZY_LHE);
    assert_int_equal(r.other[1].key[1].set, 0);
}

/* Six other moves rule move 0 out and all are listed; a window looks for the
 * first four distinct key sets in song order (move 2 repeats move 1's set in
 * another order and takes no place), so move 6's is not looked for (it
 * stays listed in the log line and the bit mask). */
static void test_other_window_takes_the_first_four_distinct_sets(void **s)
{
    (void)s;
    static const cub_director_keys k[7] = {
        KEY1(CUB_FUZZY_RH, 1),
        KEY2(CUB_FUZZY_RH, 0, CUB_FUZZY_LH, 1),
        KEY2(CUB_FUZZY_LH, 1, CUB_FUZZY_RH, 0),
        KEY1(CUB_FUZZY_RH, 2),
        KEY2(CUB_FUZZY_RH, 0, CUB_FUZZY_LHE, 1),
        KEY1(CUB_FUZZY_RH, 0),
        KEY2(CUB_FUZZY_RH, 2, CUB_FUZZY_LH, 1),
    };
    const int clips[7] = {C_SWAY, C_SWAY, C_SWAY, C_SWAY, C_SWAY, C_SWAY, C_SWAY};
    start_song(clips, k, 7);
    assert_int_equal(dir.other_moves[0], 0x7Eu);
    assert_true(logged("judge other move=0 moves=1,2,3,4,5,6"));
    cub_judge_rep r = {0};
    director_key_moment(&dir, 0, 0, 0, CUB_Q16_ONE, &r);
    assert_int_equal(r.other_count, CUB_JUDGE_MAX_OTHER);
    const int from[CUB_JUDGE_MAX_OTHER] = {1, 3, 4, 5};
    for (int i = 0; i < CUB_JUDGE_MAX_OTHER; i++) {
        const cub_director_keys *want = &k[from[i]];
        assert_int_equal(r.other[i].count, want->count);
        assert_memory_equal(r.other[i].key, want->key, sizeof want->key[0] * (size_t)want->count);
    }
    /* the judge takes the window as it is */
    r.move = 0;
    r.key_count = 1;
    r.keys[0] = k[0].key[0];
    r.start_us = 0;
    r.end_us = 1000 * 1000;
    assert_int_equal(cub_judge_begin_rep(dir.desc.judge, &r), CUB_OK);
}

/* ---- music tags -------------------------------------------------------------- */

/* Entering move 0's clip: its tag, the song time of the frame entered. */
static void test_entering_a_move_posts_its_music_tag(void **s)
{
    (void)s;
    start(v_high, NULL);
    to_dance(1000);
    const int to_frame = planned_entry()->to_frame;
    cub_event ev;
    int tag = -1;
    for (int64_t t_ms = 1033; t_ms < 2000 && tag < 0; t_ms += 33) {
        assert_int_equal(cub_director_advance(&dir, &F.loop, t_ms * 1000, 40), CUB_OK);
        while (cub_queue_pop(&F.loop.queue, &ev) == CUB_OK)
            if (ev.type == CUB_EV_MUSIC_TAG) tag = ev.b;
    }
    assert_int_equal(dir.player.clip, C_CLAP);
    const int64_t rep_ms = song[0].span_ms / song[0].reps;
    const int64_t pos_q16 = dir.player.pos_q16;
    assert_true(pos_q16 >= (int64_t)to_frame << 16);
    assert_int_equal(tag, (int32_t)(rep_ms * pos_q16 / ((int64_t)(FRAMES - 1) << 16)));
    assert_true(logged("music tag move=0"));
}

/* ---- scripted verdicts ---------------------------------------------------------- */

static void test_scripted_verdict_is_about_the_move_taught_now(void **s)
{
    (void)s;
    const cub_event v = {.type = CUB_EV_VERDICT, .a = -1, .b = 0};
    const cub_event clap = {.type = CUB_EV_CLAP, .a = -1};
    assert_int_equal(cub_director_scripted(NULL, &v).a, 0);
    start(v_high, NULL);
    assert_int_equal(cub_director_scripted(&dir, &v).a, 0); /* before the dance */
    assert_int_equal(cub_director_scripted(&dir, &clap).a, -1); /* only verdicts */
    to_dance(1000);
    dir.coach.move = 1;
    assert_int_equal(cub_director_scripted(&dir, &v).a, 1);
    cub_event named = v;
    named.a = 0;
    assert_int_equal(cub_director_scripted(&dir, &named).a, 0);
    dir.coach.move = 0;
    /* handle reads it the same way: a wrong verdict about "now" corrects. */
    send(1500, CUB_EV_VERDICT, -1, 0, 500);
    assert_int_equal(dir.coach.state, CUB_COACH_CORRECT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_desc_is_refused),
        cmocka_unit_test(test_tunables_default),
        cmocka_unit_test(test_init_plays_the_idle_clip),
        cmocka_unit_test(test_move_is_entered_at_its_first_frames),
        cmocka_unit_test(test_correction_substitutes_the_sooner_clip),
        cmocka_unit_test(test_substitute_ends_under_the_asked_name),
        cmocka_unit_test(test_correction_soon_enough_is_not_substituted),
        cmocka_unit_test(test_correction_enters_anywhere_in_the_front_half),
        cmocka_unit_test(test_leads_are_the_routes_from_the_last_frame),
        cmocka_unit_test(test_move_after_a_gap_begins_early_by_its_entry_lead),
        cmocka_unit_test(test_a_route_the_music_has_time_for_is_taken),
        cmocka_unit_test(test_a_route_too_long_for_the_music_is_not_taken),
        cmocka_unit_test(test_repetition_window_spans_the_clip_at_its_speed_and_a_beat),
        cmocka_unit_test(test_other_requests_close_the_windows),
        cmocka_unit_test(test_demonstration_is_watched_the_attempt_judged),
        cmocka_unit_test(test_other_move_the_clip_shows_is_not_listed),
        cmocka_unit_test(test_other_move_on_other_features_is_not_listed),
        cmocka_unit_test(test_other_move_that_rules_out_and_never_shows_is_listed),
        cmocka_unit_test(test_other_window_takes_the_first_four_distinct_sets),
        cmocka_unit_test(test_entering_a_move_posts_its_music_tag),
        cmocka_unit_test(test_scripted_verdict_is_about_the_move_taught_now),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

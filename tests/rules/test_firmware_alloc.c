/* Firmware allocates nothing after init (ARCHITECTURE.md). The allocator's
 * entry points are wrapped at link time (see CMakeLists.txt), so any call
 * made by firmware code while `counting` is on is seen here. The test runs
 * every firmware module through real work after its init. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/coach.h"
#include "cub/bridge.h"
#include "cub/director.h"
#include "cub/fx.h"
#include "cub/loop.h"
#include "cub/motion.h"

/* volatile: the compiler cannot know that malloc is our wrapper, and would
 * otherwise drop the stores around the calls. */
static volatile int counting;
static volatile int alloc_calls;

void *__real_malloc(size_t n);
void *__real_calloc(size_t n, size_t m);
void *__real_realloc(void *p, size_t n);
void __real_free(void *p);
void *__real_aligned_alloc(size_t a, size_t n);
int __real_posix_memalign(void **p, size_t a, size_t n);

void *__wrap_malloc(size_t n);
void *__wrap_calloc(size_t n, size_t m);
void *__wrap_realloc(void *p, size_t n);
void __wrap_free(void *p);
void *__wrap_aligned_alloc(size_t a, size_t n);
int __wrap_posix_memalign(void **p, size_t a, size_t n);

void *__wrap_malloc(size_t n) { alloc_calls += counting; return __real_malloc(n); }
void *__wrap_calloc(size_t n, size_t m) { alloc_calls += counting; return __real_calloc(n, m); }
void *__wrap_realloc(void *p, size_t n) { alloc_calls += counting; return __real_realloc(p, n); }
void __wrap_free(void *p) { alloc_calls += counting && p; __real_free(p); }
void *__wrap_aligned_alloc(size_t a, size_t n)
{
    alloc_calls += counting;
    return __real_aligned_alloc(a, n);
}
int __wrap_posix_memalign(void **p, size_t a, size_t n)
{
    alloc_calls += counting;
    return __real_posix_memalign(p, a, n);
}

static void test_counter_sees_an_allocation(void **s)
{
    counting = 1;
    alloc_calls = 0;
    void *volatile p = malloc(16); /* volatile: the optimiser may not drop the pair */
    free(p);
    counting = 0;
    assert_int_equal(alloc_calls, 2); /* proves the wrap is live */
}

/* ---- the loop ---------------------------------------------------------- */

static int64_t fake_now;
static int64_t now_hook(void *u) { return fake_now += 33333; }
static void sink(void *u, const char *line, size_t len) { (*(size_t *)u) += len; }
static void handle_hook(void *u, cub_loop *loop, const cub_event *ev)
{
    cub_log_event(&loop->log, ev->t_us, "test", "event", "type=%s a=%d q=%q",
                  cub_loop_event_name(ev->type), ev->a, 12345);
}

static void run_loop_after_init(void)
{
    static cub_event slots[16];
    static cub_loop loop;
    size_t logged = 0;
    cub_loop_desc d = {.queue_capacity = 16, .log_sink = sink, .log_user = &logged};
    assert_int_equal(cub_loop_init(&loop, &d, slots, sizeof slots), CUB_OK);
    cub_loop_hooks h = {.now_us = now_hook, .handle = handle_hook};

    counting = 1;
    cub_loop_timer_start(&loop, 7, 0, 10000, 40000);
    for (int i = 0; i < 40; i++) {
        cub_event ev = {.t_us = i, .type = CUB_EV_BUTTON_DOWN, .a = i & 1};
        cub_loop_post(&loop, &ev);
    }
    assert_int_equal(cub_loop_run(&loop, &h, 30), CUB_OK);
    counting = 0;
    assert_true(logged > 0);
}

/* ---- motion and fx ----------------------------------------------------- */

static void run_motion_after_init(void)
{
    static cub_skeleton skel;
    static cub_pose pose, a, b;
    static cub_vec3 world[CUB_MOTION_MAX_JOINTS];
    static cub_quat world_rot[CUB_MOTION_MAX_JOINTS];
    static uint8_t mem[1 << 16];
    cub_clip clip;

    cub_motion_skeleton_reset(&skel);
    int parent = -1;
    for (int j = 0; j < 12; j++) {
        char name[8] = "j00";
        name[1] = (char)('0' + j / 10);
        name[2] = (char)('0' + j % 10);
        cub_vec3 off = {0, CUB_Q16_INT(100), CUB_Q16_INT(j)};
        assert_int_equal(cub_motion_skeleton_add(&skel, name, parent, off, &parent), CUB_OK);
    }
    size_t need = cub_motion_clip_mem_size(skel.joint_count, 20, 0);
    assert_true(need <= sizeof mem);
    assert_int_equal(cub_motion_clip_init(&clip, &skel, 20, 33333333, 0, mem, sizeof mem),
                     CUB_OK);

    counting = 1;
    cub_vec3 axis = {0, 0, CUB_Q16_ONE};
    for (int f = 0; f < 20; f++) {
        cub_motion_pose_rest(&skel, &pose);
        for (int j = 0; j < skel.joint_count; j++)
            pose.rot[j] = cub_fx_quat_from_axis_angle(axis, cub_fx_sin(CUB_Q16_INT(f + j)));
        cub_motion_clip_set_frame(&clip, f, &pose);
    }
    for (int64_t t = -50000; t < 800000; t += 12345) {
        cub_motion_sample(&clip, t, CUB_MOTION_LOOP, &pose);
        cub_motion_forward(&skel, &pose, world, world_rot);
    }
    cub_motion_clip_get_frame(&clip, 3, &a);
    cub_motion_clip_get_frame(&clip, 9, &b);
    cub_motion_pose_blend(&a, &b, CUB_Q16_HALF, &pose);
    cub_q16 acc = cub_fx_sqrt(CUB_Q16_INT(2)) + cub_fx_atan2(CUB_Q16_ONE, -CUB_Q16_ONE) +
                  cub_fx_acos(CUB_Q16_HALF) + cub_fx_quat_angle(world_rot[5]);
    counting = 0;
    assert_true(acc != 0);
}

/* ---- the coach --------------------------------------------------------- */

static void run_coach_after_init(void)
{
    static const cub_coach_move moves[2] = {
        {.clip = 8, .reps = 2, .tag_ms = 0, .span_ms = 4000},
        {.clip = 9, .reps = 3, .tag_ms = 4000, .span_ms = 6000},
    };
    static const char *const names[10] = {"idle", "wake_up", "wave",  "doze", "head_shake",
                                           "watch_me", "worried", "cheer", "clap", "sway"};
    static cub_coach coach;
    size_t logged = 0;
    cub_log log = {.sink = sink, .user = &logged};
    cub_coach_desc d = {.moves = moves, .move_count = 2, .clip_count = 10,
                        .clip_names = names, .log = &log};
    assert_int_equal(cub_coach_roles_by_name(names, 10, &d.roles), CUB_OK);
    assert_int_equal(cub_coach_init(&coach, &d, 0), CUB_OK);

    counting = 1;
    const cub_event script[] = {
        {100000, CUB_EV_CLAP, 0, 0, 0},       {1500000, CUB_EV_CLIP_DONE, 1, 0, 0},
        {1600000, CUB_EV_MUSIC_TAG, 0, 0, 0}, {2000000, CUB_EV_VERDICT, 0, 0, 0},
        {3000000, CUB_EV_CLIP_DONE, 4, 0, 0}, {4000000, CUB_EV_CLIP_DONE, 8, 0, 0},
        {4500000, CUB_EV_PLAYER, 0, 0, 0},    {5000000, CUB_EV_VERDICT, 0, 1, 0},
        {5100000, CUB_EV_PLAYER, 1, 0, 0},    {6000000, CUB_EV_CLIP_DONE, 9, 0, 0},
        {9000000, CUB_EV_SONG_END, 0, 0, 0},  {9900000, CUB_EV_CLIP_DONE, 7, 0, 0},
        {9950000, CUB_EV_BUTTON_DOWN, CUB_BUTTON_STOP, 0, 0},
    };
    for (size_t i = 0; i < sizeof script / sizeof script[0]; i++) {
        cub_coach_handle(&coach, &script[i], (int32_t)(script[i].t_us / 1000) - 1500);
        cub_coach_tick(&coach, script[i].t_us + 33333, (int32_t)(script[i].t_us / 1000) - 1467);
    }
    cub_q16 speed = cub_coach_sync_speed(4000, 3900, 4000, CUB_Q16_ONE, 0);
    counting = 0;
    assert_true(speed < CUB_Q16_ONE);
    assert_true(logged > 0);
    assert_int_equal(coach.state, CUB_COACH_IDLE);
}

/* ---- the director over a finished table ---------------------------------- */

/* Every role played by clip 0, a song of clip 1: START, the dance, a wrong
 * verdict, the player's time, STOP. */
static void run_director_after_init(const cub_bridge_table *table)
{
    static const cub_coach_move moves[1] = {{.clip = 1, .reps = 2, .tag_ms = 0, .span_ms = 2000}};
    static const cub_director_keys keys[1] = {{.count = 1, .key = {{.feature = 0, .set = 1}}}};
    static uint8_t mem[1 << 15];
    static cub_director dir;
    static cub_event slots[64];
    static cub_loop loop;
    size_t logged = 0;
    cub_log log = {.sink = sink, .user = &logged};
    cub_director_desc d = {.table = table, .keys = keys, .bpm = 120,
                           .coach = {.moves = moves, .move_count = 1, .clip_count = 2,
                                     .log = &log}};
    assert_true(cub_director_mem_size(&d) <= sizeof mem);
    assert_int_equal(cub_director_init(&dir, &d, mem, sizeof mem, 0), CUB_OK);
    cub_loop_desc ld = {.queue_capacity = 64};
    assert_int_equal(cub_loop_init(&loop, &ld, slots, sizeof slots), CUB_OK);

    counting = 1;
    const cub_event script[] = {
        {100000, CUB_EV_BUTTON_DOWN, CUB_BUTTON_START, 0, 0}, {1000000, CUB_EV_CLIP_DONE, 0, 0, 0},
        {1500000, CUB_EV_VERDICT, -1, 0, 0}, {3000000, CUB_EV_BUTTON_DOWN, CUB_BUTTON_STOP, 0, 0},
    };
    for (size_t i = 0; i < sizeof script / sizeof script[0]; i++) {
        cub_director_advance(&dir, &loop, script[i].t_us, (int32_t)(script[i].t_us / 1000));
        cub_director_handle(&dir, &script[i], (int32_t)(script[i].t_us / 1000));
        cub_director_tick(&dir, script[i].t_us, (int32_t)(script[i].t_us / 1000));
    }
    counting = 0;
    assert_true(logged > 0);
    assert_int_equal(dir.coach.state, CUB_COACH_IDLE);
}

/* ---- bridge: plan, play and smooth switches ----------------------------- */

static void run_bridge_after_init(void)
{
    static cub_skeleton skel;
    static cub_pose pose;
    static uint8_t clip_mem[2][1 << 15], table_mem[1 << 16], work[1 << 15];
    static cub_bridge_table table;
    static cub_bridge_player player;
    cub_clip clips[2];

    /* Two clips on a 16-joint stick figure: arms swing, at different rates. */
    cub_motion_skeleton_reset(&skel);
    int parent = -1;
    for (int j = 0; j < 16; j++) {
        char name[8] = {'b', (char)('a' + j), 0};
        cub_vec3 off = {CUB_Q16_INT(j % 3), CUB_Q16_INT(60), 0};
        assert_int_equal(cub_motion_skeleton_add(&skel, name, j < 2 ? parent : j / 2, off, &parent),
                         CUB_OK);
    }
    cub_vec3 axis = {CUB_Q16_ONE, 0, 0};
    for (int c = 0; c < 2; c++) {
        assert_int_equal(cub_motion_clip_init(&clips[c], &skel, 30, 33333333, 0, clip_mem[c],
                                              sizeof clip_mem[c]),
                         CUB_OK);
        for (int f = 0; f < 30; f++) {
            cub_motion_pose_rest(&skel, &pose);
            for (int j = 0; j < 16; j++)
                pose.rot[j] = cub_fx_quat_from_axis_angle(axis, cub_fx_sin(CUB_Q16_INT(f) / (4 + c)) / 3);
            cub_motion_clip_set_frame(&clips[c], f, &pose);
        }
    }
    cub_bridge_table_desc d = {.skel = &skel, .clip_count = 2, .frame_total = 60,
                               .bridge_total = 8, .link_total = 4,
                               .body = {.hip_centre = 0, .spine = -1, .shoulder_centre = 1,
                                        .head = -1, .shoulder = {2, 3}, .elbow = {4, 5},
                                        .wrist = {6, 7}, .hip = {8, 9}, .knee = {10, 11},
                                        .ankle = {12, 13}, .stand_cog_mm = CUB_Q16_INT(300)}};
    assert_true(cub_bridge_table_mem_size(&d) <= sizeof table_mem);
    assert_int_equal(cub_bridge_table_init(&table, &d, table_mem, sizeof table_mem), CUB_OK);
    const int bridges[] = {2, 9, 17, 25};
    for (int c = 0; c < 2; c++)
        assert_int_equal(cub_bridge_table_add_clip(&table, &clips[c], bridges, 4, NULL), CUB_OK);
    cub_bridge_link l = {.a = 9, .b = 2, .back = 0, .d = CUB_Q16_ONE / 10};
    assert_int_equal(cub_bridge_table_set_links(&table, 0, 1, &l, 1), CUB_OK);
    assert_int_equal(cub_bridge_table_finish(&table), CUB_OK);
    cub_bridge_player_desc pd = {.table = &table};
    assert_true(cub_bridge_player_mem_size(&pd) <= sizeof work);
    assert_int_equal(cub_bridge_player_init(&player, &pd, work, sizeof work), CUB_OK);

    counting = 1;
    cub_bridge_player_start(&player, 0, 3, 0, 1);
    int switches = 0;
    for (int i = 0; i < 200; i++) {
        cub_bridge_event ev[4];
        int n = 0;
        if (i % 25 == 0) cub_bridge_player_request(&player, (i / 25) & 1, CUB_Q16_ONE * 3 / 4, 1, NULL);
        cub_bridge_player_advance(&player, 33333, ev, 4, &n);
        for (int k = 0; k < n; k++)
            switches += ev[k].type == CUB_BRIDGE_EV_SWITCH;
        cub_bridge_player_pose(&player, &pose);
    }
    counting = 0;
    assert_true(switches > 0);
    run_director_after_init(&table);
}

static void test_firmware_allocates_nothing_after_init(void **s)
{
    alloc_calls = 0;
    run_loop_after_init();
    run_motion_after_init();
    run_bridge_after_init();
    run_coach_after_init();
    print_message("firmware allocations after init: %d\n", alloc_calls);
    assert_int_equal(alloc_calls, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_counter_sees_an_allocation),
        cmocka_unit_test(test_firmware_allocates_nothing_after_init),
    };
    return cmocka_run_group_tests_name("firmware_alloc", tests, NULL, NULL);
}

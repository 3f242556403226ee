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

static void test_firmware_allocates_nothing_after_init(void **s)
{
    alloc_calls = 0;
    run_loop_after_init();
    run_motion_after_init();
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

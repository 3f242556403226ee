/* Golden images: the renderer, drawn headless (EGL surfaceless, Mesa
 * llvmpipe), compared with PNGs stored in tests/golden/expected/.
 *
 * Tolerance: a pixel differs when any channel is off by more than
 * CHANNEL_TOL (8 counts of 255); the frame passes when at most MAX_SHARE
 * (0.02%, 15 pixels) of its pixels differ. That absorbs rasteriser rounding between
 * x86-64 and aarch64 llvmpipe and between Mesa versions, while a moved
 * limb, a lost inset or a wrong colour fails.
 *
 * To regenerate the stored image after an intended change (look at it!):
 *   CUB_GOLDEN_UPDATE=1 ctest --test-dir build/host -R test_golden_render
 * On a mismatch the test writes <name>_actual.png and <name>_diff.png into
 * CUB_GOLDEN_OUT_DIR (in the build tree) and names them in the failure.
 */
#define _POSIX_C_SOURCE 200809L /* setenv */

#include <GLES2/gl2.h>
#include <SDL2/SDL.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/png.h"
#include "cub/render.h"
#include "display.h"

#define W 320
#define H 240
#define CHANNEL_TOL 8
#define MAX_SHARE 0.0002 /* 15 pixels at 320x240: a moved hand is ~150 */
#define DEPTH_W 640
#define DEPTH_H 480

/* ---- the scene ---------------------------------------------------------- */

/* A 15-joint humanoid facing the viewer (+z), both arms raised toward its
 * left (+x, the viewer's right), the right hand over the head. Positions
 * are world millimetres, hand-computed; the renderer takes floats. */
static const struct {
    const char *name;
    int parent;
    float xyz[3];
} POSE[] = {
    {"Hips", -1, {0, 950, 0}},         {"Chest", 0, {0, 1300, 0}},
    {"Head", 1, {10, 1580, 0}},        {"LeftShoulder", 1, {180, 1430, 0}},
    {"LeftElbow", 3, {380, 1630, 0}},  {"LeftHand", 4, {560, 1830, 0}},
    {"RightShoulder", 1, {-180, 1430, 0}}, {"RightElbow", 6, {-150, 1710, 60}},
    {"RightHand", 7, {90, 1900, 90}},  {"LeftHip", 0, {100, 900, 0}},
    {"LeftKnee", 9, {150, 480, 40}},   {"LeftFoot", 10, {170, 40, 0}},
    {"RightHip", 0, {-100, 900, 0}},   {"RightKnee", 12, {-170, 480, 0}},
    {"RightFoot", 13, {-210, 40, 0}},
};
#define POSE_JOINTS ((int)(sizeof POSE / sizeof POSE[0]))

static cub_skeleton g_skel;
static float g_xyz[3 * POSE_JOINTS];
static uint16_t g_depth[DEPTH_W * DEPTH_H];

static void build_skeleton(void)
{
    memset(&g_skel, 0, sizeof g_skel);
    g_skel.joint_count = POSE_JOINTS;
    for (int j = 0; j < POSE_JOINTS; j++) {
        snprintf(g_skel.joints[j].name, sizeof g_skel.joints[j].name, "%s", POSE[j].name);
        g_skel.joints[j].parent = (int16_t)POSE[j].parent;
        memcpy(g_xyz + 3 * j, POSE[j].xyz, sizeof POSE[j].xyz);
    }
}

/* Near (raw 450, ~0.55 m) on the left to far (raw 1000, ~3.8 m) on the
 * right, with a disc of "no reading" (2047) in the middle. */
static void build_depth(void)
{
    for (int y = 0; y < DEPTH_H; y++) {
        for (int x = 0; x < DEPTH_W; x++) {
            int dx = x - DEPTH_W / 2, dy = y - DEPTH_H / 2;
            g_depth[y * DEPTH_W + x] =
                dx * dx + dy * dy <= 90 * 90 ? 2047 : (uint16_t)(450 + x * 550 / (DEPTH_W - 1));
        }
    }
}

/* ---- fixture: one headless display and renderer for all tests ----------- */

typedef struct fixture {
    cub_display *disp;
    cub_render *render;
    uint8_t rgba[W * H * 4];
} fixture;

/* Both backends draw the same scene; the window group uses SDL's
 * "offscreen" video driver (EGL pbuffer, no display server), which runs
 * display_sdl.c's whole path up to the swap. */
static int setup_with(void **state, int window)
{
    static fixture f;
    char err[256] = "";
    cub_err e = window ? cub_display_open_window(W, H, "offscreen", &f.disp, err, sizeof err)
                       : cub_display_open_headless(W, H, &f.disp, err, sizeof err);
    if (e) {
        fprintf(stderr, "golden: cannot open the %s display: %s\n", window ? "window" : "headless",
                err);
        return -1;
    }
    printf("golden: %s display, GL_RENDERER=%s\n", window ? "SDL offscreen" : "EGL surfaceless",
           (const char *)glGetString(GL_RENDERER));
    cub_render_desc desc = {.width = W, .height = H};
    if (cub_render_create(&desc, &f.render)) {
        fprintf(stderr, "golden: cub_render_create failed\n");
        cub_display_close(f.disp);
        return -1;
    }
    build_skeleton();
    build_depth();
    *state = &f;
    return 0;
}

static int setup(void **state)
{
    return setup_with(state, 0);
}

static int setup_window(void **state)
{
    return setup_with(state, 1);
}

static int teardown(void **state)
{
    fixture *f = *state;
    cub_render_destroy(f->render);
    cub_display_close(f->disp);
    return 0;
}

static void draw(fixture *f, const cub_render_scene *scene)
{
    assert_int_equal(cub_render_frame(f->render, scene), CUB_OK);
    assert_int_equal(cub_display_read_rgba(f->disp, f->rgba, sizeof f->rgba), CUB_OK);
    cub_display_swap(f->disp);
}

/* ---- comparison ----------------------------------------------------------- */

static void path_in(char *out, size_t size, const char *dir, const char *name,
                    const char *suffix)
{
    snprintf(out, size, "%s/%s%s.png", dir, name, suffix);
}

/* Compare with expected/<name>.png, or write it when CUB_GOLDEN_UPDATE=1
 * and this frame is the reference one (the headless backend's). */
static void check_golden(const uint8_t *rgba, const char *name, int is_reference)
{
    char expected_path[1024], actual_path[1024], diff_path[1024];
    path_in(expected_path, sizeof expected_path, CUB_GOLDEN_EXPECTED_DIR, name, "");
    const char *update = getenv("CUB_GOLDEN_UPDATE");
    if (is_reference && update && strcmp(update, "1") == 0) {
        assert_int_equal(cub_png_write(expected_path, rgba, W, H), CUB_OK);
        printf("golden: %s written to %s (CUB_GOLDEN_UPDATE=1)\n", name, expected_path);
        return;
    }
    uint8_t *ref = NULL;
    int rw = 0, rh = 0;
    if (cub_png_read(expected_path, &ref, &rw, &rh) != CUB_OK)
        fail_msg("golden: cannot read %s; to create it run with CUB_GOLDEN_UPDATE=1",
                 expected_path);
    if (rw != W || rh != H) {
        free(ref);
        fail_msg("golden: %s is %dx%d, the frame is %dx%d", expected_path, rw, rh, W, H);
    }
    static uint8_t diff[W * H * 4];
    int max_diff = 0, over = 0;
    for (int i = 0; i < W * H; i++) {
        int worst = 0;
        for (int c = 0; c < 3; c++) {
            int d = abs((int)rgba[4 * i + c] - (int)ref[4 * i + c]);
            worst = d > worst ? d : worst;
        }
        max_diff = worst > max_diff ? worst : max_diff;
        over += worst > CHANNEL_TOL;
        /* Diff image: red where over tolerance, grey otherwise, scaled. */
        uint8_t g = (uint8_t)(worst * 8 > 255 ? 255 : worst * 8);
        diff[4 * i + 0] = worst > CHANNEL_TOL ? 255 : g;
        diff[4 * i + 1] = worst > CHANNEL_TOL ? 0 : g;
        diff[4 * i + 2] = worst > CHANNEL_TOL ? 0 : g;
        diff[4 * i + 3] = 255;
    }
    free(ref);
    double share = (double)over / (W * H);
    printf("golden: %s max_channel_diff=%d differing_pixels=%d (%.3f%%) of %d; "
           "tolerance: channel<=%d, share<=%.1f%%\n",
           name, max_diff, over, 100.0 * share, W * H, CHANNEL_TOL, 100.0 * MAX_SHARE);
    if (share > MAX_SHARE) {
        path_in(actual_path, sizeof actual_path, CUB_GOLDEN_OUT_DIR, name, "_actual");
        path_in(diff_path, sizeof diff_path, CUB_GOLDEN_OUT_DIR, name, "_diff");
        cub_png_write(actual_path, rgba, W, H);
        cub_png_write(diff_path, diff, W, H);
        fail_msg("golden: %s differs from %s: %.3f%% of pixels over %d counts (max %.1f%%); "
                 "see %s and %s",
                 name, expected_path, 100.0 * share, CHANNEL_TOL, 100.0 * MAX_SHARE,
                 actual_path, diff_path);
    }
}

/* ---- tests ------------------------------------------------------------------ */

static void test_stick_pose_matches_golden(void **state)
{
    fixture *f = *state;
    cub_render_scene scene = {.skel = &g_skel, .world_xyz_mm = g_xyz, .depth_raw = g_depth};
    draw(f, &scene);
    check_golden(f->rgba, "stick_pose", 1);
}

/* The same scene drawn twice gives the same bytes: nothing in the renderer
 * depends on time or leftover state. */
static void test_frames_are_deterministic(void **state)
{
    fixture *f = *state;
    static uint8_t first[W * H * 4];
    cub_render_scene scene = {.skel = &g_skel, .world_xyz_mm = g_xyz, .depth_raw = g_depth};
    draw(f, &scene);
    memcpy(first, f->rgba, sizeof first);
    cub_render_scene other = {.background_rgb = {0.2f, 0.2f, 0.2f}};
    draw(f, &other);
    draw(f, &scene);
    assert_memory_equal(first, f->rgba, sizeof first);
}

static const uint8_t *px(const fixture *f, int x, int y_top)
{
    return f->rgba + 4 * ((size_t)y_top * W + (size_t)x);
}

/* The inset's layout as render_inset.c documents it, at 320 wide: 64x48
 * pixels, 4 pixels from the right and bottom edges. */
#define INSET_W 64
#define INSET_H 48
#define INSET_X0 (W - 4 - INSET_W)
#define INSET_Y0 (H - 4 - INSET_H) /* top row, counted from the top */

static void test_inset_maps_no_reading_to_black_and_near_brighter(void **state)
{
    fixture *f = *state;
    cub_render_scene scene = {.depth_raw = g_depth, .background_rgb = {0.5f, 0.5f, 0.5f}};
    draw(f, &scene);
    /* The 2047 disc (radius 90 of 640 -> 9 px) at the inset's centre. */
    const uint8_t *hole = px(f, INSET_X0 + INSET_W / 2, INSET_Y0 + INSET_H / 2);
    /* 1/10 and 9/10 across, in the upper quarter, clear of the disc. */
    const uint8_t *near = px(f, INSET_X0 + INSET_W / 10, INSET_Y0 + INSET_H / 4);
    const uint8_t *far = px(f, INSET_X0 + INSET_W * 9 / 10, INSET_Y0 + INSET_H / 4);
    /* Outside the inset: the plain grey background (0.5 -> 127 or 128). */
    const uint8_t *bg = px(f, W / 2, H / 2);
    printf("golden: inset hole=%d near=%d far=%d background=%d\n", hole[0], near[0], far[0],
           bg[0]);
    for (int c = 0; c < 3; c++)
        assert_true(hole[c] <= 2);
    assert_true(near[0] >= 200);
    assert_true(far[0] >= 40); /* a far reading is dark, never a black hole */
    assert_true(near[0] > far[0] + 100);
    assert_true(near[0] == near[1] && near[1] == near[2]); /* grey shades */
    assert_true(bg[0] >= 126 && bg[0] <= 129);
}

static void test_render_rejects_bad_input(void **state)
{
    fixture *f = *state;
    cub_render *r = NULL;
    cub_render_desc no_size = {0};
    assert_int_equal(cub_render_create(&no_size, &r), CUB_ERR_ARG);
    assert_null(r);
    assert_int_equal(cub_render_frame(f->render, NULL), CUB_ERR_ARG);
    /* A skeleton without positions, and one whose parent comes later. */
    cub_render_scene no_xyz = {.skel = &g_skel};
    assert_int_equal(cub_render_frame(f->render, &no_xyz), CUB_ERR_ARG);
    static cub_skeleton bad;
    bad = g_skel;
    bad.joints[1].parent = 5;
    cub_render_scene bad_tree = {.skel = &bad, .world_xyz_mm = g_xyz};
    assert_int_equal(cub_render_frame(f->render, &bad_tree), CUB_ERR_ARG);
}

/* The window backend, read back before the swap, gives the same picture
 * (within the same tolerance) as the headless one. */
static void test_window_backend_matches_golden(void **state)
{
    fixture *f = *state;
    int w = 0, h = 0;
    cub_display_size(f->disp, &w, &h);
    assert_int_equal(w, W);
    assert_int_equal(h, H);
    assert_false(cub_display_is_headless(f->disp));
    cub_render_scene scene = {.skel = &g_skel, .world_xyz_mm = g_xyz, .depth_raw = g_depth};
    draw(f, &scene);
    check_golden(f->rgba, "stick_pose", 0);
}

/* The probe answers for this machine and leaves SDL video shut; with only
 * a headless driver to offer it says no. */
static void test_window_available_probe_is_clean(void **state)
{
    int here = cub_display_window_available();
    const char *x11 = getenv("DISPLAY"), *wayland = getenv("WAYLAND_DISPLAY");
    printf("golden: cub_display_window_available()=%d (DISPLAY=%s WAYLAND_DISPLAY=%s)\n", here,
           x11 ? x11 : "", wayland ? wayland : "");
    assert_int_equal(SDL_WasInit(SDL_INIT_VIDEO), 0);
    setenv("SDL_VIDEODRIVER", "offscreen", 1);
    assert_int_equal(cub_display_window_available(), 0);
    assert_int_equal(SDL_WasInit(SDL_INIT_VIDEO), 0);
    unsetenv("SDL_VIDEODRIVER");
}

int main(void)
{
    const struct CMUnitTest headless[] = {
        cmocka_unit_test(test_stick_pose_matches_golden),
        cmocka_unit_test(test_frames_are_deterministic),
        cmocka_unit_test(test_inset_maps_no_reading_to_black_and_near_brighter),
        cmocka_unit_test(test_render_rejects_bad_input),
    };
    const struct CMUnitTest window[] = {
        cmocka_unit_test(test_window_backend_matches_golden),
    };
    const struct CMUnitTest probe[] = {
        cmocka_unit_test(test_window_available_probe_is_clean),
    };
    int failed = cmocka_run_group_tests_name("golden_headless", headless, setup, teardown);
    failed += cmocka_run_group_tests_name("golden_window", window, setup_window, teardown);
    failed += cmocka_run_group_tests_name("display_probe", probe, NULL, NULL);
    return failed;
}

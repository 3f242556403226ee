/* Golden images: the renderer, drawn headless (EGL surfaceless, Mesa
 * llvmpipe), compared with PNGs stored in tests/golden/expected/.
 *
 * Tolerance: a pixel differs when any channel is off by more than
 * CHANNEL_TOL (8 counts of 255); the frame passes when at most MAX_SHARE
 * (0.02%, 15 pixels) of its pixels differ. That absorbs rasteriser rounding between
 * x86-64 and aarch64 llvmpipe and between Mesa versions, while a moved
 * limb, a lost inset or a wrong colour fails.
 *
 * The text, the badge, the progress bar and the child's inset are in the
 * bear images (same tolerance as the bear: their outlined glyph edges are
 * shaded edges too) and in child_step_back (stick figure, the stick
 * tolerance plus the text's edges: 0.3%). tv_dance_1280x720 checks the
 * layout at TV size with the bear's 0.3%.
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
#include <math.h>

#include "cub/character.h"
#include "cub/floor_file.h"
#include "cub/io.h"
#include "cub/walk_clip.h"
#include "cub/judge.h"
#include "cub/pack.h"
#include "cub/png.h"
#include "cub/render.h"
#include "display.h"
#include "words.h"

#define W 320
#define H 240
#define CHANNEL_TOL 8
#define MAX_SHARE 0.0002 /* 15 pixels at 320x240: a moved hand is ~150 */
/* The lit bear has many more shaded edges than the flat stick figure, so
 * more pixels sit on a rounding boundary: 0.3% (230 pixels at 320x240).
 * A face change alone moves ~200-400 pixels and a moved arm thousands. */
#define BEAR_MAX_SHARE 0.003
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

/* ---- the bear -------------------------------------------------------------- */

/* The bear of assets/bear/bear.xml in three poses, one per face. A pose is
 * a few local rotations (axis, degrees) on top of the rest T pose; world
 * positions and rotations come from the firmware's forward kinematics. */
typedef struct bend {
    const char *joint;
    float axis[3], deg;
} bend;

static const bend DANCE[] = {
    {"LeftArm", {0, 0, 1}, 55},      {"LeftForeArm", {0, 0, 1}, 45},
    {"RightArm", {0, 0, 1}, 35},     {"RightForeArm", {0, 1, 0}, 70},
    {"Spine", {0, 0, 1}, 6},         {"Head", {0, 0, 1}, -12},
    {"LeftUpLeg", {0, 0, 1}, 18},    {"LeftLeg", {1, 0, 0}, 35},
};
static const bend DOZE[] = {
    {"LeftArm", {0, 0, 1}, -72},  {"RightArm", {0, 0, 1}, 72},
    {"Spine", {1, 0, 0}, 8},      {"Head", {1, 0, 0}, 22},
    {"Neck", {0, 0, 1}, 10},
};
static const bend CORRECT[] = {
    {"LeftArm", {0, 0, 1}, -50},     {"LeftForeArm", {0, 1, 0}, -110},
    {"RightArm", {0, 0, 1}, 50},     {"RightForeArm", {0, 1, 0}, 110},
    {"Head", {0, 0, 1}, 14},
};
#define BENDS(b) b, (int)(sizeof b / sizeof b[0])

typedef struct bear_scene {
    cub_pose pose;
    cub_vec3 world[CUB_MOTION_MAX_JOINTS];
    cub_quat rot[CUB_MOTION_MAX_JOINTS];
    float xyz[3 * CUB_MOTION_MAX_JOINTS];
    float rot_xyzw[4 * CUB_MOTION_MAX_JOINTS];
} bear_scene;

static cub_character g_bear, g_seal;
static int g_bear_loaded, g_seal_loaded;
static bear_scene g_bs;

/* assets/NAME/NAME.xml into *out once (*loaded set). */
static int load_coach(const char *name, cub_character *out, int *loaded)
{
    if (*loaded)
        return 1;
    cub_diag diag = {0};
    char path[1024];
    const char *src = getenv("CUB_SOURCE_DIR");
    snprintf(path, sizeof path, "%s/assets/%s/%s.xml", src ? src : ".", name, name);
    if (cub_character_load(path, out, &diag) != CUB_OK) {
        fprintf(stderr, "golden: cannot load %s\n", path);
        return 0;
    }
    *loaded = 1;
    return 1;
}

static int load_bear(void)
{
    return load_coach("bear", &g_bear, &g_bear_loaded);
}

static cub_quat quat_deg(const float axis[3], float deg)
{
    double h = 0.5 * deg * 3.14159265358979 / 180.0, s = sin(h);
    double n = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    double one = (double)CUB_QUAT_ONE;
    return (cub_quat){(int32_t)lround(cos(h) * one), (int32_t)lround(axis[0] / n * s * one),
                      (int32_t)lround(axis[1] / n * s * one),
                      (int32_t)lround(axis[2] / n * s * one)};
}

/* g_bs.pose (of ch) to world positions and rotations; a scene of it. */
static cub_render_scene posed(const cub_character *ch, cub_render_face face)
{
    const cub_skeleton *skel = &ch->skel;
    assert_int_equal(cub_motion_forward(skel, &g_bs.pose, g_bs.world, g_bs.rot), CUB_OK);
    cub_motion_world_to_float(g_bs.world, skel->joint_count, g_bs.xyz);
    for (int j = 0; j < skel->joint_count; j++) {
        const float one = (float)CUB_QUAT_ONE;
        g_bs.rot_xyzw[4 * j + 0] = (float)g_bs.rot[j].x / one;
        g_bs.rot_xyzw[4 * j + 1] = (float)g_bs.rot[j].y / one;
        g_bs.rot_xyzw[4 * j + 2] = (float)g_bs.rot[j].z / one;
        g_bs.rot_xyzw[4 * j + 3] = (float)g_bs.rot[j].w / one;
    }
    return (cub_render_scene){.skel = skel, .world_xyz_mm = g_bs.xyz, .character = ch,
                              .world_rot_xyzw = g_bs.rot_xyzw, .face = face};
}

/* A coach bent as listed, standing on the floor; fills g_bs and returns a
 * scene showing it with face. */
static cub_render_scene coach_pose(const cub_character *ch, const bend *bends, int n,
                                   cub_render_face face)
{
    const cub_skeleton *skel = &ch->skel;
    cub_motion_pose_rest(skel, &g_bs.pose);
    g_bs.pose.root_mm = skel->joints[0].offset_mm;
    for (int i = 0; i < n; i++) {
        int j = cub_motion_skeleton_find(skel, bends[i].joint);
        assert_true(j >= 0);
        g_bs.pose.rot[j] = quat_deg(bends[i].axis, bends[i].deg);
    }
    return posed(ch, face);
}

static cub_render_scene bear_pose(const bend *bends, int n, cub_render_face face)
{
    return coach_pose(&g_bear, bends, n, face);
}

/* The coach NAME as its shipped library (assets/clips/NAME.cubclips) has
 * clip at t_us: what cubdance draws. */
static cub_render_scene library_pose(const char *name, const cub_character *ch, const char *clip,
                                     int64_t t_us)
{
    static cub_library lib;
    cub_diag diag = {0};
    char path[1024];
    const char *src = getenv("CUB_SOURCE_DIR");
    snprintf(path, sizeof path, "%s/assets/clips/%s.cubclips", src ? src : ".", name);
    assert_int_equal(cub_pack_read(path, &lib, &diag), CUB_OK);
    int c = cub_library_find(&lib, clip);
    assert_true(c >= 0);
    assert_int_equal(lib.skel.joint_count, ch->skel.joint_count);
    assert_int_equal(cub_motion_sample(&lib.clips[c].clip, t_us, CUB_MOTION_CLAMP, &g_bs.pose),
                     CUB_OK);
    cub_library_free(&lib);
    return posed(ch, CUB_RENDER_FACE_HAPPY);
}

/* ---- fixture: one headless display and renderer for all tests ----------- */

typedef struct fixture {
    cub_display *disp;
    cub_render *render;
    cub_render *bear_render; /* framing the bear's height, as cubdance does */
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
    /* 1.3 x the bear's standing height, as cub_dance_figure_height_mm gives. */
    cub_render_desc bear_desc = {.width = W, .height = H, .figure_height_mm = 1215.0f};
    if (!load_bear() || cub_render_create(&bear_desc, &f.bear_render)) {
        fprintf(stderr, "golden: no bear renderer\n");
        cub_render_destroy(f.render);
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
    cub_render_destroy(f->bear_render);
    cub_display_close(f->disp);
    return 0;
}

static void draw_with(fixture *f, cub_render *r, const cub_render_scene *scene)
{
    assert_int_equal(cub_render_frame(r, scene), CUB_OK);
    assert_int_equal(cub_display_read_rgba(f->disp, f->rgba, sizeof f->rgba), CUB_OK);
    cub_display_swap(f->disp);
}

static void draw(fixture *f, const cub_render_scene *scene)
{
    draw_with(f, f->render, scene);
}

/* ---- comparison ----------------------------------------------------------- */

static void path_in(char *out, size_t size, const char *dir, const char *name,
                    const char *suffix)
{
    snprintf(out, size, "%s/%s%s.png", dir, name, suffix);
}

static int update_requested(int is_reference)
{
    const char *update = getenv("CUB_GOLDEN_UPDATE");
    return is_reference && update && strcmp(update, "1") == 0;
}

static void write_golden(const char *path, const uint8_t *rgba, int w, int h,
                         const char *name)
{
    assert_int_equal(cub_png_write(path, rgba, w, h), CUB_OK);
    printf("golden: %s written to %s (CUB_GOLDEN_UPDATE=1)\n", name, path);
}

/* Compare with expected/<name>.png. With CUB_GOLDEN_UPDATE=1, on the
 * reference frame (the headless backend's), a golden that is missing or
 * fails is written anew; one that passes is left alone, so an update
 * touches only the images that really changed. */
static void check_golden_sized(const uint8_t *rgba, int w, int h, const char *name,
                               int is_reference, double max_share)
{
    char expected_path[1024], actual_path[1024], diff_path[1024];
    path_in(expected_path, sizeof expected_path, CUB_GOLDEN_EXPECTED_DIR, name, "");
    int update = update_requested(is_reference);
    uint8_t *ref = NULL;
    int rw = 0, rh = 0;
    if (cub_png_read(expected_path, &ref, &rw, &rh) != CUB_OK) {
        if (update) {
            write_golden(expected_path, rgba, w, h, name);
            return;
        }
        fail_msg("golden: cannot read %s; to create it run with CUB_GOLDEN_UPDATE=1",
                 expected_path);
    }
    if (rw != w || rh != h) {
        free(ref);
        if (update) {
            write_golden(expected_path, rgba, w, h, name);
            return;
        }
        fail_msg("golden: %s is %dx%d, the frame is %dx%d", expected_path, rw, rh, w, h);
    }
    uint8_t *diff = malloc((size_t)w * h * 4);
    assert_non_null(diff);
    int max_diff = 0, over = 0;
    for (int i = 0; i < w * h; i++) {
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
    double share = (double)over / ((double)w * h);
    printf("golden: %s max_channel_diff=%d differing_pixels=%d (%.3f%%) of %d; "
           "tolerance: channel<=%d, share<=%.1f%%\n",
           name, max_diff, over, 100.0 * share, w * h, CHANNEL_TOL, 100.0 * max_share);
    if (share > max_share && update) {
        free(diff);
        write_golden(expected_path, rgba, w, h, name);
        return;
    }
    if (share > max_share) {
        path_in(actual_path, sizeof actual_path, CUB_GOLDEN_OUT_DIR, name, "_actual");
        path_in(diff_path, sizeof diff_path, CUB_GOLDEN_OUT_DIR, name, "_diff");
        cub_png_write(actual_path, rgba, w, h);
        cub_png_write(diff_path, diff, w, h);
        free(diff);
        fail_msg("golden: %s differs from %s: %.3f%% of pixels over %d counts (max %.1f%%); "
                 "see %s and %s",
                 name, expected_path, 100.0 * share, CHANNEL_TOL, 100.0 * max_share,
                 actual_path, diff_path);
    }
    free(diff);
}

static void check_golden_within(const uint8_t *rgba, const char *name, int is_reference,
                                double max_share)
{
    check_golden_sized(rgba, W, H, name, is_reference, max_share);
}

static void check_golden(const uint8_t *rgba, const char *name, int is_reference)
{
    check_golden_within(rgba, name, is_reference, MAX_SHARE);
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

/* ---- what the child reads ------------------------------------------------ */

/* A child about 1.2 m tall facing the camera at depth z_mm, arms out and
 * up, in the tracker's camera space (mm, y up; the camera 0.8 m above the
 * floor), with the tracker's verdict status. */
static cub_track_skeleton g_child;

static void child_at(float z_mm, int32_t status)
{
    static const float XY[CUB_KJ_COUNT][2] = {
        [CUB_KJ_HIP_CENTRE] = {0, -150},     [CUB_KJ_SPINE] = {0, 0},
        [CUB_KJ_SHOULDER_CENTRE] = {0, 200}, [CUB_KJ_HEAD] = {0, 360},
        [CUB_KJ_SHOULDER_L] = {-150, 180},   [CUB_KJ_ELBOW_L] = {-330, 260},
        [CUB_KJ_WRIST_L] = {-450, 380},      [CUB_KJ_HAND_L] = {-490, 430},
        [CUB_KJ_SHOULDER_R] = {150, 180},    [CUB_KJ_ELBOW_R] = {320, 100},
        [CUB_KJ_WRIST_R] = {430, -10},       [CUB_KJ_HAND_R] = {470, -50},
        [CUB_KJ_HIP_L] = {-90, -190},        [CUB_KJ_KNEE_L] = {-120, -480},
        [CUB_KJ_ANKLE_L] = {-130, -760},     [CUB_KJ_FOOT_L] = {-150, -790},
        [CUB_KJ_HIP_R] = {90, -190},         [CUB_KJ_KNEE_R] = {110, -480},
        [CUB_KJ_ANKLE_R] = {120, -760},      [CUB_KJ_FOOT_R] = {140, -790},
    };
    memset(&g_child, 0, sizeof g_child);
    g_child.status = status;
    for (int j = 0; j < CUB_KJ_COUNT; j++) {
        g_child.joint_mm[j] = (cub_vec3){(cub_q16)(XY[j][0] * 65536.0f),
                                         (cub_q16)(XY[j][1] * 65536.0f),
                                         (cub_q16)(z_mm * 65536.0f)};
        g_child.confidence[j] = 65536;
    }
}

/* The icon's pose: the dancing bear's joints, kept apart from g_bs (which
 * the scene's own pose reuses). */
static float g_icon_xyz[3 * CUB_MOTION_MAX_JOINTS];

static void icon_from_dance(void)
{
    bear_pose(BENDS(DANCE), CUB_RENDER_FACE_HAPPY);
    memcpy(g_icon_xyz, g_bs.xyz, sizeof g_icon_xyz);
}

/* ---- tests ------------------------------------------------------------------ */

static void test_stick_pose_matches_golden(void **state)
{
    fixture *f = *state;
    cub_render_scene scene = {.skel = &g_skel, .world_xyz_mm = g_xyz, .depth_raw = g_depth};
    draw(f, &scene);
    check_golden(f->rgba, "stick_pose", 1);
}

static void test_bear_dancing_happy_matches_golden(void **state)
{
    fixture *f = *state;
    cub_render_scene scene = bear_pose(BENDS(DANCE), CUB_RENDER_FACE_HAPPY);
    draw_with(f, f->bear_render, &scene);
    check_golden_within(f->rgba, "bear_dance_happy", 1, BEAR_MAX_SHARE);
}

/* The second coach (assets/seal/seal.xml) bent as the bear is in
 * bear_dance_happy, the tail where the bear's left leg is. */
static void test_seal_dancing_happy_matches_golden(void **state)
{
    static const bend SEAL_DANCE[] = {
        {"LeftArm", {0, 0, 1}, 55},  {"LeftForeArm", {0, 0, 1}, 45},
        {"RightArm", {0, 0, 1}, 35}, {"RightForeArm", {0, 1, 0}, 70},
        {"Torso", {0, 0, 1}, 6},     {"Head", {0, 0, 1}, -12},
        {"Tail", {0, 0, 1}, 18},     {"TailFin", {1, 0, 0}, 35},
    };
    fixture *f = *state;
    assert_true(load_coach("seal", &g_seal, &g_seal_loaded));
    cub_render_scene scene = coach_pose(&g_seal, BENDS(SEAL_DANCE), CUB_RENDER_FACE_HAPPY);
    draw_with(f, f->bear_render, &scene);
    check_golden_within(f->rgba, "seal_dance_happy", 1, BEAR_MAX_SHARE);
}

/* Both coaches at the bottom of the squat, each from its shipped library
 * (the seal's made from the bear's by `cubtool coach seal`). */
static void test_both_coaches_squat_from_their_libraries(void **state)
{
    fixture *f = *state;
    assert_true(load_coach("seal", &g_seal, &g_seal_loaded));
    cub_render_scene scene = library_pose("bear", &g_bear, "squat", 1333333);
    draw_with(f, f->bear_render, &scene);
    check_golden_within(f->rgba, "coach_bear_squat", 1, BEAR_MAX_SHARE);
    scene = library_pose("seal", &g_seal, "squat", 1333333);
    draw_with(f, f->bear_render, &scene);
    check_golden_within(f->rgba, "coach_seal_squat", 1, BEAR_MAX_SHARE);
}

static void test_bear_doze_sleepy_matches_golden(void **state)
{
    fixture *f = *state;
    cub_render_scene scene = bear_pose(BENDS(DOZE), CUB_RENDER_FACE_SLEEPY);
    draw_with(f, f->bear_render, &scene);
    check_golden_within(f->rgba, "bear_doze_sleepy", 1, BEAR_MAX_SHARE);
}

static void test_bear_correcting_worried_matches_golden(void **state)
{
    fixture *f = *state;
    icon_from_dance();
    cub_render_scene scene = bear_pose(BENDS(CORRECT), CUB_RENDER_FACE_WORRIED);
    scene.depth_raw = g_depth;
    scene.hint = "Clap with me!";
    scene.icon_xyz_mm = g_icon_xyz;
    scene.progress = 0.4f;
    scene.has_progress = 1;
    draw_with(f, f->bear_render, &scene);
    check_golden_within(f->rgba, "bear_correct_worried", 1, BEAR_MAX_SHARE);
}

/* While the box waits: the bear dimmed behind "Press START!" and a play
 * button; no hint, badge or bar even when the scene has them. */
static void test_idle_screen_matches_golden(void **state)
{
    fixture *f = *state;
    icon_from_dance();
    cub_render_scene scene = bear_pose(BENDS(DOZE), CUB_RENDER_FACE_HAPPY);
    scene.idle = 1;
    scene.title = cub_words_title();
    scene.hint = "not shown while idle";
    scene.icon_xyz_mm = g_icon_xyz;
    scene.has_progress = 1;
    draw_with(f, f->bear_render, &scene);
    check_golden_within(f->rgba, "idle_press_start", 1, BEAR_MAX_SHARE);
}

/* The child too close: orange bones over the depth image, "Step back". */
static void test_child_inset_cue_matches_golden(void **state)
{
    fixture *f = *state;
    child_at(1300.0f, CUB_TRACK_TOO_CLOSE);
    cub_render_scene scene = {.skel = &g_skel, .world_xyz_mm = g_xyz, .depth_raw = g_depth,
                              .child = &g_child, .child_cue = cub_words_cue(g_child.status)};
    draw(f, &scene);
    check_golden_within(f->rgba, "child_step_back", 1, BEAR_MAX_SHARE);
}

/* The cue is the status's words (words.c): above the inset something is
 * drawn for too far, too close and partly out, nothing for a child tracked
 * well or for nobody; the three cues differ from each other. */
static void test_child_cue_follows_status(void **state)
{
    fixture *f = *state;
    static uint8_t plain[W * H * 4], cue[3][W * H * 4];
    cub_render_scene scene = {.background_rgb = {0.5f, 0.5f, 0.5f}, .depth_raw = g_depth};
    draw(f, &scene);
    memcpy(plain, f->rgba, sizeof plain);
    scene.child = &g_child;
    const int32_t statuses[5] = {CUB_TRACK_TOO_FAR, CUB_TRACK_TOO_CLOSE, CUB_TRACK_PARTLY_OUT,
                                 CUB_TRACK_OK, CUB_TRACK_NO_PLAYER};
    for (int i = 0; i < 5; i++) {
        child_at(2200.0f, statuses[i]);
        scene.child_cue = cub_words_cue(statuses[i]);
        draw(f, &scene);
        /* Rows above the inset's top (counted from the top), whole width. */
        int differ = 0;
        for (int y = INSET_Y0 - 30; y < INSET_Y0 - 2; y++)
            for (int x = 0; x < W; x++)
                differ += abs(px(f, x, y)[0] - plain[4 * (y * W + x)]) > CHANNEL_TOL;
        printf("golden: status %d: %d pixels above the inset differ\n", statuses[i], differ);
        if (i < 3) {
            assert_true(differ > 100);
            memcpy(cue[i], f->rgba, sizeof cue[i]);
        } else {
            assert_int_equal(differ, 0);
        }
    }
    assert_memory_not_equal(cue[0], cue[1], sizeof cue[0]);
    assert_memory_not_equal(cue[1], cue[2], sizeof cue[0]);
}

/* A font that cannot be read: no renderer, an error naming the file and
 * why; a file that is not TrueType likewise. */
static void test_render_refuses_missing_font(void **state)
{
    (void)state;
    char why[512] = "";
    cub_render *r = NULL;
    cub_render_desc desc = {.width = W, .height = H, .font_path = "/nonexistent/cub.ttf",
                            .error = why, .error_size = sizeof why};
    assert_int_equal(cub_render_create(&desc, &r), CUB_ERR_IO);
    assert_null(r);
    assert_string_equal(why, "cannot load font /nonexistent/cub.ttf: No such file or directory");
    desc.font_path = CUB_GOLDEN_EXPECTED_DIR "/stick_pose.png";
    assert_int_equal(cub_render_create(&desc, &r), CUB_ERR_FORMAT);
    assert_null(r);
    assert_non_null(strstr(why, "stick_pose.png: not a TrueType font"));
}

/* A 4K and an 8K screen (issue 18: above h ~3300 the h / 8 glyphs did not
 * fit a 4096 atlas, and the renderer refused the font): the glyphs are
 * baked at most 270 px high and drawn scaled, so both get a renderer. */
static void test_render_at_4k_and_8k(void **state)
{
    (void)state;
    static const int sizes[][2] = {{3840, 2160}, {7680, 4320}};
    for (int i = 0; i < 2; i++) {
        char why[512] = "";
        cub_render *r = NULL;
        cub_render_desc desc = {.width = sizes[i][0], .height = sizes[i][1], .error = why,
                                .error_size = sizeof why};
        cub_err e = cub_render_create(&desc, &r);
        printf("golden: %dx%d: %s%s\n", sizes[i][0], sizes[i][1], e ? "refused: " : "ok", why);
        assert_int_equal(e, CUB_OK);
        assert_non_null(r);
        cub_render_destroy(r);
    }
}

/* Only the face changes between faces: the pixels that differ between the
 * happy and the sleepy bear all lie in the head's box (the upper part of
 * the bear, centre columns), and there are enough of them to see. */
static void test_bear_faces_differ_only_on_the_head(void **state)
{
    fixture *f = *state;
    static uint8_t happy[W * H * 4];
    cub_render_scene scene = bear_pose(BENDS(DOZE), CUB_RENDER_FACE_HAPPY);
    draw_with(f, f->bear_render, &scene);
    memcpy(happy, f->rgba, sizeof happy);
    scene.face = CUB_RENDER_FACE_SLEEPY;
    draw_with(f, f->bear_render, &scene);
    int differ = 0, outside = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const uint8_t *a = happy + 4 * (y * W + x), *b = f->rgba + 4 * (y * W + x);
            if (abs(a[0] - b[0]) + abs(a[1] - b[1]) + abs(a[2] - b[2]) <= 3 * CHANNEL_TOL)
                continue;
            differ++;
            outside += x < W / 3 || x > 2 * W / 3 || y > 3 * H / 5; /* y from the top */
        }
    printf("golden: happy vs sleepy: %d pixels differ, %d outside the head's box\n", differ,
           outside);
    assert_true(differ >= 40);
    assert_int_equal(outside, 0);
}

/* A character the renderer cannot show is refused with nothing drawn: an
 * unknown face, too many joints to skin, a part on a joint that is not there. */
/* ---- the winged bear (issue 22) --------------------------------------------- */

/* assets/bear/bear_winged.xml and the child clip `cubtool evolve` made
 * (bird_flying.wings.bvh: the bear's bird_flying with our bird's wings).
 * WINGED_FRAME is mid-flap: the wings on the down stroke, near level. */
#define WINGED_FRAME 61

static cub_character g_winged;
static cub_io_motion g_winged_clip;

static void load_winged(void)
{
    cub_diag diag = {0};
    char xml[1024], bvh[1024];
    const char *src = getenv("CUB_SOURCE_DIR");
    snprintf(xml, sizeof xml, "%s/assets/bear/bear_winged.xml", src ? src : ".");
    snprintf(bvh, sizeof bvh, "%s/assets/bear/bird_flying.wings.bvh", src ? src : ".");
    assert_int_equal(cub_character_load(xml, &g_winged, &diag), CUB_OK);
    assert_int_equal(cub_io_load_bvh(bvh, NULL, &g_winged_clip, &diag), CUB_OK);
}

/* The child's frame f on the child's own skeleton (bear joints and wings). */
static cub_render_scene winged_pose(int f)
{
    const cub_skeleton *skel = &g_winged_clip.skel;
    int64_t t_us = (int64_t)f * g_winged_clip.clip.frame_ns / 1000;
    assert_int_equal(cub_motion_sample(&g_winged_clip.clip, t_us, CUB_MOTION_CLAMP, &g_bs.pose),
                     CUB_OK);
    assert_int_equal(cub_motion_forward(skel, &g_bs.pose, g_bs.world, g_bs.rot), CUB_OK);
    cub_motion_world_to_float(g_bs.world, skel->joint_count, g_bs.xyz);
    for (int j = 0; j < skel->joint_count; j++) {
        const float one = (float)CUB_QUAT_ONE;
        g_bs.rot_xyzw[4 * j + 0] = (float)g_bs.rot[j].x / one;
        g_bs.rot_xyzw[4 * j + 1] = (float)g_bs.rot[j].y / one;
        g_bs.rot_xyzw[4 * j + 2] = (float)g_bs.rot[j].z / one;
        g_bs.rot_xyzw[4 * j + 3] = (float)g_bs.rot[j].w / one;
    }
    return (cub_render_scene){.skel = skel, .world_xyz_mm = g_bs.xyz, .character = &g_winged,
                              .world_rot_xyzw = g_bs.rot_xyzw, .face = CUB_RENDER_FACE_HAPPY};
}

static void test_winged_bear_mid_flap_matches_golden(void **state)
{
    fixture *f = *state;
    load_winged();
    cub_render_scene scene = winged_pose(WINGED_FRAME);
    draw_with(f, f->bear_render, &scene);
    check_golden_within(f->rgba, "winged_bear_mid_flap", 1, BEAR_MAX_SHARE);
    cub_io_motion_free(&g_winged_clip);
}

/* ---- the forest floor (issue 24) ------------------------------------------- */

/* Where the bear stands in bear_on_forest_floor: on a hillock of the
 * shipped floor (177 mm at this sample), 3.6 m from its dancing spot. */
#define FLOOR_SPOT_X 3000.0f
#define FLOOR_SPOT_Z (-2000.0f)

static cub_floor g_floor;

/* assets/floor/forest.floor and the terrain of it (the gait planner's). */
static void load_floor(cub_gait_terrain *t)
{
    cub_diag diag = {0};
    char path[1024];
    const char *src = getenv("CUB_SOURCE_DIR");
    snprintf(path, sizeof path, "%s/assets/floor/%s", src ? src : ".", "forest.floor");
    assert_int_equal(cub_floor_load(path, &g_floor, &diag), CUB_OK);
    assert_int_equal(cub_floor_terrain(&g_floor, t), CUB_OK);
}

/* The posed coach of g_bs moved so its root is over (x, z) of the floor
 * and its feet as high as the terrain there (they stood on y = 0): the
 * bear's root position over the floor, as the walker's mid-step golden
 * will place it. Returns that height. */
static float stand_over(const cub_render_scene *scene, const cub_gait_terrain *t, float x, float z)
{
    float y = (float)cub_gait_height(t, (cub_q16)lroundf(x * 65536.0f),
                                     (cub_q16)lroundf(z * 65536.0f)) / 65536.0f;
    float dx = x - g_bs.xyz[0], dz = z - g_bs.xyz[2];
    for (int j = 0; j < scene->skel->joint_count; j++) {
        g_bs.xyz[3 * j + 0] += dx;
        g_bs.xyz[3 * j + 1] += y;
        g_bs.xyz[3 * j + 2] += dz;
    }
    return y;
}

/* The bear on the box's forest floor: rolling ground, the trees and
 * bushes standing on it, the bear on a hillock with its feet on the
 * ground; the camera follows it there. Then the whole floor seen from
 * further back. The same renderer back on the
 * meadow (no floor) draws bear_dance_happy again, and a floor that breaks
 * cub/floor.h's limits is refused. */
static void test_bear_on_the_forest_floor_matches_golden(void **state)
{
    fixture *f = *state;
    cub_gait_terrain t;
    load_floor(&t);
    cub_render *r = NULL;
    cub_render_desc d = {.width = W, .height = H, .figure_height_mm = 1215.0f};
    assert_int_equal(cub_render_create(&d, &r), CUB_OK);
    assert_int_equal(cub_render_set_floor(r, &g_floor), CUB_OK);
    cub_render_scene scene = bear_pose(BENDS(DANCE), CUB_RENDER_FACE_HAPPY);
    float y = stand_over(&scene, &t, FLOOR_SPOT_X, FLOOR_SPOT_Z);
    printf("golden: the bear stands at x=%.0f z=%.0f on ground %.1f mm high\n", FLOOR_SPOT_X,
           FLOOR_SPOT_Z, y);
    assert_true(y > 150.0f);
    draw_with(f, r, &scene);
    check_golden_within(f->rgba, "bear_on_forest_floor", 1, BEAR_MAX_SHARE);
    /* The box's own view of its floor from further back and above: the
     * bear dancing on its flat spot, the log behind it, the stones. */
    scene = bear_pose(BENDS(DANCE), CUB_RENDER_FACE_HAPPY);
    cub_render_set_view(r, &(cub_render_view){.pitch_deg = 20.0f, .zoom = 0.4f});
    draw_with(f, r, &scene);
    cub_render_set_view(r, NULL);
    check_golden_within(f->rgba, "forest_floor_wide", 1, BEAR_MAX_SHARE);

    cub_floor bad = g_floor;
    bad.nx = 1;
    assert_int_equal(cub_render_set_floor(r, &bad), CUB_ERR_ARG);
    assert_int_equal(cub_render_set_floor(r, NULL), CUB_OK);
    scene = bear_pose(BENDS(DANCE), CUB_RENDER_FACE_HAPPY);
    draw_with(f, r, &scene);
    check_golden_within(f->rgba, "bear_dance_happy", 0, BEAR_MAX_SHARE);
    cub_render_destroy(r);
}

/* The bear's walk (assets/clips/bear_walk.bvh) through the gait walker
 * over the shipped floor, across the camera's view (along +x) up the
 * hillock of bear_on_forest_floor: WALK_FRAMES frames in, one foot
 * swinging and the other planted, as the box draws it. */
#define WALK_FRAMES 52
static cub_io_motion g_walk;
static cub_walk_clip g_walk_clip; /* its tracks and phases for the walker */
static cub_gait_walker g_walker;

static void walk_on_floor(const cub_gait_terrain *t)
{
    cub_diag diag = {0};
    char path[1024];
    const char *src = getenv("CUB_SOURCE_DIR");
    snprintf(path, sizeof path, "%s/assets/clips/bear_walk.bvh", src ? src : ".");
    assert_int_equal(cub_io_load_bvh(path, &(cub_io_desc){0}, &g_walk, &diag), CUB_OK);
    const cub_skeleton *s = &g_walk.skel;
    const int ankle[2] = {cub_motion_skeleton_find(s, "LeftFoot"),
                          cub_motion_skeleton_find(s, "RightFoot")};
    const int toe[2] = {cub_motion_skeleton_find(s, "LeftFoot_end"),
                        cub_motion_skeleton_find(s, "RightFoot_end")};
    assert_int_equal(cub_walk_clip_make(&g_walk_clip, &g_walk.clip, ankle, toe), CUB_OK);
    cub_gait_walk_params p = {.start_mm = {CUB_Q16_INT(1900), 0, CUB_Q16_INT((int)FLOOR_SPOT_Z)},
                              .dir_x = CUB_Q16_INT(1)};
    assert_int_equal(cub_gait_walker_init(&g_walker, &g_walk_clip.wc, t, &p), CUB_OK);
    const cub_vec3 to = {CUB_Q16_INT(5000), 0, CUB_Q16_INT((int)FLOOR_SPOT_Z)};
    const cub_pose *pose = NULL;
    for (int i = 0; i < WALK_FRAMES; i++)
        assert_int_equal(cub_gait_walker_step(&g_walker, to, &pose), CUB_OK);
}

/* The walker's pose (the clip's skeleton, written by the retargeter from
 * the bear) as the bear's: the same joints in the same order, only the
 * end sites named otherwise (LeftFoot_end for LeftToe_end). */
static void walker_as_bear(void)
{
    const cub_skeleton *a = &g_walk.skel, *b = &g_bear.skel;
    assert_int_equal(a->joint_count, b->joint_count);
    for (int j = 0; j < b->joint_count; j++)
        if (!b->joints[j].is_end_site) assert_string_equal(a->joints[j].name, b->joints[j].name);
    g_bs.pose = g_walker.pose;
}

/* The acceptance's image: the bear mid-step on the rolling floor. */
static void test_bear_walks_mid_step_on_the_floor_matches_golden(void **state)
{
    fixture *f = *state;
    cub_gait_terrain t;
    load_floor(&t);
    walk_on_floor(&t);
    const cub_gait_walk_foot *l = &g_walker.feet[0], *r = &g_walker.feet[1];
    assert_int_equal(l->swinging + r->swinging, 1); /* mid-step: one foot up */
    const cub_gait_walk_foot *down = l->swinging ? r : l;
    cub_q16 ground = cub_gait_height(&t, down->hold_mm.x, down->hold_mm.z);
    cub_q16 root_ground = cub_gait_ground_height(&t, g_walker.pose.root_mm.x,
                                                 g_walker.pose.root_mm.z);
    printf("golden: the walking bear after %d frames: root at x=%.0f z=%.0f over ground %.1f mm; "
           "%s foot swinging, the other planted at y=%.1f (ground under its ankle %.1f mm)\n",
           WALK_FRAMES, g_walker.pose.root_mm.x / 65536.0, g_walker.pose.root_mm.z / 65536.0,
           root_ground / 65536.0, l->swinging ? "left" : "right", down->hold_mm.y / 65536.0,
           ground / 65536.0);
    /* planted: on the highest ground under its base (ankle, middle, toe),
     * which the planner keeps within 30 mm of the ankle's */
    assert_true(down->hold_mm.y >= ground && down->hold_mm.y <= ground + CUB_Q16_INT(30));
    assert_true(abs(root_ground) > CUB_Q16_INT(30)); /* on the hills, not the flat spot */
    walker_as_bear();
    cub_render *r3 = NULL;
    cub_render_desc d = {.width = W, .height = H, .figure_height_mm = 1215.0f};
    assert_int_equal(cub_render_create(&d, &r3), CUB_OK);
    assert_int_equal(cub_render_set_floor(r3, &g_floor), CUB_OK);
    cub_render_scene scene = posed(&g_bear, CUB_RENDER_FACE_HAPPY);
    draw_with(f, r3, &scene);
    check_golden_within(f->rgba, "bear_walks_on_forest_floor", 1, BEAR_MAX_SHARE);
    cub_render_destroy(r3);
    cub_walk_clip_free(&g_walk_clip);
    cub_io_motion_free(&g_walk);
}

/* A clip without the wings (the bear's skeleton): the winged bear is the
 * bear, pixel for pixel as its golden. */
static void test_winged_bear_without_wings_is_the_bear(void **state)
{
    fixture *f = *state;
    load_winged();
    cub_io_motion_free(&g_winged_clip);
    cub_render_scene scene = bear_pose(BENDS(DANCE), CUB_RENDER_FACE_HAPPY);
    scene.character = &g_winged;
    draw_with(f, f->bear_render, &scene);
    check_golden_within(f->rgba, "bear_dance_happy", 0, BEAR_MAX_SHARE);
}

static void test_bear_rejects_bad_character(void **state)
{
    fixture *f = *state;
    cub_render_scene scene = bear_pose(BENDS(DANCE), CUB_RENDER_FACE_HAPPY);
    scene.face = CUB_RENDER_FACE_COUNT;
    assert_int_equal(cub_render_frame(f->bear_render, &scene), CUB_ERR_ARG);
    static cub_character big;
    big = g_bear;
    big.skel.joint_count = CUB_MOTION_MAX_JOINTS;
    for (int j = g_bear.skel.joint_count; j < big.skel.joint_count; j++) {
        snprintf(big.skel.joints[j].name, sizeof big.skel.joints[j].name, "extra%d", j);
        big.skel.joints[j].parent = 0;
    }
    scene = bear_pose(BENDS(DANCE), CUB_RENDER_FACE_HAPPY);
    scene.character = &big;
    assert_int_equal(cub_render_frame(f->bear_render, &scene), CUB_ERR_ARG);
    static cub_character stray;
    stray = g_bear;
    stray.parts[0].joint = stray.skel.joint_count;
    scene.character = &stray;
    assert_int_equal(cub_render_frame(f->bear_render, &scene), CUB_ERR_ARG);
    /* The renderer still draws the real bear afterwards. */
    scene.character = &g_bear;
    assert_int_equal(cub_render_frame(f->bear_render, &scene), CUB_OK);
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
    /* A hint changed and changed back (laid out again each time) draws
     * the same bytes; a different hint draws different ones. */
    static uint8_t hinted[W * H * 4];
    scene.hint = "Wave!";
    draw(f, &scene);
    memcpy(hinted, f->rgba, sizeof hinted);
    assert_memory_not_equal(first, hinted, sizeof first);
    scene.hint = "Jump!";
    draw(f, &scene);
    assert_memory_not_equal(hinted, f->rgba, sizeof hinted);
    scene.hint = "Wave!";
    draw(f, &scene);
    assert_memory_equal(hinted, f->rgba, sizeof hinted);
}


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

/* ---- at TV size: the layout at 1280x720 ------------------------------------ */

#define TV_W 1280
#define TV_H 720

typedef struct tv_fixture {
    cub_display *disp;
    cub_render *render;
    uint8_t *rgba;
} tv_fixture;

static int setup_tv(void **state)
{
    static tv_fixture t;
    char err[256] = "";
    if (cub_display_open_headless(TV_W, TV_H, &t.disp, err, sizeof err)) {
        fprintf(stderr, "golden: cannot open a %dx%d headless display: %s\n", TV_W, TV_H, err);
        return -1;
    }
    cub_render_desc desc = {.width = TV_W, .height = TV_H, .figure_height_mm = 1215.0f};
    t.rgba = malloc((size_t)TV_W * TV_H * 4);
    if (!t.rgba || !load_bear() || cub_render_create(&desc, &t.render)) {
        free(t.rgba);
        cub_display_close(t.disp);
        return -1;
    }
    build_depth();
    *state = &t;
    return 0;
}

static int teardown_tv(void **state)
{
    tv_fixture *t = *state;
    cub_render_destroy(t->render);
    cub_display_close(t->disp);
    free(t->rgba);
    return 0;
}

/* Dancing at TV size with everything on: bar, badge, hint, the child
 * tracked well over the depth image (no cue). */
static void test_tv_dance_layout_matches_golden(void **state)
{
    tv_fixture *t = *state;
    icon_from_dance();
    child_at(2200.0f, CUB_TRACK_OK);
    cub_render_scene scene = bear_pose(BENDS(DANCE), CUB_RENDER_FACE_HAPPY);
    scene.hint = "Wave your paws up high!";
    scene.icon_xyz_mm = g_icon_xyz;
    scene.progress = 0.65f;
    scene.has_progress = 1;
    scene.depth_raw = g_depth;
    scene.child = &g_child;
    scene.child_cue = cub_words_cue(g_child.status);
    assert_int_equal(cub_render_frame(t->render, &scene), CUB_OK);
    assert_int_equal(cub_display_read_rgba(t->disp, t->rgba, (size_t)TV_W * TV_H * 4), CUB_OK);
    cub_display_swap(t->disp);
    check_golden_sized(t->rgba, TV_W, TV_H, "tv_dance_1280x720", 1, BEAR_MAX_SHARE);
}

/* The lower half of the TV frame (top-first rows): the hint and the
 * child's corner, without the bear's upper body. */
#define TV_CROP_Y0 (TV_H / 2)
#define TV_CROP_H (TV_H - TV_CROP_Y0)

static void draw_tv(tv_fixture *t, const cub_render_scene *scene)
{
    assert_int_equal(cub_render_frame(t->render, scene), CUB_OK);
    assert_int_equal(cub_display_read_rgba(t->disp, t->rgba, (size_t)TV_W * TV_H * 4), CUB_OK);
    cub_display_swap(t->disp);
}

/* Pixels of the mark's pink (1.0, 0.35, 0.80) in columns [x0, x1) of the
 * inset's rows; the inset at TV size: 256x192, 16 px from the right and
 * bottom edges. */
static int pink_in(const tv_fixture *t, int x0, int x1)
{
    int n = 0;
    for (int y = TV_H - 16 - 192; y < TV_H - 16; y++)
        for (int x = x0; x < x1; x++) {
            const uint8_t *p = t->rgba + 4 * ((size_t)y * TV_W + (size_t)x);
            n += p[0] > 220 && p[1] > 60 && p[1] < 130 && p[2] > 170 && p[2] < 235;
        }
    return n;
}

/* A wrong verdict's correction at TV size: the fault's words from the
 * shipped table's kind ("The other arm!") and, in the child's corner, the
 * arm to move (the child's right, at +x: the inset's right half) in pink
 * and wider. The same frame without the mark has no pink and differs
 * only in the inset. */
static void test_tv_fault_marks_the_limb_to_move(void **state)
{
    tv_fixture *t = *state;
    static uint8_t plain[TV_W * TV_H * 4];
    icon_from_dance();
    child_at(2200.0f, CUB_TRACK_OK);
    cub_render_scene scene = bear_pose(BENDS(CORRECT), CUB_RENDER_FACE_WORRIED);
    scene.hint = "The other arm!";
    scene.icon_xyz_mm = g_icon_xyz;
    scene.progress = 0.3f;
    scene.has_progress = 1;
    scene.depth_raw = g_depth;
    scene.child = &g_child;
    draw_tv(t, &scene);
    memcpy(plain, t->rgba, sizeof plain);
    scene.child_mark = cub_judge_limb_joints(CUB_JUDGE_LIMB_RIGHT_ARM);
    draw_tv(t, &scene);
    /* the collar bone starts at the inset's middle column (the child's
     * centre, x = 0): its end cap may cross it by a few pixels */
    const int x0 = TV_W - 16 - 256, mid = x0 + 128;
    int left = pink_in(t, x0, mid - 8), right = pink_in(t, mid, TV_W - 16);
    int outside = 0;
    for (int y = 0; y < TV_H; y++)
        for (int x = 0; x < TV_W; x++) {
            int in = x >= x0 - 8 && y >= TV_H - 16 - 192 - 8;
            const size_t i = 4 * ((size_t)y * TV_W + (size_t)x);
            const uint8_t *a = plain + i, *b = t->rgba + i;
            outside += !in && (a[0] != b[0] || a[1] != b[1] || a[2] != b[2]);
        }
    printf("golden: marked right arm: %d pink pixels in the inset's right half, %d left of it; "
           "%d pixels changed outside the inset\n", right, left, outside);
    assert_true(right > 300);
    assert_int_equal(left, 0);
    assert_int_equal(outside, 0);
    memcpy(t->rgba, plain, sizeof plain); /* restore for the pink count of the plain frame */
    assert_int_equal(pink_in(t, x0, TV_W - 16), 0);
    draw_tv(t, &scene);
    check_golden_sized(t->rgba + 4 * (size_t)TV_CROP_Y0 * TV_W, TV_W, TV_CROP_H,
                       "tv_fault_other_arm", 1, BEAR_MAX_SHARE);
}

int main(void)
{
    const struct CMUnitTest headless[] = {
        cmocka_unit_test(test_stick_pose_matches_golden),
        cmocka_unit_test(test_bear_dancing_happy_matches_golden),
        cmocka_unit_test(test_bear_doze_sleepy_matches_golden),
        cmocka_unit_test(test_seal_dancing_happy_matches_golden),
        cmocka_unit_test(test_both_coaches_squat_from_their_libraries),
        cmocka_unit_test(test_bear_correcting_worried_matches_golden),
        cmocka_unit_test(test_idle_screen_matches_golden),
        cmocka_unit_test(test_child_inset_cue_matches_golden),
        cmocka_unit_test(test_child_cue_follows_status),
        cmocka_unit_test(test_render_refuses_missing_font),
        cmocka_unit_test(test_render_at_4k_and_8k),
        cmocka_unit_test(test_bear_faces_differ_only_on_the_head),
        cmocka_unit_test(test_bear_rejects_bad_character),
        cmocka_unit_test(test_winged_bear_mid_flap_matches_golden),
        cmocka_unit_test(test_winged_bear_without_wings_is_the_bear),
        cmocka_unit_test(test_bear_on_the_forest_floor_matches_golden),
        cmocka_unit_test(test_bear_walks_mid_step_on_the_floor_matches_golden),
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
    const struct CMUnitTest tv[] = {
        cmocka_unit_test(test_tv_dance_layout_matches_golden),
        cmocka_unit_test(test_tv_fault_marks_the_limb_to_move),
    };
    int failed = cmocka_run_group_tests_name("golden_headless", headless, setup, teardown);
    failed += cmocka_run_group_tests_name("golden_tv", tv, setup_tv, teardown_tv);
    failed += cmocka_run_group_tests_name("golden_window", window, setup_window, teardown);
    failed += cmocka_run_group_tests_name("display_probe", probe, NULL, NULL);
    return failed;
}

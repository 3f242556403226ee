/* tracker: garbage frames, a synthetic capsule body (joint errors printed
 * and bounded), player selection with two bodies, the real Skeltrack frames
 * against the hand labels, and a determinism hash pinned for x86-64 and
 * aarch64. The body renderer is integer-only so the frames themselves are
 * identical on every CPU. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/forest.h"
#include "cub/track.h"

#define W CUB_KINECT_WIDTH
#define H CUB_KINECT_HEIGHT
#define F CUB_KINECT_FOCAL_PX

static uint16_t frame[W * H];
static int32_t zbuf[W * H];
static uint16_t mm_to_raw_tab[8192];

static void build_mm_to_raw(void)
{
    /* the inverse of the table: the raw whose depth is nearest */
    int raw = 0;
    for (int mm = 0; mm < 8192; mm++) {
        while (raw < 2046 && cub_track_raw_to_mm_int((uint16_t)(raw + 1)) &&
               cub_track_raw_to_mm_int((uint16_t)(raw + 1)) <= mm)
            raw++;
        mm_to_raw_tab[mm] = (uint16_t)raw;
    }
}

/* ---- a body of spheres along bones, in integer millimetres ------------ */

typedef struct p3 {
    int32_t x, y, z;
} p3;

static void clear_scene(int floor_y_mm)
{
    for (int v = 0; v < H; v++)
        for (int u = 0; u < W; u++) {
            int32_t z = 0;
            /* a level floor floor_y_mm below the camera, up to 4 m */
            if (floor_y_mm && v > CUB_KINECT_CY + 2) z = floor_y_mm * F / (v - CUB_KINECT_CY);
            zbuf[v * W + u] = z > 0 && z < 4000 ? z : INT32_MAX;
        }
}

static void sphere(p3 c, int32_t r)
{
    int32_t uc = CUB_KINECT_CX + c.x * F / c.z, vc = CUB_KINECT_CY - c.y * F / c.z, rp = r * F / c.z + 1;
    for (int v = vc - rp; v <= vc + rp; v++)
        for (int u = uc - rp; u <= uc + rp; u++) {
            if (u < 0 || v < 0 || u >= W || v >= H) continue;
            /* the ray's offset from the centre, at the centre's depth */
            int32_t dx = (u - CUB_KINECT_CX) * c.z / F - c.x, dy = (CUB_KINECT_CY - v) * c.z / F - c.y;
            int64_t d2 = (int64_t)dx * dx + (int64_t)dy * dy;
            if (d2 >= (int64_t)r * r) continue;
            int32_t z = c.z - (int32_t)cub_fx_isqrt64((uint64_t)((int64_t)r * r - d2));
            if (z < zbuf[v * W + u]) zbuf[v * W + u] = z;
        }
}

static void capsule(p3 a, p3 b, int32_t r)
{
    int32_t dx = b.x - a.x, dy = b.y - a.y, dz = b.z - a.z;
    int32_t len = (int32_t)cub_fx_isqrt64((uint64_t)((int64_t)dx * dx + (int64_t)dy * dy + (int64_t)dz * dz));
    int32_t n = len / 12 + 1;
    for (int32_t k = 0; k <= n; k++) sphere((p3){a.x + dx * k / n, a.y + dy * k / n, a.z + dz * k / n}, r);
}

/* With TRACK_TEST_DUMP=dir set, every rendered frame is also written there
 * as a fakenect dump, to look at with `cubtool eval-track dir --print`. */
static void to_raw(void)
{
    static int serial;
    for (int i = 0; i < W * H; i++) {
        int32_t z = zbuf[i];
        frame[i] = z >= 500 && z < 4000 ? mm_to_raw_tab[z] : CUB_KINECT_NO_READING;
    }
    const char *dir = getenv("TRACK_TEST_DUMP");
    if (!dir) return;
    char path[4096];
    snprintf(path, sizeof path, "%s/d-%d.000000-%d.pgm", dir, 1300000000 + serial, serial);
    FILE *f = fopen(path, "wb");
    if (!f) return;
    fprintf(f, "P5 640 480 65535\n");
    for (int i = 0; i < W * H; i++) fputc(frame[i] & 255, f), fputc(frame[i] >> 8, f);
    fclose(f);
    snprintf(path, sizeof path, "%s/INDEX.txt", dir);
    f = fopen(path, "a");
    if (f) fprintf(f, "d-%d.000000-%d.pgm\n", 1300000000 + serial, serial), fclose(f);
    serial++;
}

/* A child of 1150 mm at (x0, z0), feet on a floor 800 mm below the camera,
 * with the joint layout of the synthetic child (cub/synth.h truth: the
 * shoulders a little above the shoulder centre, the hip centre high).
 * arm_up: 0 arms down and out, 1 arms out level, 2 arms raised. */
static void child_pose(int32_t x0, int32_t z0, int arm_up, int32_t s_pm, p3 *j)
{
#define S(v) ((v) * s_pm / 1000)
    int32_t fy = -800;
    j[CUB_KJ_HIP_CENTRE] = (p3){x0, fy + S(761), z0};
    j[CUB_KJ_SPINE] = (p3){x0, fy + S(842), z0};
    j[CUB_KJ_SHOULDER_CENTRE] = (p3){x0, fy + S(923), z0};
    j[CUB_KJ_HEAD] = (p3){x0, fy + S(1060), z0};
    static const int32_t el[3][2] = {{60, -210}, {218, 0}, {120, 180}}, wr[3][2] = {{60, -140}, {149, 0}, {80, 125}},
                         ha[3][2] = {{15, -50}, {52, 0}, {25, 45}};
    for (int side = 0; side < 2; side++) {
        /* the image is mirrored: the player's left at smaller x */
        int32_t sg = side == 0 ? -1 : 1;
        int js = side ? CUB_KJ_SHOULDER_R : CUB_KJ_SHOULDER_L, jh = side ? CUB_KJ_HIP_R : CUB_KJ_HIP_L;
        p3 sh = {x0 + sg * S(140), fy + S(971), z0};
        j[js] = sh;
        p3 e = {sh.x + sg * S(el[arm_up][0]), sh.y + S(el[arm_up][1]), z0 - 20};
        p3 w = {e.x + sg * S(wr[arm_up][0]), e.y + S(wr[arm_up][1]), z0 - 40};
        j[js + 1] = e;
        j[js + 2] = w;
        j[js + 3] = (p3){w.x + sg * S(ha[arm_up][0]), w.y + S(ha[arm_up][1]), z0 - 40};
        p3 hip = {x0 + sg * S(65), fy + S(684), z0};
        j[jh] = hip;
        j[jh + 1] = (p3){hip.x + sg * S(50), fy + S(390), z0 - 20};
        j[jh + 2] = (p3){hip.x + sg * S(90), fy + S(90), z0};
        j[jh + 3] = (p3){hip.x + sg * S(95), fy + S(50), z0 - 80};
    }
#undef S
}

static void draw_child(const p3 *j, int32_t s_pm)
{
#define S(v) ((v) * s_pm / 1000)
    sphere((p3){j[CUB_KJ_HEAD].x, j[CUB_KJ_HEAD].y + S(10), j[CUB_KJ_HEAD].z}, S(90));
    capsule(j[CUB_KJ_SHOULDER_CENTRE], j[CUB_KJ_HEAD], S(45));
    capsule((p3){j[CUB_KJ_SHOULDER_L].x + S(50), j[CUB_KJ_SHOULDER_L].y - S(60), j[CUB_KJ_SHOULDER_L].z},
            (p3){j[CUB_KJ_HIP_L].x, j[CUB_KJ_HIP_L].y, j[CUB_KJ_HIP_L].z}, S(95));
    capsule((p3){j[CUB_KJ_SHOULDER_R].x - S(50), j[CUB_KJ_SHOULDER_R].y - S(60), j[CUB_KJ_SHOULDER_R].z},
            (p3){j[CUB_KJ_HIP_R].x, j[CUB_KJ_HIP_R].y, j[CUB_KJ_HIP_R].z}, S(95));
    for (int side = 0; side < 2; side++) {
        int js = side ? CUB_KJ_SHOULDER_R : CUB_KJ_SHOULDER_L, jh = side ? CUB_KJ_HIP_R : CUB_KJ_HIP_L;
        capsule(j[js], j[js + 1], S(38));
        capsule(j[js + 1], j[js + 3], S(32));
        capsule(j[jh], j[jh + 1], S(55));
        capsule(j[jh + 1], j[jh + 2], S(42));
        capsule(j[jh + 2], j[jh + 3], S(35));
    }
#undef S
}

static void *tracker_mem;
static cub_tracker *new_tracker_with(const cub_forest *f)
{
    cub_track_desc d = {.forest = f};
    size_t sz = cub_track_mem_size(&d);
    free(tracker_mem);
    tracker_mem = aligned_alloc(16, (sz + 15) / 16 * 16);
    assert_non_null(tracker_mem);
    cub_tracker *t = NULL;
    assert_int_equal(cub_track_init(&d, tracker_mem, sz, &t), CUB_OK);
    return t;
}

static cub_tracker *new_tracker(void)
{
    return new_tracker_with(NULL);
}

/* The committed body-part forest (assets/forest/body.forest), or skip. */
static uint8_t *forest_bytes;
static cub_forest load_forest(void)
{
    const char *src = getenv("CUB_SOURCE_DIR");
    char path[4096];
    snprintf(path, sizeof path, "%s/assets/forest/body.forest", src ? src : ".");
    FILE *f = fopen(path, "rb");
    if (!f) skip();
    fseek(f, 0, SEEK_END);
    long len = ftell(f);
    fseek(f, 0, SEEK_SET);
    free(forest_bytes);
    forest_bytes = malloc((size_t)len);
    assert_non_null(forest_bytes);
    assert_int_equal(fread(forest_bytes, 1, (size_t)len, f), (size_t)len);
    fclose(f);
    cub_forest fo;
    assert_int_equal(cub_forest_open(forest_bytes, (size_t)len, &fo, NULL), CUB_OK);
    return fo;
}

static double joint_err(const cub_track_skeleton *s, int j, p3 truth)
{
    double dx = s->joint_mm[j].x / 65536.0 - truth.x, dy = s->joint_mm[j].y / 65536.0 - truth.y,
           dz = s->joint_mm[j].z / 65536.0 - truth.z;
    return sqrt(dx * dx + dy * dy + dz * dz);
}

static void test_bad_arguments_and_garbage_give_no_player(void **st)
{
    (void)st;
    cub_track_desc d = {0};
    cub_tracker *t = NULL;
    assert_int_equal(cub_track_init(&d, NULL, 0, &t), CUB_ERR_ARG);
    static _Alignas(16) uint8_t small[64];
    assert_int_equal(cub_track_init(&d, small, sizeof small, &t), CUB_ERR_NOMEM);
    t = new_tracker();
    cub_track_skeleton s;
    assert_int_equal(cub_track_frame(t, NULL, 0, NULL, &s), CUB_ERR_ARG);
    p3 j[CUB_KJ_COUNT];
    child_pose(0, 2200, 1, 1000, j);
    for (int round = 0; round < 2; round++) {
        for (int kind = 0; kind < 3; kind++) {
            uint32_t seed = 12345;
            for (int i = 0; i < W * H; i++) {
                seed = seed * 1664525u + 1013904223u;
                frame[i] = kind == 0 ? 2047 : kind == 1 ? 0 : (uint16_t)(seed >> 16);
            }
            assert_int_equal(cub_track_frame(t, frame, kind, NULL, &s), CUB_OK);
            assert_int_equal(s.status, CUB_TRACK_NO_PLAYER);
        }
        /* good frames again: the tracker finds the player */
        clear_scene(800);
        draw_child(j, 1000);
        to_raw();
        assert_int_equal(cub_track_frame(t, frame, 10, NULL, &s), CUB_OK);
        assert_true(s.status == CUB_TRACK_OK);
        assert_true(joint_err(&s, CUB_KJ_HEAD, j[CUB_KJ_HEAD]) < 150);
    }
}

static void test_capsule_child_joints_within_10cm(void **st)
{
    (void)st;
    static const char *groups = "";
    (void)groups;
    double sum[CUB_KJ_COUNT] = {0};
    int in[CUB_KJ_COUNT] = {0}, n = 0;
    int quick = getenv("CUB_QUICK") != NULL;
    for (int grav = 0; grav < 2; grav++)
        for (int pose = 0; pose < 3; pose++)
            for (int dist = 0; dist < (quick ? 1 : 3); dist++) {
                cub_tracker *t = new_tracker();
                p3 j[CUB_KJ_COUNT];
                int32_t z0 = 2100 + 500 * dist, x0 = -150 + 150 * dist;
                child_pose(x0, z0, pose, 1000, j);
                clear_scene(800);
                draw_child(j, 1000);
                to_raw();
                cub_vec3 g = {0, -1000 * 65536, 0};
                cub_track_skeleton s;
                for (int k = 0; k < 3; k++) cub_track_frame(t, frame, k * 33333, grav ? &g : NULL, &s);
                assert_int_equal(s.status, CUB_TRACK_OK);
                for (int jj = 0; jj < CUB_KJ_COUNT; jj++) {
                    double e = joint_err(&s, jj, j[jj]);
                    sum[jj] += e;
                    in[jj] += e <= 100;
                }
                n++;
            }
    int all = 0;
    printf("track capsule child (%d views):", n);
    for (int jj = 0; jj < CUB_KJ_COUNT; jj++) {
        printf(" %s=%.0fmm", cub_kinect_joint_name(jj), sum[jj] / n);
        all += in[jj];
    }
    printf("\ntrack capsule child: %.1f%% of joints within 10 cm (%d of %d)\n", 100.0 * all / (n * CUB_KJ_COUNT),
           all, n * CUB_KJ_COUNT);
    /* head, hands, feet: the extremities the method is built on */
    static const int ends[] = {CUB_KJ_HEAD, CUB_KJ_HAND_L, CUB_KJ_HAND_R, CUB_KJ_FOOT_L, CUB_KJ_FOOT_R};
    for (size_t k = 0; k < sizeof ends / sizeof *ends; k++) assert_true(sum[ends[k]] / n < 100);
    assert_true(all >= n * CUB_KJ_COUNT * 8 / 10);
}

/* A nearer second person walking in beside the player never takes over. */
static void test_second_person_never_becomes_the_player(void **st)
{
    (void)st;
    cub_tracker *t = new_tracker();
    p3 a[CUB_KJ_COUNT], b[CUB_KJ_COUNT];
    child_pose(0, 2400, 1, 1000, a);
    cub_track_skeleton s;
    clear_scene(800);
    draw_child(a, 1000);
    to_raw();
    cub_track_frame(t, frame, 0, NULL, &s);
    int32_t id = s.player_id;
    assert_int_equal(s.status, CUB_TRACK_OK);
    for (int k = 0; k < 8; k++) {
        /* an adult-sized person, nearer, walking in from the right */
        child_pose(1400 - 80 * k, 1800, 0, 1400, b);
        for (int jj = 0; jj < CUB_KJ_COUNT; jj++) b[jj].y += 800 * 400 / 1000 - 320;
        clear_scene(800);
        draw_child(a, 1000);
        draw_child(b, 1400);
        to_raw();
        cub_track_frame(t, frame, (k + 1) * 33333, NULL, &s);
        assert_int_equal(s.player_id, id);
        assert_true(joint_err(&s, CUB_KJ_SPINE, a[CUB_KJ_SPINE]) < 200);
    }
    /* and a fresh tracker picks the nearer, central one */
    t = new_tracker();
    cub_track_frame(t, frame, 0, NULL, &s);
    assert_true(s.status != CUB_TRACK_NO_PLAYER);
}

/* ---- identity: crossing, occlusion, a sibling ---------------------------- */

/* A flat box facing the camera, x0..x1 wide, from the floor (800 mm below
 * the camera) to top_mm above it, at depth z. */
static void box(int32_t x0, int32_t x1, int32_t top_mm, int32_t z)
{
    int32_t u0 = CUB_KINECT_CX + x0 * F / z, u1 = CUB_KINECT_CX + x1 * F / z;
    int32_t v0 = CUB_KINECT_CY - (top_mm - 800) * F / z, v1 = CUB_KINECT_CY + 800 * F / z;
    for (int v = v0 < 0 ? 0 : v0; v <= v1 && v < H; v++)
        for (int u = u0 < 0 ? 0 : u0; u <= u1 && u < W; u++)
            if (z < zbuf[v * W + u]) zbuf[v * W + u] = z;
}

/* One 10 fps frame of the child at (x, z) and what else stands there
 * (draw_other); the player's id and the spine's error from the child's. */
typedef p3 (*other_fn)(int k); /* draws frame k's other person: its spine (z 0: none) */
static void identity_frame(cub_tracker *t, int k, int32_t x, int32_t z, other_fn draw_other, cub_track_skeleton *s,
                           double err[2])
{
    p3 o = {0, 0, 0};
    p3 a[CUB_KJ_COUNT];
    child_pose(x, z, k % 3, 1000, a);
    clear_scene(800);
    draw_child(a, 1000);
    if (draw_other) o = draw_other(k);
    to_raw();
    cub_vec3 g = {0, -1000 * 65536, 0};
    cub_track_frame(t, frame, (int64_t)k * 100000, &g, s);
    err[0] = joint_err(s, CUB_KJ_SPINE, a[CUB_KJ_SPINE]);
    err[1] = o.z ? joint_err(s, CUB_KJ_SPINE, o) : 1e9;
}

/* frames 10..39: an adult 700 mm before the child walks across at 1 m/s */
static p3 crosser(int k)
{
    if (k < 10) return (p3){0, 0, 0};
    p3 b[CUB_KJ_COUNT];
    child_pose(1500 - 100 * (k - 10), 1700, 0, 1400, b);
    for (int jj = 0; jj < CUB_KJ_COUNT; jj++) b[jj].y += 800 * 400 / 1000 - 320;
    draw_child(b, 1400);
    return b[CUB_KJ_SPINE];
}

/* frames 10..19 (1 s): a box as tall as an adult stands before the child, hiding it */
static p3 occluder(int k)
{
    if (k < 10 || k >= 20) return (p3){0, 0, 0};
    box(-500, 500, 1700, 1600);
    return (p3){0, 50, 1650};
}

/* frames 10..24 (1.5 s, the longest occlusion issue 20 asks the player to
 * outlast): the same box */
static p3 occluder_long(int k)
{
    if (k < 10 || k >= 25) return (p3){0, 0, 0};
    box(-500, 500, 1700, 1600);
    return (p3){0, 50, 1650};
}

/* from frame 10 on: an adult squeezes past the child at 0.5 m/s, its torso
 * 250 mm before the child's: the two are one blob while they overlap,
 * its top the adult's head (the dev renders' slow crossings of a child
 * walking into the crosser's path) */
static p3 toucher(int k)
{
    if (k < 10) return (p3){0, 0, 0};
    p3 b[CUB_KJ_COUNT];
    child_pose(900 - 50 * (k - 10), 2150, 0, 1400, b);
    for (int jj = 0; jj < CUB_KJ_COUNT; jj++) b[jj].y += 800 * 400 / 1000 - 320;
    draw_child(b, 1400);
    return b[CUB_KJ_SPINE];
}

/* a sibling of the child's height 650 mm to its side, 100 mm deeper */
static p3 sibling(int k)
{
    p3 b[CUB_KJ_COUNT];
    child_pose(550, 2500, (k + 1) % 3, 1000, b);
    draw_child(b, 1000);
    return b[CUB_KJ_SPINE];
}

/* Run 40 frames; every frame with a player has the first frame's id and
 * a spine nearer the child's than the other person's (else eval-track
 * counts a wrong person), and within 350 mm of it; the child is the
 * player in the last frame. */
static void expect_same_player(other_fn draw_other, int32_t x0, int32_t dx, const char *what)
{
    cub_tracker *t = new_tracker();
    cub_track_skeleton s;
    double e[2];
    int32_t id = -1, shown = 0, hidden = 0;
    for (int k = 0; k < 40; k++) {
        identity_frame(t, k, x0 + dx * (k % 10 < 5 ? k % 10 : 10 - k % 10), 2400, draw_other, &s, e);
        if (k == 0) id = s.player_id, assert_int_equal(s.status, CUB_TRACK_OK);
        if (s.status == CUB_TRACK_NO_PLAYER) {
            hidden++;
            continue;
        }
        shown++;
        if (s.player_id != id || e[0] >= e[1] || e[0] >= 350)
            fail_msg("%s: frame %d id %d (first %d), spine %.0f mm from the child's, %.0f from the other's", what,
                     k, s.player_id, id, e[0], e[1]);
    }
    printf("track identity %s: %d frames with the player, %d without\n", what, shown, hidden);
    assert_int_equal(s.status, CUB_TRACK_OK);
}

/* Frames of 60 whose player's spine is nearer the other person's than the
 * child's (what eval-track counts wrong); the child is the player at the
 * end, its spine within 350 mm. A child lost near the end is held unseen
 * for ID_HOLD_US (2 s) before it is taken again: up to 20 frames more
 * then, counted too. */
static int wrong_person_frames(other_fn draw_other)
{
    cub_tracker *t = new_tracker();
    cub_track_skeleton s;
    double e[2];
    int wrong = 0;
    for (int k = 0; k < 60 || (k < 80 && s.status == CUB_TRACK_NO_PLAYER); k++) {
        identity_frame(t, k, 0, 2400, draw_other, &s, e);
        wrong += s.status != CUB_TRACK_NO_PLAYER && e[1] <= e[0];
    }
    assert_int_equal(s.status, CUB_TRACK_OK);
    assert_true(e[0] < 350);
    return wrong;
}

/* An adult walks in behind the child and stays there, adult_behind_dz
 * deeper, its body overlapping the child's in the image (the moving
 * child's parent of the end to end songs) */
static int32_t adult_behind_dz = 290;
static p3 adult_behind(int k)
{
    p3 b[CUB_KJ_COUNT];
    int32_t x = 1500 - 100 * k;
    child_pose(x < 250 ? 250 : x, 2400 + adult_behind_dz, 0, 1400, b);
    for (int jj = 0; jj < CUB_KJ_COUNT; jj++) b[jj].y += 800 * 400 / 1000 - 320;
    draw_child(b, 1400);
    return b[CUB_KJ_SPINE];
}

/* A blob the player shares with someone taller who was another person
 * last frame is not the player (merged_with_taller). Without the rule the
 * adult, merged with the child when the room became known (frame 20), is
 * the player from frame 22 on and taken away (34 wrong frames, nobody at
 * the end); with it nobody is the player for 2 s, then the child again. */
static void test_taller_one_squeezing_past_is_not_the_player(void **st)
{
    (void)st;
    int wrong = wrong_person_frames(toucher);
    printf("track identity: an adult squeezing past: %d wrong-person frames\n", wrong);
    assert_int_equal(wrong, 0);
}

/* The adult behind, split from the child by split_merged the frame they
 * first touch, is not merged back as a piece of the child's cut off by
 * depth (merge_cut_off: not a blob that was someone else). Without that,
 * from 200 to 320 mm behind, the adult's cells were the player's from
 * then on, nothing was left to split and the track went to the adult:
 * 37-43 wrong-person frames of 60, the adult the player at the end. */
static void test_adult_just_behind_is_not_the_players_part(void **st)
{
    (void)st;
    static const int32_t dz[] = {200, 260, 290, 320};
    for (size_t i = 0; i < sizeof dz / sizeof dz[0]; i++) {
        adult_behind_dz = dz[i];
        int wrong = wrong_person_frames(adult_behind);
        printf("track identity: an adult %d mm behind the child: %d wrong-person frames\n", dz[i], wrong);
        assert_int_equal(wrong, 0);
    }
}

/* from frame 10 on: an adult walks across at 1 m/s at the child's own
 * depth (crosser_dz behind it), through the child's place: one blob with
 * it while they overlap (the dev renders' child walking into a crosser's
 * path) */
static int32_t crosser_dz, crosser_step = 100;
static p3 same_depth_crosser(int k)
{
    if (k < 10) return (p3){0, 0, 0};
    p3 b[CUB_KJ_COUNT];
    child_pose(1500 - crosser_step * (k - 10), 2400 + crosser_dz, 0, 1400, b);
    for (int jj = 0; jj < CUB_KJ_COUNT; jj++) b[jj].y += 800 * 400 / 1000 - 320;
    draw_child(b, 1400);
    return b[CUB_KJ_SPINE];
}

/* An adult crossing through the child's place at its depth (or 100 mm
 * before it) at 0.5, 1 and 1.5 m/s never becomes the player. A guard for
 * parting the merged blob by each one's motion (docs/tracker_eval.md
 * round 8: a first try gave 10 wrong-person frames here at 1.5 m/s and
 * the child was lost; round 9's parting has 0). Not covered: the crosser 100 mm
 * behind the child at 0.5 m/s, where main ends with the child PARTLY_OUT
 * (and the motion parting with nobody), which wrong_person_frames
 * refuses. */
static void test_crosser_at_the_players_depth_stays_the_crosser(void **st)
{
    (void)st;
    static const int32_t dz[] = {-100, 0}, step[] = {50, 100, 150};
    for (size_t i = 0; i < sizeof dz / sizeof dz[0]; i++)
        for (size_t j = 0; j < sizeof step / sizeof step[0]; j++) {
            crosser_dz = dz[i], crosser_step = step[j];
            int wrong = wrong_person_frames(same_depth_crosser);
            printf("track identity: a crosser %d mm behind the child at %d mm/s: %d wrong-person frames\n", dz[i],
                   step[j] * 10, wrong);
            assert_int_equal(wrong, 0);
        }
}

static void test_player_keeps_its_identity(void **st)
{
    (void)st;
    expect_same_player(crosser, 0, 0, "crossing");
    expect_same_player(occluder, 0, 0, "occluded 1 s");
    expect_same_player(occluder_long, 0, 0, "occluded 1.5 s");
    expect_same_player(sibling, -150, 20, "sibling");
}

/* From frame 10 on an adult crosses 800 mm before the child at 1 m/s,
 * its trailing arm swung back toward the child: the arm leaves the
 * adult's upper arm 180 mm behind it and ends at the child's chest height
 * 350 mm before it, a blob of its own by depth, lying over the child in
 * the image. crossing_from and crossing_hand: that arm this frame. */
static p3 crossing_hand, crossing_from;
static bool crossing_hand_only; /* the variant: a crosser 1100 mm before the child, only its hand seen behind it */
static p3 crosser_reaching_back(int k)
{
    crossing_hand = crossing_from = (p3){0, 0, 0};
    if (k < 10) return (p3){0, 0, 0};
    p3 b[CUB_KJ_COUNT];
    int32_t z = crossing_hand_only ? 1300 : 1600;
    child_pose(1000 - 50 * (k - 10), z, 0, 1400, b);
    for (int jj = 0; jj < CUB_KJ_COUNT; jj++) b[jj].y += 800 * 400 / 1000 - 320;
    draw_child(b, 1400);
    p3 sh = b[CUB_KJ_SHOULDER_R];
    p3 from = {sh.x + 100, sh.y - 260, 1780}, to = {sh.x + 420, 80, 2050};
    if (crossing_hand_only) from = to = (p3){sh.x + 420, 80, 1600};
    else capsule(from, to, 40);
    sphere(to, 50);
    crossing_hand = to, crossing_from = from;
    return b[CUB_KJ_SPINE];
}

/* A joint of skeleton s within 100 mm of the crosser's forearm (its
 * middle or its hand). */
static bool joint_on_crossing_arm(const cub_track_skeleton *s)
{
    p3 mid = {(crossing_from.x + crossing_hand.x) / 2, (crossing_from.y + crossing_hand.y) / 2,
              (crossing_from.z + crossing_hand.z) / 2};
    for (int j = 0; j < CUB_KJ_COUNT; j++)
        if (joint_err(s, j, crossing_hand) < 100 || joint_err(s, j, mid) < 100) return true;
    return false;
}

/* The frames of 50 with a joint of the player on the crosser's forearm,
 * and those whose player is the crosser. */
static void crossing_with_arm_back(int *on_arm, int *wrong)
{
    cub_tracker *t = new_tracker();
    cub_track_skeleton s;
    double e[2];
    *on_arm = *wrong = 0;
    for (int k = 0; k < 50; k++) {
        identity_frame(t, k, 0, 2400, crosser_reaching_back, &s, e);
        if (s.status == CUB_TRACK_NO_PLAYER) continue;
        *wrong += e[1] <= e[0];
        *on_arm += crossing_hand.z && joint_on_crossing_arm(&s);
    }
}

/* A piece joined by depth to someone else (the crosser's arm swung back,
 * continuous with the crosser, a depth jump from the child) is not a
 * hand before the hidden child's chest (joins_someone_else). */
static void test_crossers_arm_is_not_the_players_hand(void **st)
{
    (void)st;
    int on_arm, wrong;
    crossing_with_arm_back(&on_arm, &wrong);
    printf("track crossing, the crosser's arm swung back: a joint of the player on it in %d frames, %d wrong-person\n",
           on_arm, wrong);
    assert_int_equal(on_arm, 0);
    assert_int_equal(wrong, 0);
}

/* A piece farther before the player than its arm's reach is not its hand
 * (front_reach_mm): the hand of a crosser 1100 mm before the child, held
 * back 300 mm behind the crosser (too far to join it), 800 mm before the
 * child and over it in the image. */
static void test_a_piece_beyond_an_arms_reach_is_not_the_players_hand(void **st)
{
    (void)st;
    int on_arm, wrong;
    crossing_hand_only = true;
    crossing_with_arm_back(&on_arm, &wrong);
    crossing_hand_only = false;
    printf("track crossing, the crosser's hand 800 mm before the child: a joint of the player on it in %d frames, %d "
           "wrong-person\n",
           on_arm, wrong);
    assert_int_equal(on_arm, 0);
    assert_int_equal(wrong, 0);
}

/* Attract mode: for 2 s only an adult stands in the room, 900 mm right of
 * the centre, and the tracker follows it; then the child appears in the
 * middle, nearer. The track keeps the adult (its track is alive, the child
 * is outside its gate) unless START chooses afresh
 * (cub_track_choose_afresh before the child's first frame): then the
 * child is the player from that frame on, with a new id. */
static p3 attract_adult(int k)
{
    (void)k;
    p3 b[CUB_KJ_COUNT];
    child_pose(900, 2900, 0, 1400, b);
    for (int jj = 0; jj < CUB_KJ_COUNT; jj++) b[jj].y += 800 * 400 / 1000 - 320;
    draw_child(b, 1400);
    return b[CUB_KJ_SPINE];
}

/* Attract mode with a sibling of the child's height 450 mm left of the
 * centre, 100 mm deeper, its arms out level: the child who appears in the
 * middle touches its hand, one blob by depth with it from its first frame. */
static p3 attract_sibling(int k)
{
    (void)k;
    p3 b[CUB_KJ_COUNT];
    child_pose(-450, 2500, 1, 1000, b);
    draw_child(b, 1000);
    return b[CUB_KJ_SPINE];
}

/* The frames after the child appears whose player is the child (spine
 * within 350 mm of the child's, nearer it than the other's), the other
 * (attract_adult, attract_sibling) there from the first frame. */
static int child_frames_after_start(other_fn attract_other, bool start)
{
    cub_tracker *t = new_tracker();
    cub_track_skeleton s;
    cub_vec3 g = {0, -1000 * 65536, 0};
    int32_t child = 0, adult_id = -1;
    for (int k = 0; k < 40; k++) {
        p3 o = {0, 0, 0}, a[CUB_KJ_COUNT];
        clear_scene(800);
        if (k >= 20) child_pose(0, 2400, k % 3, 1000, a), draw_child(a, 1000);
        o = attract_other(k);
        to_raw();
        if (k == 20 && start) assert_int_equal(cub_track_choose_afresh(t), CUB_OK);
        cub_track_frame(t, frame, (int64_t)k * 100000, &g, &s);
        if (k == 19) adult_id = s.player_id, assert_true(joint_err(&s, CUB_KJ_SPINE, o) < 350);
        if (k < 20 || s.status == CUB_TRACK_NO_PLAYER) continue;
        double ec = joint_err(&s, CUB_KJ_SPINE, a[CUB_KJ_SPINE]), eo = joint_err(&s, CUB_KJ_SPINE, o);
        if (ec < eo && ec < 350 && s.player_id != adult_id) child++;
    }
    return child;
}

static void test_start_chooses_the_player_afresh(void **st)
{
    (void)st;
    int kept = child_frames_after_start(attract_adult, false), started = child_frames_after_start(attract_adult, true);
    printf("track START: the child is the player in %d of 20 frames without START, %d with\n", kept, started);
    assert_int_equal(kept, 0);
    assert_int_equal(started, 20);
    assert_int_equal(cub_track_choose_afresh(NULL), CUB_ERR_ARG);
}

/* START with the child one blob with a sibling the tracker followed in
 * attract mode (split_newcomer): the cells new this frame are the child,
 * a blob of its own, and START takes it; without the split START took the
 * joined blob, the sibling's body and the child's. */
static void test_start_takes_the_child_beside_its_sibling(void **st)
{
    (void)st;
    int started = child_frames_after_start(attract_sibling, true);
    printf("track START beside a sibling: the child is the player in %d of 20 frames\n", started);
    assert_int_equal(started, 20);
}

/* ---- too close (issue 20 point 9) --------------------------------------- */

/* A body 0.65 m from the camera fills the view: TOO_CLOSE, whoever stands
 * behind it (an adult at 2.4 m is not the player to judge); bending nearer
 * than the Kinect reads (0.4 m: no readings where it was), still
 * TOO_CLOSE, not NO_PLAYER ("Come closer" would be the wrong words). */
static void test_too_close_is_told(void **st)
{
    (void)st;
    cub_tracker *t = new_tracker();
    cub_track_skeleton s;
    cub_vec3 g = {0, -1000 * 65536, 0};
    for (int k = 0; k < 6; k++) {
        int32_t z = k < 3 ? 650 : 400;
        clear_scene(800);
        p3 b[CUB_KJ_COUNT];
        child_pose(-700, 2400, 0, 1400, b);
        for (int jj = 0; jj < CUB_KJ_COUNT; jj++) b[jj].y += 800 * 400 / 1000 - 320;
        draw_child(b, 1400);
        box(-250, 250, 1100, z);
        to_raw();
        cub_track_frame(t, frame, (int64_t)k * 100000, &g, &s);
        printf("track too close: body at %d mm: status %d\n", z, s.status);
        assert_int_equal(s.status, CUB_TRACK_TOO_CLOSE);
    }
}

/* ---- the real frames against the hand labels --------------------------- */

static int load_real(const char *dir, const char *name, uint16_t *out)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "rb");
    if (!f) return -1;
    static uint8_t buf[W * H * 2];
    fseek(f, -(long)sizeof buf, SEEK_END);
    size_t got = fread(buf, 1, sizeof buf, f);
    fclose(f);
    if (got != sizeof buf) return -1;
    for (int i = 0; i < W * H; i++) out[i] = (uint16_t)(buf[2 * i] | buf[2 * i + 1] << 8);
    return 0;
}

static int joint_by_name(const char *n)
{
    for (int j = 0; j < CUB_KJ_COUNT; j++)
        if (!strcmp(cub_kinect_joint_name(j), n)) return j;
    return -1;
}

/* How far a joint's centre lies behind the body's surface facing the
 * camera, for the adult of the real frames (tests/labels/README.md: half
 * the part's front-to-back depth): the head about 190 mm deep, the
 * shoulder about 100, the elbow 70, the hand 30. The tracker's joints are
 * centres too, so a label's point is the surface plus this. */
static double centre_depth_mm(int j)
{
    switch (j) {
    case CUB_KJ_HEAD: return 95;
    case CUB_KJ_SHOULDER_L:
    case CUB_KJ_SHOULDER_R: return 50;
    case CUB_KJ_ELBOW_L:
    case CUB_KJ_ELBOW_R: return 35;
    default: return 15;
    }
}

/* A label's 3D point: the median depth around the pixel (the surface),
 * plus the joint's depth behind it. */
static int label_point(const uint16_t *raw, int u, int v, int j, double *p)
{
    int zs[121], n = 0;
    for (int dv = -5; dv <= 5; dv++)
        for (int du = -5; du <= 5; du++) {
            int uu = u + du, vv = v + dv;
            if (uu < 0 || vv < 0 || uu >= W || vv >= H) continue;
            int z = cub_track_raw_to_mm_int(raw[vv * W + uu]);
            if (z) zs[n++] = z;
        }
    if (!n) return -1;
    for (int a = 1; a < n; a++)
        for (int b = a; b > 0 && zs[b] < zs[b - 1]; b--) {
            int tmp = zs[b];
            zs[b] = zs[b - 1], zs[b - 1] = tmp;
        }
    double z = zs[n / 2] + centre_depth_mm(j);
    p[0] = (u - CUB_KINECT_CX) * z / F, p[1] = (CUB_KINECT_CY - v) * z / F, p[2] = z;
    return 0;
}

/* The seam's frame s against the same frame without the forest: the
 * same confidences, and only the joints the tracker was unsure of moved. */
static void seam_kept_confidence(const cub_track_skeleton *without, const cub_track_skeleton *s)
{
    for (int j = 0; j < CUB_KJ_COUNT; j++) {
        assert_int_equal(s->confidence[j], without->confidence[j]);
        if (without->confidence[j] >= CUB_TRACK_CONFIDENT)
            assert_memory_equal(&s->joint_mm[j], &without->joint_mm[j], sizeof s->joint_mm[j]);
    }
}

/* The real frames against the labels, with the forest f in the tracker's
 * seam or not (NULL); without: each frame's skeleton into plain[] (up to
 * 16 frames), with: the confidences must be plain[]'s (the seam keeps
 * the tracker's) and a replaced joint one the tracker was not sure of. */
static cub_track_skeleton plain[16];
static void real_frames(const cub_forest *f)
{
    const char *data = getenv("CUB_DATA_DIR"), *src = getenv("CUB_SOURCE_DIR");
    char dir[4096], lpath[4096];
    if (!data || !src) skip();
    snprintf(dir, sizeof dir, "%s/depth/skeltrack", data);
    snprintf(lpath, sizeof lpath, "%s/tests/labels/skeltrack_labels.txt", src);
    FILE *lf = fopen(lpath, "r");
    if (!lf || load_real(dir, "d-1300000000.000000-1000000.pgm", frame)) {
        if (lf) fclose(lf);
        printf("track real: skipped (no %s or no frames in %s)\n", lpath, dir);
        skip();
    }
    cub_tracker *t = new_tracker_with(f);
    char line[512], cur[256] = "", printed[256] = "";
    cub_track_skeleton s = {0};
    int first_id = -1, n = 0, in = 0, nkey = 0, inkey = 0, nframe = -1;
    double esum[CUB_KJ_COUNT] = {0};
    int ecount[CUB_KJ_COUNT] = {0};
    while (fgets(line, sizeof line, lf)) {
        char fname[256], jn[64], us[16], vs[16];
        if (line[0] == '#' || sscanf(line, "%255s %63s %15s %15s", fname, jn, us, vs) != 4) continue;
        if (strcmp(fname, cur)) {
            snprintf(cur, sizeof cur, "%s", fname);
            assert_int_equal(load_real(dir, fname, frame), 0);
            cub_track_frame(t, frame, 0, NULL, &s);
            assert_true(s.status != CUB_TRACK_NO_PLAYER);
            if (++nframe < 16 && !f) plain[nframe] = s;
            if (nframe < 16 && f) seam_kept_confidence(&plain[nframe], &s);
            if (first_id < 0) first_id = s.player_id;
            assert_int_equal(s.player_id, first_id);
        }
        int j = joint_by_name(jn);
        double p[3];
        if (j < 0 || us[0] == '-' || label_point(frame, atoi(us), atoi(vs), j, p)) continue;
        double dx = s.joint_mm[j].x / 65536.0 - p[0], dy = s.joint_mm[j].y / 65536.0 - p[1],
               dz = s.joint_mm[j].z / 65536.0 - p[2];
        double e = sqrt(dx * dx + dy * dy + dz * dz);
        esum[j] += e, ecount[j]++;
        n++, in += e <= 100;
        if (j != CUB_KJ_ELBOW_L && j != CUB_KJ_ELBOW_R) nkey++, inkey += e <= 100;
        /* one line per frame: each joint's error (mm) and its depth part */
        if (strcmp(fname, printed)) printf("%strack real: %s", printed[0] ? "\n" : "", fname), snprintf(printed, sizeof printed, "%s", fname);
        printf(" %s=%.0f(dz%+.0f)", jn, e, dz);
    }
    printf("\n");
    fclose(lf);
    printf("track real:");
    for (int j = 0; j < CUB_KJ_COUNT; j++)
        if (ecount[j]) printf(" %s=%.0fmm", cub_kinect_joint_name(j), esum[j] / ecount[j]);
    printf("\ntrack real: %d of %d labelled joints within 10 cm; head/shoulders/hands %d of %d\n", in, n, inkey, nkey);
    assert_true(n > 0);
    assert_int_equal(inkey, nkey); /* head, shoulders and hands: every one within 10 cm */
}

static void test_real_frames_against_hand_labels(void **st)
{
    (void)st;
    real_frames(NULL);
}

/* The box's tracker with the committed forest (cub_track_desc.forest):
 * the real frames stay right (head, shoulders, hands within 10 cm). */
static void test_real_frames_with_the_forest(void **st)
{
    (void)st;
    cub_forest fo = load_forest();
    real_frames(NULL);
    real_frames(&fo);
}

/* ---- confidence --------------------------------------------------------- */

static int confident_joints(const cub_track_skeleton *s)
{
    int n = 0;
    for (int j = 0; j < CUB_KJ_COUNT; j++) n += s->confidence[j] >= CUB_TRACK_CONFIDENT;
    return n;
}

/* A child standing still, facing the camera at 30 fps: once a frame 100
 * ms old is there to measure its motion against (the fourth frame), its
 * head and shoulders are confident, not before; the same child 400 mm
 * aside within 33 ms (a jump no child makes: the fit took something else)
 * is not, nor is a frame without a player. */
static void test_confidence_needs_evidence(void **st)
{
    (void)st;
    cub_tracker *t = new_tracker();
    p3 j[CUB_KJ_COUNT];
    cub_track_skeleton s;
    for (int k = 0; k < 4; k++) {
        child_pose(0, 2200, 0, 1000, j);
        clear_scene(800);
        draw_child(j, 1000);
        to_raw();
        cub_track_frame(t, frame, k * 33333, NULL, &s);
        assert_int_equal(s.status, CUB_TRACK_OK);
        if (k < 3) assert_int_equal(confident_joints(&s), 0);
    }
    assert_true(s.confidence[CUB_KJ_HEAD] >= CUB_TRACK_CONFIDENT);
    assert_true(s.confidence[CUB_KJ_SHOULDER_CENTRE] >= CUB_TRACK_CONFIDENT);
    assert_true(s.confidence[CUB_KJ_SHOULDER_L] >= CUB_TRACK_CONFIDENT);
    assert_true(s.confidence[CUB_KJ_SHOULDER_R] >= CUB_TRACK_CONFIDENT);
    child_pose(400, 2200, 0, 1000, j);
    clear_scene(800);
    draw_child(j, 1000);
    to_raw();
    cub_track_frame(t, frame, 4 * 33333, NULL, &s);
    assert_int_equal(s.status, CUB_TRACK_OK);
    assert_int_equal(confident_joints(&s), 0);
    for (int i = 0; i < CUB_KJ_COUNT; i++) assert_true(s.confidence[i] >= 0 && s.confidence[i] <= CUB_Q16_ONE);
    clear_scene(800);
    to_raw();
    cub_track_frame(t, frame, 5 * 33333, NULL, &s);
    assert_int_equal(confident_joints(&s), 0);
}

/* ---- determinism -------------------------------------------------------- */

static uint64_t fnv(uint64_t h, const void *p, size_t n)
{
    const uint8_t *b = p;
    for (size_t i = 0; i < n; i++) h = (h ^ b[i]) * 1099511628211ull;
    return h;
}

static uint64_t output_hash(cub_tracker *t)
{
    uint64_t h = 1469598103934665603ull;
    cub_vec3 g = {3 * 65536, -1000 * 65536, 100 * 65536};
    for (int k = 0; k < 6; k++) {
        p3 j[CUB_KJ_COUNT];
        child_pose(-100 + 40 * k, 2000 + 100 * k, k % 3, 1000, j);
        clear_scene(800);
        draw_child(j, 1000);
        to_raw();
        cub_track_skeleton s;
        cub_track_frame(t, frame, k * 33333, (k & 1) ? &g : NULL, &s);
        h = fnv(h, &s, sizeof s);
        printf("DBG %d id %d st %d head %d\n", k, s.player_id, s.status, s.joint_mm[3].x >> 16);
    }
    return h;
}

static void test_output_hash_is_pinned(void **st)
{
    (void)st;
    uint64_t h = output_hash(new_tracker());
    printf("track hash: %016llx\n", (unsigned long long)h);
    /* pinned: the same on x86-64 and aarch64 (re-pin only for an intended change) */
    assert_true(h == 0xa18fed5be5cb1c8aull);
}

/* The same frames with the committed forest in the seam: integers only,
 * so pinned the same on every CPU (re-pin when the forest or the seam
 * changes on purpose). */
static void test_output_hash_with_the_forest_is_pinned(void **st)
{
    (void)st;
    cub_forest fo = load_forest();
    uint64_t h = output_hash(new_tracker_with(&fo));
    printf("track hash with the forest: %016llx\n", (unsigned long long)h);
    assert_true(h == 0x4b8661c0b0a41cb5ull);
}

int main(void)
{
    build_mm_to_raw();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_arguments_and_garbage_give_no_player),
        cmocka_unit_test(test_capsule_child_joints_within_10cm),
        cmocka_unit_test(test_confidence_needs_evidence),
        cmocka_unit_test(test_second_person_never_becomes_the_player),
        cmocka_unit_test(test_player_keeps_its_identity),
        cmocka_unit_test(test_taller_one_squeezing_past_is_not_the_player),
        cmocka_unit_test(test_crossers_arm_is_not_the_players_hand),
        cmocka_unit_test(test_crosser_at_the_players_depth_stays_the_crosser),
        cmocka_unit_test(test_a_piece_beyond_an_arms_reach_is_not_the_players_hand),
        cmocka_unit_test(test_adult_just_behind_is_not_the_players_part),
        cmocka_unit_test(test_start_chooses_the_player_afresh),
        cmocka_unit_test(test_start_takes_the_child_beside_its_sibling),
        cmocka_unit_test(test_too_close_is_told),
        cmocka_unit_test(test_real_frames_against_hand_labels),
        cmocka_unit_test(test_output_hash_is_pinned),
        cmocka_unit_test(test_real_frames_with_the_forest),
        cmocka_unit_test(test_output_hash_with_the_forest_is_pinned),
    };
    int r = cmocka_run_group_tests(tests, NULL, NULL);
    free(tracker_mem);
    return r;
}

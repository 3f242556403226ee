/* bridge: the player's leg phase (bridge_legs.c) on a synthetic pair of
 * standing clips. Two legs in the y-z plane; clip A stands upright, clip B
 * crouches and leans forward with its feet on the same spots of the floor
 * (its leg angles solved here by the law of cosines, in doubles). Played
 * A -> B through the player, a foot that stands on both sides of the
 * switch must not move; with the leg phase off, the fading offset (joint
 * rotations and the root's drift) swings it about. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "cub/bridge.h"

#define FRAMES 40
#define CLIPS 3
#define STEP_FORWARD_MM 300.0 /* clip 2 moves this far forward at its middle frame */
#define THIGH_MM 400.0
#define SHIN_MM 400.0
#define ANKLE_Y_MM 50.0 /* the toe (50 mm below, 100 ahead) is the floor */
#define Q(x) ((cub_q16)lround((x) * 65536.0))
#define POSES_FNV1A 0xe0fb4fcb87a1cb59ull

enum { HIPS, LUPLEG, LLEG, LFOOT, LTOE, RUPLEG, RLEG, RFOOT, RTOE, SPINE, HEAD, JOINTS };

typedef struct legs_fixture {
    cub_skeleton skel;
    cub_clip clips[CLIPS];
    uint8_t clip_mem[CLIPS][FRAMES * (JOINTS * 16 + 16) + 64];
    cub_fuzzy_frame fuzzy[CLIPS][FRAMES];
    cub_bridge_table table;
    uint8_t table_mem[1 << 16];
    uint8_t work[1 << 15];
} legs_fixture;

static legs_fixture F;

static void add_joint(int expect, const char *name, int parent, double x, double y, double z)
{
    int idx;
    cub_vec3 off = {Q(x), Q(y), Q(z)};
    assert_int_equal(cub_motion_skeleton_add(&F.skel, name, parent, off, &idx), CUB_OK);
    assert_int_equal(idx, expect);
}

static void make_skeleton(void)
{
    cub_motion_skeleton_reset(&F.skel);
    add_joint(HIPS, "Hips", -1, 0, 0, 0);
    add_joint(LUPLEG, "LeftUpLeg", HIPS, -100, 0, 0);
    add_joint(LLEG, "LeftLeg", LUPLEG, 0, -THIGH_MM, 0);
    add_joint(LFOOT, "LeftFoot", LLEG, 0, -SHIN_MM, 0);
    add_joint(LTOE, "LeftToe_end", LFOOT, 0, -ANKLE_Y_MM, 100);
    add_joint(RUPLEG, "RightUpLeg", HIPS, 100, 0, 0);
    add_joint(RLEG, "RightLeg", RUPLEG, 0, -THIGH_MM, 0);
    add_joint(RFOOT, "RightFoot", RLEG, 0, -SHIN_MM, 0);
    add_joint(RTOE, "RightToe_end", RFOOT, 0, -ANKLE_Y_MM, 100);
    add_joint(SPINE, "Spine", HIPS, 0, 200, 0);
    add_joint(HEAD, "Head", SPINE, 0, 200, 0);
}

static cub_quat about_x(double rad)
{
    return cub_fx_quat_from_axis_angle((cub_vec3){CUB_Q16_ONE, 0, 0}, Q(rad));
}

/* Leg angles (about x) putting the ankle at rel = ankle - hip joint (y, z):
 * a bone (0, -L, 0) turned by t about x points along (-cos t, -sin t). */
static void solve_leg(double ry, double rz, double *t_hip, double *t_knee)
{
    double d = hypot(ry, rz);
    double ck = (d * d - THIGH_MM * THIGH_MM - SHIN_MM * SHIN_MM) / (2 * THIGH_MM * SHIN_MM);
    *t_knee = acos(ck);
    *t_hip = atan2(-rz, -ry) - atan2(SHIN_MM * sin(*t_knee), THIGH_MM + SHIN_MM * cos(*t_knee));
}

/* A standing pose: the hips at (0, hip_y, hip_z), the trunk leaning by
 * lean rad, both ankles at (+-100, ANKLE_Y_MM, 0) with the feet flat. */
static void standing_pose(double hip_y, double hip_z, double lean, cub_pose *pose)
{
    cub_motion_pose_rest(&F.skel, pose);
    pose->root_mm = (cub_vec3){0, Q(hip_y), Q(hip_z)};
    double th, tk;
    solve_leg(ANKLE_Y_MM - hip_y, -hip_z, &th, &tk);
    const int leg[2][3] = {{LUPLEG, LLEG, LFOOT}, {RUPLEG, RLEG, RFOOT}};
    for (int s = 0; s < 2; s++) {
        pose->rot[leg[s][0]] = about_x(th);
        pose->rot[leg[s][1]] = about_x(tk);
        pose->rot[leg[s][2]] = about_x(-th - tk);
    }
    pose->rot[SPINE] = about_x(lean);
}

/* Clip c stands still; from its middle frame on, step_mm further forward
 * (the whole body: a clip that travels, which a loop plays in place). */
static void make_clip(int c, double hip_y, double hip_z, double lean, double step_mm)
{
    assert_int_equal(cub_motion_clip_init(&F.clips[c], &F.skel, FRAMES, 33333333, 0,
                                          F.clip_mem[c], sizeof F.clip_mem[c]),
                     CUB_OK);
    cub_pose pose;
    standing_pose(hip_y, hip_z, lean, &pose);
    for (int f = 0; f < FRAMES; f++) {
        if (f == FRAMES / 2) pose.root_mm.z += Q(step_mm);
        assert_int_equal(cub_motion_clip_set_frame(&F.clips[c], f, &pose), CUB_OK);
        /* Every frame alike to the features: the planner switches at once. */
        memset(&F.fuzzy[c][f], 0, sizeof F.fuzzy[c][f]);
        for (int k = 0; k < CUB_FUZZY_FEATURE_COUNT; k++)
            F.fuzzy[c][f].mu[k][0] = 32768;
    }
}

static void make_table(void)
{
    make_skeleton();
    make_clip(0, 840, 0, 0, 0);                 /* upright */
    make_clip(1, 700, 120, 0.4, 0);             /* crouched, the hips 12 cm forward, leaning */
    make_clip(2, 840, 0, 0, STEP_FORWARD_MM);   /* upright, then 30 cm forward */
    cub_fuzzy_body b = {.hip_centre = HIPS, .spine = SPINE, .shoulder_centre = SPINE,
                        .head = HEAD, .shoulder = {SPINE, SPINE}, .elbow = {SPINE, SPINE},
                        .wrist = {HEAD, HEAD}, .hip = {LUPLEG, RUPLEG}, .knee = {LLEG, RLEG},
                        .ankle = {LFOOT, RFOOT}, .stand_cog_mm = CUB_Q16_INT(500)};
    cub_bridge_table_desc d = {.skel = &F.skel, .body = b, .clip_count = CLIPS,
                               .frame_total = CLIPS * FRAMES, .bridge_total = CLIPS * FRAMES};
    assert_int_equal(cub_bridge_table_init(&F.table, &d, F.table_mem, sizeof F.table_mem), CUB_OK);
    int bridges[FRAMES];
    for (int f = 0; f < FRAMES; f++)
        bridges[f] = f;
    for (int c = 0; c < CLIPS; c++)
        assert_int_equal(cub_bridge_table_add_clip(&F.table, &F.clips[c], bridges, FRAMES,
                                                   F.fuzzy[c]),
                         CUB_OK);
    assert_int_equal(cub_bridge_table_finish(&F.table), CUB_OK);
}

static double dist_mm(cub_vec3 a, cub_vec3 b)
{
    return sqrt(pow((a.x - b.x) / 65536.0, 2) + pow((a.y - b.y) / 65536.0, 2) +
                pow((a.z - b.z) / 65536.0, 2));
}

static uint64_t g_hash; /* FNV-1a of every pose played by feet_travel_mm */

static void hash_words(const void *p, size_t n)
{
    const uint8_t *b = p;
    for (size_t i = 0; i < n; i++)
        g_hash = (g_hash ^ b[i]) * 0x100000001b3ull;
}

/* Play A -> B for three seconds; the most either ankle moves from where it
 * stood before the switch (mm). */
static double feet_travel_mm(int no_legs, int *blend_frames)
{
    g_hash = 0xcbf29ce484222325ull;
    static cub_bridge_player p;
    cub_bridge_player_desc pd = {.table = &F.table, .no_legs = no_legs};
    assert_true(cub_bridge_player_mem_size(&pd) <= sizeof F.work);
    assert_int_equal(cub_bridge_player_init(&p, &pd, F.work, sizeof F.work), CUB_OK);
    assert_int_equal(cub_bridge_player_start(&p, 0, 0, 0, 1), CUB_OK);
    static cub_pose pose;
    static cub_vec3 world[JOINTS];
    assert_int_equal(cub_bridge_player_pose(&p, &pose), CUB_OK);
    assert_int_equal(cub_motion_forward(&F.skel, &pose, world, NULL), CUB_OK);
    cub_vec3 start[2] = {world[LFOOT], world[RFOOT]};
    cub_bridge_plan plan;
    assert_int_equal(cub_bridge_player_request(&p, 1, 0, 1, &plan), CUB_OK);
    assert_int_equal(plan.step_count, 1);
    double worst = 0;
    int switched = 0;
    *blend_frames = 0;
    for (int t = 0; t < 90; t++) {
        cub_bridge_event ev[4];
        int n;
        assert_int_equal(cub_bridge_player_advance(&p, 33333, ev, 4, &n), CUB_OK);
        for (int k = 0; k < n; k++)
            switched |= ev[k].type == CUB_BRIDGE_EV_SWITCH;
        *blend_frames += switched && p.blending;
        assert_int_equal(cub_bridge_player_pose(&p, &pose), CUB_OK);
        hash_words(&pose.root_mm, sizeof pose.root_mm);
        hash_words(pose.rot, sizeof pose.rot[0] * JOINTS);
        assert_int_equal(cub_motion_forward(&F.skel, &pose, world, NULL), CUB_OK);
        worst = fmax(worst, fmax(dist_mm(world[LFOOT], start[0]), dist_mm(world[RFOOT], start[1])));
    }
    assert_true(switched);
    assert_int_equal(p.clip, 1);
    return worst;
}

static void test_clips_stand_on_the_same_spots(void **s)
{
    (void)s;
    make_table();
    static cub_pose pose;
    static cub_vec3 w[2][JOINTS];
    for (int c = 0; c < 2; c++) {
        assert_int_equal(cub_motion_clip_get_frame(&F.clips[c], 0, &pose), CUB_OK);
        assert_int_equal(cub_motion_forward(&F.skel, &pose, w[c], NULL), CUB_OK);
    }
    assert_true(dist_mm(w[0][LFOOT], w[1][LFOOT]) < 0.5);
    assert_true(dist_mm(w[0][RFOOT], w[1][RFOOT]) < 0.5);
    assert_true(dist_mm(w[0][LLEG], w[1][LLEG]) > 100); /* the knees do not */
}

static void test_planted_foot_stays_put_across_a_switch(void **s)
{
    (void)s;
    make_table();
    int frames = 0;
    double moved = feet_travel_mm(0, &frames);
    printf("bridge legs: the planted feet moved at most %.3f mm over a %d-frame blend; "
           "poses fnv1a %016llx\n",
           moved, frames, (unsigned long long)g_hash);
    assert_true(frames > 6);
    assert_true(moved < 1.0);
    /* Fixed point: the same poses on every CPU (recorded on x86-64, the
     * same under qemu-aarch64, the pi preset). */
    assert_true(g_hash == POSES_FNV1A);
}

static void test_without_the_leg_phase_the_feet_slide(void **s)
{
    (void)s;
    make_table();
    int frames = 0;
    double moved = feet_travel_mm(1, &frames);
    printf("bridge legs: without the leg phase the feet moved %.1f mm\n", moved);
    assert_true(moved > 10.0);
}

static void test_no_legs_in_the_body_no_leg_phase(void **s)
{
    (void)s;
    make_table();
    /* A body whose knee is not the hip's child: no two-bone legs. */
    cub_bridge_table t = F.table;
    t.desc.body.knee[0] = SPINE;
    static cub_bridge_player p;
    cub_bridge_player_desc pd = {.table = &t};
    assert_int_equal(cub_bridge_player_init(&p, &pd, F.work, sizeof F.work), CUB_OK);
    assert_false(p.legs.ok);
    pd.no_legs = 2;
    assert_int_equal(cub_bridge_player_init(&p, &pd, F.work, sizeof F.work), CUB_ERR_ARG);
}

/* A fresh table and a player with the leg phase, playing clip c in a loop. */
static void play_looping(cub_bridge_player *p, int c)
{
    make_table();
    cub_bridge_player_desc pd = {.table = &F.table};
    assert_int_equal(cub_bridge_player_init(p, &pd, F.work, sizeof F.work), CUB_OK);
    assert_int_equal(cub_bridge_player_start(p, c, 0, 0, 1), CUB_OK);
}

/* The ankles of pose (world). */
static void ankles(const cub_pose *pose, cub_vec3 out[2])
{
    static cub_vec3 world[JOINTS];
    assert_int_equal(cub_motion_forward(&F.skel, pose, world, NULL), CUB_OK);
    out[0] = world[LFOOT], out[1] = world[RFOOT];
}

/* A looping clip that travels (30 cm forward at its middle) is played in
 * place: each pass is a real cut, back 30 cm, whose steps (2 x 45 frames
 * at the blend's 2.5 cm a frame) would outlast the 40-frame pass. Over
 * twenty passes every leg phase must end by the end of its pass (the
 * player's leg state: where it began, how long each leg takes), late in
 * a pass the feet stand where the clip puts them, and they do not drift
 * from pass to pass. */
static void test_a_looping_clip_that_travels_ends_each_leg_phase(void **s)
{
    (void)s;
    static cub_bridge_player p;
    play_looping(&p, 2);
    static cub_pose pose;
    cub_vec3 own[2], shown[2], first[2] = {{0}};
    assert_int_equal(cub_motion_clip_get_frame(&F.clips[2], FRAMES - 2, &pose), CUB_OK);
    ankles(&pose, own);
    double worst_own = 0, worst_drift = 0;
    int passes = 0, phases = 0, overrun = -FRAMES;
    for (int t = 1; t <= 20 * FRAMES; t++) {
        cub_bridge_event ev[4];
        int n;
        assert_int_equal(cub_bridge_player_advance(&p, 33333, ev, 4, &n), CUB_OK);
        int64_t pass_end = ((p.pos_q16 >> 16) / FRAMES + 1) * FRAMES;
        if (p.legs.on && p.legs.from_q16 >> 16 == pass_end - FRAMES) {
            int64_t end = (p.legs.from_q16 >> 16) + (p.legs.planted ? 2 : 1) * p.legs.len;
            phases += (p.pos_q16 >> 16) % FRAMES == 0;
            overrun = overrun > end - pass_end ? overrun : (int)(end - pass_end);
        }
        if ((p.pos_q16 >> 16) % FRAMES != FRAMES - 2 || t < FRAMES) continue;
        assert_int_equal(cub_bridge_player_pose(&p, &pose), CUB_OK);
        ankles(&pose, shown);
        if (!passes++) first[0] = shown[0], first[1] = shown[1];
        for (int k = 0; k < 2; k++) {
            worst_own = fmax(worst_own, dist_mm(shown[k], own[k]));
            worst_drift = fmax(worst_drift, dist_mm(shown[k], first[k]));
        }
    }
    printf("bridge legs: a travelling loop over %d passes (%d leg phases): they end by their "
           "pass's end %+d frames; its feet %.3f mm from the clip's own late in each pass, "
           "drifting %.3f mm\n",
           passes, phases, overrun, worst_own, worst_drift);
    assert_true(passes >= 18);
    assert_true(phases >= 18); /* each wrap is a cut for the feet */
    assert_true(overrun <= 0);
    assert_true(worst_own < 1.0);
    assert_true(worst_drift < 1.0);
}

/* A clip whose last frame runs into its first (clip 0 stands still):
 * its loop's wraps are no cut for the feet, no leg phase starts. */
static void test_a_seamless_loop_starts_no_leg_phase(void **s)
{
    (void)s;
    static cub_bridge_player p;
    play_looping(&p, 0);
    int wraps = 0, phases = 0;
    for (int t = 0; t < 3 * FRAMES; t++) {
        cub_bridge_event ev[4];
        int n;
        assert_int_equal(cub_bridge_player_advance(&p, 33333, ev, 4, &n), CUB_OK);
        for (int k = 0; k < n; k++)
            wraps += ev[k].type == CUB_BRIDGE_EV_DONE;
        phases += p.legs.on;
    }
    assert_true(wraps >= 2);
    assert_int_equal(phases, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_no_legs_in_the_body_no_leg_phase),
        cmocka_unit_test(test_clips_stand_on_the_same_spots),
        cmocka_unit_test(test_planted_foot_stays_put_across_a_switch),
        cmocka_unit_test(test_without_the_leg_phase_the_feet_slide),
        cmocka_unit_test(test_a_looping_clip_that_travels_ends_each_leg_phase),
        cmocka_unit_test(test_a_seamless_loop_starts_no_leg_phase),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

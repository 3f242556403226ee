/* test_gait_walk — seed 003's phase analysis (cub/gait.h) on a captured
 * walk, CMU 02_01, read from $CUB_DATA_DIR at test time (never committed;
 * skipped without it). Per foot: the phases come in the cycle's order, and
 * the foot's stance covers its contact frames, found here independently of
 * the analysis (the foot planted: ankle and toe both low and still). The
 * figures (foot length, frames per phase, cycles) go to stdout. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>

#include "../synth/synth_data.h"
#include "gait_test_clip.h"
#include "cub/gait.h"
#include "cub/io.h"

/* $CUB_GAIT_CLIP names another CMU BVH clip (a held-out run by hand). */
#define CLIP clip_name()

static const char *clip_name(void)
{
    const char *c = getenv("CUB_GAIT_CLIP");
    return c && *c ? c : "02_01";
}

static cub_io_motion walk;

typedef struct foot_track {
    const char *ankle, *toe;
    cub_vec3 *a, *t;
    uint8_t *phase;
    cub_gait_foot info;
} foot_track;

static int load(void **state)
{
    (void)state;
    return gait_test_load(CLIP, &walk) < 0 ? -1 : 0;
}

static int unload(void **state)
{
    (void)state;
    if (walk.frame_mem) cub_io_motion_free(&walk);
    return 0;
}

static void track(foot_track *f)
{
    int n = walk.clip.frame_count;
    f->a = calloc((size_t)n, sizeof *f->a);
    f->t = calloc((size_t)n, sizeof *f->t);
    f->phase = calloc((size_t)n, 1);
    assert_non_null(f->a);
    assert_non_null(f->t);
    assert_non_null(f->phase);
    int ai = cub_motion_skeleton_find(&walk.skel, f->ankle);
    int ti = cub_motion_skeleton_find(&walk.skel, f->toe);
    assert_true(ai >= 0 && ti >= 0);
    assert_int_equal(cub_gait_track_clip(&walk.clip, ai, ti, f->a, f->t), CUB_OK);
    assert_int_equal(cub_gait_analyse(f->a, f->t, n, NULL, f->phase, &f->info), CUB_OK);
}

static void untrack(foot_track *f)
{
    free(f->a);
    free(f->t);
    free(f->phase);
}

/* Speed of a point at frame i in mm per second (central difference). */
static double speed(const cub_vec3 *p, int i, int n)
{
    int a = i > 0 ? i - 1 : 0, b = i < n - 1 ? i + 1 : n - 1;
    double dx = (p[b].x - p[a].x) / 65536.0, dy = (p[b].y - p[a].y) / 65536.0;
    double dz = (p[b].z - p[a].z) / 65536.0;
    double fps = 1e9 / walk.clip.frame_ns;
    return __builtin_sqrt(dx * dx + dy * dy + dz * dz) * fps / (b - a);
}

static void report(const foot_track *f)
{
    printf("gait: %s %s: foot %.1f mm, cycles %d, frames", CLIP, f->ankle,
           f->info.length_mm / 65536.0, f->info.cycles);
    for (int p = 0; p < CUB_GAIT_PHASE_COUNT_; p++)
        printf(" %s %d", cub_gait_phase_name((cub_gait_phase)p), f->info.phase_frames[p]);
    printf("\ngait: runs");
    for (int i = 0; i < walk.clip.frame_count; i++)
        if (i == 0 || f->phase[i] != f->phase[i - 1])
            printf(" %d:%s", i, cub_gait_phase_name(f->phase[i]));
    printf("\n");
}

/* Every change of phase is to the next one of the cycle: stance, lift,
 * off, strike, land, stance again. */
static void assert_phases_in_order(const foot_track *f)
{
    for (int i = 1; i < walk.clip.frame_count; i++) {
        int a = f->phase[i - 1], b = f->phase[i];
        if (a != b && b != (a + 1) % CUB_GAIT_PHASE_COUNT_)
            fail_msg("%s frame %d: %s after %s", f->ankle, i, cub_gait_phase_name(b),
                     cub_gait_phase_name(a));
    }
}

/* Contact, found apart from the analysis: the ankle and the toe both
 * slower than 25 cm/s (a swinging foot moves at 3-4 m/s). Every contact
 * frame is one of the cycle's both-down phases (land, stance) and nine
 * in ten are stance proper: land is the few frames the foot still rolls
 * flat once down. */
static void assert_stance_covers_contact(const foot_track *f)
{
    int n = walk.clip.frame_count, contact = 0, stance = 0;
    for (int i = 0; i < n; i++) {
        if (speed(f->a, i, n) >= 250 || speed(f->t, i, n) >= 250) continue;
        contact++;
        if (f->phase[i] != CUB_GAIT_STANCE && f->phase[i] != CUB_GAIT_LAND)
            fail_msg("%s frame %d: planted but %s", f->ankle, i, cub_gait_phase_name(f->phase[i]));
        stance += f->phase[i] == CUB_GAIT_STANCE;
    }
    printf("gait: %s contact frames %d, in stance %d, in land %d\n", f->ankle, contact, stance,
           contact - stance);
    assert_true(contact >= 60); /* two steps' worth, at least */
    assert_true(stance * 10 >= contact * 9);
}

static void test_phases_in_order_and_stance_covers_contact(void **state)
{
    (void)state;
    SYNTH_NEED_DATA(CLIP);
    foot_track feet[2] = {{.ankle = "LeftFoot", .toe = "LeftToeBase"},
                          {.ankle = "RightFoot", .toe = "RightToeBase"}};
    for (int k = 0; k < 2; k++) {
        foot_track *f = &feet[k];
        track(f);
        report(f);
        assert_phases_in_order(f);
        assert_true(f->info.cycles >= 2);
        /* The foot's length: CMU's ankle to the ball of the foot, 13-14 cm. */
        assert_in_range(f->info.length_mm, CUB_Q16_INT(120), CUB_Q16_INT(150));
        assert_stance_covers_contact(f);
        untrack(f);
    }
}

/* The leg IK's default ranges (knee 25..175 degrees, ankle 35..150) hold
 * the captured walk: the limits would not bend the reference. */
static void test_walk_stays_in_the_leg_ranges(void **state)
{
    (void)state;
    SYNTH_NEED_DATA(CLIP);
    static const char *const names[2][4] = {
        {"LeftUpLeg", "LeftLeg", "LeftFoot", "LeftToeBase"},
        {"RightUpLeg", "RightLeg", "RightFoot", "RightToeBase"}};
    static cub_pose pose;
    for (int k = 0; k < 2; k++) {
        int j[4];
        for (int i = 0; i < 4; i++)
            assert_true((j[i] = cub_motion_skeleton_find(&walk.skel, names[k][i])) >= 0);
        double kmin = 1e9, kmax = -1e9, amin = 1e9, amax = -1e9;
        for (int f = 0; f < walk.clip.frame_count; f++) {
            cub_vec3 p[4];
            cub_quat r;
            assert_int_equal(cub_motion_clip_get_frame(&walk.clip, f, &pose), CUB_OK);
            for (int i = 0; i < 4; i++)
                assert_int_equal(cub_motion_joint_world(&walk.skel, &pose, j[i], &p[i], &r),
                                 CUB_OK);
            double knee =
                cub_fx_vec3_angle(cub_fx_vec3_sub(p[0], p[1]), cub_fx_vec3_sub(p[2], p[1])) *
                (180.0 / 205887.0);
            double ankle = cub_gait_ankle_angle(p[1], p[2], p[3]) * (180.0 / 205887.0);
            kmin = knee < kmin ? knee : kmin;
            kmax = knee > kmax ? knee : kmax;
            amin = ankle < amin ? ankle : amin;
            amax = ankle > amax ? ankle : amax;
        }
        printf("gait: %s knee %.1f..%.1f deg, ankle %.1f..%.1f deg\n", names[k][0], kmin, kmax,
               amin, amax);
        assert_true(kmin >= 25 && kmax <= 175);
        assert_true(amin >= 35 && amax <= 150);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_phases_in_order_and_stance_covers_contact),
        cmocka_unit_test(test_walk_stays_in_the_leg_ranges),
    };
    return cmocka_run_group_tests(tests, load, unload);
}

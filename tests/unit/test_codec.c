/* test_codec — the seed's codec (firmware/codec): the quantiser's edges,
 * Squad's restore on a smooth synthetic rotation, the CCD step, and a
 * damaged stream refused with its reason. The round trip on the bear's own
 * clips and the decoded-output hash are in tests/io/test_codec_clips.c. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/codec.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#define Q30_ONE (1 << 30)
#define MM(x) ((cub_q16)lround((x)*65536.0))

static double quat_angle_deg(cub_quat a, cub_quat b)
{
    double d = ((double)a.w * b.w + (double)a.x * b.x + (double)a.y * b.y + (double)a.z * b.z) /
               ((double)Q30_ONE * Q30_ONE);
    d = fabs(d) > 1 ? 1 : fabs(d);
    return 2 * acos(d) * 180 / M_PI;
}

static double dist_mm(cub_vec3 a, cub_vec3 b)
{
    double dx = (a.x - b.x) / 65536.0, dy = (a.y - b.y) / 65536.0, dz = (a.z - b.z) / 65536.0;
    return sqrt(dx * dx + dy * dy + dz * dz);
}

static void test_quant_unit_edges(void **state)
{
    (void)state;
    assert_int_equal(cub_codec_quant_unit(Q30_ONE), 65535); /* not -1.0's 0 */
    assert_int_equal(cub_codec_quant_unit(-Q30_ONE), 0);
    assert_int_equal(cub_codec_quant_unit(0), 32768);
    assert_int_equal(cub_codec_quant_unit(Q30_ONE / 2), 49152);
    /* truncation toward zero, as (int) in the seed: just below a step */
    assert_int_equal(cub_codec_quant_unit((1 << 15) - 1), 32768);
    assert_int_equal(cub_codec_quant_unit(-((1 << 15) - 1)), 32768);
    assert_int_equal(cub_codec_quant_unit(-(1 << 15)), 32767);
    assert_int_equal(cub_codec_dequant_unit(0), -Q30_ONE);
    assert_int_equal(cub_codec_dequant_unit(32768), 0);
    assert_int_equal(cub_codec_dequant_unit(65535), Q30_ONE - (1 << 15));
    /* every code in range comes back within one step */
    for (int32_t x = -Q30_ONE; x <= Q30_ONE - 4099; x += 4099) {
        int32_t back = cub_codec_dequant_unit(cub_codec_quant_unit(x));
        assert_true(abs(back - x) < (1 << 15));
    }
}

static void test_quant_split(void **state)
{
    (void)state;
    int8_t whole;
    uint16_t code;
    cub_codec_quant_split(MM(2750.0), &whole, &code); /* 2.75 m */
    assert_int_equal(whole, 2);
    assert_int_equal(code, 57344); /* 0.75 * 32768 + 32768 */
    assert_int_equal(cub_codec_dequant_split(whole, code), MM(2750.0));
    cub_codec_quant_split(MM(-2750.0), &whole, &code);
    assert_int_equal(whole, -2);
    assert_int_equal(code, 8192);
    assert_int_equal(cub_codec_dequant_split(whole, code), MM(-2750.0));
    cub_codec_quant_split(MM(1000.0), &whole, &code); /* +1.0 m: 1 and 0, no wrap */
    assert_int_equal(whole, 1);
    assert_int_equal(code, 32768);
    cub_codec_quant_split(0, &whole, &code);
    assert_int_equal(whole, 0);
    assert_int_equal(code, 32768);
    for (int64_t m = INT32_MIN + 7LL; m < INT32_MAX - 300000LL; m += 40009 * 7) {
        int32_t mm = (int32_t)m;
        cub_codec_quant_split(mm, &whole, &code);
        /* a step is 2000 Q16.16 mm (0.031 mm); truncation loses under one */
        assert_true(llabs((long long)cub_codec_dequant_split(whole, code) - mm) < 2000);
    }
}

/* A one-joint clip whose rotation turns smoothly about a wandering axis. */
static cub_quat smooth_rot(int f)
{
    double t = f / 30.0, ang = 1.2 * sin(1.7 * t) + 0.4 * t;
    double ax[3] = {cos(0.9 * t), 0.5, sin(0.9 * t)};
    double n = sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]), s = sin(ang / 2) / n;
    return (cub_quat){(int32_t)lround(cos(ang / 2) * Q30_ONE), (int32_t)lround(ax[0] * s * Q30_ONE),
                      (int32_t)lround(ax[1] * s * Q30_ONE), (int32_t)lround(ax[2] * s * Q30_ONE)};
}

#define SYN_FRAMES 97

typedef struct fixture {
    cub_skeleton skel, out_skel;
    cub_clip clip, out;
    uint8_t mem[1 << 16], out_mem[1 << 17], stream[1 << 14], work[1 << 18];
    size_t len;
} fixture;

static fixture fx;

static void make_synthetic(void)
{
    cub_motion_skeleton_reset(&fx.skel);
    int idx;
    assert_int_equal(cub_motion_skeleton_add(&fx.skel, "Hips", -1, (cub_vec3){0, 0, 0}, &idx), CUB_OK);
    assert_int_equal(cub_motion_skeleton_add(&fx.skel, "Up", 0, (cub_vec3){0, MM(-400), 0}, &idx), CUB_OK);
    assert_int_equal(cub_motion_clip_init(&fx.clip, &fx.skel, SYN_FRAMES, 33333333, 0, fx.mem,
                                          sizeof fx.mem), CUB_OK);
    for (int f = 0; f < SYN_FRAMES; f++) {
        fx.clip.rot[f * 2 + 1] = smooth_rot(f);
        fx.clip.rot[f * 2] = f == 40 ? (cub_quat){Q30_ONE, 0, 0, 0} : smooth_rot(2 * f);
        fx.clip.root_mm[f] = (cub_vec3){MM(3000 * sin(f / 20.0)), MM(900 + f), MM(-1500.5)};
    }
    cub_codec_enc in = {&fx.clip, NULL, 0, fx.work, sizeof fx.work};
    assert_int_equal(cub_codec_encode(&in, fx.stream, sizeof fx.stream, &fx.len), CUB_OK);
}

static void decode_with(cub_codec_method m)
{
    cub_codec_opts o = {m, CUB_CODEC_IK_STREAM};
    cub_codec_out dst = {&fx.out_skel, &fx.out, fx.out_mem, sizeof fx.out_mem};
    cub_codec_problem why = {0};
    assert_int_equal(cub_codec_decode(fx.stream, fx.len, &o, &dst, &why), CUB_OK);
}

static void test_squad_restore(void **state)
{
    (void)state;
    make_synthetic();
    decode_with(CUB_CODEC_SQUAD);
    double worst = 0, worst_pos = 0;
    for (int f = 0; f < SYN_FRAMES; f++)
        for (int j = 0; j < 2; j++) {
            cub_quat src = fx.clip.rot[f * 2 + j], got = fx.out.rot[f * 2 + j];
            if (cub_codec_is_kept(f, SYN_FRAMES)) {
                /* kept: exactly the dequantised codes, normalised */
                cub_quat q = {cub_codec_dequant_unit(cub_codec_quant_unit(src.w)),
                              cub_codec_dequant_unit(cub_codec_quant_unit(src.x)),
                              cub_codec_dequant_unit(cub_codec_quant_unit(src.y)),
                              cub_codec_dequant_unit(cub_codec_quant_unit(src.z))};
                q = cub_fx_quat_normalize(q);
                assert_memory_equal(&q, &got, sizeof q);
                assert_true(quat_angle_deg(src, got) < 0.01);
            } else if (j == 1) {
                double e = quat_angle_deg(src, got);
                worst = e > worst ? e : worst;
            }
            if (j == 0) {
                double e = dist_mm(fx.clip.root_mm[f], fx.out.root_mm[f]);
                worst_pos = e > worst_pos ? e : worst_pos;
            }
        }
    printf("# synthetic smooth rotation: worst restored error %.4f deg, root %.3f mm\n", worst,
           worst_pos);
    assert_true(worst < 0.1);
    assert_true(worst_pos < 2.0);
    assert_true(cub_codec_is_kept(40, SYN_FRAMES)); /* the +1.0 frame survived */
    assert_true(quat_angle_deg(fx.out.rot[80], (cub_quat){Q30_ONE, 0, 0, 0}) < 0.01);
}

static void test_squad_control_identity(void **state)
{
    (void)state;
    /* equal neighbours: the control point is q itself (log terms vanish) */
    cub_quat q = smooth_rot(10);
    cub_quat s = cub_codec_squad_control(q, q, q);
    assert_true(quat_angle_deg(q, s) < 0.001);
    /* on a great arc at constant speed the control points lie on the arc and
     * Squad's midpoint is the arc's */
    cub_quat arc[4];
    for (int i = 0; i < 4; i++) {
        double a = 0.3 * i;
        arc[i] = (cub_quat){(int32_t)lround(cos(a / 2) * Q30_ONE), 0,
                            (int32_t)lround(sin(a / 2) * Q30_ONE), 0};
    }
    cub_quat mid = cub_codec_rot_mid(arc, CUB_CODEC_SQUAD);
    cub_quat want = {(int32_t)lround(cos(0.225) * Q30_ONE), 0, (int32_t)lround(sin(0.225) * Q30_ONE), 0};
    assert_true(quat_angle_deg(mid, want) < 0.002);
    /* -q for a neighbour is the same rotation: the same midpoint */
    arc[3] = (cub_quat){-arc[3].w, -arc[3].x, -arc[3].y, -arc[3].z};
    assert_true(quat_angle_deg(cub_codec_rot_mid(arc, CUB_CODEC_SQUAD), want) < 0.002);
}

/* A leg (hip, knee, ankle, foot) and an arm beside it. */
static void make_leg(cub_skeleton *s)
{
    int i;
    cub_motion_skeleton_reset(s);
    cub_motion_skeleton_add(s, "Hips", -1, (cub_vec3){0, 0, 0}, &i);
    cub_motion_skeleton_add(s, "LeftUpLeg", 0, (cub_vec3){MM(100), MM(-50), 0}, &i);
    cub_motion_skeleton_add(s, "LeftLeg", 1, (cub_vec3){0, MM(-420), 0}, &i);
    cub_motion_skeleton_add(s, "LeftFoot", 2, (cub_vec3){0, MM(-400), MM(10)}, &i);
    cub_motion_skeleton_add(s, "LeftToe", 3, (cub_vec3){0, MM(-50), MM(120)}, &i);
    cub_motion_skeleton_add(s, "Spine", 0, (cub_vec3){0, MM(200), 0}, &i);
    cub_motion_skeleton_add(s, "LeftHand", 5, (cub_vec3){MM(300), MM(200), 0}, &i);
}

static cub_quat axis_angle(double x, double y, double z, double ang)
{
    double n = sqrt(x * x + y * y + z * z), s = sin(ang / 2) / n;
    return (cub_quat){(int32_t)lround(cos(ang / 2) * Q30_ONE), (int32_t)lround(x * s * Q30_ONE),
                      (int32_t)lround(y * s * Q30_ONE), (int32_t)lround(z * s * Q30_ONE)};
}

static void test_ccd_step(void **state)
{
    (void)state;
    static cub_skeleton s;
    make_leg(&s);
    int eff[4];
    /* the foot; not the hand, whose grandparent is the root */
    assert_int_equal(cub_codec_pick_effectors(&s, eff, 4), 1);
    assert_int_equal(eff[0], 3);
    cub_pose goal, pose;
    cub_motion_pose_rest(&s, &goal);
    goal.rot[0] = axis_angle(0, 1, 0, 0.3);
    goal.rot[1] = axis_angle(1, 0.2, 0, -0.6);
    goal.rot[2] = axis_angle(1, 0, 0.1, 0.9);
    cub_vec3 target[8], before[8], after[8];
    assert_int_equal(cub_motion_forward(&s, &goal, target, NULL), CUB_OK);
    pose = goal;
    pose.rot[1] = axis_angle(1, 0, 0, -0.2); /* the restored pose: off by 0.4 rad at the hip */
    pose.rot[2] = axis_angle(1, 0, 0, 0.5);
    assert_int_equal(cub_motion_forward(&s, &pose, before, NULL), CUB_OK);
    double start = dist_mm(before[3], target[3]);
    assert_int_equal(cub_codec_ccd(&s, &pose, 3, target[3]), CUB_OK);
    assert_int_equal(cub_motion_forward(&s, &pose, after, NULL), CUB_OK);
    double end = dist_mm(after[3], target[3]);
    printf("# CCD: effector %.2f mm -> %.3f mm from a reachable target\n", start, end);
    assert_true(start > 100);
    assert_true(end < 1.0);
    /* joints outside the hip's subtree stay put, bit for bit */
    const int still[] = {0, 1, 5, 6};
    for (size_t k = 0; k < sizeof still / sizeof *still; k++)
        assert_memory_equal(&before[still[k]], &after[still[k]], sizeof(cub_vec3));
    for (int j = 0; j < 7; j++)
        if (j != 1 && j != 2) assert_memory_equal(&pose.rot[j], &goal.rot[j], sizeof(cub_quat));
    /* no grandparent: refused */
    assert_int_equal(cub_codec_ccd(&s, &pose, 1, target[3]), CUB_ERR_ARG);
}

static void expect_refused(const uint8_t *data, size_t len, const char *what)
{
    cub_codec_out dst = {&fx.out_skel, &fx.out, fx.out_mem, sizeof fx.out_mem};
    cub_codec_problem why = {0};
    cub_codec_info info;
    assert_int_equal(cub_codec_decode(data, len, NULL, &dst, &why), CUB_ERR_FORMAT);
    assert_non_null(why.what);
    if (!strstr(why.what, what)) fail_msg("refused with '%s', wanted '%s'", why.what, what);
    assert_int_equal(cub_codec_peek(data, len, &info, NULL), CUB_ERR_FORMAT);
}

static void test_damaged_stream(void **state)
{
    (void)state;
    make_synthetic();
    static uint8_t bad[1 << 14];
    memcpy(bad, fx.stream, fx.len);
    bad[fx.len / 2] ^= 0x10;
    expect_refused(bad, fx.len, "CRC");
    expect_refused(fx.stream, fx.len - 1, "length");
    expect_refused(fx.stream, 10, "too short");
    memcpy(bad, fx.stream, fx.len);
    bad[0] = 'X';
    expect_refused(bad, fx.len, "magic");
    memcpy(bad, fx.stream, fx.len);
    bad[7] = 9;
    expect_refused(bad, fx.len, "version");
    /* a short buffer is not a format problem */
    cub_codec_out small = {&fx.out_skel, &fx.out, fx.out_mem, 100};
    assert_int_equal(cub_codec_decode(fx.stream, fx.len, NULL, &small, NULL), CUB_ERR_NOMEM);
    cub_codec_info info;
    assert_int_equal(cub_codec_peek(fx.stream, fx.len, &info, NULL), CUB_OK);
    assert_int_equal(info.frame_count, SYN_FRAMES);
    assert_int_equal(info.joint_count, 2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_quant_unit_edges),   cmocka_unit_test(test_quant_split),
        cmocka_unit_test(test_squad_control_identity), cmocka_unit_test(test_squad_restore),
        cmocka_unit_test(test_ccd_step),           cmocka_unit_test(test_damaged_stream),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* Keyframe text clips: every error names its line; a hand-written clip on
 * the bear hits its key poses exactly at the key frames, holds what a key
 * does not write, and moves smoothly between keys (and across a loop). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/character.h"
#include "cub/keys.h"

#define PI 3.14159265358979323846

static cub_character *bear;

static int load_bear(void **state)
{
    (void)state;
    const char *src = getenv("CUB_SOURCE_DIR");
    char path[512];
    snprintf(path, sizeof(path), "%s/assets/bear/bear.xml", src ? src : "..");
    bear = malloc(sizeof(*bear));
    cub_diag d = {0};
    if (cub_character_load(path, bear, &d)) {
        fprintf(stderr, "%s:%d: %s\n", d.file, d.line, d.msg);
        return -1;
    }
    return 0;
}

static int free_bear(void **state)
{
    (void)state;
    free(bear);
    return 0;
}

static void expect_error(const char *text, int line, const char *words)
{
    cub_keys_clip *k = malloc(sizeof(*k));
    cub_diag d = {0};
    char msg[600];
    cub_err err = cub_keys_parse(text, strlen(text), "t.keys", &bear->skel, k, &d);
    cub_diag_str(&d, msg, sizeof(msg));
    printf("keys: rejected: %s\n", msg);
    assert_int_equal(err, CUB_ERR_FORMAT);
    assert_null(k->mem);
    assert_string_equal(d.file, "t.keys");
    assert_int_equal(d.line, line);
    if (!strstr(d.msg, words)) fail_msg("message '%s' lacks '%s'", d.msg, words);
    free(k);
}

#define CLIP "clip t kind=dance fps=30\n"

static void test_errors_name_the_line(void **state)
{
    (void)state;
    expect_error(CLIP "key 0 LeftArmm z=3\n", 2, "unknown joint 'LeftArmm'");
    expect_error(CLIP "key 0\n  LeftArm z=3\n  # fine\n  Hed x=1\n", 5, "unknown joint 'Hed'");
    expect_error(CLIP "key 0 LeftArm z=abc\n", 2, "bad number 'abc' for LeftArm z");
    expect_error(CLIP "key 0 LeftArm w=3\n", 2, "unknown axis in 'w=3'");
    expect_error(CLIP "key 0 LeftArm z=3 z=4\n", 2, "axis z given twice");
    expect_error(CLIP "key 0 LeftArm z=3\nkey 1 Head x=1 LeftArm x=1 Head y=2\n", 3,
                 "'Head' appears twice");
    expect_error(CLIP "key 0\nkey 0.5\nkey 0.5\n", 4,
                 "key time 0.5 is not after the previous key's 0.5 (line 3)");
    expect_error(CLIP "key 0\nkey 0.5\nkey 0.25\n", 4, "not after");
    expect_error(CLIP "key 0\nkey 0.5\nkey 0.51\n", 4, "same frame");
    expect_error(CLIP "key 0.1\n", 2, "first key must be at time 0");
    expect_error(CLIP "key x\n", 2, "bad number 'x' for the key time");
    expect_error(CLIP "key\n", 2, "needs a time");
    expect_error(CLIP "key 0 z=5\n", 2, "'z=5' does not follow a joint name");
    expect_error(CLIP "key 0 Head_end x=5\n", 2, "end site");
    expect_error(CLIP "key 0 root=1,2\n", 2, "bad root");
    expect_error(CLIP "key 0 root=1,2,3,4\n", 2, "bad root");
    expect_error(CLIP "key 0 root=1,x,3\n", 2, "bad root");
    expect_error(CLIP "key 0 LeftArm z=1e9\n", 2, "beyond");
    expect_error(CLIP "key 0\nloop\n", 3, "bare 'loop' needs two keys");
    expect_error(CLIP "key 0\nkey 1\nloop 0.5\n", 4, "must come after the last key");
    expect_error(CLIP "key 0\nloop\nkey 1\n", 4, "nothing may follow loop (line 3)");
    /* Issue 18: taken as a bare loop, or a period overflowed ("0 s"). */
    expect_error(CLIP "key 0\nkey 1\nloop -5\n", 4,
                 "the loop time '-5' must be a number of seconds above 0 and at most 600");
    expect_error(CLIP "key 0\nkey 1\nloop 1e300\n", 4,
                 "the loop time '1e300' must be a number of seconds above 0 and at most 600");
    expect_error(CLIP "key 0\nkey 1\nloop 0\n", 4, "the loop time '0' must be");
    expect_error("# no clip line\nkey 0\n", 2, "expected 'clip NAME ...' first");
    expect_error(CLIP "clip u\n", 2, "a second clip line");
    expect_error("clip t fps=0\n", 1, "fps 0 is not in 1..240");
    expect_error("clip t fps=x\n", 1, "bad integer 'x' for fps");
    expect_error("clip t speed=2\n", 1, "unknown clip option 'speed=2'");
    expect_error("clip\n", 1, "clip needs a name");
    expect_error("clip t kind=averyveryverylongkind\n", 1, "longer than 15");
    expect_error(CLIP "LeftArm z=3\n", 2, "expected clip, key or loop");
    expect_error(CLIP, 1, "no keys");
    expect_error(CLIP "# nothing else\n\n", 1, "no keys");
    expect_error("", 1, "no clip line");

    cub_keys_clip *k = malloc(sizeof(*k));
    cub_diag d = {0};
    assert_int_equal(cub_keys_load("/nonexistent/x.keys", &bear->skel, k, &d), CUB_ERR_IO);
    assert_int_equal(cub_keys_parse("x", 1, "t", NULL, k, &d), CUB_ERR_ARG);
    free(k);
}

/* ---- behaviour ----------------------------------------------------------- */

static void qmul(const double a[4], const double b[4], double out[4])
{
    out[0] = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
    out[1] = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
    out[2] = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
    out[3] = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
}

/* Rz(z) * Ry(y) * Rx(x) in doubles, from degrees; w >= 0. */
static void euler_quat(double xd, double yd, double zd, double q[4])
{
    double h = PI / 360.0; /* half angle per degree */
    double qx[4] = {cos(xd * h), sin(xd * h), 0, 0}, qy[4] = {cos(yd * h), 0, sin(yd * h), 0};
    double qz[4] = {cos(zd * h), 0, 0, sin(zd * h)}, zy[4];
    qmul(qz, qy, zy);
    qmul(zy, qx, q);
    if (q[0] < 0)
        for (int i = 0; i < 4; i++)
            q[i] = -q[i];
}

static void expect_rot(const cub_keys_clip *k, int frame, const char *joint, double x, double y,
                       double z)
{
    int j = cub_motion_skeleton_find(&bear->skel, joint);
    assert_true(j >= 0);
    cub_quat got = k->clip.rot[(size_t)frame * (size_t)bear->skel.joint_count + (size_t)j];
    double q[4], g[4] = {got.w, got.x, got.y, got.z};
    euler_quat(x, y, z, q);
    for (int i = 0; i < 4; i++)
        if (fabs(g[i] / 1073741824.0 - q[i]) > 4e-9)
            fail_msg("frame %d %s: component %d is %.10f, want %.10f", frame, joint, i,
                     g[i] / 1073741824.0, q[i]);
}

static double quat_angle_deg(cub_quat a, cub_quat b)
{
    double d = ((double)a.w * b.w + (double)a.x * b.x + (double)a.y * b.y + (double)a.z * b.z) /
               (1073741824.0 * 1073741824.0);
    d = fabs(d) > 1 ? 1 : fabs(d);
    return 2 * acos(d) * 180 / PI;
}

/* Largest rotation of any joint from one frame to the next, and the largest
 * change of that step between neighbouring frames (a kink or jump). */
static void steps(const cub_keys_clip *k, int wrap, double *max_step, double *max_kink)
{
    int n = k->clip.frame_count, jn = bear->skel.joint_count, end = wrap ? n : n - 1;
    *max_step = *max_kink = 0;
    for (int j = 0; j < jn; j++) {
        double prev = -1;
        for (int f = 0; f < end; f++) {
            const cub_quat *r = k->clip.rot;
            double s = quat_angle_deg(r[(size_t)f * jn + j], r[(size_t)((f + 1) % n) * jn + j]);
            *max_step = s > *max_step ? s : *max_step;
            if (prev >= 0 && fabs(s - prev) > *max_kink) *max_kink = fabs(s - prev);
            prev = s;
        }
    }
}

/* The fastest average speed from one key to the next, over every joint
 * (deg/frame); a cubic that eases through keys peaks at 1.5 times it. */
static double fastest_key_speed(const cub_keys_clip *k)
{
    int jn = bear->skel.joint_count, n = k->key_count;
    double best = 0;
    for (int i = 0; i + 1 < n + k->loop; i++) {
        int f0 = k->key_frame[i], f1 = i + 1 < n ? k->key_frame[i + 1] : k->clip.frame_count;
        int g1 = f1 % k->clip.frame_count;
        for (int j = 0; j < jn; j++) {
            double v =
                quat_angle_deg(k->clip.rot[(size_t)f0 * jn + j], k->clip.rot[(size_t)g1 * jn + j]) /
                (f1 - f0);
            best = v > best ? v : best;
        }
    }
    return best;
}

static const char HAND_WRITTEN[] = "# a test clip: arms, a head nod, a hop\n"
                                   "clip test kind=dance fps=30\n"
                                   "key 0    LeftArm z=-80 y=-40   RightArm z=80\n"
                                   "key 0.5  LeftArm z=-20\n"
                                   "         root=0,50,0   # the hop's top\n"
                                   "key 1.0  LeftArm z=-80 y=10   Head x=15\n";

static void test_keys_are_hit_and_held(void **state)
{
    (void)state;
    cub_keys_clip *k = malloc(sizeof(*k));
    cub_diag d = {0};
    cub_err err =
        cub_keys_parse(HAND_WRITTEN, strlen(HAND_WRITTEN), "test.keys", &bear->skel, k, &d);
    if (err) fail_msg("%s:%d: %s", d.file, d.line, d.msg);
    assert_string_equal(k->name, "test");
    assert_string_equal(k->kind, "dance");
    assert_int_equal(k->loop, 0);
    assert_int_equal(k->clip.frame_count, 31);
    assert_int_equal(k->clip.frame_ns, 33333333);
    assert_int_equal(k->key_count, 3);
    assert_int_equal(k->key_frame[1], 15);
    assert_int_equal(k->key_line[1], 4);
    /* The key poses, exactly (axes not written are 0; joints not written hold). */
    expect_rot(k, 0, "LeftArm", 0, -40, -80);
    expect_rot(k, 0, "RightArm", 0, 0, 80);
    expect_rot(k, 0, "Head", 0, 0, 0);
    expect_rot(k, 15, "LeftArm", 0, 0, -20);
    expect_rot(k, 15, "RightArm", 0, 0, 80);
    expect_rot(k, 30, "LeftArm", 0, 10, -80);
    expect_rot(k, 30, "Head", 15, 0, 0);
    expect_rot(k, 30, "RightArm", 0, 0, 80);
    for (int f = 0; f < 31; f++) /* never written: rest, exactly */
        expect_rot(k, f, "LeftUpLeg", 0, 0, 0);
    cub_vec3 rest = bear->skel.joints[0].offset_mm;
    assert_int_equal(k->clip.root_mm[0].y, rest.y);
    assert_int_equal(k->clip.root_mm[15].y, rest.y + 50 * 65536);
    assert_int_equal(k->clip.root_mm[30].y, rest.y + 50 * 65536);
    /* Between keys: inside the key range here (no overshoot for a
     * monotonic run), and smooth. */
    for (int f = 1; f < 15; f++) {
        int32_t y = k->clip.root_mm[f].y;
        assert_true(y > rest.y && y < rest.y + 50 * 65536);
        assert_true(y > k->clip.root_mm[f - 1].y);
    }
    double step, kink;
    steps(k, 0, &step, &kink);
    printf("keys: test.keys %d frames, keys at frames 0 15 30 hit exactly; max step %.2f "
           "deg/frame, max step change %.2f deg/frame\n",
           k->clip.frame_count, step, kink);
    /* No faster than an ease through the keys, and no jerks: a jump in
     * speed at a key (as linear interpolation gives) would be about a whole
     * step. */
    assert_true(step <= 1.5 * fastest_key_speed(k) + 0.05);
    assert_true(kink < 0.5 * step);
    /* It eases out of the first key and into the last. */
    int la = cub_motion_skeleton_find(&bear->skel, "LeftArm"), jn = bear->skel.joint_count;
    assert_true(quat_angle_deg(k->clip.rot[la], k->clip.rot[jn + la]) < 0.2 * step);
    assert_true(quat_angle_deg(k->clip.rot[29 * jn + la], k->clip.rot[30 * jn + la]) < 0.2 * step);
    cub_keys_free(k);
    assert_null(k->mem);
    free(k);
}

static void test_loops_close_smoothly(void **state)
{
    (void)state;
    const char *src = getenv("CUB_SOURCE_DIR");
    char path[512];
    snprintf(path, sizeof(path), "%s/assets/keys/example_wave.keys", src ? src : "..");
    cub_keys_clip *k = malloc(sizeof(*k));
    cub_diag d = {0};
    cub_err err = cub_keys_load(path, &bear->skel, k, &d);
    if (err) fail_msg("%s:%d: %s", d.file, d.line, d.msg);
    assert_int_equal(k->loop, 1);
    assert_int_equal(k->clip.frame_count, 36); /* 0.9 + 0.3 s at 30 fps */
    expect_rot(k, 0, "RightForeArm", 0, 0, -20);
    expect_rot(k, 9, "RightForeArm", 0, 0, -65);
    expect_rot(k, 27, "Spine", 0, 0, 2);
    expect_rot(k, 27, "RightArm", 0, -15, -70);
    double step, kink;
    steps(k, 1, &step, &kink); /* including last frame -> first */
    printf("keys: example_wave.keys %d frames, loop; max step %.2f deg/frame, max step change "
           "%.2f deg/frame across the wrap too\n",
           k->clip.frame_count, step, kink);
    assert_true(step <= 1.5 * fastest_key_speed(k) + 0.05);
    assert_true(kink < 0.5 * step);
    cub_keys_free(k);

    /* loop T with one key: a still pose for T seconds. */
    const char *still = "clip still fps=10\nkey 0 Head x=10\nloop 2\n";
    assert_int_equal(cub_keys_parse(still, strlen(still), "s", &bear->skel, k, &d), CUB_OK);
    assert_int_equal(k->clip.frame_count, 20);
    assert_string_equal(k->kind, "coach");
    expect_rot(k, 13, "Head", 10, 0, 0);
    cub_keys_free(k);
    free(k);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_errors_name_the_line),
        cmocka_unit_test(test_keys_are_hit_and_held),
        cmocka_unit_test(test_loops_close_smoothly),
    };
    return cmocka_run_group_tests(tests, load_bear, free_bear);
}

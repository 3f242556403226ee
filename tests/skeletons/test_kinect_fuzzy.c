/* test_kinect_fuzzy — the fuzzy features on real Kinect v1 skeletons
 * (UTKinect-Action3D, MSR Action3D under $CUB_DATA_DIR/skeletons): the
 * labelled actions must read as the postures they name, by a clear margin,
 * and the figures of how much the Kinect's leg-joint noise moves the leg
 * features are printed.
 *
 * Rate = the share of an action's frames whose crisp set (the argmax, as
 * cub_fuzzy_crisp_class picks it) is the named one; "elbow true" and "knee
 * true" and "leg outward" count a frame when either side is. Floor and standing CoG per
 * sequence: see kinect_body_for (UTKinect stands on its walk interval).
 * Under CUB_QUICK (qemu) every third MSR file is read. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cub/fuzzy.h"
#include "kinect_read.h"


static int quick(void)
{
    return getenv("CUB_QUICK") != NULL;
}

/* ---- tallies ------------------------------------------------------------ */

enum { M_SIT, M_TRUNK, M_ELBOW, M_KNEE, M_LEG_OUT, M_COUNT };
static const char *const measure_name[M_COUNT] = {"posture=sit", "trunk=true", "elbow=true",
                                                  "knee=true", "leg=outward"};

/* Per action: frame count, hits per measure, and the leg-noise sums. */
typedef struct tally {
    long frames, hit[M_COUNT];
    double knee_step, abd_step; /* sums of |frame-to-frame change|, both sides */
    long steps;
    double knee_var, abd_var; /* sums of per-interval variances, both sides */
    long intervals;
} tally;

static int get(uint32_t cls, cub_fuzzy_feature f)
{
    return (int)(cls >> (2 * f) & 3);
}

static void count_frame(tally *t, const cub_fuzzy_frame *f)
{
    uint32_t c = cub_fuzzy_crisp_class(f);
    t->frames++;
    t->hit[M_SIT] += get(c, CUB_FUZZY_POSTURE) == 1;
    t->hit[M_TRUNK] += get(c, CUB_FUZZY_TRUNK) == 0;
    t->hit[M_ELBOW] += get(c, CUB_FUZZY_RHE) == 1 || get(c, CUB_FUZZY_LHE) == 1;
    t->hit[M_KNEE] += get(c, CUB_FUZZY_RFK) == 0 || get(c, CUB_FUZZY_LFK) == 0;
    t->hit[M_LEG_OUT] += get(c, CUB_FUZZY_RF) == 1 || get(c, CUB_FUZZY_LF) == 1;
}

static double deg(cub_q16 v)
{
    return v / 65536.0;
}

static double variance(const double *v, int n)
{
    double m = 0, s = 0;
    for (int i = 0; i < n; i++)
        m += v[i];
    m /= n;
    for (int i = 0; i < n; i++)
        s += (v[i] - m) * (v[i] - m);
    return s / n;
}

/* Features of frames [from, to) of s into t, with the leg-noise figures. */
static void tally_span(tally *t, const kinect_seq *s, const cub_fuzzy_body *body, int from, int to)
{
    int n = to - from;
    if (n < 2) return;
    double *leg = malloc(4 * (size_t)n * sizeof *leg); /* RFK, LFK, RF, LF */
    assert_non_null(leg);
    const cub_fuzzy_feature legs[4] = {CUB_FUZZY_RFK, CUB_FUZZY_LFK, CUB_FUZZY_RF, CUB_FUZZY_LF};
    for (int i = 0; i < n; i++) {
        cub_fuzzy_frame f;
        assert_int_equal(cub_fuzzy_features(body, s->joint[from + i], CUB_KJ_COUNT, &f),
                         CUB_OK);
        count_frame(t, &f);
        for (int k = 0; k < 4; k++)
            leg[k * n + i] = deg(f.input[legs[k]]);
    }
    for (int i = 1; i < n; i++) {
        t->knee_step += fabs(leg[i] - leg[i - 1]) + fabs(leg[n + i] - leg[n + i - 1]);
        t->abd_step +=
            fabs(leg[2 * n + i] - leg[2 * n + i - 1]) + fabs(leg[3 * n + i] - leg[3 * n + i - 1]);
        t->steps += 2;
    }
    t->knee_var += variance(leg, n) + variance(leg + n, n);
    t->abd_var += variance(leg + 2 * n, n) + variance(leg + 3 * n, n);
    t->intervals += 2;
    free(leg);
}

static double rate(const tally *t, int m)
{
    return t->frames ? (double)t->hit[m] / t->frames : 0;
}

static void print_tally(const char *set, const char *action, const tally *t)
{
    printf("kinect: %s %s frames=%ld", set, action, t->frames);
    for (int m = 0; m < M_COUNT; m++)
        printf(" %s=%.2f", measure_name[m], rate(t, m));
    printf("\n");
}

/* a clearly above b: at least twice, and at least 0.15 more. */
static void assert_clearly_above(const char *what, double a, double b)
{
    printf("kinect: %s %.2f vs %.2f\n", what, a, b);
    if (!(a >= 2 * b && a >= b + 0.15)) fail_msg("%s: %.2f is not clearly above %.2f", what, a, b);
}

static void print_noise(const char *what, const tally *t, int fps)
{
    printf("kinect: leg noise %s (%d fps, legs still) knee_step=%.2f knee_sd=%.2f "
           "abd_step=%.2f abd_sd=%.2f deg, knee=true %.2f leg=outward %.2f of %ld frames\n",
           what, fps, t->knee_step / t->steps, sqrt(t->knee_var / t->intervals),
           t->abd_step / t->steps, sqrt(t->abd_var / t->intervals), rate(t, M_KNEE),
           rate(t, M_LEG_OUT), t->frames);
}

/* ---- UTKinect ----------------------------------------------------------- */

#define UTK_ACTIONS 10
static const char *const utk_action[UTK_ACTIONS] = {"walk",      "sitDown",  "standUp", "pickUp",
                                                    "carry",     "throw",    "push",    "pull",
                                                    "waveHands", "clapHands"};

/* Index of the first frame with frame_no >= n. */
static int frame_index(const kinect_seq *s, int n)
{
    int i = 0;
    while (i < s->count && s->frame_no[i] < n)
        i++;
    return i;
}

static void test_utkinect_postures(void **state)
{
    (void)state;
    char dir[1024], path[2048], err[2600];
    if (!kinect_data_dir("utkinect", dir, sizeof dir)) {
        printf("kinect: no $CUB_DATA_DIR/skeletons/utkinect, skipping\n");
        skip();
    }
    utk_interval iv[200];
    snprintf(path, sizeof path, "%s/actionLabel.txt", dir);
    int n = kinect_read_utk_labels(path, iv, 200, err, sizeof err);
    if (n < 0) fail_msg("%s", err);
    tally t[UTK_ACTIONS] = {{0}}, still = {0};
    for (int i = 0; i < n; i++) {
        if (i > 0 && strcmp(iv[i].run, iv[i - 1].run) == 0) continue;
        kinect_seq s;
        snprintf(path, sizeof path, "%.1023s/joints_%.15s.txt", dir, iv[i].run);
        if (kinect_read_utkinect(path, &s, err, sizeof err)) fail_msg("%s", err);
        int walk = -1;
        for (int j = i; j < n && strcmp(iv[j].run, iv[i].run) == 0; j++)
            if (strcmp(iv[j].action, "walk") == 0) walk = j;
        assert_true(walk >= 0);
        cub_fuzzy_body body = kinect_body_for(&s, frame_index(&s, iv[walk].first),
                                              frame_index(&s, iv[walk].last + 1));
        for (int j = i; j < n && strcmp(iv[j].run, iv[i].run) == 0; j++) {
            int a = 0;
            while (a < UTK_ACTIONS && strcmp(utk_action[a], iv[j].action) != 0)
                a++;
            assert_true(a < UTK_ACTIONS);
            int from = frame_index(&s, iv[j].first), to = frame_index(&s, iv[j].last + 1);
            tally_span(&t[a], &s, &body, from, to);
            if (a >= 8) tally_span(&still, &s, &body, from, to); /* wave, clap */
        }
        kinect_free(&s);
    }
    for (int a = 0; a < UTK_ACTIONS; a++)
        print_tally("utkinect", utk_action[a], &t[a]);
    assert_clearly_above("utkinect sitDown posture=sit vs walk", rate(&t[1], M_SIT),
                         rate(&t[0], M_SIT));
    assert_clearly_above("utkinect pickUp trunk=true vs walk", rate(&t[3], M_TRUNK),
                         rate(&t[0], M_TRUNK));
    print_noise("utkinect waveHands+clapHands", &still, 30);
}

/* ---- MSR Action3D ------------------------------------------------------- */

#define MSR_ACTIONS 20

static void test_msr_postures(void **state)
{
    (void)state;
    char dir[1024], path[2048], err[2600];
    if (!kinect_data_dir("msr-action3d", dir, sizeof dir)) {
        printf("kinect: no $CUB_DATA_DIR/skeletons/msr-action3d, skipping\n");
        skip();
    }
    static tally t[MSR_ACTIONS + 1];
    tally still = {0};
    memset(t, 0, sizeof t);
    double wrist_motion[2] = {0, 0}; /* a01: left, right */
    int files = 0, step = quick() ? 3 : 1, k = 0;
    for (int a = 1; a <= MSR_ACTIONS; a++)
        for (int subj = 1; subj <= 10; subj++)
            for (int e = 1; e <= 3; e++) {
                snprintf(path, sizeof path, "%s/a%02d_s%02d_e%02d_skeleton3D.txt", dir, a, subj, e);
                struct stat st;
                if (stat(path, &st) != 0 || k++ % step) continue;
                kinect_seq s;
                if (kinect_read_msr(path, &s, err, sizeof err)) {
                    printf("kinect: skipped %s\n", err + strlen(dir) + 1);
                    continue;
                }
                cub_fuzzy_body body = kinect_body_for(&s, -1, 0);
                tally_span(&t[a], &s, &body, 0, s.count);
                if (a <= 12) tally_span(&still, &s, &body, 0, s.count); /* arm-only */
                for (int i = 1; a == 1 && i < s.count; i++)
                    for (int side = 0; side < 2; side++) {
                        int w = side ? CUB_KJ_WRIST_R : CUB_KJ_WRIST_L;
                        wrist_motion[side] += fabs(deg(s.joint[i][w].y - s.joint[i - 1][w].y));
                    }
                kinect_free(&s);
                files++;
            }
    if (files == 0) {
        printf("kinect: no MSR Action3D skeleton files in %s, skipping\n", dir);
        skip();
    }
    char name[8];
    for (int a = 1; a <= MSR_ACTIONS; a++) {
        snprintf(name, sizeof name, "a%02d", a);
        print_tally("msr", name, &t[a]);
    }
    printf("kinect: msr a01 high arm wave wrist travel left=%.0f right=%.0f mm (%d files)\n",
           wrist_motion[0], wrist_motion[1], files);
    assert_true(wrist_motion[1] > 2 * wrist_motion[0]); /* the right arm waves */
    assert_clearly_above("msr a13 bend trunk=true vs a01 high wave", rate(&t[13], M_TRUNK),
                         rate(&t[1], M_TRUNK));
    assert_clearly_above("msr a13 bend trunk=true vs a02 horizontal wave", rate(&t[13], M_TRUNK),
                         rate(&t[2], M_TRUNK));
    assert_clearly_above("msr a12 side boxing elbow=true vs a11 two hand wave",
                         rate(&t[12], M_ELBOW), rate(&t[11], M_ELBOW));
    print_noise("msr a01-a12", &still, 15);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_utkinect_postures),
        cmocka_unit_test(test_msr_postures),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

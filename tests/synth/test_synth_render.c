#define _DEFAULT_SOURCE /* mkdtemp, mkstemps */
/* The depth synthesizer on real CMU clips (skipped without
 * $CUB_DATA_DIR): the dump reads back as fakenect expects it, the raw
 * values and their quantisation follow the Kinect formula, the projector's
 * shadow falls on the -x side, the truth joints sit on the body, the body
 * has the height asked for, and the noise follows the seed. Figures go to
 * stdout. Under CUB_QUICK (qemu) fewer frames. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#include "cub/kinect.h"
#include "cub/synth.h"
#include "synth_data.h"

#define W CUB_KINECT_WIDTH
#define H CUB_KINECT_HEIGHT
#define NPIX (W * H)

static const char *data_dir(void)
{
    return synth_data_dir("13_29");
}

#define NEED_DATA() SYNTH_NEED_DATA("13_29")

static cub_synth *open_clip(cub_synth_desc d, const char *clip, double from_s, double to_s,
                            int mirror)
{
    cub_synth_segment seg = {.from_s = from_s, .to_s = to_s, .mirror = mirror};
    snprintf(seg.clip, sizeof(seg.clip), "%s", clip);
    d.data_dir = data_dir();
    cub_synth *s = NULL;
    cub_diag diag;
    char buf[600];
    cub_err err = cub_synth_open(&d, &seg, 1, &s, &diag);
    if (err) printf("synth: %s\n", cub_diag_str(&diag, buf, sizeof(buf)));
    assert_int_equal(err, CUB_OK);
    return s;
}

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

static unsigned char *read_all(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    unsigned char *b = malloc(1 << 20);
    *len = fread(b, 1, 1 << 20, f);
    fclose(f);
    return b;
}

/* An a- line: the frame's own name (stamp), 12 bytes of
 * freenect_raw_tilt_state, little-endian counts of the push opposite to
 * gravity (819 a g), motor angle and status 0. */
static void check_accel_file(const char *dir, const char *name, const char *frame_stamp,
                             const float gravity[3])
{
    char path[700];
    assert_true(frame_stamp[0]);
    snprintf(path, sizeof(path), "a-%s.dump", frame_stamp);
    assert_string_equal(name, path);
    snprintf(path, sizeof(path), "%s/%s", dir, name);
    size_t len;
    unsigned char *b = read_all(path, &len);
    assert_non_null(b);
    assert_int_equal(len, 12);
    for (int i = 0; i < 3; i++) {
        int counts = (int16_t)(b[2 * i] | b[2 * i + 1] << 8);
        assert_int_equal(counts, (int)lround(-gravity[i] * CUB_KINECT_ACCEL_COUNTS_PER_G / 1000.0));
    }
    for (int i = 6; i < 12; i++) assert_int_equal(b[i], 0);
    free(b);
    unlink(path);
}

static void test_dump_reads_back(void **state)
{
    (void)state;
    NEED_DATA();
    int frames = synth_quick() ? 4 : 20;
    cub_synth *s = open_clip((cub_synth_desc){.seed = 5}, "13_29", 0, 2, 0);
    char dir[] = "/tmp/cub_synth_test_XXXXXX";
    assert_non_null(mkdtemp(dir));
    cub_diag diag;
    double t0 = now_ms();
    assert_int_equal(cub_synth_write_dump(s, dir, frames, 0, &diag), CUB_OK);
    printf("synth: render+write %.1f ms/frame (13_29, %d frames, this build)\n",
           (now_ms() - t0) / frames, frames);
    cub_synth_close(s);

    char path[700], line[200];
    snprintf(path, sizeof(path), "%s/truth.txt", dir);
    cub_synth_truth truth;
    assert_int_equal(cub_synth_truth_read(path, &truth, &diag), CUB_OK);
    assert_int_equal(truth.frame_count, frames);
    assert_true(truth.gravity[1] < -999.0f);
    snprintf(path, sizeof(path), "%s/INDEX.txt", dir);
    FILE *index = fopen(path, "r");
    assert_non_null(index);
    int n = 0;
    double prev_t = 0;
    unsigned prev_ts = 0;
    char last_stamp[64] = "";
    while (fgets(line, sizeof(line), index)) {
        double t;
        unsigned ts;
        char tail[8];
        line[strcspn(line, "\n")] = 0;
        if (line[0] == 'a') { /* after each frame, as fakenect-record writes */
            check_accel_file(dir, line, last_stamp, truth.gravity);
            last_stamp[0] = 0;
            continue;
        }
        assert_int_equal(last_stamp[0], 0); /* the frame before had its a- line */
        snprintf(last_stamp, sizeof last_stamp, "%.*s", (int)strlen(line) - 6, line + 2);
        assert_int_equal(sscanf(line, "d-%lf-%u.%3s", &t, &ts, tail), 3);
        assert_string_equal(tail, "pgm");
        assert_true(n < frames);
        if (n > 0) { /* 30 fps, in order */
            assert_true(fabs(t - prev_t - 1.0 / 30) < 2e-6);
            assert_true(ts > prev_ts);
        }
        assert_true(fabs(truth.frames[n].t_s - t) < 1e-6);
        assert_int_equal(truth.frames[n].ts, ts);
        assert_int_equal(truth.frames[n].frame, n);
        snprintf(path, sizeof(path), "%s/%s", dir, line);
        size_t len;
        unsigned char *b = read_all(path, &len);
        assert_non_null(b);
        /* exactly like the real skeltrack dump: header, then LE uint16 */
        assert_int_equal(len, 17 + NPIX * 2);
        assert_memory_equal(b, "P5 640 480 65535\n", 17);
        int valid = 0;
        for (int i = 0; i < NPIX; i++) {
            unsigned r = b[17 + 2 * i] | (unsigned)b[18 + 2 * i] << 8;
            assert_true(r <= 2047);
            if (r < 2047) {
                double mm = cub_synth_raw_to_mm((uint16_t)r);
                assert_true(mm >= 499.0 && mm <= 4001.0);
                valid++;
            }
        }
        assert_true(valid > 10000); /* the child and the floor */
        free(b);
        unlink(path);
        prev_t = t, prev_ts = ts, n++;
    }
    fclose(index);
    assert_int_equal(last_stamp[0], 0);
    assert_int_equal(n, frames);
    cub_synth_truth_free(&truth);
    snprintf(path, sizeof(path), "%s/INDEX.txt", dir);
    unlink(path);
    snprintf(path, sizeof(path), "%s/truth.txt", dir);
    unlink(path);
    rmdir(dir);
}

/* Mean gap between the distinct depths the floor shows near depth_mm. */
static double floor_step(const uint16_t *raw, double depth_mm)
{
    static unsigned char seen[2048];
    memset(seen, 0, sizeof(seen));
    for (int i = 0; i < NPIX; i++)
        if (raw[i] < 2047) seen[raw[i]] = 1;
    double lo = 0, hi = 0;
    int levels = 0;
    for (int r = 0; r < 2047; r++) {
        double mm = cub_synth_raw_to_mm((uint16_t)r);
        if (!seen[r] || fabs(mm - depth_mm) > depth_mm * 0.05) continue;
        lo = levels ? lo : mm;
        hi = mm;
        levels++;
    }
    return levels > 2 ? (hi - lo) / (levels - 1) : -1;
}

static void test_quantisation_step_grows_with_distance(void **state)
{
    (void)state;
    /* An empty room seen from a camera tilted down: the floor runs from
     * about 0.6 m to 3.5 m, every raw level shows. */
    cub_synth_desc d = {.tilt_deg = -35, .clean = 1};
    cub_synth *s = NULL;
    cub_diag diag;
    assert_int_equal(cub_synth_open(&d, NULL, 0, &s, &diag), CUB_OK);
    uint16_t *raw = malloc(NPIX * sizeof(*raw));
    assert_int_equal(cub_synth_render(s, 0, raw, NULL, NULL, NULL), CUB_OK);
    double s1 = floor_step(raw, 1000), s3 = floor_step(raw, 3000);
    /* d(mm)/d(raw) of mm = 123.6 tan(raw / 2842.5 + 1.1863) */
    double f1 = 123.6 / 2842.5 * (1 + pow(1000 / 123.6, 2));
    double f3 = 123.6 / 2842.5 * (1 + pow(3000 / 123.6, 2));
    printf("synth: quantisation step 1 m = %.2f mm (formula %.2f), 3 m = %.2f mm (formula %.2f)\n",
           s1, f1, s3, f3);
    assert_true(fabs(s1 - f1) < 0.1 * f1);
    assert_true(fabs(s3 - f3) < 0.1 * f3);
    float g[3];
    cub_synth_gravity(s, g);
    printf("synth: gravity at tilt -35 deg = (%.1f, %.1f, %.1f)\n", g[0], g[1], g[2]);
    assert_true(fabsf(g[1] + 819.2f) < 1 && fabsf(g[2] - 573.6f) < 1);
    free(raw);
    cub_synth_close(s);
}

static void test_shadow_lies_on_the_minus_x_side(void **state)
{
    (void)state;
    NEED_DATA();
    cub_synth *s = open_clip((cub_synth_desc){.room = 1, .seed = 2}, "13_29", 0, 1, 0);
    uint16_t *raw = malloc(NPIX * sizeof(*raw));
    float *z = malloc(NPIX * sizeof(*z));
    uint8_t *own = malloc(NPIX);
    assert_int_equal(cub_synth_render(s, 0, raw, NULL, z, own), CUB_OK);
    /* Per row: the band beside the body's outermost pixels, where the wall
     * (3.8 m; band about 8 px wide) is behind. */
    int left_dark = 0, left_all = 0, right_dark = 0, right_all = 0;
    for (int v = 0; v < H; v++) {
        int u0 = -1, u1 = -1;
        for (int u = 0; u < W; u++)
            if (own[v * W + u] == 1) {
                u0 = u0 < 0 ? u : u0;
                u1 = u;
            }
        if (u0 < 12 || u1 > W - 12) continue;
        for (int k = 2; k <= 6; k++) {
            int l = v * W + u0 - k, r = v * W + u1 + k;
            if (own[l] == 3 && z[l] > z[v * W + u0] + 1000) {
                left_all++;
                left_dark += raw[l] == 2047;
            }
            if (own[r] == 3 && z[r] > z[v * W + u1] + 1000) {
                right_all++;
                right_dark += raw[r] == 2047;
            }
        }
    }
    double lf = left_all ? (double)left_dark / left_all : 0;
    double rf = right_all ? (double)right_dark / right_all : 1;
    printf("synth: shadow beside the body: -x side %.2f of %d px no reading, +x side %.2f of %d\n",
           lf, left_all, rf, right_all);
    assert_true(left_all > 100 && right_all > 100);
    assert_true(lf > 0.8);
    assert_true(rf < 0.1);
    free(raw);
    free(z);
    free(own);
    cub_synth_close(s);
}

/* Any pixel in the 5x5 around (u, v) reading within tol of z. */
static int near_reading(const uint16_t *raw, int u, int v, float z, float tol)
{
    for (int dv = -2; dv <= 2; dv++)
        for (int du = -2; du <= 2; du++) {
            int x = u + du, y = v + dv;
            if (x < 0 || y < 0 || x >= W || y >= H || raw[y * W + x] >= 2047) continue;
            if (fabs(cub_synth_raw_to_mm(raw[y * W + x]) - z) < tol) return 1;
        }
    return 0;
}

static void test_visible_joints_sit_on_the_body(void **state)
{
    (void)state;
    NEED_DATA();
    const char *clips[] = {"13_29", "141_16", "05_06"};
    int seen = 0, on_body = 0, hidden = 0;
    for (int c = 0; c < 3; c++) {
        cub_synth *s = open_clip((cub_synth_desc){.seed = 9, .room = c == 2}, clips[c], 2, 0, 0);
        uint16_t *raw = malloc(NPIX * sizeof(*raw));
        int step = synth_quick() ? 60 : 10;
        for (int f = 0; f < cub_synth_frame_count(s) && f < 240; f += step) {
            cub_synth_truth_frame t;
            assert_int_equal(cub_synth_render(s, f, raw, &t, NULL, NULL), CUB_OK);
            for (int j = 0; j < CUB_KJ_COUNT; j++) {
                if (!t.visible[j]) {
                    hidden++;
                    continue;
                }
                float *p = t.joint_mm[j];
                int u = (int)lroundf(CUB_KINECT_CX + CUB_KINECT_FOCAL_PX * p[0] / p[2]),
                    v = (int)lroundf(CUB_KINECT_CY - CUB_KINECT_FOCAL_PX * p[1] / p[2]);
                seen++;
                on_body += near_reading(raw, u, v, p[2], 150);
            }
        }
        free(raw);
        cub_synth_close(s);
    }
    printf("synth: visible joints on body pixels within 15 cm: %d of %d (%d hidden)\n", on_body,
           seen, hidden);
    assert_true(seen > 100);
    assert_true(on_body >= seen * 0.99);
}

/* The child's height as the image shows it: the top of the body at its
 * depth, above the floor (camera level at 800 mm). */
static double image_height(cub_synth *s)
{
    uint16_t *raw = malloc(NPIX * sizeof(*raw));
    float *z = malloc(NPIX * sizeof(*z));
    uint8_t *own = malloc(NPIX);
    assert_int_equal(cub_synth_render(s, 0, raw, NULL, z, own), CUB_OK);
    double top = -1e9;
    for (int i = 0; i < NPIX; i++)
        if (own[i] == 1 && raw[i] < 2047) {
            double y = (CUB_KINECT_CY - i / W) * cub_synth_raw_to_mm(raw[i]) / CUB_KINECT_FOCAL_PX + 800.0;
            top = y > top ? y : top;
        }
    free(raw);
    free(z);
    free(own);
    return top;
}

static void test_height_in_image_matches(void **state)
{
    (void)state;
    NEED_DATA();
    const float heights[] = {1000, 1150, 1400};
    double worst = 0;
    for (int i = 0; i < 3; i++) {
        /* 13_29 starts in a T pose: standing straight */
        cub_synth *s =
            open_clip((cub_synth_desc){.height_mm = heights[i], .clean = 1}, "13_29", 0, 1, 0);
        double h = image_height(s);
        printf("synth: height %.0f mm -> %.0f mm in the image (%.1f %%)\n", heights[i], h,
               100 * (h - heights[i]) / heights[i]);
        worst = fmax(worst, fabs(h - heights[i]) / heights[i]);
        cub_synth_close(s);
    }
    assert_true(worst < 0.03);
}

static void test_same_seed_same_bytes(void **state)
{
    (void)state;
    NEED_DATA();
    uint16_t *a = malloc(NPIX * 2), *b = malloc(NPIX * 2), *c = malloc(NPIX * 2);
    float *za = malloc(NPIX * sizeof(float)), *zc = malloc(NPIX * sizeof(float));
    cub_synth *s1 = open_clip((cub_synth_desc){.seed = 7}, "13_29", 3, 4, 0);
    cub_synth *s2 = open_clip((cub_synth_desc){.seed = 7}, "13_29", 3, 4, 0);
    cub_synth *s3 = open_clip((cub_synth_desc){.seed = 8}, "13_29", 3, 4, 0);
    assert_int_equal(cub_synth_render(s1, 5, a, NULL, za, NULL), CUB_OK);
    assert_int_equal(cub_synth_render(s2, 5, b, NULL, NULL, NULL), CUB_OK);
    assert_int_equal(cub_synth_render(s3, 5, c, NULL, zc, NULL), CUB_OK);
    assert_memory_equal(a, b, NPIX * 2);
    assert_memory_equal(za, zc, NPIX * sizeof(float)); /* the same scene */
    int differ = 0;
    for (int i = 0; i < NPIX; i++)
        differ += a[i] != c[i];
    printf("synth: seeds 7 and 8 differ in %d pixels (noise only)\n", differ);
    assert_true(differ > 500);
    /* frames differ in noise too, not only in pose */
    assert_int_equal(cub_synth_render(s1, 6, b, NULL, NULL, NULL), CUB_OK);
    assert_memory_not_equal(a, b, NPIX * 2);
    cub_synth_close(s1);
    cub_synth_close(s2);
    cub_synth_close(s3);
    free(a), free(b), free(c), free(za), free(zc);
}

static void test_mirror_swaps_left_and_right(void **state)
{
    (void)state;
    NEED_DATA();
    cub_synth *s = open_clip((cub_synth_desc){.clean = 1}, "141_16", 2, 3, 0);
    cub_synth *m = open_clip((cub_synth_desc){.clean = 1}, "141_16", 2, 3, 1);
    uint16_t *raw = malloc(NPIX * 2);
    cub_synth_truth_frame a, b;
    assert_int_equal(cub_synth_render(s, 10, raw, &a, NULL, NULL), CUB_OK);
    assert_int_equal(cub_synth_render(m, 10, raw, &b, NULL, NULL), CUB_OK);
    for (int k = 0; k < 4; k++) {
        float *l = a.joint_mm[CUB_KJ_SHOULDER_L + k], *r = b.joint_mm[CUB_KJ_SHOULDER_R + k];
        assert_true(fabsf(l[0] + r[0]) < 1.0f && fabsf(l[1] - r[1]) < 1.0f);
    }
    /* facing the camera: the player's left shows on the image's left */
    assert_true(a.joint_mm[CUB_KJ_SHOULDER_L][0] < a.joint_mm[CUB_KJ_SHOULDER_R][0]);
    free(raw);
    cub_synth_close(s);
    cub_synth_close(m);
}

/* Every skeleton family loads, stands upright and faces the camera. */
static void test_families_stand_and_face_the_camera(void **state)
{
    (void)state;
    NEED_DATA();
    const char *clips[] = {"13_29",         "13_17",       "dab",
                           "jumping_jacks", "jesse_dance", "dataset-1_bye_childish_001",
                           "07_01"};
    uint16_t *raw = malloc(NPIX * 2);
    for (int c = 0; c < 7; c++) {
        cub_synth *s = open_clip((cub_synth_desc){.clean = 1}, clips[c], 0, 0, 0);
        cub_synth_truth_frame t;
        assert_int_equal(cub_synth_render(s, 0, raw, &t, NULL, NULL), CUB_OK);
        float(*p)[3] = t.joint_mm;
        printf("synth: %-28s head y %.0f, hips y %.0f, ankles y %.0f, shoulders x %.0f..%.0f\n",
               clips[c], p[CUB_KJ_HEAD][1], p[CUB_KJ_HIP_CENTRE][1], p[CUB_KJ_ANKLE_L][1],
               p[CUB_KJ_SHOULDER_L][0], p[CUB_KJ_SHOULDER_R][0]);
        assert_true(p[CUB_KJ_HEAD][1] > p[CUB_KJ_SHOULDER_CENTRE][1]);
        assert_true(p[CUB_KJ_SHOULDER_CENTRE][1] > p[CUB_KJ_HIP_CENTRE][1]);
        assert_true(p[CUB_KJ_HIP_CENTRE][1] > p[CUB_KJ_KNEE_L][1]);
        assert_true(p[CUB_KJ_KNEE_R][1] > p[CUB_KJ_ANKLE_R][1]);
        assert_true(p[CUB_KJ_SHOULDER_L][0] < p[CUB_KJ_SHOULDER_R][0]);
        cub_synth_close(s);
    }
    free(raw);
}

static void test_missing_joint_names_clip_and_joint(void **state)
{
    (void)state;
    /* A CMU-looking skeleton without toes. */
    char path[] = "/tmp/cub_synth_bad_XXXXXX.bvh";
    int fd = mkstemps(path, 4);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    fprintf(f, "HIERARCHY\nROOT Hips\n{\nOFFSET 0 0 0\nCHANNELS 6 Xposition Yposition Zposition "
               "Zrotation Yrotation Xrotation\nJOINT LHipJoint\n{\nOFFSET 1 0 0\nCHANNELS 3 "
               "Zrotation Yrotation Xrotation\nEnd Site\n{\nOFFSET 0 -1 0\n}\n}\n}\nMOTION\n"
               "Frames: 1\nFrame Time: 0.0083333\n0 0 0 0 0 0 0 0 0\n");
    fclose(f);
    cub_synth_desc d = {0};
    cub_synth_segment seg = {0};
    snprintf(seg.clip, sizeof(seg.clip), "%s", path);
    cub_synth *s = NULL;
    cub_diag diag;
    char buf[600];
    assert_int_equal(cub_synth_open(&d, &seg, 1, &s, &diag), CUB_ERR_FORMAT);
    printf("synth: as expected: %s\n", cub_diag_str(&diag, buf, sizeof(buf)));
    assert_non_null(strstr(buf, path));
    assert_non_null(strstr(buf, "'Spine'"));
    assert_non_null(strstr(buf, "spine"));
    unlink(path);
    snprintf(seg.clip, sizeof(seg.clip), "no_such_clip_42");
    assert_int_not_equal(cub_synth_open(&d, &seg, 1, &s, &diag), CUB_OK);
    assert_non_null(strstr(diag.msg, "no such clip"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_missing_joint_names_clip_and_joint),
        cmocka_unit_test(test_quantisation_step_grows_with_distance),
        cmocka_unit_test(test_dump_reads_back),
        cmocka_unit_test(test_shadow_lies_on_the_minus_x_side),
        cmocka_unit_test(test_visible_joints_sit_on_the_body),
        cmocka_unit_test(test_height_in_image_matches),
        cmocka_unit_test(test_same_seed_same_bytes),
        cmocka_unit_test(test_mirror_swaps_left_and_right),
        cmocka_unit_test(test_families_stand_and_face_the_camera),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

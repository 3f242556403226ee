/* test_fuzzy_mocap — the fixed-point fuzzy features against the double
 * reference (tests/support/fuzzy_ref.c) on every frame of every BVH under
 * $CUB_DATA_DIR/mocap/cmu, and on every frame of the clip library the box
 * ships (assets/clips/bear.cubclips): every membership and d within 1e-3.
 * (It lives here, not in tests/unit, because it links the BVH reader.)
 * Under CUB_QUICK (qemu) every 20th frame. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
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

#include "cub/character.h"
#include "cub/fuzzy.h"
#include "cub/io.h"
#include "cub/pack.h"
#include "fuzzy_pose.h"
#include "fuzzy_ref.h"

/* Each role's joint name in the three namings found under mocap/cmu:
 * cgspeed (13_29), the older CMU BVH (14_14: its "LeftShoulder" is the
 * shoulder, so it is tried after cgspeed's "LeftArm", whose "LeftShoulder"
 * is the clavicle) and DAZ (daz43). */
static const char *const role_names[][4] = {
    {"Hips", "hip", NULL},                       /* hip centre */
    {"Spine", "Chest", "abdomen", NULL},         /* spine */
    {"Neck", "lowerneck", "neck", NULL},         /* shoulder centre */
    {"Head", "head", NULL},                      /* head */
    {"LeftArm", "LeftShoulder", "lShldr", NULL}, /* shoulders L, R */
    {"RightArm", "RightShoulder", "rShldr", NULL},
    {"LeftForeArm", "LeftElbow", "lForeArm", NULL}, /* elbows */
    {"RightForeArm", "RightElbow", "rForeArm", NULL},
    {"LeftHand", "LeftWrist", "lHand", NULL}, /* wrists */
    {"RightHand", "RightWrist", "rHand", NULL},
    {"LeftUpLeg", "LeftHip", "lThigh", NULL}, /* hips */
    {"RightUpLeg", "RightHip", "rThigh", NULL},
    {"LeftLeg", "LeftKnee", "lShin", NULL}, /* knees */
    {"RightLeg", "RightKnee", "rShin", NULL},
    {"LeftFoot", "LeftAnkle", "lFoot", NULL}, /* ankles */
    {"RightFoot", "RightAnkle", "rFoot", NULL},
};
#define ROLES (int)(sizeof role_names / sizeof role_names[0])

static int find_role(const cub_skeleton *sk, int role)
{
    for (int i = 0; i < 3 && role_names[role][i]; i++) {
        int j = cub_motion_skeleton_find(sk, role_names[role][i]);
        if (j >= 0) return j;
    }
    return -1;
}

/* The body of a skeleton, or 0 if a role is missing. */
static int map_body(const cub_skeleton *sk, cub_fuzzy_body *b)
{
    int j[ROLES];
    for (int r = 0; r < ROLES; r++)
        if ((j[r] = find_role(sk, r)) < 0) return 0;
    *b = (cub_fuzzy_body){.hip_centre = j[0], .spine = j[1], .shoulder_centre = j[2], .head = j[3]};
    for (int s = 0; s < 2; s++) {
        b->shoulder[s] = j[4 + s];
        b->elbow[s] = j[6 + s];
        b->wrist[s] = j[8 + s];
        b->hip[s] = j[10 + s];
        b->knee[s] = j[12 + s];
        b->ankle[s] = j[14 + s];
    }
    return 1;
}

typedef struct errors {
    double mu, d, input;
    long frames, pairs;
} errors;

static cub_vec3 world[CUB_MOTION_MAX_JOINTS];
static cub_pose pose;
static double xyz[3 * CUB_MOTION_MAX_JOINTS];

static void frame_world(const cub_io_motion *m, int f)
{
    assert_int_equal(cub_motion_clip_get_frame(&m->clip, f, &pose), CUB_OK);
    assert_int_equal(cub_motion_forward(&m->skel, &pose, world, NULL), CUB_OK);
}

/* Fixed against float on the pose in `world`; d against a reference frame
 * (*f0, *r0: taken from this pose when first is set), so pairs range from
 * near to far apart. */
static void compare_frame(const cub_fuzzy_body *body, int n, int first, cub_fuzzy_frame *f0,
                          cub_fuzzy_ref_frame *r0, errors *e)
{
    cub_fuzzy_ref_body rb = fz_ref_body(body);
    cub_fuzzy_frame f;
    cub_fuzzy_ref_frame r;
    fz_to_double(world, n, xyz);
    assert_int_equal(cub_fuzzy_features(body, world, n, &f), CUB_OK);
    assert_int_equal(cub_fuzzy_ref_features(&rb, xyz, n, &r), 0);
    for (int k = 0; k < CUB_FUZZY_FEATURE_COUNT; k++)
        e->input = fmax(e->input, fabs(f.input[k] / 65536.0 - r.input[k]));
    e->mu = fmax(e->mu, fz_max_mu_err(&f, &r));
    if (first) {
        *f0 = f;
        *r0 = r;
    }
    double d = cub_fuzzy_distance(&f, f0, NULL) / 65536.0;
    e->d = fmax(e->d, fabs(d - cub_fuzzy_ref_distance(&r, r0, NULL)));
    assert_true(d >= 0 && d <= 1);
    e->frames++;
    e->pairs++;
}

static void check_file(const char *path, int step, errors *e)
{
    cub_io_motion m;
    cub_diag diag;
    char msg[600];
    if (cub_io_load_bvh(path, NULL, &m, &diag))
        fail_msg("%s", cub_diag_str(&diag, msg, sizeof msg));
    cub_fuzzy_body body;
    if (!map_body(&m.skel, &body)) {
        printf("fuzzy: %s: no joint naming known, skipped\n", path);
        cub_io_motion_free(&m);
        return;
    }
    int n = m.skel.joint_count, frames = m.clip.frame_count;
    /* Floor: the lowest ankle over the clip; standing CoG: frame 0's (the
     * clips start standing). Only scales Posture: any positive value would
     * do to compare fixed against float. */
    cub_q16 floor = CUB_Q16_MAX;
    for (int f = 0; f < frames; f += step) {
        frame_world(&m, f);
        for (int s = 0; s < 2; s++)
            if (world[body.ankle[s]].y < floor) floor = world[body.ankle[s]].y;
    }
    body.floor_y_mm = floor;
    frame_world(&m, 0);
    body.stand_cog_mm = cub_fuzzy_cog_height_mm(&body, world, n);
    if (body.stand_cog_mm < fz_q16(100)) body.stand_cog_mm = fz_q16(900);
    cub_fuzzy_frame f0;
    cub_fuzzy_ref_frame r0;
    for (int i = 0; i < frames; i += step) {
        frame_world(&m, i);
        compare_frame(&body, n, i == 0, &f0, &r0, e);
    }
    cub_io_motion_free(&m);
}

/* Every .bvh under dir (one level of subfolders), sorted order not needed. */
static void walk(const char *dir, int step, errors *e, int *files)
{
    DIR *d = opendir(dir);
    if (!d) return;
    struct dirent *de;
    while ((de = readdir(d))) {
        if (de->d_name[0] == '.') continue;
        char path[2048];
        snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
        struct stat st;
        if (stat(path, &st) != 0) continue;
        size_t len = strlen(de->d_name);
        if (S_ISDIR(st.st_mode)) {
            walk(path, step, e, files);
        } else if (len > 4 && strcmp(de->d_name + len - 4, ".bvh") == 0) {
            check_file(path, step, e);
            (*files)++;
        }
    }
    closedir(d);
}

static void test_fixed_matches_float_on_cmu_mocap(void **state)
{
    (void)state;
    const char *data = getenv("CUB_DATA_DIR");
    char dir[1024];
    struct stat st;
    snprintf(dir, sizeof dir, "%s/mocap/cmu", data ? data : "");
    if (!data || stat(dir, &st) != 0) {
        printf("fuzzy: no $CUB_DATA_DIR/mocap/cmu, skipping\n");
        skip();
    }
    errors e = {0};
    int files = 0;
    walk(dir, getenv("CUB_QUICK") ? 20 : 1, &e, &files);
    printf("fuzzy: fixed vs float max_mu_err=%.2e max_d_err=%.2e max_input_err=%.2e deg "
           "over %ld frames of %d CMU BVH files\n",
           e.mu, e.d, e.input, e.frames, files);
    assert_true(e.frames > 0);
    assert_true(e.mu < 1e-3);
    assert_true(e.d < 1e-3);
}

/* The library the box ships, on the bear's own body: d against the first
 * frame of the whole library, so pairs also cross clips. */
static void test_fixed_matches_float_on_the_shipped_library(void **state)
{
    (void)state;
    const char *src = getenv("CUB_SOURCE_DIR");
    assert_non_null(src);
    char path[1024], msg[600];
    cub_diag diag;
    static cub_character bear;
    snprintf(path, sizeof path, "%s/assets/bear/bear.xml", src);
    if (cub_character_load(path, &bear, &diag)) fail_msg("%s", cub_diag_str(&diag, msg, sizeof msg));
    cub_library lib;
    snprintf(path, sizeof path, "%s/assets/clips/bear.cubclips", src);
    if (cub_pack_read(path, &lib, &diag)) fail_msg("%s", cub_diag_str(&diag, msg, sizeof msg));
    assert_int_equal(lib.skel.joint_count, bear.skel.joint_count);
    errors e = {0};
    cub_fuzzy_frame f0;
    cub_fuzzy_ref_frame r0;
    for (int c = 0; c < lib.clip_count; c++) {
        const cub_clip *clip = &lib.clips[c].clip;
        for (int i = 0; i < clip->frame_count; i++) {
            assert_int_equal(cub_motion_clip_get_frame(clip, i, &pose), CUB_OK);
            assert_int_equal(cub_motion_forward(&lib.skel, &pose, world, NULL), CUB_OK);
            compare_frame(&bear.body, lib.skel.joint_count, c == 0 && i == 0, &f0, &r0, &e);
        }
    }
    printf("fuzzy: fixed vs float max_mu_err=%.2e max_d_err=%.2e max_input_err=%.2e deg "
           "over all %ld frames of the %d library clips\n",
           e.mu, e.d, e.input, e.frames, lib.clip_count);
    cub_library_free(&lib);
    assert_true(e.frames > 0);
    assert_true(e.mu < 1e-3);
    assert_true(e.d < 1e-3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fixed_matches_float_on_cmu_mocap),
        cmocka_unit_test(test_fixed_matches_float_on_the_shipped_library),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

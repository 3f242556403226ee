/* Real data: every BVH and every ASF/AMC pair under $CUB_DATA_DIR/mocap
 * imports; every BVH survives save -> re-import with every joint of every
 * frame within 0.1 mm; the CMU 02_02 walk stands on the floor.
 * Under CUB_QUICK (qemu) the round trip checks every 8th file only. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "cub/io.h"

#define MAX_FILES 1024

typedef struct file_list {
    char *path[MAX_FILES];
    int count;
} file_list;

static int ends_with(const char *s, const char *tail)
{
    size_t n = strlen(s), m = strlen(tail);
    return n >= m && strcmp(s + n - m, tail) == 0;
}

static void walk(const char *dir, const char *ext, file_list *out)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    if (!d)
        return;
    while ((e = readdir(d)) && out->count < MAX_FILES) {
        char path[1024];
        struct stat st;
        if (e->d_name[0] == '.')
            continue;
        snprintf(path, sizeof(path), "%s/%s", dir, e->d_name);
        if (stat(path, &st) != 0)
            continue;
        if (S_ISDIR(st.st_mode))
            walk(path, ext, out);
        else if (ends_with(e->d_name, ext))
            out->path[out->count++] = strdup(path);
    }
    closedir(d);
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static const char *mocap_dir(char *buf, size_t size)
{
    const char *data = getenv("CUB_DATA_DIR");
    struct stat st;
    if (!data)
        return NULL;
    snprintf(buf, size, "%s/mocap", data);
    return stat(buf, &st) == 0 ? buf : NULL;
}

static void list_files(const char *ext, file_list *out)
{
    char dir[1024];
    memset(out, 0, sizeof(*out));
    if (mocap_dir(dir, sizeof(dir)))
        walk(dir, ext, out);
    qsort(out->path, (size_t)out->count, sizeof(char *), cmp_str);
}

static void free_files(file_list *l)
{
    for (int i = 0; i < l->count; i++)
        free(l->path[i]);
}

static const char *short_name(const char *path)
{
    const char *m = strstr(path, "/mocap/");
    return m ? m + 7 : path;
}

static cub_vec3 world[CUB_MOTION_MAX_JOINTS], world2[CUB_MOTION_MAX_JOINTS];
static cub_pose pose, pose2;

/* World positions of frame f (Q16.16 mm). */
static void frame_world(const cub_io_motion *m, int f, cub_pose *p, cub_vec3 *w)
{
    assert_int_equal(cub_motion_clip_get_frame(&m->clip, f, p), CUB_OK);
    assert_int_equal(cub_motion_forward(&m->skel, p, w, NULL), CUB_OK);
}

/* Height: the largest extent of the first frame (files differ in which
 * axis is up: fair1 is Z-up; a dog's largest extent is its length). The
 * root is left out: Bandai's is a ground marker that stays at the origin. */
static double height_mm(const cub_io_motion *m)
{
    double lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9}, size = 0;
    frame_world(m, 0, &pose, world);
    for (int j = 1; j < m->skel.joint_count; j++) {
        const int32_t v[3] = {world[j].x, world[j].y, world[j].z};
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], v[k] / 65536.0);
            hi[k] = fmax(hi[k], v[k] / 65536.0);
        }
    }
    for (int k = 0; k < 3; k++)
        size = fmax(size, hi[k] - lo[k]);
    return size;
}

static void print_motion(const char *path, const cub_io_motion *m)
{
    printf("io: %s joints=%d frames=%d fps=%.2f unit_mm=%.3f height_mm=%.0f\n",
           short_name(path), m->skel.joint_count, m->clip.frame_count,
           1e9 / m->clip.frame_ns, m->unit_mm, height_mm(m));
}

static void test_every_bvh_imports(void **state)
{
    (void)state;
    file_list files;
    list_files(".bvh", &files);
    if (files.count == 0)
        skip(); /* no $CUB_DATA_DIR/mocap: nothing to read */
    for (int i = 0; i < files.count; i++) {
        cub_io_motion m;
        cub_diag d;
        char msg[600];
        cub_err err = cub_io_load_bvh(files.path[i], NULL, &m, &d);
        if (err)
            fail_msg("%s", cub_diag_str(&d, msg, sizeof(msg)));
        print_motion(files.path[i], &m);
        double h = height_mm(&m);
        if (!(h > 300 && h < 2500)) /* a dog or a human, in mm */
            fail_msg("%s: size %.0f mm is no dog's and no human's", files.path[i], h);
        assert_true(m.clip.frame_count > 0 && m.clip.frame_ns > 0);
        cub_io_motion_free(&m);
    }
    printf("io: %d BVH files imported\n", files.count);
    free_files(&files);
}

/* CMU pairs subject_trial.amc with subject.asf in the same folder. */
static void asf_for(const char *amc, char *asf, size_t size)
{
    snprintf(asf, size, "%s", amc);
    char *slash = strrchr(asf, '/');
    char *cut = strchr(slash ? slash : asf, '_');
    if (!cut)
        cut = strrchr(asf, '.');
    snprintf(cut, size - (size_t)(cut - asf), ".asf");
}

static void test_every_asf_amc_imports(void **state)
{
    (void)state;
    file_list files;
    list_files(".amc", &files);
    if (files.count == 0)
        skip();
    for (int i = 0; i < files.count; i++) {
        cub_io_motion m;
        cub_diag d;
        char msg[600], asf[1024];
        asf_for(files.path[i], asf, sizeof(asf));
        cub_err err = cub_io_load_asf_amc(asf, files.path[i], NULL, &m, &d);
        if (err)
            fail_msg("%s", cub_diag_str(&d, msg, sizeof(msg)));
        print_motion(files.path[i], &m);
        double h = height_mm(&m);
        if (!(h > 1000 && h < 2200))
            fail_msg("%s: height %.0f mm is not a human's", files.path[i], h);
        cub_io_motion_free(&m);
    }
    free_files(&files);
}

/* Largest per-axis difference between two motions' world positions over
 * every `step`-th frame, in mm. */
static double max_world_error_mm(const cub_io_motion *a, const cub_io_motion *b, int step)
{
    double worst = 0;
    assert_int_equal(a->skel.joint_count, b->skel.joint_count);
    assert_int_equal(a->clip.frame_count, b->clip.frame_count);
    for (int f = 0; f < a->clip.frame_count; f += step) {
        frame_world(a, f, &pose, world);
        frame_world(b, f, &pose2, world2);
        for (int j = 0; j < a->skel.joint_count; j++) {
            worst = fmax(worst, fabs((double)world[j].x - world2[j].x) / 65536.0);
            worst = fmax(worst, fabs((double)world[j].y - world2[j].y) / 65536.0);
            worst = fmax(worst, fabs((double)world[j].z - world2[j].z) / 65536.0);
        }
    }
    return worst;
}

static void round_trip(const char *path, const char *tmp, double *overall)
{
    cub_io_motion a, b;
    cub_diag d;
    char msg[600];
    cub_io_desc same_unit = {0};
    if (cub_io_load_bvh(path, NULL, &a, &d))
        fail_msg("%s", cub_diag_str(&d, msg, sizeof(msg)));
    if (cub_io_save_bvh(tmp, &a, &d))
        fail_msg("%s", cub_diag_str(&d, msg, sizeof(msg)));
    same_unit.unit_mm = a.unit_mm;
    if (cub_io_load_bvh(tmp, &same_unit, &b, &d))
        fail_msg("re-import: %s", cub_diag_str(&d, msg, sizeof(msg)));
    assert_int_equal(a.clip.frame_ns, b.clip.frame_ns);
    for (int j = 0; j < a.skel.joint_count; j++) {
        assert_string_equal(a.skel.joints[j].name, b.skel.joints[j].name);
        assert_int_equal(a.skel.joints[j].parent, b.skel.joints[j].parent);
        assert_int_equal(a.channels[j].count, b.channels[j].count);
    }
    double err = max_world_error_mm(&a, &b, 1);
    printf("io: round trip %s frames=%d max_err_mm=%.6f\n", short_name(path), a.clip.frame_count,
           err);
    assert_true(err <= 0.1);
    *overall = fmax(*overall, err);
    cub_io_motion_free(&a);
    cub_io_motion_free(&b);
}

static void test_bvh_round_trip_keeps_every_joint(void **state)
{
    (void)state;
    file_list files;
    char tmp[1100];
    const char *build = getenv("CUB_BUILD_DIR");
    int step = getenv("CUB_QUICK") ? 8 : 1, done = 0;
    double overall = 0;
    list_files(".bvh", &files);
    if (files.count == 0)
        skip();
    snprintf(tmp, sizeof(tmp), "%s/io_round_trip_%ld.bvh", build ? build : "/tmp", (long)getpid());
    for (int i = 0; i < files.count; i += step, done++)
        round_trip(files.path[i], tmp, &overall);
    remove(tmp);
    printf("io: round trip over %d BVH files: overall max_err_mm=%.6f (limit 0.1)\n", done,
           overall);
    free_files(&files);
}

static void test_cmu_walk_feet_on_floor(void **state)
{
    (void)state;
    char dir[1024], asf[1100], amc[1100];
    cub_io_motion m;
    cub_diag d;
    struct stat st;
    if (!mocap_dir(dir, sizeof(dir)))
        skip();
    snprintf(asf, sizeof(asf), "%s/cmu/asfamc/02.asf", dir);
    snprintf(amc, sizeof(amc), "%s/cmu/asfamc/02_02.amc", dir);
    if (stat(amc, &st) != 0)
        skip();
    assert_int_equal(cub_io_load_asf_amc(asf, amc, NULL, &m, &d), CUB_OK);
    int lfoot = cub_motion_skeleton_find(&m.skel, "ltoes"),
        rfoot = cub_motion_skeleton_find(&m.skel, "rtoes"),
        head = cub_motion_skeleton_find(&m.skel, "head"), hips = 0;
    assert_true(lfoot > 0 && rfoot > 0 && head > 0);
    double low_min = 1e9, low_max = -1e9, head_hips_min = 1e9;
    for (int f = 0; f < m.clip.frame_count; f++) {
        frame_world(&m, f, &pose, world);
        double low = fmin(world[lfoot].y, world[rfoot].y) / 65536.0;
        low_min = fmin(low_min, low);
        low_max = fmax(low_max, low);
        head_hips_min = fmin(head_hips_min, (world[head].y - world[hips].y) / 65536.0);
    }
    printf("io: 02_02 walk lower foot y in [%.1f, %.1f] mm, head above hips by >= %.0f mm\n",
           low_min, low_max, head_hips_min);
    /* The lower foot stays on the floor (y = 0 in CMU captures) all along. */
    assert_true(low_min > -60 && low_max < 120);
    assert_true(head_hips_min > 400);
    cub_io_motion_free(&m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_bvh_imports),
        cmocka_unit_test(test_every_asf_amc_imports),
        cmocka_unit_test(test_bvh_round_trip_keeps_every_joint),
        cmocka_unit_test(test_cmu_walk_feet_on_floor),
    };
    if (!getenv("CUB_DATA_DIR"))
        printf("io: CUB_DATA_DIR is not set: the real-data tests skip\n");
    return cmocka_run_group_tests(tests, NULL, NULL);
}

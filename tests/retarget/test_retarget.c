/* Retargeting human mocap onto the bear (cub/retarget.h).
 * First what bad input gets (mapping tables, recipes), then real CMU clips:
 * feet on the floor and pinned during contacts, no flips, bone directions
 * that follow the source, the root trajectory scaled by the leg ratio.
 * Real-data tests skip when CUB_DATA_DIR has no mocap. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/character.h"
#include "cub/retarget.h"

#define PI 3.14159265358979323846

static cub_character bear;
static cub_retarget_map map;

static void load_bear(void)
{
    char path[512];
    cub_diag d;
    snprintf(path, sizeof(path), "%s/assets/bear/bear.xml", getenv("CUB_SOURCE_DIR"));
    assert_int_equal(cub_character_load(path, &bear, &d), CUB_OK);
}

/* ---- bad input ----------------------------------------------------------- */

static void expect_map_error(const char *text, int bind, const char *want)
{
    cub_diag d;
    char msg[700];
    memset(&d, 0, sizeof(d));
    cub_err err = cub_retarget_map_parse(text, strlen(text), "t.map", &map, &d);
    if (!err && bind) {
        cub_skeleton src;
        int idx;
        cub_motion_skeleton_reset(&src);
        cub_vec3 up = {0, CUB_Q16_INT(100), 0};
        assert_int_equal(cub_motion_skeleton_add(&src, "Hips", -1, up, &idx), CUB_OK);
        assert_int_equal(cub_motion_skeleton_add(&src, "Spine", 0, up, &idx), CUB_OK);
        err = cub_retarget_map_bind(&map, &bear.skel, &src, &d);
    }
    assert_int_not_equal(err, CUB_OK);
    cub_diag_str(&d, msg, sizeof(msg));
    printf("retarget: bad map -> %s\n", msg);
    assert_non_null(strstr(msg, want));
}

static void test_map_errors_name_file_and_line(void **state)
{
    (void)state;
    load_bear();
    expect_map_error("# c\nHips Hips\nSpine Spin\n", 1, "t.map:3: no source joint \"Spin\"");
    expect_map_error("Hips Hips\n\nHipz Spine\n", 1, "t.map:3: no target joint \"Hipz\"");
    expect_map_error("Hips Hips\nHips Spine\n", 0, "t.map:2: target joint \"Hips\" already linked");
    expect_map_error("Hips Hips:-1\n", 0, "t.map:1: bad weight");
    expect_map_error("Hips\n", 0, "t.map:1: expected");
    expect_map_error("# nothing\n", 0, "no links");
    expect_map_error("Hips Hips aim\n", 1, "t.map:1: \"Hips\" is marked aim");
}

static void test_map_many_to_one_weights_normalised(void **state)
{
    (void)state;
    const char *t = "Chest Spine1:1 Spine2:3 rot\n";
    cub_diag d;
    assert_int_equal(cub_retarget_map_parse(t, strlen(t), "m.map", &map, &d), CUB_OK);
    assert_int_equal(map.link[0].source_count, 2);
    assert_true(fabs(map.link[0].source[1].weight - 0.75) < 1e-12);
    assert_int_equal(map.link[0].policy, CUB_RETARGET_ROT);
}

/* Weights whose sum overflows (issue 18): 1e308 + 1e308 is inf, and every
 * weight was normalised to 0, so the joint never moved. Now they are as
 * any equal pair, and the largest and smallest doubles keep their ratio. */
static void test_map_huge_weights_normalise_finite(void **state)
{
    (void)state;
    const char *t = "Chest Spine1:1e308 Spine2:1e308\nHips Hips:1.7e308 Spine:1e-300\n";
    cub_diag d;
    assert_int_equal(cub_retarget_map_parse(t, strlen(t), "m.map", &map, &d), CUB_OK);
    for (int l = 0; l < 2; l++) {
        double sum = 0;
        for (int i = 0; i < map.link[l].source_count; i++) {
            assert_true(isfinite(map.link[l].source[i].weight));
            sum += map.link[l].source[i].weight;
        }
        assert_true(fabs(sum - 1.0) < 1e-12);
    }
    assert_true(fabs(map.link[0].source[0].weight - 0.5) < 1e-12);
    assert_true(fabs(map.link[0].source[1].weight - 0.5) < 1e-12);
    assert_true(map.link[1].source[0].weight > 0.999999);
    expect_map_error("Hips Hips:1e309\n", 0, "t.map:1: bad weight \"1e309\"");
}

/* A map saved with a UTF-8 byte-order mark reads as without one. */
static void test_map_byte_order_mark_is_dropped(void **state)
{
    (void)state;
    const char *t = "\xEF\xBB\xBFHips Hips\n";
    cub_diag d;
    assert_int_equal(cub_retarget_map_parse(t, strlen(t), "m.map", &map, &d), CUB_OK);
    assert_string_equal(map.link[0].target_name, "Hips");
}

static void expect_recipe_error(const char *text, const char *want)
{
    static cub_recipe r;
    cub_diag d;
    char msg[700];
    assert_int_not_equal(cub_recipe_parse(text, strlen(text), "r.txt", &r, &d), CUB_OK);
    cub_diag_str(&d, msg, sizeof(msg));
    printf("retarget: bad recipe -> %s\n", msg);
    assert_non_null(strstr(msg, want));
}

static void test_recipe_errors_name_file_and_line(void **state)
{
    (void)state;
    expect_recipe_error("a dance s.bvh m.map 0 1\nb party s.bvh m.map 0 1\n", "r.txt:2: kind");
    expect_recipe_error("a dance s.bvh m.map 2 1\n", "r.txt:1: bad time range");
    expect_recipe_error("a dance s.bvh m.map 0 1\na coach s.bvh m.map 0 1\n",
                        "r.txt:2: clip \"a\" already on line 1");
    expect_recipe_error("a dance s.bvh m.map 0 1 speed=0\n", "r.txt:1: bad option");
    expect_recipe_error("a dance s.bvh\n", "r.txt:1: expected");
}

/* ---- real clips ---------------------------------------------------------- */

typedef struct real_case {
    const char *label, *file, *map;
    double from_s, to_s;
} real_case;

static int load_real(const real_case *rc, cub_io_motion *src)
{
    const char *data = getenv("CUB_DATA_DIR"), *root = getenv("CUB_SOURCE_DIR");
    char path[512], mpath[512];
    cub_diag d;
    snprintf(path, sizeof(path), "%s/%s", data ? data : "", rc->file);
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    fclose(f);
    snprintf(mpath, sizeof(mpath), "%s/assets/retarget/%s", root, rc->map);
    assert_int_equal(cub_retarget_load_source(path, NULL, src, &d), CUB_OK);
    assert_int_equal(cub_retarget_map_load(mpath, &map, &d), CUB_OK);
    assert_int_equal(cub_retarget_map_bind(&map, &bear.skel, &src->skel, &d), CUB_OK);
    return 1;
}

static cub_vec3 world_mm[CUB_MOTION_MAX_JOINTS];
static cub_pose pose;

static void world_of(const cub_clip *clip, int f, double out[][3])
{
    assert_int_equal(cub_motion_clip_get_frame(clip, f, &pose), CUB_OK);
    assert_int_equal(cub_motion_forward(clip->skel, &pose, world_mm, NULL), CUB_OK);
    for (int j = 0; j < clip->skel->joint_count; j++) {
        out[j][0] = world_mm[j].x / 65536.0;
        out[j][1] = world_mm[j].y / 65536.0;
        out[j][2] = world_mm[j].z / 65536.0;
    }
}

static double quat_angle_deg(cub_quat a, cub_quat b)
{
    double d = ((double)a.w * b.w + (double)a.x * b.x + (double)a.y * b.y + (double)a.z * b.z) /
               ((double)(1 << 30) * (double)(1 << 30));
    d = fabs(d) > 1 ? 1 : fabs(d);
    return 2 * acos(d) * 180 / PI;
}

/* Lowest foot joint of the bear's rest pose (the toe tip), mm. */
static double min_rest_foot(void)
{
    double low = 1e9;
    for (int j = 0; j < bear.skel.joint_count; j++) {
        double y = 0;
        for (int k = j; k >= 0; k = bear.skel.joints[k].parent)
            y += bear.skel.joints[k].offset_mm.y / 65536.0;
        low = fmin(low, y);
    }
    return low;
}

/* Feet on the floor, pinned in contacts, no flips. */
static void check_feet_and_flips(const real_case *rc)
{
    cub_io_motion src, out;
    memset(&src, 0, sizeof(src));
    if (!load_real(rc, &src)) {
        printf("retarget: %s skipped, no %s under CUB_DATA_DIR\n", rc->label, rc->file);
        skip();
    }
    cub_retarget_desc desc = {0};
    desc.start_s = rc->from_s, desc.end_s = rc->to_s;
    cub_retarget_report rep;
    cub_diag d;
    assert_int_equal(cub_retarget_clip(&map, &bear.skel, &src.clip, &desc, &out, &rep, &d), CUB_OK);
    static double w[CUB_MOTION_MAX_JOINTS][3];
    int lf = cub_motion_skeleton_find(&bear.skel, "LeftFoot");
    int lt = cub_motion_skeleton_find(&bear.skel, "LeftToe_end");
    int rf = cub_motion_skeleton_find(&bear.skel, "RightFoot");
    int rt = cub_motion_skeleton_find(&bear.skel, "RightToe_end");
    double min_foot = 1e9, max_ang = 0;
    int jn = bear.skel.joint_count;
    for (int f = 0; f < out.clip.frame_count; f++) {
        world_of(&out.clip, f, w);
        min_foot = fmin(min_foot, fmin(fmin(w[lf][1], w[lt][1]), fmin(w[rf][1], w[rt][1])));
        for (int j = 0; f > 0 && j < jn; j++)
            max_ang = fmax(max_ang, quat_angle_deg(out.clip.rot[(size_t)f * jn + j],
                                                   out.clip.rot[(size_t)(f - 1) * jn + j]));
    }
    printf("retarget: %s frames=%d leg_ratio=%.4f min_foot_mm=%.2f contact_frames=%d/%d "
           "contact_ankle_mm=%.1f slide_mean_mm_per_frame=%.3f slide_max_mm_per_frame=%.3f "
           "max_joint_deg_per_frame=%.1f\n",
           rc->label, out.clip.frame_count, rep.leg_ratio, min_foot, rep.contact_frames[0],
           rep.contact_frames[1], rep.contact_ankle_mm, rep.slide_mean_mm, rep.slide_max_mm,
           max_ang);
    assert_true(fabs(min_foot) < 1.0);                 /* lowest foot point on y = 0 */
    assert_true(rep.contact_frames[0] + rep.contact_frames[1] > 0);
    /* contacts stand flat: the ankle at its rest height (25 mm), not lifted
     * by the human foot's pitch */
    double rest_ankle = 0;
    for (int j = lf; j >= 0; j = bear.skel.joints[j].parent)
        rest_ankle += bear.skel.joints[j].offset_mm.y / 65536.0;
    rest_ankle -= min_rest_foot();
    printf("retarget: %s contact_ankle_mm=%.1f rest_ankle_mm=%.1f\n", rc->label,
           rep.contact_ankle_mm, rest_ankle);
    assert_true(fabs(rep.contact_ankle_mm - rest_ankle) < 2.0);
    assert_true(rep.slide_mean_mm < 1.0 && rep.slide_max_mm < 6.0);
    assert_true(max_ang < 60.0);                       /* a flip would be ~180 */
    cub_io_motion_free(&out);
    cub_io_motion_free(&src);
}

static const real_case JACKS = {"13_29 jumping jacks", "mocap/cmu/13_29.bvh", "cmu31.map", 0.5, 3.7};
static const real_case SQUAT = {"13_29 squats", "mocap/cmu/13_29.bvh", "cmu31.map", 32.0, 35.0};
static const real_case JOG = {"14_14 jog", "mocap/cmu/14_14.bvh", "cmu31_alt.map", 4.5, 8.5};

static void test_jumping_jacks_feet_and_flips(void **s) { (void)s; load_bear(); check_feet_and_flips(&JACKS); }
static void test_squats_feet_and_flips(void **s) { (void)s; load_bear(); check_feet_and_flips(&SQUAT); }
static void test_jog_feet_and_flips(void **s) { (void)s; load_bear(); check_feet_and_flips(&JOG); }

/* Bone directions follow the source, and the root follows the source's
 * root scaled by the leg ratio. Without contacts, so IK changes nothing.
 * 13_29 is at 120 fps: output frame k is source frame start + 4k exactly;
 * its rest pose is y up, facing +z, so only the reported yaw separates them. */
static void test_bone_directions_and_root_follow_source(void **state)
{
    (void)state;
    load_bear();
    cub_io_motion src, out;
    memset(&src, 0, sizeof(src));
    if (!load_real(&JACKS, &src)) {
        printf("retarget: directions skipped, no mocap under CUB_DATA_DIR\n");
        skip();
    }
    cub_retarget_desc desc = {0};
    desc.start_s = 1.0, desc.end_s = 3.0, desc.no_contacts = 1;
    cub_retarget_report rep;
    cub_diag d;
    assert_int_equal(cub_retarget_clip(&map, &bear.skel, &src.clip, &desc, &out, &rep, &d), CUB_OK);
    static double bw[CUB_MOTION_MAX_JOINTS][3], sw[CUB_MOTION_MAX_JOINTS][3];
    double yaw = rep.yaw_deg * PI / 180, c = cos(yaw), s = sin(yaw);
    double sum = 0, worst = 0, root_err = 0, s0[3] = {0}, b0[3] = {0};
    int n = 0, f0 = 120; /* 1.0 s at 120 fps */
    for (int f = 0; f < out.clip.frame_count; f++) {
        world_of(&out.clip, f, bw);
        world_of(&src.clip, f0 + 4 * f, sw);
        for (int l = 0; l < map.link_count; l++) {
            int j = map.link[l].target, ch = -1;
            for (int k = j + 1; k < bear.skel.joint_count && ch < 0; k++)
                if (bear.skel.joints[k].parent == j && cub_retarget_map_find(&map, k) >= 0)
                    ch = k;
            if (ch < 0 || map.link[l].policy == CUB_RETARGET_ROT)
                continue;
            int sj = map.link[l].source[0].joint;
            int sc = map.link[cub_retarget_map_find(&map, ch)].source[0].joint;
            double v[3] = {sw[sc][0] - sw[sj][0], sw[sc][1] - sw[sj][1], sw[sc][2] - sw[sj][2]};
            double sv[3] = {c * v[0] + s * v[2], v[1], -s * v[0] + c * v[2]}; /* yaw about y */
            double bv[3] = {bw[ch][0] - bw[j][0], bw[ch][1] - bw[j][1], bw[ch][2] - bw[j][2]};
            double dot = sv[0] * bv[0] + sv[1] * bv[1] + sv[2] * bv[2];
            double cx = sv[1] * bv[2] - sv[2] * bv[1], cy = sv[2] * bv[0] - sv[0] * bv[2],
                   cz = sv[0] * bv[1] - sv[1] * bv[0];
            double ang = atan2(sqrt(cx * cx + cy * cy + cz * cz), dot) * 180 / PI;
            sum += ang, n++;
            worst = fmax(worst, ang);
        }
        /* root: bear(f) - bear(0) == k * Yaw (src(f) - src(0)) */
        int sh = map.link[cub_retarget_map_find(&map, 0)].source[0].joint;
        if (f == 0)
            memcpy(s0, sw[sh], sizeof(s0)), memcpy(b0, bw[0], sizeof(b0));
        double v[3] = {sw[sh][0] - s0[0], sw[sh][1] - s0[1], sw[sh][2] - s0[2]};
        double want[3] = {rep.leg_ratio * (c * v[0] + s * v[2]), rep.leg_ratio * v[1],
                          rep.leg_ratio * (-s * v[0] + c * v[2])};
        for (int k = 0; k < 3; k++)
            root_err = fmax(root_err, fabs(bw[0][k] - b0[k] - want[k]));
    }
    printf("retarget: bone directions vs source over %d bone-frames: mean_deg=%.3f max_deg=%.3f; "
           "root vs leg_ratio*source max_err_mm=%.3f (leg_ratio=%.4f)\n",
           n, sum / n, worst, root_err, rep.leg_ratio);
    assert_true(n > 100);
    assert_true(sum / n < 0.1 && worst < 0.5); /* Q2.30 / Q16.16 rounding only */
    assert_true(root_err < 0.1);
    assert_true(rep.leg_ratio > 0.2 && rep.leg_ratio < 0.4); /* 285 mm bear hips / ~1 m human */
    cub_io_motion_free(&out);
    cub_io_motion_free(&src);
}

static void test_time_range_outside_source_fails(void **state)
{
    (void)state;
    load_bear();
    cub_io_motion src, out;
    memset(&src, 0, sizeof(src));
    if (!load_real(&JACKS, &src)) {
        printf("retarget: range skipped, no mocap under CUB_DATA_DIR\n");
        skip();
    }
    cub_retarget_desc desc = {0};
    desc.start_s = 30, desc.end_s = 90, desc.name = "13_29.bvh";
    cub_diag d;
    char msg[700];
    assert_int_equal(cub_retarget_clip(&map, &bear.skel, &src.clip, &desc, &out, NULL, &d),
                     CUB_ERR_RANGE);
    printf("retarget: bad range -> %s\n", cub_diag_str(&d, msg, sizeof(msg)));
    cub_io_motion_free(&src);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_map_errors_name_file_and_line),
        cmocka_unit_test(test_map_many_to_one_weights_normalised),
        cmocka_unit_test(test_map_huge_weights_normalise_finite),
        cmocka_unit_test(test_map_byte_order_mark_is_dropped),
        cmocka_unit_test(test_recipe_errors_name_file_and_line),
        cmocka_unit_test(test_time_range_outside_source_fails),
        cmocka_unit_test(test_jumping_jacks_feet_and_flips),
        cmocka_unit_test(test_squats_feet_and_flips),
        cmocka_unit_test(test_jog_feet_and_flips),
        cmocka_unit_test(test_bone_directions_and_root_follow_source),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

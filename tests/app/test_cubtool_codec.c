/* cubtool encode / decode, the real binary (argv[1]): a library clip to a
 * .cubseed stream and back to a BVH that re-reads within the codec's
 * bounds; a damaged stream and a missing clip refused by name. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <math.h>

#include "cub/codec.h"
#include "cub/io.h"
#include "cub/pack.h"
#include "run_tool.h"

#define LIBRARY CUB_ASSETS_DIR "/clips/bear.cubclips"

static const char *g_tool;
static char g_out[4096];

static int tool(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static int tool(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int st = cub_test_run_toolv(g_tool, g_out, sizeof g_out, fmt, ap);
    va_end(ap);
    return st;
}

static double dist_mm(cub_vec3 a, cub_vec3 b)
{
    double dx = (a.x - b.x) / 65536.0, dy = (a.y - b.y) / 65536.0, dz = (a.z - b.z) / 65536.0;
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* Largest joint distance between the library clip and the decoded BVH,
 * over kept and over restored frames. */
static void compare(const cub_clip *src, const cub_clip *dec, double *kept, double *restored)
{
    static cub_pose a, b;
    cub_vec3 wa[CUB_MOTION_MAX_JOINTS], wb[CUB_MOTION_MAX_JOINTS];
    *kept = *restored = 0;
    for (int f = 0; f < src->frame_count; f++) {
        assert_int_equal(cub_motion_clip_get_frame(src, f, &a), CUB_OK);
        assert_int_equal(cub_motion_clip_get_frame(dec, f, &b), CUB_OK);
        assert_int_equal(cub_motion_forward(src->skel, &a, wa, NULL), CUB_OK);
        assert_int_equal(cub_motion_forward(dec->skel, &b, wb, NULL), CUB_OK);
        double *worst = cub_codec_is_kept(f, src->frame_count) ? kept : restored;
        for (int j = 0; j < src->skel->joint_count; j++) {
            double d = dist_mm(wa[j], wb[j]);
            if (d > *worst) *worst = d;
        }
    }
}

static void test_round_trip(void **state)
{
    (void)state;
    assert_int_equal(tool("encode '%s' --clip squat --out '%s/squat.cubseed'", LIBRARY,
                          CUB_TEST_OUT_DIR), 0);
    assert_non_null(strstr(g_out, "squat.cubseed: 91 frames, 24 joints, "));
    assert_non_null(strstr(g_out, " : 1 against raw"));
    assert_int_equal(tool("decode '%s/squat.cubseed' --out '%s/squat.bvh'", CUB_TEST_OUT_DIR,
                          CUB_TEST_OUT_DIR), 0);
    static cub_library lib;
    static cub_io_motion m;
    cub_diag d = {0};
    assert_int_equal(cub_pack_read(LIBRARY, &lib, &d), CUB_OK);
    char path[1024];
    snprintf(path, sizeof path, "%s/squat.bvh", CUB_TEST_OUT_DIR);
    cub_io_desc cm = {10.0};
    assert_int_equal(cub_io_load_bvh(path, &cm, &m, &d), CUB_OK);
    const cub_clip *src = &lib.clips[cub_library_find(&lib, "squat")].clip;
    assert_int_equal(m.clip.frame_count, src->frame_count);
    assert_int_equal(m.skel.joint_count, src->skel->joint_count);
    double kept, restored;
    compare(src, &m.clip, &kept, &restored);
    printf("# squat through cubtool encode/decode and BVH text: kept frames within %.3f mm, "
           "restored within %.1f mm\n", kept, restored);
    assert_true(kept < 1.0); /* 16-bit codes and 6-decimal BVH text */
    assert_true(restored < 60.0);
    assert_true(restored > kept); /* the dropped frames are really restored, not stored */
    cub_io_motion_free(&m);
    cub_library_free(&lib);
}

static void test_refusals(void **state)
{
    (void)state;
    char src[1024], bad[1024];
    snprintf(src, sizeof src, "%s/squat.cubseed", CUB_TEST_OUT_DIR);
    snprintf(bad, sizeof bad, "%s/damaged.cubseed", CUB_TEST_OUT_DIR);
    assert_int_equal(tool("encode '%s' --clip squat --out '%s'", LIBRARY, src), 0);
    FILE *in = fopen(src, "rb"), *out = fopen(bad, "wb");
    assert_non_null(in);
    assert_non_null(out);
    static uint8_t buf[1 << 16];
    size_t n = fread(buf, 1, sizeof buf, in);
    buf[n / 2] ^= 0x40;
    assert_int_equal(fwrite(buf, 1, n, out), n);
    fclose(in);
    fclose(out);
    assert_int_equal(tool("decode '%s' --out '%s/x.bvh'", bad, CUB_TEST_OUT_DIR), 1);
    assert_non_null(strstr(g_out, "damaged.cubseed: byte "));
    assert_non_null(strstr(g_out, "CRC mismatch"));
    assert_int_equal(tool("encode '%s' --clip no_such_clip --out '%s/x.cubseed'", LIBRARY,
                          CUB_TEST_OUT_DIR), 1);
    assert_non_null(strstr(g_out, "no clip named 'no_such_clip'"));
    assert_int_equal(tool("decode '%s' --method cubic --out x.bvh", src), 2);
    assert_non_null(strstr(g_out, "--method is squad, slerp or catmull, not 'cubic'"));
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: test_cubtool_codec CUBTOOL\n");
        return 2;
    }
    g_tool = argv[1];
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip),
        cmocka_unit_test(test_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

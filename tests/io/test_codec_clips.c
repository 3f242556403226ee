/* test_codec_clips — the seed's codec (cub/codec.h) on the bear's own
 * library (assets/clips/bear.cubclips, in the repository): round-trip
 * bounds, the encoder's IK flags never making the effectors worse, and a
 * hash of every stream and every decoded frame, which must be the same on
 * x86-64 and on aarch64 (the pi preset runs this test under qemu). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/codec.h"
#include "bear_library.h"
#include "cub/pack.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* FNV-1a over the stream and the decoded clips, Squad with the stream's IK:
 * recorded on x86-64; aarch64 must give the same. A change of the codec
 * changes it on purpose: re-record it from this test's output then (and a
 * change of the shipped library: it is what the pack holds, version 2's
 * cubkeys frames since issue 21). */
#define DECODED_HASH UINT64_C(0x2d9c3827504a15ad)

static cub_library lib;

static int setup(void **state)
{
    (void)state;
    return support_bear_library(&lib);
}

static int teardown(void **state)
{
    (void)state;
    cub_library_free(&lib);
    return 0;
}

typedef struct decoded {
    cub_skeleton skel;
    cub_clip clip;
    void *mem;
} decoded;

static uint8_t *encode(const cub_clip *clip, size_t *len)
{
    int eff[CUB_CODEC_MAX_EFFECTORS];
    int ne = cub_codec_pick_effectors(clip->skel, eff, CUB_CODEC_MAX_EFFECTORS);
    assert_int_equal(ne, 4);
    size_t cap = cub_codec_encoded_max(clip, ne), work_size = cub_codec_encode_work_size(clip, ne);
    uint8_t *buf = malloc(cap);
    void *work = malloc(work_size);
    cub_codec_enc in = {clip, eff, ne, work, work_size};
    assert_int_equal(cub_codec_encode(&in, buf, cap, len), CUB_OK);
    assert_int_equal(*len, cap);
    free(work);
    return buf;
}

static void decode(const uint8_t *s, size_t len, cub_codec_ik ik, decoded *out)
{
    cub_codec_info info;
    assert_int_equal(cub_codec_peek(s, len, &info, NULL), CUB_OK);
    out->mem = malloc(info.mem_size);
    cub_codec_opts o = {CUB_CODEC_SQUAD, ik};
    cub_codec_out dst = {&out->skel, &out->clip, out->mem, info.mem_size};
    cub_codec_problem why = {0};
    assert_int_equal(cub_codec_decode(s, len, &o, &dst, &why), CUB_OK);
}

static double angle_deg(cub_quat a, cub_quat b)
{
    double d = ((double)a.w * b.w + (double)a.x * b.x + (double)a.y * b.y + (double)a.z * b.z) /
               (1073741824.0 * 1073741824.0);
    d = fabs(d) > 1 ? 1 : fabs(d);
    return 2 * acos(d) * 180 / M_PI;
}

static double dist_mm(cub_vec3 a, cub_vec3 b)
{
    double dx = (a.x - b.x) / 65536.0, dy = (a.y - b.y) / 65536.0, dz = (a.z - b.z) / 65536.0;
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* Sum of effector errors (mm) over the frames of a decoded clip. */
static double effector_error(const cub_clip *src, const cub_clip *dec, double *worst)
{
    int eff[CUB_CODEC_MAX_EFFECTORS];
    int ne = cub_codec_pick_effectors(src->skel, eff, CUB_CODEC_MAX_EFFECTORS);
    static cub_pose a, b;
    cub_vec3 wa[CUB_MOTION_MAX_JOINTS], wb[CUB_MOTION_MAX_JOINTS];
    double sum = 0;
    for (int f = 0; f < src->frame_count; f++) {
        cub_motion_clip_get_frame(src, f, &a);
        cub_motion_clip_get_frame(dec, f, &b);
        cub_motion_forward(src->skel, &a, wa, NULL);
        cub_motion_forward(dec->skel, &b, wb, NULL);
        for (int k = 0; k < ne; k++) {
            double d = dist_mm(wa[eff[k]], wb[eff[k]]);
            sum += d;
            if (d > *worst) *worst = d;
        }
    }
    return sum;
}

static void check_clip(const cub_clip *src, const decoded *d, double *rot_sum, long *rot_n)
{
    int n = src->frame_count, jn = src->skel->joint_count;
    assert_int_equal(d->clip.frame_count, n);
    assert_int_equal(d->skel.joint_count, jn);
    for (int f = 0; f < n; f++) {
        double root = dist_mm(src->root_mm[f], d->clip.root_mm[f]);
        for (int j = 0; j < jn; j++) {
            double a = angle_deg(src->rot[(size_t)f * jn + j], d->clip.rot[(size_t)f * jn + j]);
            if (cub_codec_is_kept(f, n)) {
                assert_true(a < 0.01); /* quantisation only */
            } else {
                *rot_sum += a;
                ++*rot_n;
            }
        }
        if (cub_codec_is_kept(f, n)) assert_true(root < 0.053); /* sqrt(3) code steps */
    }
}

static void test_round_trip(void **state)
{
    (void)state;
    double rot_sum = 0, on_sum = 0, off_sum = 0, on_worst = 0, off_worst = 0;
    long rot_n = 0;
    for (int i = 0; i < lib.clip_count; i++) {
        const cub_clip *src = &lib.clips[i].clip;
        size_t len;
        uint8_t *s = encode(src, &len);
        decoded on, off;
        decode(s, len, CUB_CODEC_IK_STREAM, &on);
        decode(s, len, CUB_CODEC_IK_OFF, &off);
        check_clip(src, &on, &rot_sum, &rot_n);
        double a = effector_error(src, &on.clip, &on_worst), b = effector_error(src, &off.clip, &off_worst);
        /* the flags are set per block where IK helps: never worse overall */
        assert_true(a <= b);
        on_sum += a;
        off_sum += b;
        free(on.mem);
        free(off.mem);
        free(s);
    }
    printf("# bear library: restored frames' rotation error %.3f deg mean; effectors "
           "%.0f mm summed with IK, %.0f without; worst %.1f mm with, %.1f without\n",
           rot_sum / (double)rot_n, on_sum, off_sum, on_worst, off_worst);
    assert_true(rot_sum / (double)rot_n < 2.0);
    assert_true(on_worst < 80.0);
    assert_true(on_sum < off_sum);
}

static uint64_t fnv(uint64_t h, const void *p, size_t n)
{
    const uint8_t *b = p;
    for (size_t i = 0; i < n; i++) {
        h ^= b[i];
        h *= UINT64_C(0x100000001b3);
    }
    return h;
}

/* The values in a fixed byte order, whatever the CPU's. */
static uint64_t fnv_i32(uint64_t h, int32_t v)
{
    uint8_t b[4] = {(uint8_t)v, (uint8_t)(v >> 8), (uint8_t)(v >> 16), (uint8_t)(v >> 24)};
    return fnv(h, b, 4);
}

static void test_determinism(void **state)
{
    (void)state;
    uint64_t h = UINT64_C(0xcbf29ce484222325);
    for (int i = 0; i < lib.clip_count; i++) {
        const cub_clip *src = &lib.clips[i].clip;
        size_t len;
        uint8_t *s = encode(src, &len);
        h = fnv(h, s, len);
        decoded d;
        decode(s, len, CUB_CODEC_IK_STREAM, &d);
        int jn = d.skel.joint_count;
        for (int f = 0; f < d.clip.frame_count; f++) {
            const cub_vec3 r = d.clip.root_mm[f];
            h = fnv_i32(fnv_i32(fnv_i32(h, r.x), r.y), r.z);
            for (int j = 0; j < jn; j++) {
                const cub_quat q = d.clip.rot[(size_t)f * jn + j];
                h = fnv_i32(fnv_i32(fnv_i32(fnv_i32(h, q.w), q.x), q.y), q.z);
            }
        }
        free(d.mem);
        free(s);
    }
    printf("# decoded hash 0x%016" PRIx64 "\n", h);
    assert_true(h == DECODED_HASH);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip),
        cmocka_unit_test(test_determinism),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}

/* The clip pack: damaged or hostile files get a clear error and never an
 * overread; version 1: write -> read -> write gives identical bytes, clips
 * come back within the Q1.14 quantisation; version 2 (cubkeys): the same
 * library packs to the same bytes and comes back within the codec's bound
 * (both measured as joint positions after FK). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/pack.h"

/* An independent CRC-32 (bitwise), to check the file's. */
static uint32_t crc32_bitwise(const uint8_t *p, size_t n)
{
    uint32_t c = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; i++) {
        c ^= p[i];
        for (int k = 0; k < 8; k++)
            c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1)));
    }
    return ~c;
}

static void put_u32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        p[i] = (uint8_t)(v >> (8 * i));
}

static void fix_crc(uint8_t *p, size_t n)
{
    put_u32(p + n - 4, crc32_bitwise(p, n - 4));
}

static const char *build_dir(void)
{
    const char *d = getenv("CUB_BUILD_DIR");
    return d ? d : ".";
}

static uint8_t *read_bytes(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    uint8_t *b = malloc((size_t)n + 1);
    assert_int_equal(fread(b, 1, (size_t)n, f), (size_t)n);
    fclose(f);
    *len = (size_t)n;
    return b;
}

/* ---- a small library: a 3-joint skeleton, two clips ---------------------- */

typedef struct small_lib {
    cub_library lib;
    cub_library_clip clips[2];
    uint8_t mem[2][4096];
} small_lib;

static void make_small(small_lib *s)
{
    memset(s, 0, sizeof(*s));
    cub_skeleton *sk = &s->lib.skel;
    cub_motion_skeleton_reset(sk);
    int i;
    assert_int_equal(cub_motion_skeleton_add(sk, "Root", -1, (cub_vec3){0, 0, 0}, &i), CUB_OK);
    cub_motion_skeleton_add(sk, "Arm", 0, (cub_vec3){CUB_Q16_INT(100), 0, 0}, &i);
    cub_motion_skeleton_add(sk, "Hand", 1, (cub_vec3){CUB_Q16_INT(50), 0, 0}, &i);
    sk->joints[2].is_end_site = 1;
    const char *names[2] = {"wave", "nod"};
    for (int c = 0; c < 2; c++) {
        cub_library_clip *lc = &s->clips[c];
        snprintf(lc->name, sizeof(lc->name), "%s", names[c]);
        snprintf(lc->kind, sizeof(lc->kind), "%s", c ? "coach" : "dance");
        assert_int_equal(
            cub_motion_clip_init(&lc->clip, sk, 4 + c, 33333333, 0, s->mem[c], sizeof(s->mem[c])),
            CUB_OK);
        for (int f = 0; f < lc->clip.frame_count; f++) {
            cub_vec3 axis = {0, 0, CUB_Q16_ONE};
            lc->clip.rot[f * 3 + 1] = cub_fx_quat_from_axis_angle(axis, CUB_Q16_ONE / 4 * f);
            lc->clip.root_mm[f] = (cub_vec3){CUB_Q16_INT(f), -CUB_Q16_INT(3), 12345};
        }
    }
    s->lib.clip_count = 2;
    s->lib.clips = s->clips;
}

static uint8_t *small_bytes_v(int version, size_t *len)
{
    small_lib *s = malloc(sizeof(*s));
    make_small(s);
    char path[512];
    snprintf(path, sizeof(path), "%s/test_pack_small.cubclips", build_dir());
    cub_diag d = {0};
    assert_int_equal(cub_pack_write_version(path, &s->lib, version, &d), CUB_OK);
    free(s);
    uint8_t *b = read_bytes(path, len);
    remove(path);
    return b;
}

/* The bad-input rows below walk version 1's layout. */
static uint8_t *small_bytes(size_t *len)
{
    return small_bytes_v(1, len);
}

/* Offsets in the small pack: header 20, joints 3 x 48, clip 0 at 164. */
enum { AT_VERSION = 8, AT_JOINTS = 12, AT_CLIPS = 16, AT_JOINT1 = 20 + 48, AT_CLIP0 = 164 };

static void expect_bad(const uint8_t *b, size_t len, const char *words)
{
    cub_library lib;
    cub_diag d = {0};
    char msg[600];
    /* A private copy of exactly len bytes, so ASan sees any overread. */
    uint8_t *copy = malloc(len ? len : 1);
    memcpy(copy, b, len);
    cub_err err = cub_pack_parse(copy, len, "t.cubclips", &lib, &d);
    free(copy);
    cub_diag_str(&d, msg, sizeof(msg));
    printf("pack: rejected: %s\n", msg);
    assert_int_equal(err, CUB_ERR_FORMAT);
    assert_int_equal(lib.clip_count, 0);
    assert_null(lib.clips);
    if (!strstr(d.msg, words)) fail_msg("message '%s' lacks '%s'", d.msg, words);
}

/* Every truncation is refused without an overread. */
static void expect_truncations_refused(const uint8_t *good, size_t n)
{
    for (size_t k = 0; k < n; k++) {
        cub_library lib;
        cub_diag d = {0};
        uint8_t *copy = malloc(k ? k : 1);
        memcpy(copy, good, k);
        assert_int_equal(cub_pack_parse(copy, k, "t", &lib, &d), CUB_ERR_FORMAT);
        assert_true(d.msg[0] != '\0');
        free(copy);
    }
}

static void test_bad_packs_are_refused(void **state)
{
    (void)state;
    size_t n = 0;
    uint8_t *good = small_bytes(&n);
    uint8_t *b = malloc(n + 8);
    assert_int_equal(crc32_bitwise((const uint8_t *)"123456789", 9), 0xCBF43926u);
    assert_int_equal(crc32_bitwise(good, n - 4), good[n - 4] | good[n - 3] << 8 |
                                                     good[n - 2] << 16 |
                                                     (uint32_t)good[n - 1] << 24);
#define RESET() memcpy(b, good, n)
    RESET();
    expect_bad(b, 10, "too short");
    b[0] = 'X';
    expect_bad(b, n, "not a clip pack");
    RESET();
    put_u32(b + AT_VERSION, 3);
    expect_bad(b, n, "version 3");
    RESET();
    put_u32(b + AT_JOINTS, 0);
    expect_bad(b, n, "joint count 0");
    RESET();
    put_u32(b + AT_JOINTS, 1000);
    expect_bad(b, n, "joint count 1000");
    RESET();
    put_u32(b + AT_CLIPS, 0xFFFFFFFFu);
    expect_bad(b, n, "clips cannot fit");
    RESET();
    b[AT_JOINT1 + 32] = 5; /* Arm's parent: 5 */
    expect_bad(b, n, "parent 5 is not an earlier joint");
    RESET();
    memset(b + AT_JOINT1, 'A', 32); /* no NUL */
    expect_bad(b, n, "not printable, NUL-terminated");
    RESET();
    memcpy(b + AT_JOINT1, "Root", 5); /* a second Root */
    expect_bad(b, n, "appears twice");
    RESET();
    put_u32(b + AT_CLIP0 + 52, 1000000); /* frame count */
    expect_bad(b, n, "1000000 frames need");
    RESET();
    put_u32(b + AT_CLIP0 + 48, 0); /* frame period */
    expect_bad(b, n, "frame period 0 ns");
    RESET();
    expect_bad(b, n - 1, "5 frames need 180 bytes, only 179 left");
    memset(b + n, 0, 8);
    expect_bad(b, n + 8, "found 12 bytes");
    b[AT_CLIP0 + 60] ^= 1; /* a root coordinate */
    expect_bad(b, n, "CRC mismatch");
    /* A quaternion far from unit length, behind a correct CRC. */
    RESET();
    size_t q = AT_CLIP0 + 56 + 12; /* frame 0, joint 0, w */
    b[q] = 0;
    b[q + 1] = 0x20; /* w = 8192 = 0.5 */
    fix_crc(b, n);
    expect_bad(b, n, "is not a unit quaternion");
    RESET();
    b[q] = 0;
    b[q + 1] = 0xC0; /* w = -16384 */
    fix_crc(b, n);
    expect_bad(b, n, "w >= 0");
    expect_truncations_refused(good, n);
    cub_library lib;
    cub_diag d = {0};
    assert_int_equal(cub_pack_read("/nonexistent/x.cubclips", &lib, &d), CUB_ERR_IO);
    free(b);
    free(good);
}

/* Version 2: clip 0's stream length at 220, its stream from 224. */
enum { AT_KEYS_LEN = AT_CLIP0 + 56, AT_KEYS = AT_KEYS_LEN + 4 };

static void test_bad_v2_packs_are_refused(void **state)
{
    (void)state;
    size_t n = 0;
    uint8_t *good = small_bytes_v(2, &n);
    uint8_t *b = malloc(n);
    assert_int_equal(good[AT_VERSION], 2);
    RESET();
    put_u32(b + AT_KEYS_LEN, 100000);
    expect_bad(b, n, "a stream of 100000 bytes, only");
    RESET();
    b[AT_KEYS + 20] ^= 0x10; /* inside the stream, behind a correct pack CRC */
    fix_crc(b, n);
    expect_bad(b, n, "cubkeys stream:");
    RESET();
    b[AT_JOINT1 + 36] ^= 1; /* Arm's offset: the stream's skeleton differs */
    fix_crc(b, n);
    expect_bad(b, n, "not the pack's");
    RESET();
    put_u32(b + AT_CLIP0 + 52, 5); /* frame count 4 -> 5 */
    fix_crc(b, n);
    expect_bad(b, n, "not the pack's");
    RESET();
    put_u32(b + AT_CLIPS, 1000);
    expect_bad(b, n, "clips cannot fit");
    expect_truncations_refused(good, n);
    free(b);
    free(good);
}

static void test_writer_refuses_bad_libraries(void **state)
{
    (void)state;
    small_lib *s = malloc(sizeof(*s));
    char path[512];
    snprintf(path, sizeof(path), "%s/test_pack_refused.cubclips", build_dir());
    cub_diag d = {0};
    make_small(s);
    snprintf(s->clips[1].name, sizeof(s->clips[1].name), "wave");
    assert_int_equal(cub_pack_write(path, &s->lib, &d), CUB_ERR_ARG);
    assert_non_null(strstr(d.msg, "two clips are named 'wave'"));
    make_small(s);
    s->clips[0].kind[0] = '\0';
    assert_int_equal(cub_pack_write(path, &s->lib, &d), CUB_ERR_ARG);
    make_small(s);
    s->clips[0].clip.rot[1] = (cub_quat){0, 0, 0, 0};
    assert_int_equal(cub_pack_write(path, &s->lib, &d), CUB_ERR_ARG);
    assert_non_null(strstr(d.msg, "not a unit quaternion"));
    make_small(s);
    s->clips[0].clip.trans_mm = s->clips[0].clip.root_mm;
    assert_int_equal(cub_pack_write(path, &s->lib, &d), CUB_ERR_UNSUPPORTED);
    assert_non_null(strstr(d.msg, "translations"));
    make_small(s);
    assert_int_equal(cub_pack_write("/nonexistent/dir/x.cubclips", &s->lib, &d), CUB_ERR_IO);
    free(s);
}

/* ---- round trips --------------------------------------------------------- */

/* Largest difference (mm) after FK over every frame: of joint positions
 * (ACL's virtual vertices 3 cm from a bone bound a bone's own end, not
 * an end site's), or with shell 30 of those vertices, every bone (end sites
 * are no bones), the measure version 2's bound is stated in. */
static double max_fk_error(const cub_clip *a, const cub_clip *b, int shell)
{
    static cub_pose pa, pb;
    static cub_vec3 wa[CUB_MOTION_MAX_JOINTS], wb[CUB_MOTION_MAX_JOINTS];
    static cub_quat ra[CUB_MOTION_MAX_JOINTS], rb[CUB_MOTION_MAX_JOINTS];
    double worst = 0;
    for (int f = 0; f < a->frame_count; f++) {
        assert_int_equal(cub_motion_clip_get_frame(a, f, &pa), CUB_OK);
        assert_int_equal(cub_motion_clip_get_frame(b, f, &pb), CUB_OK);
        cub_motion_forward(a->skel, &pa, wa, ra);
        cub_motion_forward(b->skel, &pb, wb, rb);
        for (int j = 0; j < a->skel->joint_count; j++) {
            if (shell && a->skel->joints[j].is_end_site) continue;
            for (int k = 0; k < (shell ? 3 : 1); k++) {
                cub_vec3 v = {k == 0 ? CUB_Q16_INT(shell) : 0, k == 1 ? CUB_Q16_INT(shell) : 0,
                              k == 2 ? CUB_Q16_INT(shell) : 0};
                cub_vec3 va = cub_fx_quat_rotate(ra[j], v), vb = cub_fx_quat_rotate(rb[j], v);
                double dx = (wa[j].x + va.x - wb[j].x - vb.x) / 65536.0,
                       dy = (wa[j].y + va.y - wb[j].y - vb.y) / 65536.0,
                       dz = (wa[j].z + va.z - wb[j].z - vb.z) / 65536.0;
                double e = sqrt(dx * dx + dy * dy + dz * dz);
                worst = e > worst ? e : worst;
            }
        }
    }
    return worst;
}

/* Version 1: write -> read -> write identical, within Q1.14 (2 mm at
 * most). Version 2: packing twice identical, within the codec's bound. */
static void round_trip(const char *what, const cub_library *lib, int version)
{
    char p1[512], p2[512];
    snprintf(p1, sizeof(p1), "%s/test_pack_rt1.cubclips", build_dir());
    snprintf(p2, sizeof(p2), "%s/test_pack_rt2.cubclips", build_dir());
    cub_diag d = {0};
    cub_library *back = malloc(sizeof(*back));
    cub_err err = cub_pack_write_version(p1, lib, version, &d);
    if (!err) err = cub_pack_read(p1, back, &d);
    if (!err) err = cub_pack_write_version(p2, version == 1 ? back : lib, version, &d);
    if (err) fail_msg("%s:%d: %s", d.file, d.line, d.msg);
    size_t n1, n2;
    uint8_t *b1 = read_bytes(p1, &n1), *b2 = read_bytes(p2, &n2);
    assert_int_equal(n1, n2);
    assert_memory_equal(b1, b2, n1);
    assert_int_equal(back->clip_count, lib->clip_count);
    assert_int_equal(back->skel.joint_count, lib->skel.joint_count);
    assert_memory_equal(back->skel.joints, lib->skel.joints,
                        sizeof(cub_joint) * (size_t)lib->skel.joint_count);
    double worst = 0, worst_shell = 0;
    long frames = 0;
    for (int c = 0; c < lib->clip_count; c++) {
        const cub_library_clip *a = &lib->clips[c];
        int i = cub_library_find(back, a->name);
        assert_int_equal(i, c);
        assert_string_equal(back->clips[i].kind, a->kind);
        assert_int_equal(back->clips[i].clip.frame_ns, a->clip.frame_ns);
        assert_int_equal(back->clips[i].clip.frame_count, a->clip.frame_count);
        assert_ptr_equal(back->clips[i].clip.skel, &back->skel);
        double e = max_fk_error(&a->clip, &back->clips[i].clip, 0);
        double es = max_fk_error(&a->clip, &back->clips[i].clip, 30);
        worst = e > worst ? e : worst;
        worst_shell = es > worst_shell ? es : worst_shell;
        frames += a->clip.frame_count;
    }
    assert_int_equal(cub_library_find(back, "no such clip"), -1);
    printf("pack v%d: %s: %d joints, %d clips, %ld frames, %zu bytes; %s identical; "
           "max error after FK: joint positions %.4f mm, 3 cm vertices %.4f mm\n",
           version, what, lib->skel.joint_count, lib->clip_count, frames, n1,
           version == 1 ? "write-read-write" : "two writes", worst, worst_shell);
    if (version == 1) assert_true(worst < 2.0);
    /* The bound, 0.1 mm, plus the Q16.16 rounding of two FKs. */
    else assert_true(worst_shell <= 0.1 + 0.002);
    free(b1);
    free(b2);
    cub_library_free(back);
    free(back);
    remove(p1);
    remove(p2);
}

static void test_small_round_trip(void **state)
{
    (void)state;
    small_lib *s = malloc(sizeof(*s));
    make_small(s);
    round_trip("small", &s->lib, 1);
    round_trip("small", &s->lib, 2);
    /* Packing twice gives the same bytes. */
    size_t n1, n2;
    uint8_t *a = small_bytes(&n1), *b = small_bytes(&n2);
    assert_int_equal(n1, n2);
    assert_memory_equal(a, b, n1);
    /* An empty library packs too. */
    s->lib.clip_count = 0;
    round_trip("empty", &s->lib, 1);
    round_trip("empty", &s->lib, 2);
    free(a);
    free(b);
    free(s);
}

/* A mocap clip, as a library of one, on its own skeleton. */
static void round_trip_bvh(const char *what, const char *path)
{
    cub_io_motion *m = malloc(sizeof(*m));
    cub_diag d = {0};
    if (cub_io_load_bvh(path, NULL, m, &d)) fail_msg("%s:%d: %s", d.file, d.line, d.msg);
    cub_library *lib = calloc(1, sizeof(*lib));
    cub_library_clip *lc = calloc(1, sizeof(*lc));
    lib->skel = m->skel;
    lc->clip = m->clip;
    lc->clip.skel = &lib->skel;
    lc->clip.trans_mm = NULL; /* packs keep rotations; these files animate none */
    snprintf(lc->name, sizeof(lc->name), "%s", what);
    snprintf(lc->kind, sizeof(lc->kind), "dance");
    lib->clips = lc;
    lib->clip_count = 1;
    round_trip(what, lib, 1);
    round_trip(what, lib, 2);
    free(lc);
    free(lib);
    cub_io_motion_free(m);
    free(m);
}

static void test_mocap_round_trip(void **state)
{
    (void)state;
    const char *src = getenv("CUB_SOURCE_DIR"), *data = getenv("CUB_DATA_DIR");
    char path[512];
    if (src) {
        snprintf(path, sizeof(path), "%s/assets/clips/hello.bvh", src);
        round_trip_bvh("hello", path);
    }
    if (!data) skip();
    snprintf(path, sizeof(path), "%s/mocap/cmu/daz43/08_01.bvh", data);
    FILE *f = fopen(path, "rb");
    if (!f) {
        printf("pack: %s is absent; skipping the CMU round trip\n", path);
        skip();
    }
    fclose(f);
    round_trip_bvh("cmu_08_01", path);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_packs_are_refused),
        cmocka_unit_test(test_bad_v2_packs_are_refused),
        cmocka_unit_test(test_writer_refuses_bad_libraries),
        cmocka_unit_test(test_small_round_trip),
        cmocka_unit_test(test_mocap_round_trip),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

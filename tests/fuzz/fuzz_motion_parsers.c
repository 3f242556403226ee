/* libFuzzer target for the motion parsers (app/io).
 * Input: byte 0 picks the parser, the rest is the text.
 *   even (e.g. 'B'): BVH; bit 1 set: a fixed unit instead of the guess.
 *   odd  (e.g. 'A'): ASF + AMC, split at the first "\n==AMC==\n".
 * Whatever the input, a parser returns (no crash, hang or overread); on
 * success the motion must be usable: forward kinematics on its frames. */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "cub/io.h"

#define MARK "\n==AMC==\n"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static size_t find_mark(const char *s, size_t n)
{
    size_t m = sizeof(MARK) - 1;
    for (size_t i = 0; i + m <= n; i++)
        if (memcmp(s + i, MARK, m) == 0)
            return i;
    return n;
}

static void use_motion(const cub_io_motion *m)
{
    static cub_pose pose;
    static cub_vec3 world[CUB_MOTION_MAX_JOINTS];
    int n = m->clip.frame_count;
    if (m->skel.joint_count < 1 || m->skel.joint_count > CUB_MOTION_MAX_JOINTS || n < 1)
        __builtin_trap();
    int frames[2] = {0, n - 1};
    for (int i = 0; i < 2; i++) {
        if (cub_motion_clip_get_frame(&m->clip, frames[i], &pose) ||
            cub_motion_forward(&m->skel, &pose, world, NULL))
            __builtin_trap();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    cub_io_motion m;
    cub_diag d;
    char msg[600];
    if (size < 1)
        return 0;
    const char *text = (const char *)data + 1;
    size_t len = size - 1;
    cub_io_desc desc = {.unit_mm = (data[0] & 2) ? 1.0 : 0.0};
    cub_err err;
    if ((data[0] & 1) == 0) {
        err = cub_io_parse_bvh(text, len, "fuzz.bvh", &desc, &m, &d);
    } else {
        size_t k = find_mark(text, len), skip = k < len ? sizeof(MARK) - 1 : 0;
        err = cub_io_parse_asf_amc(text, k, text + k + skip, len - k - skip, "fuzz", &desc, &m,
                                   &d);
    }
    cub_diag_str(&d, msg, sizeof(msg));
    if (strlen(msg) >= sizeof(msg))
        __builtin_trap();
    if (err == CUB_OK) {
        use_motion(&m);
        cub_io_motion_free(&m);
    } else if (d.msg[0] == '\0') {
        __builtin_trap(); /* every failure says why */
    }
    return 0;
}

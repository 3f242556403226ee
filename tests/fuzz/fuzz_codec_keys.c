/* libFuzzer target: a .cubkeys stream (our error-bounded codec,
 * firmware/codec/codec_keys.c) as `cubtool decode` takes it. Byte 0 steers:
 * bit 0 rewrites the length field and the CRC to match the bytes (so the
 * fuzzer gets past the CRC into the skeleton, the tracks, their key sets
 * and segments). An opened stream is then decoded at its first and last
 * frame and at up to 64 frames between. Seeds: seeds_keys/ (make_seeds.py).
 * Whatever the bytes: no crash, no read past the stream, and a refusal
 * always has a reason. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "codec_internal.h" /* codec_crc32: the stream's own CRC */
#include "fuzz_mend.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    size_t n;
    uint8_t *s = fuzz_stream(data, size, &n);
    if (!s) return 0;
    static cub_skeleton skel;
    static cub_keys k;
    static cub_pose pose;
    cub_codec_problem why = {0};
    cub_err e = cub_keys_open(s, n, &skel, &k, &why);
    if (e == CUB_ERR_FORMAT && !why.what) abort();
    if (!e) {
        int step = k.frame_count / 64 + 1;
        for (int f = 0; f < k.frame_count; f += step)
            if (cub_keys_pose(&k, f, &pose)) abort();
        if (cub_keys_pose(&k, k.frame_count - 1, &pose)) abort();
    }
    free(s);
    return 0;
}

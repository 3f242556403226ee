/* libFuzzer target: a .cubseed stream as the box and `cubtool decode` take
 * it (firmware/codec). Byte 0 steers: bit 0 rewrites the length field and
 * the CRC to match the bytes (so the fuzzer gets past the CRC into the
 * skeleton, the counts and the frames), bits 1-2 the restore method, bits
 * 3-4 the IK mode. Seeds: seeds_codec/ (make_seeds.py). Whatever the bytes:
 * no crash, no read past the stream, and a refusal always has a reason. */
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
    cub_clip clip;
    cub_codec_info info;
    cub_codec_problem why = {0};
    cub_err e = cub_codec_peek(s, n, &info, &why);
    if (e == CUB_ERR_FORMAT && !why.what) abort();
    if (!e) {
        void *mem = malloc(info.mem_size);
        cub_codec_opts o = {(cub_codec_method)((data[0] >> 1) % 3), (cub_codec_ik)((data[0] >> 3) % 3)};
        cub_codec_out out = {&skel, &clip, mem, info.mem_size};
        why.what = NULL;
        e = mem ? cub_codec_decode(s, n, &o, &out, &why) : CUB_OK;
        if (e == CUB_ERR_FORMAT && !why.what) abort();
        free(mem);
    }
    free(s);
    return 0;
}

/* cubtool encode / decode — the seed's codec (cub/codec.h) on one clip: a
 * BVH or a library clip to a .cubseed stream, and a stream back to BVH. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "codec_host.h"
#include "cub/codec_enc.h"
#include "commands.h"
#include "tool_util.h"

static void encode_usage(FILE *f)
{
    fprintf(f, "usage: cubtool encode CLIP.bvh --out X.cubseed\n"
               "       cubtool encode LIB.cubclips --clip NAME --out X.cubseed\n"
               "       cubtool encode ... --keys [--bound CM] --out X.cubkeys\n"
               "\n"
               "Compresses a clip with the folk-dance seed's codec (docs/codec.md): every\n"
               "4th frame and 6 at each end kept, 16-bit numbers, IK flags for the feet\n"
               "and hands. With --keys, with our error-bounded codec instead: every\n"
               "virtual vertex 3 cm from each bone within CM (default 0.01 cm, ACL's\n"
               "threshold) of the source, in object space. Prints frames, joints, bytes\n"
               "and the ratio against raw (10 float32 per bone per sample).\n");
}

static int write_file(const char *path, const codec_blob *b)
{
    FILE *f = fopen(path, "wb");
    int ok = f && fwrite(b->data, 1, b->len, f) == b->len;
    if (f && fclose(f)) ok = 0;
    if (!ok) fprintf(stderr, "%s: cannot write\n", path);
    return ok ? 0 : -1;
}

int cub_cmd_encode(int argc, char **argv)
{
    const char *in = NULL, *out = NULL, *clip = NULL, *bound = "0.01";
    int keys = 0;
    const cub_tool_opt opts[] = {{"--out", &out, NULL}, {"--clip", &clip, NULL}, {"--keys", NULL, &keys},
                                 {"--bound", &bound, NULL}};
    cub_tool_parsed p = cub_tool_parse_opts(argc, argv, opts, 4, &in, 1);
    if (p == CUB_TOOL_HELP) encode_usage(stdout);
    if (p != CUB_TOOL_RUN) return p == CUB_TOOL_HELP ? 0 : 2;
    char *end;
    double bound_cm = strtod(bound, &end);
    if (*end || !(bound_cm > 0 && bound_cm < 100)) {
        fprintf(stderr, "cubtool encode: --bound is a length in cm above 0, not '%s'\n", bound);
        return 2;
    }
    if (!in || !out) {
        encode_usage(stderr);
        return 2;
    }
    codec_source src;
    codec_blob blob = {0};
    if (codec_source_load(in, clip, &src)) return 1;
    int rc = keys ? codec_host_encode_keys(src.clip, 10.0 * bound_cm, &blob, in) : codec_host_encode(src.clip, &blob, in);
    rc = rc || write_file(out, &blob) ? 1 : 0;
    if (!rc)
        printf("%s: %d frames, %d joints, %zu bytes, %.2f : 1 against raw\n", out,
               src.clip->frame_count, src.clip->skel->joint_count, blob.len,
               codec_raw_bytes(src.clip) / (double)blob.len);
    free(blob.data);
    codec_source_free(&src);
    return rc;
}

static void decode_usage(FILE *f)
{
    fprintf(f, "usage: cubtool decode X.cubseed --out Y.bvh [--method squad|slerp|catmull]\n"
               "                      [--ik stream|off|all]\n"
               "       cubtool decode X.cubkeys --out Y.bvh\n"
               "\n"
               "Decodes a .cubseed stream as the box does (fixed point; Squad and the\n"
               "stream's IK flags by default), or a .cubkeys one (our error-bounded\n"
               "codec, one pose at a time; told apart by their first bytes), and writes\n"
               "it as BVH in centimetres.\n"
               "A damaged stream is refused with the byte and the reason.\n");
}

static int parse_choice(const char *s, const char *const *names, int n)
{
    for (int i = 0; i < n; i++)
        if (!strcmp(s, names[i])) return i;
    return -1;
}

int cub_cmd_decode(int argc, char **argv)
{
    static const char *const methods[] = {"squad", "slerp", "catmull"};
    static const char *const iks[] = {"stream", "off", "all"};
    const char *in = NULL, *out = NULL, *method = "squad", *ik = "stream";
    const cub_tool_opt opts[] = {{"--out", &out, NULL}, {"--method", &method, NULL}, {"--ik", &ik, NULL}};
    cub_tool_parsed p = cub_tool_parse_opts(argc, argv, opts, 3, &in, 1);
    if (p == CUB_TOOL_HELP) decode_usage(stdout);
    if (p != CUB_TOOL_RUN) return p == CUB_TOOL_HELP ? 0 : 2;
    int m = parse_choice(method, methods, 3), k = parse_choice(ik, iks, 3);
    if (m < 0) fprintf(stderr, "cubtool decode: --method is squad, slerp or catmull, not '%s'\n", method);
    if (k < 0) fprintf(stderr, "cubtool decode: --ik is stream, off or all, not '%s'\n", ik);
    if (!in || !out || m < 0 || k < 0) {
        decode_usage(stderr);
        return 2;
    }
    cub_codec_opts o = {(cub_codec_method)m, (cub_codec_ik)k};
    codec_blob blob;
    codec_decoded d;
    if (codec_blob_read(in, &blob)) return 1;
    int is_keys = blob.len >= 7 && !memcmp(blob.data, "CUBKEYS", 7);
    int rc = (is_keys ? codec_host_decode_keys(&blob, &d, in) : codec_host_decode(&blob, &o, &d, in)) ? 1 : 0;
    if (!rc) {
        rc = cub_tool_save_clip_bvh(d.skel, &d.clip, out) ? 1 : 0;
        if (!rc) printf("%s: %d frames, %d joints\n", out, d.clip.frame_count, d.skel->joint_count);
        codec_decoded_free(&d);
    }
    free(blob.data);
    return rc;
}

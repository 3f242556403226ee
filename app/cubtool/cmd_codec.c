/* cubtool encode / decode — the seed's codec (cub/codec.h) on one clip: a
 * BVH or a library clip to a .cubseed stream, and a stream back to BVH. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "codec_host.h"
#include "commands.h"

static void encode_usage(FILE *f)
{
    fprintf(f, "usage: cubtool encode CLIP.bvh --out X.cubseed\n"
               "       cubtool encode LIB.cubclips --clip NAME --out X.cubseed\n"
               "\n"
               "Compresses a clip with the folk-dance seed's codec (docs/codec.md): every\n"
               "4th frame and 6 at each end kept, 16-bit numbers, IK flags for the feet\n"
               "and hands. Prints frames, joints, bytes and the ratio against raw\n"
               "(10 float32 per bone per sample).\n");
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
    const char *in = NULL, *out = NULL, *clip = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            encode_usage(stdout);
            return 0;
        } else if (!strcmp(argv[i], "--out") && i + 1 < argc) {
            out = argv[++i];
        } else if (!strcmp(argv[i], "--clip") && i + 1 < argc) {
            clip = argv[++i];
        } else if (argv[i][0] != '-' && !in) {
            in = argv[i];
        } else {
            fprintf(stderr, "cubtool encode: unexpected '%s'\n", argv[i]);
            return 2;
        }
    }
    if (!in || !out) {
        encode_usage(stderr);
        return 2;
    }
    codec_source src;
    codec_blob blob = {0};
    if (codec_source_load(in, clip, &src)) return 1;
    int rc = codec_host_encode(src.clip, &blob, in) || write_file(out, &blob) ? 1 : 0;
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
               "\n"
               "Decodes a .cubseed stream as the box does (fixed point; Squad and the\n"
               "stream's IK flags by default) and writes it as BVH in centimetres.\n"
               "A damaged stream is refused with the byte and the reason.\n");
}

static int parse_choice(const char *s, const char *const *names, int n)
{
    for (int i = 0; i < n; i++)
        if (!strcmp(s, names[i])) return i;
    return -1;
}

/* The decoded clip as a BVH motion: root XYZ position + ZXY rotation. */
static int save_bvh(const codec_decoded *d, const char *path)
{
    cub_io_motion m;
    memset(&m, 0, sizeof m);
    m.skel = *d->skel;
    m.clip = d->clip;
    m.clip.skel = &m.skel;
    m.unit_mm = 10.0;
    for (int j = 0; j < m.skel.joint_count; j++) {
        if (m.skel.joints[j].is_end_site) continue;
        int pos = j == 0 || d->clip.trans_mm != NULL;
        m.channels[j].count = (unsigned char)(pos ? 6 : 3);
        m.channels[j].has_pos = (unsigned char)pos;
        memcpy(m.channels[j].rot_order, "ZXY", 4);
        memcpy(m.channels[j].pos_order, pos ? "XYZ" : "", pos ? 4 : 1);
    }
    cub_diag diag = {0};
    char msg[600];
    if (cub_io_save_bvh(path, &m, &diag)) {
        fprintf(stderr, "%s\n", cub_diag_str(&diag, msg, sizeof msg));
        return -1;
    }
    return 0;
}

int cub_cmd_decode(int argc, char **argv)
{
    static const char *const methods[] = {"squad", "slerp", "catmull"};
    static const char *const iks[] = {"stream", "off", "all"};
    const char *in = NULL, *out = NULL;
    cub_codec_opts o = {CUB_CODEC_SQUAD, CUB_CODEC_IK_STREAM};
    for (int i = 1; i < argc; i++) {
        int has = i + 1 < argc, v;
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            decode_usage(stdout);
            return 0;
        } else if (!strcmp(argv[i], "--out") && has) {
            out = argv[++i];
        } else if (!strcmp(argv[i], "--method") && has && (v = parse_choice(argv[i + 1], methods, 3)) >= 0) {
            o.method = (cub_codec_method)v;
            i++;
        } else if (!strcmp(argv[i], "--ik") && has && (v = parse_choice(argv[i + 1], iks, 3)) >= 0) {
            o.ik = (cub_codec_ik)v;
            i++;
        } else if (argv[i][0] != '-' && !in) {
            in = argv[i];
        } else {
            fprintf(stderr, "cubtool decode: unexpected '%s'\n", argv[i]);
            return 2;
        }
    }
    if (!in || !out) {
        decode_usage(stderr);
        return 2;
    }
    codec_blob blob;
    codec_decoded d;
    if (codec_blob_read(in, &blob)) return 1;
    int rc = codec_host_decode(&blob, &o, &d, in) ? 1 : 0;
    if (!rc) {
        rc = save_bvh(&d, out) ? 1 : 0;
        if (!rc) printf("%s: %d frames, %d joints\n", out, d.clip.frame_count, d.skel->joint_count);
        codec_decoded_free(&d);
    }
    free(blob.data);
    return rc;
}

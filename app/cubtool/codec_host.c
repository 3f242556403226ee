/* The heap and the messages around firmware/codec for cubtool. */
#include "codec_host.h"

#include "cub/codec_enc.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int codec_host_encode(const cub_clip *clip, codec_blob *out, const char *name)
{
    int eff[CUB_CODEC_MAX_EFFECTORS];
    int ne = cub_codec_pick_effectors(clip->skel, eff, CUB_CODEC_MAX_EFFECTORS);
    size_t cap = cub_codec_encoded_max(clip, ne), work_size = cub_codec_encode_work_size(clip, ne);
    memset(out, 0, sizeof *out);
    if (cap == 0 || work_size == 0) {
        fprintf(stderr, "%s: the clip cannot be encoded (empty or too many frames)\n", name);
        return -1;
    }
    out->data = malloc(cap);
    void *work = malloc(work_size);
    cub_codec_enc in = {clip, eff, ne, work, work_size};
    cub_err e = out->data && work ? cub_codec_encode(&in, out->data, cap, &out->len) : CUB_ERR_NOMEM;
    free(work);
    if (e) {
        fprintf(stderr, "%s: encoding failed: %s\n", name, cub_err_str(e));
        free(out->data);
        out->data = NULL;
        return -1;
    }
    return 0;
}

/* Say why a stream was not decoded. */
static void report(cub_err e, const cub_codec_problem *why, const char *name)
{
    if (e == CUB_ERR_FORMAT)
        fprintf(stderr, "%s: byte %zu: %s\n", name, why->offset, why->what);
    else if (e)
        fprintf(stderr, "%s: cannot decode: %s\n", name, cub_err_str(e));
}

int codec_host_decode(const codec_blob *in, const cub_codec_opts *opts, codec_decoded *out,
                      const char *name)
{
    cub_codec_info info;
    cub_codec_problem why = {"", 0};
    memset(out, 0, sizeof *out);
    cub_err e = cub_codec_peek(in->data, in->len, &info, &why);
    if (!e) {
        out->skel = malloc(sizeof *out->skel);
        out->mem = malloc(info.mem_size);
        cub_codec_out dst = {out->skel, &out->clip, out->mem, info.mem_size};
        e = out->skel && out->mem ? cub_codec_decode(in->data, in->len, opts, &dst, &why)
                                  : CUB_ERR_NOMEM;
    }
    report(e, &why, name);
    if (e) codec_decoded_free(out);
    return e ? -1 : 0;
}

int codec_host_encode_keys(const cub_clip *clip, double bound_mm, codec_blob *out, const char *name)
{
    cub_keys_result r;
    memset(out, 0, sizeof *out);
    cub_err e = cub_keys_encode(clip, bound_mm, &r);
    if (e) {
        fprintf(stderr, "%s: encoding failed: %s\n", name, cub_err_str(e));
        return -1;
    }
    out->data = r.data;
    out->len = r.len;
    return 0;
}

/* Every frame, one pose at a time, into a heap clip. */
static cub_err keys_to_clip(const cub_keys *k, codec_decoded *out)
{
    static cub_pose pose;
    size_t mem = cub_motion_clip_mem_size(k->joint_count, k->frame_count, k->has_trans);
    out->mem = malloc(mem);
    if (!out->mem) return CUB_ERR_NOMEM;
    cub_err e = cub_motion_clip_init(&out->clip, out->skel, k->frame_count, k->frame_ns, k->has_trans,
                                     out->mem, mem);
    for (int f = 0; f < k->frame_count && !e; f++) {
        e = cub_keys_pose(k, f, &pose);
        if (!e) e = cub_motion_clip_set_frame(&out->clip, f, &pose);
    }
    return e;
}

int codec_host_decode_keys(const codec_blob *in, codec_decoded *out, const char *name)
{
    static cub_keys k;
    cub_codec_problem why = {"", 0};
    memset(out, 0, sizeof *out);
    out->skel = malloc(sizeof *out->skel);
    cub_err e = out->skel ? cub_keys_open(in->data, in->len, out->skel, &k, &why) : CUB_ERR_NOMEM;
    if (!e) e = keys_to_clip(&k, out);
    report(e, &why, name);
    if (e) codec_decoded_free(out);
    return e ? -1 : 0;
}

void codec_decoded_free(codec_decoded *d)
{
    free(d->skel);
    free(d->mem);
    memset(d, 0, sizeof *d);
}

static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), k = strlen(suffix);
    return n >= k && !strcmp(s + n - k, suffix);
}

int codec_source_load(const char *path, const char *clip_name, codec_source *src)
{
    cub_diag d = {0};
    char msg[600];
    memset(src, 0, sizeof *src);
    if (ends_with(path, ".cubclips")) {
        if (cub_pack_read(path, &src->lib, &d)) {
            fprintf(stderr, "%s\n", cub_diag_str(&d, msg, sizeof msg));
            return -1;
        }
        src->from_lib = 1;
        int i = clip_name ? cub_library_find(&src->lib, clip_name) : -1;
        if (i < 0) {
            fprintf(stderr, "%s: no clip named '%s' (--clip NAME)\n", path,
                    clip_name ? clip_name : "");
            codec_source_free(src);
            return -1;
        }
        src->clip = &src->lib.clips[i].clip;
        return 0;
    }
    cub_io_desc desc = {0};
    if (cub_io_load_bvh(path, &desc, &src->motion, &d)) {
        fprintf(stderr, "%s\n", cub_diag_str(&d, msg, sizeof msg));
        return -1;
    }
    src->clip = &src->motion.clip;
    return 0;
}

void codec_source_free(codec_source *src)
{
    if (src->from_lib)
        cub_library_free(&src->lib);
    else if (src->clip)
        cub_io_motion_free(&src->motion);
    memset(src, 0, sizeof *src);
}

int codec_blob_read(const char *path, codec_blob *out)
{
    cub_diag d = {0};
    char msg[600], *text = NULL;
    cub_text_src src = {path, "cubseed stream", CUB_TEXT_MAX_CLIPS};
    memset(out, 0, sizeof *out);
    if (cub_text_read(&src, &text, &out->len, &d)) {
        fprintf(stderr, "%s\n", cub_diag_str(&d, msg, sizeof msg));
        return -1;
    }
    out->data = (uint8_t *)text;
    return 0;
}

double codec_raw_bytes(const cub_clip *clip)
{
    int bones = 0; /* end sites have no channels: not bones to ACL */
    for (int j = 0; j < clip->skel->joint_count; j++)
        bones += !clip->skel->joints[j].is_end_site;
    return 40.0 * bones * clip->frame_count;
}

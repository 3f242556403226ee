/* Reading a cubseed stream: every count, index and name is checked before
 * use, and the CRC before anything; a refusal says what and at which byte. */
#include <string.h>

#include "codec_internal.h"
#include "codec_reader.h"

static cub_q16 rd_split(reader *r)
{
    int8_t whole = (int8_t)rd_u8(r);
    return cub_codec_dequant_split(whole, rd_u16(r));
}

static cub_vec3 rd_vec3(reader *r)
{
    cub_vec3 v;
    v.x = rd_split(r);
    v.y = rd_split(r);
    v.z = rd_split(r);
    return v;
}

static cub_quat rd_quat(reader *r)
{
    cub_quat q;
    q.w = cub_codec_dequant_unit(rd_u16(r));
    q.x = cub_codec_dequant_unit(rd_u16(r));
    q.y = cub_codec_dequant_unit(rd_u16(r));
    q.z = cub_codec_dequant_unit(rd_u16(r));
    return cub_fx_quat_normalize(q);
}

typedef struct header {
    int joints, effectors, has_trans, frames;
    uint32_t frame_ns, length;
} header;

static cub_err read_header(reader *r, header *h, cub_codec_problem *why)
{
    if (r->len < CODEC_HEADER_BYTES + CODEC_CRC_BYTES)
        return refuse(why, "too short for a cubseed header", r->len);
    if (memcmp(r->p, CODEC_MAGIC, CODEC_MAGIC_LEN) != 0)
        return refuse(why, "not a cubseed stream (no CUBSEED magic)", 0);
    r->pos = CODEC_MAGIC_LEN;
    if (rd_u8(r) != CUB_CODEC_VERSION) return refuse(why, "unsupported cubseed version", 7);
    h->joints = rd_u16(r);
    h->effectors = rd_u8(r);
    unsigned flags = rd_u8(r);
    h->frames = (int)rd_u32(r);
    h->frame_ns = rd_u32(r);
    h->length = rd_u32(r);
    h->has_trans = (flags & CODEC_FLAG_TRANS) != 0;
    if (h->joints < 1 || h->joints > CUB_MOTION_MAX_JOINTS)
        return refuse(why, "joint count outside 1..128", 8);
    if (h->effectors > CUB_CODEC_MAX_EFFECTORS) return refuse(why, "more than 8 effectors", 10);
    if (flags & ~CODEC_FLAG_TRANS) return refuse(why, "unknown flag bits", 11);
    if (h->frames < 1 || h->frames > CODEC_MAX_FRAMES)
        return refuse(why, "frame count outside 1..2^20", 12);
    if (h->frame_ns == 0) return refuse(why, "frame period is zero", 16);
    /* End sites store nothing, so a short stream could ask for a huge clip. */
    if ((int64_t)h->frames * h->joints > CODEC_MAX_JOINT_FRAMES)
        return refuse(why, "more than 2^24 joint-frames", 12);
    return codec_check_crc(r, h->length, why);
}

cub_err codec_check_crc(reader *r, uint32_t length, cub_codec_problem *why)
{
    if (length != r->len) return refuse(why, "stream length differs from the header's (truncated?)", 20);
    size_t body = r->len - CODEC_CRC_BYTES;
    reader crc = {r->p, r->len, body};
    if (rd_u32(&crc) != codec_crc32(r->p, body)) return refuse(why, "CRC mismatch (damaged stream)", body);
    return CUB_OK;
}

cub_err codec_read_joint(reader *r, cub_skeleton *skel, int j, int exact, cub_codec_problem *why)
{
    size_t at = r->pos, end = r->len - (exact ? 0 : CODEC_CRC_BYTES);
    char name[CUB_MOTION_NAME_LEN];
    unsigned n = rd_u8(r);
    if (n < 1 || n >= CUB_MOTION_NAME_LEN) return refuse(why, "joint name length outside 1..31", at);
    for (unsigned i = 0; i < n; i++) {
        name[i] = (char)rd_u8(r);
        if ((unsigned char)name[i] <= ' ' || (unsigned char)name[i] > '~')
            return refuse(why, "joint name has a byte that is not printable ASCII", r->pos - 1);
    }
    name[n] = '\0';
    int parent = (int)rd_u8(r) - 1;
    unsigned end_site = rd_u8(r);
    cub_vec3 off;
    if (exact) {
        off.x = (int32_t)rd_u32(r);
        off.y = (int32_t)rd_u32(r);
        off.z = (int32_t)rd_u32(r);
    } else {
        off = rd_vec3(r);
    }
    if (r->pos > end) return refuse(why, "stream ends inside the joints", at);
    if ((j == 0) != (parent < 0) || parent >= j)
        return refuse(why, "joint parent is not an earlier joint (or a second root)", at + 1 + n);
    if (end_site > 1) return refuse(why, "end-site byte is not 0 or 1", at + 2 + n);
    int idx;
    if (cub_motion_skeleton_add(skel, name, parent, off, &idx))
        return refuse(why, "joint name repeated", at);
    skel->joints[idx].is_end_site = (uint8_t)end_site;
    return CUB_OK;
}

static cub_err read_effectors(reader *r, const cub_skeleton *skel, int *eff, int count,
                              cub_codec_problem *why)
{
    for (int k = 0; k < count; k++) {
        size_t at = r->pos;
        eff[k] = rd_u8(r);
        int p = eff[k] < skel->joint_count ? skel->joints[eff[k]].parent : -1;
        if (p < 0 || skel->joints[p].parent < 0)
            return refuse(why, "effector is not a joint with a grandparent", at);
    }
    return CUB_OK;
}

static cub_err check_size(const reader *r, const header *h, int animated, cub_codec_problem *why)
{
    size_t need = r->pos + (size_t)h->effectors +
                  (size_t)codec_kept_count(h->frames) * codec_frame_bytes(animated, h->has_trans) +
                  codec_flag_bytes(h->frames, h->effectors) + CODEC_CRC_BYTES;
    if (need != r->len) return refuse(why, "stream length does not match its frame count", r->pos);
    return CUB_OK;
}

static cub_err read_skeleton(reader *r, const header *h, cub_skeleton *skel, cub_codec_problem *why)
{
    cub_motion_skeleton_reset(skel);
    for (int j = 0; j < h->joints; j++) {
        cub_err e = codec_read_joint(r, skel, j, 0, why);
        if (e) return e;
    }
    return check_size(r, h, codec_animated(skel), why);
}

cub_err cub_codec_peek(const void *data, size_t len, cub_codec_info *info, cub_codec_problem *why)
{
    if (!data || !info) return CUB_ERR_ARG;
    reader r = {data, len, 0};
    header h;
    cub_err e = read_header(&r, &h, why);
    int animated = 0;
    for (int j = 0; j < h.joints && !e; j++) { /* names are checked by decode */
        unsigned name_len = rd_u8(&r);
        r.pos += name_len + 1u;
        animated += rd_u8(&r) == 0;
        r.pos += 3u * CODEC_SPLIT_BYTES;
    }
    if (!e && r.pos > len) e = refuse(why, "stream ends inside the joints", len);
    if (!e) e = check_size(&r, &h, animated, why);
    if (e) return e;
    info->joint_count = h.joints;
    info->frame_count = h.frames;
    info->effector_count = h.effectors;
    info->has_trans = h.has_trans;
    info->frame_ns = h.frame_ns;
    info->mem_size = codec_mem_size(h.joints, h.frames, h.has_trans, h.effectors);
    return CUB_OK;
}

static void read_frames(reader *r, cub_clip *clip)
{
    int n = clip->frame_count, joints = clip->skel->joint_count;
    for (int f = 0; f < n; f++) {
        if (!cub_codec_is_kept(f, n)) continue;
        clip->root_mm[f] = rd_vec3(r);
        for (int j = 0; j < joints; j++)
            if (!clip->skel->joints[j].is_end_site) clip->rot[(size_t)f * joints + j] = rd_quat(r);
        if (clip->trans_mm)
            for (int j = 0; j < joints; j++)
                if (!clip->skel->joints[j].is_end_site)
                    clip->trans_mm[(size_t)f * joints + j] = rd_vec3(r);
    }
}

cub_err cub_codec_decode(const void *data, size_t len, const cub_codec_opts *opts,
                         const cub_codec_out *out, cub_codec_problem *why)
{
    if (!data || !out || !out->skel || !out->clip || !out->mem) return CUB_ERR_ARG;
    cub_codec_opts o = opts ? *opts : (cub_codec_opts){CUB_CODEC_SQUAD, CUB_CODEC_IK_STREAM};
    if ((unsigned)o.method >= CUB_CODEC_METHOD_COUNT_) return CUB_ERR_ARG;
    reader r = {data, len, 0};
    header h;
    int eff[CUB_CODEC_MAX_EFFECTORS];
    cub_err e = read_header(&r, &h, why);
    if (!e) e = read_skeleton(&r, &h, out->skel, why);
    if (!e) e = read_effectors(&r, out->skel, eff, h.effectors, why);
    if (e) return e;
    size_t need = codec_mem_size(h.joints, h.frames, h.has_trans, h.effectors);
    if (out->mem_size < need) return CUB_ERR_NOMEM;
    size_t clip_bytes = (cub_motion_clip_mem_size(h.joints, h.frames, h.has_trans) + 7) & ~(size_t)7;
    e = cub_motion_clip_init(out->clip, out->skel, h.frames, h.frame_ns, h.has_trans, out->mem,
                             clip_bytes);
    if (e) return refuse(why, "skeleton is not a valid tree", CODEC_HEADER_BYTES);
    read_frames(&r, out->clip);
    codec_restore(out->clip, o.method);
    if (o.ik == CUB_CODEC_IK_OFF) return CUB_OK;
    const uint8_t *flags = o.ik == CUB_CODEC_IK_STREAM ? r.p + r.pos : NULL;
    uintptr_t at = ((uintptr_t)out->mem + clip_bytes + 7) & ~(uintptr_t)7;
    cub_vec3 *targets = (cub_vec3 *)at;
    return codec_correct(out->clip, eff, h.effectors, flags, targets);
}

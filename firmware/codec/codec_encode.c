/* Writing a cubseed stream. The encoder runs on the host (cubtool encode),
 * but lives here so that it quantises and restores with the decoder's own
 * code: the IK flags it sets come from decoding its own stream. */
#include <string.h>

#include "codec_internal.h"

typedef struct writer {
    uint8_t *p;
    size_t pos;
} writer;

static void wr_u8(writer *w, unsigned v)
{
    w->p[w->pos++] = (uint8_t)v;
}

static void wr_u16(writer *w, unsigned v)
{
    wr_u8(w, v & 0xFF);
    wr_u8(w, (v >> 8) & 0xFF);
}

static void wr_u32(writer *w, uint32_t v)
{
    wr_u16(w, v & 0xFFFF);
    wr_u16(w, v >> 16);
}

static void wr_vec3(writer *w, cub_vec3 v)
{
    const cub_q16 c[3] = {v.x, v.y, v.z};
    for (int i = 0; i < 3; i++) {
        int8_t whole;
        uint16_t frac;
        cub_codec_quant_split(c[i], &whole, &frac);
        wr_u8(w, (uint8_t)whole);
        wr_u16(w, frac);
    }
}

static void wr_quat(writer *w, cub_quat q)
{
    wr_u16(w, cub_codec_quant_unit(q.w));
    wr_u16(w, cub_codec_quant_unit(q.x));
    wr_u16(w, cub_codec_quant_unit(q.y));
    wr_u16(w, cub_codec_quant_unit(q.z));
}

static int clip_ok(const cub_clip *clip)
{
    return clip && clip->skel && clip->rot && clip->root_mm && clip->frame_count >= 1 &&
           clip->frame_count <= CODEC_MAX_FRAMES && clip->frame_ns > 0 &&
           (int64_t)clip->frame_count * clip->skel->joint_count <= CODEC_MAX_JOINT_FRAMES &&
           clip->skel->joint_count >= 1 && clip->skel->joint_count <= CUB_MOTION_MAX_JOINTS &&
           !cub_motion_skeleton_validate(clip->skel);
}

size_t cub_codec_encoded_max(const cub_clip *clip, int effector_count)
{
    if (!clip_ok(clip) || effector_count < 0 || effector_count > CUB_CODEC_MAX_EFFECTORS) return 0;
    const cub_skeleton *s = clip->skel;
    size_t n = CODEC_HEADER_BYTES;
    for (int j = 0; j < s->joint_count; j++)
        n += 1 + strlen(s->joints[j].name) + 2 + 3 * CODEC_SPLIT_BYTES;
    n += (size_t)effector_count;
    n += (size_t)codec_kept_count(clip->frame_count) *
         codec_frame_bytes(codec_animated(s), clip->trans_mm != NULL);
    return n + codec_flag_bytes(clip->frame_count, effector_count) + CODEC_CRC_BYTES;
}

/* One trial decode's room: a skeleton, a clip and its frames. */
typedef struct trial {
    cub_skeleton skel;
    cub_clip clip;
} trial;

static size_t trial_size(const cub_clip *clip, int effector_count)
{
    size_t mem = codec_mem_size(clip->skel->joint_count, clip->frame_count,
                                clip->trans_mm != NULL, effector_count);
    return ((sizeof(trial) + 7) & ~(size_t)7) + mem + 8;
}

size_t cub_codec_encode_work_size(const cub_clip *clip, int effector_count)
{
    if (!clip_ok(clip)) return 0;
    return 2 * trial_size(clip, effector_count) + 8;
}

static void write_stream(const cub_codec_enc *in, writer *w, size_t total)
{
    const cub_clip *c = in->clip;
    const cub_skeleton *s = c->skel;
    int n = c->frame_count, joints = s->joint_count;
    memcpy(w->p, CODEC_MAGIC, CODEC_MAGIC_LEN);
    w->pos = CODEC_MAGIC_LEN;
    wr_u8(w, CUB_CODEC_VERSION);
    wr_u16(w, (unsigned)joints);
    wr_u8(w, (unsigned)in->effector_count);
    wr_u8(w, c->trans_mm ? CODEC_FLAG_TRANS : 0);
    wr_u32(w, (uint32_t)n);
    wr_u32(w, c->frame_ns);
    wr_u32(w, (uint32_t)total);
    for (int j = 0; j < joints; j++) {
        size_t len = strlen(s->joints[j].name);
        wr_u8(w, (unsigned)len);
        memcpy(w->p + w->pos, s->joints[j].name, len);
        w->pos += len;
        wr_u8(w, (unsigned)(s->joints[j].parent + 1));
        wr_u8(w, s->joints[j].is_end_site);
        wr_vec3(w, s->joints[j].offset_mm);
    }
    for (int k = 0; k < in->effector_count; k++)
        wr_u8(w, (unsigned)in->effectors[k]);
    for (int f = 0; f < n; f++) {
        if (!cub_codec_is_kept(f, n)) continue;
        wr_vec3(w, c->root_mm[f]);
        for (int j = 0; j < joints; j++)
            if (!s->joints[j].is_end_site) wr_quat(w, c->rot[(size_t)f * joints + j]);
        if (c->trans_mm)
            for (int j = 0; j < joints; j++)
                if (!s->joints[j].is_end_site) wr_vec3(w, c->trans_mm[(size_t)f * joints + j]);
    }
    size_t flags = codec_flag_bytes(n, in->effector_count);
    memset(w->p + w->pos, 0xFF, flags); /* IK everywhere until measured */
    w->pos += flags;
}

static void write_crc(uint8_t *buf, size_t total)
{
    writer w = {buf, total - CODEC_CRC_BYTES};
    wr_u32(&w, codec_crc32(buf, total - CODEC_CRC_BYTES));
}

static cub_err trial_decode(const uint8_t *buf, size_t len, cub_codec_ik ik, uint8_t *room,
                            size_t room_size, trial **out)
{
    trial *t = (trial *)(((uintptr_t)room + 7) & ~(uintptr_t)7);
    size_t head = (sizeof(trial) + 7) & ~(size_t)7;
    size_t used = (size_t)((uint8_t *)t - room) + head;
    cub_codec_opts o = {CUB_CODEC_SQUAD, ik};
    cub_codec_out dst = {&t->skel, &t->clip, (uint8_t *)t + head, room_size - used};
    *out = t;
    return cub_codec_decode(buf, len, &o, &dst, NULL);
}

/* Distance of effector e of frame f of a decoded clip from the source's. */
static int64_t slip(const cub_clip *clip, int f, int effector, const cub_vec3 *truth)
{
    cub_pose pose;
    cub_vec3 world[CUB_MOTION_MAX_JOINTS];
    if (cub_motion_clip_get_frame(clip, f, &pose) ||
        cub_motion_forward(clip->skel, &pose, world, NULL))
        return INT32_MAX;
    return cub_fx_vec3_length(cub_fx_vec3_sub(world[effector], truth[effector]));
}

/* One block's flags: IK where it brings the effectors closer to the source. */
static void block_flags(const cub_codec_enc *in, const trial *off, const trial *all, int b,
                        uint8_t *flags)
{
    const cub_clip *c = in->clip;
    int n = c->frame_count, ne = in->effector_count;
    int64_t e_off[CUB_CODEC_MAX_EFFECTORS] = {0}, e_all[CUB_CODEC_MAX_EFFECTORS] = {0};
    for (int f = b * CUB_CODEC_KEEP_EVERY; f < (b + 1) * CUB_CODEC_KEEP_EVERY && f < n; f++) {
        cub_pose pose;
        cub_vec3 truth[CUB_MOTION_MAX_JOINTS];
        if (cub_codec_is_kept(f, n) || cub_motion_clip_get_frame(c, f, &pose) ||
            cub_motion_forward(c->skel, &pose, truth, NULL))
            continue;
        for (int k = 0; k < ne; k++) {
            e_off[k] += slip(&off->clip, f, in->effectors[k], truth);
            e_all[k] += slip(&all->clip, f, in->effectors[k], truth);
        }
    }
    for (int k = 0; k < ne; k++) {
        size_t bit = (size_t)b * (size_t)ne + (size_t)k;
        if (e_all[k] >= e_off[k]) flags[bit / 8] &= (uint8_t)~(1u << (bit % 8));
    }
}

static cub_err choose_flags(const cub_codec_enc *in, uint8_t *buf, size_t total)
{
    size_t room = trial_size(in->clip, in->effector_count);
    trial *off, *all;
    uint8_t *work = in->work;
    cub_err e = trial_decode(buf, total, CUB_CODEC_IK_OFF, work, room, &off);
    if (!e) e = trial_decode(buf, total, CUB_CODEC_IK_ALL, work + room, room, &all);
    if (e) return e;
    int n = in->clip->frame_count;
    uint8_t *flags = buf + total - CODEC_CRC_BYTES - codec_flag_bytes(n, in->effector_count);
    for (int b = 0; b < codec_block_count(n); b++)
        block_flags(in, off, all, b, flags);
    return CUB_OK;
}

static int effectors_ok(const cub_codec_enc *in)
{
    if (in->effector_count < 0 || in->effector_count > CUB_CODEC_MAX_EFFECTORS) return 0;
    if (in->effector_count > 0 && !in->effectors) return 0;
    const cub_skeleton *s = in->clip->skel;
    for (int k = 0; k < in->effector_count; k++) {
        int j = in->effectors[k];
        if (j < 0 || j >= s->joint_count || s->joints[j].parent < 0 ||
            s->joints[s->joints[j].parent].parent < 0)
            return 0;
    }
    return 1;
}

cub_err cub_codec_encode(const cub_codec_enc *in, void *buf, size_t cap, size_t *out_len)
{
    if (!in || !buf || !out_len || !clip_ok(in->clip) || !effectors_ok(in)) return CUB_ERR_ARG;
    size_t total = cub_codec_encoded_max(in->clip, in->effector_count);
    if (total == 0) return CUB_ERR_ARG;
    if (cap < total) return CUB_ERR_NOMEM;
    int needs_trials = in->effector_count > 0 && codec_kept_count(in->clip->frame_count) <
                                                     in->clip->frame_count;
    if (needs_trials && (!in->work || in->work_size < cub_codec_encode_work_size(in->clip, in->effector_count)))
        return CUB_ERR_NOMEM;
    writer w = {buf, 0};
    write_stream(in, &w, total);
    write_crc(buf, total);
    if (needs_trials) {
        cub_err e = choose_flags(in, buf, total);
        if (e) return e;
        write_crc(buf, total);
    }
    *out_len = total;
    return CUB_OK;
}

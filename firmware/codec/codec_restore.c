/* The decoder's two levels of restoration and its IK correction. */
#include "codec_internal.h"

int cub_codec_is_kept(int f, int n)
{
    return f < CUB_CODEC_KEEP_EDGE || f >= n - CUB_CODEC_KEEP_EDGE || f % CUB_CODEC_KEEP_EVERY == 0;
}

int codec_kept_count(int n)
{
    int k = 0;
    for (int f = 0; f < n; f++)
        k += cub_codec_is_kept(f, n);
    return k;
}

int codec_block_count(int n)
{
    return (n + CUB_CODEC_KEEP_EVERY - 1) / CUB_CODEC_KEEP_EVERY;
}

size_t codec_flag_bytes(int n, int effector_count)
{
    return ((size_t)codec_block_count(n) * (size_t)effector_count + 7) / 8;
}

size_t codec_frame_bytes(int animated, int has_trans)
{
    size_t per_joint = CODEC_QUAT_BYTES + (has_trans ? 3 * CODEC_SPLIT_BYTES : 0);
    return 3 * CODEC_SPLIT_BYTES + (size_t)animated * per_joint;
}

int codec_animated(const cub_skeleton *skel)
{
    int n = 0;
    for (int j = 0; j < skel->joint_count; j++)
        n += !skel->joints[j].is_end_site;
    return n;
}

size_t codec_mem_size(int joint_count, int frame_count, int has_trans, int effector_count)
{
    size_t clip = cub_motion_clip_mem_size(joint_count, frame_count, has_trans);
    clip = (clip + 7) & ~(size_t)7;
    return clip + 7 + (size_t)frame_count * (size_t)effector_count * sizeof(cub_vec3);
}

/* Level 1 (step 2) restores the frames at multiples of 2, level 2 (step 1)
 * the odd ones; a dropped frame f of either has f - 3 step .. f + 3 step
 * in the clip, because the 6 frames at each end are kept. */
static int restored_at(int f, int n, int step)
{
    return !cub_codec_is_kept(f, n) && (step == 2 ? f % 2 == 0 : f % 2 == 1);
}

static void restore_vec3(cub_vec3 *base, int stride, int n)
{
    for (int step = 2; step >= 1; step--)
        for (int f = 0; f < n; f++) {
            if (!restored_at(f, n, step)) continue;
            cub_vec3 p[4] = {base[(f - 3 * step) * stride], base[(f - step) * stride],
                             base[(f + step) * stride], base[(f + 3 * step) * stride]};
            base[f * stride] = cub_codec_pos_mid(p);
        }
}

static void restore_rot(cub_quat *base, int stride, int n, cub_codec_method method)
{
    for (int step = 2; step >= 1; step--)
        for (int f = 0; f < n; f++) {
            if (!restored_at(f, n, step)) continue;
            cub_quat q[4] = {base[(f - 3 * step) * stride], base[(f - step) * stride],
                             base[(f + step) * stride], base[(f + 3 * step) * stride]};
            base[f * stride] = cub_codec_rot_mid(q, method);
        }
}

void codec_restore(cub_clip *clip, cub_codec_method method)
{
    int n = clip->frame_count, joints = clip->skel->joint_count;
    restore_vec3(clip->root_mm, 1, n);
    for (int j = 0; j < joints; j++) {
        restore_rot(clip->rot + j, joints, n, method);
        if (clip->trans_mm) restore_vec3(clip->trans_mm + j, joints, n);
    }
}

static int flag_on(const uint8_t *flags, int f, int e, int effector_count)
{
    if (!flags) return 1;
    size_t bit = (size_t)(f / CUB_CODEC_KEEP_EVERY) * (size_t)effector_count + (size_t)e;
    return (flags[bit / 8] >> (bit % 8)) & 1;
}

/* The kept frames' effector positions, spline-restored in between. */
static cub_err make_targets(const cub_clip *clip, const int *eff, int ne, cub_vec3 *targets)
{
    cub_pose pose;
    cub_vec3 world[CUB_MOTION_MAX_JOINTS];
    int n = clip->frame_count;
    for (int f = 0; f < n; f++) {
        if (!cub_codec_is_kept(f, n)) continue;
        cub_err e = cub_motion_clip_get_frame(clip, f, &pose);
        if (!e) e = cub_motion_forward(clip->skel, &pose, world, NULL);
        if (e) return e;
        for (int k = 0; k < ne; k++)
            targets[f * ne + k] = world[eff[k]];
    }
    for (int k = 0; k < ne; k++)
        restore_vec3(targets + k, ne, n);
    return CUB_OK;
}

cub_err codec_correct(cub_clip *clip, const int *effectors, int effector_count,
                      const uint8_t *flags, cub_vec3 *targets)
{
    int n = clip->frame_count;
    if (effector_count == 0) return CUB_OK;
    cub_err e = make_targets(clip, effectors, effector_count, targets);
    cub_pose pose;
    for (int f = 0; f < n && !e; f++) {
        if (cub_codec_is_kept(f, n)) continue;
        e = cub_motion_clip_get_frame(clip, f, &pose);
        for (int k = 0; k < effector_count && !e; k++)
            if (flag_on(flags, f, k, effector_count))
                e = cub_codec_ccd(clip->skel, &pose, effectors[k], targets[f * effector_count + k]);
        if (!e) e = cub_motion_clip_set_frame(clip, f, &pose);
    }
    return e;
}

uint32_t codec_crc32(const uint8_t *p, size_t len)
{
    uint32_t crc = 0xFFFFFFFFu;
    for (size_t i = 0; i < len; i++) {
        crc ^= p[i];
        for (int b = 0; b < 8; b++)
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

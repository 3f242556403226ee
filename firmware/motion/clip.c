/* motion: clips (frame data in a caller's buffer), sampling at any time,
 * pose blending and the float view for the renderer. */
#include <stdint.h>
#include <string.h>

#include "cub/motion.h"

static size_t align8(size_t n)
{
    return (n + 7) & ~(size_t)7;
}

static int joint_count_ok(int n)
{
    return n >= 1 && n <= CUB_MOTION_MAX_JOINTS;
}

size_t cub_motion_clip_mem_size(int joint_count, int frame_count, int with_trans)
{
    if (!joint_count_ok(joint_count) || frame_count < 1) return 0;
    size_t per_frame = sizeof(cub_vec3) + (size_t)joint_count * sizeof(cub_quat) +
                       (with_trans ? (size_t)joint_count * sizeof(cub_vec3) : 0);
    /* Three sections, each padded to 8, plus 7 bytes to align the start. */
    if ((size_t)frame_count > (SIZE_MAX - 64) / per_frame) return 0;
    return (size_t)frame_count * per_frame + 3 * 7 + 7;
}

/* Frame f of a clip as the rest pose. */
static void set_rest_frame(cub_clip *clip, int f)
{
    const cub_skeleton *skel = clip->skel;
    int n = skel->joint_count;
    clip->root_mm[f] = (cub_vec3){0, 0, 0};
    for (int i = 0; i < n; i++) {
        clip->rot[(size_t)f * n + i] = cub_fx_quat_identity();
        if (clip->trans_mm) clip->trans_mm[(size_t)f * n + i] = skel->joints[i].offset_mm;
    }
}

cub_err cub_motion_clip_init(cub_clip *clip, const cub_skeleton *skel, int frame_count,
                             uint32_t frame_ns, int with_trans, void *mem, size_t mem_size)
{
    if (!clip || !skel || !mem || frame_count < 1 || frame_ns == 0) return CUB_ERR_ARG;
    cub_err e = cub_motion_skeleton_validate(skel);
    if (e) return e;
    size_t need = cub_motion_clip_mem_size(skel->joint_count, frame_count, with_trans);
    if (need == 0) return CUB_ERR_ARG;
    if (mem_size < need) return CUB_ERR_NOMEM;
    size_t n = (size_t)skel->joint_count, frames = (size_t)frame_count;
    uintptr_t p = ((uintptr_t)mem + 7) & ~(uintptr_t)7;
    memset(clip, 0, sizeof *clip);
    clip->skel = skel;
    clip->frame_count = frame_count;
    clip->frame_ns = frame_ns;
    clip->rot = (cub_quat *)p;
    p += align8(frames * n * sizeof(cub_quat));
    clip->root_mm = (cub_vec3 *)p;
    p += align8(frames * sizeof(cub_vec3));
    clip->trans_mm = with_trans ? (cub_vec3 *)p : NULL;
    for (int f = 0; f < frame_count; f++)
        set_rest_frame(clip, f);
    return CUB_OK;
}

static int clip_ok(const cub_clip *clip)
{
    return clip && clip->skel && joint_count_ok(clip->skel->joint_count) &&
           clip->frame_count >= 1 && clip->frame_ns > 0 && clip->rot && clip->root_mm;
}

cub_err cub_motion_clip_get_frame(const cub_clip *clip, int frame, cub_pose *out)
{
    if (!clip_ok(clip) || !out) return CUB_ERR_ARG;
    if (frame < 0 || frame >= clip->frame_count) return CUB_ERR_RANGE;
    int n = clip->skel->joint_count;
    size_t base = (size_t)frame * n;
    out->joint_count = n;
    out->root_mm = clip->root_mm[frame];
    out->has_trans = clip->trans_mm != NULL;
    memcpy(out->rot, &clip->rot[base], (size_t)n * sizeof(cub_quat));
    for (int i = 0; i < n; i++)
        out->trans_mm[i] =
            clip->trans_mm ? clip->trans_mm[base + i] : clip->skel->joints[i].offset_mm;
    return CUB_OK;
}

cub_err cub_motion_clip_set_frame(cub_clip *clip, int frame, const cub_pose *pose)
{
    if (!clip_ok(clip) || !pose) return CUB_ERR_ARG;
    if (frame < 0 || frame >= clip->frame_count) return CUB_ERR_RANGE;
    int n = clip->skel->joint_count;
    /* A clip without translations cannot keep a pose's: refuse rather than
     * drop them silently. */
    if (pose->joint_count != n || (pose->has_trans && !clip->trans_mm)) return CUB_ERR_ARG;
    size_t base = (size_t)frame * n;
    clip->root_mm[frame] = pose->root_mm;
    memcpy(&clip->rot[base], pose->rot, (size_t)n * sizeof(cub_quat));
    if (clip->trans_mm)
        for (int i = 0; i < n; i++)
            clip->trans_mm[base + i] =
                pose->has_trans ? pose->trans_mm[i] : clip->skel->joints[i].offset_mm;
    return CUB_OK;
}

int64_t cub_motion_clip_duration_us(const cub_clip *clip)
{
    if (!clip_ok(clip)) return 0;
    /* (frames - 1) * period < 2^63; rounded up so sampling at the duration
     * gives the last frame exactly. */
    uint64_t end_ns = (uint64_t)(clip->frame_count - 1) * clip->frame_ns;
    return (int64_t)((end_ns + 999) / 1000);
}

/* (a * b) mod m for a < m < 2^63, by doubling: nothing overflows. */
static uint64_t mul_mod(uint64_t a, uint64_t b, uint64_t m)
{
    uint64_t r = 0;
    for (; b != 0; b >>= 1) {
        if (b & 1) {
            r += a;
            if (r >= m) r -= m;
        }
        a <<= 1;
        if (a >= m) a -= m;
    }
    return r;
}

/* Where t_us falls: frame f0, the next frame f1 and the fraction between. */
static void locate(const cub_clip *clip, int64_t t_us, cub_motion_wrap wrap, int *f0, int *f1,
                   cub_q16 *frac)
{
    const uint64_t ns = clip->frame_ns;
    const int last = clip->frame_count - 1;
    uint64_t t_ns;
    if (wrap == CUB_MOTION_LOOP) {
        /* A loop of n frames lasts n periods: the last frame blends back to
         * the first. Reduce t modulo the loop before scaling to ns. */
        const uint64_t loop_ns = (uint64_t)clip->frame_count * ns; /* < 2^63 */
        int64_t r = t_us % (int64_t)loop_ns;
        if (r < 0) r += (int64_t)loop_ns;
        t_ns = mul_mod((uint64_t)r, 1000, loop_ns);
    } else {
        const uint64_t end_ns = (uint64_t)last * ns;
        if (t_us <= 0 || (uint64_t)t_us >= (end_ns + 999) / 1000) {
            *f0 = *f1 = t_us <= 0 ? 0 : last;
            *frac = 0;
            return;
        }
        t_ns = (uint64_t)t_us * 1000; /* < end_ns + 1000 */
    }
    uint64_t f = t_ns / ns, rem = t_ns % ns;
    *f0 = (int)f;
    *f1 = (int)f == last ? 0 : (int)f + 1;
    *frac = (cub_q16)((rem << 16) / ns); /* rem < 2^32 */
}

cub_err cub_motion_sample(const cub_clip *clip, int64_t t_us, cub_motion_wrap wrap, cub_pose *out)
{
    if (!clip_ok(clip) || !out) return CUB_ERR_ARG;
    if (wrap != CUB_MOTION_CLAMP && wrap != CUB_MOTION_LOOP) return CUB_ERR_ARG;
    int f0, f1;
    cub_q16 t;
    locate(clip, t_us, wrap, &f0, &f1, &t);
    cub_err e = cub_motion_clip_get_frame(clip, f0, out);
    if (e || t == 0) return e; /* exactly on a frame: that frame, bit for bit */
    int n = clip->skel->joint_count;
    size_t b = (size_t)f1 * n;
    out->root_mm = cub_fx_vec3_lerp(out->root_mm, clip->root_mm[f1], t);
    for (int i = 0; i < n; i++) {
        out->rot[i] = cub_fx_quat_nlerp(out->rot[i], clip->rot[b + i], t);
        if (clip->trans_mm)
            out->trans_mm[i] = cub_fx_vec3_lerp(out->trans_mm[i], clip->trans_mm[b + i], t);
    }
    return CUB_OK;
}

cub_err cub_motion_pose_blend(const cub_pose *a, const cub_pose *b, cub_q16 t, cub_pose *out)
{
    if (!a || !b || !out) return CUB_ERR_ARG;
    int n = a->joint_count;
    if (!joint_count_ok(n) || b->joint_count != n || a->has_trans != b->has_trans)
        return CUB_ERR_ARG;
    t = cub_fx_clamp(t, 0, CUB_Q16_ONE);
    /* Element by element, reading before writing: out may be a or b. */
    out->joint_count = n;
    out->has_trans = a->has_trans;
    out->root_mm = cub_fx_vec3_lerp(a->root_mm, b->root_mm, t);
    for (int i = 0; i < n; i++) {
        out->rot[i] = cub_fx_quat_nlerp(a->rot[i], b->rot[i], t);
        out->trans_mm[i] = cub_fx_vec3_lerp(a->trans_mm[i], b->trans_mm[i], t);
    }
    return CUB_OK;
}

void cub_motion_world_to_float(const cub_vec3 *world_mm, int joint_count, float *out_xyz)
{
    if (!world_mm || !out_xyz) return;
    for (int i = 0; i < joint_count; i++) {
        out_xyz[3 * i + 0] = (float)world_mm[i].x / 65536.0f;
        out_xyz[3 * i + 1] = (float)world_mm[i].y / 65536.0f;
        out_xyz[3 * i + 2] = (float)world_mm[i].z / 65536.0f;
    }
}

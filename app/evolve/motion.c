/* evolve motions: clips in doubles, forward kinematics, back to a clip. */
#include <stdlib.h>
#include <string.h>

#include "cub/evolve.h"

cub_err cub_evolve_motion_alloc(const cub_skeleton *skel, int frames, double fps,
                                cub_evolve_motion *out)
{
    memset(out, 0, sizeof(*out));
    if (!skel || skel->joint_count < 1 || frames < 1 || !(fps > 0)) return CUB_ERR_ARG;
    out->skel = *skel;
    out->frames = frames;
    out->fps = fps;
    out->root_mm = calloc((size_t)frames, sizeof(cub_dv3));
    out->rot = malloc((size_t)frames * (size_t)skel->joint_count * sizeof(cub_dq));
    if (!out->root_mm || !out->rot) {
        cub_evolve_motion_free(out);
        return CUB_ERR_NOMEM;
    }
    for (size_t i = 0; i < (size_t)frames * (size_t)skel->joint_count; i++)
        out->rot[i] = cub_dq_identity();
    return CUB_OK;
}

void cub_evolve_motion_free(cub_evolve_motion *m)
{
    if (!m) return;
    free(m->root_mm);
    free(m->rot);
    m->root_mm = NULL;
    m->rot = NULL;
    m->frames = 0;
}

cub_err cub_evolve_from_clip(const cub_clip *clip, double fps, cub_evolve_motion *out)
{
    if (!clip || !clip->skel || clip->frame_count < 1 || clip->frame_ns == 0) return CUB_ERR_ARG;
    double own = 1e9 / clip->frame_ns;
    if (!(fps > 0)) fps = own;
    double seconds = (clip->frame_count - 1) / own;
    /* + 1e-3: frame_ns is rounded (33333333 ns at 30 fps), and a clip read
     * back at its own rate must keep its last frame */
    int frames = 1 + (int)(seconds * fps + 1e-3);
    cub_err err = cub_evolve_motion_alloc(clip->skel, frames, fps, out);
    if (err) return err;
    static cub_pose pose; /* large; offline, one thread */
    for (int f = 0; f < frames; f++) {
        int64_t t_us = (int64_t)(f * 1e6 / fps + 0.5);
        cub_motion_sample(clip, t_us, CUB_MOTION_CLAMP, &pose);
        out->root_mm[f] = cub_dv3_from_fx(pose.root_mm);
        for (int j = 0; j < out->skel.joint_count; j++)
            *cub_evolve_rot(out, f, j) = cub_dq_from_fx(pose.rot[j]);
    }
    return CUB_OK;
}

void cub_evolve_forward(const cub_evolve_motion *m, int f, cub_dv3 *world)
{
    cub_dq wrot[CUB_EVOLVE_MAX_JOINTS];
    for (int j = 0; j < m->skel.joint_count; j++) {
        int p = m->skel.joints[j].parent;
        cub_dq r = *cub_evolve_rot(m, f, j);
        if (p < 0) {
            world[j] = m->root_mm[f];
            wrot[j] = r;
            continue;
        }
        cub_dv3 off = cub_dv3_from_fx(m->skel.joints[j].offset_mm);
        world[j] = cub_dv3_add(world[p], cub_dq_rotate(wrot[p], off));
        wrot[j] = cub_dq_mul(wrot[p], r);
    }
}

cub_err cub_evolve_to_io(const cub_evolve_motion *m, double unit_mm, cub_io_motion *out)
{
    memset(out, 0, sizeof(*out));
    out->skel = m->skel;
    out->unit_mm = unit_mm > 0 ? unit_mm : 10.0;
    int n = m->skel.joint_count;
    size_t size = cub_motion_clip_mem_size(n, m->frames, 0);
    out->frame_mem = malloc(size);
    if (!out->frame_mem) return CUB_ERR_NOMEM;
    uint32_t ns = (uint32_t)(1e9 / m->fps + 0.5);
    cub_err err =
        cub_motion_clip_init(&out->clip, &out->skel, m->frames, ns, 0, out->frame_mem, size);
    if (err) return err;
    for (int f = 0; f < m->frames; f++) {
        out->clip.root_mm[f] = cub_dv3_to_fx(m->root_mm[f]);
        for (int j = 0; j < n; j++)
            out->clip.rot[(size_t)f * (size_t)n + (size_t)j] =
                cub_dq_to_fx(*cub_evolve_rot(m, f, j));
    }
    for (int j = 0; j < n; j++) {
        if (m->skel.joints[j].is_end_site) continue;
        int root = j == 0;
        out->channels[j].count = (unsigned char)(root ? 6 : 3);
        out->channels[j].has_pos = (unsigned char)root;
        memcpy(out->channels[j].rot_order, "ZXY", 4);
        memcpy(out->channels[j].pos_order, root ? "XYZ" : "", root ? 4 : 1);
    }
    return CUB_OK;
}

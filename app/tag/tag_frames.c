/* tag_frames — what tagging measures on each frame: the fuzzy features and
 * crisp class (firmware/fuzzy), the head's angular speed relative to the
 * chest (step 2's exclusion rule) and how much the body moves (thinning
 * keeps the stillest frame of a run). Integer only, like the firmware, so
 * the tags are the same on every machine. */
#include <stdlib.h>
#include <string.h>

#include "tag_internal.h"

/* Central differences span about this long, so that 120 fps mocap jitter
 * does not read as head motion. */
#define SPAN_NS 66000000LL

static cub_err map_one(const cub_skeleton *from, int16_t j, const cub_skeleton *to, int16_t *out,
                       cub_diag *diag)
{
    if (j < 0) {
        *out = -1;
        return CUB_OK;
    }
    if (j >= from->joint_count) return CUB_ERR_ARG;
    int k = cub_motion_skeleton_find(to, from->joints[j].name);
    if (k < 0) {
        if (diag)
            snprintf(diag->msg, sizeof diag->msg,
                     "the library's skeleton has no joint '%s' (the character's features read it)",
                     from->joints[j].name);
        return CUB_ERR_FORMAT;
    }
    *out = (int16_t)k;
    return CUB_OK;
}

cub_err cub_tag_map_body(const cub_skeleton *from, const cub_fuzzy_body *body,
                         const cub_skeleton *to, cub_fuzzy_body *out, cub_diag *diag)
{
    if (!from || !body || !to || !out) return CUB_ERR_ARG;
    cub_fuzzy_body b = *body;
    const int16_t *src[] = {
        &body->hip_centre,  &body->spine,       &body->shoulder_centre, &body->head,
        &body->shoulder[0], &body->shoulder[1], &body->elbow[0],        &body->elbow[1],
        &body->wrist[0],    &body->wrist[1],    &body->hip[0],          &body->hip[1],
        &body->knee[0],     &body->knee[1],     &body->ankle[0],        &body->ankle[1]};
    int16_t *dst[] = {&b.hip_centre,  &b.spine,       &b.shoulder_centre, &b.head,
                      &b.shoulder[0], &b.shoulder[1], &b.elbow[0],        &b.elbow[1],
                      &b.wrist[0],    &b.wrist[1],    &b.hip[0],          &b.hip[1],
                      &b.knee[0],     &b.knee[1],     &b.ankle[0],        &b.ankle[1]};
    for (size_t i = 0; i < sizeof src / sizeof *src; i++) {
        cub_err e = map_one(from, *src[i], to, dst[i], diag);
        if (e) return e;
    }
    *out = b;
    return CUB_OK;
}

/* The head's rotation in the frame of the chest: the joint above the neck
 * base, so that bending the neck counts as head motion too. */
static cub_quat head_in_chest(const cub_skeleton *skel, const cub_fuzzy_body *body,
                              const cub_quat *world_rot)
{
    int ref = body->shoulder_centre;
    if (skel->joints[ref].parent >= 0) ref = skel->joints[ref].parent;
    return cub_fx_quat_mul(cub_fx_quat_conj(world_rot[ref]), world_rot[body->head]);
}

/* Degrees per second of turning by `angle_rad` over `frames` periods. */
static cub_q16 deg_per_s(cub_q16 angle_rad, int frames, uint32_t frame_ns)
{
    int64_t deg_q16 = (int64_t)angle_rad * 180 * 65536 / CUB_Q16_PI;
    int64_t dps = deg_q16 * 1000000000LL / ((int64_t)frames * frame_ns);
    return dps > CUB_Q16_MAX ? CUB_Q16_MAX : (cub_q16)dps;
}

/* Summed joint displacement (relative to the root) between two frames. */
static cub_q16 body_motion(const cub_vec3 *a, const cub_vec3 *b, int n)
{
    int64_t sum = 0;
    for (int j = 1; j < n; j++) {
        cub_vec3 da = cub_fx_vec3_sub(a[j], a[0]), db = cub_fx_vec3_sub(b[j], b[0]);
        sum += cub_fx_vec3_length(cub_fx_vec3_sub(da, db));
    }
    return sum > CUB_Q16_MAX ? CUB_Q16_MAX : (cub_q16)sum;
}

static int body_fits(const cub_fuzzy_body *b, int n)
{
    const int16_t *need[] = {&b->hip_centre, &b->shoulder_centre, &b->head};
    for (size_t i = 0; i < sizeof need / sizeof *need; i++)
        if (*need[i] < 0 || *need[i] >= n) return 0;
    return 1;
}

cub_err cub_tag_analyse_clip(const cub_clip *clip, const cub_fuzzy_body *body, cub_tag_frame *out)
{
    if (!clip || !clip->skel || !body || !out || clip->frame_count < 1 || clip->frame_ns == 0)
        return CUB_ERR_ARG;
    const cub_skeleton *skel = clip->skel;
    int n = skel->joint_count, frames = clip->frame_count;
    if (!body_fits(body, n)) return CUB_ERR_ARG;
    cub_pose *pose = malloc(sizeof *pose);
    cub_vec3 *world = malloc(sizeof *world * (size_t)n * (size_t)frames);
    cub_quat *rot = malloc(sizeof *rot * (size_t)n);
    cub_quat *head = malloc(sizeof *head * (size_t)frames);
    cub_err e = pose && world && rot && head ? CUB_OK : CUB_ERR_NOMEM;
    for (int f = 0; !e && f < frames; f++) {
        cub_vec3 *w = world + (size_t)f * (size_t)n;
        e = cub_motion_clip_get_frame(clip, f, pose);
        if (!e) e = cub_motion_forward(skel, pose, w, rot);
        if (!e) e = cub_fuzzy_features(body, w, n, &out[f].fuzzy);
        if (!e) {
            out[f].crisp_class = cub_fuzzy_crisp_class(&out[f].fuzzy);
            head[f] = head_in_chest(skel, body, rot);
        }
    }
    int64_t half = (SPAN_NS / 2 + clip->frame_ns / 2) / clip->frame_ns;
    int h = half < 1 ? 1 : half > 64 ? 64 : (int)half;
    for (int f = 0; !e && f < frames; f++) {
        int lo = f - h < 0 ? 0 : f - h, hi = f + h >= frames ? frames - 1 : f + h;
        if (lo == hi) {
            out[f].head_dps = 0;
            out[f].motion_mm = 0;
            continue;
        }
        cub_quat step = cub_fx_quat_mul(cub_fx_quat_conj(head[lo]), head[hi]);
        out[f].head_dps = deg_per_s(cub_fx_quat_angle(step), hi - lo, clip->frame_ns);
        /* Per frame period, so the clip's ends (shorter spans) are not favoured. */
        out[f].motion_mm =
            body_motion(world + (size_t)lo * (size_t)n, world + (size_t)hi * (size_t)n, n) /
            (hi - lo);
    }
    free(pose);
    free(world);
    free(rot);
    free(head);
    return e;
}

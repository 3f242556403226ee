/* bridge: the player — plays the coach's clip, carries out planned switches
 * at their exact frame and reports them, and smooths the cut. Time moves in
 * integer nanosecond arithmetic with the remainder kept, so between
 * switches any split of the same total time lands on the same position
 * (across a switch, within 1/65536 frame). */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "bridge_internal.h"

/* The velocity a cut carries over fades within this many frames (or the
 * blend, if shorter): long enough that the first frame after the cut moves
 * mostly as the old clip did, short enough not to overshoot far. */
#define VEL_FRAMES_MAX 10

static int speed_ok(cub_q16 s)
{
    return s >= CUB_BRIDGE_SPEED_MIN_Q16 && s <= CUB_BRIDGE_SPEED_MAX_Q16;
}

static cub_q16 speed_or_default(cub_q16 s)
{
    return s == 0 ? CUB_Q16_ONE : s;
}

static const cub_clip *clip_of(const cub_bridge_player *p, int c)
{
    return &p->desc.table->clips[c].clip;
}

size_t cub_bridge_player_mem_size(const cub_bridge_player_desc *desc)
{
    if (!desc) return 0;
    return cub_bridge_plan_work_size(desc->table) + cub_bridge_legs_mem_size(desc->table);
}

cub_err cub_bridge_player_init(cub_bridge_player *p, const cub_bridge_player_desc *desc,
                               void *mem, size_t mem_size)
{
    if (!p || !desc || !desc->table || !desc->table->finished || !mem) return CUB_ERR_ARG;
    if (desc->blend_frames < 0 || desc->blend_frames > CUB_BRIDGE_MAX_BLEND_FRAMES ||
        desc->window_frames < 0 || desc->wait_cost_mm < 0 || desc->blend_speed_mm < 0 ||
        desc->smooth < CUB_BRIDGE_SMOOTH_INERTIAL ||
        desc->smooth > CUB_BRIDGE_SMOOTH_CROSSFADE || desc->via_tween < 0 || desc->via_tween > 1 ||
        desc->no_legs < 0 || desc->no_legs > 1 || desc->no_routes < 0 || desc->no_routes > 1)
        return CUB_ERR_ARG;
    if (mem_size < cub_bridge_player_mem_size(desc)) return CUB_ERR_NOMEM;
    memset(p, 0, sizeof *p);
    p->desc = *desc;
    if (!p->desc.blend_frames) p->desc.blend_frames = CUB_BRIDGE_BLEND_FRAMES;
    if (!p->desc.window_frames) p->desc.window_frames = CUB_BRIDGE_WINDOW_FRAMES;
    if (!p->desc.blend_speed_mm) p->desc.blend_speed_mm = CUB_BRIDGE_BLEND_SPEED_MM;
    p->work = mem;
    p->work_size = cub_bridge_plan_work_size(desc->table);
    p->legs.speed_mm = p->desc.blend_speed_mm;
    p->legs.min_frames = p->desc.blend_frames;
    /* The contacts are marked either way (bench-bridge measures slides
     * with them); the leg phase runs only on inertial cuts. */
    p->legs.enabled = !desc->no_legs && desc->smooth == CUB_BRIDGE_SMOOTH_INERTIAL;
    cub_bridge_legs_init(&p->legs, desc->table, (uint8_t *)mem + p->work_size);
    p->speed_q16 = CUB_Q16_ONE;
    p->clip = -1;
    return CUB_OK;
}

cub_err cub_bridge_player_start(cub_bridge_player *p, int clip, int frame, cub_q16 speed_q16,
                                int loop)
{
    speed_q16 = speed_or_default(speed_q16);
    if (!p || !p->desc.table || clip < 0 || clip >= p->desc.table->desc.clip_count ||
        !speed_ok(speed_q16))
        return CUB_ERR_ARG;
    if (frame < 0 || frame >= clip_of(p, clip)->frame_count) return CUB_ERR_ARG;
    p->clip = clip;
    p->loop = loop != 0;
    p->pos_q16 = (int64_t)frame << 16;
    p->speed_q16 = speed_q16;
    p->rem = 0;
    p->done_sent = 0;
    p->plan.step_count = 0;
    p->next_step = 0;
    p->blending = 0;
    return CUB_OK;
}

int cub_bridge_player_pending(const cub_bridge_player *p)
{
    return p && p->next_step < p->plan.step_count;
}

cub_err cub_bridge_player_request(cub_bridge_player *p, int clip, cub_q16 speed_q16, int loop,
                                  cub_bridge_plan *out)
{
    speed_q16 = speed_or_default(speed_q16);
    if (out) memset(out, 0, sizeof *out);
    if (!p || p->clip < 0 || !speed_ok(speed_q16)) return CUB_ERR_ARG;
    if (clip < 0 || clip >= p->desc.table->desc.clip_count) return CUB_ERR_ARG;
    cub_bridge_query q = {p->clip, p->pos_q16, p->loop, clip, p->desc.window_frames,
                          p->desc.wait_cost_mm, p->desc.start_frames, p->desc.reach_frames,
                          p->desc.strict, p->desc.via_tween, p->desc.no_routes,
                          p->desc.direct_only, p->desc.on_clock, p->desc.clock_q16};
    cub_bridge_plan plan;
    cub_err e = cub_bridge_plan_switch(p->desc.table, &q, &plan, p->work, p->work_size);
    if (e) return e;
    p->plan = plan;
    p->next_step = 0;
    p->want_speed_q16 = speed_q16;
    p->want_loop = loop != 0;
    if (out) *out = plan;
    return CUB_OK;
}

cub_err cub_bridge_player_preview(cub_bridge_player *p, const cub_bridge_query *q,
                                  cub_bridge_plan *out)
{
    if (!p || !q || !out) return CUB_ERR_ARG;
    cub_bridge_query here = *q;
    if (here.from_clip < 0) {
        if (p->clip < 0) return CUB_ERR_ARG;
        here.from_clip = p->clip;
        here.pos_q16 = p->pos_q16;
        here.from_loops = p->loop;
    }
    if (!here.window_frames) here.window_frames = p->desc.window_frames;
    if (!here.wait_cost_mm) here.wait_cost_mm = p->desc.wait_cost_mm;
    here.strict |= p->desc.strict;
    here.via_tween |= p->desc.via_tween;
    here.no_routes |= p->desc.no_routes;
    here.direct_only |= p->desc.direct_only;
    return cub_bridge_plan_switch(p->desc.table, &here, out, p->work, p->work_size);
}

cub_err cub_bridge_player_set_speed(cub_bridge_player *p, cub_q16 speed_q16)
{
    if (!p || !speed_ok(speed_q16)) return CUB_ERR_ARG;
    p->speed_q16 = speed_q16;
    return CUB_OK;
}

/* ---- sampling ------------------------------------------------------- */

/* The pose of clip c at unwrapped position pos (Q16 frames): a looping clip
 * joins its last frame to its first, one that does not holds its ends. */
static cub_err sample(const cub_clip *clip, int64_t pos_q16, int loop, cub_pose *tmp,
                      cub_pose *out)
{
    int n = clip->frame_count;
    int64_t f = pos_q16 >> 16;
    cub_q16 frac = (cub_q16)(pos_q16 & 0xFFFF);
    int f0, f1;
    if (loop) {
        /* The pass's last frame holds; the next pass starts with a blend
         * (see wrap in advance): a clip cut from a capture does not join
         * its first frame. */
        f0 = (int)(f % n);
        f1 = f0 + 1 < n ? f0 + 1 : f0;
    } else {
        f0 = f >= n - 1 ? n - 1 : (int)f;
        f1 = f0 + 1 < n ? f0 + 1 : f0;
        if (f >= n - 1) frac = 0;
    }
    cub_err e = cub_motion_clip_get_frame(clip, f0, out);
    if (e || frac == 0 || f1 == f0) return e;
    e = cub_motion_clip_get_frame(clip, f1, tmp);
    return e ? e : cub_motion_pose_blend(out, tmp, frac, out);
}

cub_err cub_bridge_player_raw_pose(const cub_bridge_player *p, cub_pose *out)
{
    if (!p || !out || p->clip < 0) return CUB_ERR_ARG;
    cub_bridge_player *mp = (cub_bridge_player *)p; /* scratch only */
    return sample(clip_of(p, p->clip), p->pos_q16, p->loop, &mp->scratch[1], out);
}

/* 1 - smoothstep(s): 1 at s = 0, 0 at s >= 1, flat at both ends. */
static cub_q16 fade_weight(int64_t progress_q16, int frames)
{
    if (progress_q16 <= 0) return CUB_Q16_ONE;
    if (progress_q16 >= (int64_t)frames << 16) return 0;
    cub_q16 s = (cub_q16)(progress_q16 / frames);
    cub_q16 s2 = cub_fx_mul(s, s);
    return CUB_Q16_ONE - (3 * s2 - 2 * cub_fx_mul(s2, s));
}

/* t (1 - t/T)^2, in frames: 0 at t = 0 but rising at slope 1 (so the
 * offset moves with the velocity it carries over), back to 0 and flat at
 * t = T. Q16.16 frames in and out. */
static cub_q16 vel_weight(int64_t progress_q16, int frames)
{
    if (progress_q16 <= 0 || progress_q16 >= (int64_t)frames << 16) return 0;
    cub_q16 rest = CUB_Q16_ONE - (cub_q16)(progress_q16 / frames);
    return cub_fx_mul((cub_q16)progress_q16, cub_fx_mul(rest, rest));
}

/* Apply the inertialization offset onto a raw pose: the joints' with
 * weight w, the root's drift over the floor with its own weight w_xz, and
 * the carried-over velocity for v frames. */
static void apply_offset(const cub_bridge_player *p, cub_q16 w, cub_q16 w_xz, cub_q16 v,
                         cub_pose *pose)
{
    cub_quat id = cub_fx_quat_identity();
    for (int j = 0; j < pose->joint_count; j++) {
        cub_quat o = cub_fx_quat_nlerp(id, p->off_rot[j], w);
        if (v && p->vel_angle[j])
            o = cub_fx_quat_mul(
                cub_fx_quat_from_axis_angle(p->vel_axis[j], cub_fx_mul(p->vel_angle[j], v)), o);
        pose->rot[j] = cub_fx_quat_normalize(cub_fx_quat_mul(o, pose->rot[j]));
    }
    pose->root_mm.x += cub_fx_mul(p->off_root_mm.x, w_xz) + cub_fx_mul(p->vel_root_mm.x, v);
    pose->root_mm.y += cub_fx_mul(p->off_root_mm.y, w) + cub_fx_mul(p->vel_root_mm.y, v);
    pose->root_mm.z += cub_fx_mul(p->off_root_mm.z, w_xz) + cub_fx_mul(p->vel_root_mm.z, v);
}

cub_err cub_bridge_player_pose(cub_bridge_player *p, cub_pose *out)
{
    cub_err e = cub_bridge_player_raw_pose(p, out);
    if (e || !p->blending) return e;
    int64_t progress = p->pos_q16 - p->blend_from_q16;
    cub_q16 w = fade_weight(progress, p->blend_len);
    cub_q16 w_xz = fade_weight(progress, p->root_len);
    if (w == 0 && w_xz == 0 && cub_bridge_legs_left_q16(&p->legs, p->pos_q16) == 0) {
        p->blending = 0;
        return CUB_OK;
    }
    if (p->desc.smooth == CUB_BRIDGE_SMOOTH_INERTIAL) {
        if (p->legs.on) p->legs.raw = *out;
        apply_offset(p, w, w_xz, vel_weight(progress, p->vel_len), out);
        cub_bridge_legs_apply(&p->legs, p->desc.table->desc.skel, &p->legs.raw, p->pos_q16, out);
        return CUB_OK;
    }
    e = sample(clip_of(p, p->old_clip), p->old_pos_q16, p->old_loop, &p->scratch[1],
               &p->scratch[0]);
    return e ? e : cub_motion_pose_blend(out, &p->scratch[0], w, out);
}

/* Frames a blend needs so that fading an offset of dist_mm adds at most
 * blend_speed_mm per frame (smoothstep's steepest slope is 1.5 / frames). */
static int blend_length(const cub_bridge_player *p, cub_q16 dist_mm, int at_least)
{
    int64_t n = ((int64_t)dist_mm * 3 / 2 + p->desc.blend_speed_mm - 1) / p->desc.blend_speed_mm;
    if (n < at_least) n = at_least;
    return n > CUB_BRIDGE_MAX_BLEND_FRAMES ? CUB_BRIDGE_MAX_BLEND_FRAMES : (int)n;
}

/* The rotation q as an axis (any length, Q2.30 scale) and an angle in
 * [0, pi]: q and -q are the same rotation. */
static void axis_angle(cub_quat q, cub_vec3 *axis, cub_q16 *angle)
{
    int32_t sign = q.w < 0 ? -1 : 1;
    *axis = (cub_vec3){sign * q.x, sign * q.y, sign * q.z};
    *angle = cub_fx_quat_angle(q);
}

/* The velocity the offset carries over at a cut, per frame of the new
 * clip: what the old motion did over its last frame (scaled by the speed
 * ratio) less what the new clip does over its first, seen through the
 * offset. With it the body keeps moving as it moved when the clips change,
 * then takes up the new clip's motion over vel_len frames. */
static void carry_velocity(cub_bridge_player *p, const cub_pose *src_prev, const cub_pose *src,
                           const cub_pose *dst, const cub_pose *dst_next, cub_q16 ratio_q16)
{
    for (int j = 0; j < dst->joint_count; j++) {
        cub_quat old_step = cub_fx_quat_mul(src->rot[j], cub_fx_quat_conj(src_prev->rot[j]));
        if (ratio_q16 != CUB_Q16_ONE) {
            cub_vec3 ax;
            cub_q16 ang;
            axis_angle(old_step, &ax, &ang);
            old_step = cub_fx_quat_from_axis_angle(ax, cub_fx_mul(ang, ratio_q16));
        }
        cub_quat new_step = cub_fx_quat_mul(dst_next->rot[j], cub_fx_quat_conj(dst->rot[j]));
        cub_quat seen = cub_fx_quat_mul(cub_fx_quat_mul(p->off_rot[j], new_step),
                                        cub_fx_quat_conj(p->off_rot[j]));
        cub_quat v = cub_fx_quat_normalize(cub_fx_quat_mul(old_step, cub_fx_quat_conj(seen)));
        axis_angle(v, &p->vel_axis[j], &p->vel_angle[j]);
    }
    cub_vec3 old_root = cub_fx_vec3_scale(cub_fx_vec3_sub(src->root_mm, src_prev->root_mm), ratio_q16);
    p->vel_root_mm = cub_fx_vec3_sub(old_root, cub_fx_vec3_sub(dst_next->root_mm, dst->root_mm));
}

/* How far a joint may travel while the offset fades: each ancestor's
 * rotation offset swings it along an arc of at most angle x distance, and
 * these add up along the chain (a straight-line distance between the two
 * poses can be far shorter: a shoulder and an elbow turning opposite ways
 * swing the paw wide and bring it back). world: the pose at the cut. */
static cub_q16 offset_path_mm(const cub_bridge_player *p, const cub_skeleton *sk,
                              const cub_vec3 *world)
{
    cub_q16 angle[CUB_MOTION_MAX_JOINTS];
    for (int j = 0; j < sk->joint_count; j++)
        angle[j] = cub_fx_quat_angle(p->off_rot[j]);
    int64_t worst = 0;
    for (int j = 0; j < sk->joint_count; j++) {
        int64_t path = 0;
        for (int a = sk->joints[j].parent; a >= 0; a = sk->joints[a].parent)
            path += cub_fx_mul(cub_fx_vec3_length(cub_fx_vec3_sub(world[j], world[a])), angle[a]);
        if (path > worst) worst = path;
    }
    return worst > INT32_MAX ? INT32_MAX : (cub_q16)worst;
}

/* A switch during a leg phase (a chain's next switch): a leg the phase is
 * swinging would carry that swing on through the offset (a free foot
 * leaves from where the offset puts it), flinging it: up to 21 cm a frame
 * on the shipped library. The new phase puts the legs; they carry no
 * velocity. (A wrap keeps it: a travelling loop's legs carry the walk.) */
static void still_legs(cub_bridge_player *p)
{
    const cub_bridge_legs *l = &p->legs;
    for (int s = 0; s < 2; s++) {
        p->vel_angle[l->hip[s]] = p->vel_angle[l->knee[s]] = 0;
        for (int k = 0; k < CUB_BRIDGE_FOOT_JOINTS && l->foot[s][k] >= 0; k++)
            p->vel_angle[l->foot[s][k]] = 0;
    }
}

/* The player's leg phase at a cut (bridge_legs.c) into frame to_frame of
 * to_clip, which starts at from_q16 on its time line. */
static void begin_legs(cub_bridge_player *p, const cub_pose *src, const cub_pose *dst,
                       int64_t src_pos_q16, int to_clip, int to_frame, int64_t from_q16)
{
    int n = clip_of(p, p->clip)->frame_count;
    int64_t f = src_pos_q16 >> 16;
    int src_frame = (int)(p->loop ? f % n : f < n ? f : n - 1);
    int wrap = p->loop && to_clip == p->clip && to_frame == 0 && src_frame == n - 1;
    cub_bridge_cut cut = {src, dst, p->clip, src_frame, to_clip, to_frame, from_q16, wrap, n};
    int stepping = cub_bridge_legs_left_q16(&p->legs, src_pos_q16) > 0;
    cub_bridge_legs_begin(&p->legs, p->desc.table, &cut);
    if (stepping && !wrap && p->legs.on) still_legs(p);
}

/* At a cut (a switch, or a looping clip's new pass): remember what was on
 * screen at position src_pos of the clip playing, and how far frame
 * to_frame of to_clip (at from_q16 on its time line) is from it, so the new
 * clip can start from it; the new clip plays at new_speed_q16. */
static cub_err begin_blend(cub_bridge_player *p, int64_t src_pos_q16, int to_clip, int to_frame,
                           int64_t from_q16, cub_q16 new_speed_q16)
{
    if (p->desc.smooth == CUB_BRIDGE_SMOOTH_NONE) return CUB_OK;
    int64_t saved_pos = p->pos_q16;
    cub_pose *src = &p->scratch[2], *dst = &p->scratch[1];
    cub_pose *src_prev = &p->scratch[3], *dst_next = &p->scratch[4];
    p->pos_q16 = src_pos_q16;
    cub_err e = cub_bridge_player_pose(p, src);
    /* A frame earlier, as it was shown (the pose uses scratch[1]: dst after). */
    p->pos_q16 = src_pos_q16 >= CUB_Q16_ONE ? src_pos_q16 - CUB_Q16_ONE : src_pos_q16;
    if (!e) e = cub_bridge_player_pose(p, src_prev);
    p->pos_q16 = saved_pos;
    const cub_clip *to = clip_of(p, to_clip);
    if (!e) e = cub_motion_clip_get_frame(to, to_frame, dst);
    if (!e)
        e = cub_motion_clip_get_frame(to, to_frame + 1 < to->frame_count ? to_frame + 1 : to_frame,
                                      dst_next);
    if (e) return e;
    /* The body's distance sets the blend's length; the root's drift over
     * the floor gets its own, longer one. */
    const cub_skeleton *sk = p->desc.table->desc.skel;
    if ((e = cub_bridge_body_mm(sk, src, p->body[0])) || (e = cub_bridge_body_mm(sk, dst, p->body[1])))
        return e;
    cub_q16 dist_mm = cub_bridge_shape_dist_mm(p->body[0], p->body[1], sk->joint_count);
    for (int j = 0; j < dst->joint_count; j++)
        p->off_rot[j] = cub_fx_quat_mul(src->rot[j], cub_fx_quat_conj(dst->rot[j]));
    p->off_root_mm = cub_fx_vec3_sub(src->root_mm, dst->root_mm);
    if (p->desc.smooth == CUB_BRIDGE_SMOOTH_INERTIAL) {
        cub_q16 path_mm = offset_path_mm(p, sk, p->body[0]);
        if (path_mm > dist_mm) dist_mm = path_mm;
    }
    p->blend_len = blend_length(p, dist_mm, p->desc.blend_frames);
    cub_vec3 d = cub_fx_vec3_sub(src->root_mm, dst->root_mm);
    d.y = 0;
    p->root_len = blend_length(p, cub_fx_vec3_length(d), p->blend_len);
    p->vel_len = p->blend_len < VEL_FRAMES_MAX ? p->blend_len : VEL_FRAMES_MAX;
    if (p->desc.smooth == CUB_BRIDGE_SMOOTH_CROSSFADE) {
        p->old_clip = p->clip;
        p->old_loop = p->loop;
        p->old_pos_q16 = src_pos_q16;
        p->old_speed_q16 = p->speed_q16;
        return CUB_OK;
    }
    carry_velocity(p, src_prev, src, dst, dst_next, cub_fx_div(p->speed_q16, new_speed_q16));
    begin_legs(p, src, dst, src_pos_q16, to_clip, to_frame, from_q16);
    return CUB_OK;
}

/* ---- time ----------------------------------------------------------- */

/* Microseconds to cover dq Q16 frames of a clip at a speed. */
static int64_t time_us(int64_t dq, uint32_t frame_ns, cub_q16 speed)
{
    return dq * (int64_t)frame_ns / ((int64_t)speed * 1000);
}

/* Q16 frames covered in dt_us, keeping the remainder in *rem. */
static int64_t frames_q16(int64_t dt_us, uint32_t frame_ns, cub_q16 speed, uint64_t *rem)
{
    uint64_t num = (uint64_t)dt_us * 1000u * (uint64_t)speed + *rem;
    *rem = num % frame_ns;
    return (int64_t)(num / frame_ns);
}

static void emit(cub_bridge_event *ev, int max_ev, int *n, const cub_bridge_event *e)
{
    if (*n < max_ev) ev[*n] = *e;
    (*n)++;
}

/* Carry out the next planned step: overshoot (Q16 frames past the switch
 * frame, old clip) carries on into the new clip at the new speed. */
static cub_err do_switch(cub_bridge_player *p, int64_t overshoot_q16)
{
    const cub_bridge_step *s = &p->plan.step[p->next_step++];
    cub_err e = begin_blend(p, s->at_q16, s->to_clip, s->to_frame, (int64_t)s->to_frame << 16,
                            p->want_speed_q16);
    if (e) return e;
    const cub_clip *from = clip_of(p, p->clip), *to = clip_of(p, s->to_clip);
    int last = p->next_step == p->plan.step_count;
    int64_t carry = overshoot_q16 * (int64_t)from->frame_ns / (int64_t)to->frame_ns;
    carry = carry * p->want_speed_q16 / p->speed_q16;
    if (p->desc.smooth == CUB_BRIDGE_SMOOTH_CROSSFADE) p->old_pos_q16 += overshoot_q16;
    p->clip = s->to_clip;
    p->loop = last ? p->want_loop : 0;
    p->speed_q16 = p->want_speed_q16;
    p->pos_q16 = ((int64_t)s->to_frame << 16) + carry;
    p->blend_from_q16 = (int64_t)s->to_frame << 16;
    p->blending = p->desc.smooth != CUB_BRIDGE_SMOOTH_NONE;
    p->rem = 0;
    p->done_sent = 0;
    return CUB_OK;
}

/* A looping clip starts a new pass at mark: a cut from its (held) last
 * frame to its first, smoothed like a switch. */
static cub_err wrap(cub_bridge_player *p, int64_t mark)
{
    if (p->desc.smooth == CUB_BRIDGE_SMOOTH_NONE) return CUB_OK;
    cub_err e = begin_blend(p, mark - 1, p->clip, 0, mark, p->speed_q16);
    if (e) return e;
    p->old_loop = 0; /* a crossfade holds the old pass's last frame */
    p->old_pos_q16 = (int64_t)(clip_of(p, p->clip)->frame_count - 1) << 16;
    p->blend_from_q16 = mark;
    p->blending = 1;
    return CUB_OK;
}

/* The next thing that happens on the current clip, as a position: the
 * planned switch, the end of a clip that does not loop, or the end of a
 * looping clip's pass. INT64_MAX: nothing. */
static int64_t next_mark(const cub_bridge_player *p, int *is_switch)
{
    int n = clip_of(p, p->clip)->frame_count;
    int64_t mark = INT64_MAX;
    *is_switch = 0;
    if (p->loop) {
        mark = ((p->pos_q16 >> 16) / n + 1) * n;
        mark <<= 16;
    } else if (!p->done_sent) {
        mark = (int64_t)(n - 1) << 16;
    }
    if (cub_bridge_player_pending(p) && p->plan.step[p->next_step].at_q16 <= mark) {
        mark = p->plan.step[p->next_step].at_q16;
        *is_switch = 1;
    }
    return mark;
}

cub_err cub_bridge_player_advance(cub_bridge_player *p, int64_t dt_us, cub_bridge_event *ev,
                                  int max_ev, int *n_ev)
{
    if (n_ev) *n_ev = 0;
    if (!p || p->clip < 0 || dt_us < 0 || dt_us > 60000000 || max_ev < 0 || (max_ev && !ev) ||
        !n_ev)
        return CUB_ERR_ARG;
    const cub_clip *c = clip_of(p, p->clip);
    int64_t t_us = 0; /* time at pos, from the start of this call */
    int64_t end = p->pos_q16 + frames_q16(dt_us, c->frame_ns, p->speed_q16, &p->rem);
    if (p->blending && p->desc.smooth == CUB_BRIDGE_SMOOTH_CROSSFADE) {
        uint64_t r = 0;
        p->old_pos_q16 += frames_q16(dt_us, clip_of(p, p->old_clip)->frame_ns,
                                     p->old_speed_q16, &r);
    }
    for (int guard = 0; guard < 4 * CUB_BRIDGE_MAX_STEPS + 64; guard++) {
        int is_switch;
        int64_t mark = next_mark(p, &is_switch);
        if (mark > end) break;
        t_us += time_us(mark - p->pos_q16, c->frame_ns, p->speed_q16);
        if (t_us > dt_us) t_us = dt_us;
        cub_bridge_event e = {.t_us = t_us, .clip = p->clip};
        if (is_switch) {
            e.type = CUB_BRIDGE_EV_SWITCH;
            e.step = p->plan.step[p->next_step];
            cub_err err = do_switch(p, end - mark);
            if (err) return err;
            e.clip = p->clip;
            c = clip_of(p, p->clip);
            end = p->pos_q16;
            p->pos_q16 = (int64_t)e.step.to_frame << 16;
        } else {
            e.type = CUB_BRIDGE_EV_DONE;
            e.looped = p->loop;
            p->done_sent = !p->loop;
            if (p->loop) {
                cub_err err = wrap(p, mark);
                if (err) return err;
            }
            p->pos_q16 = mark;
        }
        emit(ev, max_ev, n_ev, &e);
    }
    /* A clip that does not loop holds its last frame. */
    int64_t last = (int64_t)(c->frame_count - 1) << 16;
    p->pos_q16 = (!p->loop && end > last) ? last : end;
    if (*n_ev > max_ev) *n_ev = max_ev;
    return CUB_OK;
}

cub_err cub_bridge_player_set_start_frames(cub_bridge_player *p, int start_frames)
{
    if (!p || start_frames < 0) return CUB_ERR_ARG;
    p->desc.start_frames = start_frames;
    return CUB_OK;
}

cub_err cub_bridge_player_set_no_routes(cub_bridge_player *p, int no_routes)
{
    if (!p || (no_routes != 0 && no_routes != 1)) return CUB_ERR_ARG;
    p->desc.no_routes = no_routes;
    return CUB_OK;
}

cub_err cub_bridge_player_set_direct_only(cub_bridge_player *p, int direct_only)
{
    if (!p || (direct_only != 0 && direct_only != 1)) return CUB_ERR_ARG;
    p->desc.direct_only = direct_only;
    return CUB_OK;
}

cub_err cub_bridge_player_set_clock(cub_bridge_player *p, int on_clock, int64_t clock_q16)
{
    const int64_t lim = (int64_t)1 << 46;
    if (!p || (on_clock != 0 && on_clock != 1) || clock_q16 <= -lim || clock_q16 >= lim)
        return CUB_ERR_ARG;
    p->desc.on_clock = on_clock;
    p->desc.clock_q16 = clock_q16;
    return CUB_OK;
}

cub_err cub_bridge_player_set_reach_frames(cub_bridge_player *p, int reach_frames)
{
    if (!p || reach_frames < 0) return CUB_ERR_ARG;
    p->desc.reach_frames = reach_frames;
    return CUB_OK;
}

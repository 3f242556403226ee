/* bridge: the table — clips, the fuzzy features of every frame, bridge
 * frames and tag links, laid out once in the caller's memory. */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "bridge_internal.h"

static size_t align8(size_t n)
{
    return (n + 7) & ~(size_t)7;
}

static int desc_ok(const cub_bridge_table_desc *d)
{
    return d && d->skel && d->clip_count >= 1 && d->clip_count <= 4096 &&
           d->frame_total >= d->clip_count && d->bridge_total >= 0 && d->link_total >= 0 &&
           d->bridge_total <= INT16_MAX * 64 && d->skel->joint_count >= 1 &&
           d->skel->joint_count <= CUB_MOTION_MAX_JOINTS;
}

size_t cub_bridge_table_mem_size(const cub_bridge_table_desc *desc)
{
    if (!desc_ok(desc)) return 0;
    size_t n = (size_t)desc->clip_count;
    return align8(n * sizeof(cub_bridge_clip)) +
           align8((size_t)desc->frame_total * sizeof(cub_fuzzy_frame)) +
           align8((size_t)desc->bridge_total * sizeof(int16_t)) +
           align8(n * n * sizeof(cub_bridge_pair)) +
           align8((size_t)desc->link_total * sizeof(cub_bridge_link)) +
           align8((size_t)desc->bridge_total * (size_t)desc->skel->joint_count *
                  sizeof(cub_vec3)) +
           7;
}

cub_err cub_bridge_body_mm(const cub_skeleton *skel, const cub_pose *pose, cub_vec3 *out)
{
    cub_err e = cub_motion_forward(skel, pose, out, NULL);
    if (e) return e;
    for (int j = 0; j < skel->joint_count; j++) {
        out[j].x -= pose->root_mm.x;
        out[j].z -= pose->root_mm.z;
    }
    return CUB_OK;
}

cub_q16 cub_bridge_shape_dist_mm(const cub_vec3 *a, const cub_vec3 *b, int joints)
{
    uint64_t worst = 0;
    for (int j = 0; j < joints; j++) {
        int64_t dx = (int64_t)a[j].x - b[j].x, dy = (int64_t)a[j].y - b[j].y,
                dz = (int64_t)a[j].z - b[j].z;
        uint64_t d2 = (uint64_t)(dx * dx) + (uint64_t)(dy * dy) + (uint64_t)(dz * dz);
        if (d2 > worst) worst = d2;
    }
    uint32_t r = cub_fx_isqrt64(worst);
    return r > INT32_MAX ? INT32_MAX : (cub_q16)r;
}

/* Every joint the features read exists (the check cub_fuzzy_features makes,
 * done once here so a bad body fails at init, not at the first clip). */
static int body_ok(const cub_fuzzy_body *b, int joints)
{
    const int16_t need[] = {b->hip_centre, b->shoulder_centre, b->shoulder[0], b->shoulder[1],
                            b->elbow[0],   b->elbow[1],        b->wrist[0],    b->wrist[1],
                            b->hip[0],     b->hip[1],          b->knee[0],     b->knee[1],
                            b->ankle[0],   b->ankle[1]};
    for (size_t i = 0; i < sizeof need / sizeof *need; i++)
        if (need[i] < 0 || need[i] >= joints) return 0;
    return b->stand_cog_mm > 0;
}

cub_err cub_bridge_table_init(cub_bridge_table *t, const cub_bridge_table_desc *desc, void *mem,
                              size_t mem_size)
{
    if (!t || !mem || !desc_ok(desc)) return CUB_ERR_ARG;
    if (!body_ok(&desc->body, desc->skel->joint_count)) return CUB_ERR_ARG;
    if (mem_size < cub_bridge_table_mem_size(desc)) return CUB_ERR_NOMEM;
    memset(t, 0, sizeof *t);
    t->desc = *desc;
    t->desc.fuzzy = cub_fuzzy_config_defaults(&desc->fuzzy);
    size_t n = (size_t)desc->clip_count;
    uintptr_t p = ((uintptr_t)mem + 7) & ~(uintptr_t)7;
    t->clips = (cub_bridge_clip *)p;
    p += align8(n * sizeof(cub_bridge_clip));
    t->fuzzy = (cub_fuzzy_frame *)p;
    p += align8((size_t)desc->frame_total * sizeof(cub_fuzzy_frame));
    t->bridges = (int16_t *)p;
    p += align8((size_t)desc->bridge_total * sizeof(int16_t));
    t->pairs = (cub_bridge_pair *)p;
    p += align8(n * n * sizeof(cub_bridge_pair));
    t->links = (cub_bridge_link *)p;
    p += align8((size_t)desc->link_total * sizeof(cub_bridge_link));
    t->bridge_body_mm = (cub_vec3 *)p;
    memset(t->clips, 0, n * sizeof(cub_bridge_clip));
    for (size_t i = 0; i < n * n; i++)
        t->pairs[i] = (cub_bridge_pair){0, -1};
    t->tween_clip = -1;
    return CUB_OK;
}

/* The features of every frame of a clip, by forward kinematics. */
static cub_err compute_fuzzy(const cub_bridge_table *t, const cub_clip *clip,
                             cub_fuzzy_frame *out)
{
    static cub_pose pose; /* static: large; the firmware is single-threaded */
    static cub_vec3 world[CUB_MOTION_MAX_JOINTS];
    for (int f = 0; f < clip->frame_count; f++) {
        cub_err e = cub_motion_clip_get_frame(clip, f, &pose);
        if (!e) e = cub_motion_forward(clip->skel, &pose, world, NULL);
        if (!e) e = cub_fuzzy_features(&t->desc.body, world, clip->skel->joint_count, &out[f]);
        if (e) return e;
    }
    return CUB_OK;
}

cub_err cub_bridge_table_add_clip(cub_bridge_table *t, const cub_clip *clip,
                                  const int *bridge_frames, int bridge_count,
                                  const cub_fuzzy_frame *fuzzy)
{
    if (!t || !t->clips || !clip || t->finished || bridge_count < 0) return CUB_ERR_ARG;
    if (bridge_count > 0 && !bridge_frames) return CUB_ERR_ARG;
    if (clip->skel != t->desc.skel || clip->frame_count < 1 || clip->frame_count > INT16_MAX ||
        clip->frame_ns == 0 || !clip->rot || !clip->root_mm)
        return CUB_ERR_ARG;
    if (t->clips_added >= t->desc.clip_count ||
        clip->frame_count > t->desc.frame_total - t->frames_used ||
        bridge_count > t->desc.bridge_total - t->bridges_used)
        return CUB_ERR_FULL;
    for (int i = 0; i < bridge_count; i++) {
        int f = bridge_frames[i];
        if (f < 0 || f >= clip->frame_count || (i > 0 && f <= bridge_frames[i - 1]))
            return CUB_ERR_ARG;
    }
    cub_fuzzy_frame *dst = t->fuzzy + t->frames_used;
    if (fuzzy) {
        memcpy(dst, fuzzy, (size_t)clip->frame_count * sizeof *dst);
    } else {
        cub_err e = compute_fuzzy(t, clip, dst);
        if (e) return e;
    }
    /* Each bridge frame's body shape, for the planner's direct check. */
    static cub_pose pose; /* static: large; the firmware is single-threaded */
    int joints = t->desc.skel->joint_count;
    for (int i = 0; i < bridge_count; i++) {
        cub_vec3 *body = t->bridge_body_mm + (size_t)(t->bridges_used + i) * (size_t)joints;
        cub_err e = cub_motion_clip_get_frame(clip, bridge_frames[i], &pose);
        if (!e) e = cub_bridge_body_mm(t->desc.skel, &pose, body);
        if (e) return e;
        t->bridges[t->bridges_used + i] = (int16_t)bridge_frames[i];
    }
    cub_bridge_clip *c = &t->clips[t->clips_added++];
    c->clip = *clip;
    c->first_frame = t->frames_used;
    c->first_bridge = t->bridges_used;
    c->bridge_count = bridge_count;
    t->frames_used += clip->frame_count;
    t->bridges_used += bridge_count;
    return CUB_OK;
}

int cub_bridge_lower_bound(const cub_bridge_table *t, int c, int f)
{
    const int16_t *b = t->bridges + t->clips[c].first_bridge;
    int lo = 0, hi = t->clips[c].bridge_count;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (b[mid] < f)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

int cub_bridge_is_bridge(const cub_bridge_table *t, int c, int f)
{
    if (!t || c < 0 || c >= t->clips_added) return 0;
    int i = cub_bridge_lower_bound(t, c, f);
    return i < t->clips[c].bridge_count && t->bridges[t->clips[c].first_bridge + i] == f;
}

cub_err cub_bridge_table_set_links(cub_bridge_table *t, int from, int to,
                                   const cub_bridge_link *links, int count)
{
    if (!t || !t->clips || t->finished || count < 0 || (count > 0 && !links)) return CUB_ERR_ARG;
    if (from < 0 || to < 0 || from >= t->clips_added || to >= t->clips_added) return CUB_ERR_ARG;
    cub_bridge_pair *pair = &t->pairs[from * t->desc.clip_count + to];
    if (pair->count >= 0) return CUB_ERR_ARG; /* set twice */
    int to_frames = t->clips[to].clip.frame_count;
    for (int i = 0; i < count; i++) {
        const cub_bridge_link *l = &links[i];
        if (!cub_bridge_is_bridge(t, from, l->a) || !cub_bridge_is_bridge(t, to, l->b)) return CUB_ERR_ARG;
        if (l->d < 0 || l->d > CUB_Q16_ONE || l->back != (2 * l->b >= to_frames))
            return CUB_ERR_ARG;
    }
    if (count > t->desc.link_total - t->links_used) return CUB_ERR_FULL;
    memcpy(t->links + t->links_used, links, (size_t)count * sizeof *links);
    *pair = (cub_bridge_pair){t->links_used, count};
    t->links_used += count;
    return CUB_OK;
}

cub_err cub_bridge_table_set_tween(cub_bridge_table *t, int c, int pass_frames)
{
    if (!t || !t->clips || t->tween_clip >= 0 || c < 0 || c >= t->clips_added) return CUB_ERR_ARG;
    const cub_bridge_clip *tc = &t->clips[c];
    if (pass_frames < 2 || tc->clip.frame_count != 2 * pass_frames ||
        tc->bridge_count != tc->clip.frame_count)
        return CUB_ERR_ARG; /* bridges ascend in range, so all frames are bridges */
    t->tween_clip = c;
    t->tween_pass = pass_frames;
    return CUB_OK;
}

cub_err cub_bridge_table_finish(cub_bridge_table *t)
{
    if (!t || !t->clips) return CUB_ERR_ARG;
    if (t->clips_added != t->desc.clip_count) return CUB_ERR_RANGE;
    int n = t->desc.clip_count;
    for (int i = 0; i < n * n; i++)
        if (t->pairs[i].count < 0) t->pairs[i] = (cub_bridge_pair){0, 0};
    t->finished = 1;
    return CUB_OK;
}

static int route_ok(const cub_bridge_table *t, const cub_bridge_route *r)
{
    int n = t->desc.clip_count;
    if (r->from < 0 || r->from >= n || r->to < 0 || r->to >= n || r->via < 0 || r->via >= n ||
        r->from == r->to)
        return 0;
    int na = t->clips[r->from].clip.frame_count, nc = t->clips[r->via].clip.frame_count;
    return r->a >= 0 && r->a < na && r->in >= 0 && r->in < r->out && r->out < nc && r->b >= 0 &&
           r->b < t->clips[r->to].clip.frame_count;
}

cub_err cub_bridge_table_set_routes(cub_bridge_table *t, const cub_bridge_route *routes,
                                    int count)
{
    if (!t || !t->finished || t->routes || count < 0 || (count > 0 && !routes))
        return CUB_ERR_ARG;
    for (int i = 0; i < count; i++) {
        if (!route_ok(t, &routes[i])) return CUB_ERR_ARG;
        for (int j = 0; j < i; j++)
            if (routes[j].from == routes[i].from && routes[j].to == routes[i].to)
                return CUB_ERR_ARG;
    }
    t->routes = count > 0 ? routes : NULL;
    t->route_count = count;
    return CUB_OK;
}

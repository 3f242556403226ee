/* bridge: the seed's tween clip — keys from the bridge frames, a closed
 * tour through them, eased legs between them (see cub/bridge.h). */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "bridge_internal.h"

#define MAX_2OPT_PASSES 64 /* each pass shortens the tour or ends the search */

typedef struct work {
    cub_pose a, b;
    int32_t key[CUB_BRIDGE_TWEEN_MAX_KEYS]; /* bridge index (into t->bridges) */
    int32_t tour[CUB_BRIDGE_TWEEN_MAX_KEYS];
    int64_t chain_mm[CUB_MOTION_MAX_JOINTS]; /* bone length from the root, Q16 mm */
    int32_t cost[];                          /* [keys * keys] frames of each leg */
} work;

static int max_keys(const cub_bridge_table *t)
{
    int n = t->desc.bridge_total;
    return n < CUB_BRIDGE_TWEEN_MAX_KEYS ? n : CUB_BRIDGE_TWEEN_MAX_KEYS;
}

size_t cub_bridge_tween_work_size(const cub_bridge_table *t)
{
    if (!t || !t->clips) return 0;
    size_t k = (size_t)(max_keys(t) > 0 ? max_keys(t) : 1);
    return sizeof(work) + k * k * sizeof(int32_t) + 8;
}

/* Which clip bridge index i belongs to. */
static int clip_of_bridge(const cub_bridge_table *t, int i)
{
    int c = 0;
    while (c + 1 < t->desc.clip_count && t->clips[c + 1].first_bridge <= i)
        c++;
    return c;
}

static const cub_fuzzy_frame *bridge_features(const cub_bridge_table *t, int i)
{
    int c = clip_of_bridge(t, i);
    return &t->fuzzy[t->clips[c].first_frame + t->bridges[i]];
}

static cub_err bridge_pose(const cub_bridge_table *t, int i, cub_pose *out)
{
    cub_err e = cub_motion_clip_get_frame(&t->clips[clip_of_bridge(t, i)].clip, t->bridges[i], out);
    out->root_mm.x = out->root_mm.z = 0; /* the tween stands still on the floor */
    return e;
}

/* Keys: every bridge frame not within cover of a key kept before it. */
static cub_err choose_keys(const cub_bridge_table *t, cub_q16 cover, work *w, int *count)
{
    int n = 0;
    for (int i = 0; i < t->desc.bridge_total; i++) {
        const cub_fuzzy_frame *f = bridge_features(t, i);
        int near = 0;
        for (int k = 0; k < n && !near; k++)
            near = cub_fuzzy_distance(f, bridge_features(t, w->key[k]), &t->desc.fuzzy) < cover;
        if (near) continue;
        if (n == CUB_BRIDGE_TWEEN_MAX_KEYS) return CUB_ERR_FULL;
        w->key[n++] = i;
    }
    *count = n;
    return n ? CUB_OK : CUB_ERR_RANGE;
}

static void chain_lengths(const cub_skeleton *sk, int64_t *out)
{
    for (int j = 0; j < sk->joint_count; j++) {
        int p = sk->joints[j].parent;
        out[j] = p < 0 ? 0 : out[p] + cub_fx_vec3_length(sk->joints[j].offset_mm);
    }
}

/* How far the fastest joint can travel from pose a to pose b along the
 * slerp (Q16 mm): each ancestor's turn times the bone chain from it down
 * to the joint, plus the root's rise. */
static int64_t leg_path_mm(const cub_skeleton *sk, const int64_t *chain, const cub_pose *a,
                           const cub_pose *b)
{
    cub_q16 turn[CUB_MOTION_MAX_JOINTS];
    for (int j = 0; j < sk->joint_count; j++)
        turn[j] = cub_fx_quat_angle(cub_fx_quat_mul(cub_fx_quat_conj(a->rot[j]), b->rot[j]));
    int64_t rise = (int64_t)a->root_mm.y - b->root_mm.y, worst = 0;
    if (rise < 0) rise = -rise;
    for (int j = 0; j < sk->joint_count; j++) {
        int64_t path = rise;
        for (int p = j; p >= 0; p = sk->joints[p].parent)
            path += ((int64_t)turn[p] * (chain[j] - chain[p])) >> 16;
        if (path > worst) worst = path;
    }
    return worst;
}

/* Frames a leg of that path needs: smoothstep's steepest slope is 1.5. */
static int32_t leg_frames(int64_t path_mm, cub_q16 speed_mm)
{
    int64_t n = (path_mm * 3 / 2 + speed_mm - 1) / speed_mm;
    if (n < 1) n = 1;
    return n > CUB_BRIDGE_TWEEN_MAX_LEG ? CUB_BRIDGE_TWEEN_MAX_LEG : (int32_t)n;
}

static cub_err leg_costs(const cub_bridge_table *t, cub_q16 speed, int n, work *w)
{
    const cub_skeleton *sk = t->desc.skel;
    chain_lengths(sk, w->chain_mm);
    for (int i = 0; i < n; i++) {
        w->cost[i * n + i] = 0;
        cub_err e = bridge_pose(t, w->key[i], &w->a);
        for (int j = i + 1; j < n && !e; j++) {
            e = bridge_pose(t, w->key[j], &w->b);
            int32_t c = leg_frames(leg_path_mm(sk, w->chain_mm, &w->a, &w->b), speed);
            w->cost[i * n + j] = w->cost[j * n + i] = c;
        }
        if (e) return e;
    }
    return CUB_OK;
}

/* A closed tour: nearest neighbour from the first key (lowest index on
 * ties), then 2-opt (reverse a stretch when that shortens the tour). */
static void order_keys(int n, work *w)
{
    uint8_t used[CUB_BRIDGE_TWEEN_MAX_KEYS] = {0};
    w->tour[0] = 0;
    used[0] = 1;
    for (int s = 1; s < n; s++) {
        int from = w->tour[s - 1], best = -1;
        for (int k = 0; k < n; k++)
            if (!used[k] && (best < 0 || w->cost[from * n + k] < w->cost[from * n + best]))
                best = k;
        w->tour[s] = best;
        used[best] = 1;
    }
    const int32_t *c = w->cost;
    for (int pass = 0, better = 1; better && pass < MAX_2OPT_PASSES; pass++) {
        better = 0;
        for (int i = 0; i + 2 < n; i++)
            for (int j = i + 2; j < n; j++) {
                int a = w->tour[i], b = w->tour[i + 1], cc = w->tour[j], d = w->tour[(j + 1) % n];
                if (a == d) continue;
                if (c[a * n + cc] + c[b * n + d] >= c[a * n + b] + c[cc * n + d]) continue;
                for (int lo = i + 1, hi = j; lo < hi; lo++, hi--) {
                    int32_t tmp = w->tour[lo];
                    w->tour[lo] = w->tour[hi];
                    w->tour[hi] = tmp;
                }
                better = 1;
            }
    }
}

cub_err cub_bridge_tween_plan(const cub_bridge_table *t, const cub_bridge_tween_config *cfg,
                              cub_bridge_tween *out, void *mem, size_t mem_size)
{
    if (out) memset(out, 0, sizeof *out);
    if (!t || !out || !t->finished || t->tween_clip >= 0) return CUB_ERR_ARG;
    if (!mem || mem_size < cub_bridge_tween_work_size(t)) return CUB_ERR_NOMEM;
    cub_q16 cover = cfg && cfg->cover_d ? cfg->cover_d : t->desc.fuzzy.threshold / 2;
    cub_q16 speed = cfg && cfg->speed_mm ? cfg->speed_mm : CUB_BRIDGE_TWEEN_SPEED_MM;
    if (cover < 0 || speed <= 0) return CUB_ERR_ARG;
    work *w = (work *)(((uintptr_t)mem + 7) & ~(uintptr_t)7);
    int n = 0;
    cub_err e = choose_keys(t, cover, w, &n);
    if (!e) e = leg_costs(t, speed, n, w);
    if (e) return e;
    order_keys(n, w);
    int at = 0;
    for (int s = 0; s < n; s++) {
        int i = w->key[w->tour[s]];
        out->key_clip[s] = (int16_t)clip_of_bridge(t, i);
        out->key_frame[s] = t->bridges[i];
        out->key_at[s] = (int16_t)at;
        at += n > 1 ? w->cost[w->tour[s] * n + w->tour[(s + 1) % n]] : 1;
    }
    out->key_count = n;
    out->frame_count = at;
    return at > INT16_MAX / 2 ? CUB_ERR_FULL : CUB_OK;
}

/* 3s^2 - 2s^3: 0 and 1 at the ends, flat at both. */
static cub_q16 ease(int step, int steps)
{
    cub_q16 s = (cub_q16)(((int64_t)step << 16) / steps);
    cub_q16 s2 = cub_fx_mul(s, s);
    return 3 * s2 - 2 * cub_fx_mul(s2, s);
}

static cub_err key_pose(const cub_bridge_table *t, const cub_bridge_tween *tw, int k, cub_pose *out)
{
    cub_err e = cub_motion_clip_get_frame(&t->clips[tw->key_clip[k]].clip, tw->key_frame[k], out);
    out->root_mm.x = out->root_mm.z = 0;
    return e;
}

/* Frame `step` of the leg from key k to the next one (wrapping). */
static cub_err leg_frame(const cub_bridge_table *t, const cub_bridge_tween *tw, int k, int step,
                         cub_pose *out)
{
    static cub_pose b; /* static: large; the firmware is single-threaded */
    int next = (k + 1) % tw->key_count;
    int end = next ? tw->key_at[next] : tw->frame_count;
    cub_err e = key_pose(t, tw, k, out);
    if (e || step == 0) return e;
    if ((e = key_pose(t, tw, next, &b))) return e;
    cub_q16 w = ease(step, end - tw->key_at[k]);
    for (int j = 0; j < out->joint_count; j++)
        out->rot[j] = cub_fx_quat_slerp(out->rot[j], b.rot[j], w);
    out->root_mm = cub_fx_vec3_lerp(out->root_mm, b.root_mm, w);
    if (out->has_trans)
        for (int j = 0; j < out->joint_count; j++)
            out->trans_mm[j] = cub_fx_vec3_lerp(out->trans_mm[j], b.trans_mm[j], w);
    return CUB_OK;
}

cub_err cub_bridge_tween_fill(const cub_bridge_table *t, const cub_bridge_tween *tw, cub_clip *clip)
{
    static cub_pose pose; /* static: large; the firmware is single-threaded */
    if (!t || !tw || !clip || tw->key_count < 1 || tw->frame_count < 1 ||
        clip->skel != t->desc.skel)
        return CUB_ERR_ARG;
    for (int k = 0; k < tw->key_count; k++)
        if (tw->key_clip[k] < 0 || tw->key_clip[k] >= t->clips_added || tw->key_frame[k] < 0 ||
            tw->key_frame[k] >= t->clips[tw->key_clip[k]].clip.frame_count ||
            (k && tw->key_at[k] <= tw->key_at[k - 1]) || tw->key_at[k] >= tw->frame_count)
            return CUB_ERR_ARG;
    if (tw->key_at[0] != 0) return CUB_ERR_ARG;
    for (int f = 0; f < clip->frame_count; f++) {
        int g = f % tw->frame_count, k = tw->key_count - 1;
        while (tw->key_at[k] > g)
            k--;
        cub_err e = leg_frame(t, tw, k, g - tw->key_at[k], &pose);
        if (!e) e = cub_motion_clip_set_frame(clip, f, &pose);
        if (e) return e;
    }
    return CUB_OK;
}

/* bridge: the planner (SEEDS.md § 000, "Switching").
 *
 * Direct: the current clip's upcoming frames against the wanted clip's
 * bridge frames, front half first; the soonest frame within the threshold
 * wins, then the smallest d. Tween: Dijkstra on frames of play over the
 * table's bridge frames: the current clip enters any clip X at a bridge
 * frame it reaches within the window (the same direct test), X plays on to
 * a tagged link into the next clip, and so on until the wanted clip is
 * entered, front half first. Within the threshold the soonest frame wins
 * and, at it, the bridge frame whose body is closest (measured directly on
 * the poses: the fuzzy d is coarse); wait_cost_mm may trade waiting for a
 * closer body. Both are tried in a 6-frame window first,
 * then in windows twice as long, up to one pass of the current clip:
 * reacting soon matters more than a perfect path. */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "bridge_internal.h"

/* An intermediate clip is shown for at least this many frames: a shorter
 * visit is a flicker, not a move. */
#define MIN_DWELL_FRAMES 2 /* a tween clip shows this long at least, inside the blend */
#define NO_DIST INT32_MAX

typedef struct node {
    int64_t cost;      /* seeds: body distance + waiting cost */
    int32_t dist;      /* frames from now until this bridge frame is entered */
    int32_t prev;      /* previous node, -1: entered from the current clip */
    int32_t from_frame;/* the frame of the previous clip the switch leaves */
    int32_t hops;
    int64_t at_q16;    /* that frame on the previous clip's unwrapped line */
    cub_q16 d;
    int16_t clip;
    uint8_t done;
    uint8_t reserved_;
} node;

/* The planner's scratch: the tween's nodes, a pose and its body shape. */
typedef struct scratch {
    cub_pose pose;
    cub_vec3 body[CUB_MOTION_MAX_JOINTS];
    int have_body; /* body holds the frame below */
    int body_frame;
    node nodes[];
} scratch;

size_t cub_bridge_plan_work_size(const cub_bridge_table *t)
{
    if (!t || !t->clips) return 0;
    return sizeof(scratch) +
           (size_t)(t->desc.bridge_total > 0 ? t->desc.bridge_total : 1) * sizeof(node) + 8;
}

static scratch *scratch_of(void *work)
{
    return (scratch *)(((uintptr_t)work + 7) & ~(uintptr_t)7);
}

/* The body shape of frame f of the current clip (computed once per frame). */
static const cub_vec3 *current_body(const cub_bridge_table *t, const cub_bridge_query *q, int f,
                                    scratch *w)
{
    if (w->have_body && w->body_frame == f) return w->body;
    const cub_clip *clip = &t->clips[q->from_clip].clip;
    if (cub_motion_clip_get_frame(clip, f, &w->pose) ||
        cub_bridge_body_mm(clip->skel, &w->pose, w->body))
        return NULL;
    w->have_body = 1;
    w->body_frame = f;
    return w->body;
}

/* How bad switching from current frame f to bridge node i after k frames
 * of waiting is: body distance + waiting. */
static int64_t switch_cost(const cub_bridge_table *t, const cub_bridge_query *q, int f, int k,
                           int i, scratch *w)
{
    const cub_vec3 *now = current_body(t, q, f, w);
    if (!now) return INT64_MAX;
    int joints = t->desc.skel->joint_count;
    int64_t wait = q->wait_cost_mm ? q->wait_cost_mm : CUB_BRIDGE_WAIT_COST_MM;
    return (int64_t)cub_bridge_shape_dist_mm(now, t->bridge_body_mm + (size_t)i * joints, joints) +
           wait * k;
}

static const cub_fuzzy_frame *features(const cub_bridge_table *t, int clip, int frame)
{
    return &t->fuzzy[t->clips[clip].first_frame + frame];
}

static int frames_of(const cub_bridge_table *t, int clip)
{
    return t->clips[clip].clip.frame_count;
}

/* The current clip's k-th upcoming frame: unwrapped, and as a frame index
 * (-1 past the end of a clip that does not loop). */
static int upcoming(const cub_bridge_query *q, int n, int64_t g0, int k, int64_t *unwrapped)
{
    int64_t g = g0 + k;
    *unwrapped = g;
    if (q->from_loops) return (int)(g % n);
    return g < n ? (int)g : -1;
}

/* A looping clip's next pass starts with a blend out of its last frame,
 * so its first frame is not on screen at that moment: no switch there
 * (the frame before it is the same moment). */
static int at_pass_start(const cub_bridge_query *q, int n, int64_t g0, int k)
{
    return q->from_loops && k > 0 && (g0 + k) % n == 0;
}

/* A switch inside one clip must jump at least a quarter of it (as the
 * tagger's self links do): shorter is a stutter, not a repeat. */
static int jump_ok(int same, int from, int to, int n)
{
    int j = from > to ? from - to : to - from;
    return !same || 4 * j >= n;
}

/* May a switch leave the current clip at its frame f, and enter clip c at
 * frame b? Always, unless the query is strict (see cub_bridge_query). */
static int leave_ok(const cub_bridge_table *t, const cub_bridge_query *q, int f)
{
    return !q->strict || cub_bridge_is_bridge(t, q->from_clip, f);
}

static int enter_ok(const cub_bridge_table *t, const cub_bridge_query *q, int c, int b)
{
    return !q->strict || cub_bridge_is_bridge(t, c, b);
}

/* The current clip's k-th upcoming frame, if a switch may leave there:
 * its features, its frame (*gf) and its unwrapped position (*at). NULL
 * when it may not; *gf < 0 past the end of a clip that does not loop. */
static const cub_fuzzy_frame *leaving(const cub_bridge_table *t, const cub_bridge_query *q,
                                      int64_t g0, int k, int *gf, int64_t *at)
{
    int nf = frames_of(t, q->from_clip);
    *gf = upcoming(q, nf, g0, k, at);
    if (*gf < 0 || at_pass_start(q, nf, g0, k) || !leave_ok(t, q, *gf)) return NULL;
    return features(t, q->from_clip, *gf);
}

typedef struct hit {
    int k, frame;
    int64_t at, cost;
    cub_q16 d;
} hit;

/* The best upcoming frame within the window, within the threshold of one
 * of the wanted clip's bridge frames in half `back` (see switch_cost). */
static int direct_search(const cub_bridge_table *t, const cub_bridge_query *q, int64_t g0,
                         int window, int back, scratch *w, hit *out)
{
    int nf = frames_of(t, q->from_clip), nt = frames_of(t, q->to_clip);
    const cub_bridge_clip *to = &t->clips[q->to_clip];
    const int16_t *bridges = t->bridges + to->first_bridge;
    int found = 0;
    for (int k = 0; k < window; k++) {
        int64_t at;
        int gf;
        const cub_fuzzy_frame *now = leaving(t, q, g0, k, &gf, &at);
        if (gf < 0) break;
        if (!now) continue;
        for (int i = 0; i < to->bridge_count; i++) {
            int b = bridges[i];
            if ((2 * b >= nt) != back) continue;
            if (!jump_ok(q->from_clip == q->to_clip, gf, b, nf)) continue;
            cub_q16 d = cub_fuzzy_distance(now, features(t, q->to_clip, b), &t->desc.fuzzy);
            if (d >= t->desc.fuzzy.threshold) continue;
            int64_t cost = switch_cost(t, q, gf, k, to->first_bridge + i, w);
            if (!found || cost < out->cost) *out = (hit){k, b, at, cost, d};
            found = 1;
        }
    }
    return found;
}

/* Where a switch can land at the wanted clip's start: the next `window`
 * frames from g0 against its first `starts` frames. */
typedef struct start_scan {
    int64_t g0;
    int window, starts;
    int nearest; /* 0: the first pair within the threshold; 1: the pair of smallest d */
} start_scan;

/* The pair s asks for, the sooner (then the earlier start frame) on a tie;
 * 0 when there is none. */
static int scan_starts(const cub_bridge_table *t, const cub_bridge_query *q, const start_scan *s,
                       hit *out)
{
    int nf = frames_of(t, q->from_clip);
    int found = 0;
    for (int k = 0; k < s->window; k++) {
        int64_t at;
        int gf;
        const cub_fuzzy_frame *now = leaving(t, q, s->g0, k, &gf, &at);
        if (gf < 0) break;
        if (!now) continue;
        for (int b = 0; b < s->starts; b++) {
            if (!jump_ok(q->from_clip == q->to_clip, gf, b, nf) || !enter_ok(t, q, q->to_clip, b))
                continue;
            cub_q16 d = cub_fuzzy_distance(now, features(t, q->to_clip, b), &t->desc.fuzzy);
            if (s->nearest ? found && d >= out->d : d >= t->desc.fuzzy.threshold) continue;
            *out = (hit){k, b, at, 0, d};
            if (!s->nearest) return 1;
            found = 1;
        }
    }
    return found;
}

/* The soonest upcoming frame within the window that is within the
 * threshold of one of the wanted clip's first q->start_frames frames, the
 * earliest of those first (see cub_bridge_query.start_frames). */
static int start_search(const cub_bridge_table *t, const cub_bridge_query *q, int64_t g0,
                        int window, hit *out)
{
    int nt = frames_of(t, q->to_clip);
    start_scan s = {g0, window, q->start_frames < nt ? q->start_frames : nt, 0};
    return scan_starts(t, q, &s, out);
}

/* ---- the tween ------------------------------------------------------- */

/* Enter every other clip's bridge frames reachable directly in the window,
 * each at its best frame (see switch_cost). */
static void seed_nodes(const cub_bridge_table *t, const cub_bridge_query *q, int64_t g0,
                       int window, scratch *w)
{
    node *nodes = w->nodes;
    for (int x = 0; x < t->desc.clip_count; x++) {
        const cub_bridge_clip *cx = &t->clips[x];
        for (int i = 0; i < cx->bridge_count; i++)
            nodes[cx->first_bridge + i] = (node){INT64_MAX, NO_DIST, -1, 0, 0, 0, 0,
                                                 (int16_t)x, 0, 0};
    }
    for (int k = 0; k < window; k++) {
        int64_t at;
        int gf;
        const cub_fuzzy_frame *now = leaving(t, q, g0, k, &gf, &at);
        if (gf < 0) break;
        if (!now) continue;
        for (int x = 0; x < t->desc.clip_count; x++) {
            if (x == q->from_clip || x == q->to_clip || x == t->tween_clip) continue;
            const cub_bridge_clip *cx = &t->clips[x];
            for (int i = 0; i < cx->bridge_count; i++) {
                int v = cx->first_bridge + i;
                cub_q16 d = cub_fuzzy_distance(now, features(t, x, t->bridges[v]),
                                               &t->desc.fuzzy);
                if (d >= t->desc.fuzzy.threshold) continue;
                int64_t cost = switch_cost(t, q, gf, k, v, w);
                if (cost < nodes[v].cost)
                    nodes[v] = (node){cost, k, -1, gf, 1, at << 16, d, (int16_t)x, 0, 0};
            }
        }
    }
}

/* Node index of bridge frame f of clip c (f is a bridge frame: tag links
 * were validated against the table). */
static int node_of(const cub_bridge_table *t, int c, int f)
{
    const cub_bridge_clip *cc = &t->clips[c];
    int i = cub_bridge_lower_bound(t, c, f);
    return cc->first_bridge + (i < cc->bridge_count ? i : cc->bridge_count - 1);
}

static void relax_from(const cub_bridge_table *t, node *nodes, int u)
{
    int x = nodes[u].clip, entry = t->bridges[u];
    for (int y = 0; y < t->desc.clip_count; y++) {
        if (y == x) continue;
        const cub_bridge_pair *pair = &t->pairs[x * t->desc.clip_count + y];
        for (int i = 0; i < pair->count; i++) {
            const cub_bridge_link *l = &t->links[pair->first + i];
            if (l->a < entry + MIN_DWELL_FRAMES) continue;
            int32_t dist = nodes[u].dist + (l->a - entry);
            int v = node_of(t, y, l->b);
            if (nodes[v].done || dist >= nodes[v].dist) continue;
            nodes[v] = (node){0, dist, u, l->a, nodes[u].hops + 1, (int64_t)l->a << 16,
                              l->d, (int16_t)y, 0, 0};
        }
    }
}

/* Dijkstra: the unfinished node with the least dist (lowest index on ties). */
static int pop_min(const node *nodes, int count)
{
    int best = -1;
    for (int i = 0; i < count; i++)
        if (!nodes[i].done && nodes[i].dist != NO_DIST &&
            (best < 0 || nodes[i].dist < nodes[best].dist))
            best = i;
    return best;
}

/* Write the chain ending at node `end` into the plan, first step first. */
static void write_chain(const cub_bridge_table *t, const cub_bridge_query *q, const node *nodes,
                        int end, cub_bridge_plan *out)
{
    int n = nodes[end].hops;
    out->step_count = n;
    out->total_frames = nodes[end].dist;
    for (int v = end, i = n - 1; v >= 0 && i >= 0; v = nodes[v].prev, i--) {
        const node *nv = &nodes[v];
        int from = nv->prev >= 0 ? nodes[nv->prev].clip : q->from_clip;
        out->step[i] = (cub_bridge_step){from, nv->from_frame, nv->clip, t->bridges[v],
                                         nv->d, CUB_BRIDGE_TWEEN, nv->at_q16};
        if (nv->prev < 0) out->wait_frames = nv->dist;
    }
}

/* A move's start through one other clip: into a clip seeded by
 * seed_nodes, play it at least MIN_DWELL_FRAMES, then out of one of its
 * frames into one of the wanted clip's first q->start_frames frames (by d).
 * The quickest such route that arrives within max_frames, or 0. */
static int start_tween(const cub_bridge_table *t, const cub_bridge_query *q, int max_frames,
                       scratch *w, cub_bridge_plan *out)
{
    const node *nodes = w->nodes;
    int nt = frames_of(t, q->to_clip), starts = q->start_frames < nt ? q->start_frames : nt;
    int best_total = max_frames + 1, bu = -1, ba = 0, bs = 0;
    cub_q16 bd = 0;
    for (int u = 0; u < t->desc.bridge_total; u++) {
        if (nodes[u].dist == NO_DIST || nodes[u].prev >= 0) continue;
        int x = nodes[u].clip, entry = t->bridges[u], nx = frames_of(t, x);
        for (int a = entry + MIN_DWELL_FRAMES; a < nx; a++) {
            int total = nodes[u].dist + (a - entry);
            if (total >= best_total) break;
            if (q->strict && !cub_bridge_is_bridge(t, x, a)) continue;
            for (int s = 0; s < starts; s++) {
                if (!enter_ok(t, q, q->to_clip, s)) continue;
                cub_q16 d = cub_fuzzy_distance(features(t, x, a), features(t, q->to_clip, s),
                                               &t->desc.fuzzy);
                if (d >= t->desc.fuzzy.threshold) continue;
                best_total = total, bu = u, ba = a, bs = s, bd = d;
                break;
            }
        }
    }
    if (bu < 0) return 0;
    const node *n = &nodes[bu];
    out->step_count = 2;
    out->step[0] = (cub_bridge_step){q->from_clip, n->from_frame, n->clip, t->bridges[bu], n->d,
                                     CUB_BRIDGE_TWEEN, n->at_q16};
    out->step[1] = (cub_bridge_step){n->clip, ba, q->to_clip, bs, bd, CUB_BRIDGE_TWEEN,
                                     (int64_t)ba << 16};
    out->wait_frames = n->dist;
    out->total_frames = best_total;
    return 1;
}

static int tween_search(const cub_bridge_table *t, const cub_bridge_query *q, int64_t g0,
                        int window, scratch *w, cub_bridge_plan *out)
{
    int count = t->desc.bridge_total;
    node *nodes = w->nodes;
    seed_nodes(t, q, g0, window, w);
    for (;;) {
        int u = pop_min(nodes, count);
        if (u < 0) break;
        nodes[u].done = 1;
        if (nodes[u].clip != q->to_clip && nodes[u].hops < CUB_BRIDGE_MAX_STEPS)
            relax_from(t, nodes, u);
    }
    /* The wanted clip's front half first, then its back half. */
    int nt = frames_of(t, q->to_clip);
    const cub_bridge_clip *to = &t->clips[q->to_clip];
    for (int back = 0; back <= 1; back++) {
        int best = -1;
        for (int i = 0; i < to->bridge_count; i++) {
            int v = to->first_bridge + i;
            if ((2 * t->bridges[v] >= nt) != back || nodes[v].dist == NO_DIST) continue;
            if (best < 0 || nodes[v].dist < nodes[best].dist) best = v;
        }
        if (best >= 0) {
            write_chain(t, q, nodes, best, out);
            return 1;
        }
    }
    return 0;
}


/* ---- the route through the tween clip ------------------------------ */

/* Per frame e of the tween's first pass: the best entry into it; per frame
 * x of both passes: the next frame from x on that can leave it. Laid over
 * the nodes' memory (a plan uses one or the other). */
typedef struct slot {
    int64_t cost, at; /* entry: switch_cost, the current clip's unwrapped frame */
    int32_t k;        /* entry: frames from now; NO_DIST: none */
    int32_t exit_b;   /* exit (first pass): the wanted clip's frame; -1: none */
    int32_t next;     /* the first frame >= x that can leave; -1: none */
    cub_q16 entry_d, exit_d;
} slot;
_Static_assert(sizeof(slot) <= sizeof(node), "slots lie over the nodes");

/* What a route must enter: the wanted clip's bridge frames in half `back`,
 * or (starts > 0) one of its first `starts` frames. */
typedef struct target {
    int back, starts;
} target;

/* Tween frame x leaves for the wanted clip at the closest (by body; by d
 * for a start) frame within the threshold (exit_b -1: none). */
static void tween_exit(const cub_bridge_table *t, const cub_bridge_query *q, const target *tg,
                       int x, slot *s)
{
    int tw = t->tween_clip, nt = frames_of(t, q->to_clip), joints = t->desc.skel->joint_count;
    const cub_fuzzy_frame *fx = features(t, tw, x);
    const cub_bridge_clip *to = &t->clips[q->to_clip];
    const cub_vec3 *body = t->bridge_body_mm + (size_t)(t->clips[tw].first_bridge + x) * joints;
    int64_t best = INT64_MAX;
    s->exit_b = -1;
    int count = tg->starts ? (tg->starts < nt ? tg->starts : nt) : to->bridge_count;
    for (int i = 0; i < count; i++) {
        int b = tg->starts ? i : t->bridges[to->first_bridge + i];
        if (tg->starts ? !enter_ok(t, q, q->to_clip, b) : (2 * b >= nt) != tg->back) continue;
        cub_q16 d = cub_fuzzy_distance(fx, features(t, q->to_clip, b), &t->desc.fuzzy);
        if (d >= t->desc.fuzzy.threshold) continue;
        int64_t cost = tg->starts ? d
                                  : cub_bridge_shape_dist_mm(
                                        body, t->bridge_body_mm + (size_t)(to->first_bridge + i) * joints,
                                        joints);
        if (cost < best) best = cost, s->exit_b = b, s->exit_d = d;
    }
}

/* The best entry into each frame of the tween's first pass from the next
 * `window` upcoming frames: the soonest, then the closest body. */
static void tween_entries(const cub_bridge_table *t, const cub_bridge_query *q, int64_t g0,
                          int window, scratch *w, slot *s)
{
    int tw = t->tween_clip, pass = t->tween_pass;
    for (int e = 0; e < pass; e++)
        s[e].k = NO_DIST;
    for (int k = 0; k < window; k++) {
        int64_t at;
        int gf;
        const cub_fuzzy_frame *now = leaving(t, q, g0, k, &gf, &at);
        if (gf < 0) break;
        if (!now) continue;
        for (int e = 0; e < pass; e++) {
            if (s[e].k != NO_DIST && s[e].k < k) continue;
            cub_q16 d = cub_fuzzy_distance(now, features(t, tw, e), &t->desc.fuzzy);
            if (d >= t->desc.fuzzy.threshold) continue;
            int64_t cost = switch_cost(t, q, gf, k, t->clips[tw].first_bridge + e, w);
            if (s[e].k == NO_DIST || cost < s[e].cost) {
                s[e].k = k, s[e].cost = cost, s[e].at = at, s[e].entry_d = d;
            }
        }
    }
}

/* Enter the tween, play it at least MIN_DWELL_FRAMES and at most one pass,
 * leave it for the target: the route that arrives first within max_total
 * frames (then the closest entry). 0 if there is none. */
static int tween_route(const cub_bridge_table *t, const cub_bridge_query *q, int64_t g0,
                       int window, const target *tg, int max_total, scratch *w,
                       cub_bridge_plan *out)
{
    int tw = t->tween_clip, pass = t->tween_pass;
    if (tw < 0 || tw == q->from_clip || tw == q->to_clip) return 0;
    slot *s = (slot *)w->nodes;
    tween_entries(t, q, g0, window, w, s);
    for (int x = 0; x < pass; x++)
        tween_exit(t, q, tg, x, &s[x]);
    for (int x = 2 * pass - 1, next = -1; x >= 0; x--) {
        if (s[x % pass].exit_b >= 0) next = x; /* the second pass repeats the first */
        s[x].next = next;
    }
    int best = -1, best_x = 0, best_total = max_total + 1;
    for (int e = 0; e < pass; e++) {
        int x = s[e].k == NO_DIST ? -1 : s[e + MIN_DWELL_FRAMES].next;
        if (x < 0 || x - e > pass) continue;
        int total = s[e].k + (x - e);
        if (total < best_total || (best >= 0 && total == best_total && s[e].cost < s[best].cost))
            best = e, best_x = x, best_total = total;
    }
    if (best < 0) return 0;
    const slot *en = &s[best], *ex = &s[best_x % pass];
    int nf = frames_of(t, q->from_clip);
    out->step_count = 2;
    out->step[0] = (cub_bridge_step){q->from_clip, (int)(en->at % nf), tw, best, en->entry_d,
                                     CUB_BRIDGE_TWEEN, en->at << 16};
    out->step[1] = (cub_bridge_step){tw, best_x, q->to_clip, ex->exit_b, ex->exit_d,
                                     CUB_BRIDGE_TWEEN, (int64_t)best_x << 16};
    out->wait_frames = en->k;
    out->total_frames = best_total;
    return 1;
}

/* ---- the plan -------------------------------------------------------- */

/* A plan of one direct switch: play on h.k frames, then into h.frame. */
static void write_direct(const cub_bridge_query *q, int nf, const hit *h, int window,
                         cub_bridge_plan *out)
{
    out->step_count = 1;
    out->step[0] = (cub_bridge_step){q->from_clip, (int)(h->at % nf), q->to_clip, h->frame, h->d,
                                     CUB_BRIDGE_DIRECT, h->at << 16};
    out->wait_frames = out->total_frames = h->k;
    out->window_frames = window;
}

static int query_ok(const cub_bridge_table *t, const cub_bridge_query *q)
{
    int n = t->desc.clip_count;
    return q->from_clip >= 0 && q->from_clip < n && q->to_clip >= 0 && q->to_clip < n &&
           q->pos_q16 >= 0 && q->pos_q16 < ((int64_t)1 << 46) && q->window_frames >= 0 &&
           q->wait_cost_mm >= 0 && q->start_frames >= 0 && q->reach_frames >= 0 &&
           (q->strict == 0 || q->strict == 1) && (q->via_tween == 0 || q->via_tween == 1) && (q->no_routes == 0 || q->no_routes == 1) &&
           (q->direct_only == 0 || (q->direct_only == 1 && q->reach_frames > 0)) &&
           (q->on_clock == 0 || (q->on_clock == 1 && q->direct_only == 1)) &&
           q->clock_q16 > -((int64_t)1 << 46) && q->clock_q16 < ((int64_t)1 << 46);
}

/* The first frame still to come; a clip that does not loop holds its
 * last frame once there. */
static int64_t first_upcoming(const cub_bridge_table *t, const cub_bridge_query *q)
{
    int nf = frames_of(t, q->from_clip);
    int64_t g0 = (q->pos_q16 + 0xFFFF) >> 16;
    return !q->from_loops && g0 > nf - 1 ? nf - 1 : g0;
}

/* Beyond the threshold, for a reaction that must not wait: of the next
 * `window` frames and the wanted clip's first start_frames frames (all
 * when 0), the pair with the smallest d, the sooner on a tie. */
static int reach_search(const cub_bridge_table *t, const cub_bridge_query *q, int64_t g0,
                        int window, hit *out)
{
    int nt = frames_of(t, q->to_clip);
    start_scan s = {g0, window, q->start_frames > 0 && q->start_frames < nt ? q->start_frames : nt,
                    1};
    return scan_starts(t, q, &s, out);
}

static cub_err plan_within(const cub_bridge_table *t, const cub_bridge_query *q,
                           cub_bridge_plan *out, void *work);

/* The table's searched route for this pair, when the current clip reaches
 * its frame a within `window` upcoming frames: a correction that comes
 * later than that is not worth the route (the reaction's 200 ms come
 * first), and the searches below plan it instead. */
static int route_take(const cub_bridge_table *t, const cub_bridge_query *q, int64_t g0,
                      int window, cub_bridge_plan *out)
{
    const cub_bridge_route *r = NULL;
    for (int i = 0; i < t->route_count && !r; i++)
        if (t->routes[i].from == q->from_clip && t->routes[i].to == q->to_clip) r = &t->routes[i];
    if (!r) return 0;
    int nf = frames_of(t, q->from_clip);
    for (int k = 0; k < window; k++) {
        int64_t at;
        int gf = upcoming(q, nf, g0, k, &at);
        if (gf < 0) return 0;
        if (gf != r->a || at_pass_start(q, nf, g0, k)) continue;
        out->step_count = 2;
        out->step[0] = (cub_bridge_step){q->from_clip, r->a, r->via, r->in, 0,
                                         CUB_BRIDGE_ROUTE, at << 16};
        out->step[1] = (cub_bridge_step){r->via, r->out, q->to_clip, r->b, 0, CUB_BRIDGE_ROUTE,
                                         (int64_t)r->out << 16};
        out->wait_frames = k;
        out->total_frames = k + (r->out - r->in);
        out->window_frames = window;
        return 1;
    }
    return 0;
}

/* No direct switch: a chain through other clips, or (via_tween) a route
 * through the tween clip, the wanted clip's front half first. */
static int route_search(const cub_bridge_table *t, const cub_bridge_query *q, int64_t g0,
                        int window, scratch *w, cub_bridge_plan *out)
{
    if (!q->via_tween) return tween_search(t, q, g0, window, w, out);
    for (int back = 0; back <= 1; back++) {
        target tg = {back, 0};
        if (tween_route(t, q, g0, window, &tg, INT32_MAX - 1, w, out)) return 1;
    }
    return 0;
}

/* on_clock: the wanted clip's frame when the switch leaves at unwrapped
 * position `at` (the clock runs on while the current clip plays to it). */
static int clock_frame(const cub_bridge_table *t, const cub_bridge_query *q, int64_t at)
{
    int64_t ahead = (at << 16) - q->pos_q16;
    int64_t f = (q->clock_q16 + (ahead > 0 ? ahead : 0) + 0x8000) >> 16;
    int nt = frames_of(t, q->to_clip);
    return f < 0 ? 0 : f >= nt ? nt - 1 : (int)f;
}

/* on_clock: of the next reach_frames frames, the soonest whose switch into
 * the clock's frame is within the threshold, else the one of smallest d
 * (the sooner on a tie). */
static int clock_search(const cub_bridge_table *t, const cub_bridge_query *q, int64_t g0,
                        hit *out)
{
    int found = 0;
    for (int k = 0; k < q->reach_frames; k++) {
        int64_t at;
        int gf;
        const cub_fuzzy_frame *now = leaving(t, q, g0, k, &gf, &at);
        if (gf < 0) break;
        if (!now) continue;
        int b = clock_frame(t, q, at);
        cub_q16 d = cub_fuzzy_distance(now, features(t, q->to_clip, b), &t->desc.fuzzy);
        if (d < t->desc.fuzzy.threshold) {
            *out = (hit){k, b, at, 0, d};
            return 1;
        }
        if (!found || d < out->d) *out = (hit){k, b, at, 0, d};
        found = 1;
    }
    return found;
}

/* direct_only: a switch within the threshold into a start frame, when it
 * comes within reach_frames; else the reach (the closest pair). On a
 * clock: into the clock's frame (clock_search). */
static cub_err plan_direct(const cub_bridge_table *t, const cub_bridge_query *q,
                           cub_bridge_plan *out)
{
    int nf = frames_of(t, q->from_clip);
    int64_t g0 = first_upcoming(t, q);
    hit h;
    if (q->on_clock) {
        if (!clock_search(t, q, g0, &h)) return CUB_ERR_RANGE;
        write_direct(q, nf, &h, q->reach_frames, out);
        return CUB_OK;
    }
    if (q->start_frames > 0 && start_search(t, q, g0, q->reach_frames, &h)) {
        write_direct(q, nf, &h, q->reach_frames, out);
        return CUB_OK;
    }
    if (!reach_search(t, q, g0, q->reach_frames, &h)) return CUB_ERR_RANGE;
    write_direct(q, nf, &h, q->reach_frames, out);
    return CUB_OK;
}

cub_err cub_bridge_plan_switch(const cub_bridge_table *t, const cub_bridge_query *q,
                               cub_bridge_plan *out, void *work, size_t work_size)
{
    if (out) memset(out, 0, sizeof *out);
    if (!t || !q || !out || !t->finished || !query_ok(t, q)) return CUB_ERR_ARG;
    if (!work || work_size < cub_bridge_plan_work_size(t)) return CUB_ERR_NOMEM;
    if (q->direct_only) return plan_direct(t, q, out);
    cub_err e = plan_within(t, q, out, work);
    if (q->reach_frames <= 0 || (!e && out->total_frames <= q->reach_frames)) return e;
    hit h;
    if (!reach_search(t, q, first_upcoming(t, q), q->reach_frames, &h)) return e;
    memset(out, 0, sizeof *out);
    write_direct(q, frames_of(t, q->from_clip), &h, q->reach_frames, out);
    return CUB_OK;
}

/* The plan within the threshold (see cub_bridge_plan_switch). */
static cub_err plan_within(const cub_bridge_table *t, const cub_bridge_query *q,
                           cub_bridge_plan *out, void *work)
{
    int nf = frames_of(t, q->from_clip);
    int64_t g0 = first_upcoming(t, q);
    int limit = q->from_loops ? nf : (int)(nf - g0);
    int window = q->window_frames ? q->window_frames : CUB_BRIDGE_WINDOW_FRAMES;
    scratch *w = scratch_of(work);
    w->have_body = 0;
    hit h;
    int first = window < limit ? window : limit;
    if (!q->no_routes && route_take(t, q, g0, first, out)) return CUB_OK;
    if (q->start_frames > 0 && start_search(t, q, g0, first, &h)) {
        write_direct(q, nf, &h, window, out);
        return CUB_OK;
    }
    if (q->start_frames > 0 && t->desc.bridge_total > 0) {
        target tg = {0, q->start_frames};
        int found = 0;
        if (q->via_tween) {
            found = tween_route(t, q, g0, first, &tg, 2 * first, w, out);
        } else {
            seed_nodes(t, q, g0, first, w);
            found = start_tween(t, q, 2 * first, w, out);
        }
        if (found) {
            out->window_frames = window;
            return CUB_OK;
        }
    }
    for (;;) {
        if (window > limit) window = limit;
        for (int back = 0; back <= 1; back++) {
            if (!direct_search(t, q, g0, window, back, w, &h)) continue;
            write_direct(q, nf, &h, window, out);
            return CUB_OK;
        }
        if (t->desc.bridge_total > 0 && route_search(t, q, g0, window, w, out)) {
            out->window_frames = window;
            return CUB_OK;
        }
        if (window >= limit) break;
        window *= 2;
    }
    memset(out, 0, sizeof *out);
    return CUB_ERR_RANGE;
}

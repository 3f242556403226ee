/* cubtool bench-bridge — how fast and how smoothly the coach switches clips
 * (issue 4). Over every ordered clip pair of the shipped library and many
 * switch moments (every --step'th frame of the current clip, which loops),
 * it plays the switch through the firmware's player at 30 Hz and prints:
 *   reaction latency: request -> the first switch, ours and the baseline
 *                     that waits for the current clip's pass to end;
 *   joint jump: the largest joint displacement (cm) between the frame
 *                     before and the frame after the switch, with our
 *                     smoothing, a crossfade and a naive cut, beside the
 *                     clips' own 99th-percentile joint speed (cm/frame);
 *   added speed: the most joint speed the smoothing adds to the clip's own
 *                     motion while it runs (frames after the cut), so a
 *                     jump cannot hide in the frames after the switch. Ours
 *                     carries the old clip's velocity over the cut and lets
 *                     it fade; that counts here as added, though it is the
 *                     old clip's own motion going on;
 *   stance-foot slide: cubtool join's measure (a foot the playing clip's
 *                     frame stands on, low on the screen on both frames:
 *                     its ankle's horizontal travel), from the frame before
 *                     the first switch to the blend's end, with the
 *                     player's contacts. "inertial,no-legs" is ours with
 *                     the leg phase off (docs/join.md).
 * --strict plans by the seed's rule (both ends of every switch a bridge
 * frame); --correct asks only for the correcting clips, as the box does
 * when a move went wrong (entry anywhere in their front half, and within
 * the reaction at the closest frame when nothing nearer comes). Each run
 * also counts the switches whose ends are not both bridge frames. --tween
 * routes through the seed's tween clip where today's planner chains
 * through other clips; either way a "routes" line measures those
 * switches: reaction, arrival in the wanted clip, every switch's jump.
 * "ours" takes the table's searched routes (assets/clips/bear.routes.txt,
 * docs/join.md "Routes"), "ours,no-routes" does not (the box before
 * them); the "searched routes" lines count the switches that took one and
 * measure them with and without their routes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "commands.h"
#include "cub/bridge.h"
#include "cub/coachlib.h"
#include "cub/director.h"
#include "tool_util.h"

#define TICK_US 33333
#define MAX_TICKS 600

typedef cub_tool_series stats;

static void push(stats *s, double x)
{
    cub_tool_series_add(s, x, "bench-bridge");
}

/* Nearest-rank percentile (q in 0..1) of the values; sorts them. */
static double pct(stats *s, double q)
{
    return cub_tool_series_pct(s, q);
}

/* Largest joint displacement between two world poses, cm. */
static double max_move_cm(const cub_vec3 *a, const cub_vec3 *b, int n)
{
    double best = 0;
    for (int j = 0; j < n; j++) {
        double dx = (a[j].x - b[j].x) / 65536.0, dy = (a[j].y - b[j].y) / 65536.0,
               dz = (a[j].z - b[j].z) / 65536.0;
        double d = dx * dx + dy * dy + dz * dz;
        if (d > best) best = d;
    }
    return sqrt(best) / 10.0;
}

/* Each clip's own joint speed, cm/frame: p99[c] and top[c] over its frames
 * of the fastest joint's move (what a switch's jump is compared with: the
 * jump is the fastest joint's move too); all_fast and all_joints collect
 * the library's per-frame fastest-joint moves and every joint's move. */
static void clip_speeds(const cub_coachlib *cl, double *p99, double *top, stats *all_fast,
                        stats *all_joints)
{
    static cub_pose pose;
    static cub_vec3 w0[CUB_MOTION_MAX_JOINTS], w1[CUB_MOTION_MAX_JOINTS];
    const cub_skeleton *sk = &cl->lib.skel;
    for (int c = 0; c < cl->lib.clip_count; c++) {
        const cub_clip *clip = &cl->lib.clips[c].clip;
        stats s = {0};
        for (int f = 1; f < clip->frame_count; f++) {
            cub_motion_clip_get_frame(clip, f - 1, &pose);
            cub_motion_forward(sk, &pose, w0, NULL);
            cub_motion_clip_get_frame(clip, f, &pose);
            cub_motion_forward(sk, &pose, w1, NULL);
            for (int j = 0; j < sk->joint_count; j++)
                push(all_joints, max_move_cm(&w0[j], &w1[j], 1));
            double fast = max_move_cm(w0, w1, sk->joint_count);
            push(&s, fast);
            push(all_fast, fast);
        }
        p99[c] = pct(&s, 0.99);
        top[c] = s.n ? s.v[s.n - 1] : 0;
        free(s.v);
    }
}

typedef struct run {
    int ok, tween, steps;
    int routed;         /* the plan is a searched route (the table's routes file) */
    cub_bridge_step first;
    double latency_ms;  /* request -> first switch */
    double arrive_ms;   /* request -> the switch into the wanted clip */
    double jump_cm;     /* across the first switch's frame */
    double blend_cm;    /* most joint speed the smoothing adds, first switch to blend end */
    double slide_cm;    /* stance-foot slide, the frame before the first switch to blend end */
    int switches;       /* carried out, up to CUB_BRIDGE_MAX_STEPS: */
    cub_bridge_step step[CUB_BRIDGE_MAX_STEPS];
    double step_jump_cm[CUB_BRIDGE_MAX_STEPS]; /* across each switch's frame */
} run;

/* The feet the playing clip's frame stands on (the player's contacts:
 * app/join's rule), and which of them are low on the screen now. */
static unsigned stance_low(const cub_bridge_player *p, const cub_vec3 *world)
{
    const cub_bridge_legs *l = &p->legs;
    if (!l->ok) return 0;
    const cub_bridge_clip *c = &p->desc.table->clips[p->clip];
    unsigned bits = 3u & l->contact[c->first_frame + (int)((p->pos_q16 >> 16) % c->clip.frame_count)];
    for (int s = 0; s < 2; s++) {
        cub_q16 low = CUB_Q16_MAX;
        for (int k = 0; k < CUB_BRIDGE_FOOT_JOINTS && l->foot[s][k] >= 0; k++)
            if (world[l->foot[s][k]].y < low) low = world[l->foot[s][k]].y;
        if ((int64_t)low - l->floor_mm[p->clip] >= CUB_Q16_INT(30)) bits &= ~(1u << s);
    }
    return bits;
}

/* Play one switch: clip a from frame m (looping), request b at once. */
static run play(const cub_coachlib *cl, cub_bridge_player *p, int a, int m, int b, int blend)
{
    static cub_pose pose;
    static cub_vec3 prev[CUB_MOTION_MAX_JOINTS], cur[CUB_MOTION_MAX_JOINTS];
    static cub_vec3 raw_prev[CUB_MOTION_MAX_JOINTS], raw_cur[CUB_MOTION_MAX_JOINTS];
    const cub_skeleton *sk = &cl->lib.skel;
    run r = {0};
    cub_bridge_plan plan;
    cub_bridge_player_start(p, a, m, 0, 1);
    if (cub_bridge_player_request(p, b, 0, 1, &plan)) return r;
    r.ok = 1;
    r.steps = plan.step_count;
    r.tween = plan.step[0].via == CUB_BRIDGE_TWEEN;
    r.routed = plan.step[0].via == CUB_BRIDGE_ROUTE;
    r.first = plan.step[0];
    cub_bridge_player_pose(p, &pose);
    cub_motion_forward(sk, &pose, prev, NULL);
    memcpy(raw_prev, prev, sizeof raw_prev);
    int first_tick = -1, quiet_after = -1;
    unsigned stance_prev = stance_low(p, prev);
    double slide_mm[2] = {0, 0};
    for (int t = 1; t < MAX_TICKS; t++) {
        cub_bridge_event ev[8];
        int n = 0;
        cub_bridge_player_advance(p, TICK_US, ev, 8, &n);
        cub_bridge_player_pose(p, &pose);
        cub_motion_forward(sk, &pose, cur, NULL);
        cub_bridge_player_raw_pose(p, &pose);
        cub_motion_forward(sk, &pose, raw_cur, NULL);
        double mv = max_move_cm(prev, cur, sk->joint_count);
        /* A foot that stands, low, on both frames slides by its ankle's
         * horizontal travel (as cubtool join measures it). */
        unsigned stance = stance_low(p, cur);
        for (int s = 0; s < 2 && p->legs.ok; s++) {
            int aj = p->legs.ankle[s];
            if (stance & stance_prev & (1u << s))
                slide_mm[s] += hypot((cur[aj].x - prev[aj].x) / 65536.0,
                                     (cur[aj].z - prev[aj].z) / 65536.0);
        }
        stance_prev = stance;
        /* What the smoothing adds to the clip's own motion: the largest
         * joint's move beyond the same joint's move in the raw clip. */
        double added = 0;
        for (int j = 0; j < sk->joint_count; j++) {
            double extra = max_move_cm(&prev[j], &cur[j], 1) -
                           max_move_cm(&raw_prev[j], &raw_cur[j], 1);
            if (extra > added) added = extra;
        }
        memcpy(prev, cur, sizeof(cub_vec3) * (size_t)sk->joint_count);
        memcpy(raw_prev, raw_cur, sizeof(cub_vec3) * (size_t)sk->joint_count);
        int cut = 0;
        for (int i = 0; i < n; i++) {
            cut |= ev[i].type == CUB_BRIDGE_EV_SWITCH || (ev[i].type == CUB_BRIDGE_EV_DONE);
            if (ev[i].type != CUB_BRIDGE_EV_SWITCH) continue;
            double at_ms = ((t - 1) * (double)TICK_US + (double)ev[i].t_us) / 1000.0;
            if (r.switches < CUB_BRIDGE_MAX_STEPS) {
                r.step[r.switches] = ev[i].step;
                r.step_jump_cm[r.switches++] = mv;
            }
            if (ev[i].step.to_clip == b) r.arrive_ms = at_ms;
            if (first_tick < 0) {
                first_tick = t;
                r.latency_ms = at_ms;
                r.jump_cm = mv;
            }
        }
        if (first_tick >= 0 && !cut && added > r.blend_cm) r.blend_cm = added;
        if (first_tick < 0) slide_mm[0] = slide_mm[1] = 0; /* before the switch */
        /* The window: the first switch until the plan is done and the
         * blend over, at least `blend` frames after the last switch. */
        if (first_tick >= 0 && cub_bridge_player_pending(p)) quiet_after = -1;
        if (first_tick >= 0 && !cub_bridge_player_pending(p) && quiet_after < 0)
            quiet_after = t + blend;
        if (quiet_after >= 0 && t >= quiet_after && !p->blending) break;
    }
    r.slide_cm = (slide_mm[0] > slide_mm[1] ? slide_mm[0] : slide_mm[1]) / 10.0;
    return r;
}

/* The clips a run asks for: every clip, or (--correct) the two correcting ones. */
static int wanted(const cub_coachlib *cl, int correct, int b)
{
    if (!correct) return 1;
    const char *name = cl->lib.clips[b].name;
    return !strcmp(name, "head_shake") || !strcmp(name, "watch_me");
}

/* How the box enters a correcting clip (firmware/director): anywhere in
 * its front half, and within the reaction at the closest frame. */
static void set_entry(cub_bridge_player *p, const cub_coachlib *cl, int correct, int b)
{
    if (!correct) return;
    cub_bridge_player_set_start_frames(p, cl->lib.clips[b].clip.frame_count / 2);
    cub_bridge_player_set_reach_frames(p, CUB_DIRECTOR_REACT_FRAMES);
}

/* Routes: the switches no direct switch served (a chain through other
 * clips, or the tween), every switch of the route counted. */
typedef struct routes {
    stats react, arrive, jump;
    long count, jumps, over_p99;
    double worst;                /* the largest jump at a route's switch, */
    cub_bridge_step worst_step;  /* at this switch, */
    int worst_index;             /* the route's worst_index'th */
} routes;

static void add_route(routes *rt, const run *r, const double *p99)
{
    if (!r->tween) return;
    rt->count++;
    push(&rt->react, r->latency_ms);
    push(&rt->arrive, r->arrive_ms);
    for (int i = 0; i < r->switches; i++) {
        const cub_bridge_step *st = &r->step[i];
        double own = p99[st->from_clip] > p99[st->to_clip] ? p99[st->from_clip] : p99[st->to_clip];
        push(&rt->jump, r->step_jump_cm[i]);
        if (r->step_jump_cm[i] > rt->worst)
            rt->worst = r->step_jump_cm[i], rt->worst_step = *st, rt->worst_index = i + 1;
        rt->jumps++;
        rt->over_p99 += r->step_jump_cm[i] > own;
    }
}

static void print_routes(routes *rt, int via_tween, const char *const *names)
{
    printf("bench-bridge: routes (%s) %ld: reaction median=%.0f p95=%.0f max=%.0f ms; "
           "in the wanted clip median=%.0f p95=%.0f p99=%.0f max=%.0f ms; jumps at their %ld switches "
           "max=%.2f p95=%.2f cm/frame, over own p99: %ld (%.1f%%)\n",
           via_tween ? "through the tween clip" : "chains through other clips", rt->count,
           pct(&rt->react, 0.5), pct(&rt->react, 0.95), pct(&rt->react, 1.0),
           pct(&rt->arrive, 0.5), pct(&rt->arrive, 0.95), pct(&rt->arrive, 0.99),
           pct(&rt->arrive, 1.0), rt->jumps,
           pct(&rt->jump, 1.0), pct(&rt->jump, 0.95), rt->over_p99,
           rt->jumps ? 100.0 * (double)rt->over_p99 / (double)rt->jumps : 0.0);
    if (rt->jumps)
        printf("bench-bridge: routes' largest jump %.2f cm/frame at switch %d of its route: "
               "%s@%d -> %s@%d\n",
               rt->worst, rt->worst_index, names[rt->worst_step.from_clip],
               rt->worst_step.from_frame, names[rt->worst_step.to_clip], rt->worst_step.to_frame);
    free(rt->react.v);
    free(rt->arrive.v);
    free(rt->jump.v);
}

/* The tween clip's own fastest-joint speed (its p99 joins the others'). */
static void tween_speeds(const cub_coachlib *cl, double *p99, double *top)
{
    static cub_pose pose;
    static cub_vec3 w0[CUB_MOTION_MAX_JOINTS], w1[CUB_MOTION_MAX_JOINTS];
    const cub_clip *clip = &cl->tween_clip;
    stats s = {0};
    for (int f = 0; f < clip->frame_count; f++) {
        cub_motion_clip_get_frame(clip, f, &pose);
        cub_motion_forward(&cl->lib.skel, &pose, w0, NULL);
        cub_motion_clip_get_frame(clip, (f + 1) % clip->frame_count, &pose);
        cub_motion_forward(&cl->lib.skel, &pose, w1, NULL);
        push(&s, max_move_cm(w0, w1, cl->lib.skel.joint_count));
    }
    *p99 = pct(&s, 0.99);
    *top = pct(&s, 1.0);
    printf("bench-bridge: tween clip: %d keys of %d bridge frames, %d frames (%.1f s a loop), "
           "its own fastest joint p99=%.2f max=%.2f cm/frame\n",
           cl->tween.key_count, cl->table.desc.bridge_total - 2 * clip->frame_count,
           clip->frame_count, clip->frame_count * TICK_US / 1e6, *p99, *top);
    free(s.v);
}

typedef struct mode {
    const char *name;
    cub_bridge_smooth smooth;
    int no_legs, no_routes;
    stats jump, blend, slide, react;
    int over_p99;
} mode;
#define MODES 5

/* The switches that took a searched route (docs/join.md, "Routes"), and
 * the same switches planned without the routes (the box before them). */
typedef struct searched {
    long pair_switches; /* switches on a pair that has a route */
    stats react[2], slide[2], jump[2];
} searched;

static int has_route(const cub_bridge_table *t, int a, int b)
{
    for (int i = 0; i < t->route_count; i++)
        if (t->routes[i].from == a && t->routes[i].to == b) return 1;
    return 0;
}

static void add_searched(searched *sr, int k, const run *r)
{
    push(&sr->react[k], r->latency_ms);
    push(&sr->slide[k], r->slide_cm);
    push(&sr->jump[k], r->jump_cm);
}

static void print_searched(searched *sr, const cub_bridge_table *t)
{
    static const char *const name[2] = {"with routes", "without (the same switches)"};
    printf("bench-bridge: searched routes: %d in the table; %zu of the %ld switches on their "
           "pairs took one (its first frame within the 200 ms window), the rest planned as "
           "before\n",
           t->route_count, sr->react[0].n, sr->pair_switches);
    for (int k = 0; k < 2 && sr->react[0].n; k++)
        printf("bench-bridge: routed switches %-27s reaction median=%.0f p95=%.0f max=%.0f ms; "
               "stance-foot slide median=%.2f p95=%.2f max=%.2f cm; jump at switch max=%.2f "
               "p95=%.2f median=%.2f cm/frame\n",
               name[k], pct(&sr->react[k], 0.5), pct(&sr->react[k], 0.95),
               pct(&sr->react[k], 1.0), pct(&sr->slide[k], 0.5), pct(&sr->slide[k], 0.95),
               pct(&sr->slide[k], 1.0), pct(&sr->jump[k], 1.0), pct(&sr->jump[k], 0.95),
               pct(&sr->jump[k], 0.5));
    for (int k = 0; k < 2; k++)
        free(sr->react[k].v), free(sr->slide[k].v), free(sr->jump[k].v);
}

static int usage(FILE *f, int code)
{
    fprintf(f, "usage: cubtool bench-bridge [--assets DIR] [--step N] [--blend N] [--window N] "
               "[--wait MM] [--strict] [--correct] [--tween]\n"
               "  Measure clip switching over every ordered clip pair of the library,\n"
               "  switching at every N'th frame (default 5) of the playing clip.\n"
               "  --blend N   shortest smoothing in frames (default %d)\n"
               "  --window N  first look-ahead window in frames (default %d)\n"
               "  --wait MM   what a frame of waiting costs against body distance, mm\n"
               "              (default -1: the soonest frame within the threshold)\n"
               "  --strict    the seed's rule: both ends of every switch are bridge frames\n"
               "  --correct   ask only for the correcting clips, entered as the box does\n"
               "  --tween     route through the seed's tween clip (built from the bridge\n"
               "              frames) where no direct switch serves, instead of chains\n"
               "              through other clips\n"
               "  --tween-cover D  the tween's keys at least this far apart (fuzzy d;\n"
               "              default half the threshold)\n"
               "  --tween-speed MM the tween's fastest joint, mm per frame (default %d)\n",
            CUB_BRIDGE_BLEND_FRAMES, CUB_BRIDGE_WINDOW_FRAMES, CUB_BRIDGE_TWEEN_SPEED_MM >> 16);
    return code;
}

int cub_cmd_bench_bridge(int argc, char **argv)
{
    const char *assets = CUB_ASSETS_DIR;
    int step = 5, blend = 0, window = 0, wait_mm = -1, strict = 0, correct = 0, via_tween = 0;
    cub_bridge_tween_config tcfg = {0};
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help")) return usage(stdout, 0);
        if (!strcmp(argv[i], "--strict")) {
            strict = 1;
            continue;
        }
        if (!strcmp(argv[i], "--correct")) {
            correct = 1;
            continue;
        }
        if (!strcmp(argv[i], "--tween")) {
            via_tween = 1;
            continue;
        }
        if (i + 1 >= argc) return usage(stderr, 2);
        if (!strcmp(argv[i], "--assets"))
            assets = argv[++i];
        else if (!strcmp(argv[i], "--step"))
            step = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--blend"))
            blend = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--window"))
            window = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--wait"))
            wait_mm = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--tween-cover"))
            tcfg.cover_d = (cub_q16)(atof(argv[++i]) * 65536.0);
        else if (!strcmp(argv[i], "--tween-speed"))
            tcfg.speed_mm = CUB_Q16_INT(atoi(argv[++i]));
        else
            return usage(stderr, 2);
    }
    if (step < 1 || blend < 0 || window < 0 || wait_mm < -1 || wait_mm > 30000 ||
        tcfg.cover_d < 0 || tcfg.cover_d > CUB_Q16_ONE || tcfg.speed_mm < 0 ||
        tcfg.speed_mm > CUB_Q16_INT(1000))
        return usage(stderr, 2);
    static cub_coachlib cl;
    cub_diag d = {0};
    char buf[600];
    /* The tween is built either way: both runs plan over the same table. */
    if (cub_coachlib_load_assets(assets, &cl, &d) || cub_coachlib_add_tween(&cl, &tcfg, &d)) {
        fprintf(stderr, "bench-bridge: %s\n", cub_diag_str(&d, buf, sizeof buf));
        return 1;
    }
    int nc = cl.lib.clip_count;
    double *p99 = calloc((size_t)nc + 1, sizeof *p99), *top = calloc((size_t)nc + 1, sizeof *top);
    stats all = {0}, joints = {0}, ours = {0}, base = {0};
    routes rt = {0};
    clip_speeds(&cl, p99, top, &all, &joints);
    tween_speeds(&cl, &p99[nc], &top[nc]);
    double lib_p99 = pct(&all, 0.99), lib_max = all.n ? all.v[all.n - 1] : 0;
    double lib_joint_p99 = pct(&joints, 0.99), lib_median = pct(&all, 0.5);

    mode modes[MODES] = {{.name = "ours(inertial)", .smooth = CUB_BRIDGE_SMOOTH_INERTIAL},
                         {.name = "ours,no-routes", .smooth = CUB_BRIDGE_SMOOTH_INERTIAL,
                          .no_routes = 1},
                         {.name = "inertial,no-legs", .smooth = CUB_BRIDGE_SMOOTH_INERTIAL,
                          .no_legs = 1},
                         {.name = "crossfade", .smooth = CUB_BRIDGE_SMOOTH_CROSSFADE},
                         {.name = "naive-cut", .smooth = CUB_BRIDGE_SMOOTH_NONE}};
    static cub_bridge_player players[MODES];
    void *work[MODES];
    for (int k = 0; k < MODES; k++) {
        cub_bridge_player_desc pd = {.table = &cl.table, .smooth = modes[k].smooth,
                                     .no_legs = modes[k].no_legs,
                                     .no_routes = modes[k].no_routes,
                                     .blend_frames = blend, .window_frames = window,
                                     .wait_cost_mm = wait_mm < 0 ? 0 : CUB_Q16_INT(wait_mm),
                                     .strict = strict, .via_tween = via_tween};
        size_t ws = cub_bridge_player_mem_size(&pd);
        work[k] = malloc(ws);
        if (!work[k] || cub_bridge_player_init(&players[k], &pd, work[k], ws)) {
            fprintf(stderr, "bench-bridge: cannot set up the player\n");
            return 1;
        }
    }
    int blend_frames = players[0].desc.blend_frames;
    long switches = 0, tweens = 0, unreachable = 0, steps = 0, loose_ends = 0;
    run worst = {0};
    int worst_m = 0, worst_b = 0;
    run slidest = {0};
    int slidest_m = 0, slidest_b = 0;
    static searched sr;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (int a = 0; a < nc; a++)
        for (int b = 0; b < nc; b++) {
            if (!wanted(&cl, correct, b)) continue;
            int n = cl.lib.clips[a].clip.frame_count;
            int routed_pair = has_route(&cl.table, a, b);
            for (int m = 0; m < n; m += step) {
                int routed = 0;
                sr.pair_switches += routed_pair;
                for (int k = 0; k < MODES; k++) {
                    set_entry(&players[k], &cl, correct, b);
                    run r = play(&cl, &players[k], a, m, b, blend_frames);
                    if (!r.ok) {
                        unreachable += k == 0;
                        continue;
                    }
                    if (k == 0 && r.blend_cm > worst.blend_cm) worst = r, worst_m = m, worst_b = b;
                    if (k == 0 && r.slide_cm > slidest.slide_cm)
                        slidest = r, slidest_m = m, slidest_b = b;
                    push(&modes[k].jump, r.jump_cm);
                    push(&modes[k].blend, r.blend_cm);
                    push(&modes[k].slide, r.slide_cm);
                    push(&modes[k].react, r.latency_ms);
                    if (k == 0) routed = r.routed;
                    if (routed && k <= 1) add_searched(&sr, k, &r);
                    /* The clips the first switch joins (a tween's first
                     * step enters a clip on the way, not b). */
                    int to = r.first.to_clip;
                    double own = p99[a] > p99[to] ? p99[a] : p99[to];
                    modes[k].over_p99 += r.jump_cm > own;
                    if (k) continue;
                    add_route(&rt, &r, p99);
                    switches++;
                    loose_ends += !cub_bridge_is_bridge(&cl.table, r.first.from_clip, r.first.from_frame) ||
                                  !cub_bridge_is_bridge(&cl.table, r.first.to_clip, r.first.to_frame);
                    tweens += r.tween;
                    steps += r.steps;
                    push(&ours, r.latency_ms);
                    push(&base, (n - m) * TICK_US / 1000.0);
                }
            }
        }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    double secs = (double)(t1.tv_sec - t0.tv_sec) + (double)(t1.tv_nsec - t0.tv_nsec) * 1e-9;
    printf("bench-bridge: clips=%d pairs=%d switches=%ld direct=%ld tween=%ld (mean steps %.2f) "
           "unreachable=%ld window=%d min_blend=%d frames, step=%d%s%s%s\n",
           nc, nc * nc, switches, switches - tweens, tweens,
           switches ? (double)steps / (double)switches : 0.0, unreachable,
           players[0].desc.window_frames, blend_frames, step, strict ? ", strict" : "",
           correct ? ", corrections only" : "", via_tween ? ", via the tween clip" : "");
    printf("bench-bridge: first switches with an end that is not a bridge frame: %ld of %ld "
           "(%.1f%%)\n",
           loose_ends, switches, switches ? 100.0 * (double)loose_ends / (double)switches : 0.0);
    double om = pct(&ours, 0.5), o95 = pct(&ours, 0.95), omax = ours.n ? ours.v[ours.n - 1] : 0;
    printf("bench-bridge: reaction ours median=%.0f ms p95=%.0f ms max=%.0f ms | "
           "wait-for-end median=%.0f ms p95=%.0f ms  (targets: median<=100 p95<=200)\n",
           om, o95, omax, pct(&base, 0.5), pct(&base, 0.95));
    printf("bench-bridge: clips' own fastest-joint speed (cm/frame) median=%.2f p99=%.2f "
           "max=%.2f over the library's frames (every joint's samples: p99=%.2f); a jump is "
           "'over own p99' when above the p99 of both clips it joins\n",
           lib_median, lib_p99, lib_max, lib_joint_p99);
    for (int k = 0; k < MODES; k++) {
        mode *md = &modes[k];
        double jm = pct(&md->jump, 1.0), bm = pct(&md->blend, 1.0); /* the largest */
        printf("bench-bridge: jump at switch %-16s max=%.2f p95=%.2f median=%.2f cm/frame, "
               "over own p99: %d of %zu (%.1f%%); added during blend max=%.2f p95=%.2f; "
               "stance-foot slide median=%.2f p95=%.2f max=%.2f cm; reaction median=%.0f "
               "p95=%.0f max=%.0f ms\n",
               md->name, jm, pct(&md->jump, 0.95), pct(&md->jump, 0.5), md->over_p99, md->jump.n,
               md->jump.n ? 100.0 * md->over_p99 / (double)md->jump.n : 0.0, bm,
               pct(&md->blend, 0.95), pct(&md->slide, 0.5), pct(&md->slide, 0.95),
               pct(&md->slide, 1.0), pct(&md->react, 0.5), pct(&md->react, 0.95),
               pct(&md->react, 1.0));
    }
    const char **names = calloc((size_t)nc + 1, sizeof *names);
    for (int c = 0; names && c <= nc; c++)
        names[c] = c < nc ? cl.lib.clips[c].name : "tween";
    if (names) print_routes(&rt, via_tween, names);
    print_searched(&sr, &cl.table);
    free(names);
    const cub_bridge_step *w = &worst.first;
    printf("bench-bridge: worst blend: %s@%d requested %s: first switch %s@%d -> %s@%d d=%.3f "
           "%s, jump %.2f, during blend %.2f cm/frame\n",
           cl.lib.clips[w->from_clip].name, worst_m, cl.lib.clips[worst_b].name,
           cl.lib.clips[w->from_clip].name, w->from_frame, cl.lib.clips[w->to_clip].name,
           w->to_frame, w->d / 65536.0, worst.tween ? "tween" : "direct", worst.jump_cm,
           worst.blend_cm);
    const cub_bridge_step *ws = &slidest.first;
    printf("bench-bridge: worst slide (ours): %s@%d requested %s: first switch -> %s@%d, "
           "%d switches, slide %.2f cm\n",
           cl.lib.clips[ws->from_clip].name, slidest_m, cl.lib.clips[slidest_b].name,
           cl.lib.clips[ws->to_clip].name, ws->to_frame, slidest.switches, slidest.slide_cm);
    fprintf(stderr, "bench-bridge: %.1f s\n", secs);
    for (int k = 0; k < MODES; k++) {
        free(modes[k].jump.v);
        free(modes[k].blend.v);
        free(modes[k].slide.v);
        free(modes[k].react.v);
        free(work[k]);
    }
    free(ours.v);
    free(base.v);
    free(all.v);
    free(joints.v);
    free(p99);
    free(top);
    cub_coachlib_free(&cl);
    return 0;
}

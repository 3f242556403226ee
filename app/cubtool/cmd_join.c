/* cubtool join — joining two clips without sliding feet (seed 002, § 5;
 * issue 21 § 3; docs/join.md). `join A B` searches the database for the
 * transition C, prints the distances, the chosen C and the join's figures
 * for each method, and writes the joins as BVH; `join --all` measures every
 * ordered pair of the library's dance clips and prints the table:
 *   direct         A's end blended into B's start, every joint at once;
 *   direct+feet    the same, the legs one at a time (the other planted);
 *   searched-all   through C, every joint at once at both seams;
 *   searched       the seed's: through C, the legs one at a time;
 *   bridge(box)    the box: the firmware's planner and player switch from
 *                  A (looping) into B's first frames (join_bridge.c), the
 *                  player's leg phase holding planted feet;
 *   tween(box)     the same with the seed's tween clip in the table: the
 *                  planner routes through it where no direct switch is;
 *   box,no-legs    bridge(box) with the leg phase off (the box before it);
 *   box+routes     bridge(box) taking the shipped searched routes (the
 *                  others ignore them).
 * Per pair, it counts where the seed's join (searched) beats bridge(box),
 * and where it does by more than a cm, whether the box playing the route
 * through C does too: then the route ships (--routes-out; docs/join.md,
 * "Routes"), else a `join route` line says why not. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "commands.h"
#include "cub/join.h"
#include "join_bridge.h"
#include "join_src.h"
#include "tool_util.h"

enum { DIRECT, DIRECT_FEET, SEARCHED_ALL, SEARCHED, METHODS };
static const char *const METHOD_NAME[METHODS] = {"direct", "direct+feet", "searched-all",
                                                 "searched"};

/* Build and measure one method; the join in *keep when not NULL. */
static int run_method(const cub_join_db *db, int a, int b, const cub_join_pick *pick, int m,
                      cub_join_figures *fig, cub_join_result *keep)
{
    cub_join_pick p = *pick;
    if (m == DIRECT || m == DIRECT_FEET) p.clip = -1;
    cub_join_result r;
    if (cub_join_build(db, a, b, &p, m == DIRECT_FEET || m == SEARCHED, &r)) return -1;
    *fig = cub_join_measure(db, &r);
    if (keep)
        *keep = r;
    else
        cub_join_result_free(&r);
    return 0;
}

/* Method m's windows played from the clips themselves, unblended (each seam
 * cut at its middle): their own slide, cm; -1 when out of memory. */
static double own_slide_cm(const cub_join_db *db, int a, int b, const cub_join_pick *pick, int m)
{
    cub_join_pick p = *pick;
    if (m == DIRECT || m == DIRECT_FEET) p.clip = -1;
    cub_join_result r;
    int feet = m == DIRECT_FEET || m == SEARCHED;
    if (cub_join_build(db, a, b, &p, feet | CUB_JOIN_CUT, &r)) return -1;
    double own = cub_join_measure(db, &r).slide_cm;
    cub_join_result_free(&r);
    return own;
}

static double rms_cm(double d_mm2)
{
    return sqrt(d_mm2) / 10.0;
}

static void print_pick(const cub_join_db *db, int a, int b, const cub_join_pick *p)
{
    char ea[64], sb[64], sc[64], ec[64];
    int na = db->clips[a].clip->frame_count;
    printf("join: A=%s (%d frames, ends on %s) B=%s (%d frames, starts on %s)\n", db->clips[a].name,
           na, cub_join_support_name(db->clips[a].support[na - 1], ea, 64), db->clips[b].name,
           db->clips[b].clip->frame_count, cub_join_support_name(db->clips[b].support[0], sb, 64));
    printf("join: direct   D(A|B)=%.1f cm2 (rms %.2f cm), B turned %.1f deg\n",
           p->direct.d_mm2 / 100, rms_cm(p->direct.d_mm2), p->direct.theta_rad * 180 / CUB_VEC_PI);
    printf("join: searched C=%s@%d-%d (%d frames) D(A|C)=%.1f cm2 (rms %.2f cm) D(C|B)=%.1f cm2 "
           "(rms %.2f cm), C turned %.1f deg moved (%.0f, %.0f) mm, %s to %s\n",
           db->clips[p->clip].name, p->first, p->last, p->last - p->first + 1, p->in.d_mm2 / 100,
           rms_cm(p->in.d_mm2), p->out.d_mm2 / 100, rms_cm(p->out.d_mm2),
           p->in.theta_rad * 180 / CUB_VEC_PI, p->in.x0_mm, p->in.z0_mm,
           cub_join_support_name(db->clips[p->clip].support[p->first], sc, 64),
           cub_join_support_name(db->clips[p->clip].support[p->last], ec, 64));
}

static int join_one(join_src *src, const char *an, const char *bn, const char *out,
                    const cub_join_cfg *cfg)
{
    int a = join_src_find(src, an, cfg), b = a < 0 ? -1 : join_src_find(src, bn, cfg);
    if (a < 0 || b < 0) return 1;
    const cub_join_db *db = &src->db;
    cub_join_pick pick;
    if (cub_join_search(db, a, b, &pick)) {
        fprintf(stderr, "join: no clip in the database is long enough for C (%d frames)\n",
                db->cfg.min_frames);
        return 1;
    }
    print_pick(db, a, b, &pick);
    printf("join: %-13s %9s %12s %s\n", "method", "slide cm", "jump cm/f2", "blend frames");
    for (int m = 0; m < METHODS; m++) {
        cub_join_figures fig;
        cub_join_result r;
        if (run_method(db, a, b, &pick, m, &fig, &r)) {
            fprintf(stderr, "join: out of memory\n");
            return 1;
        }
        printf("join: %-13s %9.2f %12.2f %d", METHOD_NAME[m], fig.slide_cm, fig.jump_cm,
               r.win_frames[0]);
        if (r.windows > 1) printf("+%d", r.win_frames[1]);
        printf(" (%d frames in all)\n", r.clip.frame_count);
        if (out && (m == SEARCHED || m == DIRECT)) {
            char path[4096];
            snprintf(path, sizeof path, "%s%s", out, m == DIRECT ? ".direct.bvh" : "");
            if (cub_tool_save_clip_bvh(r.clip.skel, &r.clip, m == DIRECT ? path : out)) {
                cub_join_result_free(&r);
                return 1;
            }
            printf("join: wrote %s (%s)\n", m == DIRECT ? path : out, METHOD_NAME[m]);
        }
        cub_join_result_free(&r);
    }
    return 0;
}

/* The clips --all pairs: the library's dance clips, or every clip when
 * no file says which are dances (BVH files). */
static int paired(const join_src *src, int c)
{
    for (int i = 0; i < src->db.count; i++)
        if (!strcmp(src->kind[i], "dance")) return !strcmp(src->kind[c], "dance");
    return 1;
}

/* The paired clips' own frame-to-frame velocity change. */
static double own_jump_p99(const cub_join_db *db, join_src *src)
{
    cub_tool_series s = {0};
    for (int c = 0; c < db->count; c++) {
        if (!paired(src, c)) continue;
        int n = db->clips[c].clip->frame_count;
        double *j = malloc(sizeof(double) * (size_t)n);
        if (!j) break;
        cub_join_clip_jumps(db, c, j);
        for (int f = 2; f < n; f++)
            cub_tool_series_add(&s, j[f], "join");
        free(j);
    }
    double p = cub_tool_series_pct(&s, 0.99);
    free(s.v);
    return p;
}

static void row(const char *name, cub_tool_series *slide, cub_tool_series *jump)
{
    printf("join --all: %-13s slide cm median=%.2f p95=%.2f max=%.2f | jump cm/f2 median=%.2f "
           "p95=%.2f max=%.2f\n",
           name, cub_tool_series_pct(slide, 0.5), cub_tool_series_pct(slide, 0.95),
           cub_tool_series_pct(slide, 1.0), cub_tool_series_pct(jump, 0.5),
           cub_tool_series_pct(jump, 0.95), cub_tool_series_pct(jump, 1.0));
}

/* A row's clips' own slide over its windows, and its slide beyond that,
 * per pair: the same measure for every row. */
static void own_rows(const char *name, cub_tool_series *own, cub_tool_series *beyond)
{
    printf("join --all: %-13s the clips' own slide over the same frames (unsmoothed) "
           "median=%.2f p95=%.2f max=%.2f cm; slide beyond it, per pair, median=%.2f p95=%.2f "
           "max=%.2f cm\n",
           name, cub_tool_series_pct(own, 0.5), cub_tool_series_pct(own, 0.95),
           cub_tool_series_pct(own, 1.0), cub_tool_series_pct(beyond, 0.5),
           cub_tool_series_pct(beyond, 0.95), cub_tool_series_pct(beyond, 1.0));
}

/* The box (k = 0), the box with the seed's tween (k = 1) and the box
 * without its leg phase (k = 2), over all pairs and (tween) over the pairs
 * it routed through the tween. */
#define BOXES 4
#define BOX_NOW 3 /* the box with the shipped routes (the others ignore them) */
typedef struct box_rows {
    cub_tool_series slide[BOXES], jump[BOXES], ms[BOXES], own[BOXES], beyond[BOXES];
    cub_tool_series tslide, tjump, tms;
    cub_join_figures last[BOXES], last_own[BOXES]; /* the pair just measured (-1: not) */
    join_bridge_fig now;                           /* BOX_NOW's pair just measured */
} box_rows;

static void box_measure(join_bridge *jb, const cub_join_db *db, int a, int b, box_rows *br)
{
    for (int k = 0; k < BOXES; k++) {
        br->last[k] = (cub_join_figures){-1, -1};
        join_bridge_fig jf;
        if (!jb[k].cl.lib.clip_count || join_bridge_measure(&jb[k], db, a, b, &jf)) continue;
        cub_join_figures f = jf.fig;
        double ms = jf.ms;
        cub_tool_series_add(&br->own[k], jf.own.slide_cm, "join");
        cub_tool_series_add(&br->beyond[k], jf.fig.slide_cm - jf.own.slide_cm, "join");
        br->last_own[k] = jf.own;
        if (k == BOX_NOW) br->now = jf;
        br->last[k] = f;
        cub_tool_series_add(&br->slide[k], f.slide_cm, "join");
        cub_tool_series_add(&br->jump[k], f.jump_cm, "join");
        cub_tool_series_add(&br->ms[k], ms, "join");
        if (!jf.tweened) continue;
        cub_tool_series_add(&br->tslide, f.slide_cm, "join");
        cub_tool_series_add(&br->tjump, f.jump_cm, "join");
        cub_tool_series_add(&br->tms, ms, "join");
    }
}

static void box_print(box_rows *br)
{
    static const char *const name[BOXES] = {"bridge(box)", "tween(box)", "box,no-legs",
                                            "box+routes"};
    for (int k = 0; k < BOXES; k++) {
        if (!br->slide[k].n) {
            printf("join --all: %-13s not measured (no assets)\n", name[k]);
            continue;
        }
        row(name[k], &br->slide[k], &br->jump[k]);
        printf("join --all: %-13s on %zu pairs; request to first switch median=%.0f p95=%.0f "
               "max=%.0f ms\n",
               name[k], br->slide[k].n, cub_tool_series_pct(&br->ms[k], 0.5),
               cub_tool_series_pct(&br->ms[k], 0.95), cub_tool_series_pct(&br->ms[k], 1.0));
        own_rows(name[k], &br->own[k], &br->beyond[k]);
    }
    printf("join --all: tween(box) went through the tween clip on %zu pairs", br->tslide.n);
    if (br->tslide.n)
        printf(": slide median=%.2f max=%.2f cm, jump median=%.2f max=%.2f, first switch "
               "median=%.0f max=%.0f ms",
               cub_tool_series_pct(&br->tslide, 0.5), cub_tool_series_pct(&br->tslide, 1.0),
               cub_tool_series_pct(&br->tjump, 0.5), cub_tool_series_pct(&br->tjump, 1.0),
               cub_tool_series_pct(&br->tms, 0.5), cub_tool_series_pct(&br->tms, 1.0));
    printf("\n");
}

static void box_free(box_rows *br)
{
    for (int k = 0; k < BOXES; k++)
        free(br->slide[k].v), free(br->jump[k].v), free(br->ms[k].v), free(br->own[k].v),
            free(br->beyond[k].v);
    free(br->tslide.v), free(br->tjump.v), free(br->tms.v);
}

/* What --all gathers over the pairs. */
typedef struct tally {
    cub_tool_series slide[METHODS], jump[METHODS], own[METHODS], beyond[METHODS], dd, ds;
    int pairs, better, self_c;
    cub_join_figures last[METHODS]; /* the pair just measured */
    cub_join_pick pick;             /* its C */
    double last_own[METHODS];
    /* pairs where the seed's join beats bridge(box): by slide, by more
     * than 1 cm of slide, by jump, by both */
    int box_pairs, beat_slide, beat_slide_1cm, beat_jump, beat_both;
    int beat_excess; /* slide beyond the clips' own: searched's below the box's */
    int clear, clear_jump; /* searched's excess > 1 cm below the box's (and jump) */
    double widest;         /* the widest such margin, cm */
    char widest_pair[2 * CUB_MOTION_NAME_LEN + 8];
} tally;

/* The route question, per pair: does the seed's searched join beat the box?
 * By raw slide, and like for like: each one's slide beyond the slide of
 * the clips it plays over its own windows. */
static void compare_box(tally *t, const box_rows *br, const char *a, const char *b)
{
    const cub_join_figures *s = &t->last[SEARCHED], *x = &br->last[0];
    if (x->slide_cm < 0) return;
    t->box_pairs++;
    t->beat_slide += s->slide_cm < x->slide_cm;
    t->beat_slide_1cm += s->slide_cm < x->slide_cm - 1.0;
    t->beat_jump += s->jump_cm < x->jump_cm;
    t->beat_both += s->slide_cm < x->slide_cm && s->jump_cm < x->jump_cm;
    double excess = x->slide_cm - br->last_own[0].slide_cm;
    double seed = s->slide_cm - t->last_own[SEARCHED];
    t->beat_excess += seed < excess;
    if (seed < excess - 1.0) {
        t->clear++;
        t->clear_jump += s->jump_cm < x->jump_cm;
        if (excess - seed > t->widest) {
            t->widest = excess - seed;
            snprintf(t->widest_pair, sizeof t->widest_pair, "%s -> %s", a, b);
        }
    }
}

/* The routes (docs/join.md, "Routes"). A pair is a candidate where the
 * seed's join slides more than ROUTE_GAIN_CM less than the box's switch,
 * each beyond the slide of the clips it plays (like for like). The box
 * then plays the route through the seed's C itself (its planner and
 * player, legs on), and the route ships when that slides more than
 * ROUTE_GAIN_CM less than its switch, beyond own, no more raw, with no
 * larger jump (or one within the paired clips' own p99 velocity change):
 * what the box would show, not what the seed's blend shows. */
#define ROUTE_GAIN_CM 1.0
typedef struct route_tally {
    cub_routes shipped;
    int candidates, no_route, late, no_gain, worse_jump;
    double own_p99; /* the paired clips' own velocity change: a jump below it is no jump */
    cub_tool_series slide, raw, jump; /* per pair: the box with the routes it ships */
} route_tally;

/* Why the box takes no route for a candidate pair; NULL: it ships. */
static const char *route_verdict(const join_bridge_fig *f, const join_bridge_fig *routed,
                                 double box, route_tally *rt, char *buf, size_t size)
{
    double got = routed->fig.slide_cm - routed->own.slide_cm;
    if (routed->ms > 200.0) {
        rt->late++;
        snprintf(buf, size, "its first switch comes %.0f ms after the request (over 200)",
                 routed->ms);
    } else if (!(got < box - ROUTE_GAIN_CM)) {
        rt->no_gain++;
        snprintf(buf, size, "the box through C slides %.2f cm beyond own, its switch %.2f",
                 got, box);
    } else if (routed->fig.slide_cm > f->fig.slide_cm) {
        rt->no_gain++;
        snprintf(buf, size, "the box through C slides %.2f cm raw, its switch %.2f",
                 routed->fig.slide_cm, f->fig.slide_cm);
    } else if (routed->fig.jump_cm > f->fig.jump_cm && routed->fig.jump_cm > rt->own_p99) {
        rt->worse_jump++;
        snprintf(buf, size, "the box through C jumps %.2f cm/f2, its switch %.2f, the clips' p99 %.2f",
                 routed->fig.jump_cm, f->fig.jump_cm, rt->own_p99);
    } else {
        return NULL;
    }
    return buf;
}

static void route_pair(join_bridge *jb, const cub_join_db *db, int a, int b, const tally *t,
                       const box_rows *br, route_tally *rt)
{
    join_bridge_fig f = {.fig = br->last[0], .own = br->last_own[0]}, routed = f;
    if (f.fig.slide_cm < 0 || !jb->cl.lib.clip_count) return;
    double box = f.fig.slide_cm - f.own.slide_cm;
    double seed = t->last[SEARCHED].slide_cm - t->last_own[SEARCHED];
    const join_bridge_fig *with = &f;
    if (seed < box - ROUTE_GAIN_CM) {
        rt->candidates++;
        cub_bridge_route r;
        char buf[160];
        const char *why = "C is not in the box's library, or too short";
        if (join_bridge_route_of(jb, db, a, b, &t->pick, &r)) {
            rt->no_route++;
        } else if (join_bridge_measure_route(jb, db, a, b, &r, &routed) || !routed.routed) {
            why = "the planner did not take it", rt->no_route++;
        } else {
            why = route_verdict(&f, &routed, box, rt, buf, sizeof buf);
        }
        printf("join route %s -> %s: C=%s@%d-%d; slide beyond own / raw cm, jump cm/f2: seed "
               "%.2f / %.2f, %.2f; box %.2f / %.2f, %.2f; box through C %.2f / %.2f, %.2f, first "
               "switch %.0f ms: %s%s\n",
               db->clips[a].name, db->clips[b].name, db->clips[t->pick.clip].name,
               t->pick.first, t->pick.last, seed, t->last[SEARCHED].slide_cm,
               t->last[SEARCHED].jump_cm, box, f.fig.slide_cm, f.fig.jump_cm,
               routed.fig.slide_cm - routed.own.slide_cm, routed.fig.slide_cm, routed.fig.jump_cm,
               routed.ms, why ? "no route: " : "route", why ? why : "");
        if (!why && rt->shipped.count < CUB_ROUTES_MAX) {
            int i = rt->shipped.count++;
            rt->shipped.route[i] = r;
            rt->shipped.align[i][0] = t->pick.in.theta_rad * 180 / CUB_VEC_PI;
            rt->shipped.align[i][1] = t->pick.in.x0_mm;
            rt->shipped.align[i][2] = t->pick.in.z0_mm;
            with = &routed;
        }
    }
    cub_tool_series_add(&rt->slide, with->fig.slide_cm - with->own.slide_cm, "join");
    cub_tool_series_add(&rt->raw, with->fig.slide_cm, "join");
    cub_tool_series_add(&rt->jump, with->fig.jump_cm, "join");
}

static void route_print(route_tally *rt)
{
    printf("join --all: routes: %d candidate pairs (the seed's join slides > %.0f cm less than "
           "the box's switch beyond own), %d shipped (the box through C slides > %.0f cm less "
           "beyond own, no more raw, no larger jump or one below the clips' p99 %.2f); not: %d "
           "no gain in the box, %d a larger jump, %d over 200 ms, %d no route\n",
           rt->candidates, ROUTE_GAIN_CM, rt->shipped.count, ROUTE_GAIN_CM, rt->own_p99,
           rt->no_gain, rt->worse_jump, rt->late, rt->no_route);
    if (rt->slide.n)
        printf("join --all: the box with these routes (%zu pairs): slide raw median=%.2f "
               "p95=%.2f max=%.2f, beyond own median=%.2f p95=%.2f max=%.2f cm | jump "
               "median=%.2f p95=%.2f max=%.2f\n",
               rt->slide.n, cub_tool_series_pct(&rt->raw, 0.5),
               cub_tool_series_pct(&rt->raw, 0.95), cub_tool_series_pct(&rt->raw, 1.0),
               cub_tool_series_pct(&rt->slide, 0.5), cub_tool_series_pct(&rt->slide, 0.95),
               cub_tool_series_pct(&rt->slide, 1.0), cub_tool_series_pct(&rt->jump, 0.5),
               cub_tool_series_pct(&rt->jump, 0.95), cub_tool_series_pct(&rt->jump, 1.0));
}

/* Search, join by every method and measure one pair. 0 ok (or no C). */
static int one_pair(const cub_join_db *db, int a, int b, int verbose, tally *t)
{
    cub_join_pick pick;
    if (cub_join_search(db, a, b, &pick)) return 0;
    t->pairs++;
    cub_tool_series_add(&t->dd, rms_cm(pick.direct.d_mm2), "join");
    cub_tool_series_add(&t->ds, rms_cm(pick.in.d_mm2 + pick.out.d_mm2), "join");
    t->better += pick.in.d_mm2 + pick.out.d_mm2 < pick.direct.d_mm2;
    t->self_c += pick.clip == a || pick.clip == b;
    t->pick = pick;
    cub_join_figures fig[METHODS];
    for (int m = 0; m < METHODS; m++) {
        if (run_method(db, a, b, &pick, m, &fig[m], NULL)) {
            fprintf(stderr, "join: out of memory\n");
            return -1;
        }
        double own = own_slide_cm(db, a, b, &pick, m);
        if (own < 0) {
            fprintf(stderr, "join: out of memory\n");
            return -1;
        }
        cub_tool_series_add(&t->slide[m], fig[m].slide_cm, "join");
        cub_tool_series_add(&t->jump[m], fig[m].jump_cm, "join");
        cub_tool_series_add(&t->own[m], own, "join");
        cub_tool_series_add(&t->beyond[m], fig[m].slide_cm - own, "join");
        t->last[m] = fig[m];
        t->last_own[m] = own;
    }
    if (verbose)
        printf("join pair %s -> %s: C=%s@%d-%d rms direct %.2f searched %.2f+%.2f cm; "
               "slide direct %.2f searched %.2f cm; jump direct %.2f searched %.2f\n",
               db->clips[a].name, db->clips[b].name, db->clips[pick.clip].name, pick.first,
               pick.last, rms_cm(pick.direct.d_mm2), rms_cm(pick.in.d_mm2), rms_cm(pick.out.d_mm2),
               fig[DIRECT].slide_cm, fig[SEARCHED].slide_cm, fig[DIRECT].jump_cm,
               fig[SEARCHED].jump_cm);
    return 0;
}

static void print_tally(const cub_join_db *db, tally *t)
{
    printf("join --all: %d ordered pairs of clips, database %d clips, window %d frames, "
           "C %d..%d frames\n",
           t->pairs, db->count, db->cfg.window_frames, db->cfg.min_frames, db->cfg.max_frames);
    printf("join --all: seam distance rms cm: direct median=%.2f p95=%.2f; searched (both "
           "seams) median=%.2f p95=%.2f; searched below direct in %d of %d; C from A or B in %d\n",
           cub_tool_series_pct(&t->dd, 0.5), cub_tool_series_pct(&t->dd, 0.95),
           cub_tool_series_pct(&t->ds, 0.5), cub_tool_series_pct(&t->ds, 0.95), t->better, t->pairs,
           t->self_c);
    for (int m = 0; m < METHODS; m++) {
        row(METHOD_NAME[m], &t->slide[m], &t->jump[m]);
        own_rows(METHOD_NAME[m], &t->own[m], &t->beyond[m]);
    }
}

/* Which way the box now goes (box+routes, the shipped routes file). */
static void print_now(const cub_join_db *db, int a, int b, const box_rows *br)
{
    const join_bridge_fig *n = &br->now;
    if (br->last[BOX_NOW].slide_cm < 0) return;
    printf("join pair %s -> %s: the box now goes %s (%d switch%s, first after %.0f ms): slide "
           "%.2f cm (own %.2f) jump %.2f\n",
           db->clips[a].name, db->clips[b].name,
           n->routed ? "by its route" : n->steps > 1 ? "by a chain" : "directly", n->steps,
           n->steps == 1 ? "" : "es", n->ms, n->fig.slide_cm, n->own.slide_cm, n->fig.jump_cm);
}

static int join_all(join_src *src, join_bridge *jb, int verbose, const char *routes_out)
{
    const cub_join_db *db = &src->db;
    static box_rows br;
    static tally t;
    static route_tally rt;
    int rc = 0;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    rt.own_p99 = own_jump_p99(db, src);
    for (int a = 0; a < db->count && !rc; a++)
        for (int b = 0; b < db->count && !rc; b++) {
            if (a == b || !paired(src, a) || !paired(src, b)) continue;
            rc = one_pair(db, a, b, verbose, &t);
            if (!jb || rc) continue;
            box_measure(jb, db, a, b, &br);
            compare_box(&t, &br, db->clips[a].name, db->clips[b].name);
            if (verbose && br.last[0].slide_cm >= 0)
                printf("join pair %s -> %s: box slide %.2f cm (own %.2f) jump %.2f; no legs "
                       "slide %.2f jump %.2f\n",
                       db->clips[a].name, db->clips[b].name, br.last[0].slide_cm,
                       br.last_own[0].slide_cm, br.last[0].jump_cm, br.last[2].slide_cm,
                       br.last[2].jump_cm);
            if (verbose) print_now(db, a, b, &br);
            route_pair(&jb[BOX_NOW], db, a, b, &t, &br, &rt);
        }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    if (!rc) {
        print_tally(db, &t);
        if (jb) box_print(&br);
        if (t.box_pairs)
            printf("join --all: searched (the seed's) beats bridge(box) on %d of %d pairs by "
                   "slide (by more than 1 cm: %d), on %d by jump, on %d by both\n",
                   t.beat_slide, t.box_pairs, t.beat_slide_1cm, t.beat_jump, t.beat_both);
        if (t.box_pairs)
            printf("join --all: like for like, each one's slide beyond its clips' own over its "
                   "windows: searched's is below bridge(box)'s on %d of %d pairs, by more than "
                   "1 cm on %d (its jump also below the box's on %d); the widest margin %.2f cm "
                   "(%s)\n",
                   t.beat_excess, t.box_pairs, t.clear, t.clear_jump, t.widest,
                   t.clear ? t.widest_pair : "-");
        printf("join --all: the paired clips' own velocity change p99=%.2f cm/f2\n",
               own_jump_p99(db, src));
        if (jb) route_print(&rt);
        cub_diag d = {0};
        char msg[600];
        if (jb && routes_out && cub_routes_write(routes_out, &jb[0].cl.lib, &rt.shipped, &d)) {
            fprintf(stderr, "join: %s\n", cub_diag_str(&d, msg, sizeof msg));
            rc = -1;
        } else if (jb && routes_out) {
            printf("join --all: wrote %d routes to %s\n", rt.shipped.count, routes_out);
        }
        fprintf(stderr, "join --all: %.1f s\n",
                (double)(t1.tv_sec - t0.tv_sec) + (double)(t1.tv_nsec - t0.tv_nsec) * 1e-9);
    }
    for (int m = 0; m < METHODS; m++)
        free(t.slide[m].v), free(t.jump[m].v), free(t.own[m].v), free(t.beyond[m].v);
    free(t.dd.v), free(t.ds.v);
    box_free(&br);
    free(rt.slide.v), free(rt.raw.v), free(rt.jump.v);
    return rc ? 1 : 0;
}

static int usage(FILE *f, int code)
{
    fprintf(f, "usage: cubtool join A B [--lib LIB.cubclips] [--db CLIPS]... [--out C.bvh]\n"
               "       cubtool join --all [--assets DIR] [--db CLIPS]... [--pairs] [--routes-out F]\n"
               "  A, B      clip names in the database, or .bvh files on its skeleton\n"
               "  --lib     the library (default: the shipped assets/clips/bear.cubclips), or\n"
               "            a .bvh: then --all pairs every clip given\n"
               "  --db      more clips to search (a .cubclips or a .bvh; repeatable)\n"
               "  --out     write the seed's join (searched, legs one at a time) as BVH,\n"
               "            and the direct one as C.bvh.direct.bvh\n"
               "  --all     every ordered pair of the library's dance clips: the table, with\n"
               "            the box's switch (bridge planner + player, with and without its\n"
               "            leg phase) from --assets DIR\n"
               "  --pairs   with --all, a line per pair (and which way the box now goes)\n"
               "  --routes-out FILE  with --all, write the routes the box ships\n"
               "            (assets/clips/bear.routes.txt; docs/join.md, \"Routes\")\n");
    return code;
}

int cub_cmd_join(int argc, char **argv)
{
    const char *lib = NULL, *assets = CUB_ASSETS_DIR, *out = NULL, *pos[2] = {NULL, NULL};
    const char *routes_out = NULL;
    const char *db_files[JOIN_SRC_MAX];
    int ndb = 0, all = 0, verbose = 0, npos = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) return usage(stdout, 0);
        if (!strcmp(argv[i], "--all")) {
            all = 1;
        } else if (!strcmp(argv[i], "--pairs")) {
            verbose = 1;
        } else if (argv[i][0] == '-' && i + 1 < argc && !strcmp(argv[i], "--lib")) {
            lib = argv[++i];
        } else if (argv[i][0] == '-' && i + 1 < argc && !strcmp(argv[i], "--assets")) {
            assets = argv[++i];
        } else if (argv[i][0] == '-' && i + 1 < argc && !strcmp(argv[i], "--routes-out")) {
            routes_out = argv[++i];
        } else if (argv[i][0] == '-' && i + 1 < argc && !strcmp(argv[i], "--out")) {
            out = argv[++i];
        } else if (argv[i][0] == '-' && i + 1 < argc && !strcmp(argv[i], "--db") &&
                   ndb < JOIN_SRC_MAX - 1) {
            db_files[ndb++] = argv[++i];
        } else if (argv[i][0] != '-' && npos < 2) {
            pos[npos++] = argv[i];
        } else {
            fprintf(stderr, "cubtool join: unexpected '%s'\n", argv[i]);
            return usage(stderr, 2);
        }
    }
    if (all ? npos != 0 : npos != 2) return usage(stderr, 2);
    static join_src src;
    static join_bridge jb[BOXES];
    char lib_path[4096];
    snprintf(lib_path, sizeof lib_path, "%s/clips/bear.cubclips", assets);
    cub_join_cfg cfg = {0};
    int rc = join_src_add(&src, lib ? lib : lib_path, &cfg) ? 1 : 0;
    for (int i = 0; !rc && i < ndb; i++)
        rc = join_src_add(&src, db_files[i], &cfg) ? 1 : 0;
    int have_jb = !rc && all && !join_bridge_open(&jb[0], assets, &src.db, 0, 1, 0);
    if (have_jb && join_bridge_open(&jb[1], assets, &src.db, 1, 1, 0)) memset(&jb[1], 0, sizeof jb[1]);
    if (have_jb && join_bridge_open(&jb[2], assets, &src.db, 0, 0, 0)) memset(&jb[2], 0, sizeof jb[2]);
    if (have_jb && join_bridge_open(&jb[3], assets, &src.db, 0, 1, 1)) memset(&jb[3], 0, sizeof jb[3]);
    if (!rc)
        rc = all ? join_all(&src, have_jb ? jb : NULL, verbose, routes_out)
                 : join_one(&src, pos[0], pos[1], out, &cfg);
    for (int k = 0; have_jb && k < BOXES; k++)
        join_bridge_close(&jb[k]);
    join_src_free(&src);
    return rc;
}

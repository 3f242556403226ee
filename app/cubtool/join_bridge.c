#include "join_bridge.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TICK_US 33333
#define MAX_TICKS 240
#define START_FRAMES 4 /* the director's start_frames default */

int join_bridge_open(join_bridge *jb, const char *assets, const cub_join_db *db, int via_tween,
                     int legs, int routes)
{
    cub_diag d = {0};
    char msg[600];
    memset(jb, 0, sizeof *jb);
    jb->via_tween = via_tween;
    if (cub_coachlib_load_assets(assets, &jb->cl, &d) ||
        (via_tween && (cub_coachlib_add_tween(&jb->cl, NULL, &d) ||
                       cub_join_db_init(&jb->tween, &jb->cl.lib.skel, &db->cfg, &d)))) {
        fprintf(stderr, "join: %s\n", cub_diag_str(&d, msg, sizeof msg));
        join_bridge_close(jb);
        return -1;
    }
    if (via_tween && cub_join_db_add(&jb->tween, "tween", &jb->cl.tween_clip, NULL)) {
        fprintf(stderr, "join: the tween clip cannot be measured\n");
        join_bridge_close(jb);
        return -1;
    }
    cub_bridge_player_desc pd = {
        .table = &jb->cl.table, .smooth = CUB_BRIDGE_SMOOTH_INERTIAL, .via_tween = via_tween,
        .no_legs = !legs, .no_routes = !routes};
    size_t ws = cub_bridge_player_mem_size(&pd);
    jb->work = malloc(ws);
    jb->db_of = malloc(sizeof(int) * (size_t)jb->cl.table.desc.clip_count);
    if (!jb->work || !jb->db_of || cub_bridge_player_init(&jb->player, &pd, jb->work, ws)) {
        fprintf(stderr, "join: cannot set up the bridge player\n");
        join_bridge_close(jb);
        return -1;
    }
    for (int c = 0; c < jb->cl.table.desc.clip_count; c++)
        jb->db_of[c] = -1;
    for (int c = 0; c < jb->cl.lib.clip_count; c++) {
        jb->db_of[c] = -1;
        for (int i = 0; i < db->count; i++)
            if (!strcmp(db->clips[i].name, jb->cl.lib.clips[c].name) &&
                db->clips[i].clip->frame_count == jb->cl.lib.clips[c].clip.frame_count)
                jb->db_of[c] = i;
    }
    return 0;
}

static int lib_of(const join_bridge *jb, int db_clip)
{
    for (int c = 0; c < jb->cl.lib.clip_count; c++)
        if (jb->db_of[c] == db_clip) return c;
    return -1;
}

/* The stance bits of what the player shows now: the feet the playing
 * clip's frame stands on. */
static unsigned char stance_now(const join_bridge *jb, const cub_join_db *db)
{
    const cub_bridge_player *p = &jb->player;
    int c = jb->db_of[p->clip];
    const cub_join_clip *jc = c >= 0 ? &db->clips[c] : NULL;
    if (jb->via_tween && p->clip == jb->cl.tween_index)
        jc = &jb->tween.clips[0]; /* two passes of the loop: frames modulo one */
    if (!jc) return 0;
    int f = (int)((p->pos_q16 >> 16) % jc->clip->frame_count);
    return (unsigned char)(jc->foot[0][f] | jc->foot[1][f] << 1);
}

/* The poses of one switch: shown (smoothed) and the clips' own (raw). */
typedef struct played {
    cub_join_result shown, raw;
} played;

static void put(join_bridge *jb, const cub_join_db *db, played *pl, int t, int cut)
{
    static cub_pose pose;
    cub_bridge_player_pose(&jb->player, &pose);
    cub_motion_clip_set_frame(&pl->shown.clip, t, &pose);
    cub_bridge_player_raw_pose(&jb->player, &pose);
    cub_motion_clip_set_frame(&pl->raw.clip, t, &pose);
    pl->shown.stance[t] = stance_now(jb, db);
    /* The raw clips jump at a cut: no foot stands across it there. */
    pl->raw.stance[t] = cut ? 0 : pl->shown.stance[t];
}

/* Play until the plan is done and the blend over, the poses into pl
 * (frames allocated by the caller, MAX_TICKS + 1). Returns the first
 * switch's tick, or -1. */
static int play(join_bridge *jb, const cub_join_db *db, played *pl, double *ms)
{
    cub_bridge_player *p = &jb->player;
    int first = -1, t = 0;
    put(jb, db, pl, 0, 0);
    for (t = 1; t <= MAX_TICKS; t++) {
        cub_bridge_event ev[8];
        int n = 0;
        cub_bridge_player_advance(p, TICK_US, ev, 8, &n);
        put(jb, db, pl, t, n > 0);
        for (int i = 0; i < n; i++)
            if (ev[i].type == CUB_BRIDGE_EV_SWITCH && first < 0) {
                first = t;
                *ms = ((t - 1) * (double)TICK_US + (double)ev[i].t_us) / 1000.0;
            }
        if (first >= 0 && !cub_bridge_player_pending(p) && !p->blending) break;
    }
    int frames = t <= MAX_TICKS ? t + 1 : MAX_TICKS + 1;
    pl->shown.clip.frame_count = pl->raw.clip.frame_count = frames;
    return first;
}

static int alloc_result(const cub_join_db *db, cub_join_result *r)
{
    size_t size = cub_motion_clip_mem_size(db->skel->joint_count, MAX_TICKS + 1, 0);
    r->mem = malloc(size);
    r->stance = calloc(MAX_TICKS + 1, 1);
    return r->mem && r->stance &&
           !cub_motion_clip_init(&r->clip, db->skel, MAX_TICKS + 1, 33333333, 0, r->mem, size);
}

/* The join: from the frame before the switch to the blend's end. */
static cub_join_figures measure(const cub_join_db *db, int a, int first, cub_join_result *r)
{
    r->windows = 1;
    r->win_first[0] = first;
    r->win_frames[0] = r->clip.frame_count - 1 - first;
    r->floor_mm = db->clips[a].floor_mm;
    return cub_join_measure(db, r);
}

int join_bridge_measure(join_bridge *jb, const cub_join_db *db, int a, int b, join_bridge_fig *out)
{
    int la = lib_of(jb, a), lb = lib_of(jb, b);
    if (la < 0 || lb < 0) return -1;
    int na = jb->cl.lib.clips[la].clip.frame_count, w = db->cfg.window_frames;
    cub_bridge_player_set_start_frames(&jb->player, START_FRAMES);
    cub_bridge_plan plan;
    if (cub_bridge_player_start(&jb->player, la, na - w, 0, 1) ||
        cub_bridge_player_request(&jb->player, lb, 0, 0, &plan))
        return -1;
    memset(out, 0, sizeof *out);
    for (int i = 0; i < plan.step_count; i++) {
        out->tweened |= jb->via_tween && plan.step[i].to_clip == jb->cl.tween_index;
        out->routed |= plan.step[i].via == CUB_BRIDGE_ROUTE;
    }
    out->steps = plan.step_count;
    played pl;
    memset(&pl, 0, sizeof pl);
    int ok = alloc_result(db, &pl.shown) && alloc_result(db, &pl.raw);
    int first = ok ? play(jb, db, &pl, &out->ms) : -1;
    if (first >= 0) {
        out->fig = measure(db, a, first, &pl.shown);
        out->own = measure(db, a, first, &pl.raw);
    }
    cub_join_result_free(&pl.shown);
    cub_join_result_free(&pl.raw);
    return first >= 0 ? 0 : -1;
}

int join_bridge_route_of(const join_bridge *jb, const cub_join_db *db, int a, int b,
                         const cub_join_pick *pick, cub_bridge_route *out)
{
    int la = lib_of(jb, a), lb = lib_of(jb, b), lc = pick->clip >= 0 ? lib_of(jb, pick->clip) : -1;
    int w = db->cfg.window_frames, in = pick->first + w, o = pick->last - w;
    if (la < 0 || lb < 0 || lc < 0 || in >= o) return -1;
    int na = jb->cl.lib.clips[la].clip.frame_count;
    *out = (cub_bridge_route){(int16_t)la, (int16_t)lb, (int16_t)lc, (int16_t)(na - 1),
                              (int16_t)in, (int16_t)o, 0, 0};
    return 0;
}

int join_bridge_measure_route(join_bridge *jb, const cub_join_db *db, int a, int b,
                              const cub_bridge_route *r, join_bridge_fig *out)
{
    cub_bridge_table *t = &jb->cl.table;
    const cub_bridge_route *keep = t->routes;
    int keep_n = t->route_count;
    t->routes = r; /* the tool's own table: a trial, put back below */
    t->route_count = 1;
    int rc = join_bridge_measure(jb, db, a, b, out);
    t->routes = keep;
    t->route_count = keep_n;
    return rc;
}

void join_bridge_close(join_bridge *jb)
{
    cub_coachlib_free(&jb->cl);
    if (jb->via_tween) cub_join_db_free(&jb->tween);
    free(jb->work);
    free(jb->db_of);
    memset(jb, 0, sizeof *jb);
}

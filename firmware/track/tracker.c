/* tracker — one Kinect v1 depth frame to the player's 20-joint skeleton.
 *
 * Method: geodesic extremities (Skeltrack's idea) on a downsampled depth
 * graph, then a body model placed by proportions of the measured stature.
 * No training, invariant to pose and size, integer everywhere (the same
 * output on x86-64 and aarch64). docs/tracker.md tells every step in
 * detail, why this method, and the tuning history with its figures;
 * docs/tracker_eval.md the held-out protocol every change is measured by.
 *
 * The pipeline, per frame (cub_track_frame below), and where each step is:
 *   1. depth: a 160x120 grid of 4x4-pixel cells, each the nearest valid
 *      reading, raw -> mm by table                   trk_grid.c trk_grid_fill
 *   2. floor: up from gravity, else the camera pitch whose heights have
 *      the densest low layer; floor cells go   trk_floor_update, _remove;
 *      the room's background (per cell the farthest depth that stayed
 *      still, learnt over time, never stored): cells at it go   trk_bg.c
 *   3. blobs by depth continuity                          trk_components
 *   4. player: the person-like blob on the player's track (its centre
 *      and velocity along the floor; nobody else takes over while the
 *      track lives, 2 s unseen), chosen afresh once when the room becomes
 *      known; its hands before it merged back, a blob joining it to
 *      another person split                          trk_pick_player
 *   5. geodesic: root = the silhouette's thickest cell (the torso);
 *      Dijkstra over the player's cells with 3D steps, depth jumps
 *      costing extra; the extremities are the farthest points, one by
 *      one                         trk_geo.c trk_root_cell, trk_extrema
 *   6. head and stature: the round, central extremity that stands out
 *      farthest (or the column's top above the root); stature from the
 *      floor or the neck base, learnt over frames   trk_head.c trk_fit_head
 *   7. body frame: shoulder centre, pelvis, torso axis, left direction,
 *      stature and the arms' roots, computed once into a trk_frame that
 *      every later step reads                       trk_fit.c body_frame
 *   8. limbs: an extremity is a leg when its path joins the torso low and
 *      is long or its tip is low; the two longest legs are the feet; the
 *      hands are named both at once by a cost per candidate and side
 *      (surface from each shoulder, side of the body, path's side, last
 *      frame's hand)    trk_fit.c classify_limbs, name_feet; trk_hands.c
 *      trk_cost_hands, trk_choose_hands
 *   9. resolvers: the special poses those rules get wrong (a bow, a foot
 *      raised within reach, a knee, a bump on a shoulder or the skull, a
 *      path from across the body, the reach along the surface (not for
 *      an arm pointing at the camera), legs together, a hand before the
 *      torso, an elbow taken for the hand or a guard's fist, an arm
 *      hanging against the thigh), each a function of one signature, run
 *      in the order of one table at the stage of step 8 it names, each
 *      with its unit test (tests/track/test_trk_resolvers.c) trk_resolve.c
 *  10. joints: torso joints down the axis onto the surface; elbows and
 *      knees fit both bone lengths scaled to the limb's reach learnt per
 *      player; a limb with no extremity hangs or keeps last frame's pose
 *                                     trk_fit.c trk_fit_skeleton
 *  11. smoothing: jitter averaged, real motion (limits per 100 ms)
 *      passed through                                trk_smooth
 *  12. confidence: a found joint is confident only when the depth backs
 *      it (its cell the player's at its depth, the cells around agreeing,
 *      the body facing the camera and, left or right, not side-on in the
 *      last 2 s, little motion since last frame)
 *                                          trk_conf.c trk_confidence
 *  13. the forest (cub_track_desc.forest, when given): the body-part
 *      forest on the mask's pixels; its confident joints replace those the
 *      tracker is not confident of, feet excepted    trk_forest.c
 *
 * Units: mm in camera space (x right, y up, z away; the image is
 * mirrored, TRK_LEFT_SIGN); thresholds of the body in per mille of the
 * stature (pm() in trk_body.h) unless their name says mm; weights in
 * quarters. trk_internal.h holds the tracker's state, trk_body.h the
 * body's proportions and the geometry helpers.
 *
 * To change a heuristic: find its resolver in trk_resolve.c's table, its
 * history in docs/tracker.md, run its test in tests/track
 * (test_trk_resolvers), then the folds (docs/tracker_eval.md).
 *
 * Defaults: min_mm 500, max_mm 4500 (readings outside are ignored). Status:
 * TOO_CLOSE when the player's centre is nearer than 1000 mm or any body
 * that near fills an eighth of the view (with or without a player: a
 * child bent over at 0.6 m is no person-like blob, and whoever stands
 * behind it is not the player to judge), TOO_FAR beyond 3500 mm,
 * PARTLY_OUT when the body touches the image's edge. */
#include "trk_internal.h"

#define TRK_DEFAULT_MIN_MM 500
#define TRK_DEFAULT_MAX_MM 4500
#define TRK_LOST_RESET 60 /* frames without the player before a new one may take over (2 s at 30 fps;
                           * trk_pick_player holds 2 s by the frames' times) */

/* The forest's scratch goes after the struct, at a 16-byte boundary. */
#define TRK_STRUCT_BYTES ((sizeof(cub_tracker) + 15) & ~(size_t)15)

size_t cub_track_mem_size(const cub_track_desc *desc)
{
    return TRK_STRUCT_BYTES + 16 + (desc ? trk_forest_mem(desc->forest) : 0);
}

cub_err cub_track_init(const cub_track_desc *desc, void *mem, size_t mem_size, cub_tracker **out)
{
    if (!desc || !mem || !out) return CUB_ERR_ARG;
    if ((uintptr_t)mem % 16) return CUB_ERR_ARG;
    if (mem_size < TRK_STRUCT_BYTES + trk_forest_mem(desc->forest)) return CUB_ERR_NOMEM;
    cub_tracker *t = mem;
    memset(t, 0, sizeof *t);
    t->min_mm = desc->min_mm > 0 ? desc->min_mm : TRK_DEFAULT_MIN_MM;
    t->max_mm = desc->max_mm > 0 ? desc->max_mm : TRK_DEFAULT_MAX_MM;
    if (t->max_mm > 8191) t->max_mm = 8191;
    if (t->min_mm >= t->max_mm) return CUB_ERR_ARG;
    for (int32_t p = 0; p < TRK_PITCHES; p++) {
        /* pitch -20..+20 degrees about the camera's x axis */
        cub_q16 a = (p - TRK_PITCHES / 2) * 2 * 1144; /* 1144 = 1 degree in Q16 radians */
        t->pitch_up[p] = (cub_vec3){0, cub_fx_cos(a), cub_fx_sin(a)};
    }
    t->up = t->pitch_up[TRK_PITCHES / 2];
    trk_bg_reset(t);
    t->bg_resets = 0;
    trk_forest_setup(t, desc->forest, (uint8_t *)mem + TRK_STRUCT_BYTES);
    for (int32_t i = 0; i < TRK_CELLS; i++) t->label_prev[i] = -1;
    t->other_label = -1;
    *out = t;
    return CUB_OK;
}

static int32_t status_of(const cub_tracker *t, int32_t comp)
{
    const trk_comp *c = &t->comps[comp];
    int32_t z = (int32_t)(c->sz / c->n);
    if (z < TRK_CLOSE_MM) return CUB_TRACK_TOO_CLOSE;
    if (z > TRK_FAR_MM) return CUB_TRACK_TOO_FAR;
    int32_t border = 0;
    for (int32_t gx = 0; gx < TRK_GW; gx++) border += t->mask[gx] + t->mask[(TRK_GH - 1) * TRK_GW + gx];
    for (int32_t gy = 0; gy < TRK_GH; gy++) border += t->mask[gy * TRK_GW] + t->mask[gy * TRK_GW + TRK_GW - 1];
    return border > 2 ? CUB_TRACK_PARTLY_OUT : CUB_TRACK_OK;
}

/* A body nearer than the play range fills a good part of the view (an
 * eighth of the grid: a child at 0.6-0.9 m, even bent so far that it is
 * no person-like blob): the camera cannot see the player whole, whoever
 * else it sees behind. */
#define CLOSE_BODY_CELLS (TRK_CELLS / 8)
static bool body_too_close(const cub_tracker *t)
{
    for (int32_t k = 0; k < t->ncomps; k++) {
        const trk_comp *c = &t->comps[k];
        if (c->n >= CLOSE_BODY_CELLS && c->sz / c->n < TRK_CLOSE_MM) return true;
    }
    return false;
}

/* The player was too close last time it was seen, and where it was the
 * camera now reads nothing in most cells: it came nearer than the
 * Kinect's 0.5 m (a child bending toward the box), it did not leave. */
static bool still_too_close(const cub_tracker *t)
{
    if (!t->have_prev || t->prev.status != CUB_TRACK_TOO_CLOSE || t->lost_frames > TRK_LOST_RESET) return false;
    int32_t blank = 0, cells = 0;
    for (int32_t gy = 0; gy < TRK_GH; gy++)
        for (int32_t gx = t->seen_gx0; gx <= t->seen_gx1 && gx < TRK_GW; gx++)
            cells++, blank += t->z[gy * TRK_GW + gx] == 0;
    return cells > 0 && blank * 2 >= cells;
}

static void no_player(cub_tracker *t, cub_track_skeleton *out)
{
    if (++t->lost_frames > TRK_LOST_RESET) t->tracked = false;
    if (t->have_prev) *out = t->prev;
    out->status = CUB_TRACK_NO_PLAYER;
    for (int j = 0; j < CUB_KJ_COUNT; j++) out->confidence[j] = 0;
}

cub_err cub_track_frame(cub_tracker *t, const uint16_t *raw, int64_t t_us, const cub_vec3 *gravity_mm,
                        cub_track_skeleton *out)
{
    if (!t || !raw || !out) return CUB_ERR_ARG;
    memset(out, 0, sizeof *out);
    /* the time since the last frame scales the smoothing's limits: at
     * least 10 ms, a long gap 200 ms, unknown the Kinect's 33 ms */
    int64_t dt = t_us - t->prev_t_us;
    int32_t learn_us = t->frame_no > 0 && dt > 0 ? (int32_t)(dt < 1000000 ? dt : 1000000) : 0;
    t->dt_us = t->have_prev && dt > 0 ? (int32_t)(dt < 10000 ? 10000 : dt < 200000 ? dt : 200000) : 33333;
    t->prev_t_us = t_us;
    t->frame_no++;
    trk_grid_fill(t, raw);
    trk_bg_learn(t, learn_us);
    trk_floor_update(t, gravity_mm);
    trk_floor_remove(t);
    trk_bg_remove(t);
    trk_components(t);
    int32_t comp = trk_pick_player(t);
    int32_t root = comp >= 0 ? trk_root_cell(t) : -1;
    bool close = body_too_close(t);
    if (root < 0) {
        if (!close) close = still_too_close(t);
        no_player(t, out);
        if (close) out->status = CUB_TRACK_TOO_CLOSE;
        return CUB_OK;
    }
    int32_t ext[TRK_MAX_EXTREMA];
    int32_t n = trk_extrema(t, root, 150, ext, TRK_MAX_EXTREMA);
    out->status = close ? CUB_TRACK_TOO_CLOSE : status_of(t, comp);
    out->player_id = t->player_id;
    trk_fit_skeleton(t, root, ext, n, out);
    trk_smooth(t, out);
    trk_confidence(t, t_us, out);
    t->lost_frames = 0;
    t->prev = *out;
    t->have_prev = true;
    if (t->forest) trk_forest_override(t, raw, out); /* after prev: the tracker's state stays its own */
    return CUB_OK;
}

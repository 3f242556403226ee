/* What a join looks like, in two numbers over its blend windows (and the
 * frame on each side of them):
 *   slide: a stance foot - one that stands in the clips the frame comes
 *          from (in a blend, in both: neither source moves it) - whose
 *          lowest point stays within the contact height of the floor from
 *          one frame to the next is on the floor; its ankle's horizontal
 *          travel then is sliding. The most any foot slides over the join.
 *          A foot the join lifts off the floor (a step) does not slide.
 *   jump:  the largest change of a joint's velocity from one frame to the
 *          next, ‖p_f − 2 p_{f−1} + p_{f−2}‖ (a cut shows as a spike, a
 *          blend as a bump). */
#include <math.h>
#include <stdlib.h>

#include "join_internal.h"

static double foot_low(const cub_join_db *db, const cub_dv3 *pos, int side)
{
    double low = INFINITY;
    for (int k = 0; k < CUB_JOIN_PART_JOINTS && db->body.part[side][k] >= 0; k++)
        low = fmin(low, pos[db->body.part[side][k]].y);
    return low;
}

static double accel_cm(const cub_dv3 *p0, const cub_dv3 *p1, const cub_dv3 *p2, int nj)
{
    double best = 0;
    for (int j = 0; j < nj; j++) {
        cub_dv3 a = cub_dv3_add(cub_dv3_sub(p2[j], cub_dv3_scale(p1[j], 2)), p0[j]);
        best = fmax(best, cub_dv3_len(a));
    }
    return best / 10.0;
}

/* Slide and jump over frames [f0, f1] of clip (f0 >= 2 for the jump). */
static void window(const cub_join_db *db, const cub_join_result *r, int f0, int f1,
                   double slide_mm[2], double *jump_cm)
{
    const cub_clip *clip = &r->clip;
    double floor_mm = r->floor_mm;
    int nj = db->skel->joint_count;
    cub_dv3 *p = malloc(sizeof(cub_dv3) * (size_t)nj * 3);
    if (!p) return;
    double h = db->cfg.contact.height_mm > 0 ? db->cfg.contact.height_mm : 30;
    for (int f = f0 - 2; f <= f1; f++) {
        if (f < 0 || f >= clip->frame_count) continue;
        cub_dv3 *cur = p + (size_t)(f % 3) * nj;
        join_frame_world(clip, f, cur, NULL);
        if (f < f0 || f < 1) continue;
        const cub_dv3 *prev = p + (size_t)((f + 2) % 3) * nj;
        for (int s = 0; s < 2; s++) {
            int aj = db->body.leg[s].ankle;
            int stance = r->stance[f - 1] & r->stance[f] & (1 << s);
            if (stance && foot_low(db, prev, s) - floor_mm < h &&
                foot_low(db, cur, s) - floor_mm < h)
                slide_mm[s] += hypot(cur[aj].x - prev[aj].x, cur[aj].z - prev[aj].z);
        }
        if (f >= 2)
            *jump_cm = fmax(*jump_cm, accel_cm(p + (size_t)((f + 1) % 3) * nj, prev, cur, nj));
    }
    free(p);
}

cub_join_figures cub_join_measure(const cub_join_db *db, const cub_join_result *r)
{
    cub_join_figures fig = {0, 0};
    double slide[2] = {0, 0};
    for (int w = 0; w < r->windows; w++)
        window(db, r, r->win_first[w], r->win_first[w] + r->win_frames[w], slide, &fig.jump_cm);
    fig.slide_cm = fmax(slide[0], slide[1]) / 10.0;
    return fig;
}

void cub_join_clip_jumps(const cub_join_db *db, int c, double *out)
{
    const cub_join_clip *jc = &db->clips[c];
    int nj = db->skel->joint_count;
    for (int f = 0; f < jc->clip->frame_count; f++)
        out[f] = f < 2 ? 0
                       : accel_cm(jc->pos + (size_t)(f - 2) * nj, jc->pos + (size_t)(f - 1) * nj,
                                  jc->pos + (size_t)f * nj, nj);
}

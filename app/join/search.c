/* The search for a transition clip C (seed 002, § 5.1, fig. 5.2): C's
 * first window of frames should look like A's last, C's last window like
 * B's first, each compared by Kovar's distance (rotation about the
 * vertical and floor translation factored out). Exhaustive over every
 * clip and window of the database: the library is small (2233
 * frames), so no precomputed graph is needed. */
#include <math.h>
#include <stdlib.h>

#include "join_internal.h"

/* The point cloud of frames [f, f + W) of clip c. */
static const cub_dv3 *cloud(const cub_join_db *db, int c, int f)
{
    return db->clips[c].pos + (size_t)f * db->skel->joint_count;
}

static int cloud_n(const cub_join_db *db)
{
    return db->cfg.window_frames * db->skel->joint_count;
}

/* D of every window start of every clip against the cloud p. */
static void distances(const cub_join_db *db, const cub_dv3 *p, double **out)
{
    int w = db->cfg.window_frames;
    for (int c = 0; c < db->count; c++)
        for (int f = 0; f + w <= db->clips[c].clip->frame_count; f++)
            out[c][f] = cub_join_kovar(p, cloud(db, c, f), NULL, cloud_n(db)).d_mm2;
}

static double **alloc_rows(const cub_join_db *db)
{
    double **rows = calloc((size_t)db->count, sizeof *rows);
    for (int c = 0; rows && c < db->count; c++) {
        rows[c] = malloc(sizeof(double) * (size_t)db->clips[c].clip->frame_count);
        if (!rows[c]) {
            while (c--)
                free(rows[c]);
            free(rows);
            return NULL;
        }
    }
    return rows;
}

static void free_rows(const cub_join_db *db, double **rows)
{
    for (int c = 0; rows && c < db->count; c++)
        free(rows[c]);
    free(rows);
}

void cub_join_direct(const cub_join_db *db, int a, int b, cub_join_pick *out)
{
    int w = db->cfg.window_frames, na = db->clips[a].clip->frame_count;
    out->clip = out->first = out->last = -1;
    out->direct = cub_join_kovar(cloud(db, a, na - w), cloud(db, b, 0), NULL, cloud_n(db));
}

/* The best (clip, first, last) for the two rows of distances. */
static double best_window(const cub_join_db *db, double **din, double **dout, cub_join_pick *out)
{
    int w = db->cfg.window_frames, lo = db->cfg.min_frames, hi = db->cfg.max_frames;
    double best = INFINITY;
    for (int c = 0; c < db->count; c++) {
        int n = db->clips[c].clip->frame_count;
        for (int i = 0; i + w <= n; i++)
            for (int last = i + lo - 1; last < n && last <= i + hi - 1; last++) {
                double d = din[c][i] + dout[c][last - w + 1];
                if (d < best) best = d, out->clip = c, out->first = i, out->last = last;
            }
    }
    return best;
}

cub_err cub_join_search(const cub_join_db *db, int a, int b, cub_join_pick *out)
{
    int w = db->cfg.window_frames;
    cub_join_direct(db, a, b, out);
    double **din = alloc_rows(db), **dout = alloc_rows(db);
    if (!din || !dout) {
        free_rows(db, din), free_rows(db, dout);
        return CUB_ERR_NOMEM;
    }
    distances(db, cloud(db, a, db->clips[a].clip->frame_count - w), din);
    distances(db, cloud(db, b, 0), dout);
    double best = best_window(db, din, dout, out);
    free_rows(db, din), free_rows(db, dout);
    if (!isfinite(best)) return CUB_ERR_EMPTY;
    /* C onto A's end, then B onto where C's end now is. */
    int n = cloud_n(db);
    out->in = cub_join_kovar(cloud(db, a, db->clips[a].clip->frame_count - w),
                             cloud(db, out->clip, out->first), NULL, n);
    cub_dv3 *moved = malloc(sizeof(cub_dv3) * (size_t)n);
    if (!moved) return CUB_ERR_NOMEM;
    const cub_dv3 *end = cloud(db, out->clip, out->last - w + 1);
    for (int i = 0; i < n; i++)
        moved[i] = cub_join_apply(&out->in, end[i]);
    out->out = cub_join_kovar(moved, cloud(db, b, 0), NULL, n);
    free(moved);
    return CUB_OK;
}

/* coachlib: the seed's tween, built from the table's bridge frames and
 * appended to the table (see cub_coachlib_add_tween). */
#include <stdlib.h>
#include <string.h>

#include "cub/coachlib.h"

/* Lay a clip of `frames` frames of the tween out at *mem and fill it. */
static cub_err tween_clip(const cub_coachlib *cl, int frames, unsigned char **mem, cub_clip *out)
{
    size_t size = cub_motion_clip_mem_size(cl->lib.skel.joint_count, frames, 0);
    cub_err e = cub_motion_clip_init(out, &cl->lib.skel, frames, cl->lib.clips[0].clip.frame_ns, 0,
                                     *mem, size);
    if (!e) e = cub_bridge_tween_fill(&cl->table, &cl->tween, out);
    *mem += (size + 7) & ~(size_t)7;
    return e;
}

/* The table again, every clip and link as before, the tween (two passes,
 * every frame a bridge frame) appended. */
static cub_err rebuild(const cub_bridge_table *old, const cub_clip *unrolled, int pass,
                       cub_bridge_table *t, void **mem_out)
{
    int n = old->desc.clip_count, frames = unrolled->frame_count;
    cub_bridge_table_desc d = old->desc;
    d.clip_count = n + 1;
    d.frame_total += frames;
    d.bridge_total += frames;
    size_t size = cub_bridge_table_mem_size(&d);
    void *mem = malloc(size);
    int most = frames > old->desc.bridge_total ? frames : old->desc.bridge_total;
    int *all = malloc(sizeof(int) * (size_t)most); /* one clip's bridge frames at a time */
    cub_err e = mem && all ? cub_bridge_table_init(t, &d, mem, size) : CUB_ERR_NOMEM;
    for (int c = 0; c < n && !e; c++) {
        const cub_bridge_clip *bc = &old->clips[c];
        for (int i = 0; i < bc->bridge_count; i++)
            all[i] = old->bridges[bc->first_bridge + i];
        e = cub_bridge_table_add_clip(t, &bc->clip, all, bc->bridge_count,
                                      old->fuzzy + bc->first_frame);
    }
    for (int f = 0; f < frames && !e; f++)
        all[f] = f;
    if (!e) e = cub_bridge_table_add_clip(t, unrolled, all, frames, NULL);
    for (int a = 0; a < n && !e; a++)
        for (int b = 0; b < n && !e; b++) {
            const cub_bridge_pair *p = &old->pairs[a * n + b];
            e = cub_bridge_table_set_links(t, a, b, old->links + p->first, p->count);
        }
    if (!e) e = cub_bridge_table_set_tween(t, n, pass);
    if (!e) e = cub_bridge_table_finish(t);
    if (!e && old->route_count > 0) e = cub_bridge_table_set_routes(t, old->routes, old->route_count);
    free(all);
    if (e) free(mem);
    *mem_out = e ? NULL : mem;
    return e;
}

cub_err cub_coachlib_add_tween(cub_coachlib *cl, const cub_bridge_tween_config *cfg, cub_diag *diag)
{
    if (!cl || !cl->table.finished || cl->tween_index >= 0 || cl->tween_mem) return CUB_ERR_ARG;
    size_t ws = cub_bridge_tween_work_size(&cl->table);
    void *work = malloc(ws);
    cub_err e = work ? cub_bridge_tween_plan(&cl->table, cfg, &cl->tween, work, ws) : CUB_ERR_NOMEM;
    free(work);
    if (e)
        return cub_diag_fail(diag, e, "bear.tags.xml", 0,
                             "cannot build the tween from the bridge frames (%s)", cub_err_str(e));
    int pass = cl->tween.frame_count;
    size_t js = (size_t)cl->lib.skel.joint_count;
    cl->tween_mem = malloc(cub_motion_clip_mem_size((int)js, pass, 0) +
                           cub_motion_clip_mem_size((int)js, 2 * pass, 0) + 16);
    if (!cl->tween_mem) return cub_diag_fail(diag, CUB_ERR_NOMEM, "coachlib", 0, "out of memory");
    unsigned char *mem = cl->tween_mem;
    cub_clip unrolled;
    cub_bridge_table t;
    void *table_mem = NULL;
    e = tween_clip(cl, pass, &mem, &cl->tween_clip);
    if (!e) e = tween_clip(cl, 2 * pass, &mem, &unrolled);
    if (!e) e = rebuild(&cl->table, &unrolled, pass, &t, &table_mem);
    if (e) {
        free(cl->tween_mem);
        cl->tween_mem = NULL;
        memset(&cl->tween_clip, 0, sizeof cl->tween_clip);
        return cub_diag_fail(diag, e, "coachlib", 0, "cannot add the tween to the table (%s)",
                             cub_err_str(e));
    }
    free(cl->table_mem);
    cl->table_mem = table_mem;
    cl->table = t;
    cl->tween_index = cl->lib.clip_count;
    return CUB_OK;
}

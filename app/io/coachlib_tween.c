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

/* Clips appended to the table. */
typedef struct extra_clips {
    const cub_coachlib_extra *items;
    int count;
    int tween_pass; /* > 0: the first is the tween of that pass */
} extra_clips;

static int extra_bridges(const cub_coachlib_extra *x)
{
    return x->bridges ? x->bridge_count : x->clip->frame_count;
}

static cub_bridge_table_desc grown_desc(const cub_bridge_table *old, const extra_clips *x,
                                        int *most)
{
    cub_bridge_table_desc d = old->desc;
    *most = old->desc.bridge_total;
    d.clip_count += x->count;
    for (int i = 0; i < x->count; i++) {
        const cub_clip *c = x->items[i].clip;
        d.frame_total += c->frame_count;
        d.bridge_total += extra_bridges(&x->items[i]);
        if (c->frame_count > *most) *most = c->frame_count;
    }
    return d;
}

/* One appended clip: its bridge frames as given, else every frame. */
static cub_err add_extra(cub_bridge_table *t, const cub_coachlib_extra *x, int *all)
{
    int n = extra_bridges(x);
    for (int f = 0; f < n; f++)
        all[f] = x->bridges ? x->bridges[f] : f;
    return cub_bridge_table_add_clip(t, x->clip, all, n, x->fuzzy);
}

static cub_err add_old_clips(const cub_bridge_table *old, cub_bridge_table *t, int *all)
{
    cub_err e = CUB_OK;
    for (int c = 0; c < old->desc.clip_count && !e; c++) {
        const cub_bridge_clip *bc = &old->clips[c];
        for (int i = 0; i < bc->bridge_count; i++)
            all[i] = old->bridges[bc->first_bridge + i];
        e = cub_bridge_table_add_clip(t, &bc->clip, all, bc->bridge_count,
                                      old->fuzzy + bc->first_frame);
    }
    return e;
}

/* The table again, every clip and link as before, the extra clips
 * appended. */
static cub_err rebuild(const cub_bridge_table *old, const extra_clips *x, cub_bridge_table *t,
                       void **mem_out)
{
    int n = old->desc.clip_count, most;
    cub_bridge_table_desc d = grown_desc(old, x, &most);
    size_t size = cub_bridge_table_mem_size(&d);
    void *mem = malloc(size);
    int *all = malloc(sizeof(int) * (size_t)(most + 1)); /* one clip's bridge frames at a time */
    cub_err e = mem && all ? cub_bridge_table_init(t, &d, mem, size) : CUB_ERR_NOMEM;
    if (!e) e = add_old_clips(old, t, all);
    for (int i = 0; i < x->count && !e; i++)
        e = add_extra(t, &x->items[i], all);
    for (int a = 0; a < n && !e; a++)
        for (int b = 0; b < n && !e; b++) {
            const cub_bridge_pair *p = &old->pairs[a * n + b];
            e = cub_bridge_table_set_links(t, a, b, old->links + p->first, p->count);
        }
    /* the tween, new or kept (clips are appended after it) */
    int tween = x->tween_pass > 0 ? n : old->tween_clip;
    int pass = x->tween_pass > 0 ? x->tween_pass : old->tween_pass;
    if (!e && tween >= 0) e = cub_bridge_table_set_tween(t, tween, pass);
    if (!e) e = cub_bridge_table_finish(t);
    if (!e && old->route_count > 0) e = cub_bridge_table_set_routes(t, old->routes, old->route_count);
    free(all);
    if (e) free(mem);
    *mem_out = e ? NULL : mem;
    return e;
}

/* The rebuilt table replaces the old one. */
static void take_table(cub_coachlib *cl, const cub_bridge_table *t, void *mem)
{
    free(cl->table_mem);
    cl->table_mem = mem;
    cl->table = *t;
}

static int extras_ok(const cub_coachlib_extra *clips, int count)
{
    for (int i = 0; i < count; i++) {
        const cub_coachlib_extra *x = &clips[i];
        if (!x->clip || x->clip->frame_count < 1 || x->bridge_count < 0 ||
            (x->bridges && x->bridge_count > x->clip->frame_count))
            return 0;
    }
    return 1;
}

cub_err cub_coachlib_add_clips(cub_coachlib *cl, const cub_coachlib_extra *clips, int count,
                               cub_diag *diag)
{
    if (!cl || !cl->table.finished || count < 0 || (count > 0 && !clips)) return CUB_ERR_ARG;
    if (count == 0) return CUB_OK;
    if (!extras_ok(clips, count)) return CUB_ERR_ARG;
    extra_clips x = {.items = clips, .count = count};
    cub_bridge_table t;
    void *mem = NULL;
    cub_err e = rebuild(&cl->table, &x, &t, &mem);
    if (e)
        return cub_diag_fail(diag, e, "coachlib", 0, "cannot add %d clips to the table (%s)",
                             count, cub_err_str(e));
    take_table(cl, &t, mem);
    return CUB_OK;
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
    cub_coachlib_extra one = {.clip = &unrolled}; /* every frame a bridge frame */
    extra_clips x = {.items = &one, .count = 1, .tween_pass = pass};
    if (!e) e = rebuild(&cl->table, &x, &t, &table_mem);
    if (e) {
        free(cl->tween_mem);
        cl->tween_mem = NULL;
        memset(&cl->tween_clip, 0, sizeof cl->tween_clip);
        return cub_diag_fail(diag, e, "coachlib", 0, "cannot add the tween to the table (%s)",
                             cub_err_str(e));
    }
    take_table(cl, &t, table_mem);
    cl->tween_index = cl->lib.clip_count;
    return CUB_OK;
}

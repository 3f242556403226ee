/* The dance's motion graph by support points (seed 002, § 5.2, figs. 5.7
 * and 5.8): a node per support class (which parts touch the floor), an
 * edge per change of class inside a clip. Kovar's graph joins clips where
 * poses match; the seed's classes say which joins are plausible at all (a
 * two-feet pose can go to one foot, a hip-and-feet pose must get up). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/png.h"
#include "join_internal.h"

int cub_join_segments(const cub_join_db *db, int c, int min_frames, cub_join_segment *out, int max)
{
    const cub_join_clip *jc = &db->clips[c];
    int frames = jc->clip->frame_count, n = 0;
    cub_join_segment cur = {0, -1, jc->support[0]};
    for (int f = 0; f <= frames; f++) {
        if (f < frames && jc->support[f] == cur.mask) {
            cur.last = f;
            continue;
        }
        int len = cur.last - cur.first + 1;
        if (n > 0 && len < min_frames && n - 1 < max) /* too short: the run before takes it */
            out[n - 1].last = cur.last;
        else if (n > 0 && n - 1 < max && out[n - 1].mask == cur.mask)
            out[n - 1].last = cur.last;
        else {
            if (n < max) out[n] = cur;
            n++;
        }
        if (f < frames) cur = (cub_join_segment){f, f, jc->support[f]};
    }
    /* A first segment too short joins the next. */
    if (n > 1 && max > 1 && out[0].last - out[0].first + 1 < min_frames) {
        out[1].first = 0;
        memmove(out, out + 1, sizeof *out * (size_t)((n < max ? n : max) - 1));
        n--;
    }
    return n;
}

cub_err cub_join_graph_build(const cub_join_db *db, int min_frames, cub_join_graph *g)
{
    memset(g, 0, sizeof *g);
    for (int c = 0; c < db->count; c++) {
        int max = db->clips[c].clip->frame_count;
        cub_join_segment *seg = malloc(sizeof *seg * (size_t)max);
        if (!seg) return CUB_ERR_NOMEM;
        int n = cub_join_segments(db, c, min_frames, seg, max);
        for (int i = 0; i < n; i++) {
            g->frames[seg[i].mask] += seg[i].last - seg[i].first + 1;
            g->segments[seg[i].mask]++;
            if (i) g->edges[seg[i - 1].mask][seg[i].mask]++;
        }
        free(seg);
    }
    return CUB_OK;
}

/* ---- drawing ---------------------------------------------------------------- */

#define SIZE 900

static void arrow(cub_png_canvas *c, const double xy[4], double r_to, int width, int count)
{
    static const uint8_t ink[3] = {90, 90, 110}, head[3] = {200, 80, 40}, text[3] = {20, 20, 20};
    double dx = xy[2] - xy[0], dy = xy[3] - xy[1], len = hypot(dx, dy);
    if (len < 1) return;
    /* Both directions of a pair would overlap: shift each to its right. */
    double nx = -dy / len * 6, ny = dx / len * 6;
    double l[4] = {xy[0] + nx, xy[1] + ny, xy[2] + nx - dx / len * r_to,
                   xy[3] + ny - dy / len * r_to};
    cub_png_line(c, l, width, ink);
    cub_png_dot(c, (int)lround(l[2]), (int)lround(l[3]), width + 4, head);
    char num[16];
    snprintf(num, sizeof num, "%d", count);
    cub_png_text(c, (int)lround(l[0] + (l[2] - l[0]) * 0.6 + nx),
                 (int)lround(l[1] + (l[3] - l[1]) * 0.6 + ny), 2, num, text);
}

static void draw(cub_png_canvas *c, const cub_join_graph *g, const int *cls, int n)
{
    static const uint8_t node[3] = {150, 190, 230}, text[3] = {10, 10, 40};
    double x[CUB_JOIN_CLASSES], y[CUB_JOIN_CLASSES], r[CUB_JOIN_CLASSES];
    int most = 1;
    for (int i = 0; i < n; i++)
        most = g->frames[cls[i]] > most ? g->frames[cls[i]] : most;
    for (int i = 0; i < n; i++) {
        double a = 2 * CUB_VEC_PI * i / n - CUB_VEC_PI / 2;
        x[i] = SIZE / 2.0 + 0.36 * SIZE * cos(a);
        y[i] = SIZE / 2.0 + 0.36 * SIZE * sin(a);
        r[i] = 30 + 40 * sqrt((double)g->frames[cls[i]] / most);
    }
    for (int i = 0; i < n; i++)
        for (int k = 0; k < n; k++) {
            int e = g->edges[cls[i]][cls[k]];
            if (!e || i == k) continue;
            const double xy[4] = {x[i], y[i], x[k], y[k]};
            arrow(c, xy, r[k], 1 + (int)log2(1 + e), e);
        }
    for (int i = 0; i < n; i++) {
        cub_png_dot(c, (int)x[i], (int)y[i], (int)r[i], node);
        char name[64], frames[32];
        cub_join_support_name((unsigned)cls[i], name, sizeof name);
        snprintf(frames, sizeof frames, "%d F", g->frames[cls[i]]);
        cub_png_text(c, (int)x[i] - (int)strlen(name) * 6, (int)y[i] - 16, 2, name, text);
        cub_png_text(c, (int)x[i] - (int)strlen(frames) * 6, (int)y[i] + 2, 2, frames, text);
    }
}

cub_err cub_join_graph_png(const cub_join_graph *g, const char *path)
{
    int cls[CUB_JOIN_CLASSES], n = 0;
    for (int m = 0; m < CUB_JOIN_CLASSES; m++)
        if (g->frames[m]) cls[n++] = m;
    cub_png_canvas c = {malloc((size_t)SIZE * SIZE * 4), SIZE, SIZE};
    if (!c.px) return CUB_ERR_NOMEM;
    for (size_t i = 0; i < (size_t)SIZE * SIZE; i++)
        memcpy(c.px + i * 4, (const uint8_t[4]){248, 248, 244, 255}, 4);
    static const uint8_t title[3] = {40, 40, 40};
    cub_png_text(&c, 16, 16, 2, "SUPPORT CLASSES (F = FRAMES), EDGES: CHANGES IN A CLIP", title);
    draw(&c, g, cls, n);
    cub_err e = cub_png_write(path, c.px, c.w, c.h);
    free(c.px);
    return e;
}

/* A contact sheet for a person to look at a clip: a software-drawn stick
 * figure, front view (top row) and side view (bottom row), at evenly spaced
 * frames, floor line at y = 0; left limbs blue, right red, trunk dark. No
 * GPU needed, so it runs anywhere cubtool does. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cub/png.h"
#include "cub/retarget.h"
#include "rt_internal.h"

#define CELL_W 200
#define CELL_H 240

typedef cub_png_canvas canvas;

static void line(canvas *c, double x0, double y0, double x1, double y1, int r,
                 const uint8_t rgb[3])
{
    const double xy[4] = {x0, y0, x1, y1};
    cub_png_line(c, xy, r, rgb);
}

static const uint8_t *bone_colour(const cub_skeleton *s, int j)
{
    static const uint8_t left[3] = {40, 90, 220}, right[3] = {210, 50, 40}, mid[3] = {60, 45, 35};
    const char *n = s->joints[j].name;
    return !strncmp(n, "Left", 4) || n[0] == 'l' ? left
           : !strncmp(n, "Right", 5) || n[0] == 'r' ? right
                                                    : mid;
}

/* One figure in a cell: view 0 = front (x to the viewer's right is the
 * bear's left, +x), view 1 = side (from the bear's left: +z to the right). */
static void draw_figure(canvas *c, int cx, int cy, const cub_skeleton *s, const cub_dv3 *pos,
                        int view, double mm_per_px)
{
    static const uint8_t floor_rgb[3] = {120, 160, 90};
    double ox = cx + CELL_W / 2.0, oy = cy + CELL_H - 20;
    line(c, cx + 8, oy, cx + CELL_W - 8, oy, 0, floor_rgb);
    for (int j = 1; j < s->joint_count; j++) {
        int p = s->joints[j].parent;
        double h0 = view ? pos[p].z : pos[p].x, h1 = view ? pos[j].z : pos[j].x;
        line(c, ox + h0 / mm_per_px, oy - pos[p].y / mm_per_px, ox + h1 / mm_per_px,
             oy - pos[j].y / mm_per_px, 2, bone_colour(s, j));
    }
}

cub_err cub_retarget_sheet_png(const char *path, const cub_clip *clip, int columns)
{
    if (!path || !clip || !clip->skel || clip->frame_count < 1 || columns < 1 || columns > 64)
        return CUB_ERR_ARG;
    canvas c = {NULL, CELL_W * columns, CELL_H * 2};
    c.px = malloc((size_t)c.w * c.h * 4);
    if (!c.px)
        return CUB_ERR_NOMEM;
    for (size_t i = 0; i < (size_t)c.w * c.h; i++)
        memcpy(c.px + i * 4, (const uint8_t[4]){235, 238, 242, 255}, 4);
    const cub_skeleton *s = clip->skel;
    cub_dv3 pos[CUB_MOTION_MAX_JOINTS];
    cub_dq rot[CUB_MOTION_MAX_JOINTS], wrot[CUB_MOTION_MAX_JOINTS];
    double mm_per_px = 5.5; /* the 0.93 m bear plus a jump fits a 240 px cell */
    for (int col = 0; col < columns; col++) {
        int f = columns > 1 ? (int)((long)col * (clip->frame_count - 1) / (columns - 1)) : 0;
        for (int j = 0; j < s->joint_count; j++)
            rot[j] = cub_dq_norm(cub_dq_from_fx(clip->rot[(size_t)f * s->joint_count + j]));
        rt_forward(s, cub_dv3_from_fx(clip->root_mm[f]), rot, NULL, pos, wrot);
        for (int view = 0; view < 2; view++)
            draw_figure(&c, col * CELL_W, view * CELL_H, s, pos, view, mm_per_px);
    }
    cub_err err = cub_png_write(path, c.px, c.w, c.h);
    free(c.px);
    return err;
}

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

/* The posed joints of clip's frame f in pos. */
static void pose_at(const cub_clip *clip, int f, cub_dv3 *pos)
{
    const cub_skeleton *s = clip->skel;
    cub_dq rot[CUB_MOTION_MAX_JOINTS], wrot[CUB_MOTION_MAX_JOINTS];
    for (int j = 0; j < s->joint_count; j++)
        rot[j] = cub_dq_norm(cub_dq_from_fx(clip->rot[(size_t)f * s->joint_count + j]));
    rt_forward(s, cub_dv3_from_fx(clip->root_mm[f]), rot, NULL, pos, wrot);
}

/* The frame of column col when columns frames are spread over the clip. */
static int frame_of(const cub_clip *clip, int col, int columns)
{
    return columns > 1 ? (int)((long)col * (clip->frame_count - 1) / (columns - 1)) : 0;
}

/* One scale for every figure of the sheet: 5.5 mm a pixel (the 0.93 m bear
 * plus a jump fits a 240 px cell), coarser when a taller skeleton (a
 * 1.7 m human crossed with a dog) would leave its cell. */
static double sheet_scale(const cub_clip *const *clips, int n, int columns)
{
    cub_dv3 pos[CUB_MOTION_MAX_JOINTS];
    double top = 0;
    for (int i = 0; i < n; i++)
        for (int col = 0; col < columns; col++) {
            pose_at(clips[i], frame_of(clips[i], col, columns), pos);
            for (int j = 0; j < clips[i]->skel->joint_count; j++)
                top = fmax(top, pos[j].y);
        }
    return fmax(5.5, top / (CELL_H - 30));
}

static int sheet_ok(const cub_clip *clip)
{
    return clip && clip->skel && clip->frame_count >= 1 &&
           clip->skel->joint_count <= CUB_MOTION_MAX_JOINTS;
}

cub_err cub_retarget_sheet_multi_png(const char *path, const cub_clip *const *clips,
                                     const char *const *titles, int n, int columns)
{
    static const uint8_t ink[3] = {60, 45, 35}, rule[3] = {150, 150, 160};
    if (!path || !clips || n < 1 || n > 8 || columns < 1 || columns > 64) return CUB_ERR_ARG;
    for (int i = 0; i < n; i++)
        if (!sheet_ok(clips[i])) return CUB_ERR_ARG;
    int title_h = titles ? CUB_SHEET_TITLE_H : 0;
    canvas c = {NULL, CELL_W * columns * n, title_h + CELL_H * 2};
    c.px = malloc((size_t)c.w * c.h * 4);
    if (!c.px) return CUB_ERR_NOMEM;
    for (size_t i = 0; i < (size_t)c.w * c.h; i++)
        memcpy(c.px + i * 4, (const uint8_t[4]){235, 238, 242, 255}, 4);
    cub_dv3 pos[CUB_MOTION_MAX_JOINTS];
    double mm_per_px = sheet_scale(clips, n, columns);
    for (int i = 0; i < n; i++) {
        int x0 = i * columns * CELL_W;
        if (titles && titles[i]) cub_png_text(&c, x0 + 8, 5, 2, titles[i], ink);
        if (i) line(&c, x0, 0, x0, c.h - 1, 0, rule); /* where one clip's block ends */
        for (int col = 0; col < columns; col++) {
            pose_at(clips[i], frame_of(clips[i], col, columns), pos);
            for (int view = 0; view < 2; view++)
                draw_figure(&c, x0 + col * CELL_W, title_h + view * CELL_H, clips[i]->skel, pos,
                            view, mm_per_px);
        }
    }
    cub_err err = cub_png_write(path, c.px, c.w, c.h);
    free(c.px);
    return err;
}

cub_err cub_retarget_sheet_png(const char *path, const cub_clip *clip, int columns)
{
    return cub_retarget_sheet_multi_png(path, &clip, NULL, 1, columns);
}

/* render_shapes — flat 2D shapes in pixels, with alpha, for what is drawn
 * over the scene (panels, the progress bar, the badge, the child's figure).
 * They go into the same triangle batch as the stick figure; the caller
 * draws it with blending on. */
#include <math.h>

#include "render_internal.h"

#define ARC_SEGMENTS 24 /* a full disc; a corner gets a quarter of it */

static cub_render_vtx v2(const cub_render *r, float x, float y, const float rgba[4])
{
    return cub_render_px_vtx(r, x, y, rgba, rgba[3]);
}

static void tri(cub_render *r, float ax, float ay, float bx, float by, float cx, float cy,
                const float rgba[4])
{
    cub_render_batch_tri(&r->batch, (cub_render_vtx[3]){v2(r, ax, ay, rgba),
                                                        v2(r, bx, by, rgba),
                                                        v2(r, cx, cy, rgba)});
}

void cub_render_shape_rect(cub_render *r, float x0, float y0, float x1, float y1,
                           const float rgba[4])
{
    if (x1 <= x0 || y1 <= y0)
        return;
    tri(r, x0, y0, x1, y0, x1, y1, rgba);
    tri(r, x0, y0, x1, y1, x0, y1, rgba);
}

/* A pie slice from angle a0 over `segments` of the full disc's steps. */
static void fan(cub_render *r, float cx, float cy, float radius, float a0, int segments,
                const float rgba[4])
{
    const float step = 6.2831853f / ARC_SEGMENTS;
    for (int i = 0; i < segments; i++) {
        float a = a0 + step * (float)i, b = a + step;
        tri(r, cx, cy, cx + radius * cosf(a), cy + radius * sinf(a), cx + radius * cosf(b),
            cy + radius * sinf(b), rgba);
    }
}

void cub_render_shape_disc(cub_render *r, float cx, float cy, float radius, const float rgba[4])
{
    fan(r, cx, cy, radius, 0.0f, ARC_SEGMENTS, rgba);
}

/* Three rectangles and four quarter discs, none overlapping, so a
 * translucent panel has one even shade. */
void cub_render_shape_round_rect(cub_render *r, float x0, float y0, float x1, float y1,
                                 float radius, const float rgba[4])
{
    float half = 0.5f * fminf(x1 - x0, y1 - y0);
    float k = radius < half ? radius : half;
    cub_render_shape_rect(r, x0 + k, y0, x1 - k, y1, rgba);
    cub_render_shape_rect(r, x0, y0 + k, x0 + k, y1 - k, rgba);
    cub_render_shape_rect(r, x1 - k, y0 + k, x1, y1 - k, rgba);
    const int q = ARC_SEGMENTS / 4;
    const float pi = 3.14159265f;
    fan(r, x1 - k, y1 - k, k, 0.0f, q, rgba);
    fan(r, x0 + k, y1 - k, k, 0.5f * pi, q, rgba);
    fan(r, x0 + k, y0 + k, k, pi, q, rgba);
    fan(r, x1 - k, y0 + k, k, 1.5f * pi, q, rgba);
}

void cub_render_shape_limb(cub_render *r, float x0, float y0, float x1, float y1, float hw,
                           const float rgba[4])
{
    float dx = x1 - x0, dy = y1 - y0, len = sqrtf(dx * dx + dy * dy);
    if (len > 1e-3f) {
        float nx = -dy / len * hw, ny = dx / len * hw;
        tri(r, x0 + nx, y0 + ny, x0 - nx, y0 - ny, x1 - nx, y1 - ny, rgba);
        tri(r, x0 + nx, y0 + ny, x1 - nx, y1 - ny, x1 + nx, y1 + ny, rgba);
    }
    cub_render_shape_disc(r, x0, y0, hw, rgba);
    cub_render_shape_disc(r, x1, y1, hw, rgba);
}

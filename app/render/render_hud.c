/* render_hud — what the child reads over the scene: the song's progress as
 * a bar along the top, the hint in a banner at the bottom centre with the
 * move's icon on a round badge in the lower-left corner (the child's inset
 * has the lower-right), and while the box waits, the scene dimmed under a
 * big title (the scene's words) and a round play button for those who
 * cannot read yet.
 * Sizes are shares of the viewport height, so 1280x720 and 1920x1080 look
 * the same from the sofa. */
#include <ctype.h>
#include <math.h>

#include "render_internal.h"

#define HINT_SCALE 0.55f   /* of the atlas' glyph height (h / 8) */
#define TITLE_SCALE 1.5f
#define BADGE_SHARE 0.11f  /* badge radius, share of h */

static const float PANEL[4] = {0.12f, 0.10f, 0.22f, 0.62f};
static const float HINT_RGB[3] = {1.0f, 0.97f, 0.86f};
static const float TITLE_RGB[3] = {1.0f, 0.86f, 0.25f};
static const float BAR_FILL[4] = {1.0f, 0.80f, 0.22f, 1.0f};
static const float WHITE[4] = {1.0f, 1.0f, 1.0f, 1.0f};

static float margin(const cub_render *r)
{
    return (float)r->h / 40.0f;
}

static void progress_bar(cub_render *r, float p)
{
    p = p > 1.0f ? 1.0f : p;
    float bh = (float)r->h / 30.0f, m = margin(r);
    float x0 = 0.2f * (float)r->w, x1 = 0.8f * (float)r->w;
    float y1 = (float)r->h - m, y0 = y1 - bh;
    float pad = 0.2f * bh;
    cub_render_shape_round_rect(r, x0 - pad, y0 - pad, x1 + pad, y1 + pad, 0.5f * bh + pad,
                                PANEL);
    float end = x0 + p * (x1 - x0);
    if (end - x0 >= bh) /* shorter than round: a knob alone says "just started" */
        cub_render_shape_round_rect(r, x0, y0, end, y1, 0.5f * bh, BAR_FILL);
    cub_render_shape_disc(r, end < x0 + 0.5f * bh ? x0 + 0.5f * bh : end - 0.5f * bh,
                          0.5f * (y0 + y1), 0.75f * bh, WHITE);
}

/* The banner between the badge and the inset; a long hint shrinks to fit. */
static void hint_banner(cub_render *r, const char *hint)
{
    cub_render_text_layout(r, &r->hint_label, hint);
    const cub_render_label *l = &r->hint_label;
    float room = 0.56f * (float)r->w, scale = HINT_SCALE;
    if (l->width_px * scale > room)
        scale = room / l->width_px;
    float tw = l->width_px * scale, px = r->text.px * scale, m = margin(r);
    float x = 0.5f * ((float)r->w - tw), base = m + 0.55f * px;
    cub_render_shape_round_rect(r, x - 0.5f * px, m, x + tw + 0.5f * px,
                                base + r->text.ascent_px * scale + 0.25f * px, 0.4f * px,
                                PANEL);
    cub_render_batch_draw(r);
    cub_render_text_draw(r, l, x, base, scale, HINT_RGB);
    cub_render_text_flush(r);
}

static int is_head(const char *name)
{
    static const char HEAD[] = "head";
    for (int i = 0; i < 5; i++)
        if (tolower((unsigned char)name[i]) != HEAD[i])
            return 0;
    return 1;
}

/* The move's pose seen from the front, fitted into the badge: chunky limbs
 * and a big head, so it reads as a pose and not as a diagram. */
static void icon_badge(cub_render *r, const cub_skeleton *skel, const float *xyz)
{
    float rad = BADGE_SHARE * (float)r->h, m = margin(r);
    float cx = m + rad, cy = m + rad;
    static const float RING[4] = {1.0f, 0.80f, 0.22f, 1.0f};
    static const float FACE[4] = {0.99f, 0.96f, 0.88f, 1.0f};
    static const float BODY[4] = {0.45f, 0.27f, 0.13f, 1.0f};
    cub_render_shape_disc(r, cx, cy, rad, RING);
    cub_render_shape_disc(r, cx, cy, 0.88f * rad, FACE);
    float lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int j = 0; j < skel->joint_count; j++)
        for (int k = 0; k < 2; k++) {
            lo[k] = fminf(lo[k], xyz[3 * j + k]);
            hi[k] = fmaxf(hi[k], xyz[3 * j + k]);
        }
    float span = fmaxf(hi[0] - lo[0], hi[1] - lo[1]);
    if (!(span > 1.0f) || !isfinite(span))
        return;
    float k = 1.2f * rad / span; /* the pose's larger side: 1.2 radii */
    float mx = 0.5f * (lo[0] + hi[0]), my = 0.5f * (lo[1] + hi[1]);
    float hw = 0.085f * rad;
    for (int j = 0; j < skel->joint_count; j++) {
        int p = skel->joints[j].parent;
        const float *a = xyz + 3 * j;
        float ax = cx + (a[0] - mx) * k, ay = cy + (a[1] - my) * k;
        if (p >= 0) {
            const float *b = xyz + 3 * p;
            cub_render_shape_limb(r, ax, ay, cx + (b[0] - mx) * k, cy + (b[1] - my) * k, hw,
                                  BODY);
        }
        if (is_head(skel->joints[j].name))
            cub_render_shape_disc(r, ax, ay, 0.2f * rad, BODY);
    }
}

/* Dim the scene, then the title along the top and a round play button in
 * the lower-left corner (where a move's badge goes while dancing): the bear
 * between them stays in view, so a dozing bear still shows its sleepy face. */
static void idle_screen(cub_render *r, const char *title)
{
    static const float DIM[4] = {0.05f, 0.08f, 0.20f, 0.45f};
    static const float BUTTON[4] = {0.20f, 0.72f, 0.30f, 1.0f};
    float w = (float)r->w, h = (float)r->h;
    cub_render_shape_rect(r, 0, 0, w, h, DIM);
    float rad = 0.12f * h, m = margin(r), cx = m + rad * 1.08f, cy = m + rad * 1.08f;
    cub_render_shape_disc(r, cx, cy, rad * 1.08f, WHITE);
    cub_render_shape_disc(r, cx, cy, rad, BUTTON);
    const float tri[3][2] = {{-0.35f, 0.45f}, {-0.35f, -0.45f}, {0.5f, 0.0f}};
    cub_render_vtx v[3];
    for (int i = 0; i < 3; i++)
        v[i] = cub_render_px_vtx(r, cx + tri[i][0] * rad, cy + tri[i][1] * rad, WHITE, 1.0f);
    cub_render_batch_tri(&r->batch, v);
    cub_render_batch_draw(r);
    if (!title || !title[0]) return;
    cub_render_text_layout(r, &r->title_label, title);
    float scale = TITLE_SCALE;
    if (r->title_label.width_px * scale > 0.9f * w)
        scale = 0.9f * w / r->title_label.width_px;
    float x = 0.5f * (w - r->title_label.width_px * scale);
    cub_render_text_draw(r, &r->title_label, x, 0.80f * h, scale, TITLE_RGB);
    cub_render_text_flush(r);
}

void cub_render_hud_draw(cub_render *r, const cub_render_scene *scene)
{
    if (scene->idle) {
        idle_screen(r, scene->title);
        return; /* the hint, badge and bar belong to a song playing */
    }
    if (scene->has_progress && isfinite(scene->progress))
        progress_bar(r, scene->progress < 0.0f ? 0.0f : scene->progress);
    if (scene->icon_xyz_mm && scene->skel)
        icon_badge(r, scene->skel, scene->icon_xyz_mm);
    cub_render_batch_draw(r);
    if (scene->hint && scene->hint[0])
        hint_banner(r, scene->hint);
}

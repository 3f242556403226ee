/* render_child — the child's own skeleton in the lower-right inset, drawn
 * over the depth image (projected with the Kinect's own camera model, so
 * the bones sit on the child's silhouette; a parent sees both what the
 * camera sees and what the tracker made of it), or on a dark panel when
 * there is no depth image. Above the inset, the cue the scene gives (the
 * words for a child the camera does not read well). Green bones: tracked
 * whole; orange: tracked, but not well; pink and wider: the limb the hint
 * asks the child to move (the scene's child_mark). */
#include "cub/kinect.h"
#include "cub/track.h"
#include "render_internal.h"

#define CUE_SCALE 0.42f


/* Camera mm -> inset pixel through the depth image's pixel (u, v);
 * 0 for a joint at or behind the camera. */
static int to_inset(const cub_vec3 *p, int x0, int y0, int iw, int ih, float out[2])
{
    float z = (float)p->z / 65536.0f;
    if (!(z > 1.0f))
        return 0;
    float u = CUB_KINECT_CX + CUB_KINECT_FOCAL_PX * ((float)p->x / 65536.0f) / z;
    float v = CUB_KINECT_CY - CUB_KINECT_FOCAL_PX * ((float)p->y / 65536.0f) / z;
    out[0] = (float)x0 + u * (float)iw / CUB_KINECT_WIDTH;
    out[1] = (float)(y0 + ih) - v * (float)ih / CUB_KINECT_HEIGHT;
    return 1;
}

/* One way of drawing bones: those of the joints in mask (in = 1) or of
 * the others (in = 0), hw wide, in rgba. */
typedef struct bone_pass {
    uint32_t mask;
    int in;
    float hw;
    const float *rgba;
} bone_pass;

static void bone_set(cub_render *r, const cub_track_skeleton *c, const int rect[4],
                     const bone_pass *bp)
{
    float a[2], b[2];
    for (int j = 0; j < CUB_KJ_COUNT; j++) {
        int p = cub_kinect_joint_parent(j);
        if (p < 0 || ((bp->mask >> j & 1u) != 0) != (bp->in != 0)) continue;
        if (to_inset(&c->joint_mm[j], rect[0], rect[1], rect[2], rect[3], a) &&
            to_inset(&c->joint_mm[p], rect[0], rect[1], rect[2], rect[3], b))
            cub_render_shape_limb(r, a[0], a[1], b[0], b[1], bp->hw, bp->rgba);
    }
}

/* The marked limb (the one the hint asks to move) is pink and wider, on
 * top: a colour of its own beside the green and orange of the tracking,
 * clear on the grey depth image, and the width tells it without colour. */
static void bones(cub_render *r, const cub_track_skeleton *c, int x0, int y0, int iw, int ih,
                  uint32_t mark)
{
    static const float OK_RGBA[4] = {0.35f, 0.95f, 0.45f, 1.0f};
    static const float CUE_RGBA[4] = {1.0f, 0.60f, 0.15f, 1.0f};
    static const float MARK_RGBA[4] = {1.0f, 0.35f, 0.80f, 1.0f};
    const float *rgba = c->status == CUB_TRACK_OK ? OK_RGBA : CUE_RGBA;
    const int rect[4] = {x0, y0, iw, ih};
    float hw = (float)iw / 60.0f;
    hw = hw < 1.0f ? 1.0f : hw;
    bone_set(r, c, rect, &(bone_pass){mark, 0, hw, rgba});
    float a[2];
    if (to_inset(&c->joint_mm[CUB_KJ_HEAD], x0, y0, iw, ih, a))
        cub_render_shape_disc(r, a[0], a[1], 3.0f * hw, rgba);
    if (mark) bone_set(r, c, rect, &(bone_pass){mark, 1, 1.75f * hw, MARK_RGBA});
}

static void cue(cub_render *r, const char *text, int x0, int y0, int iw, int ih)
{
    static const float PANEL[4] = {0.12f, 0.10f, 0.22f, 0.70f};
    static const float CUE_RGB[3] = {1.0f, 0.75f, 0.30f};
    cub_render_text_layout(r, &r->cue_label, text);
    const cub_render_label *l = &r->cue_label;
    float scale = CUE_SCALE, px = r->text.px * scale;
    float room = 0.30f * (float)r->w; /* may reach left past the inset, not the edge */
    if (l->width_px * scale > room)
        scale = room / l->width_px, px = r->text.px * scale;
    float tw = l->width_px * scale;
    float right = (float)(x0 + iw), x = right - tw - 0.4f * px;
    if (x > (float)x0 + 0.5f * ((float)iw - tw)) /* short: centred over the inset */
        x = (float)x0 + 0.5f * ((float)iw - tw);
    float base = (float)(y0 + ih) + 0.55f * px;
    cub_render_shape_round_rect(r, x - 0.4f * px, (float)(y0 + ih) + 0.15f * px,
                                x + tw + 0.4f * px, base + r->text.ascent_px * scale + 0.2f * px,
                                0.35f * px, PANEL);
    cub_render_batch_draw(r);
    cub_render_text_draw(r, l, x, base, scale, CUE_RGB);
    cub_render_text_flush(r);
}

void cub_render_child_draw(cub_render *r, const cub_track_skeleton *child, const char *cue_text,
                           uint32_t mark, int have_depth)
{
    int x0, y0, iw, ih;
    cub_render_inset_rect(r->w, r->h, &x0, &y0, &iw, &ih);
    if (iw < 4 || ih < 3)
        return;
    if (!have_depth) {
        static const float FRAME[4] = {1.0f, 1.0f, 1.0f, 1.0f};
        static const float DARK[4] = {0.10f, 0.12f, 0.20f, 1.0f};
        float b = (float)(r->w / 320 > 1 ? r->w / 320 : 1);
        cub_render_shape_rect(r, (float)x0 - b, (float)y0 - b, (float)(x0 + iw) + b,
                              (float)(y0 + ih) + b, FRAME);
        cub_render_shape_rect(r, (float)x0, (float)y0, (float)(x0 + iw), (float)(y0 + ih), DARK);
    }
    if (child->status != CUB_TRACK_NO_PLAYER) {
        /* A child too near the camera reaches past the image: its bones
         * are cut at the inset's edge (the frame runs with the scissor on,
         * set to the viewport). */
        cub_render_batch_draw(r);
        glScissor(r->x0 + x0, r->y0 + y0, iw, ih);
        bones(r, child, x0, y0, iw, ih, mark);
        cub_render_batch_draw(r);
        glScissor(r->x0, r->y0, r->w, r->h);
    }
    cub_render_batch_draw(r);
    if (cue_text && cue_text[0])
        cue(r, cue_text, x0, y0, iw, ih);
}

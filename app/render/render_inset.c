/* render_inset — the Kinect depth image as a small picture in the
 * lower-right corner, so a parent can see what the box sees.
 *
 * Raw 11-bit disparity to distance through the firmware's table
 * (cub_track_raw_to_mm, the data README's formula), so the inset and the
 * tracker agree on every value. Shade: near bright, far dark; "no reading"
 * (2047, or a value the table has no depth for) is black, and every real
 * reading is at least FAR_SHADE so it never looks like a hole.
 *
 * Layout: width = w/5, height = 3/4 of that (the 640x480 aspect), a margin
 * of max(2, w/80) pixels from the right and bottom edges, and a white frame
 * of max(1, w/320) pixels around it. */
#include <math.h>

#include "cub/track.h"
#include "render_internal.h"

#define NEAR_MM 500.0f
#define FAR_MM 4000.0f
#define FAR_SHADE 48.0f

void cub_render_inset_init_lut(uint8_t lut[2048])
{
    for (int raw = 0; raw < 2048; raw++) {
        double mm = cub_track_raw_to_mm((uint16_t)raw) / 65536.0;
        if (mm <= 0.0) {
            lut[raw] = 0;
            continue;
        }
        float t = ((float)mm - NEAR_MM) / (FAR_MM - NEAR_MM);
        t = t < 0.0f ? 0.0f : t > 1.0f ? 1.0f : t;
        lut[raw] = (uint8_t)lrintf(255.0f - t * (255.0f - FAR_SHADE));
    }
}

void cub_render_inset_rect(int w, int h, int *x0, int *y0, int *iw, int *ih)
{
    (void)h;
    int margin = w / 80 > 2 ? w / 80 : 2;
    *iw = w / 5;
    *ih = *iw * 3 / 4;
    *x0 = w - margin - *iw;
    *y0 = margin;
}

static void upload(cub_render *r, const uint16_t *depth_raw)
{
    for (int i = 0; i < CUB_RENDER_DEPTH_W * CUB_RENDER_DEPTH_H; i++) {
        uint16_t v = depth_raw[i];
        r->depth_lum[i] = v < 2048 ? r->depth_lut[v] : 0;
    }
    glBindTexture(GL_TEXTURE_2D, r->depth_tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, CUB_RENDER_DEPTH_W, CUB_RENDER_DEPTH_H,
                    GL_LUMINANCE, GL_UNSIGNED_BYTE, r->depth_lum);
}

void cub_render_inset_draw(cub_render *r, const uint16_t *depth_raw)
{
    int x0, y0, iw, ih;
    cub_render_inset_rect(r->w, r->h, &x0, &y0, &iw, &ih);
    if (iw < 4 || ih < 3)
        return;
    int b = r->w / 320 > 1 ? r->w / 320 : 1;
    static const float WHITE[3] = {1.0f, 1.0f, 1.0f};
    cub_render_batch_rect_px(r, (float)(x0 - b), (float)(y0 - b), (float)(x0 + iw + b),
                             (float)(y0 + ih + b), WHITE, WHITE);
    cub_render_batch_draw(r);

    upload(r, depth_raw);
    /* x, y in NDC, then u, v; the image's first row at the inset's top. */
    float l = 2.0f * (float)x0 / (float)r->w - 1.0f;
    float rt = 2.0f * (float)(x0 + iw) / (float)r->w - 1.0f;
    float bt = 2.0f * (float)y0 / (float)r->h - 1.0f;
    float tp = 2.0f * (float)(y0 + ih) / (float)r->h - 1.0f;
    const float quad[6][4] = {{l, bt, 0, 1}, {rt, bt, 1, 1}, {rt, tp, 1, 0},
                              {l, bt, 0, 1}, {rt, tp, 1, 0}, {l, tp, 0, 0}};
    glUseProgram(r->tex_prog);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, r->depth_tex);
    glUniform1i(r->tex_sampler, 0);
    glBindBuffer(GL_ARRAY_BUFFER, r->vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof quad, quad, GL_STREAM_DRAW);
    glEnableVertexAttribArray((GLuint)r->tex_pos);
    glEnableVertexAttribArray((GLuint)r->tex_uv);
    glVertexAttribPointer((GLuint)r->tex_pos, 2, GL_FLOAT, GL_FALSE, 4 * sizeof(float),
                          (const void *)0);
    glVertexAttribPointer((GLuint)r->tex_uv, 2, GL_FLOAT, GL_FALSE, 4 * sizeof(float),
                          (const void *)(2 * sizeof(float)));
    glDrawArrays(GL_TRIANGLES, 0, 6);
    glDisableVertexAttribArray((GLuint)r->tex_pos);
    glDisableVertexAttribArray((GLuint)r->tex_uv);
}

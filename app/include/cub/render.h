/* render — the OpenGL ES 2 renderer. It draws what the firmware decided this
 * tick and decides nothing itself. Needs a current GLES2 context (the
 * board's display). For now: a stick-figure coach and the depth image as a
 * small inset in the lower-right corner.
 */
#ifndef CUB_RENDER_H
#define CUB_RENDER_H

#include <stdint.h>

#include "cub/err.h"
#include "cub/motion.h"

typedef struct cub_render cub_render; /* opaque */

typedef struct cub_render_desc {
    int width, height;        /* viewport in pixels; required */
    float figure_height_mm;   /* height the camera frames; default 1800 */
} cub_render_desc;

typedef struct cub_render_scene {
    /* The coach: joint world positions (mm, y up), 3 floats each, and the
     * skeleton for the bone list. skel == NULL draws no figure. */
    const cub_skeleton *skel;
    const float *world_xyz_mm;
    /* The depth inset: raw 11-bit Kinect values, 640x480; NULL = no inset. */
    const uint16_t *depth_raw;
    float background_rgb[3];  /* all zero = the default sky colour */
} cub_render_scene;

cub_err cub_render_create(const cub_render_desc *desc, cub_render **out);
void cub_render_destroy(cub_render *r);
/* Draw one frame into the current framebuffer. */
cub_err cub_render_frame(cub_render *r, const cub_render_scene *scene);

#endif

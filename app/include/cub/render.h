/* render — the OpenGL ES 2 renderer. It draws what the firmware decided this
 * tick and decides nothing itself. Needs a current GLES2 context (the
 * board's display). The coach is either a lit, rounded character (its
 * body parts from the character file, skinned to the pose in the vertex
 * shader) standing on a cartoon forest stage, or, without a character, a
 * stick figure on a flat sky; the depth image is a small inset in the
 * lower-right corner.
 */
#ifndef CUB_RENDER_H
#define CUB_RENDER_H

#include <stdint.h>

#include "cub/character.h"
#include "cub/err.h"
#include "cub/motion.h"

typedef struct cub_render cub_render; /* opaque */

typedef struct cub_render_desc {
    int width, height;        /* viewport in pixels; required */
    float figure_height_mm;   /* height the camera frames; default 1800 */
    int x, y;                 /* viewport origin in the framebuffer, pixels from
                                 the bottom-left; default 0, 0. A frame clears and
                                 draws only its own viewport, so several renderers
                                 can share one framebuffer (side by side). */
} cub_render_desc;

/* The camera around the framed figure, for viewers (cubtool play); the box
 * keeps the default. Zero-initialised = the default front view. */
typedef struct cub_render_view {
    float yaw_deg;   /* orbit about the vertical through the figure; + = the
                        camera moves to the figure's left (its left side shows) */
    float pitch_deg; /* orbit up (+, looking down on it) or down; clamped to +-80 */
    float zoom;      /* > 1 = closer; 0 = 1; clamped to 0.1..10 */
} cub_render_view;

/* The character's face. Who picks it: the caller, from the coach's state
 * (session.c: dozing -> sleepy, correcting or worried -> worried). */
typedef enum cub_render_face {
    CUB_RENDER_FACE_HAPPY = 0, /* open eyes with a sparkle, a smile */
    CUB_RENDER_FACE_WORRIED,   /* brows raised in the middle, a small wobbly mouth */
    CUB_RENDER_FACE_SLEEPY,    /* closed eyes, a small round mouth */
    CUB_RENDER_FACE_COUNT
} cub_render_face;

typedef struct cub_render_scene {
    /* The coach: joint world positions (mm, y up), 3 floats each, and the
     * skeleton for the bone list. skel == NULL draws no figure. */
    const cub_skeleton *skel;
    const float *world_xyz_mm;
    /* With a character and joint world rotations (unit quaternions x, y,
     * z, w per joint of skel, as cub_motion_forward gives them) the coach
     * is the character on the forest stage; its parts follow skel's joints
     * of the same names. Without (or when no part's joint is in skel): the
     * stick figure. The character's meshes are built on the first frame
     * that shows it and kept while the same character is shown. */
    const cub_character *character;
    const float *world_rot_xyzw;
    cub_render_face face;
    /* The depth inset: raw 11-bit Kinect values, 640x480; NULL = no inset. */
    const uint16_t *depth_raw;
    float background_rgb[3];  /* all zero = the default sky (stick figure only) */
} cub_render_scene;

cub_err cub_render_create(const cub_render_desc *desc, cub_render **out);
void cub_render_destroy(cub_render *r);
/* Draw one frame into the current framebuffer. CUB_ERR_ARG for a scene
 * whose skeleton or character does not hold together (nothing drawn);
 * CUB_ERR_DEVICE when GL fails. */
cub_err cub_render_frame(cub_render *r, const cub_render_scene *scene);
/* The camera for the following frames; NULL = the default view. It turns
 * and scales the coach (and the stage) about a point at mid-height of the
 * frame above the root; the background and the depth inset stay put. */
void cub_render_set_view(cub_render *r, const cub_render_view *view);

#endif

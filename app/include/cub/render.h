/* render — the OpenGL ES 2 renderer. It draws what the firmware decided this
 * tick and decides nothing itself. Needs a current GLES2 context (the
 * board's display). The coach is either a lit, rounded character (its
 * body parts from the character file, skinned to the pose in the vertex
 * shader) standing on a cartoon forest stage, or, without a character, a
 * stick figure on a flat sky; the depth image is a small inset in the
 * lower-right corner with the child's own skeleton and a distance cue.
 * Over it: the hint text with the move's icon, the song's progress, and
 * the idle screen while the box waits (render_hud.c). Every word drawn is
 * the scene's (app/cubdance/words.c chooses them).
 */
#ifndef CUB_RENDER_H
#define CUB_RENDER_H

#include <stddef.h>
#include <stdint.h>

#include "cub/character.h"
#include "cub/err.h"
#include "cub/floor.h"
#include "cub/motion.h"
#include "cub/track.h"

/* Debian's fonts-dejavu-core; a bold face reads best from a sofa. */
#define CUB_RENDER_DEFAULT_FONT "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf"

typedef struct cub_render cub_render; /* opaque */

typedef struct cub_render_desc {
    int width, height;        /* viewport in pixels; required */
    float figure_height_mm;   /* height the camera frames; default 1800 */
    int x, y;                 /* viewport origin in the framebuffer, pixels from
                                 the bottom-left; default 0, 0. A frame clears and
                                 draws only its own viewport, so several renderers
                                 can share one framebuffer (side by side). */
    /* The TrueType font of every text; NULL = CUB_RENDER_DEFAULT_FONT. A
     * font that cannot be read fails cub_render_create. */
    const char *font_path;
    /* Where cub_render_create puts a message for the user when it fails
     * ("cannot load font PATH: why"); NULL = none. */
    char *error;
    size_t error_size;
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

    /* What the child reads. The caller picks all of it, words included,
     * from the tick's state; the renderer lays it out and never chooses a
     * word. Strings are UTF-8 (Latin-1 range drawn, other characters as
     * '?'), laid out again only when changed. */
    const char *hint;         /* under the coach; NULL or "" = none */
    /* The current move's icon: the coach's skel in the move's most telling
     * pose (joint world positions, mm, 3 floats each), drawn as a chunky
     * silhouette on a round badge beside the hint. NULL = no badge. */
    const float *icon_xyz_mm;
    /* The song's progress 0..1 as a bar along the top when has_progress
     * (a flag rather than "< 0 = none", so a zero scene, e.g. cubtool's
     * viewer, draws no bar). */
    float progress;
    int has_progress;
    int idle;                 /* 1: the idle screen over the coach: dimmed, a play
                                 button and the title */
    const char *title;        /* with idle: its words ("Press START!"); NULL = none */
    /* The child in the inset: the tracker's skeleton (camera mm), drawn
     * over the depth image (or on a dark panel without one), orange unless
     * its status is OK. NULL = none. */
    const cub_track_skeleton *child;
    const char *child_cue;    /* with child: words above the inset ("Step back"); NULL = none */
    /* With child: the joints (bit CUB_KJ_*) whose bones to their parents
     * are drawn marked, wider and in pink: the limb the hint asks the
     * child to move. 0 = none. */
    uint32_t child_mark;
} cub_render_scene;

/* CUB_ERR_ARG for a bad desc, CUB_ERR_IO / CUB_ERR_FORMAT for a font that
 * cannot be read or is not TrueType (the message in desc->error),
 * CUB_ERR_DEVICE when GL fails. */
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
/* The ground the character stands on (cub/floor.h; copied): the rolling
 * floor with its logs and stones, drawn where it is (the camera follows the
 * root over it, at the ground's height under the root), the trees and
 * bushes on it. The caller puts the character on it: the scene's joints
 * are world positions, their heights the floor's (cub_floor_terrain).
 * NULL: the flat meadow that follows the root (the default). CUB_ERR_ARG
 * for a floor cub_floor_check refuses, CUB_ERR_DEVICE when GL fails. */
cub_err cub_render_set_floor(cub_render *r, const cub_floor *floor);

/* ---- the motion player's scene (cubtool play, SEEDS.md § 002) ----------- */

#define CUB_RENDER_PLAYER_MAX_POINTS 256 /* joints or markers of one character */

/* One character: joints (or markers) in world mm, y up. */
typedef struct cub_render_player_figure {
    int joint_count;           /* 0..CUB_RENDER_PLAYER_MAX_POINTS */
    const int16_t *parent;     /* [joint_count], -1 for a root; NULL: markers, always
                                  drawn as numbered points */
    const float *world_xyz_mm; /* 3 floats per joint; a NaN x: not there (a lost marker) */
    float rgb[3];
    float ground_mm[2];        /* x, z of its spot on the floor (the selection ring's centre) */
    int selected;              /* a ring on the floor around its spot */
} cub_render_player_figure;

typedef struct cub_render_player_scene {
    const cub_render_player_figure *figures;
    int figure_count;
    int points;           /* 1: every joint a point with its number beside it; 0: sticks */
    float floor_mm;       /* the square floor's side, centred on the origin; 0 = none */
    float target_mm[3];   /* what the camera looks at */
    float yaw_deg;        /* the camera's orbit about the target: + turns it to the right */
    float pitch_deg;      /* + looks down from above; -89..89 */
    float distance_mm;    /* from the target; > 0 */
} cub_render_player_scene;

/* Draw one frame of the motion player into the renderer's viewport: a
 * dark sky, the floor as a grid of 10 x 10 cells, the figures in one
 * perspective view (40 degrees high), and in points mode each joint's
 * index beside it. CUB_ERR_ARG for a bad scene (nothing drawn). */
cub_err cub_render_player_frame(cub_render *r, const cub_render_player_scene *scene);

#endif

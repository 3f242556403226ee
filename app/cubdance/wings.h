/* wings — the bear with wings while it dances bird_flying (issue 22,
 * docs/evolve.md). `cubtool evolve` crossed the bear's bird_flying with our
 * bird's flapping (assets/keys/bird_flap.keys) into a child: the bear's
 * joints and the bird's wings. The box keeps dancing the library's clips
 * on the bear's skeleton (what the director, the judge and the log see is
 * unchanged); only the picture gains the child's optional joints: their
 * rotations from the child's clip, hung on the bear's posed joints, and
 * the renderer draws their parts (assets/bear/bear_winged.xml).
 *
 * In and out (bridges): the wings unfold from a fold along the back over
 * WINGS_OPEN_S when bird_flying starts (or the coach's move becomes it),
 * and fold back the same way after it ends and the move is another, still
 * beating while they fold; folded, they are hidden. The fold
 * is the same for any optional joints: the first bone of a chain lies
 * down the back, each further bone doubles back on the one before. */
#ifndef CUB_APP_WINGS_H
#define CUB_APP_WINGS_H

#include <stdint.h>

#include "cub/character.h"
#include "cub/io.h"
#include "cub/motion.h"

typedef struct cub_wings {
    int loaded;
    cub_character ch;     /* the winged bear: the bear's joints and parts, then the wings */
    cub_io_motion motion; /* the child's clip: every joint of ch */
    int clip;             /* the library clip that has the wings (bird_flying) */
    int move_clip;        /* the clip of the move the coach is on; -1 none */
    int extra;            /* optional joints of ch (the last ones) */
    int src[CUB_MOTION_MAX_JOINTS];  /* per optional joint: its joint in motion */
    float fold[CUB_MOTION_MAX_JOINTS][4]; /* per optional joint: the folded rotation, xyzw */
    float open;           /* 0 folded (hidden) .. 1 flapping */
    double frame;         /* where the wings are in the child's clip */
    int64_t last_us;
    cub_skeleton skel;    /* the library's skeleton and the optional joints */
    float xyz[3 * CUB_MOTION_MAX_JOINTS], rot[4 * CUB_MOTION_MAX_JOINTS];
    float icon[3 * CUB_MOTION_MAX_JOINTS];
} cub_wings;

/* Load the winged character and its clip beside the coach's character
 * (dir of character_path: <name>_winged.xml and <clip>.wings.bvh) for the
 * library clip named clip_name. Missing files: no wings (0, loaded 0); a
 * broken file: 1 with a message in err. */
int cub_wings_open(cub_wings *w, const char *character_path, const char *clip_name,
                   const cub_skeleton *lib_skel, int clip, char *err, size_t err_size);
void cub_wings_close(cub_wings *w);
/* The clip of the song move the coach is dancing or correcting (-1: none).
 * While it is the winged clip the wings stay out, whatever clip plays (a
 * correcting head shake or watch_me): they belong to the move. */
void cub_wings_move(cub_wings *w, int move_clip);
/* This tick: the player plays clip at pos_q16 (frames, Q16). 1 when the
 * wings show: w->skel, w->xyz and w->rot are the scene's (the bear's
 * joints as given, then the wings). */
int cub_wings_pose(cub_wings *w, int clip, int64_t pos_q16, int64_t t_us, const float *xyz,
                   const float *rot);
/* icon (joint positions on the library's skeleton) with the wings folded
 * onto their parents, for w->skel. */
const float *cub_wings_icon(cub_wings *w, const float *icon);

#endif

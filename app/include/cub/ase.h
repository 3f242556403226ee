/* ase — skeletal animation in 3ds Max's ASCII export (.ase), as the
 * folk-dance seed's player reads it (SEEDS.md § 002), and a writer for the
 * round trip (no real ASE animation file is at hand).
 *
 *   *3DSMAX_ASCIIEXPORT 200
 *   *SCENE { *SCENE_FIRSTFRAME 0  *SCENE_LASTFRAME n-1  *SCENE_FRAMESPEED 30
 *            *SCENE_TICKSPERFRAME 160 }
 *   *HELPEROBJECT {              (or *GEOMOBJECT; one per bone, parents first)
 *     *NODE_NAME "Hips"  *NODE_PARENT "..."  *HELPER_CLASS "Bone" ("Dummy": an end site)
 *     *NODE_TM { *TM_ROW0..3 (rows of the world rest matrix, row vectors)
 *                *TM_POS x y z  *TM_QUATERNION x y z w (world rest rotation) }
 *     *TM_ANIMATION {
 *       *CONTROL_POS_TRACK { *CONTROL_POS_SAMPLE tick x y z ... }
 *       *CONTROL_ROT_TRACK { *CONTROL_ROT_SAMPLE tick ax ay az angle ... } } }
 *
 * World transforms: M_i = M_parent · T_i · R_i. T_i is the node's
 * CONTROL_POS_SAMPLE at that frame (a pure translation) or, without one,
 * the rest offset (TM_POS_i − TM_POS_parent) in the parent's rest frame
 * (TM_QUATERNION, else the rotation of TM_ROW0..2). R_i: the first
 * CONTROL_ROT_SAMPLE is relative to the parent, each later one to the
 * previous frame (rot[i] = rot[i−1] · rot[i]); without a track, the rest
 * rotation relative to the parent's. [ours, where 3ds Max and the seed
 * leave it open: a rotation sample is a unit axis and an angle in radians,
 * as 3ds Max writes it; every track has one sample a frame, at ticks
 * (first + k) · ticks per frame; TM_QUATERNION is x y z w.]
 *
 * Errors name the file and line: no *3DSMAX_ASCIIEXPORT first, no *SCENE
 * before the nodes, a node without a name or with an unknown or later
 * parent, a name twice, more than CUB_MOTION_MAX_JOINTS nodes, a sample at
 * the wrong tick or a track of the wrong length, a number that is not one,
 * an axis that is not unit, unbalanced braces. Never a crash
 * (tests/fuzz/fuzz_ase.c). */
#ifndef CUB_ASE_H
#define CUB_ASE_H

#include <stddef.h>

#include "cub/err.h"
#include "cub/io.h"

#define CUB_ASE_TICKS_PER_FRAME 160 /* what the writer puts (3ds Max's default) */

/* Read from memory (name for messages) or a file into out (free with
 * cub_io_motion_free). desc->unit_mm: millimetres per file unit, 0 or a
 * NULL desc to guess from the rest skeleton's size (cub_io_guess_unit_mm). */
cub_err cub_ase_parse(const char *text, size_t len, const char *name, const cub_io_desc *desc,
                      cub_io_motion *out, cub_diag *diag);
cub_err cub_ase_load(const char *path, const cub_io_desc *desc, cub_io_motion *out,
                     cub_diag *diag);
/* Write m's skeleton and clip (units mm): rest transforms from frame 0,
 * a position track for the root (and every joint of a clip that animates
 * translations), a rotation track for every joint but end sites. */
cub_err cub_ase_save(const char *path, const cub_io_motion *m, cub_diag *diag);

#endif

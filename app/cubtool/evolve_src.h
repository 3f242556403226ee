/* evolve_src — what `cubtool evolve` crosses and writes besides BVH: a
 * parent from a .bvh, a pack's clip (LIB.cubclips:NAME) or our own keys on
 * a character's skeleton (CHARACTER.xml:KEYS.keys); and the child as a
 * character file (its skeleton, parent 1's parts, parent 2's parts on the
 * joints it gave, those marked optional="1"). */
#ifndef CUB_CUBTOOL_EVOLVE_SRC_H
#define CUB_CUBTOOL_EVOLVE_SRC_H

#include "cub/character.h"
#include "cub/evolve.h"

/* Load spec resampled at fps; *unit_mm the file unit for writing the child
 * back (10: centimetres, for packs and keys). If spec names a character
 * and ch is not NULL, it is loaded into *ch and *has_ch set. 0 ok; 1 with a
 * message naming the file and the problem. */
int evolve_src_load(const char *spec, double fps, cub_evolve_motion *out, double *unit_mm,
                    cub_character *ch, int *has_ch);

/* The child character file at path: child's joints (names, parents, rest
 * offsets), c1's features and parts on the joints from parent 1, c2's
 * parts on the joints appended from parent 2 (which are optional="1").
 * c1's and c2's skeletons must be the parents' (joints found by name for
 * parent 1, by index for parent 2). 0 ok; 1 with a message. */
int evolve_character_write(const char *path, const char *name, const cub_skeleton *child,
                           const cub_evolve_meta *meta, const cub_evolve_pop *pop,
                           const cub_character *c1, const cub_character *c2);

#endif

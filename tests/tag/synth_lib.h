/* A small hand-made clip library on the bear's skeleton, for the tagging
 * tests before (and besides) the real one: five clips at 30 fps whose
 * poses are easy to reason about. */
#ifndef CUB_TEST_SYNTH_LIB_H
#define CUB_TEST_SYNTH_LIB_H

#include "cub/character.h"
#include "cub/pack.h"

/* The clips, in library order. */
enum { SYNTH_ARMS_UP, SYNTH_RIGHT_WAVE, SYNTH_SQUAT, SYNTH_HEAD_SHAKE, SYNTH_IDLE, SYNTH_CLIPS };

/* Frames of the head-shake clip where the head moves fast (its middle);
 * the first and last SYNTH_SHAKE_STILL frames hold still. */
#define SYNTH_SHAKE_STILL 15

/* Load the bear (CUB_SOURCE_DIR/assets/bear/bear.xml) and build the
 * library on its skeleton. 0 on success. */
int synth_library(cub_character *bear, cub_library *out);
void synth_library_free(cub_library *lib);

#endif

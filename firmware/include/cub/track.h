/* track — from Kinect depth to the player's skeleton (seed card; the
 * tracker itself comes with its own issue). For now: the depth units.
 *
 * The Kinect v1 reports raw 11-bit disparity; 2047 means no reading. Depth
 * in millimetres is mm = 123.6 * tan(raw / 2842.5 + 1.1863) (the data
 * README), looked up in a table computed offline, so no libm is needed and
 * every CPU gets the same numbers.
 */
#ifndef CUB_TRACK_H
#define CUB_TRACK_H

#include <stdint.h>

#include "cub/fx.h"

#define CUB_TRACK_RAW_NO_READING 2047

/* Depth of a raw value in Q16.16 mm (step 1/8 mm); 0 = no usable reading
 * (2047, values above 2047, or farther than 8191 mm). */
cub_q16 cub_track_raw_to_mm(uint16_t raw);
/* The same, rounded to whole millimetres; 0 = no reading. */
uint16_t cub_track_raw_to_mm_int(uint16_t raw);

#endif

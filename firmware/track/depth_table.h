/* The raw->mm table (private to track). See depth_table.c. */
#ifndef CUB_TRACK_DEPTH_TABLE_H
#define CUB_TRACK_DEPTH_TABLE_H

#include <stdint.h>

#include "cub/kinect.h"

extern const uint16_t cub_track_depth_mm_q3[2048];

/* A raw reading in whole mm, 0 for none (cub_track_raw_to_mm_int): inline
 * for the tracker's grid and the forest's image, which read every pixel
 * they sample. */
static inline uint16_t trk_raw_mm(uint16_t raw)
{
    if (raw >= CUB_KINECT_NO_READING) return 0;
    return (uint16_t)((cub_track_depth_mm_q3[raw] + 4) >> 3);
}

#endif

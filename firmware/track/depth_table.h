/* The raw->mm table (private to track). See depth_table.c. */
#ifndef CUB_TRACK_DEPTH_TABLE_H
#define CUB_TRACK_DEPTH_TABLE_H

#include <stdint.h>

extern const uint16_t cub_track_depth_mm_q3[2048];

#endif

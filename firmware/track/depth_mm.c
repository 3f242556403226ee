#include "cub/track.h"
#include "depth_table.h"

cub_q16 cub_track_raw_to_mm(uint16_t raw)
{
    if (raw >= CUB_KINECT_NO_READING) return 0;
    return (cub_q16)cub_track_depth_mm_q3[raw] << 13; /* Q13.3 -> Q16.16 */
}

uint16_t cub_track_raw_to_mm_int(uint16_t raw) { return trk_raw_mm(raw); }

/* track_dump — a fakenect dump's depth frames in memory, and a tracker to
 * run over them (shared by eval-track and bench-track). */
#ifndef CUB_CUBTOOL_TRACK_DUMP_H
#define CUB_CUBTOOL_TRACK_DUMP_H

#include <stdint.h>

#include "cub/forest.h"
#include "cub/track.h"

#define CUB_TOOL_FRAME_PIXELS (CUB_KINECT_WIDTH * CUB_KINECT_HEIGHT)

/* One dump: its depth frames in INDEX order. */
typedef struct cub_tool_dump {
    int n;
    uint16_t *raw;  /* n * CUB_TOOL_FRAME_PIXELS, raw 11-bit */
    int64_t *t_us;  /* n: the seconds stamp of each name */
    char (*name)[128];
} cub_tool_dump;

/* Load up to max_frames depth frames of DIR/INDEX.txt; a bad frame is
 * reported ("<who>: <file>: <problem>") and skipped. 0 when at least one
 * frame loaded. */
int cub_tool_dump_load(const char *dir, cub_tool_dump *d, int max_frames, const char *who);
void cub_tool_dump_free(cub_tool_dump *d);

/* A forest asset read from a file and opened (f a view of *bytes, to
 * free). 0 on success; -1 with "<who>: <path>: <problem>" on stderr. */
int cub_tool_forest_load(const char *path, char **bytes, cub_forest *f, const char *who);

/* A tracker with the default desc (and the forest f, or NULL: the
 * heuristic tracker alone) in fresh aligned memory (*mem, to free); NULL
 * with "<who>: cannot set up the tracker" on stderr. */
cub_tracker *cub_tool_tracker_new(void **mem, const cub_forest *f, const char *who);

#endif

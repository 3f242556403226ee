/* record — opt-in recording of what the Kinect sees, as a fakenect dump
 * (INDEX.txt, d-<time>-<timestamp>.pgm raw 11-bit depth, a-<...>.dump the
 * accelerometer as libfreenect's freenect_raw_tilt_state), the format
 * fakenect-record writes and `cubdance --replay` plays back.
 *
 * Nothing records unless the app opens a recorder, which it does only for
 * recording=1 in the config or --record DIR. Each recording is a new folder
 * (mode 0700) under the recording directory, named by the local time it
 * began. Recording stops for good, with a log line, once the directory
 * holds max_bytes in all (what earlier runs left counts) or the disk would
 * keep less than reserve_bytes free. The log gets start and stop lines,
 * never image data. */
#ifndef CUB_APP_RECORD_H
#define CUB_APP_RECORD_H

#include <stddef.h>
#include <stdint.h>

#include "cub/board.h"
#include "cub/loop.h"

typedef struct cub_record_desc {
    const char *dir;       /* where recordings go (created if missing) */
    int64_t max_bytes;     /* all of dir together; default 2 GB */
    int64_t reserve_bytes; /* free space always left on the disk; default 256 MB */
    cub_log *log;          /* start/stop lines; NULL = none */
} cub_record_desc;

typedef struct cub_record cub_record;

/* Check or create dir and count what it holds. CUB_ERR_IO with "PATH: why"
 * in err when it cannot be made or written. */
cub_err cub_record_open(const cub_record_desc *desc, cub_record **out, char *err,
                        size_t err_size);
/* Start a new recording folder; frames go there until cub_record_end. */
void cub_record_begin(cub_record *r, int64_t t_us);
/* Close the current recording (if any), logging why ("idle", "exit"). */
void cub_record_end(cub_record *r, int64_t t_us, const char *reason);
/* Store one frame (a cub_board_depth_tap; user is the recorder). */
void cub_record_frame(void *r, const cub_depth_frame *frame);
/* 1 while frames are being written. */
int cub_record_active(const cub_record *r);
void cub_record_close(cub_record *r);

#endif

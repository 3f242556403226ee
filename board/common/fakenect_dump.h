/* fakenect_dump — look at a fakenect dump before fakenect reads it, and
 * mend bad depth frames (private to board/; depth_freenect.c calls it).
 *
 * fakenect (Debian 0.5.3) trusts its dump: it calls exit() on a file named
 * in INDEX.txt that will not open, and copies a whole frame out of a frame
 * file whatever its size (a short file is read past its end). A camera that
 * wrote half a frame, or a frame lost from a copy, must not stop the box: a
 * bad depth frame is replayed as a frame without readings (what a Kinect
 * gives when it sees nothing), and the box recovers at the next good frame.
 *
 * For that fakenect is handed a private view of the dump: a fresh directory
 * (mode 0700, under $TMPDIR or /tmp) with a copy of INDEX.txt, a symbolic
 * link to every good file, and for each bad depth frame a file of the same
 * name holding 640x480 raw 2047 (no reading). The bad file's bytes are never
 * copied: the box keeps no camera data. An empty a-* file (fakenect's read
 * of it fails, and it ends the replay there) gets a file of the same name
 * holding a reading of zeros, which the box takes for no reading. fakenect
 * sleeps between two lines for the difference of their recorded seconds,
 * inside freenect_process_events where no --seconds can end it: a line
 * whose seconds jump more than 10 s past the line before is listed under a
 * name with the jump taken out (one frame's step instead), linked to its
 * file, and so is every line after it. Every
 * other fault (no FAKENECT_PATH or INDEX.txt, a missing a-* file, a missing
 * or short r-* file, no good depth frame at all) refuses the dump with
 * INDEX.txt:line. */
#ifndef CUB_BOARD_FAKENECT_DUMP_H
#define CUB_BOARD_FAKENECT_DUMP_H

#include <stddef.h>

#include "cub/err.h"

#define CUB_FAKENECT_PATH_MAX 4096

typedef struct cub_fakenect_view {
    char dir[CUB_FAKENECT_PATH_MAX]; /* the view; "" when the dump is replayed as it is */
    char *saved_path;                /* the caller's FAKENECT_PATH, to put back */
    int env_pointed;                 /* FAKENECT_PATH names dir until restored */
    int bad_frames;                  /* depth frames replayed without readings */
} cub_fakenect_view;

/* Check the dump named by FAKENECT_PATH. All good: CUB_OK, v->dir "". Bad
 * depth frames: builds the view, warns once per bad file on stderr, points
 * FAKENECT_PATH at the view and returns CUB_OK. Refused: CUB_ERR_DEVICE (no
 * FAKENECT_PATH), CUB_ERR_IO (no INDEX.txt, the view cannot be made) or
 * CUB_ERR_FORMAT, with "fakenect dump <dir>: INDEX.txt:<line>: ..." in err.
 * v must be zeroed; release it on every path. */
cub_err cub_fakenect_dump_prepare(cub_fakenect_view *v, char *err, size_t err_size);

/* Put the caller's FAKENECT_PATH back once fakenect has read it (0.5.3 reads
 * it at the first freenect_process_events and keeps the pointer). */
void cub_fakenect_dump_restore_env(cub_fakenect_view *v);

/* Restore FAKENECT_PATH if still pointed, remove the view. Safe on a zeroed
 * or released v. Call only once fakenect reads no more (after shutdown). */
void cub_fakenect_dump_release(cub_fakenect_view *v);

#endif

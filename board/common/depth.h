/* depth — the depth sources behind cub_board_depth_poll (private to board/).
 *
 *   freenect  libfreenect: a live Kinect, or a dump replayed by fakenect
 *             (same calls either way; depth_freenect.c)
 *   empty     a built-in empty scene: every pixel CUB_DEPTH_NO_READING,
 *             a frame every 1/30 s of board time (depth_empty.c)
 *
 * Frame times (t_us) are board time, read from the board's clock. */
#ifndef CUB_BOARD_DEPTH_H
#define CUB_BOARD_DEPTH_H

#include <stddef.h>
#include <stdint.h>

#include "clock.h"
#include "cub/board.h"

#define CUB_DEPTH_EMPTY_PERIOD_NUM_US 1000000 /* frame k is due at k * NUM / DEN us */
#define CUB_DEPTH_EMPTY_PERIOD_DEN 30

typedef struct cub_depth cub_depth;

/* Open the source for mode. AUTO: libfreenect if a device opens, else the
 * empty scene. OFF: *out = NULL and CUB_OK. Fails with CUB_ERR_DEVICE (and a
 * message in err) when FREENECT is asked for and no device opens. */
cub_err cub_depth_open(cub_depth_mode mode, const cub_board_clock *clock, cub_depth **out,
                       char *err, size_t err_size);
/* As cub_board_depth_poll; d NULL gives CUB_ERR_DEVICE. */
cub_err cub_depth_poll(cub_depth *d, cub_depth_frame *out);
/* "freenect" (a live Kinect), "fakenect" (a replayed dump), "empty" or
 * (d NULL) "off". */
const char *cub_depth_name(const cub_depth *d);
void cub_depth_close(cub_depth *d);

/* The two implementations (depth.c picks one). */
typedef struct cub_depth_freenect cub_depth_freenect;
cub_err cub_depth_freenect_open(const cub_board_clock *clock, cub_depth_freenect **out,
                                char *err, size_t err_size);
cub_err cub_depth_freenect_poll(cub_depth_freenect *s, cub_depth_frame *out);
/* 1 when fakenect (not a live Kinect) serves the frames. */
int cub_depth_freenect_is_replay(const cub_depth_freenect *s);
void cub_depth_freenect_close(cub_depth_freenect *s);

typedef struct cub_depth_empty cub_depth_empty;
cub_err cub_depth_empty_open(const cub_board_clock *clock, cub_depth_empty **out);
cub_err cub_depth_empty_poll(cub_depth_empty *s, cub_depth_frame *out);
void cub_depth_empty_close(cub_depth_empty *s);

#endif

/* buttons_script — button presses replayed from a timeline file (private to
 * board/; both boards use it, for replays and tests).
 *
 * The file, one entry per line, times in seconds since the board opened:
 *
 *     # comments and blank lines are ignored
 *     1.5  start           (same as "press")
 *     4    stop  down
 *     4.25 stop  up
 *     9    start press     (down now, up 100 ms later)
 *
 * Times must not decrease from line to line; a button may not go down while
 * it is down, nor up while it is up. Errors name file:line and the problem. */
#ifndef CUB_BOARD_BUTTONS_SCRIPT_H
#define CUB_BOARD_BUTTONS_SCRIPT_H

#include <stddef.h>
#include <stdint.h>

#include "cub/err.h"
#include "cub/loop.h"

#define CUB_BUTTON_SCRIPT_PRESS_US 100000 /* how long a "press" holds the button */
#define CUB_BUTTON_SCRIPT_MAX_BYTES (1 << 20)

typedef struct cub_button_script cub_button_script;

/* Parse text (len bytes; NUL not required). `file` names it in errors.
 * CUB_ERR_FORMAT with "file:line: problem" in err on bad input. */
cub_err cub_button_script_parse(const char *text, size_t len, const char *file,
                                cub_button_script **out, char *err, size_t err_size);
/* Read and parse a file (CUB_ERR_IO if it cannot be read). */
cub_err cub_button_script_load(const char *path, cub_button_script **out, char *err,
                               size_t err_size);
void cub_button_script_free(cub_button_script *s);

/* Number of edges (a press counts two). */
size_t cub_button_script_edges(const cub_button_script *s);
/* 1 and *ev filled with the next edge if it is due by now_us, else 0.
 * ev: CUB_EV_BUTTON_DOWN/UP, a = cub_button, t_us = the scripted time. */
int cub_button_script_next(cub_button_script *s, int64_t now_us, cub_event *ev);
/* Post every edge due by now_us to the loop, in time order. If the queue is
 * full the rest wait for the next poll. */
void cub_button_script_poll(cub_button_script *s, cub_loop *loop, int64_t now_us);

#endif

/* timeline — a scripted stand-in for the judge until the tracker feeds real
 * verdicts: a text file of timed events, replayed into the loop.
 *
 *   # seconds  what
 *   12.0  wrong      the child got the current move wrong
 *   14.5  right      ... and now right
 *   20.0  nobody     the child walks out of view
 *   26.0  player     ... and comes back
 *   30.0  clap       the child claps (wakes the coach)
 *
 * Times are seconds since the program started, non-decreasing; `#` starts a
 * comment. Verdicts carry move index -1 ("the move being taught now"); the
 * app fills in the move when it delivers them. */
#ifndef CUB_APP_TIMELINE_H
#define CUB_APP_TIMELINE_H

#include <stddef.h>
#include <stdint.h>

#include "cub/err.h"
#include "cub/loop.h"

typedef struct cub_timeline cub_timeline;

/* Parse text (name is for messages); errors go to err as "name:line: why". */
cub_err cub_timeline_parse(const char *text, size_t len, const char *name, cub_timeline **out,
                           char *err, size_t err_size);
cub_err cub_timeline_load(const char *path, cub_timeline **out, char *err, size_t err_size);
void cub_timeline_free(cub_timeline *t);
/* How many events the file holds. */
int cub_timeline_count(const cub_timeline *t);
/* The next event due at or before now_us, or 0 when none is due yet. */
int cub_timeline_next(cub_timeline *t, int64_t now_us, cub_event *out);

#endif

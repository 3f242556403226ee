/* event_log — the file the event log's lines go to. Under systemd the box
 * runs for weeks and restarts after a failure: before a line that would
 * take it past max_bytes the file is moved to <path>.1 (replacing the
 * older one) and a new one begins with that line, so the
 * log never holds more than twice that; and a capped log that already has
 * lines when the program starts (the run before a restart, whose last
 * lines say why it ended) is moved to <path>.1 first instead of being
 * overwritten. Done here rather than by logrotate: the app knows its line
 * boundaries, needs no cron job or copytruncate race, and the cap is one
 * key in the config. */
#ifndef CUB_APP_EVENT_LOG_H
#define CUB_APP_EVENT_LOG_H

#include <stddef.h>
#include <stdio.h>

typedef struct cub_event_log_file {
    FILE *f;              /* stderr for no path or "-"; NULL if a reopen failed */
    const char *path;
    long max_bytes, bytes; /* max 0 = no cap */
    long lost_lines;       /* lines that could not be written (a full disk) */
    int write_errno;       /* the first failed write's errno; 0: none failed */
} cub_event_log_file;

/* Open path ("-" or NULL = stderr) with a cap of max_kb (0 = none). -1 with
 * a message on stderr when the file cannot be written. */
int cub_event_log_open(cub_event_log_file *lf, const char *path, long max_kb);
/* A cub_loop log sink: user is the cub_event_log_file. A line that cannot
 * be written is counted in lost_lines; the first such says so on stderr
 * (the lines before it stay in the file). */
void cub_event_log_line(void *user, const char *line, size_t len);
/* Close the file; 0, or -1 when a line was lost or the close failed, with
 * what was lost on stderr. */
int cub_event_log_close(cub_event_log_file *lf);

#endif

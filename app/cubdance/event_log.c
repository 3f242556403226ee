/* event_log — see event_log.h. */
#include "event_log.h"

#include <errno.h>
#include <string.h>
#include <sys/stat.h>

/* The stream's buffer is ours, and a new file after a move reuses the
 * stream (freopen): moving the log allocates nothing in a running box. */
static char line_buf[BUFSIZ];

/* A new file at path; into `reuse` when there is one. */
static FILE *open_path(const char *path, FILE *reuse)
{
    FILE *f = reuse ? freopen(path, "w", reuse) : fopen(path, "w");
    if (!f) {
        fprintf(stderr, "cubdance: cannot write the event log %s: %s\n", path, strerror(errno));
        return NULL;
    }
    setvbuf(f, line_buf, _IOLBF, sizeof line_buf); /* a line reaches the file as it happens */
    return f;
}

static void keep_as_older(const char *path)
{
    char old[4096];
    snprintf(old, sizeof old, "%s.1", path);
    if (rename(path, old) != 0)
        fprintf(stderr, "cubdance: cannot move the event log to %s: %s\n", old, strerror(errno));
}

int cub_event_log_open(cub_event_log_file *lf, const char *path, long max_kb)
{
    *lf = (cub_event_log_file){.f = stderr, .path = path, .max_bytes = max_kb * 1024L};
    if (!path || !strcmp(path, "-")) return 0;
    struct stat st;
    if (lf->max_bytes > 0 && stat(path, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0)
        keep_as_older(path);
    lf->f = open_path(path, NULL);
    return lf->f ? 0 : -1;
}

/* The first lost line says so at once: the box's memory is going. */
static void lost(cub_event_log_file *lf, int err)
{
    if (lf->lost_lines++ == 0) {
        lf->write_errno = err ? err : EIO;
        fprintf(stderr, "cubdance: cannot write the event log %s: %s; lines are being lost\n",
                lf->path ? lf->path : "(stderr)", strerror(lf->write_errno));
    }
}

void cub_event_log_line(void *user, const char *line, size_t len)
{
    cub_event_log_file *lf = user;
    if (!lf->f) { /* the log could not be reopened: the run goes on */
        lost(lf, errno);
        return;
    }
    /* Move the log before a line that would pass the cap, not after one
     * that reached it: the newest file then always ends with the last
     * line written (a run's `app end`), wherever the cap falls. */
    if (lf->max_bytes > 0 && lf->bytes > 0 && lf->bytes + (long)len + 1 > lf->max_bytes &&
        lf->f != stderr) {
        fflush(lf->f);
        keep_as_older(lf->path); /* the open stream follows the file to its new name */
        lf->f = open_path(lf->path, lf->f);
        lf->bytes = 0;
        if (!lf->f) {
            lost(lf, errno);
            return;
        }
    }
    /* Line-buffered: the newline writes the line, and fails if it cannot. */
    errno = 0;
    if (fwrite(line, 1, len, lf->f) != len || fputc('\n', lf->f) == EOF || ferror(lf->f)) {
        lost(lf, errno);
        clearerr(lf->f);
        return;
    }
    lf->bytes += (long)len + 1;
}

int cub_event_log_close(cub_event_log_file *lf)
{
    errno = 0;
    if (lf->f && lf->f != stderr && fclose(lf->f) != 0) lost(lf, errno);
    lf->f = NULL;
    if (lf->lost_lines == 0) return 0;
    fprintf(stderr, "cubdance: the event log %s is incomplete: %ld line%s lost (%s)\n",
            lf->path ? lf->path : "(stderr)", lf->lost_lines, lf->lost_lines == 1 ? "" : "s",
            strerror(lf->write_errno));
    return -1;
}

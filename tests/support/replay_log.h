/* replay_log — cmocka helpers for the tests that read a replay's event
 * log: the log (loaded by the group's setup), freeing it, skipping when the
 * dump was absent, and a numeric field that fails the test when missing.
 * Header-only; include after <cmocka.h>. Test code only. */
#ifndef CUB_REPLAY_LOG_H
#define CUB_REPLAY_LOG_H

#include <stdio.h>

#include "logread.h"

static logread events; /* the run's events.log */

/* OUT_DIR/events.log into events: 0, or -1 (the group fails). */
static inline int replay_load_log(const char *out_dir)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/events.log", out_dir);
    return logread_load(path, &events);
}

static inline int replay_teardown(void **s)
{
    (void)s;
    logread_free(&events);
    return 0;
}

/* Skip the test, naming the dump, when it was not there to replay. */
static inline void replay_need_dump(int have, const char *dump_dir)
{
    if (!have) {
        print_message("SKIP: no dump at %s (../shared/data is absent)\n", dump_dir);
        skip();
    }
}

/* key=<number> of log line `line` (0-based); fails the test if absent. */
static inline double field(int line, const char *key)
{
    int ok;
    double v = logread_number(&events.lines[line], key, &ok);
    if (!ok) fail_msg("log line %d has no numeric %s=", line + 1, key);
    return v;
}

#endif

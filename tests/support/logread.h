/* logread — read a cubdance event log in tests: every line is
 * `t=<seconds> <source> <event> key=value ...`. */
#ifndef CUB_TEST_LOGREAD_H
#define CUB_TEST_LOGREAD_H

#include <stddef.h>

typedef struct logread_line {
    double t_s;
    char source[32];
    char event[32];
    char rest[480]; /* the key=value part */
} logread_line;

typedef struct logread {
    logread_line *lines;
    int count;
} logread;

/* 0 on success; -1 if the file cannot be read or a line is malformed
 * (the message names the file and line, printed to stdout). */
int logread_load(const char *path, logread *out);
void logread_free(logread *log);
/* Next line index >= from with this source and event (NULL = any); -1 if none. */
int logread_find(const logread *log, int from, const char *source, const char *event);
/* Count lines with this source and event. */
int logread_count(const logread *log, const char *source, const char *event);
/* The value of key in a line as text (copied into buf) or NULL if absent. */
const char *logread_field(const logread_line *line, const char *key, char *buf, size_t size);
/* The value of key as a number; *ok = 0 if absent or not a number. */
double logread_number(const logread_line *line, const char *key, int *ok);

#endif

/* run_tool — run a program (a test's cubtool) through the shell with
 * stderr joined to stdout: its output into buf (NUL-terminated, cut at
 * size - 1), its exit status returned (-1 if it did not exit). */
#ifndef CUB_TEST_RUN_TOOL_H
#define CUB_TEST_RUN_TOOL_H

#include <stdarg.h>
#include <stddef.h>

/* `'tool' ARGS 2>&1`, ARGS printf-formatted from fmt. */
int cub_test_run_toolv(const char *tool, char *buf, size_t size, const char *fmt, va_list ap)
    __attribute__((format(printf, 4, 0)));

#endif

#define _XOPEN_SOURCE 700 /* popen */
#include "run_tool.h"

#include <stdio.h>
#include <sys/wait.h>

int cub_test_run_toolv(const char *tool, char *buf, size_t size, const char *fmt, va_list ap)
{
    char args[4096], cmd[8192];
    vsnprintf(args, sizeof args, fmt, ap);
    snprintf(cmd, sizeof cmd, "'%s' %s 2>&1", tool, args);
    buf[0] = '\0';
    FILE *f = popen(cmd, "r");
    if (!f) return -1;
    size_t n = fread(buf, 1, size - 1, f);
    buf[n] = '\0';
    int st = pclose(f);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* tool_util — small helpers the cubtool commands share. */
#ifndef CUB_CUBTOOL_UTIL_H
#define CUB_CUBTOOL_UTIL_H

#include <stddef.h>

/* Create dir and its missing parents (like mkdir -p). 0 on success; -1 with
 * a message "<who>: cannot create <dir>: <reason>" on stderr. */
int cub_tool_make_dir(const char *dir, const char *who);

/* A growing list of samples for a bench's percentiles. */
typedef struct cub_tool_series {
    double *v;
    size_t n, cap;
} cub_tool_series;

/* Append x; out of memory ends the program with "<who>: out of memory". */
void cub_tool_series_add(cub_tool_series *s, double x, const char *who);
/* Nearest-rank percentile (q in 0..1; 1 is the largest), 0 when empty; sorts. */
double cub_tool_series_pct(cub_tool_series *s, double q);

#endif

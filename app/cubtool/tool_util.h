/* tool_util — small helpers the cubtool commands share. */
#ifndef CUB_CUBTOOL_UTIL_H
#define CUB_CUBTOOL_UTIL_H

#include <stddef.h>

#include "cub/motion.h"

/* Create dir and its missing parents (like mkdir -p). 0 on success; -1 with
 * a message "<who>: cannot create <dir>: <reason>" on stderr. */
int cub_tool_make_dir(const char *dir, const char *who);

/* Options of a command: "--name VALUE" into *value, or a bare "--name"
 * setting *flag to 1 (value NULL). */
typedef struct cub_tool_opt {
    const char *name;
    const char **value;
    int *flag;
} cub_tool_opt;

/* What cub_tool_parse_opts found. */
typedef enum cub_tool_parsed {
    CUB_TOOL_RUN = 0, /* go on */
    CUB_TOOL_HELP,    /* --help / -h: print the usage, exit 0 */
    CUB_TOOL_BAD,     /* said why on stderr ("cubtool <who>: unexpected 'x'"): exit 2 */
} cub_tool_parsed;

/* argv[1..] against opts (n of them); words without a dash fill
 * positional[0..npos) in order (NULL: none allowed). */
cub_tool_parsed cub_tool_parse_opts(int argc, char **argv, const cub_tool_opt *opts, int n,
                                    const char **positional, int npos);

/* A growing list of samples for a bench's percentiles. */
typedef struct cub_tool_series {
    double *v;
    size_t n, cap;
} cub_tool_series;

/* Append x; out of memory ends the program with "<who>: out of memory". */
void cub_tool_series_add(cub_tool_series *s, double x, const char *who);
/* Nearest-rank percentile (q in 0..1; 1 is the largest), 0 when empty; sorts. */
double cub_tool_series_pct(cub_tool_series *s, double q);

/* A clip as a BVH file (centimetres; root XYZ position, every joint ZXY
 * rotation, joint positions too when the clip animates them). 0 on
 * success; -1 with the file's problem on stderr. */
int cub_tool_save_clip_bvh(const cub_skeleton *skel, const cub_clip *clip, const char *path);

#endif

/* tool_util — small helpers the cubtool commands share. */
#ifndef CUB_CUBTOOL_UTIL_H
#define CUB_CUBTOOL_UTIL_H

/* Create dir and its missing parents (like mkdir -p). 0 on success; -1 with
 * a message "<who>: cannot create <dir>: <reason>" on stderr. */
int cub_tool_make_dir(const char *dir, const char *who);

#endif

/* Finding motion files: every .bvh under a folder, sorted by path. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/io.h"

static int collect(const char *dir, int depth, char **out, int n, int max)
{
    DIR *d = opendir(dir);
    if (!d) return n;
    struct dirent *e;
    while ((e = readdir(d)) && n < max) {
        if (e->d_name[0] == '.') continue;
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        size_t len = strlen(e->d_name);
        if (len > 4 && !strcmp(e->d_name + len - 4, ".bvh")) {
            char *copy = strdup(path);
            if (copy) out[n++] = copy;
        } else if (depth > 0) {
            n = collect(path, depth - 1, out, n, max);
        }
    }
    closedir(d);
    return n;
}

static int by_path(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

int cub_io_list_bvh(const char *dir, int depth, char **out, int max)
{
    int n = collect(dir, depth, out, 0, max);
    qsort(out, (size_t)n, sizeof *out, by_path);
    return n;
}

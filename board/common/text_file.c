#include "text_file.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

cub_err cub_board_read_text(const char *path, const char *what, size_t max_bytes, char **text,
                            size_t *len, char *err, size_t err_size)
{
    *text = NULL;
    *len = 0;
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, err_size, "%s: cannot open the %s", path, what);
        return CUB_ERR_IO;
    }
    /* One byte more than allowed, to tell "exactly full" from "too big". */
    char *buf = malloc(max_bytes + 1);
    size_t got = buf ? fread(buf, 1, max_bytes + 1, f) : 0;
    int read_err = ferror(f);
    fclose(f);
    cub_err e = CUB_OK;
    if (!buf) {
        e = CUB_ERR_NOMEM;
        snprintf(err, err_size, "%s: out of memory", path);
    } else if (read_err) {
        e = CUB_ERR_IO;
        snprintf(err, err_size, "%s: read error", path);
    } else if (got > max_bytes) {
        e = CUB_ERR_FORMAT;
        snprintf(err, err_size, "%s: larger than %zu bytes (not a %s?)", path, max_bytes, what);
    }
    if (e) {
        free(buf);
        return e;
    }
    *text = buf;
    *len = got;
    return CUB_OK;
}

cub_err cub_board_fail_at(const cub_board_at *at, const char *fmt, ...)
{
    int n = snprintf(at->err, at->err_size, "%s:%d: ", at->file, at->line);
    if (n >= 0 && (size_t)n < at->err_size) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(at->err + n, at->err_size - (size_t)n, fmt, ap);
        va_end(ap);
    }
    return CUB_ERR_FORMAT;
}

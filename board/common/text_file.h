/* text_file — read a small text file the user gave the board (a button
 * timeline, a GPIO config) whole, with a size cap, and say clearly what
 * went wrong (private to board/). */
#ifndef CUB_BOARD_TEXT_FILE_H
#define CUB_BOARD_TEXT_FILE_H

#include <stddef.h>

#include "cub/err.h"

/* Read path into a malloc'ed buffer (*text, free with free(); not NUL
 * terminated) of *len <= max_bytes. what names the file's kind in messages:
 * "%s: cannot open the <what>", "%s: larger than N bytes (not a <what>?)". */
cub_err cub_board_read_text(const char *path, const char *what, size_t max_bytes, char **text,
                            size_t *len, char *err, size_t err_size);

/* Where a parser of such a file is, and where its message goes. */
typedef struct cub_board_at {
    const char *file; /* for messages */
    int line;         /* 1-based */
    char *err;
    size_t err_size;
} cub_board_at;

/* "<file>:<line>: <message>" into at->err (cut to err_size); returns
 * CUB_ERR_FORMAT, for the parsers' `return cub_board_fail_at(...)`. */
cub_err cub_board_fail_at(const cub_board_at *at, const char *fmt, ...);

#endif

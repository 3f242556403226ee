/* text_file — read a small text file the user gave the board (a button
 * timeline, a GPIO config) whole, with a size cap, and say clearly what
 * went wrong (private to board/). */
#ifndef CUB_BOARD_TEXT_FILE_H
#define CUB_BOARD_TEXT_FILE_H

#include <stdarg.h>
#include <stddef.h>

#include "cub/err.h"

/* Read path into a malloc'ed buffer (*text, free with free(); not NUL
 * terminated) of *len <= max_bytes. what names the file's kind in messages:
 * "%s: cannot open the <what>", "%s: larger than N bytes (not a <what>?)". */
cub_err cub_board_read_text(const char *path, const char *what, size_t max_bytes, char **text,
                            size_t *len, char *err, size_t err_size);

/* "<file>:<line>: <message>" into err (cut to err_size); returns
 * CUB_ERR_FORMAT, for the parsers' `return fail(...)`. */
cub_err cub_board_vfail_at(char *err, size_t err_size, const char *file, int line,
                           const char *fmt, va_list ap);

#endif

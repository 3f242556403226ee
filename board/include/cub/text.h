/* text — reading the files people write by hand (retarget maps, recipes,
 * keyframes, BVH, XML, button and judge timelines, the box's config): read
 * one whole with a size cap, hand it to a parser as a whole or line by
 * line, free it. Every problem lands in a cub_diag as "file:line: what".
 *
 * It is the lowest host layer: the board's parsers need it and the board
 * may not depend on app/, while the firmware makes no OS calls. So it lives
 * in board/, as its own small library (libc only), which app/ links too.
 * Sizes are bytes; lines are numbered from 1. */
#ifndef CUB_TEXT_H
#define CUB_TEXT_H

#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>

#include "cub/err.h"

/* What went wrong and where: how every reader on the host reports. */
typedef struct cub_diag {
    char file[256];
    int line; /* 1-based; 0 when the problem is not tied to a line */
    char msg[256];
} cub_diag;

/* Format "file:line: msg" (or "file: msg") into buf; returns buf. */
const char *cub_diag_str(const cub_diag *d, char *buf, size_t size);
/* Fill diag (when not NULL) with file (NULL: ""), line and the printf-style
 * message, and return err. */
cub_err cub_diag_fail(cub_diag *diag, cub_err err, const char *file, int line, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
cub_err cub_diag_vfail(cub_diag *diag, cub_err err, const char *file, int line, const char *fmt,
                       va_list ap) __attribute__((format(printf, 5, 0)));
/* For readers whose API reports into a string: when e failed with a
 * message in d, "file:line: msg" into buf. Returns e. */
cub_err cub_diag_report(cub_err e, const cub_diag *d, char *buf, size_t size);

/* How large each kind of file may be: far above any real one (the figures
 * are the largest the repo ships), low enough that a huge or endless file
 * is refused before a byte of it is read, in a message that states the
 * limit. A reader that names no limit gets CUB_TEXT_MAX_BYTES. */
#define CUB_TEXT_KB ((size_t)1 << 10)
#define CUB_TEXT_MB ((size_t)1 << 20)
#define CUB_TEXT_MAX_BYTES (64 * CUB_TEXT_MB)
#define CUB_TEXT_MAX_CONFIG (64 * CUB_TEXT_KB)   /* the box's config: 1 kB */
#define CUB_TEXT_MAX_SMALL (1 * CUB_TEXT_MB)     /* maps, recipes, keys, characters: 5 kB */
#define CUB_TEXT_MAX_SONG (4 * CUB_TEXT_MB)      /* a song.xml: 3 kB */
#define CUB_TEXT_MAX_MIDI (4 * CUB_TEXT_MB)      /* a song's MIDI: 2 kB */
#define CUB_TEXT_MAX_TIMELINE (4 * CUB_TEXT_MB)  /* timelines, scripts, sequences */
#define CUB_TEXT_MAX_TAGS (64 * CUB_TEXT_MB)     /* a clip library's tags: 0.9 MB */
#define CUB_TEXT_MAX_CLIPS (64 * CUB_TEXT_MB)    /* a clip library (.cubclips): 0.45 MB */
#define CUB_TEXT_MAX_MOCAP (64 * CUB_TEXT_MB)    /* BVH, ASF/AMC takes, truth: 3.8 MB */
#define CUB_TEXT_MAX_FONT (32 * CUB_TEXT_MB)     /* DejaVuSans-Bold: 0.7 MB */
#define CUB_TEXT_MAX_VOICE (32 * CUB_TEXT_MB)    /* the bear's spoken words: 2.2 MB */

/* n bytes in words for a message: "4 MB", "64 kB", else "1234 bytes". */
const char *cub_text_size_str(size_t n, char *buf, size_t size);

/* A file to read. */
typedef struct cub_text_src {
    const char *path; /* also its name in messages */
    const char *what; /* its kind in messages, e.g. "recipe" (NULL: "file") */
    size_t max_bytes; /* larger is refused; 0: CUB_TEXT_MAX_BYTES */
} cub_text_src;

/* A text in memory, as a parser gets it. */
typedef struct cub_text {
    const char *s; /* len bytes, NUL-terminated when read from a file */
    size_t len;
    const char *name; /* for messages */
    cub_diag *diag;   /* where a problem goes (may be NULL) */
} cub_text;

/* Where a parser is in a text, for its messages. */
typedef struct cub_text_at {
    const char *name;
    int line; /* 1-based; 0: the text as a whole */
    cub_diag *diag;
} cub_text_at;

/* One line, as a line parser gets it: without its newline, a '\r' before
 * it, or a '#' comment; NUL-terminated and the parser's to cut up. */
typedef struct cub_text_line {
    char *s;
    cub_text_at at;
} cub_text_line;

/* A parser of a whole text: in is what it reads against (may be NULL), out
 * what it fills. */
typedef cub_err (*cub_text_whole_fn)(const cub_text *t, const void *in, void *out);
typedef cub_err (*cub_text_line_fn)(void *ctx, cub_text_line *ln);

/* The one way the box opens a file it is given: refuse, without blocking,
 * what is not a regular file (a FIFO would hang the open, a device never
 * ends, a directory reads nothing) or is larger than src's cap, saying
 * which, with errno in words and the file's name in diag. The fd (close
 * it) in *fd, the file's size in *size. CUB_ERR_IO when it cannot be read,
 * CUB_ERR_FORMAT when too large. */
cub_err cub_text_open(const cub_text_src *src, int *fd, size_t *size, cub_diag *diag);
/* cub_text_open as a stdio stream "rb" (fclose it); f NULL only checks. */
cub_err cub_text_fopen(const cub_text_src *src, FILE **f, size_t *size, cub_diag *diag);
/* Read src->path whole into *out (malloc'ed, NUL-terminated, *len bytes
 * before the NUL; free() it). CUB_ERR_IO when it cannot be read,
 * CUB_ERR_FORMAT when it is larger than the cap, CUB_ERR_NOMEM. */
cub_err cub_text_read(const cub_text_src *src, char **out, size_t *len, cub_diag *diag);
/* 3 when s starts with a UTF-8 byte-order mark (which cub_text_parse and
 * cub_text_lines drop), else 0: for readers that take the text themselves. */
size_t cub_text_bom_len(const char *s, size_t len);
/* Hand t whole to parse(t, in, out), without a UTF-8 byte-order mark at
 * its start, and return its result; CUB_ERR_ARG when t has a length but no
 * bytes, or out is NULL. */
cub_err cub_text_parse(const cub_text *t, cub_text_whole_fn parse, const void *in, void *out);
/* Read src->path, cub_text_parse it, free it; parse's result, or
 * cub_text_read's failure. */
cub_err cub_text_load(const cub_text_src *src, cub_text_whole_fn parse, const void *in, void *out,
                      cub_diag *diag);
/* Hand fn every line of t (a UTF-8 byte-order mark at its start dropped)
 * that holds more than blanks once its comment is cut, in order; stops at fn's first failure and returns it. A line with a
 * NUL byte fails ("contains a NUL byte"); CUB_ERR_ARG when t->s is NULL
 * with a length. */
cub_err cub_text_lines(const cub_text *t, cub_text_line_fn fn, void *ctx);
/* Split s in place at blanks into words[0..max); returns how many, or
 * max + 1 when there are more. */
int cub_text_words(char *s, char **words, int max);
/* "name:line: message" into at->diag; returns CUB_ERR_FORMAT. */
cub_err cub_text_fail(const cub_text_at *at, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

#endif

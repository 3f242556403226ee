/* io internals shared by the BVH and ASF/AMC parsers: a tokenizer that
 * tracks line numbers, diagnostics, and the conversions to the firmware's
 * fixed-point types (the rotation maths are cub/vec.h). Not public. */
#ifndef CUB_IO_INTERNAL_H
#define CUB_IO_INTERNAL_H

#include <stddef.h>

#include "cub/io.h"
#include "cub/vec.h"

/* Frame data larger than this is refused as absurd (a clip of 128 joints
 * at 120 fps for 10 minutes needs about 150 MB). */
#define IO_MEM_CAP_BYTES ((size_t)512 << 20)
/* Largest |value| a Q16.16 millimetre can hold, with a little margin. */
#define IO_MM_LIMIT 32767.0

/* ---- tokens ------------------------------------------------------------ */

typedef struct io_tok {
    const char *s;
    size_t n;
    int line;          /* 1-based line the token is on */
    int first_on_line; /* nothing but blanks before it on its line */
} io_tok;

typedef struct io_lex {
    const char *p, *end;
    int line;
    int at_line_start;
    int split_braces; /* '{' and '}' are tokens of their own (BVH) */
    int hash_comments; /* '#' starts a comment to the end of line (ASF/AMC) */
    const char *name;
    cub_diag *diag;
} io_lex;

void io_lex_init(io_lex *lx, const char *text, size_t len, const char *name, cub_diag *diag);
/* Next token; 0 at the end of the input. */
int io_lex_next(io_lex *lx, io_tok *t);
/* The next token without consuming it; 0 at the end. */
int io_lex_peek(const io_lex *lx, io_tok *t);
/* Next token if it is on the current line; 0 at a line end or the end. */
int io_lex_next_same_line(io_lex *lx, io_tok *t);
/* Skip to the start of the next line. */
void io_lex_skip_line(io_lex *lx);
/* Bytes left after the current position. */
size_t io_lex_left(const io_lex *lx);

int io_tok_is(const io_tok *t, const char *word);
int io_tok_is_nocase(const io_tok *t, const char *word);
/* The token as a printable, quoted, shortened string for messages. */
const char *io_tok_show(const io_tok *t, char *buf, size_t size);
/* Copy a token into a NUL-terminated buffer; 0 if it does not fit. */
int io_tok_copy(const io_tok *t, char *buf, size_t size);

/* Parse a finite decimal number ("-1.5", ".03", "2.9e-15"). On failure
 * fill the diag ("bad number 'x' for <what>") and return CUB_ERR_FORMAT. */
int io_parse_double(const io_tok *t, double *out); /* 1 if it is one */
cub_err io_tok_double(io_lex *lx, const io_tok *t, const char *what, double *out);
/* Parse a decimal integer into a long (sign allowed). */
cub_err io_tok_long(io_lex *lx, const io_tok *t, const char *what, long *out);

/* Fill the diag (file from lx->name) and return CUB_ERR_FORMAT. */
cub_err io_fail(io_lex *lx, int line, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* With an explicit error code and file name (no lexer): cub_diag_fail. */

/* ---- fixed point ------------------------------------------------------- */

/* Q2.30 with w >= 0, rounded to nearest (the identity for a zero or
 * non-finite q): the one sign for q and -q that clips are stored with. */
cub_quat io_quat_to_fx(cub_dq q);
/* Millimetres to Q16.16; the caller checks the range first. */
int32_t io_mm_to_q16(double mm);
double io_q16_to_mm(int32_t q);

/* Allocate and lay out m->clip for this many frames (checks the memory
 * cap; fills the diag on failure). m->skel must be complete. */
cub_err io_clip_alloc(cub_io_motion *m, int frame_count, uint32_t frame_ns, int with_trans,
                      const char *file, int line, cub_diag *diag);

#endif

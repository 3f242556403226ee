/* err — the one error type every fallible cubdance function returns.
 * CUB_OK is zero, so `if (err) ...` reads naturally. */
#ifndef CUB_ERR_H
#define CUB_ERR_H

typedef enum cub_err {
    CUB_OK = 0,
    CUB_ERR_ARG,         /* a NULL pointer, a zero size, a value out of its domain */
    CUB_ERR_NOMEM,       /* the caller's buffer or pool is too small */
    CUB_ERR_RANGE,       /* an index or time outside what the object holds */
    CUB_ERR_FULL,        /* a queue or table has no free slot */
    CUB_ERR_EMPTY,       /* nothing to take (no event, no new frame yet) */
    CUB_ERR_FORMAT,      /* input data is malformed */
    CUB_ERR_IO,          /* the OS refused a read or write */
    CUB_ERR_UNSUPPORTED, /* valid input we do not handle */
    CUB_ERR_DEVICE,      /* hardware missing or failing */
    CUB_ERR_END,         /* a stream (a replayed recording) has ended */
    CUB_ERR_COUNT_
} cub_err;

/* A short lowercase name for the error, e.g. "format"; never NULL. */
const char *cub_err_str(cub_err e);

#endif

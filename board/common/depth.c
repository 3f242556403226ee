/* depth — picks a depth source for the mode and forwards to it. */
#include "depth.h"

#include <stdio.h>
#include <stdlib.h>

typedef enum depth_kind { DEPTH_FREENECT, DEPTH_EMPTY } depth_kind;

struct cub_depth {
    depth_kind kind;
    cub_depth_freenect *freenect;
    cub_depth_empty *empty;
};

static cub_err wrap(depth_kind kind, cub_depth_freenect *fn, cub_depth_empty *em, cub_depth **out)
{
    cub_depth *d = calloc(1, sizeof *d);
    if (!d) {
        cub_depth_freenect_close(fn);
        cub_depth_empty_close(em);
        return CUB_ERR_NOMEM;
    }
    d->kind = kind;
    d->freenect = fn;
    d->empty = em;
    *out = d;
    return CUB_OK;
}

static cub_err open_empty(const cub_board_clock *clock, cub_depth **out, char *err, size_t err_size)
{
    cub_depth_empty *em = NULL;
    cub_err e = cub_depth_empty_open(clock, &em);
    if (e) {
        snprintf(err, err_size, "depth: cannot set up the empty scene: %s", cub_err_str(e));
        return e;
    }
    return wrap(DEPTH_EMPTY, NULL, em, out);
}

cub_err cub_depth_open(cub_depth_mode mode, const cub_board_clock *clock, cub_depth **out, char *err,
                       size_t err_size)
{
    if (!out || !err || err_size == 0) {
        return CUB_ERR_ARG;
    }
    *out = NULL;
    err[0] = '\0';
    switch (mode) {
    case CUB_DEPTH_OFF:
        return CUB_OK;
    case CUB_DEPTH_EMPTY:
        return open_empty(clock, out, err, err_size);
    case CUB_DEPTH_AUTO:
    case CUB_DEPTH_FREENECT: {
        cub_depth_freenect *fn = NULL;
        cub_err e = cub_depth_freenect_open(clock, &fn, err, err_size);
        if (e == CUB_OK) {
            return wrap(DEPTH_FREENECT, fn, NULL, out);
        }
        if (mode == CUB_DEPTH_FREENECT || e != CUB_ERR_DEVICE) {
            return e;
        }
        /* AUTO without a Kinect: the empty scene keeps the program running. */
        err[0] = '\0';
        return open_empty(clock, out, err, err_size);
    }
    }
    snprintf(err, err_size, "depth: unknown depth mode %d", (int)mode);
    return CUB_ERR_ARG;
}

cub_err cub_depth_poll(cub_depth *d, cub_depth_frame *out)
{
    if (!d) {
        return CUB_ERR_DEVICE;
    }
    if (!out) {
        return CUB_ERR_ARG;
    }
    return d->kind == DEPTH_FREENECT ? cub_depth_freenect_poll(d->freenect, out)
                                     : cub_depth_empty_poll(d->empty, out);
}

const char *cub_depth_name(const cub_depth *d)
{
    if (!d) {
        return "off";
    }
    if (d->kind == DEPTH_FREENECT) {
        return cub_depth_freenect_is_replay(d->freenect) ? "fakenect" : "freenect";
    }
    return "empty";
}

void cub_depth_close(cub_depth *d)
{
    if (!d) {
        return;
    }
    cub_depth_freenect_close(d->freenect);
    cub_depth_empty_close(d->empty);
    free(d);
}

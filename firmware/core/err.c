#include "cub/err.h"

const char *cub_err_str(cub_err e)
{
    static const char *const names[CUB_ERR_COUNT_] = {
        [CUB_OK] = "ok",
        [CUB_ERR_ARG] = "bad argument",
        [CUB_ERR_NOMEM] = "buffer too small",
        [CUB_ERR_RANGE] = "out of range",
        [CUB_ERR_FULL] = "full",
        [CUB_ERR_EMPTY] = "empty",
        [CUB_ERR_FORMAT] = "malformed input",
        [CUB_ERR_IO] = "i/o error",
        [CUB_ERR_UNSUPPORTED] = "unsupported",
        [CUB_ERR_DEVICE] = "device error",
        [CUB_ERR_END] = "end of stream",
    };
    if ((unsigned)e >= CUB_ERR_COUNT_) return "unknown error";
    return names[e];
}

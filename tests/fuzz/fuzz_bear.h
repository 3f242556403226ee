/* For the fuzz targets that bind a map to a skeleton: the bear's. */
#ifndef CUB_FUZZ_BEAR_H
#define CUB_FUZZ_BEAR_H

#include <stdlib.h>

#include "cub/io.h"

/* The bear's skeleton and a little motion (assets/clips/hello.bvh), loaded
 * once: the other side of a map or a cross. */
static inline const cub_io_motion *cub_fuzz_bear(void)
{
    static cub_io_motion bear;
    static int loaded;
    cub_diag d;
    if (!loaded && cub_io_load_bvh(CUB_SOURCE_DIR "/assets/clips/hello.bvh", NULL, &bear, &d) != CUB_OK)
        abort();
    loaded = 1;
    return &bear;
}

#endif

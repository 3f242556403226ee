/* The bear's clip library as the repository holds it
 * ($CUB_SOURCE_DIR/assets/clips/bear.cubclips), for tests that link cub_io
 * (inline: the support library itself does not link cub_io). */
#ifndef CUB_TEST_BEAR_LIBRARY_H
#define CUB_TEST_BEAR_LIBRARY_H

#include <stdio.h>
#include <stdlib.h>

#include "cub/pack.h"

/* Read it into lib; 0, or -1 after saying why on stderr. */
static inline int support_bear_library(cub_library *lib)
{
    const char *src = getenv("CUB_SOURCE_DIR");
    char path[1024];
    snprintf(path, sizeof path, "%s/assets/clips/bear.cubclips", src ? src : ".");
    cub_diag d = {0};
    if (cub_pack_read(path, lib, &d)) {
        fprintf(stderr, "cannot read %s: %s\n", path, d.msg);
        return -1;
    }
    return 0;
}

#endif

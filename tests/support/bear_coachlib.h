/* The coach's shipped clips as a bridge table ($CUB_SOURCE_DIR/assets:
 * cub_coachlib_load_assets), for tests that link cub_io (inline: the
 * support library itself does not link cub_io). */
#ifndef CUB_TEST_BEAR_COACHLIB_H
#define CUB_TEST_BEAR_COACHLIB_H

#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "cub/coachlib.h"

static inline const char *support_src_dir(void)
{
    const char *s = getenv("CUB_SOURCE_DIR");
    return s ? s : ".";
}

/* Load it into cl: 1 loaded, 0 the library is not built yet (the tests
 * skip), -1 after saying why on stderr (who: the test's name). */
static inline int support_bear_coachlib(cub_coachlib *cl, const char *who)
{
    char assets[1024], lib[1200], buf[600];
    snprintf(assets, sizeof assets, "%s/assets", support_src_dir());
    snprintf(lib, sizeof lib, "%s/clips/bear.cubclips", assets);
    if (access(lib, R_OK) != 0) return 0;
    cub_diag d = {0};
    if (cub_coachlib_load_assets(assets, cl, &d)) {
        fprintf(stderr, "%s: %s\n", who, cub_diag_str(&d, buf, sizeof buf));
        return -1;
    }
    return 1;
}

#endif

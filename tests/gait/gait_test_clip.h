/* The CMU walk the gait tests read from $CUB_DATA_DIR at test time (never
 * committed): one loader for test_gait_walk and test_gait_walker. */
#ifndef CUB_TEST_GAIT_CLIP_H
#define CUB_TEST_GAIT_CLIP_H

#include <stdio.h>

#include "../synth/synth_data.h"
#include "cub/io.h"

/* Load mocap/cmu/<name>.bvh into *m: 0 loaded, 1 no data here (the tests
 * skip; *m stays empty), -1 a file that would not load (said on stdout). */
static inline int gait_test_load(const char *name, cub_io_motion *m)
{
    const char *dir = synth_data_dir(name);
    if (!dir) return 1;
    char path[700];
    snprintf(path, sizeof path, "%s/mocap/cmu/%s.bvh", dir, name);
    cub_diag d = {0};
    if (cub_io_load_bvh(path, &(cub_io_desc){0}, m, &d)) {
        printf("gait: %s:%d: %s\n", d.file, d.line, d.msg);
        return -1;
    }
    return 0;
}

#endif

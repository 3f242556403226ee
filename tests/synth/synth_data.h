/* The shared data the synth tests render from: $CUB_DATA_DIR when it holds
 * the CMU clip named (e.g. "13_29"), else NULL (the test skips). */
#ifndef CUB_TEST_SYNTH_DATA_H
#define CUB_TEST_SYNTH_DATA_H

#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

static inline const char *synth_data_dir(const char *cmu_clip)
{
    const char *d = getenv("CUB_DATA_DIR");
    char probe[600];
    if (!d) return NULL;
    snprintf(probe, sizeof(probe), "%s/mocap/cmu/%s.bvh", d, cmu_clip);
    return access(probe, R_OK) == 0 ? d : NULL;
}

/* In a cmocka test: skip it when the clip's data is missing. */
#define SYNTH_NEED_DATA(cmu_clip)                                                                  \
    do {                                                                                           \
        if (!synth_data_dir(cmu_clip)) {                                                           \
            printf("synth: skipped, no CMU clips under $CUB_DATA_DIR/mocap\n");                   \
            skip();                                                                                \
        }                                                                                          \
    } while (0)

/* CUB_QUICK set: the ctest sample, fewer frames. */
static inline int synth_quick(void)
{
    return getenv("CUB_QUICK") != NULL;
}

#endif

/* A default tracker in its own heap block, for the cmocka tests that paint
 * the tracker's grid through its internal header. One per test file:
 * group setup opens it, teardown frees it. */
#ifndef CUB_TESTS_TRACKER_FIXTURE_H
#define CUB_TESTS_TRACKER_FIXTURE_H

#include <stdlib.h>

#include "cub/track.h"

static void *tracker_fixture_mem;
static cub_tracker *t;

static int tracker_fixture_open(void **st)
{
    (void)st;
    cub_track_desc d = {0};
    size_t sz = cub_track_mem_size(&d);
    free(tracker_fixture_mem);
    tracker_fixture_mem = aligned_alloc(16, (sz + 15) / 16 * 16);
    if (!tracker_fixture_mem || cub_track_init(&d, tracker_fixture_mem, sz, &t) != CUB_OK) return -1;
    return 0;
}

static int tracker_fixture_close(void **st)
{
    (void)st;
    free(tracker_fixture_mem);
    tracker_fixture_mem = NULL;
    return 0;
}

#endif

/* mem_stats — --stats' memory figures: the box's own memory apart from the
 * GL driver's (mem_census.h), the heap's high-water, and the allocations
 * each tick makes, per phase of the run: before the first START, the first
 * song (START until the box waits again), and the steady state after it
 * (every later tick, later songs included). A line at each song start
 * gives resident memory, open descriptors and the heap for a soak.
 *
 * Allocations are counted by libcub_alloc_count.so (cub/alloc_count.h)
 * when it is preloaded; without it the heap is sampled once a tick from
 * malloc's own totals and allocations are not counted; a sanitizer build
 * says both are unavailable. With CUB_ALLOC_OWNERS=1 as well, the counter
 * tells whose each block is, and ours leaves the GL driver's heap out.
 * CUB_ALLOC_TRACE=N in the environment prints
 * the call stacks of the first N allocations of the first song and of the
 * steady state (stderr, `alloc-trace:`). */
#ifndef CUB_APP_MEM_STATS_H
#define CUB_APP_MEM_STATS_H

#include <stdint.h>
#include <stdio.h>

#include "cub/alloc_count.h"

typedef enum cub_mem_phase_id {
    CUB_MEM_BEFORE_START = 0,
    CUB_MEM_FIRST_SONG,
    CUB_MEM_STEADY,
    CUB_MEM_PHASE_COUNT
} cub_mem_phase_id;

typedef struct cub_mem_phase {
    uint32_t ticks, ticks_allocating, max_tick_allocs;
    uint64_t allocs, frees;
    uint64_t owner_allocs[CUB_ALLOC_OWNER_COUNT]; /* with CUB_ALLOC_OWNERS=1 */
} cub_mem_phase;

typedef struct cub_mem_stats {
    cub_alloc_count_read_fn *read;   /* the counter, or NULL */
    cub_alloc_count_trace_fn *trace;
    cub_alloc_count_owners_fn *owners; /* the heap by owner, or NULL */
    const char *heap_missing;        /* why there is no heap figure, or NULL */
    int trace_n;                     /* CUB_ALLOC_TRACE */
    cub_mem_phase_id phase;
    int dancing;                     /* as of the last tick */
    uint32_t songs;                  /* song starts seen */
    cub_alloc_stats last;            /* the counter at the end of the last tick */
    cub_alloc_owners last_owners;    /* ... by owner, when tracked */
    int owners_on;
    int64_t heap_bytes, heap_peak_bytes;
    cub_mem_phase phases[CUB_MEM_PHASE_COUNT];
} cub_mem_stats;

/* Find the counter (or the fallback) and read CUB_ALLOC_TRACE. */
void cub_mem_stats_open(cub_mem_stats *m);
/* At the end of every tick: count its allocations, follow the phases; at a
 * song start (dancing turns 1) write the `stats: song` line to stdout. */
void cub_mem_stats_tick(cub_mem_stats *m, int64_t t_us, int dancing);
/* The memory lines (`stats: memory ...`, `stats: allocations ...`). */
void cub_mem_stats_print(const cub_mem_stats *m, FILE *out);

/* The goal for the box's own memory (heap high-water + static data +
 * stacks), issue 17: it must fit beside the Pi's GL driver and the OS. */
#define CUB_MEM_GOAL_KB (24 * 1024)

#endif

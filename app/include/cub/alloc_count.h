/* alloc_count — what the allocation counter (libcub_alloc_count.so, loaded
 * with LD_PRELOAD for a measurement only) tells the program that reads it.
 * The counter wraps malloc, calloc, realloc, free, posix_memalign,
 * aligned_alloc, memalign, valloc and pvalloc of the whole process: the
 * program's own calls and every library's (FluidSynth, Mesa, libfreenect,
 * SDL, libc's own strdup / fopen ...). Sizes are what the allocator really
 * hands out (malloc_usable_size), so the high-water is what the heap holds.
 *
 * The program finds the counter at run time (dlsym of CUB_ALLOC_COUNT_READ):
 * without it nothing is counted and nothing changes. A sanitizer build has
 * its own allocator and cannot load the counter. */
#ifndef CUB_ALLOC_COUNT_H
#define CUB_ALLOC_COUNT_H

#include <stdint.h>

typedef struct cub_alloc_stats {
    uint64_t allocs;     /* calls that returned memory (realloc counts as one) */
    uint64_t frees;      /* free of a pointer other than NULL, realloc to 0 */
    int64_t live_bytes;  /* usable bytes handed out and not freed yet */
    int64_t peak_bytes;  /* the high-water of live_bytes since the start */
} cub_alloc_stats;

/* Whose allocation it is (CUB_ALLOC_OWNERS=1 in the environment): the
 * library of the innermost frame of its call stack that is not an
 * allocation wrapper (libc's strdup / fopen, libstdc++'s operator new,
 * glib, libpng, tinyxml2 count for their caller). */
typedef enum cub_alloc_owner {
    CUB_ALLOC_OURS = 0, /* the program itself */
    CUB_ALLOC_GL,       /* Mesa, LLVM, EGL / GLES / glvnd */
    CUB_ALLOC_MUSIC,    /* FluidSynth and what it calls (OpenMP, libsndfile, libinstpatch) */
    CUB_ALLOC_CAMERA,   /* libfreenect, or fakenect replaying */
    CUB_ALLOC_SDL,      /* SDL2 */
    CUB_ALLOC_OTHER,    /* any other library */
    CUB_ALLOC_UNTRACKED, /* owners not asked for, or the owners' table was full */
    CUB_ALLOC_OWNER_COUNT
} cub_alloc_owner;

typedef struct cub_alloc_owners {
    uint64_t allocs[CUB_ALLOC_OWNER_COUNT];    /* calls that returned memory */
    int64_t live_bytes[CUB_ALLOC_OWNER_COUNT];
    int64_t peak_bytes[CUB_ALLOC_OWNER_COUNT]; /* each owner's own high-water */
    int64_t not_gl_peak_bytes; /* the high-water of all owners' but the GL driver's */
} cub_alloc_owners;

/* The counter's totals since the process started. */
typedef void cub_alloc_count_read_fn(cub_alloc_stats *out);
/* Print the call stack of each of the next n allocations (any thread) to
 * stderr, one `alloc-trace:` line then one line per frame; n = 0 stops. */
typedef void cub_alloc_count_trace_fn(int n);

/* Each owner's bytes, or 0 when owners are not tracked (the figures are
 * then all CUB_ALLOC_UNTRACKED). */
typedef int cub_alloc_count_owners_fn(cub_alloc_owners *out);

#define CUB_ALLOC_COUNT_READ "cub_alloc_count_read"
#define CUB_ALLOC_COUNT_TRACE "cub_alloc_count_trace"
#define CUB_ALLOC_COUNT_OWNERS "cub_alloc_count_owners"

#endif

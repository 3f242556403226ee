/* owners — whose each live allocation is (cub/alloc_count.h,
 * CUB_ALLOC_OWNERS=1): the owner is found from the call stack when the
 * block is handed out and kept in a table beside the heap (mmap'd, never
 * malloc'd) until it is freed. Slow (a stack walk per allocation): for a
 * measurement run only. */
#ifndef CUB_ALLOC_OWNERS_H
#define CUB_ALLOC_OWNERS_H

#include <stdint.h>

#include "cub/alloc_count.h"

/* Start tracking if the environment asks for it; 1 when on. */
int cub_owners_start(void);
/* A block of n usable bytes was handed out / is about to be freed. */
void cub_owners_add(void *p, int64_t n);
void cub_owners_remove(void *p, int64_t n);
/* The figures (see cub_alloc_count_owners_fn). */
int cub_owners_read(cub_alloc_owners *out);

#endif

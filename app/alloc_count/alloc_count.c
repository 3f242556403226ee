/* alloc_count — an allocation counter for measurements (cub/alloc_count.h):
 * a library loaded with LD_PRELOAD whose malloc family counts each call and
 * the bytes in use, then hands the call to glibc's own allocator
 * (__libc_malloc and friends), so the program allocates exactly as it
 * would without it. Nothing here allocates: the counters are atomics, a
 * trace goes straight to fd 2. */
#define _GNU_SOURCE
#include <errno.h>
#include <execinfo.h>
#include <malloc.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "cub/alloc_count.h"
#include "owners.h"

#define EXPORT __attribute__((visibility("default")))
#define TRACE_FRAMES 24

extern void *__libc_malloc(size_t n);
extern void *__libc_calloc(size_t count, size_t n);
extern void *__libc_realloc(void *p, size_t n);
extern void __libc_free(void *p);
extern void *__libc_memalign(size_t align, size_t n);

static atomic_uint_least64_t allocs, frees;
static atomic_int_least64_t live_bytes, peak_bytes;
static atomic_int trace_left;
/* Initial-exec TLS: the general model may call malloc on first use. */
static __thread int tracing __attribute__((tls_model("initial-exec")));

static void raise_peak(int64_t live)
{
    int64_t peak = atomic_load_explicit(&peak_bytes, memory_order_relaxed);
    while (live > peak && !atomic_compare_exchange_weak(&peak_bytes, &peak, live)) {
    }
}

/* The call stack of this allocation, while traces are wanted; allocations
 * made by the unwinder itself are counted but not traced. */
static void trace(size_t n)
{
    if (tracing || atomic_load_explicit(&trace_left, memory_order_relaxed) <= 0) return;
    if (atomic_fetch_sub(&trace_left, 1) <= 0) return;
    tracing = 1;
    void *frames[TRACE_FRAMES];
    int depth = backtrace(frames, TRACE_FRAMES);
    char head[64];
    int len = snprintf(head, sizeof head, "alloc-trace: size=%zu frames=%d\n", n, depth);
    if (write(2, head, (size_t)len) < 0) (void)0;
    /* All of them: which of the first are this library's depends on what
     * the compiler inlined (scripts/alloc_sites.py skips them by name). */
    backtrace_symbols_fd(frames, depth, 2);
    tracing = 0;
}

static void *counted(void *p, size_t asked)
{
    if (!p) return NULL;
    atomic_fetch_add_explicit(&allocs, 1, memory_order_relaxed);
    int64_t n = (int64_t)malloc_usable_size(p);
    raise_peak(atomic_fetch_add_explicit(&live_bytes, n, memory_order_relaxed) + n);
    cub_owners_add(p, n);
    trace(asked);
    return p;
}

static void uncounted(void *p)
{
    if (!p) return;
    atomic_fetch_add_explicit(&frees, 1, memory_order_relaxed);
    int64_t n = (int64_t)malloc_usable_size(p);
    atomic_fetch_sub_explicit(&live_bytes, n, memory_order_relaxed);
    cub_owners_remove(p, n);
}

EXPORT void *malloc(size_t n)
{
    return counted(__libc_malloc(n), n);
}

EXPORT void *calloc(size_t count, size_t n)
{
    return counted(__libc_calloc(count, n), count * n);
}

EXPORT void free(void *p)
{
    uncounted(p);
    __libc_free(p);
}

/* The old block leaves the count before the call (realloc may free it);
 * if realloc fails it is still there, and comes back. */
EXPORT void *realloc(void *p, size_t n)
{
    if (!p) return malloc(n);
    if (n == 0) {
        free(p);
        return NULL;
    }
    int64_t old = (int64_t)malloc_usable_size(p);
    atomic_fetch_sub_explicit(&live_bytes, old, memory_order_relaxed);
    cub_owners_remove(p, old);
    void *q = __libc_realloc(p, n);
    if (!q) {
        atomic_fetch_add_explicit(&live_bytes, old, memory_order_relaxed);
        cub_owners_add(p, old);
        return NULL;
    }
    return counted(q, n);
}

EXPORT void *memalign(size_t align, size_t n)
{
    return counted(__libc_memalign(align, n), n);
}

EXPORT void *aligned_alloc(size_t align, size_t n)
{
    return counted(__libc_memalign(align, n), n);
}

EXPORT int posix_memalign(void **out, size_t align, size_t n)
{
    if (align < sizeof(void *) || (align & (align - 1))) return EINVAL;
    void *p = counted(__libc_memalign(align, n), n);
    if (!p && n) return ENOMEM;
    *out = p;
    return 0;
}

EXPORT void *valloc(size_t n)
{
    return counted(__libc_memalign((size_t)sysconf(_SC_PAGESIZE), n), n);
}

EXPORT void *pvalloc(size_t n)
{
    size_t page = (size_t)sysconf(_SC_PAGESIZE);
    return counted(__libc_memalign(page, (n + page - 1) / page * page), n);
}

EXPORT void cub_alloc_count_read(cub_alloc_stats *out)
{
    out->allocs = atomic_load(&allocs);
    out->frees = atomic_load(&frees);
    out->live_bytes = atomic_load(&live_bytes);
    out->peak_bytes = atomic_load(&peak_bytes);
}

EXPORT int cub_alloc_count_owners(cub_alloc_owners *out)
{
    return cub_owners_read(out);
}

__attribute__((constructor)) static void start(void)
{
    cub_owners_start();
}

EXPORT void cub_alloc_count_trace(int n)
{
    /* The unwinder loads libgcc_s at its first use: do that here, not
     * inside an allocation. */
    void *prime[2];
    tracing = 1;
    backtrace(prime, 2);
    tracing = 0;
    atomic_store(&trace_left, n > 0 ? n : 0);
}

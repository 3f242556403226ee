/* bench_gl — time spent inside GL calls, for `cubtool bench-render`.
 * cubtool is linked with -Wl,--wrap=<fn> for every GL entry point the
 * renderer calls (the list is CUB_BENCH_GL_WRAPPED in CMakeLists.txt), so a
 * call to glDrawElements lands in __wrap_glDrawElements here, which times
 * the real call with the calling thread's CPU clock when timing is on.
 * With timing off (every other command) a wrapper costs one branch. */
#ifndef CUB_CUBTOOL_BENCH_GL_H
#define CUB_CUBTOOL_BENCH_GL_H

#include <stdint.h>

/* Start (1) or stop (0) timing; starting also zeroes the sums. */
void cub_bench_gl_timing(int on);
/* The calling thread's CPU nanoseconds inside GL calls and the number of
 * calls since the last take (or start), then zero both. */
void cub_bench_gl_take(int64_t *inside_ns, int64_t *calls);
/* CPU nanoseconds of this thread / of the whole process (all threads). */
int64_t cub_bench_thread_ns(void);
int64_t cub_bench_process_ns(void);

#endif

/* The allocation counter (libcub_alloc_count.so, preloaded by ctest with
 * CUB_ALLOC_OWNERS=1) and the memory census the box prints with --stats:
 * what they count, and that reading them allocates nothing. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <fcntl.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <unistd.h>

#include <cmocka.h>

#include "cub/alloc_count.h"
#include "mem_census.h"

static cub_alloc_count_read_fn *count_read;
static cub_alloc_count_owners_fn *count_owners;

static cub_alloc_stats now(void)
{
    cub_alloc_stats s;
    count_read(&s);
    return s;
}

static void test_a_missing_block_is_not_counted(void **state)
{
    (void)state;
    cub_alloc_stats a = now();
    free(NULL);
    void *p = realloc(NULL, 0); /* glibc hands out a minimal block */
    free(p);
    cub_alloc_stats b = now();
    assert_int_equal(b.frees - a.frees, p ? 1 : 0);
    assert_int_equal(b.live_bytes, a.live_bytes);
}

static void test_each_call_counts_once_and_frees_give_back(void **state)
{
    (void)state;
    cub_alloc_stats a = now();
    void *m = malloc(1000), *c = calloc(10, 100), *al = aligned_alloc(64, 640), *pm = NULL;
    assert_int_equal(posix_memalign(&pm, 256, 512), 0);
    cub_alloc_stats b = now();
    assert_int_equal(b.allocs - a.allocs, 4);
    assert_true(b.live_bytes - a.live_bytes >= 1000 + 1000 + 640 + 512);
    assert_int_equal((uintptr_t)al % 64, 0);
    assert_int_equal((uintptr_t)pm % 256, 0);
    free(m), free(c), free(al), free(pm);
    cub_alloc_stats d = now();
    assert_int_equal(d.frees - b.frees, 4);
    assert_int_equal(d.live_bytes, a.live_bytes);
}

static void test_realloc_moves_the_bytes_not_the_count(void **state)
{
    (void)state;
    cub_alloc_stats a = now();
    char *p = malloc(16);
    p = realloc(p, 100000);
    assert_non_null(p);
    cub_alloc_stats b = now();
    assert_int_equal(b.allocs - a.allocs, 2);
    assert_true(b.live_bytes - a.live_bytes >= 100000);
    assert_true(b.live_bytes - a.live_bytes < 100000 + 4096);
    free(p);
    assert_int_equal(now().live_bytes, a.live_bytes);
}

static void test_the_peak_remembers_a_freed_block(void **state)
{
    (void)state;
    cub_alloc_stats a = now();
    free(malloc(8 << 20));
    cub_alloc_stats b = now();
    assert_true(b.peak_bytes >= a.live_bytes + (8 << 20));
    assert_int_equal(b.live_bytes, a.live_bytes);
}

static void test_our_blocks_are_ours(void **state)
{
    (void)state;
    cub_alloc_owners a, b;
    assert_int_equal(count_owners(&a), 1);
    void *p = malloc(5000);
    assert_int_equal(count_owners(&b), 1);
    assert_int_equal(b.allocs[CUB_ALLOC_OURS] - a.allocs[CUB_ALLOC_OURS], 1);
    assert_true(b.live_bytes[CUB_ALLOC_OURS] - a.live_bytes[CUB_ALLOC_OURS] >= 5000);
    assert_int_equal(b.allocs[CUB_ALLOC_GL], a.allocs[CUB_ALLOC_GL]);
    free(p);
    assert_int_equal(count_owners(&b), 1);
    assert_int_equal(b.live_bytes[CUB_ALLOC_OURS], a.live_bytes[CUB_ALLOC_OURS]);
}

static void test_the_census_sees_a_new_descriptor(void **state)
{
    (void)state;
    int before = cub_mem_fd_count();
    assert_true(before >= 3);
    int fd = open("/dev/null", O_RDONLY);
    assert_int_equal(cub_mem_fd_count(), before + 1);
    close(fd);
    assert_int_equal(cub_mem_fd_count(), before);
}

/* .bss: sized, resident only once touched; not static, so the compiler
 * keeps it whole. */
char cub_test_big_static[1 << 20];

static void test_the_census_splits_and_allocates_nothing(void **state)
{
    (void)state;
    cub_test_big_static[0] = 1;
    cub_mem_census c;
    cub_alloc_stats a = now();
    assert_int_equal(cub_mem_census_take(&c), 0);
    long rss = cub_mem_rss_kb();
    cub_alloc_stats b = now();
    assert_int_equal(b.allocs, a.allocs);
    assert_true(c.static_size_kb >= (long)(sizeof cub_test_big_static / 1024));
    assert_true(c.static_kb > 0 && c.static_kb <= c.static_size_kb);
    assert_true(c.stack_kb > 0);
    assert_true(c.libs_kb > 0); /* libc at least */
    assert_int_equal(c.gl_kb, 0); /* no GL driver in this program */
    assert_true(rss > 0 && c.rss_kb > 0);
    assert_true(c.static_kb + c.stack_kb + c.exe_code_kb + c.libs_kb + c.anon_kb <= c.rss_kb + 64);
}

int main(void)
{
    count_read = (cub_alloc_count_read_fn *)dlsym(RTLD_DEFAULT, CUB_ALLOC_COUNT_READ);
    count_owners = (cub_alloc_count_owners_fn *)dlsym(RTLD_DEFAULT, CUB_ALLOC_COUNT_OWNERS);
    if (!count_read || !count_owners) {
        fprintf(stderr, "SKIP: libcub_alloc_count.so is not preloaded\n");
        return 77;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_missing_block_is_not_counted),
        cmocka_unit_test(test_each_call_counts_once_and_frees_give_back),
        cmocka_unit_test(test_realloc_moves_the_bytes_not_the_count),
        cmocka_unit_test(test_the_peak_remembers_a_freed_block),
        cmocka_unit_test(test_our_blocks_are_ours),
        cmocka_unit_test(test_the_census_sees_a_new_descriptor),
        cmocka_unit_test(test_the_census_splits_and_allocates_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

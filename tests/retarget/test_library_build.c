/* The shipped clip library is reproducible: `cubtool build` from the
 * recipe and ../shared/data gives assets/clips/bear.cubclips byte for byte.
 * argv[1] is the cubtool binary. Skips when the data is absent. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <cmocka.h>

#include "cub/io.h"

static const char *cubtool;

static void test_build_reproduces_committed_library(void **state)
{
    (void)state;
    const char *data = getenv("CUB_DATA_DIR"), *src = getenv("CUB_SOURCE_DIR"),
               *bin = getenv("CUB_BUILD_DIR");
    char probe[512], cmd[2048], out[512], committed[512];
    assert_non_null(src);
    assert_non_null(bin);
    snprintf(probe, sizeof(probe), "%s/mocap/cmu/13_29.bvh", data ? data : "");
    struct stat st;
    if (!data || stat(probe, &st)) {
        printf("library: skipped, no mocap under CUB_DATA_DIR\n");
        skip();
    }
    snprintf(out, sizeof(out), "%s/tests/retarget/bear.cubclips", bin);
    snprintf(committed, sizeof(committed), "%s/assets/clips/bear.cubclips", src);
    snprintf(cmd, sizeof(cmd), "'%s' build --data '%s' --out '%s' > '%s.txt' 2> /dev/null",
             cubtool, data, out, out);
    assert_int_equal(system(cmd), 0);

    char *a = NULL, *b = NULL;
    size_t na = 0, nb = 0;
    cub_diag d;
    assert_int_equal(cub_text_read(&(cub_text_src){out, NULL, 0}, &a, &na, &d), CUB_OK);
    assert_int_equal(cub_text_read(&(cub_text_src){committed, NULL, 0}, &b, &nb, &d), CUB_OK);
    size_t first = 0;
    while (first < na && first < nb && a[first] == b[first])
        first++;
    printf("library: rebuilt %zu bytes, committed %zu bytes, %s\n", na, nb,
           na == nb && first == na ? "identical" : "DIFFERENT");
    if (na != nb || first != na)
        printf("library: first difference at byte %zu\n", first);
    assert_int_equal(na, nb);
    assert_memory_equal(a, b, na);
    free(a);
    free(b);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: test_library_build CUBTOOL\n");
        return 2;
    }
    cubtool = argv[1];
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_build_reproduces_committed_library),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

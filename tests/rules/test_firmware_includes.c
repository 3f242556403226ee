/* Every file under firmware/ may include only the C headers that need no OS
 * (ARCHITECTURE.md: stdint, stddef, stdbool, string, limits; plus stdarg,
 * which is freestanding too) and the project's own "cub/..." headers. */
#include <dirent.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <cmocka.h>

static const char *const allowed[] = {"stdint.h", "stddef.h", "stdbool.h",
                                      "string.h", "limits.h", "stdarg.h"};

/* 1 if this #include line is allowed; fills why otherwise. */
static int include_allowed(const char *line, char *why, size_t why_size)
{
    const char *p = line;
    while (*p == ' ' || *p == '\t') p++;
    if (*p != '#') return 1;
    p++;
    while (*p == ' ' || *p == '\t') p++;
    if (strncmp(p, "include", 7) != 0) return 1;
    p += 7;
    while (*p == ' ' || *p == '\t') p++;
    char open = *p, close = open == '<' ? '>' : '"';
    const char *name = p + 1, *end = strchr(name, close);
    if ((open != '<' && open != '"') || !end) {
        snprintf(why, why_size, "unparsable include: %s", line);
        return 0;
    }
    size_t n = (size_t)(end - name);
    if (open == '"' && n > 4 && strncmp(name, "cub/", 4) == 0) return 1;
    if (open == '"' && !memchr(name, '/', n)) return 1; /* a module's own private header */
    for (size_t i = 0; i < sizeof allowed / sizeof *allowed; i++)
        if (strlen(allowed[i]) == n && strncmp(name, allowed[i], n) == 0) return 1;
    snprintf(why, why_size, "includes %.*s", (int)n, name);
    return 0;
}

static int scan_file(const char *path, int *files)
{
    FILE *f = fopen(path, "r");
    if (!f) return 1;
    (*files)++;
    char line[512], why[600];
    int lineno = 0, bad = 0;
    while (fgets(line, sizeof line, f)) {
        lineno++;
        line[strcspn(line, "\r\n")] = '\0';
        if (!include_allowed(line, why, sizeof why)) {
            printf("firmware rule broken: %s:%d: %s\n", path, lineno, why);
            bad++;
        }
    }
    fclose(f);
    return bad;
}

static int scan_dir(const char *dir, int *files)
{
    DIR *d = opendir(dir);
    if (!d) return 0;
    int bad = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.') continue;
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        struct stat st;
        if (stat(path, &st) != 0) continue;
        size_t len = strlen(e->d_name);
        if (S_ISDIR(st.st_mode)) bad += scan_dir(path, files);
        else if (len > 2 && (strcmp(e->d_name + len - 2, ".c") == 0 ||
                             strcmp(e->d_name + len - 2, ".h") == 0))
            bad += scan_file(path, files);
    }
    closedir(d);
    return bad;
}

static void test_checker_flags_os_and_io_headers(void **s)
{
    char why[600];
    assert_false(include_allowed("#include <stdio.h>", why, sizeof why));
    assert_false(include_allowed("  #  include <stdlib.h>", why, sizeof why));
    assert_false(include_allowed("#include <math.h>", why, sizeof why));
    assert_false(include_allowed("#include <sys/time.h>", why, sizeof why));
    assert_false(include_allowed("#include \"../app/include/cub/io.h\"", why, sizeof why));
    assert_true(include_allowed("#include <stdint.h>", why, sizeof why));
    assert_true(include_allowed("#include \"cub/fx.h\"", why, sizeof why));
    assert_true(include_allowed("#include \"fx_tables.h\"", why, sizeof why));
}

static void test_firmware_includes_only_freestanding_headers(void **s)
{
    const char *src = getenv("CUB_SOURCE_DIR");
    if (!src) {
        print_message("CUB_SOURCE_DIR not set: run through ctest\n");
        fail();
    }
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/firmware", src);
    int files = 0;
    int bad = scan_dir(dir, &files);
    printf("firmware includes: %d files scanned, %d forbidden includes\n", files, bad);
    assert_true(files > 5);
    assert_int_equal(bad, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_checker_flags_os_and_io_headers),
        cmocka_unit_test(test_firmware_includes_only_freestanding_headers),
    };
    return cmocka_run_group_tests_name("firmware_includes", tests, NULL, NULL);
}

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

static int file_exists(const char *dir, const char *name, size_t n)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%.*s", dir, (int)n, name);
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* 1 if this #include line, in a file in dir, is allowed; fills why
 * otherwise. A quoted name must be one of the firmware's own headers,
 * beside the file or under firmware/include (root): a quoted "stdio.h"
 * would otherwise fall back to the system's. */
static int include_allowed(const char *line, const char *dir, const char *root, char *why,
                           size_t why_size)
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
    if (open == '"') {
        if ((n > 4 && !strncmp(name, "cub/", 4) && file_exists(root, name, n)) ||
            (!memchr(name, '/', n) && file_exists(dir, name, n)))
            return 1;
        snprintf(why, why_size, "includes \"%.*s\", which is not a firmware header", (int)n,
                 name);
        return 0;
    }
    for (size_t i = 0; i < sizeof allowed / sizeof *allowed; i++)
        if (strlen(allowed[i]) == n && strncmp(name, allowed[i], n) == 0) return 1;
    snprintf(why, why_size, "includes %.*s", (int)n, name);
    return 0;
}

static int scan_file(const char *path, const char *dir, const char *root, int *files)
{
    FILE *f = fopen(path, "r");
    if (!f) return 1;
    (*files)++;
    char line[512], why[600];
    int lineno = 0, bad = 0;
    while (fgets(line, sizeof line, f)) {
        lineno++;
        line[strcspn(line, "\r\n")] = '\0';
        if (!include_allowed(line, dir, root, why, sizeof why)) {
            printf("firmware rule broken: %s:%d: %s\n", path, lineno, why);
            bad++;
        }
    }
    fclose(f);
    return bad;
}

static int scan_dir(const char *dir, const char *root, int *files)
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
        if (S_ISDIR(st.st_mode)) bad += scan_dir(path, root, files);
        else if (len > 2 && (strcmp(e->d_name + len - 2, ".c") == 0 ||
                             strcmp(e->d_name + len - 2, ".h") == 0))
            bad += scan_file(path, dir, root, files);
    }
    closedir(d);
    return bad;
}

static const char *source_dir(void)
{
    const char *src = getenv("CUB_SOURCE_DIR");
    if (!src) {
        print_message("CUB_SOURCE_DIR not set: run through ctest\n");
        fail();
    }
    return src;
}

static void test_checker_flags_os_and_io_headers(void **s)
{
    char why[600], dir[1024], root[1024];
    snprintf(dir, sizeof dir, "%s/firmware/track", source_dir());
    snprintf(root, sizeof root, "%s/firmware/include", source_dir());
    assert_false(include_allowed("#include <stdio.h>", dir, root, why, sizeof why));
    assert_false(include_allowed("  #  include <stdlib.h>", dir, root, why, sizeof why));
    assert_false(include_allowed("#include <math.h>", dir, root, why, sizeof why));
    assert_false(include_allowed("#include <sys/time.h>", dir, root, why, sizeof why));
    assert_false(include_allowed("#include \"stdio.h\"", dir, root, why, sizeof why));
    assert_false(include_allowed("#include \"cub/stdio.h\"", dir, root, why, sizeof why));
    assert_false(include_allowed("#include \"../app/include/cub/io.h\"", dir, root, why,
                                 sizeof why));
    assert_true(include_allowed("#include <stdint.h>", dir, root, why, sizeof why));
    assert_true(include_allowed("#include \"cub/fx.h\"", dir, root, why, sizeof why));
    assert_true(include_allowed("#include \"depth_table.h\"", dir, root, why, sizeof why));
}

static void test_firmware_includes_only_freestanding_headers(void **s)
{
    char dir[1024], root[1024];
    snprintf(dir, sizeof dir, "%s/firmware", source_dir());
    snprintf(root, sizeof root, "%s/firmware/include", source_dir());
    int files = 0;
    int bad = scan_dir(dir, root, &files);
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

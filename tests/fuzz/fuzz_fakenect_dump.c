/* libFuzzer target: the fakenect dump check (board/common/fakenect_dump.c)
 * reading any INDEX.txt. The input is the index; the dump folder beside it
 * holds a good depth frame, a short one, accelerometer files (12 bytes,
 * 16, and empty), a short colour frame and a sub-folder, so the index can name good, bad, missing
 * and odd files. Whatever the index, prepare + release must neither crash
 * nor leave a view behind, and FAKENECT_PATH must name the dump again. */
#define _POSIX_C_SOURCE 200809L /* setenv, mkdir */

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <dirent.h>
#include <unistd.h>

#include "fakenect_dump.h"

static char dump_dir[256], tmp_dir[256];

static void write_file(const char *dir, const char *name, const void *data, size_t n)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(data, 1, n, f) != n) abort();
    fclose(f);
}

static void make_dump(void)
{
    /* In the working folder (ctest's: the build tree), reused run to run. */
    char cwd[160];
    if (!getcwd(cwd, sizeof cwd)) abort();
    snprintf(dump_dir, sizeof dump_dir, "%s/fuzz_fakenect_dump.dump", cwd);
    snprintf(tmp_dir, sizeof tmp_dir, "%s.tmp", dump_dir);
    mkdir(dump_dir, 0700);
    mkdir(tmp_dir, 0700);
    static const char head[] = "P5 640 480 65535\n";
    size_t n = sizeof head - 1 + 640 * 480 * 2;
    unsigned char *frame = calloc(1, n);
    if (!frame) abort();
    memcpy(frame, head, sizeof head - 1);
    write_file(dump_dir, "d-good.pgm", frame, n);
    write_file(dump_dir, "d-short.pgm", frame, 20);
    write_file(dump_dir, "a-1.dump", frame, 16);
    write_file(dump_dir, "a-12.dump", frame + 20, 12); /* freenect_raw_tilt_state's size */
    write_file(dump_dir, "a-empty.dump", frame, 0);
    write_file(dump_dir, "r-short.ppm", "P6 640 480 255\n", 15);
    free(frame);
    char sub[512];
    snprintf(sub, sizeof sub, "%s/sub", dump_dir);
    mkdir(sub, 0700);
    setenv("TMPDIR", tmp_dir, 1);
}

static int dir_is_empty(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return 0;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)))
        n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
    closedir(d);
    return n == 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!dump_dir[0]) make_dump();
    write_file(dump_dir, "INDEX.txt", data, size);
    setenv("FAKENECT_PATH", dump_dir, 1);
    cub_fakenect_view v;
    memset(&v, 0, sizeof v);
    char err[512];
    (void)cub_fakenect_dump_prepare(&v, err, sizeof err);
    cub_fakenect_dump_release(&v);
    const char *p = getenv("FAKENECT_PATH");
    if (!p || strcmp(p, dump_dir) != 0) abort();
    if (!dir_is_empty(tmp_dir)) abort();
    return 0;
}

/* The fuzz dump builder (fuzz_dump_build.h). */
#define _GNU_SOURCE /* setenv, strndup, strtok_r */

#include "fuzz_dump_build.h"

#include <dirent.h>
#include <libfreenect.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define DEPTH_BYTES (640 * 480 * 2)
#define RGB_BYTES (640 * 480 * 3)
#define MAX_FILES 16

static char dump_dir[256], tmp_dir[256];
static unsigned char *good_depth, *good_rgb;

typedef struct stream {
    const uint8_t *p;
    size_t n;
} stream;

static unsigned next(stream *s)
{
    if (!s->n) return 0;
    s->n--;
    return *s->p++;
}

static void write_file(const char *name, const void *bytes, size_t n)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dump_dir, name);
    FILE *f = fopen(path, "wb");
    if (!f) return; /* a name the file system refuses stays missing */
    if (n && fwrite(bytes, 1, n, f) != n) abort();
    fclose(f);
}

static void remove_tree(const char *dir, int keep_top)
{
    DIR *d = opendir(dir);
    if (!d) return;
    struct dirent *e;
    char path[1024];
    while ((e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        struct stat st;
        if (lstat(path, &st) == 0 && S_ISDIR(st.st_mode))
            remove_tree(path, 0);
        else
            unlink(path);
    }
    closedir(d);
    if (!keep_top) rmdir(dir);
}

/* The dump and the TMPDIR beside it go when the fuzzer ends. */
static void remove_dump(void)
{
    remove_tree(dump_dir, 0);
    remove_tree(tmp_dir, 0);
}

static void setup_once(const char *tag)
{
    char cwd[160];
    if (!getcwd(cwd, sizeof cwd)) abort();
    snprintf(dump_dir, sizeof dump_dir, "%s/%s.%d.dump", cwd, tag, (int)getpid());
    snprintf(tmp_dir, sizeof tmp_dir, "%s.tmp", dump_dir);
    mkdir(dump_dir, 0700);
    mkdir(tmp_dir, 0700);
    setenv("TMPDIR", tmp_dir, 1);
    atexit(remove_dump);
    static const char dh[] = "P5 640 480 65535\n", rh[] = "P6 640 480 255\n";
    good_depth = calloc(1, sizeof dh - 1 + DEPTH_BYTES);
    good_rgb = calloc(1, sizeof rh - 1 + RGB_BYTES);
    if (!good_depth || !good_rgb) abort();
    memcpy(good_depth, dh, sizeof dh - 1);
    memcpy(good_rgb, rh, sizeof rh - 1);
}

/* The bytes a name's letter expects. */
static const unsigned char *expected(const char *name, size_t *n)
{
    static const unsigned char accel[16] = {0, 1, 2, 3, 4, 5, 6, 0};
    switch (name[0]) {
    case 'd': *n = 17 + DEPTH_BYTES; return good_depth;
    case 'r': *n = 15 + RGB_BYTES; return good_rgb;
    case 'a': *n = sizeof(freenect_raw_tilt_state); return accel;
    default: *n = 16; return accel;
    }
}

static void make_file(const char *name, stream *s)
{
    size_t n;
    const unsigned char *full = expected(name, &n);
    unsigned c = next(s) & 7;
    if (c == 0) {
        write_file(name, full, n);
    } else if (c == 2) {
        size_t len = next(s);
        len |= (size_t)next(s) << 8;
        write_file(name, full, len < n ? len : n);
    } else if (c == 3) {
        size_t len = next(s);
        len = len < s->n ? len : s->n;
        write_file(name, s->p, len);
        s->p += len, s->n -= len;
    } else if (c == 4) {
        write_file(name, "", 0);
    } else if (c == 5) {
        char path[512];
        snprintf(path, sizeof path, "%s/%s", dump_dir, name);
        mkdir(path, 0700);
    } else if (c == 6) {
        unsigned char *b = malloc(64 + DEPTH_BYTES);
        if (!b) abort();
        size_t h = 0;
        while (h < 64 && s->n) {
            b[h] = (unsigned char)next(s);
            if (b[h++] == '\n') break;
        }
        memset(b + h, 0, DEPTH_BYTES);
        write_file(name, b, h + DEPTH_BYTES);
        free(b);
    } else if (c == 7) {
        size_t more = 1000 * (size_t)next(s);
        unsigned char *b = calloc(1, n + more);
        if (!b) abort();
        memcpy(b, full, n);
        write_file(name, b, n + more);
        free(b);
    } /* 1: missing */
}

/* A name fakenect would open under the dump: nothing outside it. */
static int plain_name(const char *name)
{
    return name[0] && strlen(name) < 100 && !strchr(name, '/') && strcmp(name, ".") &&
           strcmp(name, "..") && strcmp(name, "INDEX.txt");
}

int cub_fuzz_dump_make(const uint8_t *data, size_t size)
{
    remove_tree(dump_dir, 1);
    size_t len = size >= 2 ? (size_t)data[0] | (size_t)data[1] << 8 : 0;
    data += size >= 2 ? 2 : size;
    size -= size >= 2 ? 2 : size;
    len = len < size ? len : size;
    write_file("INDEX.txt", data, len);
    stream s = {data + len, size - len};
    char *text = strndup((const char *)data, len), *save = NULL;
    if (!text) abort();
    int files = 0, lines = 0;
    for (char *ln = strtok_r(text, "\n", &save); ln; ln = strtok_r(NULL, "\n", &save)) {
        lines++;
        if (files < MAX_FILES && plain_name(ln)) {
            char path[512];
            struct stat st;
            snprintf(path, sizeof path, "%s/%s", dump_dir, ln);
            if (lstat(path, &st) != 0) make_file(ln, &s), files++;
        }
    }
    free(text);
    return lines;
}

const char *cub_fuzz_dump_dir(const char *tag)
{
    if (!dump_dir[0]) setup_once(tag);
    return dump_dir;
}

const char *cub_fuzz_dump_tmp(void)
{
    return tmp_dir;
}

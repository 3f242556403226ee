/* BVH import and export speed on the largest BVH file of the shared data
 * (or the file given as argv[1]). Prints figures; fails only if the file
 * cannot be read:
 *   bench_bvh: cmu/14_14.bvh 3.3 MB import 40.1 MB/s export 20.3 MB/s */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cub/io.h"

#define RUNS 5

static void find_largest(const char *dir, char *best, size_t size, off_t *best_size)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    if (!d)
        return;
    while ((e = readdir(d))) {
        char path[1024];
        struct stat st;
        size_t n = strlen(e->d_name);
        if (e->d_name[0] == '.')
            continue;
        snprintf(path, sizeof(path), "%s/%s", dir, e->d_name);
        if (stat(path, &st) != 0)
            continue;
        if (S_ISDIR(st.st_mode))
            find_largest(path, best, size, best_size);
        else if (n > 4 && strcmp(e->d_name + n - 4, ".bvh") == 0 && st.st_size > *best_size) {
            *best_size = st.st_size;
            snprintf(best, size, "%s", path);
        }
    }
    closedir(d);
}

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + t.tv_nsec * 1e-9;
}

int main(int argc, char **argv)
{
    char path[1024] = "", out[1100], msg[600];
    const char *data = getenv("CUB_DATA_DIR"), *build = getenv("CUB_BUILD_DIR");
    off_t size = 0;
    if (argc > 1) {
        snprintf(path, sizeof(path), "%s", argv[1]);
    } else if (data) {
        char dir[1024];
        snprintf(dir, sizeof(dir), "%s/mocap", data);
        find_largest(dir, path, sizeof(path), &size);
    }
    if (!path[0]) {
        printf("bench_bvh: no BVH file (set CUB_DATA_DIR or pass a file): skipped\n");
        return 0;
    }
    char *text = NULL;
    size_t len = 0;
    cub_diag d;
    if (cub_text_read(&(cub_text_src){path, NULL, 0}, &text, &len, &d)) {
        fprintf(stderr, "bench_bvh: %s\n", cub_diag_str(&d, msg, sizeof(msg)));
        return 1;
    }
    cub_io_motion m;
    double best_in = 1e9, best_out = 1e9, mb = len / 1048576.0;
    for (int r = 0; r < RUNS; r++) {
        double t0 = now_s();
        if (cub_io_parse_bvh(text, len, path, NULL, &m, &d)) {
            fprintf(stderr, "bench_bvh: %s\n", cub_diag_str(&d, msg, sizeof(msg)));
            return 1;
        }
        double t1 = now_s();
        best_in = t1 - t0 < best_in ? t1 - t0 : best_in;
        if (r + 1 < RUNS)
            cub_io_motion_free(&m);
    }
    snprintf(out, sizeof(out), "%s/bench_bvh_%ld.bvh", build ? build : "/tmp", (long)getpid());
    for (int r = 0; r < RUNS; r++) {
        double t0 = now_s();
        if (cub_io_save_bvh(out, &m, &d)) {
            fprintf(stderr, "bench_bvh: %s\n", cub_diag_str(&d, msg, sizeof(msg)));
            return 1;
        }
        double t1 = now_s();
        best_out = t1 - t0 < best_out ? t1 - t0 : best_out;
    }
    struct stat st;
    double out_mb = stat(out, &st) == 0 ? st.st_size / 1048576.0 : 0;
    remove(out);
    const char *shown = strstr(path, "/mocap/") ? strstr(path, "/mocap/") + 7 : path;
    printf("bench_bvh: %s %.1f MB import %.1f MB/s (%d frames x %d joints, best of %d)\n", shown,
           mb, mb / best_in, m.clip.frame_count, m.skel.joint_count, RUNS);
    printf("bench_bvh: %s export %.1f MB at %.1f MB/s\n", shown, out_mb, out_mb / best_out);
    cub_io_motion_free(&m);
    free(text);
    return 0;
}

/* The seed's codec (cub/codec.h) on the bear's library: decode time per
 * pose for the box's way (Squad with the stream's IK flags) and without IK,
 * and encode time per clip. The best of RUNS runs (the machine is shared).
 * Prints figures; fails only if the library cannot be read or coded:
 *   bench_codec: bear library 23 clips 2233 poses: decode squad+IK 12.3 us/pose ... */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "cub/codec.h"
#include "cub/pack.h"

#define RUNS 5

typedef struct coded {
    uint8_t *data;
    size_t len, mem_size;
} coded;

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + t.tv_nsec * 1e-9;
}

static int encode_all(const cub_library *lib, coded *out)
{
    for (int i = 0; i < lib->clip_count; i++) {
        const cub_clip *c = &lib->clips[i].clip;
        int eff[CUB_CODEC_MAX_EFFECTORS];
        int ne = cub_codec_pick_effectors(c->skel, eff, CUB_CODEC_MAX_EFFECTORS);
        size_t cap = cub_codec_encoded_max(c, ne), work_size = cub_codec_encode_work_size(c, ne);
        void *work = malloc(work_size);
        out[i].data = malloc(cap);
        cub_codec_enc in = {c, eff, ne, work, work_size};
        cub_codec_info info;
        if (!work || !out[i].data || cub_codec_encode(&in, out[i].data, cap, &out[i].len) ||
            cub_codec_peek(out[i].data, out[i].len, &info, NULL))
            return -1;
        out[i].mem_size = info.mem_size;
        free(work);
    }
    return 0;
}

/* Seconds for one decode of every clip, the best of RUNS. */
static double decode_all(const coded *s, int n, cub_codec_opts o, void *mem)
{
    static cub_skeleton skel;
    cub_clip clip;
    double best = 1e30;
    for (int r = 0; r < RUNS; r++) {
        double t0 = now_s();
        for (int i = 0; i < n; i++) {
            cub_codec_out out = {&skel, &clip, mem, s[i].mem_size};
            if (cub_codec_decode(s[i].data, s[i].len, &o, &out, NULL)) return -1;
        }
        double t = now_s() - t0;
        best = t < best ? t : best;
    }
    return best;
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : CUB_ASSETS_DIR "/clips/bear.cubclips";
    cub_library lib;
    cub_diag d = {0};
    if (cub_pack_read(path, &lib, &d)) {
        fprintf(stderr, "bench_codec: %s: %s\n", path, d.msg);
        return 1;
    }
    coded *s = calloc((size_t)lib.clip_count, sizeof *s);
    double t0 = now_s();
    if (!s || encode_all(&lib, s)) {
        fprintf(stderr, "bench_codec: %s: encoding failed\n", path);
        return 1;
    }
    double enc = now_s() - t0;
    size_t biggest = 0;
    long poses = 0;
    for (int i = 0; i < lib.clip_count; i++) {
        biggest = s[i].mem_size > biggest ? s[i].mem_size : biggest;
        poses += lib.clips[i].clip.frame_count;
    }
    void *mem = malloc(biggest);
    double ik = decode_all(s, lib.clip_count, (cub_codec_opts){CUB_CODEC_SQUAD, CUB_CODEC_IK_STREAM}, mem);
    double no_ik = decode_all(s, lib.clip_count, (cub_codec_opts){CUB_CODEC_SQUAD, CUB_CODEC_IK_OFF}, mem);
    if (ik < 0 || no_ik < 0) {
        fprintf(stderr, "bench_codec: %s: a stream did not decode\n", path);
        return 1;
    }
    printf("bench_codec: bear library %d clips %ld poses: decode squad+IK %.1f us/pose, "
           "squad without IK %.1f us/pose; encode %.1f ms per clip\n",
           lib.clip_count, poses, 1e6 * ik / (double)poses, 1e6 * no_ik / (double)poses,
           1e3 * enc / lib.clip_count);
    for (int i = 0; i < lib.clip_count; i++)
        free(s[i].data);
    free(s);
    free(mem);
    cub_library_free(&lib);
    return 0;
}

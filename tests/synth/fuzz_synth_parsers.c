/* libFuzzer target for the depth synthesizer's text parsers (app/synth).
 * Input: byte 0 picks the parser, the rest is the text (not NUL-terminated:
 * the parsers must stay inside it).
 *   'T': truth.txt (cub_synth_truth_parse)
 *   'J': a joint track (cub_synth_jtrack_parse)
 *   anything else (e.g. 'S'): a sequence file (cub_synth_sequence_parse)
 * Whatever the input: no crash, hang or overread; a failure names the
 * file and says why; a success holds what the format promises. Built by
 * tests/fuzz with -DCUB_FUZZ=ON (see the report of the change for the
 * CMake lines). Seeds: seeds_synth/ (tests/fuzz/make_seeds.py). */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cub/synth.h"
#include "../fuzz/fuzz_tally.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check_truth(const char *text, size_t len)
{
    cub_synth_truth t;
    cub_diag d;
    int ok = cub_synth_truth_parse(text, len, "fuzz.txt", &t, &d) == CUB_OK;
    cub_fuzz_tally("fuzz_synth_parsers", ok);
    if (!ok) {
        if (!d.msg[0] || strcmp(d.file, "fuzz.txt") != 0) abort();
        return;
    }
    for (int i = 0; i < t.frame_count; i++) {
        if (i > 0 && t.frames[i].frame <= t.frames[i - 1].frame) abort();
        for (int j = 0; j < CUB_KJ_COUNT; j++)
            if (t.frames[i].visible[j] > 1 || !isfinite(t.frames[i].joint_mm[j][2])) abort();
    }
    cub_synth_truth_free(&t);
}

static void check_sequence(const char *text, size_t len)
{
    cub_synth_segment *s;
    int n;
    cub_diag d;
    int ok = cub_synth_sequence_parse(text, len, "fuzz.seq", &s, &n, &d) == CUB_OK;
    cub_fuzz_tally("fuzz_synth_parsers", ok);
    if (!ok) {
        if (!d.msg[0] || s || n) abort();
        return;
    }
    for (int i = 0; i < n; i++)
        if (!s[i].clip[0] || s[i].from_s < 0 || (s[i].to_s != 0 && s[i].to_s <= s[i].from_s) ||
            s[i].mirror > 1)
            abort();
    free(s);
}

static void check_jtrack(const char *text, size_t len)
{
    cub_synth_jtrack t;
    cub_diag d;
    int ok = cub_synth_jtrack_parse(text, len, "fuzz.jtrack", &t, &d) == CUB_OK;
    cub_fuzz_tally("fuzz_synth_parsers", ok);
    if (!ok) {
        if (!d.msg[0] || t.points_mm || t.frame_count) abort();
        return;
    }
    if (t.frame_count < 1 || !(t.fps > 0) || !(t.unit_mm > 0)) abort();
    for (size_t k = 0; k < (size_t)t.frame_count * CUB_SYNTH_JTRACK_POINTS * 3; k++)
        if (!isfinite(t.points_mm[k])) abort();
    cub_synth_jtrack_free(&t);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1) return 0;
    /* A copy of exactly the input's size, so ASan sees any overread. */
    char *text = malloc(size - 1 ? size - 1 : 1);
    if (!text) return 0;
    memcpy(text, data + 1, size - 1);
    if (data[0] == 'T')
        check_truth(text, size - 1);
    else if (data[0] == 'J')
        check_jtrack(text, size - 1);
    else
        check_sequence(text, size - 1);
    free(text);
    return 0;
}

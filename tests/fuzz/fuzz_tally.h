/* How many inputs a fuzz target ran and how many took its success path
 * (the parser accepted them), for the coverage note: with CUB_FUZZ_TALLY
 * set to a file, one line "<target> <ok> of <runs> inputs accepted" is
 * appended to it at exit. Off (a counter only) otherwise. */
#ifndef CUB_FUZZ_TALLY_H
#define CUB_FUZZ_TALLY_H

#include <stdio.h>
#include <stdlib.h>

static unsigned long cub_fuzz_runs, cub_fuzz_ok;
static const char *cub_fuzz_name = "fuzz";

static void cub_fuzz_tally_write(void)
{
    const char *path = getenv("CUB_FUZZ_TALLY");
    FILE *f = path ? fopen(path, "a") : NULL;
    if (!f) return;
    fprintf(f, "%s %lu of %lu inputs accepted\n", cub_fuzz_name, cub_fuzz_ok, cub_fuzz_runs);
    fclose(f);
}

/* Once per input: ok when it took the success path. */
static inline void cub_fuzz_tally(const char *name, int ok)
{
    if (!cub_fuzz_runs++) {
        cub_fuzz_name = name;
        atexit(cub_fuzz_tally_write);
    }
    cub_fuzz_ok += ok != 0;
}

#endif

/* For the fuzz targets that read their input from a file, as cubtool reads
 * it (so the bounded file reader runs too): one temporary file per process,
 * named after the target, rewritten for each input. */
#ifndef CUB_FUZZ_FILE_H
#define CUB_FUZZ_FILE_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

/* Writes the input to "TARGET.PID.EXT" in the working directory and returns
 * that path (valid until the next call). */
static inline const char *cub_fuzz_file(const char *target, const char *ext, const uint8_t *data,
                                        size_t size)
{
    static char path[96];
    if (!path[0]) snprintf(path, sizeof path, "%s.%d.%s", target, (int)getpid(), ext);
    FILE *f = fopen(path, "wb");
    if (!f || (size && fwrite(data, 1, size, f) != size)) abort();
    fclose(f);
    return path;
}

#endif

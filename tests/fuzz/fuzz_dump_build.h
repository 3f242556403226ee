/* A fakenect dump built from fuzz input, shared by fuzz_fakenect_dump and
 * fuzz_track_dump. Input: two bytes (little-endian) give the length of
 * INDEX.txt, which follows; the rest is a stream that makes the files
 * INDEX.txt names, one control byte each (then what the control byte asks
 * for):
 *   0 what the name's letter expects: d- a full depth frame, r- a full
 *     colour frame, a- a 12-byte accelerometer reading, else 16 bytes
 *   1 missing           2 truncated to the next 2 bytes (LE) of length
 *   3 the next byte's count of raw stream bytes   4 empty
 *   5 a directory       6 a full depth frame under a header from the
 *     stream (to '\n', 64 at most)   7 a full frame and N*1000 bytes more
 * Past the stream every name gets 0; 16 files at most. The dump is built
 * afresh per input in the working folder (tests/fuzz/make_seeds.py writes
 * seeds in this form). */
#ifndef CUB_FUZZ_DUMP_BUILD_H
#define CUB_FUZZ_DUMP_BUILD_H

#include <stddef.h>
#include <stdint.h>

/* The dump's folder and a private TMPDIR beside it (set in the
 * environment), made at the first call; tag names them. */
const char *cub_fuzz_dump_dir(const char *tag);
const char *cub_fuzz_dump_tmp(void);
/* Empty the dump and build it from the input; the count of INDEX.txt lines. */
int cub_fuzz_dump_make(const uint8_t *data, size_t size);

#endif

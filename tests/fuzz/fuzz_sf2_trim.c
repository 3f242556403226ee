/* libFuzzer target for the music module's readers (app/music/sf2_trim.h).
 * Byte 0 picks: 'M' the presets of a MIDI file (cub_midi_presets), any
 * other byte a SoundFont 2 file cut to one preset: bank 128 if bit 7 of
 * byte 0 is set, else 0; program byte 0 & 127.
 * Whatever the input: no crash, hang or overread; a failure names the file;
 * a cut file is one the reader accepts again, and cutting it again to the
 * same presets gives the same bytes. */
#define _POSIX_C_SOURCE 200809L /* fmemopen */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sf2_trim.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static cub_err trim(const uint8_t *file, size_t len, const cub_sf2_presets *want, uint8_t **out,
                    size_t *out_len)
{
    FILE *f = fmemopen((void *)file, len, "rb");
    if (!f) return CUB_ERR_IO;
    cub_diag d = {0};
    cub_err e = cub_sf2_trim(f, "fuzz.sf2", want, out, out_len, &d);
    fclose(f);
    if (e && strcmp(d.file, "fuzz.sf2") != 0) abort();
    return e;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1) return 0;
    if (data[0] == 'M') {
        cub_sf2_presets p;
        cub_err e = cub_midi_presets(data + 1, size - 1, &p);
        if (!e && (p.count < 0 || p.count > CUB_SF2_MAX_PRESETS)) abort();
        return 0;
    }
    if (size < 2) return 0;
    cub_sf2_presets want = {0};
    cub_sf2_presets_add(&want, data[0] & 0x80 ? 128 : 0, data[0] & 127);
    uint8_t *a = NULL, *b = NULL;
    size_t na = 0, nb = 0;
    if (trim(data + 1, size - 1, &want, &a, &na) == CUB_OK) {
        if (trim(a, na, &want, &b, &nb) != CUB_OK || nb != na || memcmp(a, b, na) != 0) abort();
    }
    free(a);
    free(b);
    return 0;
}

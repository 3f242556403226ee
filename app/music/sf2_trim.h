/* sf2_trim — a SoundFont 2 cut down, in memory, to the presets one song
 * plays: those presets, their instruments, their samples (sample data copied
 * byte for byte with their loops and 46 guard points), every generator and
 * modulator in the original order. FluidSynth loads every preset of a
 * SoundFont it is given: for the General MIDI set (TimGM6mb, 136 presets)
 * that is 5.8 MB of samples and 2063 instrument zones (about 4 MB), when a
 * song uses two presets. Private to the music module.
 *
 * The file is read through a FILE * (header, the preset data, then only the
 * sample ranges wanted), never whole. Anything this reader does not
 * understand or cannot cut exactly — a malformed chunk or index, 24-bit or
 * ROM samples, a wanted preset the file lacks — is an error with a cub_diag
 * naming the file and the chunk: the caller then gives FluidSynth the whole
 * file, as before. */
#ifndef CUB_MUSIC_SF2_TRIM_H
#define CUB_MUSIC_SF2_TRIM_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "cub/err.h"
#include "cub/io.h"

#define CUB_SF2_MAX_PRESETS 64

/* The presets a song selects: bank (128 = percussion) and program. */
typedef struct cub_sf2_presets {
    int count;
    uint16_t bank[CUB_SF2_MAX_PRESETS];
    uint8_t program[CUB_SF2_MAX_PRESETS];
} cub_sf2_presets;

/* Add a preset once; CUB_ERR_FULL beyond CUB_SF2_MAX_PRESETS. */
cub_err cub_sf2_presets_add(cub_sf2_presets *p, int bank, int program);

/* Whether f is a SoundFont this reader can cut (the checks of cub_sf2_trim
 * but for the presets): CUB_OK, or the error cub_sf2_trim would give. */
cub_err cub_sf2_check(FILE *f, const char *name, cub_diag *diag);

/* The presets a standard MIDI file selects (cub_midi_scan must accept it):
 * per channel that plays notes, the program of each Program Change, and
 * program 0 when a note may sound before the first one (channel 10: bank
 * 128, percussion). CUB_ERR_UNSUPPORTED when the file can switch presets in
 * ways not followed here (Bank Select, SysEx): play the whole SoundFont. */
cub_err cub_midi_presets(const uint8_t *data, size_t len, cub_sf2_presets *out);

/* Write into *out (malloc'd, the caller frees) a SoundFont 2 holding only
 * the presets in want. f is the original, name its file name for the diag.
 * CUB_ERR_FORMAT for a malformed file, CUB_ERR_UNSUPPORTED for one this
 * reader will not cut (24-bit or ROM samples; a wanted preset missing, as
 * FluidSynth's fallback preset would then be missing too), CUB_ERR_NOMEM,
 * CUB_ERR_IO. */
cub_err cub_sf2_trim(FILE *f, const char *name, const cub_sf2_presets *want, uint8_t **out,
                     size_t *out_len, cub_diag *diag);

#endif

/* The MIDI scan's events, for readers built on it (midi_groove.c): the
 * scan checks the structure and walks every track in file order; a sink
 * sees each channel message and meta event as it passes. */
#ifndef CUB_MIDI_INTERNAL_H
#define CUB_MIDI_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "cub/music.h"

typedef struct cub_midi_sink {
    void *ctx;
    /* status 0x80..0xEF (running status resolved); data: its 1 or 2 bytes */
    void (*channel)(void *ctx, int track, int64_t tick, uint8_t status, const uint8_t *data);
    void (*meta)(void *ctx, int track, int64_t tick, uint8_t type, const uint8_t *data, uint32_t n);
} cub_midi_sink;

/* cub_midi_scan, telling sink (may be NULL) the events on the way. A sink
 * sees the events of a file that fails later too: use them only on CUB_OK. */
cub_err cub_midi_walk(const uint8_t *data, size_t len, const char *name, const cub_midi_sink *sink,
                      cub_midi_info *out, cub_diag *diag);

#endif

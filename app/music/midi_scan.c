/* midi_scan — check a standard MIDI file's structure and measure it before
 * FluidSynth plays it: FluidSynth's player reports a broken file only by
 * stopping, so the music module rejects it here with a byte offset, and the
 * song's length comes from the tempo map, exactly. */
#include <stdio.h>
#include <string.h>

#include "cub/music.h"
#include "midi_internal.h"
#include "sf2_trim.h"

#define MAX_TEMPOS 512
#define MAX_TICK ((int64_t)1 << 31)
#define DEFAULT_TEMPO_US 500000 /* 120 bpm until the first Set Tempo */

typedef struct scan {
    const uint8_t *p;
    size_t len, at; /* at: offset into p */
    const char *name;
    cub_diag *diag;
    int64_t tempo_tick[MAX_TEMPOS];
    uint32_t tempo_us[MAX_TEMPOS];
    int tempo_count;
    cub_midi_info *info;
    /* For cub_midi_presets: per channel, the first note's and first
     * Program Change's tick (-1: none), the programs set, and whether a
     * Bank Select or SysEx was seen. */
    int64_t first_note[16], first_program[16];
    uint8_t programs[16][16];
    int switches_banks;
    const cub_midi_sink *sink; /* may be NULL: only the scan */
    int track_index;
} scan;

static cub_err fail(scan *s, size_t at, const char *what)
{
    return cub_diag_fail(s->diag, CUB_ERR_FORMAT, s->name, 0, "byte %zu: %s", at, what);
}

static uint32_t be(const uint8_t *p, int n)
{
    uint32_t v = 0;
    for (int i = 0; i < n; i++)
        v = v << 8 | p[i];
    return v;
}

/* A variable-length quantity (at most 4 bytes) before end. */
static cub_err vlq(scan *s, size_t end, uint32_t *out)
{
    uint32_t v = 0;
    for (int i = 0; i < 4; i++) {
        if (s->at >= end) return fail(s, s->at, "a track ends inside a number");
        uint8_t b = s->p[s->at++];
        v = v << 7 | (b & 0x7F);
        if (!(b & 0x80)) {
            *out = v;
            return CUB_OK;
        }
    }
    return fail(s, s->at, "a variable-length number longer than 4 bytes");
}

static cub_err meta_event(scan *s, size_t end, int64_t tick, int *ended)
{
    if (s->at >= end) return fail(s, s->at, "a meta event without its type");
    uint8_t type = s->p[s->at++];
    uint32_t n = 0;
    cub_err e = vlq(s, end, &n);
    if (e) return e;
    if (n > end - s->at) return fail(s, s->at, "a meta event longer than its track");
    if (type == 0x51) {
        if (n != 3) return fail(s, s->at, "a Set Tempo event whose length is not 3");
        uint32_t us = be(s->p + s->at, 3);
        if (us == 0) return fail(s, s->at, "a tempo of 0 microseconds per quarter note");
        if (s->tempo_count == MAX_TEMPOS) return fail(s, s->at, "more than 512 tempo changes");
        s->tempo_tick[s->tempo_count] = tick;
        s->tempo_us[s->tempo_count++] = us;
    } else if (type == 0x2F) {
        *ended = 1;
    }
    if (s->sink && s->sink->meta)
        s->sink->meta(s->sink->ctx, s->track_index, tick, type, s->p + s->at, n);
    s->at += n;
    return CUB_OK;
}

static void note_presets(scan *s, uint8_t status, const uint8_t *data, int64_t tick)
{
    int ch = status & 0x0F;
    if ((status & 0xF0) == 0x90 && data[1] > 0 && s->first_note[ch] < 0) s->first_note[ch] = tick;
    if ((status & 0xF0) == 0xB0 && (data[0] == 0 || data[0] == 32)) s->switches_banks = 1;
    if ((status & 0xF0) == 0xC0) {
        s->programs[ch][data[0] >> 3] |= (uint8_t)(1u << (data[0] & 7));
        if (s->first_program[ch] < 0 || tick < s->first_program[ch]) s->first_program[ch] = tick;
    }
}

static cub_err track(scan *s, size_t end)
{
    int64_t tick = 0;
    int status = 0, ended = 0;
    while (!ended) {
        if (s->at >= end) return fail(s, s->at, "a track without End of Track");
        uint32_t delta = 0;
        cub_err e = vlq(s, end, &delta);
        if (e) return e;
        tick += delta;
        if (tick > MAX_TICK) return fail(s, s->at, "a track longer than 2^31 ticks");
        if (s->at >= end) return fail(s, s->at, "a track ends after a delta time");
        uint8_t b = s->p[s->at];
        if (b & 0x80) {
            s->at++;
        } else if (!status) {
            return fail(s, s->at, "a data byte with no running status");
        } else {
            b = (uint8_t)status;
        }
        if (b == 0xFF) {
            e = meta_event(s, end, tick, &ended);
        } else if (b == 0xF0 || b == 0xF7) {
            uint32_t n = 0;
            status = 0;
            e = vlq(s, end, &n);
            if (!e && n > end - s->at) e = fail(s, s->at, "a SysEx longer than its track");
            s->switches_banks = 1; /* a GS / XG part change could make any channel drums */
            if (!e) s->at += n;
        } else if (b >= 0xF0) {
            e = fail(s, s->at - 1, "a system message that does not belong in a file");
        } else {
            int n = (b & 0xF0) == 0xC0 || (b & 0xF0) == 0xD0 ? 1 : 2;
            status = b;
            if ((size_t)n > end - s->at) return fail(s, s->at, "a track ends inside an event");
            for (int i = 0; i < n; i++)
                if (s->p[s->at + (size_t)i] & 0x80)
                    return fail(s, s->at + (size_t)i, "a data byte above 127");
            if ((b & 0xF0) == 0x90 && s->p[s->at + 1] > 0) s->info->notes++;
            note_presets(s, b, s->p + s->at, tick);
            if (s->sink && s->sink->channel)
                s->sink->channel(s->sink->ctx, s->track_index, tick, b, s->p + s->at);
            s->at += (size_t)n;
        }
        if (e) return e;
    }
    if (tick > s->info->end_tick) s->info->end_tick = tick;
    return CUB_OK;
}

/* end_tick through the tempo map (tempo changes sorted by tick, stable). */
static int64_t length_us(scan *s)
{
    for (int i = 1; i < s->tempo_count; i++)
        for (int j = i; j > 0 && s->tempo_tick[j - 1] > s->tempo_tick[j]; j--) {
            int64_t t = s->tempo_tick[j];
            uint32_t u = s->tempo_us[j];
            s->tempo_tick[j] = s->tempo_tick[j - 1];
            s->tempo_us[j] = s->tempo_us[j - 1];
            s->tempo_tick[j - 1] = t;
            s->tempo_us[j - 1] = u;
        }
    int64_t sum = 0, tick = 0; /* sum of ticks × µs per quarter */
    uint32_t tempo = DEFAULT_TEMPO_US;
    for (int i = 0; i < s->tempo_count && s->tempo_tick[i] < s->info->end_tick; i++) {
        sum += (s->tempo_tick[i] - tick) * tempo;
        tick = s->tempo_tick[i];
        tempo = s->tempo_us[i];
    }
    sum += (s->info->end_tick - tick) * tempo;
    return sum / s->info->division;
}

static cub_err scan_file(scan *s, const uint8_t *data, size_t len, const char *name,
                         cub_midi_info *out, cub_diag *diag)
{
    cub_diag scratch;
    s->diag = diag ? diag : &scratch;
    s->name = name ? name : "(midi)";
    s->p = data;
    s->len = data ? len : 0;
    for (int ch = 0; ch < 16; ch++)
        s->first_note[ch] = s->first_program[ch] = -1;
    if (!out) return CUB_ERR_ARG;
    memset(out, 0, sizeof(*out));
    s->info = out;
    if (s->len < 14 || memcmp(data, "MThd", 4) != 0)
        return fail(s, 0, "not a standard MIDI file (no MThd header)");
    uint32_t hlen = be(data + 4, 4);
    if (hlen < 6 || hlen > s->len - 8) return fail(s, 4, "a header chunk of a bad length");
    out->format = (int)be(data + 8, 2);
    out->tracks = (int)be(data + 10, 2);
    out->division = (int)be(data + 12, 2);
    if (out->format > 1) return fail(s, 8, "MIDI format 2 is not supported (0 or 1)");
    if (out->tracks < 1 || (out->format == 0 && out->tracks != 1))
        return fail(s, 10, "a bad number of tracks");
    if (out->division == 0 || (out->division & 0x8000))
        return fail(s, 12, "SMPTE or zero timing (ticks per quarter note expected)");
    s->at = 8 + hlen;
    int found = 0;
    while (found < out->tracks) {
        if (s->len - s->at < 8) return fail(s, s->at, "fewer track chunks than the header says");
        uint32_t clen = be(data + s->at + 4, 4);
        int is_track = memcmp(data + s->at, "MTrk", 4) == 0;
        s->at += 8;
        if (clen > s->len - s->at) return fail(s, s->at - 4, "a chunk longer than the file");
        size_t end = s->at + clen;
        if (is_track) {
            s->track_index = found;
            cub_err e = track(s, end);
            if (e) return e;
            found++;
        }
        s->at = end; /* unknown chunks are skipped, as the standard says */
    }
    out->tempo_changes = s->tempo_count;
    out->length_us = length_us(s);
    return CUB_OK;
}

cub_err cub_midi_scan(const uint8_t *data, size_t len, const char *name, cub_midi_info *out,
                      cub_diag *diag)
{
    scan s;
    memset(&s, 0, sizeof(s));
    return scan_file(&s, data, len, name, out, diag);
}

cub_err cub_midi_walk(const uint8_t *data, size_t len, const char *name, const cub_midi_sink *sink,
                      cub_midi_info *out, cub_diag *diag)
{
    scan s;
    memset(&s, 0, sizeof(s));
    s.sink = sink;
    return scan_file(&s, data, len, name, out, diag);
}

cub_err cub_midi_presets(const uint8_t *data, size_t len, cub_sf2_presets *out)
{
    scan s;
    cub_midi_info info;
    if (!out) return CUB_ERR_ARG;
    memset(out, 0, sizeof(*out));
    memset(&s, 0, sizeof(s));
    cub_err e = scan_file(&s, data, len, NULL, &info, NULL);
    if (e) return e;
    if (s.switches_banks) return CUB_ERR_UNSUPPORTED;
    for (int ch = 0; ch < 16 && !e; ch++) {
        if (s.first_note[ch] < 0) continue; /* silent: its presets never sound */
        int bank = ch == 9 ? 128 : 0;
        /* The program FluidSynth starts a channel on, when a note may come
         * first (ties too: tracks at one tick play in an order not ours). */
        if (s.first_program[ch] < 0 || s.first_note[ch] <= s.first_program[ch])
            e = cub_sf2_presets_add(out, bank, 0);
        for (int pg = 0; pg < 128 && !e; pg++)
            if (s.programs[ch][pg >> 3] & (1u << (pg & 7))) e = cub_sf2_presets_add(out, bank, pg);
    }
    return e == CUB_ERR_FULL ? CUB_ERR_UNSUPPORTED : e;
}

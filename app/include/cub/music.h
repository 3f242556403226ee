/* music — a song's MIDI file played by FluidSynth with a General MIDI
 * SoundFont (Debian timgm6mb-soundfont), rendered as interleaved stereo
 * int16 PCM into the caller's buffer: the board's audio fill callback
 * (cub_board_audio_start) calls cub_music_render, or passes cub_music_fill
 * itself. The music clock is the audio: frames rendered since play / rate,
 * in exact integer microseconds. Nothing renders faster or slower; the coach
 * follows this clock (SEEDS.md § 000, "Music sync").
 *
 *   cub_music *m;
 *   cub_music_open(&(cub_music_desc){0}, &m, &diag);      // default SoundFont, 44.1 kHz
 *   cub_music_load(m, "assets/songs/twinkle.mid", &diag);
 *   cub_music_play(m);
 *   cub_board_audio_start(board, cub_music_fill, m);       // audio thread renders
 *   ... t_us = cub_music_clock_us(m);                      // main loop reads the clock
 *   cub_music_close(m);
 *
 * Threads: render (audio thread) and load / play / stop / clock (main
 * thread) may run at once; a mutex orders them, the clock is atomic.
 * Errors (missing SoundFont, a file that is not a MIDI file) are cub_err
 * plus a cub_diag naming the file; FluidSynth's own log is captured, not
 * printed. */
#ifndef CUB_MUSIC_H
#define CUB_MUSIC_H

#include <stdint.h>

#include "cub/err.h"
#include "cub/groove.h"
#include "cub/io.h"

#define CUB_MUSIC_SOUNDFONT "/usr/share/sounds/sf2/TimGM6mb.sf2"

typedef struct cub_music_desc {
    const char *soundfont; /* NULL = CUB_MUSIC_SOUNDFONT */
    int rate;              /* frames per second; 0 = 44100 (the board's default) */
    int gain_permille;     /* FluidSynth's master gain ×1000; 0 = 800 (peaks near -6 dBFS) */
} cub_music_desc;

typedef struct cub_music cub_music; /* opaque */

/* Open a synthesiser with the SoundFont. CUB_ERR_IO when the SoundFont
 * cannot be read, CUB_ERR_FORMAT when FluidSynth rejects it. */
cub_err cub_music_open(const cub_music_desc *desc, cub_music **out, cub_diag *diag);
/* Stop and free; NULL is fine. */
void cub_music_close(cub_music *m);

/* Stop whatever plays and load a standard MIDI file (format 0 or 1, PPQ
 * timing). The file is checked first — chunks, events, lengths — so a bad
 * file is CUB_ERR_FORMAT with the byte offset, not a silent player. The
 * SoundFont's samples are loaded here, cut to the presets the song uses
 * (app/music/sf2_trim.c): a SoundFont that FluidSynth rejects fails here
 * (CUB_ERR_FORMAT, naming it), after cub_music_open checked its shape. */
cub_err cub_music_load(cub_music *m, const char *midi_path, cub_diag *diag);
/* Start the loaded song from its beginning; the clock restarts at 0.
 * CUB_ERR_EMPTY when nothing is loaded. */
cub_err cub_music_play(cub_music *m);
/* Stop playing (all notes off); the clock stops where it is. */
void cub_music_stop(cub_music *m);
/* Hold the song where it is (paused = 1: silence, the clock stands still)
 * or go on from there (0). Nothing happens when nothing plays. */
void cub_music_pause(cub_music *m, int paused);

/* Render `frames` frames of interleaved stereo int16 into stereo[2*frames].
 * Silence when not playing. While playing the clock advances by exactly
 * `frames`, also after the song's end (its last notes ring out). */
void cub_music_render(cub_music *m, int16_t *stereo, int frames);
/* The same with the board's cub_audio_fill signature (user = the music). */
void cub_music_fill(void *user, int16_t *stereo, int frames);

/* The music clock: frames rendered since play × 1e6 / rate, µs (floored),
 * times the clock scale. Safe from any thread. Subtract the audio
 * device's output latency for what is being heard. */
int64_t cub_music_clock_us(const cub_music *m);
/* Frames rendered since play. */
uint64_t cub_music_frames(const cub_music *m);
/* The loaded song's length, µs, from its tempo map: the time of its last
 * event (End of Track). 0 when nothing is loaded. */
int64_t cub_music_length_us(const cub_music *m);
/* 1 from play until FluidSynth's player passes the song's last tick (its
 * last notes may still ring on for a while), or stop. */
int cub_music_playing(const cub_music *m);
int cub_music_rate(const cub_music *m);

/* For tests: make the clock report `scale` × the true time (0.5..2; e.g.
 * 0.95 or 1.05), which simulates an audio device whose clock drifts 5 %
 * slow or fast against the board's. CUB_ERR_ARG outside the range. */
cub_err cub_music_set_clock_scale(cub_music *m, double scale);

/* A MIDI file's shape, as cub_music_load checks it (no FluidSynth needed). */
typedef struct cub_midi_info {
    int format; /* 0 or 1 */
    int tracks;
    int division;      /* ticks per quarter note */
    int64_t end_tick;  /* the latest End of Track over all tracks */
    int64_t length_us; /* end_tick through the tempo map */
    int notes;         /* note-on events with velocity > 0 */
    int tempo_changes;
} cub_midi_info;
cub_err cub_midi_scan(const uint8_t *data, size_t len, const char *name, cub_midi_info *out,
                      cub_diag *diag);

/* A MIDI file's notes for the groove module (seed 001): every note-on
 * paired with a note-off (per track, channel and pitch, a note-off ends
 * every note of its key that started before it, as FluidSynth does; so
 * repeated same-pitch notes stay separate, and a note-off and a note-on at
 * one tick, in either order, are both kept), the tempo map and the time
 * signatures, sorted
 * as cub_groove_song asks. A bad file fails as cub_midi_scan does, with the
 * file's name and the byte; the arrays are the reader's (free them). */
typedef struct cub_midi_groove {
    cub_groove_song song; /* points into the arrays below */
    cub_groove_midi_note *notes;
    cub_groove_tempo *tempos;
    cub_groove_meter *meters;
} cub_midi_groove;
cub_err cub_midi_groove_read(const uint8_t *data, size_t len, const char *name, cub_midi_groove *out,
                             cub_diag *diag);
/* The same from a file (size bounded like the box's songs). */
cub_err cub_midi_groove_load(const char *path, cub_midi_groove *out, cub_diag *diag);
void cub_midi_groove_free(cub_midi_groove *g);

/* A plan's storage on the heap for a song of note_count MIDI notes (the
 * cap cub_groove_store asks: 2 x notes + 1). CUB_ERR_NOMEM, with nothing
 * left allocated. */
cub_err cub_groove_store_alloc(cub_groove_store *m, int note_count);
void cub_groove_store_free(cub_groove_store *m);

#endif

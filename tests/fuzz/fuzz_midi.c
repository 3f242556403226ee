/* libFuzzer target: a MIDI file as the box reads it (app/music): our own
 * scan (midi_scan.c: length, tempo map, presets) and FluidSynth's player
 * loading the bytes our scan accepts with fluid_player_add_mem on a synthesiser with
 * no audio driver and no SoundFont, played for up to 0.5 s of rendered
 * samples (the player is timed by the samples, as music.c sets it).
 * FluidSynth is not instrumented: a bad read inside it shows only as a
 * crash. Seeds: the songs in assets/songs/ (made by scripts/make_songs.py). */
#include <fluidsynth.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cub/music.h"
#include "fuzz_tally.h"

#define RATE 22050
#define BLOCK 1024

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static fluid_settings_t *settings;
static fluid_synth_t *synth;

static void quiet(int level, const char *message, void *data)
{
    (void)level, (void)message, (void)data;
}

static void setup_once(void)
{
    for (int level = FLUID_PANIC; level <= FLUID_DBG; level++) fluid_set_log_function(level, quiet, NULL);
    settings = new_fluid_settings();
    if (!settings) abort();
    fluid_settings_setnum(settings, "synth.sample-rate", RATE);
    fluid_settings_setstr(settings, "player.timing-source", "sample");
    fluid_settings_setint(settings, "synth.polyphony", 16);
    synth = new_fluid_synth(settings);
    if (!synth) abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!synth) setup_once();
    cub_midi_info info;
    cub_diag d;
    int scanned = cub_midi_scan(data, size, "fuzz.mid", &info, &d) == CUB_OK, played = 0;
    if (scanned) {
        if (info.tracks < 1 || info.division <= 0 || info.length_us < 0 || info.notes < 0) abort();
    } else if (!d.msg[0]) {
        abort();
    }
    /* FluidSynth gets only what our scan accepted, as cub_music_load does
     * (a file without End of Track can spin FluidSynth's player). */
    fluid_player_t *player = scanned ? new_fluid_player(synth) : NULL;
    if (scanned && !player) abort();
    if (player && fluid_player_add_mem(player, data, size) == FLUID_OK &&
        fluid_player_play(player) == FLUID_OK) {
        static float left[BLOCK], right[BLOCK];
        for (int k = 0; k < RATE / 2 / BLOCK && fluid_player_get_status(player) == FLUID_PLAYER_PLAYING; k++)
            fluid_synth_write_float(synth, BLOCK, left, 0, 1, right, 0, 1), played = 1;
        fluid_player_stop(player);
    }
    if (player) delete_fluid_player(player);
    cub_fuzz_tally("fuzz_midi", scanned && played); /* ours and FluidSynth's both took it */
    fluid_synth_system_reset(synth);
    return 0;
}

/* audio_sdl — an SDL2 audio device fed by the app's fill callback. */
#include "audio_sdl.h"

#include <SDL.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define BUFFER_FRAMES 1024 /* ~23 ms at 44.1 kHz: small enough for lip-sync */

struct cub_audio_sdl {
    SDL_AudioDeviceID dev;
    cub_audio_fill fill;
    void *user;
    int gain_q15; /* volume: 32768 = as filled */
    _Atomic uint64_t frames;
};

/* SDL's audio thread. */
static void on_audio(void *userdata, Uint8 *stream, int len)
{
    cub_audio_sdl *a = userdata;
    int frames = len / (int)(2 * sizeof(int16_t));
    memset(stream, 0, (size_t)len);
    a->fill(a->user, (int16_t *)stream, frames);
    if (a->gain_q15 != 32768) {
        int16_t *s = (int16_t *)stream;
        for (int i = 0; i < frames * 2; i++) {
            s[i] = (int16_t)(((int32_t)s[i] * a->gain_q15) >> 15);
        }
    }
    atomic_fetch_add(&a->frames, (uint64_t)frames);
}

/* The driver is chosen when the audio subsystem starts; the hint must be
 * set before. */
static int init_subsystem(const char *driver, const char *disk_file, char *err, size_t err_size)
{
    if (driver) {
        SDL_SetHint(SDL_HINT_AUDIODRIVER, driver);
    } else {
        SDL_ResetHint(SDL_HINT_AUDIODRIVER); /* back to SDL_AUDIODRIVER or SDL's choice */
    }
    if (disk_file && driver && SDL_strcasecmp(driver, "disk") == 0) {
        SDL_setenv("SDL_DISKAUDIOFILE", disk_file, 1);
    }
    if (SDL_InitSubSystem(SDL_INIT_AUDIO) != 0) {
        snprintf(err, err_size, "audio: SDL audio (driver %s) would not start: %s",
                 driver ? driver : "default", SDL_GetError());
        return 0;
    }
    const char *now = SDL_GetCurrentAudioDriver();
    if (driver && (!now || SDL_strcasecmp(now, driver) != 0)) {
        snprintf(err, err_size, "audio: asked for SDL audio driver %s but %s is running", driver,
                 now ? now : "none");
        SDL_QuitSubSystem(SDL_INIT_AUDIO);
        return 0;
    }
    return 1;
}

cub_err cub_audio_sdl_open(const char *driver, const char *disk_file, int rate, int volume_pct,
                           cub_audio_fill fill, void *user, cub_audio_sdl **out, char *err, size_t err_size)
{
    if (!out || !fill || rate <= 0 || volume_pct < 0 || volume_pct > 100 || !err ||
        err_size == 0) {
        return CUB_ERR_ARG;
    }
    *out = NULL;
    cub_audio_sdl *a = calloc(1, sizeof *a);
    if (!a) {
        snprintf(err, err_size, "audio: out of memory");
        return CUB_ERR_NOMEM;
    }
    a->fill = fill;
    a->user = user;
    /* Linear in the sample value: volume=50 halves every sample. */
    a->gain_q15 = volume_pct * 32768 / 100;
    atomic_init(&a->frames, 0);
    if (!init_subsystem(driver, disk_file, err, err_size)) {
        free(a);
        return CUB_ERR_DEVICE;
    }
    SDL_AudioSpec want = {0}, have;
    want.freq = rate;
    want.format = AUDIO_S16SYS;
    want.channels = 2;
    want.samples = BUFFER_FRAMES;
    want.callback = on_audio;
    want.userdata = a;
    /* No allowed changes: SDL converts if the hardware differs, so the
     * fill callback always sees stereo int16 at `rate`. */
    a->dev = SDL_OpenAudioDevice(NULL, 0, &want, &have, 0);
    if (a->dev == 0) {
        snprintf(err, err_size, "audio: no SDL audio device (driver %s): %s",
                 driver ? driver : SDL_GetCurrentAudioDriver(), SDL_GetError());
        SDL_QuitSubSystem(SDL_INIT_AUDIO);
        free(a);
        return CUB_ERR_DEVICE;
    }
    SDL_PauseAudioDevice(a->dev, 0);
    *out = a;
    return CUB_OK;
}

void cub_audio_sdl_close(cub_audio_sdl *a)
{
    if (!a) {
        return;
    }
    SDL_CloseAudioDevice(a->dev); /* waits for the callback to return */
    SDL_QuitSubSystem(SDL_INIT_AUDIO);
    free(a);
}

uint64_t cub_audio_sdl_frames(const cub_audio_sdl *a)
{
    return a ? atomic_load(&((cub_audio_sdl *)a)->frames) : 0;
}

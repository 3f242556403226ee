/* audio_sdl — the PCM sink behind cub_board_audio_* (private to board/):
 * an SDL2 audio device, stereo int16 at the board's rate, whose callback
 * (on SDL's audio thread) asks the app to fill each buffer. The count of
 * frames handed to the device is the music clock. */
#ifndef CUB_BOARD_AUDIO_SDL_H
#define CUB_BOARD_AUDIO_SDL_H

#include <stddef.h>
#include <stdint.h>

#include "cub/board.h"

typedef struct cub_audio_sdl cub_audio_sdl;

/* driver: an SDL audio driver name ("dummy", "disk", "alsa"...) or NULL for
 * SDL's choice. disk_file: where the "disk" driver writes (NULL: SDL's
 * default). CUB_ERR_DEVICE with a message in err if no device opens. */
/* volume_pct 0..100 scales what fill writes (100 = as filled). */
cub_err cub_audio_sdl_open(const char *driver, const char *disk_file, int rate, int volume_pct,
                           cub_audio_fill fill, void *user, cub_audio_sdl **out, char *err, size_t err_size);
void cub_audio_sdl_close(cub_audio_sdl *a);
/* Frames handed to the device so far (any thread). */
uint64_t cub_audio_sdl_frames(const cub_audio_sdl *a);

#endif

/* dance_music — the song's music while the box dances: FluidSynth played
 * by the board's audio device (real time; the device clocks it), or
 * rendered by the loop exactly as far as its time says (the virtual clock,
 * or no audio device), so that a replay's music clock is as deterministic
 * as the rest. The music clock is song milliseconds, less what the audio
 * device still holds before the speaker; CUB_COACH_NO_MUSIC while nothing
 * plays. Started, paused, resumed and stopped as the director asks.
 *
 * The bear's words go over it (cub/voice.h) in the same audio fill, from
 * the voice pack, when the config's speech=1 and the pack reads: a missing
 * or bad pack is a warning naming it (the words are still shown). Rendered
 * music (the virtual clock) has no listener and no voice: what is said is
 * only logged. */
#ifndef CUB_APP_DANCE_MUSIC_H
#define CUB_APP_DANCE_MUSIC_H

#include <stddef.h>
#include <stdint.h>

#include "cub/board.h"
#include "cub/music.h"
#include "cub/voice.h"
#include "cub/voicepack.h"
#include "options.h"

typedef struct cub_dance_music {
    cub_music *music;
    cub_board *board;
    int pull;                /* the loop renders the music */
    int audio_open;          /* the board's audio device plays it */
    int started;             /* started (and not stopped) */
    int paused;              /* held (the camera is gone) */
    int end_told;            /* its end was reported */
    int64_t paused_at_us;    /* loop time it was held */
    int64_t pull_origin_us;  /* loop time the rendered music started */
    uint32_t pull_scale_ppm; /* rendered frames per loop second, ppm of the rate */
    int16_t *pcm;            /* scratch for rendering */
    cub_voicepack voicepack; /* count 0: nothing to say */
    cub_voice voice;         /* mixed into the device's buffers */
} cub_dance_music;

/* What cub_dance_music_say did. */
typedef enum cub_dance_said {
    CUB_DANCE_SAID = 0,   /* the device plays it (or would: rendered music) */
    CUB_DANCE_UNSAID,     /* no voice pack, or speech=0 */
    CUB_DANCE_NO_PHRASE,  /* the pack lacks these words */
} cub_dance_said;

/* Open the synthesiser with o's SoundFont, load midi_path, and choose who
 * plays it. On failure a message naming the file and problem is in err. */
cub_err cub_dance_music_open(cub_dance_music *m, const cub_app_options *o, cub_board *board,
                             const char *midi_path, char *err, size_t err_size);
void cub_dance_music_close(cub_dance_music *m);
/* Say text over the music from the next audio buffer on (cub/voice.h),
 * cutting short what is being said. */
cub_dance_said cub_dance_music_say(cub_dance_music *m, const char *text);
/* Frames handed to the audio device so far (0 when none plays). */
uint64_t cub_dance_music_device_frames(const cub_dance_music *m);
/* The music clock (song ms), or CUB_COACH_NO_MUSIC when nothing plays. */
int32_t cub_dance_music_ms(const cub_dance_music *m);
/* From the beginning at loop time t_us / held or going on / stopped. */
void cub_dance_music_start(cub_dance_music *m, int64_t t_us);
void cub_dance_music_pause(cub_dance_music *m, int paused, int64_t t_us);
void cub_dance_music_stop(cub_dance_music *m);
/* At the start of each loop step: render what is due by now_us (when the
 * loop renders it). 1 once when the started music has played to its end. */
int cub_dance_music_poll(cub_dance_music *m, int64_t now_us);

#endif

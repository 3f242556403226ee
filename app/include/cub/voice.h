/* voice — the bear's words mixed over the music in the audio fill: after
 * the music is rendered into a buffer, cub_voice_mix ducks it (to
 * CUB_VOICE_DUCK_PERMILLE, ramped) while a phrase plays and adds the
 * phrase on top, resampled from the pack's rate to the device's by linear
 * interpolation (integer, so the same requests give the same samples).
 *
 * One phrase at a time: a phrase asked for while another plays replaces
 * it, after a CUB_VOICE_FADE_MS fade of the old one. The box says what the
 * TV shows now; a hint that waited behind the last one would speak of a
 * move the bear has left (a correction comes within 200 ms of the
 * mistake). The same phrase asked for again while it plays goes on.
 *
 * Threads: cub_voice_say on the loop's thread, cub_voice_mix on the audio
 * thread; the request is one atomic word, read at the start of each
 * buffer, so a phrase starts at the first buffer begun after it was asked
 * for. The pack must outlive the audio device. */
#ifndef CUB_VOICE_H
#define CUB_VOICE_H

#include <stdatomic.h>
#include <stdint.h>

#include "cub/voicepack.h"

#define CUB_VOICE_DUCK_PERMILLE 300 /* the music's gain under the voice */
#define CUB_VOICE_ATTACK_MS 10      /* music ramps down this fast */
#define CUB_VOICE_RELEASE_MS 120    /* and back up after the phrase */
#define CUB_VOICE_FADE_MS 8         /* a replaced phrase fades out */
#define CUB_VOICE_GAIN_PERMILLE 1000 /* the voice as packed (it peaks near -3 dBFS) */

typedef struct cub_voice {
    const cub_voicepack *pack; /* NULL: silent, the music untouched */
    int rate;                  /* the device's frames per second */
    uint32_t step_q16;         /* pack frames per device frame, Q16 */
    int32_t attack_q15, release_q15; /* duck gain change per frame */
    int32_t fade_frames;
    _Atomic uint32_t request; /* (serial << 12) | phrase + 1 from cub_voice_say */
    /* the audio thread's */
    uint32_t seen;     /* the last request taken */
    int playing;       /* phrase index, or -1 */
    int next;          /* phrase to start once the fade ends, or -1 */
    uint64_t pos_q16;  /* in the playing phrase, pack frames, Q16 */
    int32_t fade_left; /* frames of the fade still to go; 0: none */
    int32_t duck_q15;  /* the music's gain now, 32768 = full */
} cub_voice;

/* Ready v for a device at rate (Hz) with pack (NULL: mix does nothing).
 * CUB_ERR_ARG for a rate out of the pack's range. */
cub_err cub_voice_init(cub_voice *v, const cub_voicepack *pack, int rate);
/* Ask for phrase (an index of the pack); -1 stops what is said. */
void cub_voice_say(cub_voice *v, int phrase);
/* Duck the music in stereo[2*frames] and add the voice (audio thread). */
void cub_voice_mix(cub_voice *v, int16_t *stereo, int frames);

#endif

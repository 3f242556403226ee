/* The voice over the music (see cub/voice.h). */
#include "cub/voice.h"

#include <string.h>

#define Q15_ONE 32768
#define DUCK_Q15 (CUB_VOICE_DUCK_PERMILLE * Q15_ONE / 1000)
#define REQ_PHRASE_BITS 12u
#define REQ_PHRASE_MASK ((1u << REQ_PHRASE_BITS) - 1u)

cub_err cub_voice_init(cub_voice *v, const cub_voicepack *pack, int rate)
{
    if (!v || rate < CUB_VOICEPACK_RATE_MIN || rate > CUB_VOICEPACK_RATE_MAX) return CUB_ERR_ARG;
    memset(v, 0, sizeof *v);
    v->pack = pack && pack->count > 0 ? pack : NULL;
    v->rate = rate;
    v->step_q16 = v->pack ? (uint32_t)(((uint64_t)pack->rate << 16) / (uint64_t)rate) : 0;
    int32_t attack = rate * CUB_VOICE_ATTACK_MS / 1000, release = rate * CUB_VOICE_RELEASE_MS / 1000;
    v->attack_q15 = (Q15_ONE - DUCK_Q15) / (attack > 0 ? attack : 1) + 1;
    v->release_q15 = (Q15_ONE - DUCK_Q15) / (release > 0 ? release : 1) + 1;
    v->fade_frames = rate * CUB_VOICE_FADE_MS / 1000;
    if (v->fade_frames < 1) v->fade_frames = 1;
    v->playing = v->next = -1;
    v->duck_q15 = Q15_ONE;
    atomic_init(&v->request, 0);
    return CUB_OK;
}

void cub_voice_say(cub_voice *v, int phrase)
{
    if (!v || !v->pack || phrase < -1 || phrase >= v->pack->count) return;
    uint32_t serial = (atomic_load(&v->request) >> REQ_PHRASE_BITS) + 1u;
    atomic_store(&v->request, (serial << REQ_PHRASE_BITS) | (uint32_t)(phrase + 1));
}

static void start(cub_voice *v, int phrase)
{
    v->playing = phrase;
    v->next = -1;
    v->pos_q16 = 0;
    v->fade_left = 0;
}

/* A new request: start it, or fade out what plays and start it after. */
static void take_request(cub_voice *v)
{
    uint32_t req = atomic_load(&v->request);
    if (req == v->seen) return;
    v->seen = req;
    int phrase = (int)(req & REQ_PHRASE_MASK) - 1;
    if (phrase == v->playing && v->fade_left == 0) return; /* the same words go on */
    if (v->playing < 0) {
        if (phrase >= 0) start(v, phrase);
        return;
    }
    v->next = phrase;
    if (v->fade_left == 0) v->fade_left = v->fade_frames;
}

/* The playing phrase's sample at the current position, then one step on. */
static int32_t voice_sample(cub_voice *v)
{
    const cub_voice_phrase *ph = &v->pack->phrases[v->playing];
    uint64_t i = v->pos_q16 >> 16;
    if (i >= ph->frames) {
        v->playing = v->next;
        v->next = -1;
        v->pos_q16 = 0;
        v->fade_left = 0;
        return 0;
    }
    int32_t a = ph->pcm[i], b = i + 1 < ph->frames ? ph->pcm[i + 1] : 0;
    int32_t frac = (int32_t)(v->pos_q16 & 0xffff);
    int32_t s = a + (int32_t)(((int64_t)(b - a) * frac) >> 16);
    v->pos_q16 += v->step_q16;
    if (v->fade_left > 0) {
        s = (int32_t)((int64_t)s * v->fade_left / v->fade_frames);
        if (--v->fade_left == 0) {
            if (v->next >= 0) start(v, v->next);
            else v->playing = -1;
        }
    }
    return s * CUB_VOICE_GAIN_PERMILLE / 1000;
}

static void follow_duck(cub_voice *v)
{
    if (v->playing >= 0 || v->next >= 0) {
        v->duck_q15 -= v->attack_q15;
        if (v->duck_q15 < DUCK_Q15) v->duck_q15 = DUCK_Q15;
    } else if (v->duck_q15 < Q15_ONE) {
        v->duck_q15 += v->release_q15;
        if (v->duck_q15 > Q15_ONE) v->duck_q15 = Q15_ONE;
    }
}

static int16_t clamp16(int32_t x)
{
    return (int16_t)(x > 32767 ? 32767 : x < -32768 ? -32768 : x);
}

void cub_voice_mix(cub_voice *v, int16_t *stereo, int frames)
{
    if (!v || !v->pack || !stereo) return;
    take_request(v);
    if (v->playing < 0 && v->duck_q15 == Q15_ONE) return; /* nothing to do: the music as it is */
    for (int f = 0; f < frames; f++) {
        int32_t s = v->playing >= 0 ? voice_sample(v) : 0;
        follow_duck(v);
        for (int c = 0; c < 2; c++) {
            int32_t m = stereo[2 * f + c];
            stereo[2 * f + c] = clamp16(((m * v->duck_q15) >> 15) + s);
        }
    }
}

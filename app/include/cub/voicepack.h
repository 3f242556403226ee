/* voicepack — the bear's spoken words (build/assets/voice/bear.cubvoice,
 * made at build time by `cubvoice` with espeak-ng): every phrase the
 * box can show, as mono int16 PCM, found by its text.
 *
 * Format (little-endian, versioned; the same phrases and samples always
 * give the same bytes):
 *   "CUBVOICE" u32 version, u32 rate (Hz), u32 phrase_count
 *   per phrase: u32 id (cub_voicepack_id of its text), u32 text_bytes,
 *               the text (UTF-8, no NUL), u32 frames, frames x i16
 *   u32 CRC-32 of everything before it
 * Reading checks every count and length against the bytes left, that each
 * id is its text's, that no text comes twice, and the CRC, and says what
 * is wrong at which byte. A pack is one heap block; free it. */
#ifndef CUB_VOICEPACK_H
#define CUB_VOICEPACK_H

#include <stddef.h>
#include <stdint.h>

#include "cub/err.h"
#include "cub/io.h"

#define CUB_VOICEPACK_MAX_PHRASES 1024
#define CUB_VOICEPACK_TEXT_MAX 255      /* bytes of one phrase's text */
#define CUB_VOICEPACK_MAX_SECONDS 10    /* one phrase at most */
#define CUB_VOICEPACK_RATE_MIN 8000
#define CUB_VOICEPACK_RATE_MAX 96000

typedef struct cub_voice_phrase {
    uint32_t id;         /* cub_voicepack_id(text) */
    const char *text;    /* NUL-terminated */
    const int16_t *pcm;  /* frames mono samples at the pack's rate */
    uint32_t frames;
} cub_voice_phrase;

typedef struct cub_voicepack {
    int rate; /* Hz */
    int count;
    cub_voice_phrase *phrases; /* in file order; points into mem */
    void *mem;                 /* owned */
} cub_voicepack;

/* The phrase's name: FNV-1a (32 bit) of its UTF-8 bytes. */
uint32_t cub_voicepack_id(const char *text);
/* Index of the phrase with exactly this text, or -1 (also for NULL). */
int cub_voicepack_find(const cub_voicepack *pack, const char *text);
/* Parse a pack in memory (name for messages). CUB_ERR_FORMAT with the
 * byte offset and the problem in diag; CUB_ERR_NOMEM. */
cub_err cub_voicepack_parse(const void *data, size_t len, const char *name, cub_voicepack *out,
                            cub_diag *diag);
/* Read a file (at most CUB_TEXT_MAX_VOICE bytes) and parse it. */
cub_err cub_voicepack_read(const char *path, cub_voicepack *out, cub_diag *diag);
/* Write count phrases (their id is computed from the text) at rate. */
cub_err cub_voicepack_write(const char *path, int rate, const cub_voice_phrase *phrases, int count,
                            cub_diag *diag);
void cub_voicepack_free(cub_voicepack *pack);

#endif

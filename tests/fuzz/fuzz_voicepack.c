/* libFuzzer target: the voice pack (cub/voicepack.h) as the box reads it,
 * and the mixer over what it accepts. Each input is parsed as it is, then
 * again with its CRC made right, so that mutations reach past the CRC into
 * the phrases. A refusal must name the file; an accepted pack must hold
 * only phrases within the documented limits, each found by its own text,
 * and mix without reading past a phrase. Seeds: seeds_voice/ (make_seeds.py). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cub/voice.h"
#include "cub/voicepack.h"
#include "fuzz_tally.h"
#include "pack_internal.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check_accepted(const cub_voicepack *p)
{
    if (p->rate < CUB_VOICEPACK_RATE_MIN || p->rate > CUB_VOICEPACK_RATE_MAX) abort();
    if (p->count < 1 || p->count > CUB_VOICEPACK_MAX_PHRASES) abort();
    for (int i = 0; i < p->count; i++) {
        const cub_voice_phrase *ph = &p->phrases[i];
        if (strlen(ph->text) > CUB_VOICEPACK_TEXT_MAX || ph->id != cub_voicepack_id(ph->text))
            abort();
        if (cub_voicepack_find(p, ph->text) != i) abort();
        if (ph->frames < 1 || ph->frames > (uint32_t)p->rate * CUB_VOICEPACK_MAX_SECONDS) abort();
    }
    static cub_voice v;
    static int16_t buf[2 * 4096];
    if (cub_voice_init(&v, p, 44100)) abort();
    cub_voice_say(&v, p->count - 1);
    cub_voice_mix(&v, buf, 4096); /* ASan: within the phrase's samples */
    cub_voice_say(&v, 0);
    cub_voice_mix(&v, buf, 4096);
}

static int parse_once(const uint8_t *data, size_t size)
{
    cub_voicepack p;
    cub_diag diag;
    cub_err e = cub_voicepack_parse(data, size, "fuzz.cubvoice", &p, &diag);
    if (e == CUB_OK) {
        check_accepted(&p);
        cub_voicepack_free(&p);
        return 1;
    }
    if (e != CUB_ERR_FORMAT || strcmp(diag.file, "fuzz.cubvoice") != 0 || !diag.msg[0]) abort();
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    int ok = parse_once(data, size);
    if (size >= 8 && size < (1u << 20)) {
        uint8_t *fixed = malloc(size);
        if (!fixed) return 0;
        memcpy(fixed, data, size);
        uint32_t crc = pack_crc32(fixed, size - 4);
        for (int i = 0; i < 4; i++) fixed[size - 4 + i] = (uint8_t)(crc >> (8 * i));
        ok |= parse_once(fixed, size);
        free(fixed);
    }
    cub_fuzz_tally("fuzz_voicepack", ok);
    return 0;
}

/* The voice pack (format in cub/voicepack.h). Pass one walks the records
 * and checks each against the bytes left, its id and the CRC; pass two
 * copies the texts and samples into one block. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/voicepack.h"
#include "pack_internal.h"

#define VOICE_MAGIC "CUBVOICE"
#define VOICE_VERSION 1u
#define VOICE_HEADER_BYTES 20u /* magic, version, rate, count */

uint32_t cub_voicepack_id(const char *text)
{
    uint32_t h = 2166136261u;
    for (const unsigned char *p = (const unsigned char *)text; *p; p++) h = (h ^ *p) * 16777619u;
    return h;
}

int cub_voicepack_find(const cub_voicepack *pack, const char *text)
{
    if (!pack || !text) return -1;
    for (int i = 0; i < pack->count; i++)
        if (!strcmp(pack->phrases[i].text, text)) return i;
    return -1;
}

void cub_voicepack_free(cub_voicepack *pack)
{
    if (!pack) return;
    free(pack->mem);
    memset(pack, 0, sizeof *pack);
}

/* ---- reading -------------------------------------------------------------- */

typedef struct voice_reader {
    const uint8_t *data;
    size_t len, pos;
    const char *file;
    cub_diag *diag;
} voice_reader;

static cub_err bad(const voice_reader *r, size_t at, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static cub_err bad(const voice_reader *r, size_t at, const char *fmt, ...)
{
    char msg[224];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return cub_diag_fail(r->diag, CUB_ERR_FORMAT, r->file, 0, "at byte %zu: %s", at, msg);
}

/* Bytes left before the CRC. */
static size_t left(const voice_reader *r)
{
    return r->len - PACK_CRC_BYTES - r->pos;
}

static cub_err read_header(voice_reader *r, int *rate, int *count)
{
    if (r->len < VOICE_HEADER_BYTES + PACK_CRC_BYTES)
        return bad(r, 0, "only %zu bytes, too short for a voice pack", r->len);
    if (memcmp(r->data, VOICE_MAGIC, 8) != 0)
        return bad(r, 0, "not a voice pack (no \"CUBVOICE\" at the start)");
    uint32_t version = pack_get_u32(r->data + 8), hz = pack_get_u32(r->data + 12);
    uint32_t n = pack_get_u32(r->data + 16);
    if (version != VOICE_VERSION)
        return bad(r, 8, "version %u; this reader knows version %u", version, VOICE_VERSION);
    if (hz < CUB_VOICEPACK_RATE_MIN || hz > CUB_VOICEPACK_RATE_MAX)
        return bad(r, 12, "rate %u Hz is not in %d..%d", hz, CUB_VOICEPACK_RATE_MIN,
                   CUB_VOICEPACK_RATE_MAX);
    if (n < 1 || n > CUB_VOICEPACK_MAX_PHRASES)
        return bad(r, 16, "phrase count %u is not in 1..%d", n, CUB_VOICEPACK_MAX_PHRASES);
    uint32_t stored = pack_get_u32(r->data + r->len - PACK_CRC_BYTES);
    if (stored != pack_crc32(r->data, r->len - PACK_CRC_BYTES))
        return bad(r, r->len - PACK_CRC_BYTES, "CRC mismatch: the file is damaged");
    *rate = (int)hz;
    *count = (int)n;
    r->pos = VOICE_HEADER_BYTES;
    return CUB_OK;
}

/* Pass one over phrase i at r->pos: its shape; the text's offset in *text_at. */
static cub_err scan_phrase(voice_reader *r, int i, int rate, size_t *text_at, uint32_t *frames)
{
    size_t at = r->pos;
    if (left(r) < 8) return bad(r, at, "phrase %d: the header is cut off", i);
    uint32_t id = pack_get_u32(r->data + at), n = pack_get_u32(r->data + at + 4);
    if (n < 1 || n > CUB_VOICEPACK_TEXT_MAX)
        return bad(r, at + 4, "phrase %d: text of %u bytes is not in 1..%d", i, n,
                   CUB_VOICEPACK_TEXT_MAX);
    if (left(r) < 8 + (size_t)n + 4) return bad(r, at, "phrase %d: cut off in its text", i);
    char text[CUB_VOICEPACK_TEXT_MAX + 1];
    memcpy(text, r->data + at + 8, n);
    text[n] = '\0';
    if (strlen(text) != n) return bad(r, at + 8, "phrase %d: the text holds a NUL byte", i);
    if (cub_voicepack_id(text) != id)
        return bad(r, at, "phrase %d \"%s\": id %08x is not its text's (%08x)", i, text, id,
                   cub_voicepack_id(text));
    r->pos = at + 8 + n;
    *frames = pack_get_u32(r->data + r->pos);
    uint32_t most = (uint32_t)rate * CUB_VOICEPACK_MAX_SECONDS;
    if (*frames < 1 || *frames > most)
        return bad(r, r->pos, "phrase %d \"%s\": %u frames is not in 1..%u (%d s)", i, text,
                   *frames, most, CUB_VOICEPACK_MAX_SECONDS);
    r->pos += 4;
    if (left(r) / 2 < *frames)
        return bad(r, r->pos, "phrase %d \"%s\": %u frames need %zu bytes, only %zu left", i, text,
                   *frames, (size_t)*frames * 2, left(r));
    *text_at = at + 8;
    r->pos += (size_t)*frames * 2;
    return CUB_OK;
}

typedef struct voice_scan {
    size_t text_at[CUB_VOICEPACK_MAX_PHRASES];
    uint32_t text_len[CUB_VOICEPACK_MAX_PHRASES];
    uint32_t frames[CUB_VOICEPACK_MAX_PHRASES];
} voice_scan;

static cub_err scan_all(voice_reader *r, int rate, int count, voice_scan *s, size_t *mem)
{
    *mem = (size_t)count * sizeof(cub_voice_phrase);
    for (int i = 0; i < count; i++) {
        cub_err e = scan_phrase(r, i, rate, &s->text_at[i], &s->frames[i]);
        if (e) return e;
        s->text_len[i] = pack_get_u32(r->data + s->text_at[i] - 4);
        for (int k = 0; k < i; k++)
            if (s->text_len[k] == s->text_len[i] &&
                !memcmp(r->data + s->text_at[k], r->data + s->text_at[i], s->text_len[i]))
                return bad(r, s->text_at[i], "phrase %d: the same text as phrase %d", i, k);
        *mem += s->text_len[i] + 1 + (size_t)s->frames[i] * 2;
    }
    if (left(r) != 0)
        return bad(r, r->pos, "%zu bytes after the last phrase, before the CRC", left(r));
    return CUB_OK;
}

/* Pass two: the phrases, then the samples (2-aligned), then the texts. */
static void copy_all(const voice_reader *r, const voice_scan *s, cub_voicepack *out)
{
    uint8_t *base = out->mem;
    cub_voice_phrase *ph = out->phrases = (cub_voice_phrase *)base;
    size_t pcm_at = (size_t)out->count * sizeof *ph, text_at = pcm_at;
    for (int i = 0; i < out->count; i++) text_at += (size_t)s->frames[i] * 2;
    for (int i = 0; i < out->count; i++) {
        const uint8_t *src = r->data + s->text_at[i] + s->text_len[i] + 4;
        int16_t *pcm = (int16_t *)(void *)(base + pcm_at);
        for (uint32_t k = 0; k < s->frames[i]; k++) pcm[k] = pack_get_i16(src + 2 * k);
        char *text = (char *)base + text_at;
        memcpy(text, r->data + s->text_at[i], s->text_len[i]);
        text[s->text_len[i]] = '\0';
        ph[i] = (cub_voice_phrase){.id = cub_voicepack_id(text), .text = text, .pcm = pcm,
                                   .frames = s->frames[i]};
        pcm_at += (size_t)s->frames[i] * 2;
        text_at += s->text_len[i] + 1;
    }
}

cub_err cub_voicepack_parse(const void *data, size_t len, const char *name, cub_voicepack *out,
                            cub_diag *diag)
{
    if (!out || (!data && len)) return CUB_ERR_ARG;
    memset(out, 0, sizeof *out);
    voice_reader r = {.data = data, .len = len, .file = name ? name : "voice pack", .diag = diag};
    int rate = 0, count = 0;
    cub_err e = read_header(&r, &rate, &count);
    voice_scan *s = e ? NULL : malloc(sizeof *s);
    if (!e && !s) e = CUB_ERR_NOMEM;
    size_t mem = 0;
    if (!e) e = scan_all(&r, rate, count, s, &mem);
    if (!e && !(out->mem = malloc(mem))) e = CUB_ERR_NOMEM;
    if (!e) {
        out->rate = rate;
        out->count = count;
        copy_all(&r, s, out);
    }
    free(s);
    if (e == CUB_ERR_NOMEM) cub_diag_fail(diag, e, r.file, 0, "out of memory");
    return e;
}

static cub_err parse_text(const cub_text *t, const void *in, void *out)
{
    (void)in;
    return cub_voicepack_parse(t->s, t->len, t->name, out, t->diag);
}

cub_err cub_voicepack_read(const char *path, cub_voicepack *out, cub_diag *diag)
{
    if (out) memset(out, 0, sizeof *out);
    return cub_text_load(&(cub_text_src){path, "voice pack", CUB_TEXT_MAX_VOICE}, parse_text, NULL,
                         out, diag);
}

/* ---- writing -------------------------------------------------------------- */

static void put_u32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++) p[i] = (uint8_t)(v >> (8 * i));
}

static size_t encoded_size(const cub_voice_phrase *ph, int count)
{
    size_t n = VOICE_HEADER_BYTES + PACK_CRC_BYTES;
    for (int i = 0; i < count; i++) n += 12 + strlen(ph[i].text) + (size_t)ph[i].frames * 2;
    return n;
}

static void encode(uint8_t *buf, size_t size, int rate, const cub_voice_phrase *ph, int count)
{
    memcpy(buf, VOICE_MAGIC, 8);
    put_u32(buf + 8, VOICE_VERSION);
    put_u32(buf + 12, (uint32_t)rate);
    put_u32(buf + 16, (uint32_t)count);
    uint8_t *p = buf + VOICE_HEADER_BYTES;
    for (int i = 0; i < count; i++) {
        size_t n = strlen(ph[i].text);
        put_u32(p, cub_voicepack_id(ph[i].text));
        put_u32(p + 4, (uint32_t)n);
        memcpy(p + 8, ph[i].text, n);
        p += 8 + n;
        put_u32(p, ph[i].frames);
        p += 4;
        for (uint32_t k = 0; k < ph[i].frames; k++, p += 2) {
            uint16_t u = (uint16_t)ph[i].pcm[k];
            p[0] = (uint8_t)u;
            p[1] = (uint8_t)(u >> 8);
        }
    }
    put_u32(buf + size - PACK_CRC_BYTES, pack_crc32(buf, size - PACK_CRC_BYTES));
}

/* The writer refuses what the reader would, so no pack it makes is bad. */
static cub_err check_phrases(const char *path, int rate, const cub_voice_phrase *ph, int count,
                             cub_diag *diag)
{
    if (rate < CUB_VOICEPACK_RATE_MIN || rate > CUB_VOICEPACK_RATE_MAX ||
        count < 1 || count > CUB_VOICEPACK_MAX_PHRASES)
        return cub_diag_fail(diag, CUB_ERR_ARG, path, 0, "rate %d Hz or %d phrases out of range",
                             rate, count);
    for (int i = 0; i < count; i++) {
        size_t n = ph[i].text ? strlen(ph[i].text) : 0;
        if (n < 1 || n > CUB_VOICEPACK_TEXT_MAX || !ph[i].pcm || ph[i].frames < 1 ||
            ph[i].frames > (uint32_t)rate * CUB_VOICEPACK_MAX_SECONDS)
            return cub_diag_fail(diag, CUB_ERR_ARG, path, 0,
                                 "phrase %d: text of %zu bytes, %u frames out of range", i, n,
                                 ph[i].frames);
        for (int k = 0; k < i; k++)
            if (!strcmp(ph[k].text, ph[i].text))
                return cub_diag_fail(diag, CUB_ERR_ARG, path, 0, "phrase \"%s\" given twice",
                                     ph[i].text);
    }
    return CUB_OK;
}

cub_err cub_voicepack_write(const char *path, int rate, const cub_voice_phrase *phrases, int count,
                            cub_diag *diag)
{
    if (!path || !phrases) return CUB_ERR_ARG;
    cub_err e = check_phrases(path, rate, phrases, count, diag);
    if (e) return e;
    size_t size = encoded_size(phrases, count);
    uint8_t *buf = malloc(size);
    if (!buf) return cub_diag_fail(diag, CUB_ERR_NOMEM, path, 0, "out of memory");
    encode(buf, size, rate, phrases, count);
    FILE *f = fopen(path, "wb");
    int ok = f && fwrite(buf, 1, size, f) == size;
    if (f && fclose(f) != 0) ok = 0;
    free(buf);
    return ok ? CUB_OK : cub_diag_fail(diag, CUB_ERR_IO, path, 0, "cannot write the voice pack");
}

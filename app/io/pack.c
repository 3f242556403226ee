/* The clip library pack (format in cub/pack.h). Writing lays every byte
 * out explicitly (little-endian, zero padding), so a library always packs
 * to the same bytes. Reading makes two passes: the first checks the shape
 * (magic, version, counts against the bytes left, names, parents) and the
 * CRC without touching frame data; the second decodes the frames into one
 * allocation and checks every quaternion (pack_read.c). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/pack.h"
#include "io_internal.h"
#include "pack_internal.h"

static void put_u16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
}

static void put_u32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        p[i] = (uint8_t)(v >> (8 * i));
}

/* ---- CRC-32 ---------------------------------------------------------------- */

uint32_t pack_crc32(const void *data, size_t len)
{
    static uint32_t table[256];
    static int ready;
    if (!ready) { /* idempotent, so a race only repeats the same work */
        for (uint32_t i = 0; i < 256; i++) {
            uint32_t c = i;
            for (int k = 0; k < 8; k++)
                c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            table[i] = c;
        }
        ready = 1;
    }
    const uint8_t *p = data;
    uint32_t crc = 0xFFFFFFFFu;
    for (size_t i = 0; i < len; i++)
        crc = table[(crc ^ p[i]) & 0xFF] ^ (crc >> 8);
    return crc ^ 0xFFFFFFFFu;
}

/* ---- quaternions: Q2.30 <-> Q1.14 ---------------------------------------- */

int pack_q14_roughly_unit(const int16_t c[4])
{
    int64_t n2 = 0;
    for (int i = 0; i < 4; i++)
        n2 += (int64_t)c[i] * c[i];
    const int64_t one = (int64_t)1 << 28, tol = one / 50;
    return n2 >= one - tol && n2 <= one + tol;
}

static int16_t round_q30_to_q14(int64_t v)
{
    int64_t r = v + 32768; /* round half up: floor((v + 2^15) / 2^16) */
    r = r >= 0 ? r / 65536 : -((-r + 65535) / 65536);
    return (int16_t)(r > 32767 ? 32767 : r < -32768 ? -32768 : r);
}

static void q30_to_q14(cub_quat q, int16_t out[4])
{
    int64_t s = q.w < 0 ? -1 : 1; /* one sign for q and -q: w >= 0 */
    out[0] = round_q30_to_q14(s * q.w);
    out[1] = round_q30_to_q14(s * q.x);
    out[2] = round_q30_to_q14(s * q.y);
    out[3] = round_q30_to_q14(s * q.z);
}

cub_quat pack_q14_to_quat(const int16_t c[4])
{
    cub_quat q = {(int32_t)c[0] * 65536, (int32_t)c[1] * 65536, (int32_t)c[2] * 65536,
                  (int32_t)c[3] * 65536};
    return cub_fx_quat_normalize(q);
}

static int q14_stable(const int16_t c[4])
{
    int16_t back[4];
    q30_to_q14(pack_q14_to_quat(c), back);
    return memcmp(back, c, sizeof(back)) == 0;
}

/* The Q1.14 form of q that reading (renormalising) and writing again gives
 * back unchanged, so write -> read -> write is byte-for-byte stable: the
 * plain rounding is nearly always such a fixed point; else follow the
 * round trip, else take the nearest stable neighbour. */
void pack_quat_to_q14(cub_quat q, int16_t out[4])
{
    q30_to_q14(q, out);
    for (int i = 0; i < 4 && !q14_stable(out); i++)
        q30_to_q14(pack_q14_to_quat(out), out);
    if (q14_stable(out)) return;
    int16_t base[4], best[4];
    int64_t best_d = INT64_MAX;
    memcpy(base, out, sizeof(base));
    memcpy(best, out, sizeof(best));
    for (int k = 0; k < 81; k++) {
        int16_t c[4];
        int64_t d = 0;
        for (int i = 0, m = k; i < 4; i++, m /= 3)
            c[i] = (int16_t)(base[i] + m % 3 - 1);
        for (int i = 0; i < 4; i++)
            d += (int64_t)(c[i] - base[i]) * (c[i] - base[i]);
        if (c[0] >= 0 && d < best_d && q14_stable(c)) {
            best_d = d;
            memcpy(best, c, sizeof(best));
        }
    }
    memcpy(out, best, sizeof(best));
}

/* ---- writing ------------------------------------------------------------- */

static size_t bounded_len(const char *s, size_t cap)
{
    const char *nul = memchr(s, '\0', cap);
    return nul ? (size_t)(nul - s) : cap;
}

static int name_ok(const char *s, size_t cap)
{
    size_t n = bounded_len(s, cap);
    if (n == 0 || n == cap) return 0;
    for (size_t i = 0; i < n; i++)
        if ((unsigned char)s[i] < 32 || (unsigned char)s[i] > 126) return 0;
    return 1;
}

/* Norm squared within 2% of one (in Q.22, so the sum fits 64 bits). */
static int q30_roughly_unit(cub_quat q)
{
    const int64_t c[4] = {q.w / 256, q.x / 256, q.y / 256, q.z / 256};
    int64_t n2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2] + c[3] * c[3];
    const int64_t one = (int64_t)1 << 44, tol = one / 50;
    return n2 >= one - tol && n2 <= one + tol;
}

/* Quaternions that are not near unit length are a bug upstream: refuse. */
static cub_err check_unit(const cub_library_clip *lc, const char *file, cub_diag *diag)
{
    const cub_clip *c = &lc->clip;
    int jn = c->skel->joint_count;
    for (int f = 0; f < c->frame_count; f++)
        for (int j = 0; j < jn; j++)
            if (!q30_roughly_unit(c->rot[(size_t)f * (size_t)jn + (size_t)j]))
                return cub_diag_fail(diag, CUB_ERR_ARG, file, 0,
                                     "clip '%s' frame %d joint %d: not a unit quaternion",
                                     lc->name, f, j);
    return CUB_OK;
}

static cub_err check_library(const cub_library *lib, const char *file, cub_diag *diag)
{
    int jn = lib->skel.joint_count;
    if (jn < 1 || jn > CUB_MOTION_MAX_JOINTS || cub_motion_skeleton_validate(&lib->skel))
        return cub_diag_fail(diag, CUB_ERR_ARG, file, 0, "the library's skeleton is not valid");
    if (lib->clip_count < 0 || (lib->clip_count > 0 && !lib->clips))
        return cub_diag_fail(diag, CUB_ERR_ARG, file, 0, "bad clip count %d", lib->clip_count);
    for (int i = 0; i < lib->clip_count; i++) {
        const cub_library_clip *lc = &lib->clips[i];
        const cub_clip *c = &lc->clip;
        if (!name_ok(lc->name, sizeof(lc->name)) || !name_ok(lc->kind, sizeof(lc->kind)))
            return cub_diag_fail(diag, CUB_ERR_ARG, file, 0,
                              "clip %d: name and kind must be printable, 1 to %zu and %zu bytes", i,
                              sizeof(lc->name) - 1, sizeof(lc->kind) - 1);
        if (!c->skel || c->skel->joint_count != jn || c->frame_count < 1 || !c->root_mm ||
            !c->rot || c->frame_ns == 0)
            return cub_diag_fail(diag, CUB_ERR_ARG, file, 0,
                              "clip '%s': not a clip of %d joints with frames", lc->name, jn);
        if (c->trans_mm)
            return cub_diag_fail(diag, CUB_ERR_UNSUPPORTED, file, 0,
                              "clip '%s' animates joint translations, which packs do not store",
                              lc->name);
        for (int k = 0; k < i; k++)
            if (!strcmp(lib->clips[k].name, lc->name))
                return cub_diag_fail(diag, CUB_ERR_ARG, file, 0, "two clips are named '%s'", lc->name);
        cub_err err = check_unit(lc, file, diag);
        if (err) return err;
    }
    return CUB_OK;
}

static uint8_t *put_joints(uint8_t *p, const cub_skeleton *skel)
{
    for (int j = 0; j < skel->joint_count; j++) {
        const cub_joint *jt = &skel->joints[j];
        memset(p, 0, PACK_JOINT_BYTES);
        memcpy(p, jt->name, bounded_len(jt->name, CUB_MOTION_NAME_LEN - 1));
        put_u16(p + 32, (uint16_t)jt->parent);
        p[34] = jt->is_end_site ? 1 : 0;
        put_u32(p + 36, (uint32_t)jt->offset_mm.x);
        put_u32(p + 40, (uint32_t)jt->offset_mm.y);
        put_u32(p + 44, (uint32_t)jt->offset_mm.z);
        p += PACK_JOINT_BYTES;
    }
    return p;
}

/* check_unit passed; the Q1.14 form is checked too. */
static uint8_t *put_clip(uint8_t *p, const cub_library_clip *lc, int jn, const char *file,
                         cub_diag *diag, cub_err *err)
{
    const cub_clip *c = &lc->clip;
    memset(p, 0, PACK_CLIP_HEADER_BYTES);
    memcpy(p, lc->name, strlen(lc->name));
    memcpy(p + 32, lc->kind, strlen(lc->kind));
    put_u32(p + 48, c->frame_ns);
    put_u32(p + 52, (uint32_t)c->frame_count);
    p += PACK_CLIP_HEADER_BYTES;
    for (int f = 0; f < c->frame_count; f++) {
        put_u32(p, (uint32_t)c->root_mm[f].x);
        put_u32(p + 4, (uint32_t)c->root_mm[f].y);
        put_u32(p + 8, (uint32_t)c->root_mm[f].z);
        p += 12;
        for (int j = 0; j < jn; j++, p += 8) {
            int16_t q[4];
            cub_quat r = c->rot[(size_t)f * (size_t)jn + (size_t)j];
            pack_quat_to_q14(r, q);
            if (!q30_roughly_unit(r) || !pack_q14_roughly_unit(q)) {
                *err = cub_diag_fail(diag, CUB_ERR_ARG, file, 0,
                                  "clip '%s' frame %d joint %d: not a unit quaternion", lc->name, f,
                                  j);
                return p;
            }
            for (int i = 0; i < 4; i++)
                put_u16(p + 2 * i, (uint16_t)q[i]);
        }
    }
    return p;
}

/* Version 2's clip: the header, the stream's length, the stream. */
static uint8_t *put_keys_clip(uint8_t *p, const cub_library_clip *lc, const cub_keys_result *k)
{
    memset(p, 0, PACK_CLIP_HEADER_BYTES);
    memcpy(p, lc->name, strlen(lc->name));
    memcpy(p + 32, lc->kind, strlen(lc->kind));
    put_u32(p + 48, lc->clip.frame_ns);
    put_u32(p + 52, (uint32_t)lc->clip.frame_count);
    put_u32(p + PACK_CLIP_HEADER_BYTES, (uint32_t)k->len);
    p += PACK_CLIP_HEADER_BYTES + PACK_KEYS_LEN_BYTES;
    memcpy(p, k->data, k->len);
    return p + k->len;
}

static size_t clip_bytes(const cub_library *lib, int i, const cub_keys_result *keys)
{
    if (keys) return PACK_CLIP_HEADER_BYTES + PACK_KEYS_LEN_BYTES + keys[i].len;
    return PACK_CLIP_HEADER_BYTES +
           (size_t)lib->clips[i].clip.frame_count * (12 + 8 * (size_t)lib->skel.joint_count);
}

static cub_err lay_out(const cub_library *lib, const char *file, uint32_t version,
                       const cub_keys_result *keys, uint8_t *buf, size_t size, cub_diag *diag)
{
    cub_err err = CUB_OK;
    uint8_t *p = buf;
    memcpy(p, PACK_MAGIC, 8);
    put_u32(p + 8, version);
    put_u32(p + 12, (uint32_t)lib->skel.joint_count);
    put_u32(p + 16, (uint32_t)lib->clip_count);
    p = put_joints(p + PACK_HEADER_BYTES, &lib->skel);
    for (int i = 0; !err && i < lib->clip_count; i++)
        p = keys ? put_keys_clip(p, &lib->clips[i], &keys[i])
                 : put_clip(p, &lib->clips[i], lib->skel.joint_count, file, diag, &err);
    if (!err) put_u32(p, pack_crc32(buf, size - PACK_CRC_BYTES));
    return err;
}

cub_err pack_encode(const cub_library *lib, const char *file, uint32_t version, uint8_t **out,
                    size_t *out_len, cub_diag *diag)
{
    *out = NULL;
    *out_len = 0;
    if (version != PACK_VERSION_RAW && version != PACK_VERSION_KEYS)
        return cub_diag_fail(diag, CUB_ERR_ARG, file, 0, "no pack version %u", version);
    cub_err err = check_library(lib, file, diag);
    if (err) return err;
    cub_keys_result *keys = NULL;
    if (version == PACK_VERSION_KEYS) {
        keys = calloc((size_t)lib->clip_count + 1, sizeof(*keys));
        if (!keys) return cub_diag_fail(diag, CUB_ERR_NOMEM, file, 0, "out of memory");
        err = pack_keys_encode_all(lib, file, keys, diag);
    }
    size_t size = PACK_HEADER_BYTES + (size_t)lib->skel.joint_count * PACK_JOINT_BYTES +
                  PACK_CRC_BYTES;
    for (int i = 0; !err && i < lib->clip_count; i++)
        size += clip_bytes(lib, i, keys);
    uint8_t *buf = err ? NULL : malloc(size);
    if (!err && !buf)
        err = cub_diag_fail(diag, CUB_ERR_NOMEM, file, 0, "out of memory for %zu bytes", size);
    if (!err) err = lay_out(lib, file, version, keys, buf, size, diag);
    pack_keys_free(keys, lib->clip_count);
    free(keys);
    if (err) {
        free(buf);
        return err;
    }
    *out = buf;
    *out_len = size;
    return CUB_OK;
}

cub_err cub_pack_write(const char *path, const cub_library *lib, cub_diag *diag)
{
    return cub_pack_write_version(path, lib, CUB_PACK_VERSION, diag);
}

cub_err cub_pack_write_version(const char *path, const cub_library *lib, int version,
                               cub_diag *diag)
{
    const char *file = path ? path : "(null)";
    if (!path || !lib) return cub_diag_fail(diag, CUB_ERR_ARG, file, 0, "no path or no library");
    uint8_t *bytes = NULL;
    size_t len = 0;
    cub_err err = pack_encode(lib, file, (uint32_t)version, &bytes, &len, diag);
    if (err) return err;
    FILE *f = fopen(path, "wb");
    if (!f) {
        free(bytes);
        return cub_diag_fail(diag, CUB_ERR_IO, file, 0, "cannot create the file");
    }
    int ok = fwrite(bytes, 1, len, f) == len;
    ok = (fclose(f) == 0) && ok;
    free(bytes);
    return ok ? CUB_OK : cub_diag_fail(diag, CUB_ERR_IO, file, 0, "write failed");
}

int cub_library_find(const cub_library *lib, const char *name)
{
    for (int i = 0; lib && name && i < lib->clip_count; i++)
        if (!strcmp(lib->clips[i].name, name)) return i;
    return -1;
}

void cub_library_free(cub_library *lib)
{
    if (!lib) return;
    free(lib->clips);
    free(lib->mem);
    memset(lib, 0, sizeof(*lib));
}

int pack_name_field_ok(const uint8_t *field, size_t cap)
{
    size_t n = 0;
    while (n < cap && field[n])
        n++;
    if (n == 0 || n == cap) return 0;
    for (size_t i = 0; i < n; i++)
        if (field[i] < 32 || field[i] > 126) return 0;
    for (size_t i = n; i < cap; i++) /* the writer pads with zeros */
        if (field[i]) return 0;
    return 1;
}

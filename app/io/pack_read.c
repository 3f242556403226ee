/* Reading a clip pack (format in cub/pack.h). Pass one walks the headers
 * and checks the shape, the counts against the bytes left and the CRC;
 * pass two decodes the frames. Every read is bounds-checked first, and
 * every problem names the byte offset where it is. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/pack.h"
#include "io_internal.h"
#include "pack_internal.h"

typedef struct pack_reader {
    const uint8_t *data;
    size_t len, pos;
    const char *file;
    cub_diag *diag;
    cub_library *out;
    size_t *clip_at; /* offset of each clip's header, from pass one */
    uint32_t version;
    cub_keys *keys; /* version 2: the stream being checked or decoded */
} pack_reader;

static cub_err bad(const pack_reader *r, size_t at, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static cub_err bad(const pack_reader *r, size_t at, const char *fmt, ...)
{
    char msg[224];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof(msg), fmt, ap);
    va_end(ap);
    return cub_diag_fail(r->diag, CUB_ERR_FORMAT, r->file, 0, "at byte %zu: %s", at, msg);
}

static size_t left(const pack_reader *r)
{
    return r->len - r->pos;
}

static size_t frame_bytes(int joints)
{
    return 12 + 8 * (size_t)joints;
}

/* The fewest bytes a clip of this version takes: its header and one frame,
 * or its header and a stream's length. */
static size_t min_clip_bytes(uint32_t version, int joints)
{
    return PACK_CLIP_HEADER_BYTES +
           (version == PACK_VERSION_RAW ? frame_bytes(joints) : PACK_KEYS_LEN_BYTES);
}

static cub_err read_header(pack_reader *r, uint32_t *joints, uint32_t *clips)
{
    if (r->len < PACK_HEADER_BYTES + PACK_JOINT_BYTES + PACK_CRC_BYTES)
        return bad(r, 0, "only %zu bytes, too short for a clip pack", r->len);
    if (memcmp(r->data, PACK_MAGIC, 8) != 0)
        return bad(r, 0, "not a clip pack (no \"CUBCLIPS\" at the start)");
    uint32_t version = pack_get_u32(r->data + 8);
    *joints = pack_get_u32(r->data + 12);
    *clips = pack_get_u32(r->data + 16);
    if (version != PACK_VERSION_RAW && version != PACK_VERSION_KEYS)
        return bad(r, 8, "version %u; this reader knows versions %u and %u", version,
                   PACK_VERSION_RAW, PACK_VERSION_KEYS);
    r->version = version;
    if (*joints < 1 || *joints > CUB_MOTION_MAX_JOINTS)
        return bad(r, 12, "joint count %u is not in 1..%d", *joints, CUB_MOTION_MAX_JOINTS);
    r->pos = PACK_HEADER_BYTES;
    if (left(r) < PACK_CRC_BYTES + *joints * (size_t)PACK_JOINT_BYTES)
        return bad(r, 12, "%u joints need %zu bytes, only %zu left", *joints,
                   *joints * (size_t)PACK_JOINT_BYTES, left(r) - PACK_CRC_BYTES);
    size_t body = left(r) - PACK_CRC_BYTES - *joints * (size_t)PACK_JOINT_BYTES;
    if (*clips > body / min_clip_bytes(version, (int)*joints))
        return bad(r, 16, "%u clips cannot fit in the %zu bytes left", *clips, body);
    return CUB_OK;
}

static cub_err read_joint(pack_reader *r, int j)
{
    cub_skeleton *skel = &r->out->skel;
    const uint8_t *p = r->data + r->pos;
    if (!pack_name_field_ok(p, CUB_MOTION_NAME_LEN))
        return bad(r, r->pos,
                   "joint %d: the name is not printable, NUL-terminated and "
                   "zero-padded",
                   j);
    const char *name = (const char *)p;
    int parent = pack_get_i16(p + 32);
    if ((j == 0 && parent != -1) || (j > 0 && (parent < 0 || parent >= j)))
        return bad(r, r->pos + 32, "joint %d '%s': parent %d is not %s", j, name, parent,
                   j == 0 ? "-1 (the first joint is the root)" : "an earlier joint");
    if (p[34] > 1 || p[35] != 0)
        return bad(r, r->pos + 34, "joint %d '%s': end-site flag %u / reserved byte %u", j, name,
                   p[34], p[35]);
    if (parent >= 0 && skel->joints[parent].is_end_site)
        return bad(r, r->pos + 32, "joint %d '%s': parent '%s' is an end site", j, name,
                   skel->joints[parent].name);
    if (cub_motion_skeleton_find(skel, name) >= 0)
        return bad(r, r->pos, "joint %d: the name '%s' appears twice", j, name);
    cub_vec3 off = {pack_get_i32(p + 36), pack_get_i32(p + 40), pack_get_i32(p + 44)};
    int index = 0;
    if (cub_motion_skeleton_add(skel, name, parent, off, &index))
        return bad(r, r->pos, "joint %d '%s' cannot be added", j, name);
    skel->joints[index].is_end_site = p[34];
    r->pos += PACK_JOINT_BYTES;
    return CUB_OK;
}

/* Version 1: the frames are all there. */
static cub_err skip_frames(pack_reader *r, int i, const char *name, uint32_t frames)
{
    int jn = r->out->skel.joint_count;
    size_t room = left(r) - PACK_CRC_BYTES;
    if (frames > room / frame_bytes(jn))
        return bad(r, r->pos, "clip %d '%s': %u frames need %.0f bytes, only %zu left", i, name,
                   frames, (double)frames * (double)frame_bytes(jn), room);
    r->pos += frames * frame_bytes(jn);
    return CUB_OK;
}

/* Version 2: the stream is all there, whole and the pack's own. */
static cub_err check_stream(pack_reader *r, int i, const char *name, uint32_t frames,
                            uint32_t frame_ns)
{
    size_t room = left(r) - PACK_CRC_BYTES;
    if (room < PACK_KEYS_LEN_BYTES)
        return bad(r, r->pos, "clip %d '%s': the stream's length is cut off", i, name);
    uint32_t n = pack_get_u32(r->data + r->pos);
    if (n > room - PACK_KEYS_LEN_BYTES)
        return bad(r, r->pos, "clip %d '%s': a stream of %u bytes, only %zu left", i, name, n,
                   room - PACK_KEYS_LEN_BYTES);
    r->pos += PACK_KEYS_LEN_BYTES;
    cub_codec_problem why;
    cub_err err = pack_keys_check(r->data + r->pos, n, &r->out->skel, (int)frames, frame_ns,
                                  r->keys, &why);
    if (err == CUB_ERR_NOMEM)
        return cub_diag_fail(r->diag, err, r->file, 0, "out of memory for a stream");
    if (err)
        return bad(r, r->pos + why.offset, "clip %d '%s': cubkeys stream: %s", i, name, why.what);
    r->pos += n;
    return CUB_OK;
}

/* Pass one over clip i: its header, and that its frames are all there. */
static cub_err scan_clip(pack_reader *r, int i, size_t *mem_total)
{
    const uint8_t *p = r->data + r->pos;
    if (left(r) < PACK_CLIP_HEADER_BYTES + PACK_CRC_BYTES)
        return bad(r, r->pos, "clip %d: the header is cut off", i);
    if (!pack_name_field_ok(p, CUB_MOTION_NAME_LEN) ||
        !pack_name_field_ok(p + 32, CUB_PACK_KIND_LEN))
        return bad(r, r->pos,
                   "clip %d: the name or kind is not printable, NUL-terminated and "
                   "zero-padded",
                   i);
    const char *name = (const char *)p;
    uint32_t frame_ns = pack_get_u32(p + 48), frames = pack_get_u32(p + 52);
    if (frame_ns == 0 || frames == 0 || frames > INT32_MAX)
        return bad(r, r->pos + 48, "clip %d '%s': frame period %u ns, %u frames", i, name, frame_ns,
                   frames);
    for (int k = 0; k < i; k++)
        if (!strcmp((const char *)r->data + r->clip_at[k], name))
            return bad(r, r->pos, "clip %d: the name '%s' appears twice", i, name);
    r->clip_at[i] = r->pos;
    r->pos += PACK_CLIP_HEADER_BYTES;
    cub_err err = r->version == PACK_VERSION_RAW ? skip_frames(r, i, name, frames)
                                                 : check_stream(r, i, name, frames, frame_ns);
    if (err) return err;
    int jn = r->out->skel.joint_count;
    size_t need = (cub_motion_clip_mem_size(jn, (int)frames, 0) + 7) & ~(size_t)7;
    *mem_total += need;
    if (*mem_total > IO_MEM_CAP_BYTES)
        return bad(r, r->clip_at[i], "the clips need over %zu MB", IO_MEM_CAP_BYTES >> 20);
    return CUB_OK;
}

static cub_err check_crc(pack_reader *r)
{
    if (left(r) != PACK_CRC_BYTES)
        return bad(r, r->pos, "expected the 4-byte CRC to end the file, found %zu bytes", left(r));
    uint32_t stored = pack_get_u32(r->data + r->pos);
    uint32_t computed = pack_crc32(r->data, r->pos);
    if (stored != computed)
        return bad(r, r->pos,
                   "CRC mismatch: stored 0x%08x, computed 0x%08x (the file is "
                   "damaged)",
                   stored, computed);
    return CUB_OK;
}

/* Version 2: every frame of the stream at p (its length first), checked
 * in pass one, into the clip. */
static cub_err decode_stream(pack_reader *r, cub_library_clip *lc, const uint8_t *p)
{
    cub_skeleton *own = malloc(sizeof(*own));
    cub_pose *pose = malloc(sizeof(*pose));
    cub_err err = own && pose ? CUB_OK : CUB_ERR_NOMEM;
    if (!err) err = cub_keys_open(p + PACK_KEYS_LEN_BYTES, pack_get_u32(p), own, r->keys, NULL);
    for (int f = 0; !err && f < lc->clip.frame_count; f++) {
        err = cub_keys_pose(r->keys, f, pose);
        if (!err) err = cub_motion_clip_set_frame(&lc->clip, f, pose);
    }
    free(own);
    free(pose);
    if (err == CUB_ERR_NOMEM)
        return cub_diag_fail(r->diag, err, r->file, 0, "out of memory decoding '%s'", lc->name);
    return err ? bad(r, (size_t)(p - r->data), "clip '%s': cannot decode", lc->name) : CUB_OK;
}

/* Pass two over clip i: lay out its frames in mem and decode them. */
static cub_err decode_clip(pack_reader *r, int i, uint8_t *mem, size_t size)
{
    cub_library_clip *lc = &r->out->clips[i];
    const cub_skeleton *skel = &r->out->skel;
    int jn = skel->joint_count;
    size_t at = r->clip_at[i];
    const uint8_t *p = r->data + at;
    memcpy(lc->name, p, CUB_MOTION_NAME_LEN);
    memcpy(lc->kind, p + 32, CUB_PACK_KIND_LEN);
    int frames = (int)pack_get_u32(p + 52);
    if (cub_motion_clip_init(&lc->clip, skel, frames, pack_get_u32(p + 48), 0, mem, size))
        return bad(r, at, "clip %d '%s': cannot lay out %d frames", i, lc->name, frames);
    p += PACK_CLIP_HEADER_BYTES;
    if (r->version == PACK_VERSION_KEYS) return decode_stream(r, lc, p);
    for (int f = 0; f < frames; f++) {
        lc->clip.root_mm[f] = (cub_vec3){pack_get_i32(p), pack_get_i32(p + 4), pack_get_i32(p + 8)};
        p += 12;
        for (int j = 0; j < jn; j++, p += 8) {
            int16_t q[4] = {pack_get_i16(p), pack_get_i16(p + 2), pack_get_i16(p + 4),
                            pack_get_i16(p + 6)};
            if (q[0] < 0 || !pack_q14_roughly_unit(q))
                return bad(r, (size_t)(p - r->data),
                           "clip '%s' frame %d joint '%s': quaternion (%d %d %d %d) is not a "
                           "unit quaternion with w >= 0",
                           lc->name, f, skel->joints[j].name, q[0], q[1], q[2], q[3]);
            lc->clip.rot[(size_t)f * (size_t)jn + (size_t)j] = pack_q14_to_quat(q);
        }
    }
    return CUB_OK;
}

static cub_err read_all(pack_reader *r)
{
    uint32_t joints = 0, clips = 0;
    cub_err err = read_header(r, &joints, &clips);
    for (uint32_t j = 0; !err && j < joints; j++)
        err = read_joint(r, (int)j);
    if (err) return err;
    size_t mem_total = 0;
    r->clip_at = calloc(clips ? clips : 1, sizeof(size_t));
    r->out->clips = calloc(clips ? clips : 1, sizeof(cub_library_clip));
    if (!r->clip_at || !r->out->clips)
        return cub_diag_fail(r->diag, CUB_ERR_NOMEM, r->file, 0, "out of memory for %u clips", clips);
    for (uint32_t i = 0; !err && i < clips; i++)
        err = scan_clip(r, (int)i, &mem_total);
    if (!err) err = check_crc(r);
    if (err) return err;
    r->out->mem = malloc(mem_total ? mem_total : 1);
    if (!r->out->mem)
        return cub_diag_fail(r->diag, CUB_ERR_NOMEM, r->file, 0, "out of memory for %zu bytes",
                          mem_total);
    size_t off = 0;
    for (uint32_t i = 0; !err && i < clips; i++) {
        int frames = (int)pack_get_u32(r->data + r->clip_at[i] + 52);
        size_t size = (cub_motion_clip_mem_size((int)joints, frames, 0) + 7) & ~(size_t)7;
        err = decode_clip(r, (int)i, (uint8_t *)r->out->mem + off, size);
        off += size;
    }
    r->out->clip_count = (int)clips;
    return err;
}

cub_err cub_pack_parse(const void *data, size_t len, const char *name, cub_library *out,
                       cub_diag *diag)
{
    const char *file = name ? name : "(memory)";
    if (!out || (!data && len))
        return cub_diag_fail(diag, CUB_ERR_ARG, file, 0, "no data or no output");
    memset(out, 0, sizeof(*out));
    cub_motion_skeleton_reset(&out->skel);
    pack_reader r = {data, len, 0, file, diag, out, NULL, 0, malloc(sizeof(cub_keys))};
    cub_err err = r.keys ? read_all(&r)
                         : cub_diag_fail(diag, CUB_ERR_NOMEM, file, 0, "out of memory");
    free(r.clip_at);
    free(r.keys);
    if (err) cub_library_free(out);
    return err;
}

static cub_err parse_bytes(const cub_text *t, const void *in, void *out)
{
    return cub_pack_parse(t->s, t->len, t->name, out, t->diag);
}

cub_err cub_pack_read(const char *path, cub_library *out, cub_diag *diag)
{
    if (out) memset(out, 0, sizeof(*out));
    return cub_text_load(&(cub_text_src){path, "clip pack", CUB_TEXT_MAX_CLIPS}, parse_bytes, NULL, out, diag);
}

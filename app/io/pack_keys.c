/* Version 2 of the clip pack: each clip's frames are a cubkeys stream
 * (cub/codec.h), encoded within 0.01 cm at ACL's virtual vertices. The
 * stream carries its own skeleton; the pack's joint table stays the one the
 * box reads, and every stream must agree with it exactly. */
#include <stdlib.h>
#include <string.h>

#include "io_internal.h"
#include "pack_internal.h"

void pack_keys_free(cub_keys_result *streams, int count)
{
    for (int i = 0; streams && i < count; i++) {
        free(streams[i].data);
        streams[i].data = NULL;
    }
}

cub_err pack_keys_encode_all(const cub_library *lib, const char *file, cub_keys_result *streams,
                             cub_diag *diag)
{
    for (int i = 0; i < lib->clip_count; i++) {
        cub_err err = cub_keys_encode(&lib->clips[i].clip, PACK_KEYS_BOUND_MM, &streams[i]);
        if (err) {
            pack_keys_free(streams, i);
            return cub_diag_fail(diag, err, file, 0, "clip '%s': the cubkeys encoder refused it",
                                 lib->clips[i].name);
        }
    }
    return CUB_OK;
}

static int same_joint(const cub_joint *a, const cub_joint *b)
{
    return a->parent == b->parent && a->is_end_site == b->is_end_site &&
           a->offset_mm.x == b->offset_mm.x && a->offset_mm.y == b->offset_mm.y &&
           a->offset_mm.z == b->offset_mm.z && !strcmp(a->name, b->name);
}

cub_err pack_keys_check(const uint8_t *data, size_t len, const cub_skeleton *skel, int frames,
                        uint32_t frame_ns, cub_keys *k, cub_codec_problem *why)
{
    static const cub_codec_problem shape = {"the stream's joints, frames or period are not "
                                            "the pack's",
                                            0};
    if (why) *why = (cub_codec_problem){NULL, 0};
    cub_skeleton *own = malloc(sizeof(*own));
    if (!own) return CUB_ERR_NOMEM;
    cub_err err = cub_keys_open(data, len, own, k, why);
    if (!err && (own->joint_count != skel->joint_count || k->frame_count != frames ||
                 k->frame_ns != frame_ns || k->has_trans))
        err = CUB_ERR_FORMAT;
    for (int j = 0; !err && j < skel->joint_count; j++)
        if (!same_joint(&own->joints[j], &skel->joints[j])) err = CUB_ERR_FORMAT;
    if (err == CUB_ERR_FORMAT && why && !why->what) *why = shape;
    free(own);
    return err;
}

/* codec_host — the cubtool side of the seed's codec (cub/codec.h): encode a
 * clip into a heap stream, decode one into a heap clip, load a clip to
 * encode from a BVH or a clip library, with errors naming the file. */
#ifndef CUB_CUBTOOL_CODEC_HOST_H
#define CUB_CUBTOOL_CODEC_HOST_H

#include <stddef.h>
#include <stdint.h>

#include "cub/codec.h"
#include "cub/io.h"
#include "cub/pack.h"

typedef struct codec_blob {
    uint8_t *data;
    size_t len;
} codec_blob;

typedef struct codec_decoded {
    cub_skeleton *skel;
    cub_clip clip;
    void *mem;
} codec_decoded;

/* A clip loaded from a BVH (motion) or a library (lib, clip by name). */
typedef struct codec_source {
    cub_io_motion motion;
    cub_library lib;
    int from_lib;
    const cub_clip *clip;
} codec_source;

/* Encode clip with the effectors cub_codec_pick_effectors finds. 0 ok. */
int codec_host_encode(const cub_clip *clip, codec_blob *out, const char *name);
/* Decode a stream; on refusal print "name: byte N: what". 0 ok. */
int codec_host_decode(const codec_blob *in, const cub_codec_opts *opts, codec_decoded *out,
                      const char *name);
void codec_decoded_free(codec_decoded *d);
/* The same with our error-bounded codec (cubkeys) within bound_mm. */
int codec_host_encode_keys(const cub_clip *clip, double bound_mm, codec_blob *out, const char *name);
int codec_host_decode_keys(const codec_blob *in, codec_decoded *out, const char *name);
/* Load path (a .bvh, or a .cubclips with clip_name). 0 ok. */
int codec_source_load(const char *path, const char *clip_name, codec_source *src);
void codec_source_free(codec_source *src);
/* Read a .cubseed file whole (free out->data). 0 ok. */
int codec_blob_read(const char *path, codec_blob *out);
/* Raw size as ACL counts it: 10 float32 per bone per sample. */
double codec_raw_bytes(const cub_clip *clip);

#endif

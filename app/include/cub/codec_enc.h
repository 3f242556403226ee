/* codec_enc — the encoder of the error-bounded clip stream (cubkeys,
 * cub/codec.h), on the host: cubtool, the tests and the benchmarks.
 *
 * The bound is ACL's measure: the distance between the source's and the
 * decoded pose's virtual vertices, 30 mm from each bone along its three
 * axes, in object space, every bone (end sites are not bones) and every
 * frame. The encoder gives each track a share of the bound (rotations by
 * the length of the chain they swing), keeps per track the fewest keys and
 * bits that hold its share, then decodes the stream with the box's own
 * decoder and measures; it scales the shares until the largest measured
 * error is within the bound. Heap, doubles: not firmware. */
#ifndef CUB_CODEC_ENC_H
#define CUB_CODEC_ENC_H

#include <stddef.h>
#include <stdint.h>

#include "cub/err.h"
#include "cub/motion.h"

#define CUB_KEYS_SHELL_MM 30.0 /* ACL's virtual vertex distance, 3 cm */

typedef struct cub_keys_result {
    uint8_t *data; /* the stream (heap; free it) */
    size_t len;
    double max_err_mm; /* the largest vertex error measured on the decoded stream */
    int trials;        /* encodings tried */
} cub_keys_result;

/* Encode clip within bound_mm (> 0). CUB_ERR_ARG for a bad clip or bound,
 * CUB_ERR_NOMEM. */
cub_err cub_keys_encode(const cub_clip *clip, double bound_mm, cub_keys_result *out);
/* The largest virtual-vertex error (mm) of an opened stream against clip. */
double cub_keys_max_error(const cub_clip *clip, const void *data, size_t len);

#endif

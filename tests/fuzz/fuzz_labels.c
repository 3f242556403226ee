/* libFuzzer target: hand labels of real frames (cub_ft_labels_parse,
 * tests/labels/skeltrack_labels.txt's format) as eval-forest --labels
 * reads them. Seeds: tests/labels/. Whatever the bytes: no crash; a
 * refusal names a line; every label kept is a joint and a pixel in the
 * image (or not in view). */
#include <stdint.h>
#include <stdlib.h>

#include "cub/forest_train.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static cub_ft_labels lab;
    cub_diag diag = {0};
    cub_err e = cub_ft_labels_parse((const char *)data, size, "fuzz", &lab, &diag);
    if (e && (e != CUB_ERR_FORMAT || diag.line < 1)) abort();
    if (e) return 0;
    for (int k = 0; k < lab.n; k++) {
        const cub_ft_label *l = &lab.l[k];
        if (l->joint < 0 || l->joint >= CUB_KJ_COUNT) abort();
        if (l->u >= CUB_KINECT_WIDTH || l->v >= CUB_KINECT_HEIGHT || (l->u < 0) != (l->v < 0))
            abort();
    }
    return 0;
}

/* libFuzzer target: a body-part forest asset (cub/forest.h) as the box will
 * load it, then every pixel of a small depth image (made from the input's
 * first bytes) classified by it. Seeds: seeds_forest/ (make_seeds.py).
 * Whatever the bytes: no crash, no read past the asset, a refusal always
 * has a reason and an offset inside it, and a class within the forest's. */
#include <stdint.h>
#include <stdlib.h>

#include "cub/forest.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define IW 24
#define IH 18

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    cub_forest f;
    cub_forest_problem why = {0};
    cub_err e = cub_forest_open(data, size, &f, &why);
    if (e == CUB_ERR_FORMAT && (!why.what || why.offset > size)) abort();
    if (e) return 0;
    static uint16_t mm[IW * IH];
    for (int i = 0; i < IW * IH; i++) /* a body of the input's bytes, some holes */
        mm[i] = (uint16_t)(data[i % size] * 16 * (i % 7 != 0));
    cub_forest_image im = {mm, IW, IH};
    uint32_t score[CUB_FOREST_MAX_CLASSES];
    for (int y = 0; y < IH; y++)
        for (int x = 0; x < IW; x++) {
            int c = cub_forest_classify(&f, &im, x, y, score);
            if (c < 0 || c >= f.classes) abort();
        }
    return 0;
}

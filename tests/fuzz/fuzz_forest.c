/* libFuzzer target: a body-part forest asset (cub/forest.h) as the box will
 * load it, then every pixel of a small depth image (made from the input's
 * first bytes) classified by it. Seeds: seeds_forest/ (make_seeds.py).
 * Whatever the bytes: no crash, no read past the asset, a refusal always
 * has a reason and an offset inside it, a class within the forest's, and
 * part proposals from those pixels within their bounds. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

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
    /* the part proposals over the same pixels: every class, a mode inside
     * the points' box, a share within [0, 1] */
    static int32_t pmm[IW * IH][3];
    static uint16_t prob[IW * IH * CUB_FOREST_MAX_CLASSES];
    static int32_t list[IW * IH];
    cub_forest_points pts = {pmm, prob, 0, IW * IH, f.classes, 1, NULL};
    cub_forest_gather(&f, &im, 1 + data[0] % 3, &pts);
    for (int c = 0; c < f.classes; c++) {
        cub_forest_shift sh = {1 + data[size - 1] * 4, (uint16_t)(data[c % size] * 64), 50};
        cub_forest_proposal pr, listed;
        pts.part_pts = NULL;
        cub_forest_propose(&pts, c, &sh, &pr);
        if (pr.found && (pr.share < 0 || pr.share > 65536 || pr.area_mm2 < 0)) abort();
        pts.part_pts = list; /* the part's points listed: the same proposal */
        cub_forest_propose(&pts, c, &sh, &listed);
        if (memcmp(&pr, &listed, sizeof(pr)) != 0) abort();
    }
    return 0;
}

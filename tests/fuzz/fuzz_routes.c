/* libFuzzer target: the bridge planner's searched routes (cub/routes.h,
 * app/io/routes.c; assets/clips/bear.routes.txt) against a fixed library
 * of the shipped clip names, 130 frames each. Seeds: seeds_routes/. A file
 * that parses holds routes the bridge table takes: clips and frames in
 * range, in < out, from != to, one route per pair, finite alignments;
 * every failure names the file and a line or the whole. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cub/routes.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define FRAMES 130
static const char *const NAMES[] = {"twist", "kick", "squat", "clap", "side_kick",
                                    "bird_flying", "sway", "swing"};
#define CLIPS ((int)(sizeof NAMES / sizeof *NAMES))

static int route_ok(const cub_routes *r, int i)
{
    const cub_bridge_route *q = &r->route[i];
    int ok = q->from >= 0 && q->from < CLIPS && q->to >= 0 && q->to < CLIPS && q->via >= 0 &&
             q->via < CLIPS && q->from != q->to && q->a >= 0 && q->a < FRAMES && q->in >= 0 &&
             q->in < q->out && q->out < FRAMES && q->b >= 0 && q->b < FRAMES;
    for (int k = 0; k < 3; k++)
        ok = ok && isfinite(r->align[i][k]);
    for (int j = 0; j < i; j++)
        ok = ok && !(r->route[j].from == q->from && r->route[j].to == q->to);
    return ok;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static cub_library_clip clips[CLIPS];
    for (int c = 0; c < CLIPS; c++) {
        strcpy(clips[c].name, NAMES[c]);
        clips[c].clip.frame_count = FRAMES;
    }
    cub_library lib = {.clip_count = CLIPS, .clips = clips};
    char *text = malloc(size + 1);
    if (!text) return 0;
    memcpy(text, data, size);
    text[size] = 0;
    static cub_routes r;
    cub_diag d = {0};
    cub_err e = cub_routes_parse(text, size, "fuzz.routes.txt", &lib, &r, &d);
    free(text);
    if (e) {
        if (!d.msg[0] || strcmp(d.file, "fuzz.routes.txt")) abort();
        return 0;
    }
    if (r.count < 0 || r.count > CUB_ROUTES_MAX) abort();
    for (int i = 0; i < r.count; i++)
        if (!route_ok(&r, i)) abort();
    return 0;
}

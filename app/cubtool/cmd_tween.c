/* cubtool tween — the seed's tween clip (SEEDS.md § 000, "Switching"),
 * built from the shipped library's bridge frames as the planner builds it
 * (cub/bridge.h, "the tween clip"; cub_coachlib_add_tween), written as a
 * BVH on the bear's skeleton so that other tools can load it, with its
 * keys listed on stdout. */
#include <stdio.h>
#include <stdlib.h>

#include "commands.h"
#include "cub/coachlib.h"
#include "tool_util.h"

static int usage(FILE *f, int code)
{
    fprintf(f,
            "usage: cubtool tween [--assets DIR] [--cover D] [--speed MM] [--out FILE.bvh]\n"
            "  Build the seed's tween: one looping clip through the library's bridge\n"
            "  frames (keys at least D apart in fuzzy distance, default half the\n"
            "  threshold), eased legs keeping the fastest joint within MM per frame\n"
            "  (default %d). Lists its keys; --out writes one loop as BVH (cm).\n",
            CUB_BRIDGE_TWEEN_SPEED_MM >> 16);
    return code;
}

int cub_cmd_tween(int argc, char **argv)
{
    const char *assets = CUB_ASSETS_DIR, *out = NULL, *cover = NULL, *speed = NULL;
    const cub_tool_opt opts[] = {{"--assets", &assets, NULL},
                                 {"--out", &out, NULL},
                                 {"--cover", &cover, NULL},
                                 {"--speed", &speed, NULL}};
    cub_tool_parsed p = cub_tool_parse_opts(argc, argv, opts, 4, NULL, 0);
    if (p == CUB_TOOL_HELP) return usage(stdout, 0);
    if (p == CUB_TOOL_BAD) return usage(stderr, 2);
    cub_bridge_tween_config cfg = {0};
    if (cover) cfg.cover_d = (cub_q16)(atof(cover) * 65536.0);
    if (speed) cfg.speed_mm = CUB_Q16_INT(atoi(speed));
    if (cfg.cover_d < 0 || cfg.cover_d > CUB_Q16_ONE || (speed && cfg.speed_mm <= 0) ||
        cfg.speed_mm > CUB_Q16_INT(1000))
        return usage(stderr, 2);
    static cub_coachlib cl;
    cub_diag d = {0};
    char buf[600];
    if (cub_coachlib_load_assets(assets, &cl, &d) || cub_coachlib_add_tween(&cl, &cfg, &d)) {
        fprintf(stderr, "tween: %s\n", cub_diag_str(&d, buf, sizeof buf));
        cub_coachlib_free(&cl);
        return 1;
    }
    const cub_bridge_tween *tw = &cl.tween;
    printf("tween: %d keys, %d frames (%.1f s a loop)\n", tw->key_count, tw->frame_count,
           tw->frame_count / 30.0);
    for (int k = 0; k < tw->key_count; k++)
        printf("  key %2d at frame %4d: %s@%d\n", k, tw->key_at[k],
               cl.lib.clips[tw->key_clip[k]].name, tw->key_frame[k]);
    int rc = out && cub_tool_save_clip_bvh(&cl.lib.skel, &cl.tween_clip, out) ? 1 : 0;
    if (out && !rc) fprintf(stderr, "tween: wrote %s\n", out);
    cub_coachlib_free(&cl);
    return rc;
}

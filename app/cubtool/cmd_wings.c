/* cubtool wings — the winged bear's assets, rebuilt (issue 22,
 * docs/evolve.md): `cubtool evolve` with the one recipe the box's
 * bird_flying uses. The bear's bird_flying (parent 1) crossed with our
 * bird's flapping (parent 2, assets/keys/bird_flap.keys on
 * assets/bird/bird.xml); one mutation, the bird's tail weighted out (the
 * seed's horn example: a bear with two wings); x = 0, so the bear's joints
 * keep the library's motion exactly and the wings take the bird's. */
#include <stdio.h>
#include <string.h>

#include "commands.h"

#define PATH_LEN 1024

static void usage(FILE *f)
{
    fprintf(f, "usage: cubtool wings [--assets DIR] [--out-dir DIR]\n"
               "\n"
               "Rebuilds the winged bear: DIR/bear/bear_winged.xml (the child character)\n"
               "and DIR/bear/bird_flying.wings.bvh (its clip), from the shipped assets\n"
               "(default %s) through `cubtool evolve`; --out-dir writes them elsewhere.\n",
               CUB_ASSETS_DIR);
}

int cub_cmd_wings(int argc, char **argv)
{
    const char *assets = CUB_ASSETS_DIR, *out_dir = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--assets") && i + 1 < argc)
            assets = argv[++i];
        else if (!strcmp(argv[i], "--out-dir") && i + 1 < argc)
            out_dir = argv[++i];
        else {
            usage(strcmp(argv[i], "--help") ? stderr : stdout);
            return strcmp(argv[i], "--help") ? 2 : 0;
        }
    }
    static char p1[PATH_LEN], p2[PATH_LEN], c1[PATH_LEN], bvh[PATH_LEN], xml[PATH_LEN],
        dir[PATH_LEN];
    snprintf(dir, sizeof dir, "%s", out_dir ? out_dir : assets);
    if (!out_dir) strncat(dir, "/bear", sizeof dir - strlen(dir) - 1);
    snprintf(p1, sizeof p1, "%s/clips/bear.cubclips:bird_flying", assets);
    snprintf(p2, sizeof p2, "%s/bird/bird.xml:%s/keys/bird_flap.keys", assets, assets);
    snprintf(c1, sizeof c1, "%s/bear/bear.xml", assets);
    snprintf(bvh, sizeof bvh, "%s/bird_flying.wings.bvh", dir);
    snprintf(xml, sizeof xml, "%s/bear_winged.xml", dir);
    char *args[] = {"evolve", p1, p2, "--mutations", "1", "--weight", "Tail=-2", "--blend", "0",
                    "--character1", c1, "--out", bvh, "--out-character", xml};
    return cub_cmd_evolve((int)(sizeof args / sizeof *args), args);
}

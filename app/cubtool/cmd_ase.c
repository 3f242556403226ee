/* cubtool ase-export — a clip (.bvh, .asf + .amc, or .ase) written as a
 * 3ds Max ASCII export (cub/ase.h), for the player and the round trip. */
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "cub/ase.h"
#include "cub/retarget.h"

static int ends_with(const char *s, const char *tail)
{
    size_t n = strlen(s), m = strlen(tail);
    return n >= m && !strcmp(s + n - m, tail);
}

static const char usage[] = "usage: cubtool ase-export CLIP.bvh|CLIP.ase|SKEL.asf MOTION.amc OUT.ase\n";

int cub_cmd_ase_export(int argc, char **argv)
{
    if (argc == 2 && !strcmp(argv[1], "--help")) {
        printf("%sRead a clip (BVH, ASF + AMC, or ASE) and write it as a 3ds Max ASCII\n"
               "export in mm: rest transforms from frame 0, a position track for the\n"
               "root, a rotation track per bone (the first sample relative to the\n"
               "parent, each later one to the previous frame). A bad file is refused\n"
               "as file:line: why.\n",
               usage);
        return 0;
    }
    int amc = argc == 4;
    if (argc != 3 && !(amc && ends_with(argv[1], ".asf"))) {
        fprintf(stderr, "%s", usage);
        return 2;
    }
    static cub_io_motion m;
    cub_diag d = {0};
    char msg[600];
    cub_err err = ends_with(argv[1], ".ase")
                      ? cub_ase_load(argv[1], NULL, &m, &d)
                      : cub_retarget_load_source(argv[1], amc ? argv[2] : NULL, &m, &d);
    if (!err) err = cub_ase_save(argv[argc - 1], &m, &d);
    if (err) fprintf(stderr, "cubtool ase-export: %s\n", cub_diag_str(&d, msg, sizeof msg));
    else
        printf("ase-export: %s: %d joints, %d frames\n", argv[argc - 1], m.skel.joint_count,
               m.clip.frame_count);
    cub_io_motion_free(&m);
    return err ? 1 : 0;
}

/* cubtool trc-info — what a TRC marker file holds (cub/trc.h), as the box's
 * reader sees it: markers, frames, rate, how many marker-frames are lost. */
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "cub/trc.h"

int cub_cmd_trc_info(int argc, char **argv)
{
    if (argc == 2 && !strcmp(argv[1], "--help")) {
        printf("usage: cubtool trc-info FILE.trc\n"
               "Read a TRC marker file and print its markers, frames, frame rate and\n"
               "the marker-frames it lost; a bad file is refused as file:line: why.\n");
        return 0;
    }
    if (argc != 2) {
        fprintf(stderr, "usage: cubtool trc-info FILE.trc\n");
        return 2;
    }
    cub_trc t;
    cub_diag d = {0};
    char msg[600];
    if (cub_trc_load(argv[1], &t, &d)) {
        fprintf(stderr, "cubtool trc-info: %s\n", cub_diag_str(&d, msg, sizeof msg));
        cub_trc_free(&t);
        return 1;
    }
    long lost = 0;
    for (long i = 0; i < (long)t.frames * t.markers; i++)
        lost += !t.present[i];
    printf("markers %d\nframes %d\nrate %g\nlost %ld\n", t.markers, t.frames, t.rate, lost);
    for (int m = 0; m < t.markers; m++)
        printf("marker %d %s\n", m + 1, t.names[m]);
    cub_trc_free(&t);
    return 0;
}

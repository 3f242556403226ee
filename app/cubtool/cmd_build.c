/* Placeholder so the tree builds while `cubtool build` is being written;
 * replaced by the real command. */
#include <stdio.h>

#include "commands.h"

int cub_cmd_build(int argc, char **argv)
{
    fprintf(stderr, "cubtool build: not available in this build yet\n");
    return 1;
}

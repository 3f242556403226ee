/* Placeholder so the tree builds while `cubtool retarget` is being written;
 * replaced by the real command. */
#include <stdio.h>

#include "commands.h"

int cub_cmd_retarget(int argc, char **argv)
{
    fprintf(stderr, "cubtool retarget: not available in this build yet\n");
    return 1;
}

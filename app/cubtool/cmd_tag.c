/* Placeholder so the tree builds while `cubtool tag` is being written;
 * replaced by the real command. */
#include <stdio.h>

#include "commands.h"

int cub_cmd_tag(int argc, char **argv)
{
    fprintf(stderr, "cubtool tag: not available in this build yet\n");
    return 1;
}

/* cubtool retarget's option parser for fuzz_cli: the command's file is
 * compiled in here, whole, so its static parser is fuzzed as it is. */
#include "../../app/cubtool/cmd_retarget.c"

int cub_fuzz_cli_retarget(int argc, char **argv);

int cub_fuzz_cli_retarget(int argc, char **argv)
{
    retarget_args a;
    return parse_args(argc, argv, &a);
}

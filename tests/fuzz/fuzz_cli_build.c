/* cubtool build's option parser for fuzz_cli: the command's file is
 * compiled in here, whole, so its static parser is fuzzed as it is. */
#include "../../app/cubtool/cmd_build.c"

int cub_fuzz_cli_build(int argc, char **argv);

int cub_fuzz_cli_build(int argc, char **argv)
{
    build_args a;
    return parse_args(argc, argv, &a);
}

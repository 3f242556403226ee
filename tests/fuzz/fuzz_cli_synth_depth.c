/* cubtool synth-depth's option parser for fuzz_cli: the command's file is
 * compiled in here, whole, so its static parser is fuzzed as it is. */
#include "../../app/cubtool/cmd_synth_depth.c"

int cub_fuzz_cli_synth_depth(int argc, char **argv);

int cub_fuzz_cli_synth_depth(int argc, char **argv)
{
    opts o = {.d = {.seed = 1}};
    for (int i = 1; i < argc; i++)
        if (!parse_opt(&o, argc, argv, &i)) return 2;
    return 0;
}

/* cubtool bench-codec — our codecs against ACL on the same clips: runs the
 * benchmark program tests/bench/bench_codec_vs with the same options. ACL
 * is a peer that only that benchmark includes (built when ../shared/peers/acl
 * exists), so cubtool itself never links it. */
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "commands.h"

int cub_cmd_bench_codec(int argc, char **argv)
{
#ifdef CUB_BENCH_CODEC_VS
    const char *exe = CUB_BENCH_CODEC_VS;
    if (access(exe, X_OK) == 0) {
        argv[0] = (char *)exe;
        fflush(stdout);
        execv(exe, argv);
        perror(exe);
        return 1;
    }
    fprintf(stderr,
            "cubtool bench-codec: %s is not built: cmake --build --preset release "
            "--target bench_codec_vs\n",
            exe);
#else
    fprintf(stderr, "cubtool bench-codec: this tree has no tests/bench (bench_codec_vs)\n");
#endif
    (void)argc;
    return 2;
}

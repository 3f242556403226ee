/* bench_codec_vs without ACL: ../shared/peers/acl was not there at build time. */
#include "codec_vs.h"

int vs_acl_codec(vs_codec *out)
{
    (void)out;
    return -1;
}

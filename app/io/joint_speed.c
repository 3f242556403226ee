/* The clip library's joint speeds (cub/pack.h): the yardstick for the
 * motion the box makes itself (the groove, its bridges). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cub/pack.h"

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static size_t speed_count(const cub_library *lib)
{
    size_t n = 0;
    for (int c = 0; c < lib->clip_count; c++)
        if (lib->clips[c].clip.frame_count > 1)
            n += (size_t)(lib->clips[c].clip.frame_count - 1) * (size_t)lib->skel.joint_count;
    return n;
}

/* Every joint's speed from frame f - 1 (prev) to f (now) of clip, into v. */
static size_t clip_speeds(const cub_library *lib, const cub_clip *clip, double *v)
{
    static cub_pose pose;
    static cub_vec3 now[CUB_MOTION_MAX_JOINTS], prev[CUB_MOTION_MAX_JOINTS];
    size_t n = 0;
    for (int f = 0; f < clip->frame_count; f++) {
        cub_motion_clip_get_frame(clip, f, &pose);
        cub_motion_forward(&lib->skel, &pose, now, NULL);
        for (int j = 0; f > 0 && j < lib->skel.joint_count; j++) {
            const double dx = (now[j].x - prev[j].x) / 65536.0, dy = (now[j].y - prev[j].y) / 65536.0,
                         dz = (now[j].z - prev[j].z) / 65536.0;
            v[n++] = sqrt(dx * dx + dy * dy + dz * dz) * 1e9 / clip->frame_ns;
        }
        memcpy(prev, now, sizeof now);
    }
    return n;
}

double cub_library_joint_speed_pct(const cub_library *lib, double q)
{
    const size_t total = speed_count(lib);
    if (!total) return 0;
    double *v = malloc(total * sizeof *v);
    if (!v) return -1;
    size_t n = 0;
    for (int c = 0; c < lib->clip_count; c++) n += clip_speeds(lib, &lib->clips[c].clip, v + n);
    qsort(v, n, sizeof *v, cmp_double);
    const size_t i = (size_t)(q * (double)n + 0.999999);
    const double pct = v[i ? (i > n ? n - 1 : i - 1) : 0];
    free(v);
    return pct;
}

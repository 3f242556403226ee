/* fakenect_nosleep — for tests that replay under `--clock virtual` (the
 * soak, the scenarios, scripts/e2e_child.sh): a library loaded
 * with LD_PRELOAD whose sleep and usleep return at once. fakenect paces a
 * replay by sleeping on the wall clock until each frame's recorded time;
 * under `--clock virtual` the box already hands each frame out at its
 * recorded time on the loop's own clock (board/common/depth_freenect.c), so
 * those sleeps only hold box time to real time (the same event log, two to
 * four times slower). Never preloaded into a real-clock run. Nothing
 * else in the box calls sleep or usleep (the board sleeps with
 * clock_nanosleep, and not at all under the virtual clock). */
#define _DEFAULT_SOURCE /* usleep */
#include <unistd.h>

#define EXPORT __attribute__((visibility("default")))

EXPORT unsigned int sleep(unsigned int seconds)
{
    (void)seconds;
    return 0;
}

EXPORT int usleep(useconds_t us)
{
    (void)us;
    return 0;
}

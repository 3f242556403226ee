#include "replay.h"

#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#ifndef CUB_FAKENECT_DIR
#define CUB_FAKENECT_DIR "/usr/lib/fakenect"
#endif

static int same_dir(const char *a, const char *b)
{
    char ra[PATH_MAX], rb[PATH_MAX];
    if (!realpath(a, ra) || !realpath(b, rb)) return 0;
    return strcmp(ra, rb) == 0;
}

int cub_replay_prepare(const char *dir, char **argv, FILE *err)
{
    char index[PATH_MAX];
    struct stat st;
    snprintf(index, sizeof index, "%s/INDEX.txt", dir);
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        fprintf(err, "cubdance: --replay %s: no such directory\n", dir);
        return -1;
    }
    if (stat(index, &st) != 0) {
        if (errno == ENOENT)
            fprintf(err, "cubdance: --replay %s: not a fakenect dump (no INDEX.txt)\n", dir);
        else
            fprintf(err, "cubdance: --replay %s: cannot open INDEX.txt: %s\n", dir, strerror(errno));
        return -1;
    }
    /* Already set up (by the `fakenect` wrapper, a test, or our re-exec)?
     * Both halves must be there: the dump, and fakenect's library first. */
    const char *current = getenv("FAKENECT_PATH");
    const char *libs = getenv("LD_LIBRARY_PATH");
    if (current && same_dir(current, dir) && libs && strstr(libs, CUB_FAKENECT_DIR)) return 0;

    setenv("FAKENECT_PATH", dir, 1);
    const char *old = getenv("LD_LIBRARY_PATH");
    char libpath[PATH_MAX * 2];
    snprintf(libpath, sizeof libpath, "%s%s%s", CUB_FAKENECT_DIR, old && *old ? ":" : "",
             old ? old : "");
    setenv("LD_LIBRARY_PATH", libpath, 1);
    execv("/proc/self/exe", argv);
    fprintf(err,
            "cubdance: --replay %s: could not restart under fakenect (%s is needed; "
            "or run: FAKENECT_PATH=%s LD_LIBRARY_PATH=%s cubdance ...)\n",
            dir, CUB_FAKENECT_DIR, dir, CUB_FAKENECT_DIR);
    return -1;
}

/* replay — run under fakenect: libfreenect's own replay library serves a
 * recorded dump through the very calls that read a live Kinect. */
#ifndef CUB_APP_REPLAY_H
#define CUB_APP_REPLAY_H

#include <stdio.h>

/* Make sure this process reads `dir` through fakenect. If the environment
 * already says so, returns 0. Otherwise sets FAKENECT_PATH and puts
 * fakenect's libfreenect first on LD_LIBRARY_PATH, then re-executes the
 * program (the dynamic loader reads LD_LIBRARY_PATH only at start-up): it
 * returns only on failure, -1 with a message on err. */
int cub_replay_prepare(const char *dir, char **argv, FILE *err);

#endif

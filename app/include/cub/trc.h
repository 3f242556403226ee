/* trc — marker positions from a motion-capture lab (.trc, as OpenSim and
 * most optical systems write them): tab-separated text.
 *
 *   PathFileType  4  (X/Y/Z)  walk.trc
 *   DataRate  CameraRate  NumFrames  NumMarkers  Units  OrigDataRate  ...
 *   60        60          151        41          mm     60            ...
 *   Frame#  Time  R.ASIS  (tab tab)  L.ASIS ...
 *           X1 Y1 Z1 X2 Y2 Z2 ...
 *   (blank lines)
 *   1  0.000  617.2  1055.3  170.8  639.6 ...
 *
 * The header's names and values may be split by any blanks; each data row
 * is split at tabs: frame, time, then x y z per marker, one trailing empty
 * cell allowed. A marker the cameras lost is three empty cells: it is kept
 * as missing (present = 0), never as zeros. Units mm or m, kept in mm.
 *
 * Errors name the file and line: no PathFileType line, a header without
 * DataRate, NumFrames, NumMarkers or Units, unknown units, marker names
 * that disagree with NumMarkers, more than CUB_TRC_MAX_MARKERS markers or
 * CUB_TRC_MAX_FRAMES frames, a row with too few or too many cells, a
 * number that is not one or not finite, a marker partly missing, rows that
 * disagree with NumFrames, a frame number that is not a whole number. */
#ifndef CUB_TRC_H
#define CUB_TRC_H

#include <stdint.h>

#include "cub/err.h"
#include "cub/text.h"

#define CUB_TRC_MAX_MARKERS 256
#define CUB_TRC_MAX_FRAMES (1 << 20)
#define CUB_TRC_NAME_LEN 64

typedef struct cub_trc {
    int frames, markers;
    double rate;                      /* DataRate, frames a second */
    char (*names)[CUB_TRC_NAME_LEN];  /* markers names */
    double *time;                     /* frames seconds */
    float *pos;                       /* frames * markers * 3, mm; 0 where missing */
    uint8_t *present;                 /* frames * markers: 0 = missing */
} cub_trc;

/* Read from memory (name for messages). CUB_ERR_FORMAT with diag, or
 * CUB_ERR_NOMEM; out is empty on failure. cub_trc_free it either way. */
cub_err cub_trc_parse(const char *text, size_t len, const char *name, cub_trc *out,
                      cub_diag *diag);
/* The same from a file (CUB_ERR_IO when it cannot be read). */
cub_err cub_trc_load(const char *path, cub_trc *out, cub_diag *diag);
void cub_trc_free(cub_trc *t);

#endif

/* io — motion files in and out: BVH import and export, ASF/AMC import.
 *
 * Importers read a whole file, build a cub_skeleton and a cub_clip (frame
 * data on the heap, owned by the cub_io_motion), and convert lengths to
 * millimetres. Every failure fills a cub_diag naming the file, the line and
 * the problem, e.g. `walk.bvh:42: expected a number after OFFSET, got "x"`.
 * Parsers never crash, hang or read past their input, whatever it holds
 * (tests/fuzz/fuzz_motion_parsers.c).
 *
 * The app layer may use the heap and libm; the firmware it feeds may not.
 */
#ifndef CUB_IO_H
#define CUB_IO_H

#include <stdarg.h>
#include <stddef.h>

#include "cub/err.h"
#include "cub/motion.h"
#include "cub/text.h" /* cub_diag */

/* How one joint's channels were stored in the source file, kept so that
 * export writes the same layout back. */
typedef struct cub_io_channels {
    unsigned char count;     /* 0, 3 or 6 */
    unsigned char has_pos;   /* Xposition/Yposition/Zposition present */
    char rot_order[4];       /* e.g. "ZXY": rotation channel order as listed */
    char pos_order[4];       /* e.g. "XYZ" */
} cub_io_channels;

typedef struct cub_io_motion {
    cub_skeleton skel;
    cub_clip clip;           /* clip.skel points at skel above */
    cub_io_channels channels[CUB_MOTION_MAX_JOINTS];
    double unit_mm;          /* millimetres per unit of the source file */
    void *frame_mem;         /* owned; freed by cub_io_motion_free */
} cub_io_motion;

typedef struct cub_io_desc {
    double unit_mm; /* mm per file unit; 0 = guess (see cub_io_guess_unit_mm) */
} cub_io_desc;

/* Millimetres per file unit for a rest skeleton whose largest extent is
 * rest_size_units: a table of known conventions (metres, CMU's inch/0.45,
 * centimetres, millimetres) by size, else the unit that makes a 1.7 m
 * human. What importers use when desc->unit_mm is 0. */
double cub_io_guess_unit_mm(double rest_size_units);

/* BVH from a file or from memory (name is used in diagnostics). */
cub_err cub_io_load_bvh(const char *path, const cub_io_desc *desc, cub_io_motion *out,
                        cub_diag *diag);
cub_err cub_io_parse_bvh(const char *text, size_t len, const char *name,
                         const cub_io_desc *desc, cub_io_motion *out, cub_diag *diag);
/* Up to max paths of the .bvh files in dir (and, depth > 0, that many
 * folders below), sorted; each a heap string for the caller to free. */
int cub_io_list_bvh(const char *dir, int depth, char **out, int max);
/* ASF skeleton + AMC motion (CMU format). */
cub_err cub_io_load_asf_amc(const char *asf_path, const char *amc_path,
                            const cub_io_desc *desc, cub_io_motion *out, cub_diag *diag);
cub_err cub_io_parse_asf_amc(const char *asf, size_t asf_len, const char *amc,
                             size_t amc_len, const char *name, const cub_io_desc *desc,
                             cub_io_motion *out, cub_diag *diag);
/* Write a BVH in the channel layout of m->channels, in the source unit. */
cub_err cub_io_save_bvh(const char *path, const cub_io_motion *m, cub_diag *diag);
void cub_io_motion_free(cub_io_motion *m);

#endif

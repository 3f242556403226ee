/* floor_file — reading the forest floor (cub/floor.h) from its asset,
 * assets/floor/forest.floor: a small text for content makers to edit.
 *
 *   cubfloor 1                          # the first line: the format and its version
 *   grid NX NZ CELL_MM X0_MM Z0_MM      # samples, their spacing, where sample (0, 0) is
 *   row H H H ...                       # NZ rows of NX heights (mm), z rising row by row
 *   log X_MM Z_MM LENGTH_MM RADIUS_MM x|z   # a log lying along x or z
 *   stone X_MM Z_MM HALF_X_MM HALF_Z_MM HEIGHT_MM
 *
 * Numbers are whole millimetres; '#' starts a comment. The grid comes
 * before its rows, the rows before the things. Errors name the file and
 * line: a missing or wrong first line, an unknown keyword, a word too many
 * or too few, a number that is not whole or is past its limit (cub/floor.h:
 * the grid within +-30 m, samples within +-2 m, things 10 mm to 5 m, at most
 * CUB_FLOOR_MAX_THINGS), a second grid, rows too many or too few. */
#ifndef CUB_FLOOR_FILE_H
#define CUB_FLOOR_FILE_H

#include <stddef.h>

#include "cub/floor.h"
#include "cub/text.h"

/* The asset under an assets directory. */
#define CUB_FLOOR_ASSET "floor/forest.floor"

/* len bytes of text (not NUL-terminated) named name in messages into
 * *out. CUB_ERR_FORMAT with "name:line: what" in diag; *out is zeroed on
 * failure. */
cub_err cub_floor_parse(const char *text, size_t len, const char *name, cub_floor *out,
                        cub_diag *diag);
/* The same from a file (CUB_TEXT_MAX_SMALL at most); CUB_ERR_IO when it
 * cannot be read. */
cub_err cub_floor_load(const char *path, cub_floor *out, cub_diag *diag);

#endif

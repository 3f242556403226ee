/* routes — the bridge planner's searched routes (cub_bridge_route), as a
 * text file beside the bridge tags (assets/clips/bear.routes.txt), made by
 * `cubtool join --all --routes-out FILE` (docs/join.md, "Routes"):
 *
 *   cubroutes 1
 *   # from to via a in out b turn_deg x_mm z_mm
 *   twist kick jump 80 12 40 0 -3.1 12.0 -40.5
 *
 * From frame a of clip `from`, into frame `in` of clip `via`, play it to
 * frame `out`, then into frame b of clip `to`. turn_deg, x_mm, z_mm: the
 * seed's move of C onto A's end (Kovar's T), recorded for the reader; the
 * box's player does not apply it (it plays every clip where it stands).
 * '#' starts a comment. Every problem is reported as file:line. */
#ifndef CUB_ROUTES_H
#define CUB_ROUTES_H

#include <stddef.h>

#include "cub/bridge.h"
#include "cub/pack.h"
#include "cub/text.h"

#define CUB_ROUTES_MAX 512

typedef struct cub_routes {
    int count;
    cub_bridge_route route[CUB_ROUTES_MAX]; /* clip indices into the library */
    double align[CUB_ROUTES_MAX][3];        /* turn_deg, x_mm, z_mm */
    int line[CUB_ROUTES_MAX];
} cub_routes;

/* Parse text (len bytes, name for messages) against the library: clip
 * names, frames in range, in < out, from != to, one route per pair.
 * CUB_ERR_FORMAT with diag file:line. */
cub_err cub_routes_parse(const char *text, size_t len, const char *name, const cub_library *lib,
                         cub_routes *out, cub_diag *diag);
cub_err cub_routes_read(const char *path, const cub_library *lib, cub_routes *out, cub_diag *diag);
/* The file cub_routes_read reads back; CUB_ERR_IO. */
cub_err cub_routes_write(const char *path, const cub_library *lib, const cub_routes *r,
                         cub_diag *diag);

#endif

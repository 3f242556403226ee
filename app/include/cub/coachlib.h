/* coachlib — the coach's clips as the firmware's bridge table: loads the
 * shipped library (assets/clips/bear.cubclips), its bridge tags
 * (assets/clips/bear.tags.xml) and the bear (assets/bear/bear.xml), checks
 * they belong together, and builds the cub_bridge_table the switch planner
 * and the clip player read (firmware/include/cub/bridge.h): every clip, the
 * fuzzy features of every frame (forward kinematics on the bear), the
 * bridge frames and the tagged links. The distance weights and threshold
 * are the ones the tags were made with.
 *
 * Every failure names the file (and line, for the XML) and the problem:
 *   bear.tags.xml:12: clip "jump" has 91 frames in the library, 90 here
 * The app layer: heap for the owned memory, freed by cub_coachlib_free. */
#ifndef CUB_COACHLIB_H
#define CUB_COACHLIB_H

#include "cub/bridge.h"
#include "cub/character.h"
#include "cub/err.h"
#include "cub/io.h"
#include "cub/pack.h"
#include "cub/routes.h"
#include "cub/tags.h"

typedef struct cub_coachlib {
    cub_character bear;
    cub_library lib;
    cub_tags tags;
    cub_bridge_table table; /* finished; clips in library order */
    void *table_mem;        /* owned */
    /* after cub_coachlib_add_tween: */
    cub_bridge_tween tween; /* its keys (the bridge frames it passes) */
    cub_clip tween_clip;    /* one pass of the loop, on lib.skel (frame_count 0: none) */
    int tween_index;        /* the table's clip holding it unrolled (two passes), -1: none */
    void *tween_mem;        /* owned */
    cub_routes *routes;     /* the searched routes the table's planner takes: the
                               file beside the tags (X.tags.xml -> X.routes.txt),
                               NULL when there is none; owned */
} cub_coachlib;

/* Load the three files and build the table; with the routes beside the
 * tags (see routes above) when that file exists. out is zeroed first; on
 * failure everything is freed again and diag says what is wrong. */
cub_err cub_coachlib_load(const char *library_path, const char *tags_path,
                          const char *bear_path, cub_coachlib *out, cub_diag *diag);
/* The same from an assets folder: <dir>/clips/bear.cubclips,
 * <dir>/clips/bear.tags.xml, <dir>/bear/bear.xml. */
cub_err cub_coachlib_load_assets(const char *assets_dir, cub_coachlib *out, cub_diag *diag);
/* Build the seed's tween from the table's bridge frames (cub/bridge.h, "the
 * tween clip"; cfg NULL = defaults) and rebuild the table with it appended
 * as clip lib.clip_count (table.tween_clip), so that a player with
 * via_tween can route through it. The clips of the library keep their
 * indices; tween_clip is the loop itself, for tools that play or measure
 * it. Once per coachlib; on failure the table is as it was. */
cub_err cub_coachlib_add_tween(cub_coachlib *cl, const cub_bridge_tween_config *cfg,
                               cub_diag *diag);
/* A clip appended to the table by cub_coachlib_add_clips. */
typedef struct cub_coachlib_extra {
    const cub_clip *clip;         /* on lib.skel; its frames must outlive cl */
    const cub_fuzzy_frame *fuzzy; /* per frame, or NULL: measured by the table */
    const int *bridges;           /* its bridge frames, ascending (the tagger's
                                     rules: cub_tag_pick_clip), or NULL: every frame */
    int bridge_count;
} cub_coachlib_extra;

/* Rebuild the table with count clips appended after every clip it holds,
 * no links to or from them (the planner reaches them by
 * cub_bridge_query.start_frames and reach_frames): the song's groove clips
 * (issue 23). On failure the table is as it was. */
cub_err cub_coachlib_add_clips(cub_coachlib *cl, const cub_coachlib_extra *clips, int count,
                               cub_diag *diag);
/* Index of a clip by name, or -1. */
int cub_coachlib_find(const cub_coachlib *cl, const char *name);
/* Free what it owns; the struct is zeroed. NULL is fine. */
void cub_coachlib_free(cub_coachlib *cl);

#endif

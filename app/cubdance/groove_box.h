/* groove_box — the bear's own dance where a song teaches no move (issue 23,
 * docs/groove.md "The box"): at song load, the groove plan from the song's
 * MIDI (seed 001), one clip per span the song leaves free (the intro, the
 * bars between moves, the <free> bars, the bars after the last move), made
 * on the music clock at the library's 30 fps, fuzzy-tagged frame by frame
 * as the bridge table tags the library's clips, its bridge frames picked
 * by the tagger's rules against the library's frequent pose classes
 * (cub_tag_made_clip, cl's tag parameters). Each span is logged:
 *   t=0.000 groove span kind=free bar=7 bars=2 start_ms=.. frames=.. classes=.. fuzzy=.. bridges=..
 * (fuzzy: a hash of every frame's memberships, so a log pins the motion).
 * dance.c appends the clips to the bridge table and hands the spans to the
 * coach (cub_coach_groove), which dances them instead of idling. */
#ifndef CUB_GROOVE_BOX_H
#define CUB_GROOVE_BOX_H

#include "cub/coachlib.h"
#include "cub/fuzzy.h"
#include "cub/groove.h"
#include "cub/loop.h"
#include "cub/music.h"
#include "cub/song.h"

#define CUB_GROOVE_BOX_FRAME_NS 33333333u /* the clip library's 30 fps */

typedef struct cub_groove_box {
    cub_midi_groove midi;
    cub_groove_pick pick;
    cub_groove_store mem;
    cub_groove_plan plan;
    cub_groove_rig rig;
    int span_count;
    cub_song_span spans[CUB_SONG_MAX_SPANS];
    cub_clip clips[CUB_SONG_MAX_SPANS];        /* one per span, on the library's skeleton */
    void *clip_mem[CUB_SONG_MAX_SPANS];        /* owned */
    cub_fuzzy_frame *fuzzy[CUB_SONG_MAX_SPANS]; /* [frame] per clip, owned */
    int *bridges[CUB_SONG_MAX_SPANS];           /* per clip, by the tagger's rules; owned */
    int bridge_count[CUB_SONG_MAX_SPANS];
    char names[CUB_SONG_MAX_SPANS][24];         /* groove_<kind>_<bar>, for the log */
} cub_groove_box;

/* Plan, fill and tag; log one line per span. A skeleton the groove cannot
 * move (no Spine, Chest, Head, two-bone arms: the seal) gets no clips and
 * one line `groove none why=skeleton`. On failure err names the file. */
cub_err cub_groove_box_open(cub_groove_box *g, const cub_song *song, const cub_coachlib *cl,
                            cub_log *log, char *err, size_t size);
void cub_groove_box_close(cub_groove_box *g);

#endif

/* words — every word the child reads on the TV, chosen here and nowhere
 * else: the coach's hint (a move's own words from the song, what to fix in
 * it from the song's fault words table (cub/faults.h), "Come closer!",
 * "I can't see you!", "Where are you?") and the cue over the child's inset from the tracker's
 * status ("Step back", "Come closer", "Step into the middle"), and the idle
 * screen's title ("Press START!") and the cheer at the song's end. Each
 * is spoken too (the voice pack holds every phrase; dance.c asks). The renderer
 * is handed the strings and draws them; it never picks one. Strings are
 * UTF-8 and live as long as the song. */
#ifndef CUB_APP_WORDS_H
#define CUB_APP_WORDS_H

#include <stdint.h>

#include "cub/faults.h"
#include "cub/song.h"

/* The hint's words: hint is a move index of song or a CUB_COACH_HINT_*;
 * NULL for none (CUB_COACH_HINT_NONE, a move without a hint, out of range). */
const char *cub_words_hint(const cub_song *song, int32_t hint);
/* The words for what to fix in move (a song move index) after a wrong
 * verdict's fault (cub_judge_fault_code): the move's own line of faults,
 * else the general one for the key and how; the move's hint when the
 * table has neither or fault is 0. Shown instead of the move's hint while
 * the correction runs: one short line, what to do now. */
const char *cub_words_fault(const cub_song *song, const cub_faults *faults, int32_t move,
                            int32_t fault);
/* Every phrase the box can show a child, each once: the fixed ones (title,
 * cheer, the coach's own hints, the tracker's cues), each move's hint of
 * song and each line's words of faults (either may be NULL). fn gets each
 * in turn with ctx. The voice pack is built from this list (`cubvoice`), so
 * a phrase added here is spoken with no other change; a new words function
 * must be walked here too: test_words checks each phrase comes once,
 * test_voicepack that the built pack holds every one, and test_scenarios
 * that no phrase said in the scenarios was missing (`speech missing`). */
typedef void (*cub_words_fn)(void *ctx, const char *phrase);
void cub_words_each(const cub_song *song, const cub_faults *faults, cub_words_fn fn, void *ctx);
/* The idle screen's title, while the box waits for START. */
const char *cub_words_title(void);
/* What the bear says when the song is over (shown and spoken). */
const char *cub_words_cheer(void);
/* The cue for a tracker status (cub_track_status); NULL when the child is
 * seen well or nobody is there. */
const char *cub_words_cue(int32_t track_status);

#endif

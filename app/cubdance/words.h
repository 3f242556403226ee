/* words — every word the child reads on the TV, chosen here and nowhere
 * else: the coach's hint (a move's own words from the song, "Come closer!",
 * "I can't see you!") and the cue over the child's inset from the tracker's
 * status ("Step back", "Come closer", "Step into the middle"), and the idle
 * screen's title ("Press START!") and the cheer at the song's end. Each
 * is spoken too (the voice pack holds every phrase; dance.c asks). The renderer
 * is handed the strings and draws them; it never picks one. Strings are
 * UTF-8 and live as long as the song. */
#ifndef CUB_APP_WORDS_H
#define CUB_APP_WORDS_H

#include <stdint.h>

#include "cub/song.h"

/* The hint's words: hint is a move index of song or a CUB_COACH_HINT_*;
 * NULL for none (CUB_COACH_HINT_NONE, a move without a hint, out of range). */
const char *cub_words_hint(const cub_song *song, int32_t hint);
/* The idle screen's title, while the box waits for START. */
const char *cub_words_title(void);
/* What the bear says when the song is over (shown and spoken). */
const char *cub_words_cheer(void);
/* The cue for a tracker status (cub_track_status); NULL when the child is
 * seen well or nobody is there. */
const char *cub_words_cue(int32_t track_status);

/* Every phrase the functions above can give for song (NULL: those that
 * need none), each handed to fn once per way it can be reached (a phrase
 * may come twice); returns how many calls. The voice pack is built from
 * this list (`cubvoice`), so a phrase added here, or reached by a new
 * hint or status below the bounds, is spoken with no other change; a new
 * function must be walked here too: test_voicepack checks the built pack
 * holds every phrase listed here, and test_scenarios that no phrase the
 * box said in its scenarios was missing from it (`speech missing`). */
typedef void (*cub_words_fn)(void *user, const char *phrase);
int cub_words_each(const cub_song *song, cub_words_fn fn, void *user);
/* The bounds cub_words_each walks: hints from this up, statuses below the
 * count (CUB_TRACK_* values are small; the coach's hints are -1, -2, ...). */
#define CUB_WORDS_HINT_LOWEST (-64)
#define CUB_WORDS_STATUS_COUNT 64

#endif

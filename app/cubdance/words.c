/* The child's words (see words.h). */
#include "words.h"

#include <stddef.h>

#include "cub/coach.h"
#include "cub/track.h"

const char *cub_words_hint(const cub_song *song, int32_t hint)
{
    if (hint == CUB_COACH_HINT_COME_CLOSER) return "Come closer!";
    if (hint == CUB_COACH_HINT_CANT_SEE) return "I can't see you!";
    if (!song || hint < 0 || hint >= song->move_count) return NULL;
    return song->moves[hint].hint[0] ? song->moves[hint].hint : NULL;
}

const char *cub_words_title(void)
{
    return "Press START!";
}

const char *cub_words_cheer(void)
{
    return "Hooray! You did it!";
}

/* Where the camera reads the child badly, what the child can do about it. */
const char *cub_words_cue(int32_t track_status)
{
    switch (track_status) {
    case CUB_TRACK_TOO_CLOSE: return "Step back";
    case CUB_TRACK_TOO_FAR: return "Come closer";
    case CUB_TRACK_PARTLY_OUT: return "Step into the middle";
    default: return NULL;
    }
}

/* Every input each function above takes, so that nothing it can return is
 * left out: the hints from the lowest CUB_COACH_HINT_* up through the
 * song's moves, every tracker status, the title and the cheer. */
int cub_words_each(const cub_song *song, cub_words_fn fn, void *user)
{
    int n = 0;
    const char *fixed[2] = {cub_words_title(), cub_words_cheer()};
    for (int i = 0; i < 2; i++, n++) fn(user, fixed[i]);
    int moves = song ? song->move_count : 0;
    for (int32_t h = CUB_WORDS_HINT_LOWEST; h < moves; h++) {
        const char *w = cub_words_hint(song, h);
        if (w) fn(user, w), n++;
    }
    for (int32_t st = 0; st < CUB_WORDS_STATUS_COUNT; st++) {
        const char *w = cub_words_cue(st);
        if (w) fn(user, w), n++;
    }
    return n;
}

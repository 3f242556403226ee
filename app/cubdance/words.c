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

/* The child's words (see words.h). */
#include "words.h"

#include <stddef.h>
#include <string.h>

#include "cub/coach.h"
#include "cub/judge.h"
#include "cub/track.h"

const char *cub_words_hint(const cub_song *song, int32_t hint)
{
    if (hint == CUB_COACH_HINT_COME_CLOSER) return "Come closer!";
    if (hint == CUB_COACH_HINT_CANT_SEE) return "I can't see you!";
    if (hint == CUB_COACH_HINT_WHERE) return "Where are you?";
    if (hint == CUB_COACH_HINT_STEP_BACK) return "Step back";
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

const char *cub_words_fault(const cub_song *song, const cub_faults *faults, int32_t move,
                            int32_t fault)
{
    if (!song || move < 0 || move >= song->move_count) return NULL;
    cub_judge_fault f = cub_judge_fault_of(fault);
    const char *w = f.how == CUB_JUDGE_HOW_NONE
                        ? NULL
                        : cub_faults_words(faults, song->moves[move].clip, f.how, f.feature, f.set);
    return w ? w : cub_words_hint(song, move);
}

/* fn(phrase) unless an earlier one of list[0..n) is the same. */
static void once(const char *const *list, int n, cub_words_fn fn, void *ctx)
{
    if (!list[n] || !list[n][0]) return;
    for (int i = 0; i < n; i++)
        if (list[i] && !strcmp(list[i], list[n])) return;
    fn(ctx, list[n]);
}

void cub_words_each(const cub_song *song, const cub_faults *faults, cub_words_fn fn, void *ctx)
{
    enum { FIXED = 9 };
    const char *list[FIXED + CUB_SONG_MAX_MOVES + CUB_FAULTS_MAX];
    int n = 0;
    list[n++] = cub_words_title();
    list[n++] = cub_words_cheer();
    list[n++] = cub_words_hint(NULL, CUB_COACH_HINT_COME_CLOSER);
    list[n++] = cub_words_hint(NULL, CUB_COACH_HINT_CANT_SEE);
    list[n++] = cub_words_hint(NULL, CUB_COACH_HINT_WHERE);
    const int32_t cues[] = {CUB_TRACK_TOO_CLOSE, CUB_TRACK_TOO_FAR, CUB_TRACK_PARTLY_OUT};
    for (size_t i = 0; i < sizeof cues / sizeof cues[0]; i++)
        list[n++] = cub_words_cue(cues[i]);
    for (int m = 0; song && m < song->move_count; m++)
        list[n++] = song->moves[m].hint;
    for (int i = 0; faults && i < faults->count; i++)
        list[n++] = faults->w[i].words;
    for (int i = 0; i < n; i++)
        once(list, i, fn, ctx);
}

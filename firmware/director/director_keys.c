/* The coach's key moments: where in each move's own clip the bear shows
 * every key of the move together, clearly (cub_judge_key_moment), whether
 * the keys' left/right mirror ever shows there, and which other moves'
 * keys never do. The judge's early verdicts are timed from them
 * (cub/judge.h). */
#include "director_internal.h"

static const cub_fuzzy_frame *clip_frames(const cub_director *d, int clip, int32_t *count)
{
    const cub_bridge_clip *bc = &d->desc.table->clips[clip];
    *count = bc->clip.frame_count;
    return &d->desc.table->fuzzy[bc->first_frame];
}

static bool same_set(const cub_director_keys *a, const cub_director_keys *b)
{
    if (a->count != b->count) return false;
    for (int i = 0; i < a->count; i++) {
        bool found = false;
        for (int k = 0; k < b->count && !found; k++)
            found = a->key[i].feature == b->key[k].feature && a->key[i].set == b->key[k].set;
        if (!found) return false;
    }
    return true;
}

/* Does set a rule set b out: a feature both name, in different sets (an arm
 * up is not an arm half raised)? Keys on features b does not read (a knee
 * bent, for a leg kicked out) may come with b's, in a child's own style. */
static bool excludes(const cub_director_keys *a, const cub_director_keys *b)
{
    for (int i = 0; i < a->count; i++)
        for (int k = 0; k < b->count; k++)
            if (a->key[i].feature == b->key[k].feature && a->key[i].set != b->key[k].set)
                return true;
    return false;
}

/* The moves whose keys rule move m's out and that the bear never shows in
 * m's clip: a child holding them does another move (the previous one, or
 * a guess) instead, which is a mistake at once. Logged when there are any. */
static void find_other_moves(cub_director *d, int m, const cub_fuzzy_frame *fr, int32_t n)
{
    const cub_judge *j = d->desc.judge;
    const cub_director_keys *keys = d->desc.keys;
    char list[96];
    size_t len = 0;
    d->other_moves[m] = 0;
    for (int o = 0; o < d->desc.coach.move_count && o < 64; o++) {
        const cub_director_keys *k = &keys[o];
        if (o == m || k->count <= 0 || k->count > CUB_JUDGE_MAX_KEYS || same_set(k, &keys[m]) ||
            !excludes(k, &keys[m]))
            continue;
        if (cub_judge_first_match(j, k->key, k->count, fr, n) >= 0) continue;
        d->other_moves[m] |= 1ull << o;
        if (len + 8 < sizeof list)
            len += cub_log_format(list + len, sizeof list - len, "%s%d", len ? "," : "", o);
    }
    if (d->other_moves[m])
        cub_log_event(d->desc.coach.log, d->now_us, "judge", "other", "move=%d moves=%s", m, list);
}

void director_find_keys(cub_director *d)
{
    const cub_judge *j = d->desc.judge;
    for (int i = 0; i < d->desc.coach.move_count; i++) {
        d->key_frame[i] = -1;
        d->mirror_wrong[i] = false;
        d->other_moves[i] = 0;
        const cub_director_keys *k = d->desc.keys ? &d->desc.keys[i] : NULL;
        if (!j || !k || k->count <= 0 || k->count > CUB_JUDGE_MAX_KEYS) continue;
        int32_t n = 0;
        const cub_fuzzy_frame *fr = clip_frames(d, d->moves[i].clip, &n);
        d->key_frame[i] = cub_judge_key_moment(j, k->key, k->count, fr, n);
        cub_judge_key mirror[CUB_JUDGE_MAX_KEYS];
        /* A clip that shows the mirror too (boxing's two fists) makes it no
         * mistake: only a mirror the bear never shows is the other arm. */
        d->mirror_wrong[i] = cub_judge_mirror_keys(k->key, k->count, mirror) &&
                             cub_judge_first_match(j, mirror, k->count, fr, n) < 0;
        cub_log_event(d->desc.coach.log, d->now_us, "judge", "keys",
                      "move=%d clip=%s key_frame=%d mirror_wrong=%d", i,
                      director_clip_name(d, d->moves[i].clip), d->key_frame[i],
                      d->mirror_wrong[i] ? 1 : 0);
        find_other_moves(d, i, fr, n);
    }
}

void director_key_moment(const cub_director *d, int move, int32_t entry_frame, int32_t wait_frames,
                         cub_q16 speed, cub_judge_rep *r)
{
    if (move < 0 || move >= d->desc.coach.move_count || d->key_frame[move] < 0) return;
    const cub_clip *clip = &d->desc.table->clips[d->moves[move].clip].clip;
    int64_t ahead = d->key_frame[move] - entry_frame;
    int64_t play_us = (ahead > 0 ? ahead : 0) * clip->frame_ns / 1000 * CUB_Q16_ONE /
                      (speed > 0 ? speed : CUB_Q16_ONE);
    r->has_key = 1;
    r->key_us = (int64_t)wait_frames * clip->frame_ns / 1000 + play_us;
    r->mirror_wrong = d->mirror_wrong[move];
    r->other_count = 0;
    for (int o = 0; o < d->desc.coach.move_count && o < 64; o++) {
        if (!(d->other_moves[move] >> o & 1u) || r->other_count >= CUB_JUDGE_MAX_OTHER) continue;
        const cub_director_keys *k = &d->desc.keys[o];
        bool dup = false; /* two moves of one set (jumping jacks, bird flying) */
        for (int i = 0; i < r->other_count && !dup; i++) {
            cub_director_keys seen = {.count = r->other[i].count};
            for (int q = 0; q < seen.count; q++)
                seen.key[q] = r->other[i].key[q];
            dup = same_set(k, &seen);
        }
        if (dup) continue;
        r->other[r->other_count].count = k->count;
        for (int q = 0; q < k->count; q++)
            r->other[r->other_count].key[q] = k->key[q];
        r->other_count++;
    }
}

/* tag_links — step 3 of SEEDS.md § 000 "Bridge-frame tagging" and the
 * search order of "Switching": for every ordered pair of clips (A, B),
 * self pairs included, and every bridge frame a of A, the bridge frames b
 * of B with d(a, b) < threshold, best first, B's front half first. Also the
 * reachability of clips through those links. */
#include <stdlib.h>
#include <string.h>

#include "tag_internal.h"

static int cmp_link(const void *pa, const void *pb)
{
    const cub_tag_link *a = pa, *b = pb;
    if (a->half != b->half) return a->half < b->half ? -1 : 1;
    if (a->d != b->d) return a->d < b->d ? -1 : 1;
    return (a->b > b->b) - (a->b < b->b);
}

/* Within one clip a jump shorter than a quarter of it is a stutter, not a
 * repeat or a loop: self links must skip at least that far. */
static int self_gap(int frame_count)
{
    int g = frame_count / 4;
    return g < 1 ? 1 : g;
}

/* The links from bridge a of clip `from` into clip `to`, appended to pair. */
static cub_err link_one(const cub_tags *tags, const cub_tag_measured *m, const cub_tag_params *p,
                        int from, int to, const cub_tag_bridge *a, cub_tag_link *scratch,
                        cub_tag_pair *pair)
{
    const cub_tag_clip *B = &tags->clips[to];
    const cub_tag_frame *fa = &m->frames[from][a->frame];
    int n = 0;
    for (int i = 0; i < B->bridge_count; i++) {
        int b = B->bridges[i].frame;
        if (from == to && abs(b - a->frame) < self_gap(B->frame_count)) continue;
        cub_q16 d = cub_fuzzy_distance(&fa->fuzzy, &m->frames[to][b].fuzzy, &p->fuzzy);
        if (d < p->fuzzy.threshold)
            scratch[n++] = (cub_tag_link){a->frame, b, d,
                                          2 * b < B->frame_count ? CUB_TAG_FRONT : CUB_TAG_BACK};
    }
    qsort(scratch, (size_t)n, sizeof *scratch, cmp_link);
    int kept[2] = {0, 0};
    for (int i = 0; i < n; i++) {
        cub_tag_half h = scratch[i].half;
        if (p->max_links >= 0 && kept[h] >= p->max_links) continue;
        kept[h]++;
        cub_tag_link *grown = realloc(pair->links, sizeof *grown * (size_t)(pair->link_count + 1));
        if (!grown) return CUB_ERR_NOMEM;
        pair->links = grown;
        pair->links[pair->link_count++] = scratch[i];
    }
    return CUB_OK;
}

cub_err cub_tag_link_pairs(const cub_library *lib, const cub_tag_measured *m,
                           const cub_tag_params *p, cub_tags *tags, cub_tag_progress progress,
                           void *user)
{
    int nc = tags->clip_count, most = 1;
    for (int c = 0; c < nc; c++)
        most = tags->clips[c].bridge_count > most ? tags->clips[c].bridge_count : most;
    cub_tag_link *scratch = malloc(sizeof *scratch * (size_t)most);
    if (!scratch) return CUB_ERR_NOMEM;
    cub_err e = CUB_OK;
    for (int from = 0; !e && from < nc; from++) {
        if (progress) progress(user, "link", from, nc);
        const cub_tag_clip *A = &tags->clips[from];
        for (int to = 0; !e && to < nc; to++)
            for (int i = 0; !e && i < A->bridge_count; i++)
                e = link_one(tags, m, p, from, to, &A->bridges[i], scratch,
                             &tags->pairs[from * nc + to]);
    }
    if (!e && progress) progress(user, "link", nc, nc);
    free(scratch);
    (void)lib;
    return e;
}

int cub_tags_chain_length(const cub_tags *tags, int from, int to)
{
    int nc = tags ? tags->clip_count : 0;
    if (from < 0 || to < 0 || from >= nc || to >= nc) return -1;
    int *dist = malloc(sizeof *dist * (size_t)nc), *queue = malloc(sizeof *queue * (size_t)nc);
    if (!dist || !queue) {
        free(dist);
        free(queue);
        return -1;
    }
    for (int c = 0; c < nc; c++)
        dist[c] = -1;
    /* Breadth first; an edge into `to` is checked before `visited`, so a
     * self pair with links answers 1 for from == to. */
    int head = 0, tail = 0, found = -1;
    dist[from] = 0;
    queue[tail++] = from;
    while (head < tail && found < 0) {
        int c = queue[head++];
        for (int t = 0; t < nc && found < 0; t++) {
            if (tags->pairs[c * nc + t].link_count == 0) continue;
            if (t == to)
                found = dist[c] + 1;
            else if (dist[t] < 0) {
                dist[t] = dist[c] + 1;
                queue[tail++] = t;
            }
        }
    }
    free(dist);
    free(queue);
    return found;
}

/* Joint correspondences between two skeletons (SEEDS.md § 004): the map
 * file's rows first, then names, then structure. */
#include <ctype.h>
#include <stdio.h>
#include <string.h>

#include "cub/evolve.h"

typedef struct corr_state {
    const cub_skeleton *a, *b;
    cub_evolve_corr *out;
    unsigned char fixed[2][CUB_EVOLVE_MAX_JOINTS]; /* decided (paired or none) */
} corr_state;

/* A joint name compared loosely: lower case, no '_', a leading "L"/"R"
 * before a capital read as "left"/"right" (CMU's LHipJoint = LeftHipJoint). */
static void loose(const char *name, char *out, size_t size)
{
    size_t o = 0;
    const char *s = name;
    if ((s[0] == 'L' || s[0] == 'R') && isupper((unsigned char)s[1])) {
        const char *side = s[0] == 'L' ? "left" : "right";
        o = (size_t)snprintf(out, size, "%s", side);
        s++;
    }
    for (; *s && o + 1 < size; s++)
        if (*s != '_') out[o++] = (char)tolower((unsigned char)*s);
    out[o] = '\0';
}

static void add_pair(corr_state *st, int ja, int jb)
{
    cub_evolve_corr *c = st->out;
    if (c->pair_count >= 2 * CUB_EVOLVE_MAX_JOINTS) return;
    c->pair[c->pair_count++] = (cub_evolve_pair){ja, jb};
    st->fixed[0][ja] = st->fixed[1][jb] = 1;
}

static cub_err find_named(const cub_skeleton *s, const char *name, int side,
                          const cub_evolve_map *map, int line, int *out, cub_diag *diag)
{
    *out = cub_motion_skeleton_find(s, name);
    if (*out < 0)
        return cub_diag_fail(diag, CUB_ERR_FORMAT, map->file, line, "no joint \"%s\" in parent %d",
                             name, side + 1);
    return CUB_OK;
}

static cub_err apply_row(corr_state *st, const cub_evolve_map *map, const cub_evolve_map_row *row,
                         cub_diag *diag)
{
    int ja[CUB_EVOLVE_MAP_SIDE], jb[CUB_EVOLVE_MAP_SIDE];
    cub_err err = CUB_OK;
    for (int i = 0; i < row->a_count && !err; i++)
        err = find_named(st->a, row->a[i], 0, map, row->line, &ja[i], diag);
    for (int i = 0; i < row->b_count && !err; i++)
        err = find_named(st->b, row->b[i], 1, map, row->line, &jb[i], diag);
    if (err) return err;
    for (int i = 0; i < row->a_count; i++)
        st->fixed[0][ja[i]] = 1;
    for (int i = 0; i < row->b_count; i++)
        st->fixed[1][jb[i]] = 1;
    for (int i = 0; i < row->a_count; i++)
        for (int k = 0; k < row->b_count; k++)
            add_pair(st, ja[i], jb[k]);
    return CUB_OK;
}

static void by_name(corr_state *st)
{
    char na[64], nb[64];
    for (int i = 0; i < st->a->joint_count; i++) {
        if (st->fixed[0][i]) continue;
        loose(st->a->joints[i].name, na, sizeof na);
        for (int k = 0; k < st->b->joint_count; k++) {
            if (st->fixed[1][k]) continue;
            loose(st->b->joints[k].name, nb, sizeof nb);
            if (!strcmp(na, nb)) {
                add_pair(st, i, k);
                break;
            }
        }
    }
}

static int partner(const corr_state *st, int ja)
{
    return cub_evolve_partner_of_a(st->out, ja);
}

/* The one undecided child of parent p on side (its end site only when
 * want_end), or -1 when none or several. */
static int only_child(const corr_state *st, int side, int p, int want_end)
{
    const cub_skeleton *s = side ? st->b : st->a;
    int found = -1;
    for (int j = 0; j < s->joint_count; j++) {
        if (s->joints[j].parent != p || st->fixed[side][j]) continue;
        if (!!s->joints[j].is_end_site != want_end) continue;
        if (found >= 0) return -1;
        found = j;
    }
    return found;
}

/* Parents first, so that a matched joint lets its only child match next.
 * Only from one-to-one pairs: below two legs that share a tail, which leg's
 * shin would the tail's tip be? */
static void by_structure(corr_state *st)
{
    for (int ja = 0; ja < st->a->joint_count; ja++) {
        int pb = partner(st, ja);
        if (pb < 0 || cub_evolve_kind_of(st->out, 1, ja) != CUB_EVOLVE_ONE_TO_ONE) continue;
        for (int end = 0; end < 2; end++) {
            int ca = only_child(st, 0, ja, end), cb = only_child(st, 1, pb, end);
            if (ca >= 0 && cb >= 0) add_pair(st, ca, cb);
        }
    }
}

cub_err cub_evolve_correspond(const cub_skeleton *a, const cub_skeleton *b,
                              const cub_evolve_map *map, cub_evolve_corr *out, cub_diag *diag)
{
    if (!a || !b || !out || a->joint_count < 1 || b->joint_count < 1)
        return cub_diag_fail(diag, CUB_ERR_ARG, "(evolve)", 0, "no skeleton");
    static corr_state st;
    memset(&st, 0, sizeof st);
    memset(out, 0, sizeof(*out));
    st.a = a;
    st.b = b;
    st.out = out;
    out->a_count = a->joint_count;
    out->b_count = b->joint_count;
    for (int r = 0; map && r < map->row_count; r++) {
        cub_err err = apply_row(&st, map, &map->row[r], diag);
        if (err) return err;
    }
    if (!st.fixed[0][0] && !st.fixed[1][0]) add_pair(&st, 0, 0);
    by_name(&st);
    by_structure(&st);
    return CUB_OK;
}

int cub_evolve_partner_of_a(const cub_evolve_corr *c, int ja)
{
    for (int i = 0; i < c->pair_count; i++)
        if (c->pair[i].a == ja) return c->pair[i].b;
    return -1;
}

static int count_of(const cub_evolve_corr *c, int side, int j)
{
    int n = 0;
    for (int i = 0; i < c->pair_count; i++)
        n += (side == 1 ? c->pair[i].a : c->pair[i].b) == j;
    return n;
}

cub_evolve_kind cub_evolve_kind_of(const cub_evolve_corr *c, int side, int joint)
{
    int mine = count_of(c, side, joint);
    if (mine == 0) return CUB_EVOLVE_NONE;
    if (mine > 1) return CUB_EVOLVE_ONE_TO_MANY;
    for (int i = 0; i < c->pair_count; i++) {
        const cub_evolve_pair *p = &c->pair[i];
        if ((side == 1 ? p->a : p->b) != joint) continue;
        int other = side == 1 ? p->b : p->a;
        return count_of(c, side == 1 ? 2 : 1, other) > 1 ? CUB_EVOLVE_MANY_TO_ONE
                                                         : CUB_EVOLVE_ONE_TO_ONE;
    }
    return CUB_EVOLVE_NONE;
}

const char *cub_evolve_kind_str(cub_evolve_kind k)
{
    static const char *names[] = {"none", "one-to-one", "many-to-one", "one-to-many"};
    return (unsigned)k < 4 ? names[k] : "?";
}

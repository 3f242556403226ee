/* evolve map files: which joints of parent 1 and parent 2 are the same
 * (format in cub/evolve.h). Binding the names is cub_evolve_correspond's. */
#include <stdio.h>
#include <string.h>

#include "cub/evolve.h"
#include "cub/text.h"

#define MAP_MAX_WORDS (2 * CUB_EVOLVE_MAP_SIDE + 1)

/* One side's names into names[]; "-" alone is the empty side. */
static cub_err parse_side(char **w, int n, char names[][CUB_MOTION_NAME_LEN], int *count,
                          const char *which, const cub_text_at *at)
{
    *count = 0;
    if (n == 0) return cub_text_fail(at, "nothing on the %s side of '='", which);
    if (n == 1 && !strcmp(w[0], "-")) return CUB_OK;
    if (n > CUB_EVOLVE_MAP_SIDE)
        return cub_text_fail(at, "more than %d joints on the %s side", CUB_EVOLVE_MAP_SIDE, which);
    for (int i = 0; i < n; i++) {
        if (!strcmp(w[i], "-"))
            return cub_text_fail(at, "'-' beside joint names on the %s side", which);
        if (strlen(w[i]) >= CUB_MOTION_NAME_LEN)
            return cub_text_fail(at, "joint name \"%.40s...\" too long", w[i]);
        snprintf(names[i], CUB_MOTION_NAME_LEN, "%s", w[i]);
    }
    *count = n;
    return CUB_OK;
}

/* The line where name already appears on side (0: parent 1's), or 0. */
static int seen_on(const cub_evolve_map *map, int side, const char *name)
{
    for (int r = 0; r < map->row_count; r++) {
        const cub_evolve_map_row *row = &map->row[r];
        int n = side ? row->b_count : row->a_count;
        for (int i = 0; i < n; i++)
            if (!strcmp(side ? row->b[i] : row->a[i], name)) return row->line;
    }
    return 0;
}

static cub_err check_row(const cub_evolve_map *map, const cub_evolve_map_row *row,
                         const cub_text_at *at)
{
    if (row->a_count > 1 && row->b_count > 1)
        return cub_text_fail(at, "many joints on both sides (one side must have one)");
    if (row->a_count == 0 && row->b_count == 0) return cub_text_fail(at, "'-' on both sides");
    for (int side = 0; side < 2; side++) {
        int n = side ? row->b_count : row->a_count;
        for (int i = 0; i < n; i++) {
            const char *name = side ? row->b[i] : row->a[i];
            int line = seen_on(map, side, name);
            for (int k = 0; k < i && !line; k++)
                line = !strcmp(side ? row->b[k] : row->a[k], name) ? at->line : 0;
            if (line)
                return cub_text_fail(at, "parent %d's joint \"%s\" already mapped on line %d",
                                     side + 1, name, line);
        }
    }
    return CUB_OK;
}

static cub_err map_line(void *ctx, cub_text_line *ln)
{
    cub_evolve_map *map = ctx;
    char *w[MAP_MAX_WORDS];
    int n = cub_text_words(ln->s, w, MAP_MAX_WORDS);
    if (n > MAP_MAX_WORDS) return cub_text_fail(&ln->at, "more than %d words", MAP_MAX_WORDS);
    int eq = -1;
    for (int i = 0; i < n; i++)
        if (!strcmp(w[i], "=")) {
            if (eq >= 0) return cub_text_fail(&ln->at, "more than one '='");
            eq = i;
        }
    if (eq < 0)
        return cub_text_fail(
            &ln->at, "expected `Parent1Joint... = Parent2Joint...`, no ' = ' in \"%s\"", w[0]);
    if (map->row_count >= CUB_EVOLVE_MAX_JOINTS)
        return cub_text_fail(&ln->at, "more than %d rows", CUB_EVOLVE_MAX_JOINTS);
    cub_evolve_map_row *row = &map->row[map->row_count];
    memset(row, 0, sizeof(*row));
    row->line = ln->at.line;
    cub_err err = parse_side(w, eq, row->a, &row->a_count, "left (parent 1)", &ln->at);
    if (!err)
        err =
            parse_side(w + eq + 1, n - eq - 1, row->b, &row->b_count, "right (parent 2)", &ln->at);
    if (!err) err = check_row(map, row, &ln->at);
    if (!err) map->row_count++;
    return err;
}

static cub_err parse_text(const cub_text *t, const void *in, void *out)
{
    (void)in;
    cub_evolve_map *map = out;
    memset(map, 0, sizeof(*map));
    snprintf(map->file, sizeof(map->file), "%s", t->name);
    cub_err err = cub_text_lines(t, map_line, map);
    if (!err && map->row_count == 0)
        err = cub_diag_fail(t->diag, CUB_ERR_FORMAT, t->name, 0, "no rows in the map");
    return err;
}

cub_err cub_evolve_map_parse(const char *text, size_t len, const char *name, cub_evolve_map *out,
                             cub_diag *diag)
{
    cub_text t = {text, len, name ? name : "(evolve map)", diag};
    return cub_text_parse(&t, parse_text, NULL, out);
}

cub_err cub_evolve_map_load(const char *path, cub_evolve_map *out, cub_diag *diag)
{
    return cub_text_load(&(cub_text_src){path, "evolve map", CUB_TEXT_MAX_SMALL}, parse_text, NULL,
                         out, diag);
}

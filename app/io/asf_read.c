/* ASF skeleton reader (Acclaim, as the CMU database writes it): sections
 * :units, :root, :bonedata (begin ... end per bone) and :hierarchy.
 * Builds the bone table that amc_read.c turns into a skeleton and clip. */
#include <stdio.h>
#include <string.h>

#include "asf_internal.h"

static int starts_section(const io_tok *t)
{
    return t->n > 0 && t->s[0] == ':' && t->first_on_line;
}

static void skip_section(io_lex *lx)
{
    io_tok t;
    while (io_lex_peek(lx, &t) && !starts_section(&t))
        io_lex_next(lx, &t);
}

/* count numbers on the current line after a keyword. */
static cub_err read_numbers(io_lex *lx, const io_tok *key, double *out, int count)
{
    io_tok t;
    char shown[40], what[48];
    for (int i = 0; i < count; i++) {
        if (!io_lex_next_same_line(lx, &t))
            return io_fail(lx, key->line, "%s needs %d numbers", io_tok_show(key, shown, sizeof(shown)),
                           count);
        snprintf(what, sizeof(what), "%.30s", io_tok_show(key, shown, sizeof(shown)));
        cub_err err = io_tok_double(lx, &t, what, &out[i]);
        if (err)
            return err;
    }
    return CUB_OK;
}

static int axis_letter(char c)
{
    return (c == 'x' || c == 'X') ? 0 : (c == 'y' || c == 'Y') ? 1 : (c == 'z' || c == 'Z') ? 2 : -1;
}

/* An axis order such as "XYZ": three distinct axes. */
static cub_err read_order(io_lex *lx, const io_tok *key, int order[3])
{
    io_tok t;
    char shown[40];
    if (!io_lex_next_same_line(lx, &t))
        return io_fail(lx, key->line, "axis order missing (e.g. XYZ)");
    int ok = t.n == 3;
    for (int i = 0; ok && i < 3; i++) {
        order[i] = axis_letter(t.s[i]);
        ok = order[i] >= 0 && (i == 0 || order[i] != order[0]) && (i < 2 || order[2] != order[1]);
    }
    if (!ok)
        return io_fail(lx, t.line, "bad axis order %s (expected e.g. XYZ)",
                       io_tok_show(&t, shown, sizeof(shown)));
    return CUB_OK;
}

/* A dof list: rx ry rz (and tx ty tz for the root). */
static cub_err read_dofs(io_lex *lx, asf_bone *b, int is_root)
{
    io_tok t;
    char shown[40];
    b->ndof = 0;
    while (io_lex_next_same_line(lx, &t)) {
        int axis = t.n == 2 ? axis_letter(t.s[1]) : -1;
        int kind = -1;
        if (axis >= 0 && (t.s[0] == 'r' || t.s[0] == 'R'))
            kind = axis;
        else if (axis >= 0 && (t.s[0] == 't' || t.s[0] == 'T'))
            kind = 3 + axis;
        if (kind < 0 || (kind >= 3 && !is_root))
            return cub_diag_fail(lx->diag, kind < 0 ? CUB_ERR_FORMAT : CUB_ERR_UNSUPPORTED, lx->name,
                              t.line, "%s dof %s in '%s'", kind < 0 ? "unknown" : "unsupported",
                              io_tok_show(&t, shown, sizeof(shown)), b->name);
        for (int i = 0; i < b->ndof; i++)
            if (b->dof[i] == kind)
                return io_fail(lx, t.line, "dof %s listed twice", io_tok_show(&t, shown, sizeof(shown)));
        b->dof[b->ndof++] = kind;
    }
    return CUB_OK;
}

static cub_err parse_units(asf_skel *s, io_lex *lx)
{
    io_tok t, v;
    char shown[40];
    while (io_lex_peek(lx, &t) && !starts_section(&t)) {
        io_lex_next(lx, &t);
        cub_err err = CUB_OK;
        if (io_tok_is(&t, "length")) {
            err = read_numbers(lx, &t, &s->length_unit, 1);
            if (!err && !(s->length_unit > 0))
                return io_fail(lx, t.line, "length unit must be positive");
        } else if (io_tok_is(&t, "angle")) {
            if (!io_lex_next_same_line(lx, &v))
                return io_fail(lx, t.line, "angle unit missing");
            if (io_tok_is_nocase(&v, "deg"))
                s->angle_deg = 1;
            else if (io_tok_is_nocase(&v, "rad"))
                s->angle_deg = 0;
            else
                return io_fail(lx, v.line, "angle unit %s is not deg or rad",
                               io_tok_show(&v, shown, sizeof(shown)));
        }
        if (err)
            return err;
        io_lex_skip_line(lx); /* mass and anything else */
    }
    return CUB_OK;
}

static cub_err parse_root(asf_skel *s, io_lex *lx)
{
    io_tok t;
    char shown[40];
    asf_bone *r = &s->bone[0];
    while (io_lex_peek(lx, &t) && !starts_section(&t)) {
        io_lex_next(lx, &t);
        cub_err err;
        if (io_tok_is(&t, "order"))
            err = read_dofs(lx, r, 1);
        else if (io_tok_is(&t, "axis"))
            err = read_order(lx, &t, r->axis_order);
        else if (io_tok_is(&t, "position"))
            err = read_numbers(lx, &t, s->root_pos, 3);
        else if (io_tok_is(&t, "orientation"))
            err = read_numbers(lx, &t, r->axis, 3);
        else
            err = io_fail(lx, t.line, "unknown :root field %s", io_tok_show(&t, shown, sizeof(shown)));
        if (err)
            return err;
    }
    return CUB_OK;
}

static cub_err parse_bone_field(asf_skel *s, io_lex *lx, asf_bone *b, const io_tok *t)
{
    io_tok v;
    char shown[40];
    if (io_tok_is(t, "id") || io_tok_is(t, "bodymass") || io_tok_is(t, "cofmass")) {
        io_lex_skip_line(lx);
    } else if (io_tok_is(t, "name")) {
        if (!io_lex_next_same_line(lx, &v))
            return io_fail(lx, t->line, "bone name missing");
        if (!io_tok_copy(&v, b->name, sizeof(b->name)) || v.n > CUB_MOTION_NAME_LEN - 5)
            return io_fail(lx, v.line, "bone name %s is longer than %d characters",
                           io_tok_show(&v, shown, sizeof(shown)), CUB_MOTION_NAME_LEN - 5);
        if (asf_find(s, b->name) >= 0)
            return io_fail(lx, v.line, "bone '%s' defined twice", b->name);
    } else if (io_tok_is(t, "direction")) {
        return read_numbers(lx, t, b->dir, 3);
    } else if (io_tok_is(t, "length")) {
        return read_numbers(lx, t, &b->len, 1);
    } else if (io_tok_is(t, "axis")) {
        cub_err err = read_numbers(lx, t, b->axis, 3);
        return err ? err : read_order(lx, t, b->axis_order);
    } else if (io_tok_is(t, "dof")) {
        return read_dofs(lx, b, 0);
    } else if (io_tok_is(t, "limits")) {
        /* One "(lo hi)" per dof, the first on this line: skip them all. */
        io_lex_skip_line(lx);
        while (io_lex_peek(lx, &v) && v.s[0] == '(') {
            io_lex_next(lx, &v);
            io_lex_skip_line(lx);
        }
    } else {
        return io_fail(lx, t->line, "unknown bone field %s", io_tok_show(t, shown, sizeof(shown)));
    }
    return CUB_OK;
}

static cub_err parse_bonedata(asf_skel *s, io_lex *lx)
{
    io_tok t;
    char shown[40];
    while (io_lex_peek(lx, &t) && !starts_section(&t)) {
        io_lex_next(lx, &t);
        if (!io_tok_is(&t, "begin"))
            return io_fail(lx, t.line, "expected 'begin' in :bonedata, got %s",
                           io_tok_show(&t, shown, sizeof(shown)));
        if (s->count >= ASF_MAX_BONES)
            return io_fail(lx, t.line, "more than %d bones", ASF_MAX_BONES - 1);
        asf_bone *b = &s->bone[s->count];
        memset(b, 0, sizeof(*b));
        b->parent = -1;
        b->line = t.line;
        b->axis_order[0] = 0, b->axis_order[1] = 1, b->axis_order[2] = 2;
        for (;;) {
            if (!io_lex_next(lx, &t))
                return io_fail(lx, lx->line, "file ends inside a bone (missing 'end')");
            if (io_tok_is(&t, "end"))
                break;
            cub_err err = parse_bone_field(s, lx, b, &t);
            if (err)
                return err;
        }
        if (!b->name[0])
            return io_fail(lx, b->line, "bone without a name");
        s->count++;
    }
    return CUB_OK;
}

static cub_err parse_hierarchy(asf_skel *s, io_lex *lx)
{
    io_tok t, c;
    char name[CUB_MOTION_NAME_LEN], shown[40];
    if (!io_lex_next(lx, &t) || !io_tok_is(&t, "begin"))
        return io_fail(lx, lx->line, "expected 'begin' after :hierarchy");
    for (;;) {
        if (!io_lex_next(lx, &t))
            return io_fail(lx, lx->line, "file ends inside :hierarchy (missing 'end')");
        if (io_tok_is(&t, "end"))
            return CUB_OK;
        int p = io_tok_copy(&t, name, sizeof(name)) ? asf_find(s, name) : -1;
        if (p < 0)
            return io_fail(lx, t.line, "unknown bone %s in :hierarchy", io_tok_show(&t, shown, sizeof(shown)));
        while (io_lex_next_same_line(lx, &c)) {
            int k = io_tok_copy(&c, name, sizeof(name)) ? asf_find(s, name) : -1;
            if (k < 0)
                return io_fail(lx, c.line, "unknown bone %s in :hierarchy",
                               io_tok_show(&c, shown, sizeof(shown)));
            if (k == 0 || s->bone[k].parent >= 0)
                return io_fail(lx, c.line, "bone '%s' is given a second parent", s->bone[k].name);
            s->bone[k].parent = p;
        }
    }
}

int asf_find(const asf_skel *s, const char *name)
{
    for (int i = 0; i < s->count; i++)
        if (strcmp(s->bone[i].name, name) == 0)
            return i;
    return -1;
}

cub_err asf_parse(asf_skel *s, const char *text, size_t len, const char *name, cub_diag *diag)
{
    io_lex lx;
    io_tok t;
    char shown[40];
    memset(s, 0, sizeof(*s));
    io_lex_init(&lx, text, len, name, diag);
    lx.hash_comments = 1;
    s->length_unit = 1.0;
    s->angle_deg = 1;
    s->count = 1; /* bone 0 is the root */
    snprintf(s->bone[0].name, sizeof(s->bone[0].name), "root");
    s->bone[0].parent = -1;
    s->bone[0].axis_order[1] = 1, s->bone[0].axis_order[2] = 2;
    int has_hierarchy = 0;
    if (!io_lex_peek(&lx, &t))
        return io_fail(&lx, 1, "empty ASF file");
    while (io_lex_next(&lx, &t)) {
        cub_err err = CUB_OK;
        if (!starts_section(&t))
            return io_fail(&lx, t.line, "expected a ':section', got %s",
                           io_tok_show(&t, shown, sizeof(shown)));
        if (io_tok_is(&t, ":units"))
            err = parse_units(s, &lx);
        else if (io_tok_is(&t, ":root"))
            err = parse_root(s, &lx);
        else if (io_tok_is(&t, ":bonedata"))
            err = parse_bonedata(s, &lx);
        else if (io_tok_is(&t, ":hierarchy"))
            err = (has_hierarchy = 1, parse_hierarchy(s, &lx));
        else
            skip_section(&lx); /* :version, :name, :documentation, ... */
        if (err)
            return err;
    }
    if (!has_hierarchy)
        return io_fail(&lx, lx.line, "no :hierarchy section");
    for (int i = 1; i < s->count; i++)
        if (s->bone[i].parent < 0)
            return io_fail(&lx, s->bone[i].line, "bone '%s' is not in the :hierarchy",
                           s->bone[i].name);
    return CUB_OK;
}

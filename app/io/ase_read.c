/* Reading 3ds Max ASCII exports (format and conventions in cub/ase.h).
 * One pass collects the nodes (names, parents, rest transforms, sampled
 * tracks) with file:line errors; then the skeleton and clip are built from
 * them in doubles and rounded once to the firmware's fixed point. */
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cub/ase.h"
#include "io_internal.h"

#define ASE_MAX_FRAMES (1 << 20)

typedef struct ase_node {
    char name[CUB_MOTION_NAME_LEN];
    int parent, line, dummy;
    int has_pos, has_q, rows; /* TM_POS or TM_ROW3; TM_QUATERNION; TM_ROW0..2 bits */
    cub_dv3 tm_pos, row[3];
    cub_dq tm_q;
    cub_dv3 *pos; /* [frames] CONTROL_POS_SAMPLE, or NULL */
    cub_dq *rot;  /* [frames] CONTROL_ROT_SAMPLE accumulated, or NULL */
    int pos_n, rot_n, pos_line, rot_line;
} ase_node;

typedef struct ase_reader {
    io_lex lx;
    ase_node *nodes;
    int count;
    long first, tpf;
    int frames, scene_line;
    double fps;
} ase_reader;

/* ---- tokens ------------------------------------------------------------- */

static int is_key(const io_tok *t)
{
    return t->n > 1 && t->s[0] == '*';
}

/* The values after a key, on its line, up to a brace. */
static void skip_values(ase_reader *r)
{
    io_tok t;
    while (io_lex_peek(&r->lx, &t) && !t.first_on_line && !io_tok_is(&t, "{") &&
           !io_tok_is(&t, "}"))
        io_lex_next(&r->lx, &t);
}

/* A block's body after its '{', skipped to the matching '}'. */
static cub_err skip_block(ase_reader *r, int open_line)
{
    io_tok t;
    long depth = 1;
    while (depth > 0 && io_lex_next(&r->lx, &t))
        depth += io_tok_is(&t, "{") ? 1 : io_tok_is(&t, "}") ? -1 : 0;
    return depth ? io_fail(&r->lx, open_line, "the block opened here is not closed") : CUB_OK;
}

/* An item this reader does not use: its values and its block, if any. */
static cub_err skip_item(ase_reader *r, const io_tok *key)
{
    io_tok t;
    skip_values(r);
    if (io_lex_peek(&r->lx, &t) && io_tok_is(&t, "{")) {
        io_lex_next(&r->lx, &t);
        return skip_block(r, key->line);
    }
    return CUB_OK;
}

static cub_err expect_open(ase_reader *r, const io_tok *key)
{
    io_tok t;
    char buf[48], what[48];
    if (io_lex_next(&r->lx, &t) && io_tok_is(&t, "{")) return CUB_OK;
    return io_fail(&r->lx, key->line, "expected '{' after %s, got %s",
                   io_tok_show(key, what, sizeof(what)),
                   r->lx.p < r->lx.end ? io_tok_show(&t, buf, sizeof(buf)) : "the end of the file");
}

/* The next key of a block, 0 at its '}'; an error at the end of the file
 * or for a stray value. */
static int next_key(ase_reader *r, int open_line, io_tok *t, cub_err *err)
{
    char buf[48];
    if (!io_lex_next(&r->lx, t)) {
        *err = io_fail(&r->lx, open_line, "the block opened here is not closed");
        return 0;
    }
    if (io_tok_is(t, "}")) return 0;
    if (!is_key(t)) {
        *err = io_fail(&r->lx, t->line, "expected a *KEYWORD or '}', got %s",
                       io_tok_show(t, buf, sizeof(buf)));
        return 0;
    }
    return 1;
}

static cub_err read_numbers(ase_reader *r, const io_tok *key, double *v, int n)
{
    char what[48];
    io_tok_show(key, what, sizeof(what));
    for (int i = 0; i < n; i++) {
        io_tok t;
        if (!io_lex_next_same_line(&r->lx, &t))
            return io_fail(&r->lx, key->line, "%s needs %d numbers, found %d", what, n, i);
        cub_err err = io_tok_double(&r->lx, &t, what, &v[i]);
        if (err) return err;
    }
    return CUB_OK;
}

static cub_err read_long(ase_reader *r, const io_tok *key, long lo, long hi, long *out)
{
    double v;
    char what[48];
    cub_err err = read_numbers(r, key, &v, 1);
    if (err) return err;
    if (v != floor(v) || v < (double)lo || v > (double)hi)
        return io_fail(&r->lx, key->line, "%s %g is not a whole number in %ld..%ld",
                       io_tok_show(key, what, sizeof(what)), v, lo, hi);
    *out = (long)v;
    return CUB_OK;
}

/* A quoted name on the key's line: printable, 1 .. cap - 1 bytes. */
static cub_err read_name(ase_reader *r, const io_tok *key, char *out, size_t cap)
{
    io_lex *lx = &r->lx;
    char what[48];
    io_tok_show(key, what, sizeof(what));
    while (lx->p < lx->end && (*lx->p == ' ' || *lx->p == '\t'))
        lx->p++;
    if (lx->p >= lx->end || *lx->p != '"')
        return io_fail(lx, key->line, "%s: expected a quoted name", what);
    const char *s = ++lx->p;
    while (lx->p < lx->end && *lx->p != '"' && *lx->p != '\n')
        lx->p++;
    if (lx->p >= lx->end || *lx->p != '"')
        return io_fail(lx, key->line, "%s: the closing quote is missing", what);
    size_t n = (size_t)(lx->p - s);
    lx->p++;
    for (size_t i = 0; i < n; i++)
        if ((unsigned char)s[i] < 32 || (unsigned char)s[i] > 126)
            return io_fail(lx, key->line, "%s: the name holds a byte that is not printable", what);
    if (n == 0 || n >= cap)
        return io_fail(lx, key->line, "%s: the name is empty or longer than %zu bytes", what,
                       cap - 1);
    memcpy(out, s, n);
    out[n] = '\0';
    return CUB_OK;
}

/* ---- the scene ---------------------------------------------------------- */

static cub_err read_scene(ase_reader *r, const io_tok *key)
{
    io_tok t;
    long last = LONG_MIN, first = 0, tpf = CUB_ASE_TICKS_PER_FRAME;
    double fps = 0;
    /* the tracks already read were sized and checked by the first scene */
    if (r->scene_line)
        return io_fail(&r->lx, key->line, "a second *SCENE block (the first is at line %d)",
                       r->scene_line);
    cub_err err = expect_open(r, key);
    while (!err && next_key(r, key->line, &t, &err)) {
        if (io_tok_is(&t, "*SCENE_FIRSTFRAME")) err = read_long(r, &t, -1000000, 1000000, &first);
        else if (io_tok_is(&t, "*SCENE_LASTFRAME")) err = read_long(r, &t, -1000000, 2000000, &last);
        else if (io_tok_is(&t, "*SCENE_TICKSPERFRAME")) err = read_long(r, &t, 1, 100000, &tpf);
        else if (io_tok_is(&t, "*SCENE_FRAMESPEED")) {
            err = read_numbers(r, &t, &fps, 1);
            if (!err && !(fps >= 0.5 && fps <= 10000))
                err = io_fail(&r->lx, t.line, "*SCENE_FRAMESPEED %g is not in 0.5..10000", fps);
        } else err = skip_item(r, &t);
    }
    if (err) return err;
    if (last == LONG_MIN || fps == 0)
        return io_fail(&r->lx, key->line, "*SCENE needs *SCENE_LASTFRAME and *SCENE_FRAMESPEED");
    if (last < first || last - first >= ASE_MAX_FRAMES)
        return io_fail(&r->lx, key->line, "frames %ld..%ld: not 1 to %d frames", first, last,
                       ASE_MAX_FRAMES);
    r->first = first;
    r->tpf = tpf;
    r->fps = fps;
    r->frames = (int)(last - first + 1);
    r->scene_line = key->line;
    return CUB_OK;
}

/* ---- a node's rest transform and tracks ---------------------------------- */

static cub_err read_tm(ase_reader *r, ase_node *n, const io_tok *key)
{
    io_tok t;
    double v[4];
    cub_err err = expect_open(r, key);
    while (!err && next_key(r, key->line, &t, &err)) {
        int row = io_tok_is(&t, "*TM_ROW0") ? 0 : io_tok_is(&t, "*TM_ROW1") ? 1
                : io_tok_is(&t, "*TM_ROW2") ? 2 : io_tok_is(&t, "*TM_ROW3") ? 3 : -1;
        if (row >= 0 || io_tok_is(&t, "*TM_POS")) {
            err = read_numbers(r, &t, v, 3);
            cub_dv3 p = cub_dv3_make(v[0], v[1], v[2]);
            if (row >= 0 && row < 3) n->row[row] = p, n->rows |= 1 << row;
            else if (row < 0 || !n->has_pos) n->tm_pos = p, n->has_pos = 1;
        } else if (io_tok_is(&t, "*TM_QUATERNION")) {
            err = read_numbers(r, &t, v, 4);
            double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
            if (!err && fabs(len - 1) > 1e-3)
                err = io_fail(&r->lx, t.line, "*TM_QUATERNION has length %g, not 1", len);
            n->tm_q = (cub_dq){v[3], v[0], v[1], v[2]};
            n->has_q = 1;
        } else err = skip_item(r, &t);
    }
    return err;
}

/* The tick of sample k, or a message. */
static cub_err check_tick(ase_reader *r, const io_tok *key, int k, double tick)
{
    double want = (double)(r->first + k) * (double)r->tpf;
    if (k >= r->frames)
        return io_fail(&r->lx, key->line, "more samples than the scene's %d frames", r->frames);
    if (tick != want)
        return io_fail(&r->lx, key->line, "sample %d is at tick %g; frame %ld is at tick %.0f", k,
                       tick, r->first + k, want);
    return CUB_OK;
}

static cub_err pos_sample(ase_reader *r, ase_node *n, const io_tok *t)
{
    double v[4];
    cub_err err = read_numbers(r, t, v, 4);
    if (!err) err = check_tick(r, t, n->pos_n, v[0]);
    if (!err && !n->pos && !(n->pos = malloc(sizeof(*n->pos) * (size_t)r->frames)))
        err = cub_diag_fail(r->lx.diag, CUB_ERR_NOMEM, r->lx.name, t->line, "out of memory");
    if (!err) n->pos[n->pos_n++] = cub_dv3_make(v[1], v[2], v[3]);
    return err;
}

/* Frame 1 relative to the parent, frame k to frame k - 1: accumulated here. */
static cub_err rot_sample(ase_reader *r, ase_node *n, const io_tok *t)
{
    double v[5];
    cub_err err = read_numbers(r, t, v, 5);
    if (!err) err = check_tick(r, t, n->rot_n, v[0]);
    double len = sqrt(v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
    if (!err && v[4] != 0 && fabs(len - 1) > 1e-3)
        err = io_fail(&r->lx, t->line, "the axis (%g %g %g) is not a unit vector", v[1], v[2],
                      v[3]);
    if (!err && !n->rot && !(n->rot = malloc(sizeof(*n->rot) * (size_t)r->frames)))
        err = cub_diag_fail(r->lx.diag, CUB_ERR_NOMEM, r->lx.name, t->line, "out of memory");
    if (err) return err;
    cub_dq q = v[4] == 0 ? cub_dq_identity()
                         : cub_dq_axis_angle(cub_dv3_make(v[1] / len, v[2] / len, v[3] / len), v[4]);
    n->rot[n->rot_n] = n->rot_n ? cub_dq_norm(cub_dq_mul(n->rot[n->rot_n - 1], q)) : q;
    n->rot_n++;
    return CUB_OK;
}

static cub_err read_track(ase_reader *r, ase_node *n, const io_tok *key, int rot)
{
    io_tok t;
    char buf[48];
    const char *sample = rot ? "*CONTROL_ROT_SAMPLE" : "*CONTROL_POS_SAMPLE";
    if ((rot ? n->rot_n : n->pos_n) > 0)
        return io_fail(&r->lx, key->line, "node '%s' has a second %s", n->name,
                       rot ? "rotation track" : "position track");
    cub_err err = expect_open(r, key);
    while (!err && next_key(r, key->line, &t, &err)) {
        if (!io_tok_is(&t, sample))
            return io_fail(&r->lx, t.line, "%s: this reader takes sampled tracks (%s) only",
                           io_tok_show(&t, buf, sizeof(buf)), sample);
        err = rot ? rot_sample(r, n, &t) : pos_sample(r, n, &t);
    }
    int got = rot ? n->rot_n : n->pos_n;
    if (!err && got != r->frames)
        err = io_fail(&r->lx, key->line, "the track has %d samples; the scene has %d frames", got,
                      r->frames);
    *(rot ? &n->rot_line : &n->pos_line) = key->line;
    return err;
}

static cub_err read_anim(ase_reader *r, ase_node *n, const io_tok *key)
{
    io_tok t;
    cub_err err = expect_open(r, key);
    while (!err && next_key(r, key->line, &t, &err)) {
        if (io_tok_is(&t, "*CONTROL_POS_TRACK")) err = read_track(r, n, &t, 0);
        else if (io_tok_is(&t, "*CONTROL_ROT_TRACK")) err = read_track(r, n, &t, 1);
        else err = skip_item(r, &t);
    }
    return err;
}

/* ---- a node ------------------------------------------------------------- */

static int find_node(const ase_reader *r, const char *name)
{
    for (int i = 0; i < r->count; i++)
        if (!strcmp(r->nodes[i].name, name)) return i;
    return -1;
}

static cub_err node_item(ase_reader *r, ase_node *n, const io_tok *t, char *parent)
{
    char cls[CUB_MOTION_NAME_LEN];
    if (io_tok_is(t, "*NODE_NAME")) return read_name(r, t, n->name, sizeof(n->name));
    if (io_tok_is(t, "*NODE_PARENT")) return read_name(r, t, parent, CUB_MOTION_NAME_LEN);
    if (io_tok_is(t, "*HELPER_CLASS")) {
        cub_err err = read_name(r, t, cls, sizeof(cls));
        n->dummy = !err && !strcmp(cls, "Dummy");
        return err;
    }
    if (io_tok_is(t, "*NODE_TM")) return read_tm(r, n, t);
    if (io_tok_is(t, "*TM_ANIMATION")) return read_anim(r, n, t);
    return skip_item(r, t);
}

static cub_err place_node(ase_reader *r, ase_node *n, const char *parent)
{
    io_lex *lx = &r->lx;
    if (!n->name[0]) return io_fail(lx, n->line, "the node has no *NODE_NAME");
    if (find_node(r, n->name) >= 0)
        return io_fail(lx, n->line, "a second node named '%s'", n->name);
    if (!n->has_pos) return io_fail(lx, n->line, "node '%s' has no *NODE_TM with *TM_POS", n->name);
    n->parent = parent[0] ? find_node(r, parent) : -1;
    if (parent[0] && n->parent < 0)
        return io_fail(lx, n->line, "node '%s': parent '%s' is not a node before it", n->name,
                       parent);
    if (!parent[0] && r->count > 0)
        return io_fail(lx, n->line, "node '%s' has no parent; only the first node is the root",
                       n->name);
    if (parent[0] && !strcmp(parent, n->name))
        return io_fail(lx, n->line, "node '%s' is its own parent", n->name);
    if (n->parent >= 0 && r->nodes[n->parent].dummy)
        return io_fail(lx, n->line, "node '%s': parent '%s' is an end site (\"Dummy\")", n->name,
                       parent);
    if (n->dummy && n->rot)
        return io_fail(lx, n->rot_line, "end site '%s' has a rotation track", n->name);
    r->count++;
    return CUB_OK;
}

static cub_err read_node(ase_reader *r, const io_tok *key)
{
    if (!r->frames) return io_fail(&r->lx, key->line, "a node before the *SCENE block");
    if (r->count >= CUB_MOTION_MAX_JOINTS)
        return io_fail(&r->lx, key->line, "more than %d nodes", CUB_MOTION_MAX_JOINTS);
    ase_node *n = &r->nodes[r->count];
    memset(n, 0, sizeof(*n));
    n->line = key->line;
    char parent[CUB_MOTION_NAME_LEN] = "";
    io_tok t;
    cub_err err = expect_open(r, key);
    while (!err && next_key(r, key->line, &t, &err))
        err = node_item(r, n, &t, parent);
    if (!err) err = place_node(r, n, parent);
    if (err) { /* not counted: free its tracks here */
        free(n->pos);
        free(n->rot);
    }
    return err;
}

static cub_err read_file(ase_reader *r)
{
    io_tok t;
    char buf[48];
    if (!io_lex_next(&r->lx, &t) || !io_tok_is(&t, "*3DSMAX_ASCIIEXPORT"))
        return io_fail(&r->lx, 1, "not an ASE file: no *3DSMAX_ASCIIEXPORT at the start");
    skip_values(r);
    cub_err err = CUB_OK;
    while (!err && io_lex_next(&r->lx, &t)) {
        if (io_tok_is(&t, "*SCENE")) err = read_scene(r, &t);
        else if (io_tok_is(&t, "*HELPEROBJECT") || io_tok_is(&t, "*GEOMOBJECT"))
            err = read_node(r, &t);
        else if (is_key(&t)) err = skip_item(r, &t);
        else err = io_fail(&r->lx, t.line, "expected a *KEYWORD, got %s",
                           io_tok_show(&t, buf, sizeof(buf)));
    }
    if (!err && !r->count)
        err = io_fail(&r->lx, r->lx.line, "no *HELPEROBJECT or *GEOMOBJECT node");
    return err;
}

/* ---- to the skeleton and clip ------------------------------------------- */

/* The node's rest rotation in the world: TM_QUATERNION, else TM_ROW0..2. */
static cub_dq rest_rot(const ase_node *n)
{
    if (n->has_q) return cub_dq_norm(n->tm_q);
    if (n->rows == 7)
        return cub_dq_frames(cub_dv3_make(1, 0, 0), cub_dv3_make(0, 1, 0), n->row[0], n->row[1]);
    return cub_dq_identity();
}

static cub_err to_mm(ase_reader *r, int line, cub_dv3 v, double unit, cub_vec3 *out)
{
    cub_dv3 mm = cub_dv3_scale(v, unit);
    if (!(fabs(mm.x) <= IO_MM_LIMIT && fabs(mm.y) <= IO_MM_LIMIT && fabs(mm.z) <= IO_MM_LIMIT))
        return io_fail(&r->lx, line, "a position of (%g %g %g) mm is beyond +-%.0f mm", mm.x,
                       mm.y, mm.z, IO_MM_LIMIT);
    *out = cub_dv3_to_fx(mm);
    return CUB_OK;
}

static double guess_unit(const ase_reader *r, const cub_io_desc *desc)
{
    if (desc && desc->unit_mm > 0) return desc->unit_mm;
    cub_dv3 lo = r->nodes[0].tm_pos, hi = lo;
    for (int i = 1; i < r->count; i++) {
        cub_dv3 p = r->nodes[i].tm_pos;
        lo = cub_dv3_make(fmin(lo.x, p.x), fmin(lo.y, p.y), fmin(lo.z, p.z));
        hi = cub_dv3_make(fmax(hi.x, p.x), fmax(hi.y, p.y), fmax(hi.z, p.z));
    }
    return cub_io_guess_unit_mm(fmax(hi.x - lo.x, fmax(hi.y - lo.y, hi.z - lo.z)));
}

static cub_err build_skeleton(ase_reader *r, cub_io_motion *m)
{
    cub_motion_skeleton_reset(&m->skel);
    for (int i = 0; i < r->count; i++) {
        const ase_node *n = &r->nodes[i];
        cub_vec3 off = {0, 0, 0};
        cub_err err = CUB_OK;
        if (n->parent >= 0) {
            const ase_node *p = &r->nodes[n->parent];
            cub_dv3 d = cub_dq_rotate(cub_dq_conj(rest_rot(p)), cub_dv3_sub(n->tm_pos, p->tm_pos));
            err = to_mm(r, n->line, d, m->unit_mm, &off);
        }
        int index = 0;
        if (!err && cub_motion_skeleton_add(&m->skel, n->name, n->parent, off, &index))
            err = io_fail(&r->lx, n->line, "node '%s' cannot join the skeleton", n->name);
        if (err) return err;
        m->skel.joints[index].is_end_site = n->dummy;
    }
    return CUB_OK;
}

static cub_err fill_frame(ase_reader *r, cub_io_motion *m, int f, int with_trans)
{
    cub_clip *c = &m->clip;
    int jn = r->count;
    for (int j = 0; j < jn; j++) {
        const ase_node *n = &r->nodes[j];
        cub_dq q = n->rot ? n->rot[f]
                 : n->parent < 0 ? rest_rot(n)
                 : cub_dq_mul(cub_dq_conj(rest_rot(&r->nodes[n->parent])), rest_rot(n));
        c->rot[(size_t)f * (size_t)jn + (size_t)j] = io_quat_to_fx(q);
        cub_err err = CUB_OK;
        if (j == 0) err = to_mm(r, n->pos_line, n->pos ? n->pos[f] : n->tm_pos, m->unit_mm,
                                &c->root_mm[f]);
        else if (with_trans)
            c->trans_mm[(size_t)f * (size_t)jn + (size_t)j] = m->skel.joints[j].offset_mm;
        if (!err && j > 0 && with_trans && n->pos)
            err = to_mm(r, n->pos_line, n->pos[f], m->unit_mm,
                        &c->trans_mm[(size_t)f * (size_t)jn + (size_t)j]);
        if (err) return err;
    }
    return CUB_OK;
}

static cub_err build(ase_reader *r, const cub_io_desc *desc, cub_io_motion *m)
{
    m->unit_mm = guess_unit(r, desc);
    cub_err err = build_skeleton(r, m);
    int with_trans = 0;
    for (int j = 1; j < r->count; j++)
        with_trans |= r->nodes[j].pos != NULL;
    uint32_t frame_ns = (uint32_t)lround(1e9 / r->fps);
    if (!err)
        err = io_clip_alloc(m, r->frames, frame_ns, with_trans, r->lx.name, r->scene_line,
                            r->lx.diag);
    for (int f = 0; !err && f < r->frames; f++)
        err = fill_frame(r, m, f, with_trans);
    return err;
}

static cub_err parse_text(const cub_text *t, const void *desc, void *out)
{
    cub_io_motion *m = out;
    memset(m, 0, sizeof(*m));
    ase_reader *r = calloc(1, sizeof(*r));
    ase_node *nodes = calloc(CUB_MOTION_MAX_JOINTS, sizeof(*nodes));
    cub_err err = CUB_OK;
    if (!r || !nodes) err = cub_diag_fail(t->diag, CUB_ERR_NOMEM, t->name, 0, "out of memory");
    if (!err) {
        io_lex_init(&r->lx, t->s ? t->s : "", t->len, t->name, t->diag);
        r->lx.split_braces = 1;
        r->nodes = nodes;
        err = read_file(r);
        if (!err) err = build(r, desc, m);
    }
    for (int i = 0; r && i < r->count; i++) {
        free(nodes[i].pos);
        free(nodes[i].rot);
    }
    free(nodes);
    free(r);
    if (err) {
        cub_io_motion_free(m);
        memset(m, 0, sizeof(*m));
    }
    return err;
}

cub_err cub_ase_parse(const char *text, size_t len, const char *name, const cub_io_desc *desc,
                      cub_io_motion *out, cub_diag *diag)
{
    cub_text t = {text, len, name ? name : "(ase)", diag};
    return cub_text_parse(&t, parse_text, desc, out);
}

cub_err cub_ase_load(const char *path, const cub_io_desc *desc, cub_io_motion *out,
                     cub_diag *diag)
{
    if (out) memset(out, 0, sizeof(*out));
    return cub_text_load(&(cub_text_src){path, "ASE file", CUB_TEXT_MAX_MOCAP}, parse_text, desc,
                         out, diag);
}

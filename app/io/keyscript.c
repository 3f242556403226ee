/* keyscript — keys pressed at output frames (see cub/keyscript.h). */
#include "cub/keyscript.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static const struct {
    const char *name;
    int key;
} NAMED[] = {
    {"Tab", CUB_KEY_TAB},     {"Space", CUB_KEY_SPACE},   {"Esc", CUB_KEY_ESC},
    {"Up", CUB_KEY_UP},       {"Down", CUB_KEY_DOWN},     {"Left", CUB_KEY_LEFT},
    {"Right", CUB_KEY_RIGHT}, {"Plus", CUB_KEY_PLUS},     {"Minus", CUB_KEY_MINUS},
    {"Home", CUB_KEY_HOME},   {"PageUp", CUB_KEY_PAGEUP}, {"PageDown", CUB_KEY_PAGEDOWN},
};
#define NAMED_COUNT ((int)(sizeof NAMED / sizeof NAMED[0]))

int cub_key_from_name(const char *name)
{
    if (!name || !name[0]) return -1;
    if (!name[1] && isalnum((unsigned char)name[0])) return toupper((unsigned char)name[0]);
    for (int i = 0; i < NAMED_COUNT; i++)
        if (!strcasecmp(name, NAMED[i].name)) return NAMED[i].key;
    return -1;
}

const char *cub_key_name(int key)
{
    static const char *const ALNUM[36] = {
        "0", "1", "2", "3", "4", "5", "6", "7", "8", "9", "A", "B", "C", "D", "E", "F", "G", "H",
        "I", "J", "K", "L", "M", "N", "O", "P", "Q", "R", "S", "T", "U", "V", "W", "X", "Y", "Z"};
    if (key >= '0' && key <= '9') return ALNUM[key - '0'];
    if (key >= 'A' && key <= 'Z') return ALNUM[10 + key - 'A'];
    for (int i = 0; i < NAMED_COUNT; i++)
        if (NAMED[i].key == key) return NAMED[i].name;
    return "?";
}

typedef struct parser {
    cub_keyscript *s;
    int cap, last_frame;
} parser;

static int whole_number(const char *s, int max, int *out)
{
    long v = 0;
    if (!*s) return 0;
    for (; *s; s++) {
        if (*s < '0' || *s > '9') return 0;
        v = v * 10 + (*s - '0');
        if (v > max) return 0;
    }
    *out = (int)v;
    return 1;
}

static cub_err push(parser *p, const cub_text_at *at, int frame, int key)
{
    cub_keyscript *s = p->s;
    if (s->count == CUB_KEYSCRIPT_MAX_PRESSES)
        return cub_text_fail(at, "more than %d key presses", CUB_KEYSCRIPT_MAX_PRESSES);
    if (s->count == p->cap) {
        int cap = p->cap ? 2 * p->cap : 64;
        cub_keypress *n = realloc(s->press, (size_t)cap * sizeof *n);
        if (!n) return cub_diag_fail(at->diag, CUB_ERR_NOMEM, at->name, at->line, "out of memory");
        s->press = n;
        p->cap = cap;
    }
    s->press[s->count++] = (cub_keypress){frame, key, at->line};
    return CUB_OK;
}

static cub_err parse_line(void *ctx, cub_text_line *ln)
{
    parser *p = ctx;
    const cub_text_at *at = &ln->at;
    char *w[CUB_KEYSCRIPT_MAX_LINE + 2];
    int n = cub_text_words(ln->s, w, CUB_KEYSCRIPT_MAX_LINE + 1), frame;
    if (!whole_number(w[0], CUB_KEYSCRIPT_MAX_FRAME, &frame))
        return cub_text_fail(at, "bad frame \"%.40s\" (want a whole number 0..%d)", w[0],
                             CUB_KEYSCRIPT_MAX_FRAME);
    if (frame <= p->last_frame)
        return cub_text_fail(at, "frame %d after frame %d (frames ascend, each once)", frame,
                             p->last_frame);
    p->last_frame = frame;
    if (n < 2) return cub_text_fail(at, "frame %d has no keys", frame);
    if (n > CUB_KEYSCRIPT_MAX_LINE + 1)
        return cub_text_fail(at, "more than %d keys on one line", CUB_KEYSCRIPT_MAX_LINE);
    for (int i = 1; i < n; i++) {
        int key = cub_key_from_name(w[i]);
        if (key < 0)
            return cub_text_fail(at,
                                 "unknown key \"%.40s\" (want a letter, a digit, Tab, Space, "
                                 "Esc, Up, Down, Left, Right, Plus, Minus, Home, PageUp or "
                                 "PageDown)",
                                 w[i]);
        cub_err e = push(p, at, frame, key);
        if (e) return e;
    }
    return CUB_OK;
}

static cub_err parse_text(const cub_text *t, const void *in, void *out)
{
    (void)in;
    parser p = {out, 0, -1};
    return cub_text_lines(t, parse_line, &p);
}

cub_err cub_keyscript_parse(const char *text, size_t len, const char *name, cub_keyscript *out,
                            cub_diag *diag)
{
    if (!out) return CUB_ERR_ARG;
    memset(out, 0, sizeof *out);
    cub_text t = {text, len, name ? name : "(keys)", diag};
    cub_err e = cub_text_parse(&t, parse_text, NULL, out);
    if (e) cub_keyscript_free(out);
    return e;
}

cub_err cub_keyscript_load(const char *path, cub_keyscript *out, cub_diag *diag)
{
    if (!out) return CUB_ERR_ARG;
    memset(out, 0, sizeof *out);
    cub_text_src src = {path, "key script", CUB_TEXT_MAX_TIMELINE};
    cub_err e = cub_text_load(&src, parse_text, NULL, out, diag);
    if (e) cub_keyscript_free(out);
    return e;
}

void cub_keyscript_free(cub_keyscript *s)
{
    if (!s) return;
    free(s->press);
    memset(s, 0, sizeof *s);
}

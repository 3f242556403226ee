/* keyscript — keys pressed at given output frames, so that a viewer run
 * headless (`cubtool play --frames DIR --keys FILE`) can be driven and
 * tested like a person at the keyboard:
 *
 *   # frame  keys pressed, in order, before that frame is drawn
 *   0   Space
 *   5   2 L L L
 *   12  N Up Up
 *
 * One line per frame (a whole number, 0..CUB_KEYSCRIPT_MAX_FRAME),
 * frames ascending, each at most once; then 1..CUB_KEYSCRIPT_MAX_LINE key
 * names separated by blanks. A name is a letter or a digit (either case),
 * or one of Tab, Space, Esc, Up, Down, Left, Right, Plus, Minus, Home,
 * PageUp, PageDown (either case). '#' starts a comment.
 *
 * Errors name the file and line: a frame that is not a whole number or is
 * out of range, frames not ascending, a line without keys or with too
 * many, an unknown key name, more than CUB_KEYSCRIPT_MAX_PRESSES presses. */
#ifndef CUB_KEYSCRIPT_H
#define CUB_KEYSCRIPT_H

#include <stddef.h>

#include "cub/err.h"
#include "cub/text.h"

#define CUB_KEYSCRIPT_MAX_FRAME 1000000
#define CUB_KEYSCRIPT_MAX_LINE 64
#define CUB_KEYSCRIPT_MAX_PRESSES 100000

/* A key: 'A'..'Z' and '0'..'9' stand for themselves, the others follow. */
enum {
    CUB_KEY_TAB = 256,
    CUB_KEY_SPACE,
    CUB_KEY_ESC,
    CUB_KEY_UP,
    CUB_KEY_DOWN,
    CUB_KEY_LEFT,
    CUB_KEY_RIGHT,
    CUB_KEY_PLUS,
    CUB_KEY_MINUS,
    CUB_KEY_HOME,
    CUB_KEY_PAGEUP,
    CUB_KEY_PAGEDOWN,
};

typedef struct cub_keypress {
    int frame, key, line;
} cub_keypress;

typedef struct cub_keyscript {
    cub_keypress *press; /* [count], in order; heap, owned */
    int count;
} cub_keyscript;

/* The key a name stands for, or -1. */
int cub_key_from_name(const char *name);
/* The name of a key ("L", "Tab"), or "?" for no key. */
const char *cub_key_name(int key);

/* From memory (name for messages). CUB_ERR_FORMAT with diag, or
 * CUB_ERR_NOMEM; out is empty on failure. cub_keyscript_free it either way. */
cub_err cub_keyscript_parse(const char *text, size_t len, const char *name, cub_keyscript *out,
                            cub_diag *diag);
/* The same from a file (CUB_ERR_IO when it cannot be read). */
cub_err cub_keyscript_load(const char *path, cub_keyscript *out, cub_diag *diag);
void cub_keyscript_free(cub_keyscript *s);

#endif

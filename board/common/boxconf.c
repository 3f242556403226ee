/* boxconf — the box's config file: a table of keys, each with its kind,
 * its place in cub_boxconf and its allowed values, so that parsing,
 * messages and the documentation check all walk the same list. */
#include "cub/boxconf.h"
#include "cub/text.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_LINE 512
#define MAX_BYTES (64 * 1024)

typedef enum kind { K_NAME, K_PATH, K_INT, K_BOOL, K_SIZE, K_WORD } kind;

typedef struct key {
    const char *name;
    kind kind;
    size_t off, cap;            /* where in cub_boxconf; a string's room */
    int lo, hi;                 /* K_INT range */
    const char *const *words;   /* K_WORD choices, NULL-terminated */
    int line;                   /* K_NAME GPIO lines: index into line_at, else -1 */
} key;

#define AT(f) offsetof(cub_boxconf, f), sizeof(((cub_boxconf *)0)->f)
#define GPIO_LINE(n, i) {n, K_NAME, AT(gpio.line[i]), 0, 0, NULL, i}

static const char *const video_words[] = {"auto", "kmsdrm", "x11", "wayland", NULL};
static const char *const audio_words[] = {"auto", "alsa", "pulseaudio", "pipewire",
                                          "dummy", "disk", NULL};

static const key keys[] = {
    {"chip", K_NAME, AT(gpio.chip), 0, 0, NULL, -1},
    GPIO_LINE("start_line", CUB_BOXCONF_LINE_START),
    GPIO_LINE("stop_line", CUB_BOXCONF_LINE_STOP),
    {"active_low", K_BOOL, AT(gpio.active_low), 0, 1, NULL, -1},
    {"debounce_ms", K_INT, AT(gpio.debounce_ms), 0, 1000, NULL, -1},
    GPIO_LINE("led_line", CUB_BOXCONF_LINE_LED),
    {"led_active_low", K_BOOL, AT(gpio.led_active_low), 0, 1, NULL, -1},
    {"video_driver", K_WORD, AT(video_driver), 0, 0, video_words, -1},
    {"resolution", K_SIZE, AT(width), 0, 0, NULL, -1},
    {"fullscreen", K_BOOL, AT(fullscreen), 0, 1, NULL, -1},
    {"volume", K_INT, AT(volume), 0, 100, NULL, -1},
    {"audio_driver", K_WORD, AT(audio_driver), 0, 0, audio_words, -1},
    {"speech", K_BOOL, AT(speech), 0, 1, NULL, -1},
    {"attract_after_s", K_INT, AT(attract_after_s), 1, 3600, NULL, -1},
    {"doze_after_s", K_INT, AT(doze_after_s), 2, 86400, NULL, -1},
    {"assets_dir", K_PATH, AT(assets_dir), 0, 0, NULL, -1},
    {"songs_dir", K_PATH, AT(songs_dir), 0, 0, NULL, -1},
    {"song", K_NAME, AT(song), 0, 0, NULL, -1},
    {"coach", K_NAME, AT(coach), 0, 0, NULL, -1},
    {"soundfont", K_PATH, AT(soundfont), 0, 0, NULL, -1},
    {"font", K_PATH, AT(font), 0, 0, NULL, -1},
    {"recording", K_BOOL, AT(recording), 0, 1, NULL, -1},
    {"recording_dir", K_PATH, AT(recording_dir), 0, 0, NULL, -1},
    {"recording_max_mb", K_INT, AT(recording_max_mb), 1, 1048576, NULL, -1},
    {"log_max_kb", K_INT, AT(log_max_kb), 0, 1048576, NULL, -1},
};
#define KEY_COUNT ((int)(sizeof keys / sizeof *keys))

typedef struct parser {
    cub_boxconf *cfg;
    cub_text_at at;      /* the file, the line, the message */
    int seen[KEY_COUNT]; /* per key: the line it was set on, to refuse repeats */
} parser;

void cub_boxconf_defaults(cub_boxconf *c)
{
    memset(c, 0, sizeof *c);
    snprintf(c->gpio.file, sizeof c->gpio.file, "(built-in defaults)");
    snprintf(c->gpio.chip, sizeof c->gpio.chip, "gpiochip0");
    snprintf(c->gpio.line[CUB_BOXCONF_LINE_START], CUB_BOXCONF_NAME_MAX, "GPIO17");
    snprintf(c->gpio.line[CUB_BOXCONF_LINE_STOP], CUB_BOXCONF_NAME_MAX, "GPIO27");
    c->gpio.active_low = 1;
    c->gpio.debounce_ms = 30;
    snprintf(c->video_driver, sizeof c->video_driver, "auto");
    c->width = 1280;
    c->height = 720;
    c->fullscreen = 1;
    c->volume = 80;
    snprintf(c->audio_driver, sizeof c->audio_driver, "auto");
    c->speech = 1;
    snprintf(c->coach, sizeof c->coach, "bear");
    c->attract_after_s = 20;
    c->doze_after_s = 60;
    snprintf(c->soundfont, sizeof c->soundfont, "/usr/share/sounds/sf2/TimGM6mb.sf2");
    snprintf(c->font, sizeof c->font, "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf");
    snprintf(c->recording_dir, sizeof c->recording_dir, "/var/lib/cubdance/recordings");
    c->recording_max_mb = 2048;
    c->log_max_kb = 10240;
}

/* Digits only (no sign, no blanks), at most hi. */
static int parse_int(const char *s, int lo, int hi, int *out)
{
    long v = 0;
    if (!*s) {
        return 0;
    }
    for (; *s; s++) {
        if (*s < '0' || *s > '9' || (v = v * 10 + (*s - '0')) > hi) {
            return 0;
        }
    }
    if (v < lo) {
        return 0;
    }
    *out = (int)v;
    return 1;
}

static char *trim(char *s)
{
    s += strspn(s, " \t");
    size_t n = strlen(s);
    while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t')) {
        s[--n] = '\0';
    }
    return s;
}

static int parse_bool(const char *s, int *out)
{
    static const char *const no[] = {"0", "no", "off"}, *const yes[] = {"1", "yes", "on"};
    for (int i = 0; i < 3; i++) {
        if (!strcmp(s, no[i]) || !strcmp(s, yes[i])) {
            *out = !strcmp(s, yes[i]);
            return 1;
        }
    }
    return 0;
}

/* "auto" (0x0) or WxH within what a TV and the GPU can show. */
static int parse_size(const char *s, int *w, int *h)
{
    if (!strcmp(s, "auto")) {
        *w = *h = 0;
        return 1;
    }
    char buf[32];
    const char *x = strchr(s, 'x');
    if (!x || (size_t)(x - s) >= sizeof buf) {
        return 0;
    }
    memcpy(buf, s, (size_t)(x - s));
    buf[x - s] = '\0';
    return parse_int(buf, 320, 7680, w) && parse_int(x + 1, 200, 4320, h);
}

static void list_words(const char *const *words, char *buf, size_t size)
{
    size_t n = 0;
    buf[0] = '\0';
    for (int i = 0; words[i] && n < size; i++) {
        int w = snprintf(buf + n, size - n, "%s%s", i ? ", " : "", words[i]);
        n += w > 0 ? (size_t)w : 0;
    }
}

static cub_err set_string(parser *p, const key *k, const char *value)
{
    char *dst = (char *)p->cfg + k->off;
    if (strlen(value) >= k->cap) {
        return cub_text_fail(&p->at, "%s: value longer than %zu characters", k->name, k->cap - 1);
    }
    if (k->kind == K_NAME && strpbrk(value, " \t/")) {
        return cub_text_fail(&p->at, "%s: \"%s\" is not a name (no blanks or slashes)", k->name, value);
    }
    if (k->kind == K_PATH && *value && *value != '/') {
        return cub_text_fail(&p->at, "%s: \"%s\" is not an absolute path (it must start with /)", k->name,
                    value);
    }
    memcpy(dst, value, strlen(value) + 1);
    return CUB_OK;
}

static cub_err set_value(parser *p, const key *k, const char *value)
{
    int *num = (int *)((char *)p->cfg + k->off);
    char words[128];
    switch (k->kind) {
    case K_NAME:
    case K_PATH:
        return set_string(p, k, value);
    case K_INT:
        return parse_int(value, k->lo, k->hi, num)
                   ? CUB_OK
                   : cub_text_fail(&p->at, "%s: \"%s\" is not a whole number in %d..%d", k->name, value, k->lo,
                          k->hi);
    case K_BOOL:
        return parse_bool(value, num) ? CUB_OK
                                       : cub_text_fail(&p->at, "%s: \"%s\" is not 0 or 1 (or off/on, no/yes)",
                                              k->name, value);
    case K_SIZE:
        return parse_size(value, &p->cfg->width, &p->cfg->height)
                   ? CUB_OK
                   : cub_text_fail(&p->at, "%s: \"%s\" is not auto or WxH (320..7680 x 200..4320), e.g. "
                             "1280x720",
                          k->name, value);
    case K_WORD:
        for (int i = 0; k->words[i]; i++) {
            if (!strcmp(value, k->words[i])) {
                return set_string(p, k, value);
            }
        }
        list_words(k->words, words, sizeof words);
        return cub_text_fail(&p->at, "%s: \"%s\" is not one of %s", k->name, value, words);
    }
    return cub_text_fail(&p->at, "%s: unhandled kind", k->name);
}

/* Edit distance of two short words (keys), for "did you mean". */
static int distance(const char *a, const char *b)
{
    int prev[40], cur[40];
    size_t n = strlen(b);
    if (strlen(a) >= 40 || n >= 40) {
        return 99;
    }
    for (size_t j = 0; j <= n; j++) {
        prev[j] = (int)j;
    }
    for (size_t i = 1; a[i - 1]; i++) {
        cur[0] = (int)i;
        for (size_t j = 1; j <= n; j++) {
            int sub = prev[j - 1] + (a[i - 1] != b[j - 1]);
            int del = prev[j] + 1, ins = cur[j - 1] + 1;
            cur[j] = sub < del ? (sub < ins ? sub : ins) : (del < ins ? del : ins);
        }
        memcpy(prev, cur, sizeof prev);
    }
    return prev[n];
}

static cub_err unknown_key(parser *p, const char *name)
{
    int best = -1, best_d = 3; /* further than two edits is no typo */
    for (int k = 0; k < KEY_COUNT; k++) {
        int d = distance(name, keys[k].name);
        if (d < best_d) {
            best = k;
            best_d = d;
        }
    }
    if (best >= 0) {
        return cub_text_fail(&p->at, "unknown key '%s' (did you mean '%s'?)", name, keys[best].name);
    }
    return cub_text_fail(&p->at, "unknown key '%s' (the keys are listed in cubdance.conf)", name);
}

/* Keys whose empty value means something ("none", "the built-in place"). */
static int may_be_empty(const char *name)
{
    static const char *const names[] = {"led_line", "assets_dir", "songs_dir", "song"};
    for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
        if (!strcmp(name, names[i])) {
            return 1;
        }
    }
    return 0;
}

static cub_err parse_line(parser *p, char *text)
{
    char *eq = strchr(text, '=');
    if (!eq) {
        return cub_text_fail(&p->at, "expected key=value, got \"%s\"", text);
    }
    *eq = '\0';
    char *name = trim(text), *value = trim(eq + 1);
    for (int k = 0; k < KEY_COUNT; k++) {
        if (strcmp(name, keys[k].name) == 0) {
            if (p->seen[k]) {
                return cub_text_fail(&p->at, "%s set again (first set on line %d)", name, p->seen[k]);
            }
            p->seen[k] = p->at.line;
            if (keys[k].line >= 0) {
                p->cfg->gpio.line_at[keys[k].line] = p->at.line;
            }
            if (!*value && !may_be_empty(name)) {
                return cub_text_fail(&p->at, "%s has no value", name);
            }
            return set_value(p, &keys[k], value);
        }
    }
    return unknown_key(p, name);
}

/* The line to blame for a combination: the later of two keys' lines. */
static int blame(const parser *p, const char *a, const char *b)
{
    int line = 0;
    for (int k = 0; k < KEY_COUNT; k++) {
        if ((!strcmp(keys[k].name, a) || !strcmp(keys[k].name, b)) && p->seen[k] > line) {
            line = p->seen[k];
        }
    }
    return line;
}

static cub_err check(parser *p)
{
    const cub_boxconf *c = p->cfg;
    static const char *const names[] = {"start_line", "stop_line", "led_line"};
    for (int i = 0; i < CUB_BOXCONF_LINES; i++) {
        for (int j = i + 1; j < CUB_BOXCONF_LINES; j++) {
            if (c->gpio.line[i][0] && !strcmp(c->gpio.line[i], c->gpio.line[j])) {
                p->at.line = blame(p, names[i], names[j]);
                return cub_text_fail(&p->at, "%s and %s both name %s", names[i], names[j], c->gpio.line[i]);
            }
        }
    }
    if (c->doze_after_s <= c->attract_after_s) {
        p->at.line = blame(p, "attract_after_s", "doze_after_s");
        return cub_text_fail(&p->at, "doze_after_s (%d) must be longer than attract_after_s (%d)",
                    c->doze_after_s, c->attract_after_s);
    }
    return CUB_OK;
}

/* One line (comment cut) into p. */
static cub_err parse_one(void *ctx, cub_text_line *ln)
{
    parser *p = ctx;
    p->at.line = ln->at.line;
    if (strlen(ln->s) >= MAX_LINE) {
        return cub_text_fail(&p->at, "line longer than %d characters", MAX_LINE - 1);
    }
    ln->s[strcspn(ln->s, "\r")] = '\0';
    char *line = trim(ln->s);
    return *line ? parse_line(p, line) : CUB_OK;
}

static cub_err parse_text(const cub_text *t, void *cfg)
{
    parser p = {.cfg = cfg, .at = {t->name, 0, t->diag}};
    cub_err e = cub_text_lines(t, parse_one, &p);
    return e ? e : check(&p);
}

cub_err cub_boxconf_parse(const char *text, size_t len, const char *file, cub_boxconf *cfg,
                          char *err, size_t err_size)
{
    if (!cfg || !err || err_size == 0 || (!text && len)) {
        return CUB_ERR_ARG;
    }
    err[0] = '\0';
    cub_boxconf_defaults(cfg);
    snprintf(cfg->gpio.file, sizeof cfg->gpio.file, "%s", file ? file : "(config)");
    cub_diag d = {0};
    cub_text t = {text, len, cfg->gpio.file, &d};
    return cub_diag_report(parse_text(&t, cfg), &d, err, err_size);
}

static cub_err load_text(const cub_text *t, const void *in, void *cfg)
{
    cub_boxconf *c = cfg;
    cub_boxconf_defaults(c);
    snprintf(c->gpio.file, sizeof c->gpio.file, "%s", t->name);
    return parse_text(t, c);
}

cub_err cub_boxconf_load(const char *path, cub_boxconf *cfg, char *err, size_t err_size)
{
    if (!path || !cfg || !err || err_size == 0) {
        return CUB_ERR_ARG;
    }
    err[0] = '\0';
    cub_diag d = {0};
    cub_text_src src = {path, "config file", MAX_BYTES};
    return cub_diag_report(cub_text_load(&src, load_text, NULL, cfg, &d), &d, err, err_size);
}

int cub_boxconf_key_count(void)
{
    return KEY_COUNT;
}

const char *cub_boxconf_key_name(int k)
{
    return k >= 0 && k < KEY_COUNT ? keys[k].name : NULL;
}

void cub_boxconf_value_str(const cub_boxconf *cfg, int k, char *buf, size_t size)
{
    if (k < 0 || k >= KEY_COUNT || !buf || size == 0) {
        return;
    }
    const char *at = (const char *)cfg + keys[k].off;
    switch (keys[k].kind) {
    case K_INT:
    case K_BOOL:
        snprintf(buf, size, "%d", *(const int *)at);
        break;
    case K_SIZE:
        if (cfg->width == 0) {
            snprintf(buf, size, "auto");
        } else {
            snprintf(buf, size, "%dx%d", cfg->width, cfg->height);
        }
        break;
    default:
        snprintf(buf, size, "%s", at);
    }
}

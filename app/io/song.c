/* song — reading a choreography file and validating it against the clip
 * library (cub/song.h; README.md, "Songs"). Every problem is "file:line: what". */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/song.h"
#include "cub/xml.h"

#define MAX_BARS 2000

static cub_err known_attrs(const cub_xml_el *el, const char *const *known, cub_diag *diag)
{
    const char *bad = cub_xml_unknown_attr(el, known);
    return bad ? cub_xml_fail_attr(el, bad, diag, "<%s> has an unknown attribute '%s'",
                                   cub_xml_name(el), bad)
               : CUB_OK;
}

/* A required text attribute that fits in size bytes (and is not empty). */
static cub_err get_text(const cub_xml_el *el, const char *attr, char *out, size_t size,
                        cub_diag *diag)
{
    const char *s = cub_xml_attr(el, attr);
    if (!s) return cub_xml_fail(el, diag, "<%s> needs %s=\"...\"", cub_xml_name(el), attr);
    if (!s[0]) return cub_xml_fail_attr(el, attr, diag, "%s is empty", attr);
    if (strlen(s) >= size)
        return cub_xml_fail_attr(el, attr, diag, "%s is longer than %zu characters", attr,
                                 size - 1);
    memcpy(out, s, strlen(s) + 1);
    return CUB_OK;
}

static cub_err get_meter(const cub_xml_el *el, cub_song *s, cub_diag *diag)
{
    const char *m = cub_xml_attr(el, "meter");
    if (!m) return cub_xml_fail(el, diag, "<song> needs meter=\"N/D\" (e.g. \"4/4\")");
    int num = 0, den = 0, used = 0;
    if (sscanf(m, "%2d/%2d%n", &num, &den, &used) != 2 || m[used] != '\0' || num < 1 || num > 16 ||
        (den != 2 && den != 4 && den != 8 && den != 16))
        return cub_xml_fail_attr(el, "meter", diag,
                                 "meter=\"%s\" is not N/D with N in 1..16 and D 2, 4, 8 or 16", m);
    s->meter_num = num;
    s->meter_den = den;
    return CUB_OK;
}

/* "RHE=true LHE=true": feature names and set names of cub/fuzzy.h. */
static cub_err get_keys(const cub_xml_el *el, cub_song_move *mv, cub_diag *diag)
{
    const char *p = cub_xml_attr(el, "keys");
    if (!p) return cub_xml_fail(el, diag, "<move> needs keys=\"FEATURE=set ...\"");
    mv->key_count = 0;
    for (;;) {
        while (*p == ' ' || *p == '\t' || *p == '\n')
            p++;
        if (!*p) break;
        char word[64];
        size_t n = strcspn(p, " \t\n");
        if (n >= sizeof(word))
            return cub_xml_fail_attr(el, "keys", diag, "key point '%.20s...' is too long", p);
        memcpy(word, p, n);
        word[n] = '\0';
        p += n;
        char *eq = strchr(word, '=');
        if (!eq)
            return cub_xml_fail_attr(el, "keys", diag, "key point '%s' is not FEATURE=set", word);
        *eq = '\0';
        int f = 0;
        while (f < CUB_FUZZY_FEATURE_COUNT && strcmp(cub_fuzzy_feature_name(f), word))
            f++;
        if (f == CUB_FUZZY_FEATURE_COUNT)
            return cub_xml_fail_attr(el, "keys", diag,
                                     "key point '%s': no fuzzy feature '%s' (RH RHE LH LHE "
                                     "Posture Trunk RF RFK LF LFK)",
                                     word, word);
        int set = 0, sets = cub_fuzzy_set_count(f);
        while (set < sets && strcmp(cub_fuzzy_set_name(f, set), eq + 1))
            set++;
        if (set == sets)
            return cub_xml_fail_attr(el, "keys", diag, "key point %s=%s: %s has no set '%s'", word,
                                     eq + 1, word, eq + 1);
        for (int k = 0; k < mv->key_count; k++)
            if (mv->keys[k].feature == (cub_fuzzy_feature)f)
                return cub_xml_fail_attr(el, "keys", diag, "key point %s is given twice", word);
        if (mv->key_count == CUB_SONG_MAX_KEYS)
            return cub_xml_fail_attr(el, "keys", diag, "more than %d key points",
                                     CUB_SONG_MAX_KEYS);
        mv->keys[mv->key_count++] = (cub_song_key){(cub_fuzzy_feature)f, set};
    }
    if (mv->key_count == 0) return cub_xml_fail_attr(el, "keys", diag, "keys is empty");
    return CUB_OK;
}

static cub_err get_icon(const cub_xml_el *el, cub_song_move *mv, cub_diag *diag)
{
    cub_err e = get_text(el, "icon", mv->icon, sizeof(mv->icon), diag);
    if (e) return e;
    for (const char *c = mv->icon; *c; c++)
        if (!((*c >= 'a' && *c <= 'z') || (*c >= '0' && *c <= '9') || *c == '_'))
            return cub_xml_fail_attr(el, "icon", diag, "icon=\"%s\" is not a name of [a-z0-9_]",
                                     mv->icon);
    return CUB_OK;
}

/* The clip must be a kid move of the library, and reps of it must fill the
 * span at a speed the coach can play (within ±CUB_SONG_SPEED_PCT %). */
static cub_err check_clip(const cub_xml_el *el, const cub_library *lib, cub_song_move *mv,
                          cub_diag *diag)
{
    int c = cub_library_find(lib, mv->clip);
    if (c < 0) return cub_xml_fail_attr(el, "clip", diag, "the library has no clip '%s'", mv->clip);
    if (strcmp(lib->clips[c].kind, "dance") != 0)
        return cub_xml_fail_attr(el, "clip", diag, "clip '%s' is a %s clip, not a kid's move",
                                 mv->clip, lib->clips[c].kind);
    mv->clip_index = c;
    const cub_clip *clip = &lib->clips[c].clip;
    /* A repetition plays the clip from its first frame to its last: one
     * frame interval fewer than it has frames (the last meets the next
     * repetition's first). */
    int64_t clip_us = (int64_t)(clip->frame_count - 1) * clip->frame_ns / 1000;
    int64_t dance_us = clip_us * mv->reps, span_us = mv->end_us - mv->start_us;
    if (clip_us <= 0 || span_us <= 0)
        return cub_xml_fail(el, diag, "clip '%s' or its span has no length", mv->clip);
    int64_t permille = (dance_us * 1000 + span_us / 2) / span_us;
    mv->speed_permille = (int)(permille > 1000000 ? 1000000 : permille);
    if (permille < 1000 - 10 * CUB_SONG_SPEED_PCT || permille > 1000 + 10 * CUB_SONG_SPEED_PCT)
        return cub_xml_fail(el, diag,
                            "%s x%d lasts %.2f s at speed 1 but bars %d-%d last %.2f s (speed "
                            "%.2f; the coach plays a move at 1 +-%d%%)",
                            mv->clip, mv->reps, (double)dance_us / 1e6, mv->bar,
                            mv->bar + mv->bars - 1, (double)span_us / 1e6, (double)permille / 1e3,
                            CUB_SONG_SPEED_PCT);
    return CUB_OK;
}

/* bar="B" bars="N" of a <move> or <free>: inside the song, after the bar
 * *before* ends (prev_end_bar). */
static cub_err read_bar_span(const cub_xml_el *el, const cub_song *s, int prev_end_bar,
                             const char *before, int *bar, int *bars, cub_diag *diag)
{
    cub_err e = cub_xml_get_int(el, "bar", 1, s->bars, bar, diag);
    if (!e) e = cub_xml_get_int(el, "bars", 1, s->bars, bars, diag);
    if (e) return e;
    if (*bar < prev_end_bar)
        return cub_xml_fail_attr(el, "bar", diag, "bar=%d overlaps %s, which lasts until bar %d",
                                 *bar, before, prev_end_bar - 1);
    if (*bar + *bars - 1 > s->bars)
        return cub_xml_fail_attr(el, "bars", diag, "bars %d-%d pass the song's end (bar %d)",
                                 *bar, *bar + *bars - 1, s->bars);
    return CUB_OK;
}

static cub_err read_move(const cub_xml_el *el, const cub_library *lib, cub_song *s,
                         cub_song_move *mv, int prev_end_bar, cub_diag *diag)
{
    static const char *const known[] = {"clip", "reps", "bar",  "bars",
                                        "keys", "hint", "icon", NULL};
    memset(mv, 0, sizeof(*mv));
    mv->line = cub_xml_line(el);
    cub_err e = known_attrs(el, known, diag);
    if (!e) e = get_text(el, "clip", mv->clip, sizeof(mv->clip), diag);
    if (!e) e = cub_xml_get_int(el, "reps", 1, 1000, &mv->reps, diag);
    if (!e && mv->reps < CUB_SONG_MIN_REPS)
        return cub_xml_fail_attr(el, "reps", diag,
                                 "reps=%d: each move plays at least %d times in a row", mv->reps,
                                 CUB_SONG_MIN_REPS);
    if (!e) e = read_bar_span(el, s, prev_end_bar, "the previous move", &mv->bar, &mv->bars, diag);
    if (e) return e;
    mv->start_us = cub_song_bar_us(s, mv->bar);
    mv->end_us = cub_song_bar_us(s, mv->bar + mv->bars);
    e = get_keys(el, mv, diag);
    if (!e) e = get_text(el, "hint", mv->hint, sizeof(mv->hint), diag);
    if (!e) e = get_icon(el, mv, diag);
    if (!e) e = check_clip(el, lib, mv, diag);
    return e;
}

static int count_distinct(const cub_song *s)
{
    int n = 0;
    for (int i = 0; i < s->move_count; i++) {
        int seen = 0;
        for (int j = 0; j < i && !seen; j++)
            seen = s->moves[j].clip_index == s->moves[i].clip_index;
        n += !seen;
    }
    return n;
}

/* A file the song names (its MIDI, its fault words) sits beside the song
 * file unless it is absolute: value of attr into path. */
static cub_err resolve_beside(const cub_xml_el *el, const char *attr, const char *name,
                              const char *value, char *path, size_t size, cub_diag *diag)
{
    const char *slash = strrchr(name, '/');
    int dir = value[0] == '/' || !slash ? 0 : (int)(slash - name + 1);
    if (strstr(value, "..") || (size_t)dir + strlen(value) >= size)
        return cub_xml_fail_attr(el, attr, diag, "%s=\"%s\" is not a file name beside the song",
                                 attr, value);
    snprintf(path, size, "%.*s%s", dir, name, value);
    return CUB_OK;
}

/* faults="..." is optional: without it a wrong move shows its own hint. */
static cub_err get_faults(const cub_xml_el *el, const char *name, cub_song *s, cub_diag *diag)
{
    if (!cub_xml_attr(el, "faults")) return CUB_OK;
    cub_err e = get_text(el, "faults", s->faults, sizeof(s->faults), diag);
    return e ? e
             : resolve_beside(el, "faults", name, s->faults, s->faults_path,
                              sizeof(s->faults_path), diag);
}

/* <free bar="B" bars="N"/>: bars the bear grooves through (cub_song_spans). */
static cub_err read_free(const cub_xml_el *el, cub_song *s, int prev_end_bar, cub_diag *diag)
{
    static const char *const known[] = {"bar", "bars", NULL};
    if (s->free_count == CUB_SONG_MAX_FREE)
        return cub_xml_fail(el, diag, "more than %d <free> spans", CUB_SONG_MAX_FREE);
    cub_song_free *f = &s->frees[s->free_count];
    memset(f, 0, sizeof(*f));
    f->line = cub_xml_line(el);
    cub_err e = known_attrs(el, known, diag);
    if (!e) e = read_bar_span(el, s, prev_end_bar, "the move or <free> before", &f->bar, &f->bars,
                              diag);
    if (e) return e;
    f->start_us = cub_song_bar_us(s, f->bar);
    f->end_us = cub_song_bar_us(s, f->bar + f->bars);
    s->free_count++;
    return CUB_OK;
}

/* One child of <song>, a <move> or a <free>, after the bar *prev_end_bar. */
static cub_err read_child(const cub_xml_el *el, const cub_library *lib, cub_song *s,
                          int *prev_end_bar, cub_diag *diag)
{
    if (strcmp(cub_xml_name(el), "free") == 0) {
        cub_err e = read_free(el, s, *prev_end_bar, diag);
        if (!e) *prev_end_bar = s->frees[s->free_count - 1].bar + s->frees[s->free_count - 1].bars;
        return e;
    }
    if (strcmp(cub_xml_name(el), "move") != 0)
        return cub_xml_fail(el, diag, "unknown element <%s> (a song holds <move>s and <free>s)",
                            cub_xml_name(el));
    if (s->move_count == CUB_SONG_MAX_MOVES)
        return cub_xml_fail(el, diag, "more than %d moves", CUB_SONG_MAX_MOVES);
    cub_song_move *mv = &s->moves[s->move_count];
    cub_err e = read_move(el, lib, s, mv, *prev_end_bar, diag);
    if (e) return e;
    *prev_end_bar = mv->bar + mv->bars;
    s->move_count++;
    s->distinct_moves = count_distinct(s);
    if (s->distinct_moves > CUB_SONG_MAX_DISTINCT)
        return cub_xml_fail(el, diag, "'%s' is the song's %dth different move; at most %d",
                            mv->clip, s->distinct_moves, CUB_SONG_MAX_DISTINCT);
    return CUB_OK;
}

static cub_err read_song(const cub_xml_el *root, const char *name, const cub_library *lib,
                         cub_song *s, cub_diag *diag)
{
    static const char *const known[] = {"version", "name",  "midi", "faults",
                                        "bpm",     "meter", "bars", NULL};
    int version = 0;
    if (strcmp(cub_xml_name(root), "song") != 0)
        return cub_xml_fail(root, diag, "the root element is <%s>, not <song>", cub_xml_name(root));
    cub_err e = known_attrs(root, known, diag);
    if (!e) e = cub_xml_get_int(root, "version", 1, 1, &version, diag);
    if (!e) e = get_text(root, "name", s->name, sizeof(s->name), diag);
    if (!e) e = get_text(root, "midi", s->midi, sizeof(s->midi), diag);
    if (!e)
        e = resolve_beside(root, "midi", name, s->midi, s->midi_path, sizeof(s->midi_path), diag);
    if (!e) e = get_faults(root, name, s, diag);
    if (!e) e = cub_xml_get_int(root, "bpm", 30, 300, &s->bpm, diag);
    if (!e) e = get_meter(root, s, diag);
    if (!e) e = cub_xml_get_int(root, "bars", 1, MAX_BARS, &s->bars, diag);
    if (e) return e;
    int prev_end_bar = 1;
    const cub_xml_el *last = root;
    for (const cub_xml_el *el = cub_xml_child(root, NULL); el && !e; el = cub_xml_next(el, NULL)) {
        last = el;
        e = read_child(el, lib, s, &prev_end_bar, diag);
    }
    if (e) return e;
    /* No move at all: a groove song, danced to its own notes throughout. */
    if (s->move_count > 0 && s->distinct_moves < CUB_SONG_MIN_MOVES)
        return cub_xml_fail(last, diag,
                            "the song uses %d different moves; it needs %d to %d (or none: "
                            "a groove song)",
                            s->distinct_moves, CUB_SONG_MIN_MOVES, CUB_SONG_MAX_DISTINCT);
    return CUB_OK;
}

cub_err cub_song_parse(const char *text, size_t len, const char *name, const cub_library *lib,
                       cub_song *out, cub_diag *diag)
{
    cub_diag scratch;
    if (!diag) diag = &scratch;
    memset(diag, 0, sizeof(*diag));
    if (!out || !lib || (!text && len) || !name) {
        snprintf(diag->msg, sizeof(diag->msg), "cub_song_parse: bad arguments");
        return CUB_ERR_ARG;
    }
    memset(out, 0, sizeof(*out));
    cub_xml_doc *doc = NULL;
    cub_err e = cub_xml_parse(text ? text : "", len, name, &doc, diag);
    if (e) return e;
    e = read_song(cub_xml_root(doc), name, lib, out, diag);
    cub_xml_free(doc);
    if (e) memset(out, 0, sizeof(*out));
    return e;
}

static cub_err parse_text(const cub_text *t, const void *lib, void *out)
{
    return cub_song_parse(t->s, t->len, t->name, lib, out, t->diag);
}

cub_err cub_song_load(const char *path, const cub_library *lib, cub_song *out, cub_diag *diag)
{
    cub_diag scratch; /* cub_song_parse wants one */
    cub_text_src src = {path, "song", CUB_TEXT_MAX_SONG};
    return cub_text_load(&src, parse_text, lib, out, diag ? diag : &scratch);
}

int64_t cub_song_bar_us(const cub_song *song, int bar)
{
    if (!song || song->bpm <= 0 || song->meter_den <= 0 || bar < 1) return 0;
    return (int64_t)(bar - 1) * song->meter_num * 240000000 /
           ((int64_t)song->meter_den * song->bpm);
}

int64_t cub_song_length_us(const cub_song *song)
{
    return song ? cub_song_bar_us(song, song->bars + 1) : 0;
}

int cub_song_move_at(const cub_song *song, int64_t t_us)
{
    for (int i = 0; song && i < song->move_count; i++)
        if (t_us >= song->moves[i].start_us && t_us < song->moves[i].end_us) return i;
    return -1;
}

/* ---- spans ---------------------------------------------------------------- */

static int push_span(cub_song_span *out, int n, int max, cub_song_span sp)
{
    if (sp.bars <= 0) return n;
    if (n < max) out[n] = sp;
    return n + 1;
}

/* The unmarked bars [from, to) before the next move or free (or the end). */
static cub_song_span plain_span(const cub_song *s, int from, int to, int moves_before)
{
    int kind = moves_before == 0                ? CUB_SONG_SPAN_INTRO
               : moves_before == s->move_count ? CUB_SONG_SPAN_OUTRO
                                                : CUB_SONG_SPAN_GAP;
    return (cub_song_span){kind, -1, from, to - from, cub_song_bar_us(s, from),
                           cub_song_bar_us(s, to)};
}

int cub_song_spans(const cub_song *song, cub_song_span *out, int max)
{
    if (!song || song->bars < 1 || (!out && max > 0)) return 0;
    int n = 0, bar = 1, m = 0, f = 0;
    while (m < song->move_count || f < song->free_count) {
        /* moves and frees are each in bar order and never overlap */
        int take_move = f == song->free_count ||
                        (m < song->move_count && song->moves[m].bar < song->frees[f].bar);
        int at = take_move ? song->moves[m].bar : song->frees[f].bar;
        int bars = take_move ? song->moves[m].bars : song->frees[f].bars;
        n = push_span(out, n, max, plain_span(song, bar, at, m));
        cub_song_span sp = {take_move ? CUB_SONG_SPAN_MOVE : CUB_SONG_SPAN_FREE,
                            take_move ? m : f, at, bars, cub_song_bar_us(song, at),
                            cub_song_bar_us(song, at + bars)};
        n = push_span(out, n, max, sp);
        bar = at + bars;
        m += take_move;
        f += !take_move;
    }
    n = push_span(out, n, max, plain_span(song, bar, song->bars + 1, m));
    return n < max ? n : max;
}

int cub_song_groove_spans(const cub_song *song, cub_song_span *out, int max)
{
    cub_song_span all[CUB_SONG_MAX_SPANS];
    int n = cub_song_spans(song, all, CUB_SONG_MAX_SPANS), k = 0;
    for (int i = 0; i < n; i++)
        if (all[i].kind != CUB_SONG_SPAN_MOVE && k < max) out[k++] = all[i];
    return k;
}

const char *cub_song_span_name(int kind)
{
    static const char *const names[] = {"move", "intro", "gap", "free", "outro"};
    return kind >= 0 && kind <= CUB_SONG_SPAN_OUTRO ? names[kind] : "?";
}

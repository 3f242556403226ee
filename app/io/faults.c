/* faults — reading the fault words table (cub/faults.h). */
#include <stdio.h>
#include <string.h>

#include "cub/faults.h"
#include "cub/fuzzy.h"
#include "cub/judge.h"

typedef struct faults_parse {
    cub_faults *out;
    const cub_library *lib;
} faults_parse;

/* The next blank-separated word of *p (cut in place), or NULL at the end. */
static char *next_word(char **p)
{
    char *s = *p;
    while (*s == ' ' || *s == '\t')
        s++;
    if (!*s) return NULL;
    char *w = s;
    while (*s && *s != ' ' && *s != '\t')
        s++;
    if (*s) *s++ = '\0';
    *p = s;
    return w;
}

static cub_err get_key(char *word, cub_fault_words *fw, const cub_text_at *at)
{
    char *eq = strchr(word, '=');
    if (!eq) return cub_text_fail(at, "'%s' is not a key point FEATURE=set", word);
    *eq = '\0';
    int f = 0;
    while (f < CUB_FUZZY_FEATURE_COUNT && strcmp(cub_fuzzy_feature_name(f), word))
        f++;
    if (f == CUB_FUZZY_FEATURE_COUNT)
        return cub_text_fail(at,
                             "no fuzzy feature '%s' (RH RHE LH LHE Posture Trunk RF RFK LF LFK)",
                             word);
    int set = 0, sets = cub_fuzzy_set_count(f);
    while (set < sets && strcmp(cub_fuzzy_set_name(f, set), eq + 1))
        set++;
    if (set == sets) return cub_text_fail(at, "%s has no set '%s'", word, eq + 1);
    fw->feature = f;
    fw->set = set;
    return CUB_OK;
}

static cub_err get_how(const char *word, cub_fault_words *fw, const cub_text_at *at)
{
    if (!word) return cub_text_fail(at, "the key needs how it failed: missed or mirror");
    if (!strcmp(word, "missed")) fw->how = CUB_JUDGE_HOW_MISSED;
    else if (!strcmp(word, "mirror")) fw->how = CUB_JUDGE_HOW_MIRROR;
    else return cub_text_fail(at, "'%s' is not how a key fails (missed or mirror)", word);
    int sided = fw->feature != CUB_FUZZY_POSTURE && fw->feature != CUB_FUZZY_TRUNK;
    if (fw->how == CUB_JUDGE_HOW_MIRROR && !sided)
        return cub_text_fail(at, "%s has no other side to mirror",
                             cub_fuzzy_feature_name(fw->feature));
    return CUB_OK;
}

static cub_err get_clip(const char *name, const faults_parse *p, cub_fault_words *fw,
                        const cub_text_at *at)
{
    if (!name[0] || strlen(name) >= sizeof fw->clip)
        return cub_text_fail(at, "for= needs a clip name of 1 to %zu characters",
                             sizeof fw->clip - 1);
    if (p->lib) {
        int c = cub_library_find(p->lib, name);
        if (c < 0) return cub_text_fail(at, "the library has no clip '%s'", name);
        if (strcmp(p->lib->clips[c].kind, "dance") != 0)
            return cub_text_fail(at, "clip '%s' is a %s clip, not a kid's move", name,
                                 p->lib->clips[c].kind);
    }
    memcpy(fw->clip, name, strlen(name) + 1);
    return CUB_OK;
}

/* Bytes that are UTF-8: the words are drawn and spoken. */
static int utf8_ok(const unsigned char *s, size_t n)
{
    for (size_t i = 0; i < n;) {
        unsigned char c = s[i];
        size_t len = c < 0x80 ? 1 : (c & 0xe0) == 0xc0 ? 2 : (c & 0xf0) == 0xe0 ? 3
                                  : (c & 0xf8) == 0xf0 ? 4 : 0;
        if (!len || (len == 2 && c < 0xc2) || i + len > n) return 0;
        for (size_t k = 1; k < len; k++)
            if ((s[i + k] & 0xc0) != 0x80) return 0;
        if (len == 3 && c == 0xed && s[i + 1] >= 0xa0) return 0; /* a UTF-16 surrogate */
        i += len;
    }
    return 1;
}

/* The rest of the line, without trailing blanks: what the child is told. */
static cub_err get_words(char *rest, cub_fault_words *fw, const cub_text_at *at)
{
    while (*rest == ' ' || *rest == '\t')
        rest++;
    size_t n = strlen(rest);
    while (n > 0 && (rest[n - 1] == ' ' || rest[n - 1] == '\t'))
        n--;
    if (n == 0) return cub_text_fail(at, "no words to say");
    if (n >= sizeof fw->words)
        return cub_text_fail(at, "the words are longer than %zu bytes", sizeof fw->words - 1);
    for (size_t i = 0; i < n; i++)
        if ((unsigned char)rest[i] < 0x20 || rest[i] == 0x7f)
            return cub_text_fail(at, "the words hold a control character (byte %zu)", i + 1);
    if (!utf8_ok((const unsigned char *)rest, n))
        return cub_text_fail(at, "the words are not UTF-8");
    memcpy(fw->words, rest, n);
    fw->words[n] = '\0';
    return CUB_OK;
}

static int same_line(const cub_fault_words *a, const cub_fault_words *b)
{
    return a->how == b->how && a->feature == b->feature && a->set == b->set &&
           !strcmp(a->clip, b->clip);
}

static cub_err faults_line(void *ctx, cub_text_line *ln)
{
    faults_parse *p = ctx;
    const cub_text_at *at = &ln->at;
    if (p->out->count == CUB_FAULTS_MAX)
        return cub_text_fail(at, "more than %d lines", CUB_FAULTS_MAX);
    cub_fault_words fw = {.line = at->line};
    char *rest = ln->s, *key = next_word(&rest);
    cub_err e = key ? get_key(key, &fw, at) : cub_text_fail(at, "an empty line");
    if (!e) e = get_how(next_word(&rest), &fw, at);
    if (e) return e;
    rest += strspn(rest, " \t");
    if (!strncmp(rest, "for=", 4)) e = get_clip(next_word(&rest) + 4, p, &fw, at);
    if (!e) e = get_words(rest, &fw, at);
    if (e) return e;
    for (int i = 0; i < p->out->count; i++)
        if (same_line(&p->out->w[i], &fw))
            return cub_text_fail(at, "%s=%s %s%s%s is given twice (first on line %d)",
                                 cub_fuzzy_feature_name(fw.feature),
                                 cub_fuzzy_set_name(fw.feature, fw.set), cub_judge_how_name(fw.how),
                                 fw.clip[0] ? " for=" : "", fw.clip, p->out->w[i].line);
    p->out->w[p->out->count++] = fw;
    return CUB_OK;
}

static cub_err parse_text(const cub_text *t, const void *lib, void *out)
{
    faults_parse p = {out, lib};
    memset(p.out, 0, sizeof *p.out);
    cub_err e = cub_text_lines(t, faults_line, &p);
    if (e) memset(p.out, 0, sizeof *p.out);
    return e;
}

cub_err cub_faults_parse(const char *text, size_t len, const char *name, const cub_library *lib,
                         cub_faults *out, cub_diag *diag)
{
    cub_text t = {text, len, name ? name : "(faults)", diag};
    return cub_text_parse(&t, parse_text, lib, out);
}

cub_err cub_faults_load(const char *path, const cub_library *lib, cub_faults *out,
                        cub_diag *diag)
{
    return cub_text_load(&(cub_text_src){path, "fault words", CUB_TEXT_MAX_SMALL}, parse_text, lib,
                         out, diag);
}

const char *cub_faults_words(const cub_faults *f, const char *clip, int32_t how, int32_t feature,
                             int32_t set)
{
    const char *general = NULL;
    for (int i = 0; f && i < f->count; i++) {
        const cub_fault_words *w = &f->w[i];
        if (w->how != how || w->feature != feature || w->set != set) continue;
        if (!w->clip[0]) general = w->words;
        else if (clip && !strcmp(w->clip, clip)) return w->words;
    }
    return general;
}

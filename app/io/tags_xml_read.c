/* tags_xml_read — reading a bridge tag file and validating it against the
 * clip library it names: every problem is reported as "file:line: what"
 * (schema: README.md, "Bridge tags (XML)"). A file that passes holds only
 * links between bridge frames, in search order, below its threshold. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/tags.h"
#include "cub/xml.h"

#define CLASS_BITS (2 * CUB_FUZZY_FEATURE_COUNT) /* cub_fuzzy_crisp_class */

typedef struct reader {
    const cub_library *lib;
    cub_tags *t;
    cub_diag *diag;
    unsigned char *seen_pair; /* [from * n + to] */
} reader;

/* A number attribute in [lo, hi] as Q16.16 (rounded to the nearest step). */
static cub_err get_q16(const cub_xml_el *el, const char *attr, double lo, double hi, cub_q16 *out,
                       cub_diag *diag)
{
    double v = 0;
    cub_err e = cub_xml_attr_double(el, attr, &v);
    if (e == CUB_ERR_EMPTY)
        return cub_xml_fail(el, diag, "<%s> needs %s=\"...\"", cub_xml_name(el), attr);
    if (e) return cub_xml_fail(el, diag, "%s=\"%s\" is not a number", attr, cub_xml_attr(el, attr));
    if (!(v >= lo && v <= hi))
        return cub_xml_fail(el, diag, "%s=%s is outside [%g, %g]", attr, cub_xml_attr(el, attr), lo,
                            hi);
    *out = (cub_q16)floor(v * 65536.0 + 0.5);
    return CUB_OK;
}

static cub_err known_attrs(const cub_xml_el *el, const char *const *known, cub_diag *diag)
{
    const char *bad = cub_xml_unknown_attr(el, known);
    return bad ? cub_xml_fail(el, diag, "<%s> has an unknown attribute '%s'", cub_xml_name(el), bad)
               : CUB_OK;
}

static int find_clip(const cub_library *lib, const char *name)
{
    for (int c = 0; name && c < lib->clip_count; c++)
        if (strcmp(lib->clips[c].name, name) == 0) return c;
    return -1;
}

/* "0x" and hex digits, at most CLASS_BITS bits. */
static cub_err get_class(const cub_xml_el *el, uint32_t *out, cub_diag *diag)
{
    const char *s = cub_xml_attr(el, "class");
    if (!s) return cub_xml_fail(el, diag, "<bridge> needs class=\"0x...\"");
    uint32_t v = 0;
    int digits = 0;
    if (s[0] == '0' && s[1] == 'x')
        for (const char *p = s + 2; *p && digits <= 8; p++, digits++) {
            int h = *p >= '0' && *p <= '9'   ? *p - '0'
                    : *p >= 'a' && *p <= 'f' ? *p - 'a' + 10
                    : *p >= 'A' && *p <= 'F' ? *p - 'A' + 10
                                             : -1;
            if (h < 0) {
                digits = 0;
                break;
            }
            v = v << 4 | (uint32_t)h;
        }
    if (digits < 1 || digits > 8 || v >> CLASS_BITS)
        return cub_xml_fail(el, diag,
                            "class=\"%s\" is not a pose class (0x and at most %d bits of hex)", s,
                            CLASS_BITS);
    *out = v;
    return CUB_OK;
}

static cub_err read_weights(const cub_xml_el *el, cub_tag_params *p, cub_diag *diag)
{
    const char *known[CUB_FUZZY_FEATURE_COUNT + 1];
    int64_t sum = 0;
    for (int f = 0; f < CUB_FUZZY_FEATURE_COUNT; f++) {
        known[f] = cub_fuzzy_feature_name((cub_fuzzy_feature)f);
        cub_err e = get_q16(el, known[f], 0.0, 1.0, &p->fuzzy.weight[f], diag);
        if (e) return e;
        sum += p->fuzzy.weight[f];
    }
    known[CUB_FUZZY_FEATURE_COUNT] = NULL;
    if (known_attrs(el, known, diag)) return CUB_ERR_FORMAT;
    /* Normalised weights keep d within [0, 1]; allow the rounding of ten
     * printed values. */
    if (sum < CUB_Q16_ONE - 66 || sum > CUB_Q16_ONE + 66)
        return cub_xml_fail(el, diag, "the weights sum to %.5f, not 1", (double)sum / 65536.0);
    return CUB_OK;
}

static cub_err read_tagging(const cub_xml_el *el, cub_tag_params *p, cub_diag *diag)
{
    static const char *const known[] = {"class_share", "class_clips", "head_dps",
                                        "spacing_ms",  "max_links",   NULL};
    cub_err e = known_attrs(el, known, diag);
    if (!e) e = get_q16(el, "class_share", 0.0, 1.0, &p->class_share, diag);
    if (!e) e = cub_xml_get_int(el, "class_clips", 1, 1000000, &p->class_clips, diag);
    if (!e) e = get_q16(el, "head_dps", 0.0, 30000.0, &p->head_dps, diag);
    if (!e) e = cub_xml_get_int(el, "spacing_ms", 1, 1000000, &p->spacing_ms, diag);
    if (!e) e = cub_xml_get_int(el, "max_links", -1, 1000000, &p->max_links, diag);
    if (!e && p->max_links == 0)
        return cub_xml_fail(el, diag, "max_links=0 would keep no link (-1 keeps all)");
    return e;
}

static cub_err read_clip(reader *r, const cub_xml_el *el)
{
    static const char *const known[] = {"name", "frames", NULL};
    static const char *const bridge_known[] = {"frame", "class", NULL};
    const char *name = cub_xml_attr(el, "name");
    if (known_attrs(el, known, r->diag)) return CUB_ERR_FORMAT;
    if (!name) return cub_xml_fail(el, r->diag, "<clip> needs name=\"...\"");
    int c = find_clip(r->lib, name);
    if (c < 0) return cub_xml_fail(el, r->diag, "the library has no clip '%s'", name);
    cub_tag_clip *tc = &r->t->clips[c];
    if (tc->name[0]) return cub_xml_fail(el, r->diag, "clip '%s' is tagged twice", name);
    int frames = 0, lib_frames = r->lib->clips[c].clip.frame_count;
    if (cub_xml_get_int(el, "frames", 1, INT32_MAX, &frames, r->diag)) return CUB_ERR_FORMAT;
    if (frames != lib_frames)
        return cub_xml_fail(el, r->diag,
                            "clip '%s' has %d frames in the library, not %d (stale tags?)", name,
                            lib_frames, frames);
    snprintf(tc->name, sizeof tc->name, "%s", name);
    tc->frame_count = frames;
    int count = 0;
    for (cub_xml_el *b = cub_xml_child(el, NULL); b; b = cub_xml_next(b, NULL), count++)
        if (strcmp(cub_xml_name(b), "bridge") != 0)
            return cub_xml_fail(b, r->diag, "unexpected <%s> in <clip> (only <bridge>)",
                                cub_xml_name(b));
    tc->bridges = malloc(sizeof *tc->bridges * (size_t)(count ? count : 1));
    if (!tc->bridges) return CUB_ERR_NOMEM;
    for (cub_xml_el *b = cub_xml_child(el, "bridge"); b; b = cub_xml_next(b, "bridge")) {
        cub_tag_bridge *tb = &tc->bridges[tc->bridge_count];
        if (known_attrs(b, bridge_known, r->diag) ||
            cub_xml_get_int(b, "frame", 0, frames - 1, &tb->frame, r->diag) ||
            get_class(b, &tb->crisp_class, r->diag))
            return CUB_ERR_FORMAT;
        if (tc->bridge_count > 0 && tb->frame <= tb[-1].frame)
            return cub_xml_fail(b, r->diag, "bridge frame %d after %d: frames must ascend",
                                tb->frame, tb[-1].frame);
        tc->bridge_count++;
    }
    return CUB_OK;
}

static int is_bridge(const cub_tag_clip *c, int frame)
{
    int lo = 0, hi = c->bridge_count - 1;
    while (lo <= hi) {
        int mid = (lo + hi) / 2;
        if (c->bridges[mid].frame == frame) return 1;
        if (c->bridges[mid].frame < frame)
            lo = mid + 1;
        else
            hi = mid - 1;
    }
    return 0;
}

/* Links come in search order: by a, then front before back, then d, then b. */
static int in_order(const cub_tag_link *prev, const cub_tag_link *l)
{
    if (prev->a != l->a) return prev->a < l->a;
    if (prev->half != l->half) return prev->half < l->half;
    if (prev->d != l->d) return prev->d < l->d;
    return prev->b < l->b;
}

static cub_err read_link(reader *r, const cub_xml_el *k, int from, int to, cub_tag_link *l)
{
    static const char *const known[] = {"a", "b", "d", "half", NULL};
    const cub_tag_clip *A = &r->t->clips[from], *B = &r->t->clips[to];
    double thr = (double)r->t->params.fuzzy.threshold / 65536.0;
    if (known_attrs(k, known, r->diag) || cub_xml_get_int(k, "a", 0, A->frame_count - 1, &l->a, r->diag) ||
        cub_xml_get_int(k, "b", 0, B->frame_count - 1, &l->b, r->diag) ||
        get_q16(k, "d", 0.0, 1.0, &l->d, r->diag))
        return CUB_ERR_FORMAT;
    if (!is_bridge(A, l->a))
        return cub_xml_fail(k, r->diag, "a=%d is not a bridge frame of clip '%s'", l->a, A->name);
    if (!is_bridge(B, l->b))
        return cub_xml_fail(k, r->diag, "b=%d is not a bridge frame of clip '%s'", l->b, B->name);
    if (l->d >= r->t->params.fuzzy.threshold)
        return cub_xml_fail(k, r->diag, "d=%s is not below the threshold %g", cub_xml_attr(k, "d"),
                            thr);
    const char *half = cub_xml_attr(k, "half");
    cub_tag_half want = 2 * l->b < B->frame_count ? CUB_TAG_FRONT : CUB_TAG_BACK;
    if (!half || (strcmp(half, "front") != 0 && strcmp(half, "back") != 0))
        return cub_xml_fail(k, r->diag, "<link> needs half=\"front\" or half=\"back\"");
    l->half = strcmp(half, "front") == 0 ? CUB_TAG_FRONT : CUB_TAG_BACK;
    if (l->half != want)
        return cub_xml_fail(k, r->diag, "b=%d lies in the %s half of '%s' (%d frames), not the %s",
                            l->b, want == CUB_TAG_FRONT ? "front" : "back", B->name, B->frame_count,
                            half);
    return CUB_OK;
}

static cub_err read_links(reader *r, const cub_xml_el *el)
{
    static const char *const known[] = {"from", "to", NULL};
    int n = r->t->clip_count;
    const char *fs = cub_xml_attr(el, "from"), *ts = cub_xml_attr(el, "to");
    if (known_attrs(el, known, r->diag)) return CUB_ERR_FORMAT;
    if (!fs || !ts) return cub_xml_fail(el, r->diag, "<links> needs from=\"...\" and to=\"...\"");
    int from = find_clip(r->lib, fs), to = find_clip(r->lib, ts);
    if (from < 0 || to < 0)
        return cub_xml_fail(el, r->diag, "the library has no clip '%s'", from < 0 ? fs : ts);
    if (r->seen_pair[from * n + to]++)
        return cub_xml_fail(el, r->diag, "links from '%s' to '%s' are listed twice", fs, ts);
    cub_tag_pair *pair = &r->t->pairs[from * n + to];
    int count = 0;
    for (cub_xml_el *k = cub_xml_child(el, NULL); k; k = cub_xml_next(k, NULL), count++)
        if (strcmp(cub_xml_name(k), "link") != 0)
            return cub_xml_fail(k, r->diag, "unexpected <%s> in <links> (only <link>)",
                                cub_xml_name(k));
    if (count == 0)
        return cub_xml_fail(el, r->diag, "<links> from '%s' to '%s' holds no <link>", fs, ts);
    pair->links = malloc(sizeof *pair->links * (size_t)count);
    if (!pair->links) return CUB_ERR_NOMEM;
    int per_half = 0, max = r->t->params.max_links;
    for (cub_xml_el *k = cub_xml_child(el, "link"); k; k = cub_xml_next(k, "link")) {
        cub_tag_link *l = &pair->links[pair->link_count];
        if (read_link(r, k, from, to, l)) return CUB_ERR_FORMAT;
        const cub_tag_link *prev = pair->link_count ? l - 1 : NULL;
        if (prev && !in_order(prev, l))
            return cub_xml_fail(k, r->diag,
                                "links must come by a, front before back, then d, then b");
        per_half = prev && prev->a == l->a && prev->half == l->half ? per_half + 1 : 1;
        if (max > 0 && per_half > max)
            return cub_xml_fail(k, r->diag, "more than max_links=%d links for a=%d in one half",
                                max, l->a);
        pair->link_count++;
    }
    return CUB_OK;
}

static cub_err read_root(reader *r, const cub_xml_el *root)
{
    static const char *const known[] = {"version", "library", "threshold", NULL};
    if (strcmp(cub_xml_name(root), "cubtags") != 0)
        return cub_xml_fail(root, r->diag, "the root element is <%s>, expected <cubtags>",
                            cub_xml_name(root));
    int version = 0;
    if (known_attrs(root, known, r->diag) ||
        cub_xml_get_int(root, "version", CUB_TAGS_VERSION, CUB_TAGS_VERSION, &version, r->diag))
        return CUB_ERR_FORMAT;
    const char *lib = cub_xml_attr(root, "library");
    if (!lib || !lib[0] || strlen(lib) >= CUB_TAGS_LIBRARY_LEN)
        return cub_xml_fail(root, r->diag,
                            "<cubtags> needs library=\"...\" (the clip file, < %d chars)",
                            CUB_TAGS_LIBRARY_LEN);
    snprintf(r->t->library, sizeof r->t->library, "%s", lib);
    /* A threshold of 0 would link nothing; above 1 is beyond any d. */
    if (get_q16(root, "threshold", 0.0, 1.0, &r->t->params.fuzzy.threshold, r->diag))
        return CUB_ERR_FORMAT;
    if (r->t->params.fuzzy.threshold == 0)
        return cub_xml_fail(root, r->diag, "threshold=0 would link nothing");
    return CUB_OK;
}

/* <weights> and <tagging> exactly once, <clip>s; then <links> (they need
 * every clip's bridge frames). */
static cub_err read_body(reader *r, const cub_xml_el *root)
{
    const cub_xml_el *weights = NULL, *tagging = NULL;
    for (cub_xml_el *el = cub_xml_child(root, NULL); el; el = cub_xml_next(el, NULL)) {
        const char *name = cub_xml_name(el);
        const cub_xml_el **once = !strcmp(name, "weights")   ? &weights
                                  : !strcmp(name, "tagging") ? &tagging
                                                             : NULL;
        if (once && *once) return cub_xml_fail(el, r->diag, "<%s> appears twice", name);
        if (once)
            *once = el;
        else if (!strcmp(name, "clip")) {
            cub_err e = read_clip(r, el);
            if (e) return e;
        } else if (strcmp(name, "links") != 0)
            return cub_xml_fail(el, r->diag, "unknown element <%s> in <cubtags>", name);
    }
    if (!weights || !tagging)
        return cub_xml_fail(root, r->diag, "<cubtags> needs a <%s> element",
                            weights ? "tagging" : "weights");
    if (read_weights(weights, &r->t->params, r->diag) ||
        read_tagging(tagging, &r->t->params, r->diag))
        return CUB_ERR_FORMAT;
    for (int c = 0; c < r->lib->clip_count; c++)
        if (!r->t->clips[c].name[0])
            return cub_xml_fail(root, r->diag,
                                "the library's clip '%s' is not tagged (stale tags?)",
                                r->lib->clips[c].name);
    for (cub_xml_el *el = cub_xml_child(root, "links"); el; el = cub_xml_next(el, "links")) {
        cub_err e = read_links(r, el);
        if (e) return e;
    }
    return CUB_OK;
}

cub_err cub_tags_parse(const char *text, size_t len, const char *name, const cub_library *lib,
                       cub_tags *out, cub_diag *diag)
{
    if (!text || !lib || !out || lib->clip_count < 1 || !lib->clips) return CUB_ERR_ARG;
    memset(out, 0, sizeof *out);
    if (diag) memset(diag, 0, sizeof *diag);
    cub_xml_doc *doc = NULL;
    cub_err e = cub_xml_parse(text, len, name ? name : "(tags)", &doc, diag);
    if (e) return e;
    int n = lib->clip_count;
    out->clip_count = n;
    out->clips = calloc((size_t)n, sizeof *out->clips);
    out->pairs = calloc((size_t)n * (size_t)n, sizeof *out->pairs);
    reader r = {.lib = lib, .t = out, .diag = diag, .seen_pair = calloc((size_t)n * (size_t)n, 1)};
    const cub_xml_el *root = cub_xml_root(doc);
    if (!out->clips || !out->pairs || !r.seen_pair)
        e = CUB_ERR_NOMEM;
    else if (!root)
        e = CUB_ERR_FORMAT;
    else
        e = read_root(&r, root);
    if (!e) e = read_body(&r, root);
    free(r.seen_pair);
    cub_xml_free(doc);
    if (e == CUB_ERR_NOMEM && diag) {
        snprintf(diag->file, sizeof diag->file, "%s", name ? name : "(tags)");
        snprintf(diag->msg, sizeof diag->msg, "out of memory");
    } else if (e && diag && !diag->msg[0]) {
        snprintf(diag->file, sizeof diag->file, "%s", name ? name : "(tags)");
        snprintf(diag->msg, sizeof diag->msg, "no root element");
    }
    if (e) cub_tags_free(out);
    return e;
}

static cub_err parse_text(const cub_text *t, const void *lib, void *out)
{
    return cub_tags_parse(t->s, t->len, t->name, lib, out, t->diag);
}

cub_err cub_tags_read(const char *path, const cub_library *lib, cub_tags *out, cub_diag *diag)
{
    if (!path || !lib || !out) return CUB_ERR_ARG;
    return cub_text_load(&(cub_text_src){path, "tag file", CUB_TEXT_MAX_TAGS}, parse_text, lib, out, diag);
}

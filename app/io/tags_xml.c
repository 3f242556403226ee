/* tags_xml — the bridge tag file (cub/tags.h), written and read through
 * the tinyxml2 shim (cub/xml.h). Schema: README.md, "Bridge tags (XML)".
 *
 * Writing is deterministic: clips in the library's order, pairs by (from,
 * to), links in search order, Q16.16 numbers as the shortest decimal of
 * at most 5 places that reads back as the exact Q16.16 value (5 always
 * does), so write -> read -> write gives the same bytes. Reading (tags_xml_read.c) validates
 * everything against the library. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/tags.h"
#include "cub/xml.h"

#define Q16_DECIMALS 5

void cub_tags_free(cub_tags *tags)
{
    if (!tags) return;
    for (int c = 0; tags->clips && c < tags->clip_count; c++)
        free(tags->clips[c].bridges);
    for (int i = 0; tags->pairs && i < tags->clip_count * tags->clip_count; i++)
        free(tags->pairs[i].links);
    free(tags->clips);
    free(tags->pairs);
    memset(tags, 0, sizeof *tags);
}

/* The shortest decimal (at most 5 places) that reads back as exactly v:
 * 26214 is written "0.4", not "0.39999". */
static cub_err set_q16(cub_xml_el *el, const char *attr, cub_q16 v)
{
    double x = (double)v / 65536.0;
    int places = 0;
    for (; places < Q16_DECIMALS; places++) {
        char buf[64];
        cub_xml_format_double(x, places, buf, sizeof buf);
        if ((cub_q16)floor(strtod(buf, NULL) * 65536.0 + 0.5) == v) break;
    }
    return cub_xml_set_double(el, attr, x, places);
}

static cub_err write_params(cub_xml_el *root, const cub_tag_params *p)
{
    cub_err e = set_q16(root, "threshold", p->fuzzy.threshold);
    cub_xml_el *w = cub_xml_add(root, "weights");
    if (!w) return CUB_ERR_NOMEM;
    for (int f = 0; !e && f < CUB_FUZZY_FEATURE_COUNT; f++)
        e = set_q16(w, cub_fuzzy_feature_name((cub_fuzzy_feature)f), p->fuzzy.weight[f]);
    cub_xml_el *t = cub_xml_add(root, "tagging");
    if (!t) return CUB_ERR_NOMEM;
    if (!e) e = set_q16(t, "class_share", p->class_share);
    if (!e) e = cub_xml_set_int(t, "class_clips", p->class_clips);
    if (!e) e = set_q16(t, "head_dps", p->head_dps);
    if (!e) e = cub_xml_set_int(t, "spacing_ms", p->spacing_ms);
    if (!e) e = cub_xml_set_int(t, "max_links", p->max_links);
    return e;
}

static cub_err write_clip(cub_xml_el *root, const cub_tag_clip *c)
{
    cub_xml_el *el = cub_xml_add(root, "clip");
    if (!el) return CUB_ERR_NOMEM;
    cub_err e = cub_xml_set(el, "name", c->name);
    if (!e) e = cub_xml_set_int(el, "frames", c->frame_count);
    for (int i = 0; !e && i < c->bridge_count; i++) {
        cub_xml_el *b = cub_xml_add(el, "bridge");
        char hex[16];
        snprintf(hex, sizeof hex, "0x%05x", (unsigned)c->bridges[i].crisp_class);
        e = b ? cub_xml_set_int(b, "frame", c->bridges[i].frame) : CUB_ERR_NOMEM;
        if (!e) e = cub_xml_set(b, "class", hex);
    }
    return e;
}

static cub_err write_pair(cub_xml_el *root, const cub_tags *t, int from, int to)
{
    const cub_tag_pair *pair = &t->pairs[from * t->clip_count + to];
    if (pair->link_count == 0) return CUB_OK; /* no <links>: no direct bridge */
    cub_xml_el *el = cub_xml_add(root, "links");
    if (!el) return CUB_ERR_NOMEM;
    cub_err e = cub_xml_set(el, "from", t->clips[from].name);
    if (!e) e = cub_xml_set(el, "to", t->clips[to].name);
    for (int i = 0; !e && i < pair->link_count; i++) {
        const cub_tag_link *l = &pair->links[i];
        cub_xml_el *k = cub_xml_add(el, "link");
        e = k ? cub_xml_set_int(k, "a", l->a) : CUB_ERR_NOMEM;
        if (!e) e = cub_xml_set_int(k, "b", l->b);
        if (!e) e = set_q16(k, "d", l->d);
        if (!e) e = cub_xml_set(k, "half", l->half == CUB_TAG_FRONT ? "front" : "back");
    }
    return e;
}

static cub_err build_doc(const cub_tags *t, cub_xml_doc **out)
{
    cub_xml_doc *doc = cub_xml_new("cubtags");
    cub_xml_el *root = cub_xml_root(doc);
    if (!doc || !root) {
        cub_xml_free(doc);
        return CUB_ERR_NOMEM;
    }
    cub_err e = cub_xml_set_int(root, "version", CUB_TAGS_VERSION);
    if (!e) e = cub_xml_set(root, "library", t->library);
    if (!e)
        e = cub_xml_add_comment(root, " Bridge frames and the links between them, made by "
                                      "`cubtool tag`. Schema: README.md, \"Bridge tags (XML)\". ");
    if (!e) e = write_params(root, &t->params);
    for (int c = 0; !e && c < t->clip_count; c++)
        e = write_clip(root, &t->clips[c]);
    for (int from = 0; !e && from < t->clip_count; from++)
        for (int to = 0; !e && to < t->clip_count; to++)
            e = write_pair(root, t, from, to);
    if (e) {
        cub_xml_free(doc);
        return e;
    }
    *out = doc;
    return CUB_OK;
}

cub_err cub_tags_print(const cub_tags *tags, char **out, size_t *out_len)
{
    if (!tags || !out || tags->clip_count < 0 ||
        (tags->clip_count && (!tags->clips || !tags->pairs)))
        return CUB_ERR_ARG;
    cub_xml_doc *doc = NULL;
    cub_err e = build_doc(tags, &doc);
    if (!e) e = cub_xml_print(doc, out, out_len);
    cub_xml_free(doc);
    return e;
}

cub_err cub_tags_write(const char *path, const cub_tags *tags, cub_diag *diag)
{
    if (!path || !tags || tags->clip_count < 0 ||
        (tags->clip_count && (!tags->clips || !tags->pairs)))
        return CUB_ERR_ARG;
    cub_xml_doc *doc = NULL;
    cub_err e = build_doc(tags, &doc);
    if (e)
        return cub_diag_fail(diag, e, path, 0, "cannot build the tag document: %s", cub_err_str(e));
    e = cub_xml_save(doc, path, diag);
    cub_xml_free(doc);
    return e;
}

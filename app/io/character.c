/* The character file (assets/bear/bear.xml, format in its header comment):
 * <character> holds one <skeleton> of <joint>s, one <features> naming the
 * joints the fuzzy features read, and one <body> of <part>s. Everything is
 * checked, and each problem is reported at the line it is on. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/character.h"
#include "cub/xml.h"
#include "io_internal.h"

#define CHAR_VERSION 1
/* Sizes past this are certainly a typo (a 10 m bear). */
#define CHAR_MAX_SIZE_MM 10000.0

static const char *const CHARACTER_ATTRS[] = {"name", "version", NULL};
static const char *const JOINT_ATTRS[] = {"name", "parent", "offset", "end", "optional", NULL};
static const char *const PART_ATTRS[] = {"joint",  "shape",      "centre", "radii",
                                         "radius", "end_radius", "colour", NULL};

/* <features> attributes and where each goes in cub_fuzzy_body. */
typedef struct feature_slot {
    const char *attr;
    size_t offset;
    int optional;
} feature_slot;

#define SLOT(a, member, opt)                                                                       \
    {                                                                                              \
        a, offsetof(cub_fuzzy_body, member), opt                                                   \
    }
static const feature_slot FEATURE_SLOTS[] = {
    SLOT("hip_centre", hip_centre, 0),
    SLOT("spine", spine, 1),
    SLOT("shoulder_centre", shoulder_centre, 0),
    SLOT("head", head, 0),
    SLOT("left_shoulder", shoulder[0], 0),
    SLOT("right_shoulder", shoulder[1], 0),
    SLOT("left_elbow", elbow[0], 0),
    SLOT("right_elbow", elbow[1], 0),
    SLOT("left_wrist", wrist[0], 0),
    SLOT("right_wrist", wrist[1], 0),
    SLOT("left_hip", hip[0], 0),
    SLOT("right_hip", hip[1], 0),
    SLOT("left_knee", knee[0], 0),
    SLOT("right_knee", knee[1], 0),
    SLOT("left_ankle", ankle[0], 0),
    SLOT("right_ankle", ankle[1], 0),
};
#define FEATURE_SLOT_COUNT ((int)(sizeof(FEATURE_SLOTS) / sizeof(FEATURE_SLOTS[0])))

/* What the parse keeps beside the output: where each joint was defined. */
typedef struct char_ctx {
    cub_character *out;
    cub_diag *diag;
    int joint_line[CUB_MOTION_MAX_JOINTS];
    int has_child[CUB_MOTION_MAX_JOINTS];
    cub_pose rest;
    cub_vec3 world[CUB_MOTION_MAX_JOINTS];
} char_ctx;

static cub_err check_attrs(const cub_xml_el *el, const char *const *known, cub_diag *diag)
{
    const char *bad = cub_xml_unknown_attr(el, known);
    if (bad)
        return cub_xml_fail_attr(el, bad, diag, "<%s>: unknown attribute '%s'", cub_xml_name(el),
                                 bad);
    return CUB_OK;
}

/* n numbers, each finite and within +-limit. */
static cub_err read_vec(const cub_xml_el *el, const char *attr, const char *who, int n,
                        double limit, double *v, cub_diag *diag)
{
    cub_err err = cub_xml_attr_doubles(el, attr, v, n);
    if (err == CUB_ERR_EMPTY) return cub_xml_fail(el, diag, "%s: missing %s=\"...\"", who, attr);
    if (err)
        return cub_xml_fail_attr(el, attr, diag, "%s: %s=\"%s\" is not %d number%s", who, attr,
                                 cub_xml_attr(el, attr), n, n > 1 ? "s" : "");
    for (int i = 0; i < n; i++)
        if (fabs(v[i]) > limit)
            return cub_xml_fail_attr(el, attr, diag, "%s: %s value %g is beyond +-%g mm", who, attr,
                                     v[i], limit);
    return CUB_OK;
}

static cub_err read_positive(const cub_xml_el *el, const char *attr, const char *who, int n,
                             double *v, cub_diag *diag)
{
    cub_err err = read_vec(el, attr, who, n, CHAR_MAX_SIZE_MM, v, diag);
    for (int i = 0; !err && i < n; i++)
        if (!(v[i] > 0))
            err = cub_xml_fail_attr(el, attr, diag, "%s: %s must be positive, got %g", who, attr,
                                    v[i]);
    return err;
}

/* ---- skeleton ------------------------------------------------------------ */

static cub_err joint_parent(char_ctx *c, const cub_xml_el *j, const char *name, int *parent)
{
    const cub_skeleton *skel = &c->out->skel;
    const char *p = cub_xml_attr(j, "parent");
    if (!p)
        return cub_xml_fail(j, c->diag, "joint '%s': missing parent=\"...\" (\"\" for the root)",
                            name);
    if (p[0] == '\0') {
        if (skel->joint_count > 0)
            return cub_xml_fail_attr(j, "parent", c->diag,
                                     "joint '%s' has no parent; only the first joint is the root",
                                     name);
        *parent = -1;
        return CUB_OK;
    }
    if (skel->joint_count == 0)
        return cub_xml_fail_attr(j, "parent", c->diag,
                                 "joint '%s': the first joint is the root and needs parent=\"\"",
                                 name);
    *parent = cub_motion_skeleton_find(skel, p);
    if (*parent < 0) {
        /* Say whether it comes later or is not there at all. */
        const cub_xml_el *later = cub_xml_next(j, "joint");
        while (later && strcmp(cub_xml_attr(later, "name") ? cub_xml_attr(later, "name") : "", p))
            later = cub_xml_next(later, "joint");
        if (later)
            return cub_xml_fail_attr(j, "parent", c->diag,
                                     "joint '%s': parent '%s' is not defined above it (it comes "
                                     "on line %d; parents must come first)",
                                     name, p, cub_xml_line(later));
        return cub_xml_fail_attr(j, "parent", c->diag,
                                 "joint '%s': parent '%s' is not defined above it", name, p);
    }
    if (skel->joints[*parent].is_end_site)
        return cub_xml_fail_attr(j, "parent", c->diag,
                                 "joint '%s': parent '%s' is an end site (end=\"1\") and cannot "
                                 "have children",
                                 name, p);
    return CUB_OK;
}

static cub_err read_joint(char_ctx *c, const cub_xml_el *j)
{
    cub_skeleton *skel = &c->out->skel;
    cub_err err = check_attrs(j, JOINT_ATTRS, c->diag);
    if (err) return err;
    const char *name = cub_xml_attr(j, "name");
    if (!name || !name[0]) return cub_xml_fail(j, c->diag, "joint without a name=\"...\"");
    if (strlen(name) >= CUB_MOTION_NAME_LEN)
        return cub_xml_fail_attr(j, "name", c->diag, "joint name '%.40s...' is longer than %d",
                                 name, CUB_MOTION_NAME_LEN - 1);
    int dup = cub_motion_skeleton_find(skel, name);
    if (dup >= 0)
        return cub_xml_fail_attr(j, "name", c->diag,
                                 "joint '%s' is defined twice (first on line %d)", name,
                                 c->joint_line[dup]);
    if (skel->joint_count >= CUB_MOTION_MAX_JOINTS)
        return cub_xml_fail(j, c->diag, "more than %d joints", CUB_MOTION_MAX_JOINTS);
    int parent = -1, end = 0, index = 0;
    char who[64];
    snprintf(who, sizeof(who), "joint '%s'", name);
    double off[3];
    if ((err = joint_parent(c, j, name, &parent)) ||
        (err = read_vec(j, "offset", who, 3, IO_MM_LIMIT, off, c->diag)))
        return err;
    const char *e = cub_xml_attr(j, "end");
    if (e && strcmp(e, "0") && strcmp(e, "1"))
        return cub_xml_fail_attr(j, "end", c->diag, "%s: end=\"%s\" must be \"0\" or \"1\"", who,
                                 e);
    end = e && e[0] == '1';
    const char *opt = cub_xml_attr(j, "optional");
    if (opt && strcmp(opt, "0") && strcmp(opt, "1"))
        return cub_xml_fail_attr(j, "optional", c->diag,
                                 "%s: optional=\"%s\" must be \"0\" or \"1\"", who, opt);
    cub_vec3 off_mm = {io_mm_to_q16(off[0]), io_mm_to_q16(off[1]), io_mm_to_q16(off[2])};
    if (cub_motion_skeleton_add(skel, name, parent, off_mm, &index))
        return cub_xml_fail(j, c->diag, "%s cannot be added to the skeleton", who);
    skel->joints[index].is_end_site = (uint8_t)end;
    c->out->optional[index] = (uint8_t)(opt && opt[0] == '1');
    c->joint_line[index] = cub_xml_line(j);
    if (parent >= 0) c->has_child[parent] = 1;
    return CUB_OK;
}

static cub_err read_skeleton(char_ctx *c, const cub_xml_el *s)
{
    cub_motion_skeleton_reset(&c->out->skel);
    cub_err err = check_attrs(s, (const char *const[]){NULL}, c->diag);
    for (const cub_xml_el *j = cub_xml_child(s, NULL); !err && j; j = cub_xml_next(j, NULL)) {
        if (strcmp(cub_xml_name(j), "joint"))
            return cub_xml_fail(j, c->diag, "unknown element <%s> in <skeleton> (only <joint>)",
                                cub_xml_name(j));
        err = read_joint(c, j);
    }
    if (!err && c->out->skel.joint_count == 0)
        err = cub_xml_fail(s, c->diag, "<skeleton> has no joints");
    if (!err && cub_motion_skeleton_validate(&c->out->skel))
        err = cub_xml_fail(s, c->diag, "the skeleton is not a valid tree");
    return err;
}

/* ---- features ------------------------------------------------------------ */

static cub_err read_features(char_ctx *c, const cub_xml_el *f)
{
    cub_fuzzy_body *body = &c->out->body;
    const char *known[FEATURE_SLOT_COUNT + 1];
    for (int i = 0; i < FEATURE_SLOT_COUNT; i++)
        known[i] = FEATURE_SLOTS[i].attr;
    known[FEATURE_SLOT_COUNT] = NULL;
    cub_err err = check_attrs(f, known, c->diag);
    for (int i = 0; !err && i < FEATURE_SLOT_COUNT; i++) {
        const feature_slot *s = &FEATURE_SLOTS[i];
        int16_t *slot = (int16_t *)((char *)body + s->offset);
        const char *v = cub_xml_attr(f, s->attr);
        *slot = -1;
        if (!v || !v[0]) {
            if (!s->optional)
                err = cub_xml_fail_attr(f, s->attr, c->diag, "<features>: missing %s=\"joint\"",
                                        s->attr);
            continue;
        }
        int j = cub_motion_skeleton_find(&c->out->skel, v);
        if (j < 0)
            err = cub_xml_fail_attr(f, s->attr, c->diag, "<features>: %s '%s' is not a joint",
                                    s->attr, v);
        *slot = (int16_t)j;
    }
    return err;
}

/* ---- body ---------------------------------------------------------------- */

static int hex_digit(char ch)
{
    if (ch >= '0' && ch <= '9') return ch - '0';
    if (ch >= 'a' && ch <= 'f') return ch - 'a' + 10;
    if (ch >= 'A' && ch <= 'F') return ch - 'A' + 10;
    return -1;
}

static cub_err read_colour(const cub_xml_el *p, const char *who, float rgb[3], cub_diag *diag)
{
    const char *s = cub_xml_attr(p, "colour");
    if (!s) return cub_xml_fail(p, diag, "%s: missing colour=\"#rrggbb\"", who);
    int ok = s[0] == '#' && strlen(s) == 7;
    for (int i = 0; ok && i < 3; i++) {
        int hi = hex_digit(s[1 + 2 * i]), lo = hex_digit(s[2 + 2 * i]);
        ok = hi >= 0 && lo >= 0;
        rgb[i] = (float)(hi * 16 + lo) / 255.0f;
    }
    if (!ok)
        return cub_xml_fail_attr(p, "colour", diag, "%s: bad colour '%.20s' (want #rrggbb)", who,
                                 s);
    return CUB_OK;
}

static cub_err read_ellipsoid(const cub_xml_el *p, const char *who, cub_character_part *part,
                              cub_diag *diag)
{
    double centre[3] = {0, 0, 0}, radii[3];
    if (cub_xml_has(p, "radius") || cub_xml_has(p, "end_radius"))
        return cub_xml_fail(p, diag, "%s: an ellipsoid takes centre and radii, not radius", who);
    cub_err err = CUB_OK;
    if (cub_xml_has(p, "centre"))
        err = read_vec(p, "centre", who, 3, CHAR_MAX_SIZE_MM, centre, diag);
    if (!err) err = read_positive(p, "radii", who, 3, radii, diag);
    for (int i = 0; !err && i < 3; i++) {
        part->centre_mm[i] = (float)centre[i];
        part->radii_mm[i] = (float)radii[i];
    }
    return err;
}

static cub_err read_capsule(char_ctx *c, const cub_xml_el *p, const char *who,
                            cub_character_part *part)
{
    double r, end_r;
    if (cub_xml_has(p, "centre") || cub_xml_has(p, "radii"))
        return cub_xml_fail(p, c->diag,
                            "%s: a capsule takes radius and end_radius, not "
                            "centre or radii",
                            who);
    if (!c->has_child[part->joint])
        return cub_xml_fail_attr(p, "joint", c->diag,
                                 "%s: a capsule runs to the joint's child, and this joint has none",
                                 who);
    cub_err err = read_positive(p, "radius", who, 1, &r, c->diag);
    end_r = r;
    if (!err && cub_xml_has(p, "end_radius"))
        err = read_positive(p, "end_radius", who, 1, &end_r, c->diag);
    part->radius_mm = (float)r;
    part->end_radius_mm = (float)end_r;
    return err;
}

static cub_err read_part(char_ctx *c, const cub_xml_el *p)
{
    cub_character *ch = c->out;
    cub_err err = check_attrs(p, PART_ATTRS, c->diag);
    if (err) return err;
    if (ch->part_count >= CUB_CHARACTER_MAX_PARTS)
        return cub_xml_fail(p, c->diag, "more than %d parts", CUB_CHARACTER_MAX_PARTS);
    cub_character_part *part = &ch->parts[ch->part_count];
    const char *joint = cub_xml_attr(p, "joint");
    if (!joint) return cub_xml_fail(p, c->diag, "part without a joint=\"...\"");
    part->joint = cub_motion_skeleton_find(&ch->skel, joint);
    if (part->joint < 0)
        return cub_xml_fail_attr(p, "joint", c->diag, "part on unknown joint '%.40s'", joint);
    char who[64];
    snprintf(who, sizeof(who), "part on '%s'", joint);
    const char *shape = cub_xml_attr(p, "shape");
    if (!shape) return cub_xml_fail(p, c->diag, "%s: missing shape=\"ellipsoid|capsule\"", who);
    if (!strcmp(shape, "ellipsoid")) {
        part->shape = CUB_PART_ELLIPSOID;
        err = read_ellipsoid(p, who, part, c->diag);
    } else if (!strcmp(shape, "capsule")) {
        part->shape = CUB_PART_CAPSULE;
        err = read_capsule(c, p, who, part);
    } else {
        return cub_xml_fail_attr(p, "shape", c->diag,
                                 "%s: unknown shape '%.20s' (ellipsoid or capsule)", who, shape);
    }
    if (!err) err = read_colour(p, who, part->rgb, c->diag);
    if (!err) ch->part_count++;
    return err;
}

static cub_err read_body(char_ctx *c, const cub_xml_el *b)
{
    cub_err err = check_attrs(b, (const char *const[]){NULL}, c->diag);
    for (const cub_xml_el *p = cub_xml_child(b, NULL); !err && p; p = cub_xml_next(p, NULL)) {
        if (strcmp(cub_xml_name(p), "part"))
            return cub_xml_fail(p, c->diag, "unknown element <%s> in <body> (only <part>)",
                                cub_xml_name(p));
        err = read_part(c, p);
    }
    if (!err && c->out->part_count == 0) err = cub_xml_fail(b, c->diag, "<body> has no parts");
    return err;
}

/* ---- the whole file ------------------------------------------------------ */

/* The standing height of the centre of gravity: the rest pose with the root
 * at its offset, so the feet are on the floor (y = 0). */
static void fill_stand_cog(char_ctx *c)
{
    cub_character *ch = c->out;
    cub_motion_pose_rest(&ch->skel, &c->rest);
    c->rest.root_mm = ch->skel.joints[0].offset_mm;
    cub_motion_forward(&ch->skel, &c->rest, c->world, NULL);
    ch->body.floor_y_mm = 0;
    ch->body.stand_cog_mm = cub_fuzzy_cog_height_mm(&ch->body, c->world, ch->skel.joint_count);
}

static cub_err read_character(char_ctx *c, const cub_xml_el *root)
{
    cub_character *ch = c->out;
    if (strcmp(cub_xml_name(root), "character"))
        return cub_xml_fail(root, c->diag, "expected <character>, found <%.40s>",
                            cub_xml_name(root));
    cub_err err = check_attrs(root, CHARACTER_ATTRS, c->diag);
    if (err) return err;
    const char *name = cub_xml_attr(root, "name");
    if (!name || !name[0] || strlen(name) >= sizeof(ch->name))
        return cub_xml_fail(root, c->diag, "<character> needs a name=\"...\" of 1 to %zu bytes",
                            sizeof(ch->name) - 1);
    snprintf(ch->name, sizeof(ch->name), "%s", name);
    int version = CHAR_VERSION;
    err = cub_xml_attr_int(root, "version", &version);
    if (err == CUB_ERR_FORMAT || version != CHAR_VERSION)
        return cub_xml_fail_attr(root, "version", c->diag, "unsupported version '%.20s' (want %d)",
                                 cub_xml_attr(root, "version"), CHAR_VERSION);
    static const char *const sections[] = {"skeleton", "features", "body"};
    const cub_xml_el *found[3] = {NULL, NULL, NULL};
    for (const cub_xml_el *e = cub_xml_child(root, NULL); e; e = cub_xml_next(e, NULL)) {
        int k = 0;
        while (k < 3 && strcmp(cub_xml_name(e), sections[k]))
            k++;
        if (k == 3)
            return cub_xml_fail(e, c->diag,
                                "unknown element <%.40s> in <character> (skeleton, features, body)",
                                cub_xml_name(e));
        if (found[k])
            return cub_xml_fail(e, c->diag, "a second <%s> (the first is on line %d)", sections[k],
                                cub_xml_line(found[k]));
        found[k] = e;
    }
    for (int k = 0; k < 3; k++)
        if (!found[k]) return cub_xml_fail(root, c->diag, "<character> has no <%s>", sections[k]);
    if ((err = read_skeleton(c, found[0])) || (err = read_features(c, found[1])) ||
        (err = read_body(c, found[2])))
        return err;
    fill_stand_cog(c);
    return CUB_OK;
}

static cub_err parse_text(const cub_text *t, const void *in, void *out)
{
    memset(out, 0, sizeof(cub_character));
    cub_xml_doc *doc = NULL;
    cub_err err = cub_xml_parse(t->s, t->len, t->name, &doc, t->diag);
    if (err) return err;
    char_ctx *c = calloc(1, sizeof(*c));
    if (!c) {
        cub_xml_free(doc);
        return cub_diag_fail(t->diag, CUB_ERR_NOMEM, t->name, 0, "out of memory");
    }
    c->out = out;
    c->diag = t->diag;
    err = read_character(c, cub_xml_root(doc));
    free(c);
    cub_xml_free(doc);
    return err;
}

cub_err cub_character_parse(const char *xml, size_t len, const char *name, cub_character *out,
                            cub_diag *diag)
{
    cub_text t = {xml, len, name ? name : "(memory)", diag};
    return cub_text_parse(&t, parse_text, NULL, out);
}

cub_err cub_character_load(const char *path, cub_character *out, cub_diag *diag)
{
    return cub_text_load(&(cub_text_src){path, "character file", CUB_TEXT_MAX_SMALL}, parse_text, NULL, out, diag);
}

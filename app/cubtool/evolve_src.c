/* evolve_src — see evolve_src.h. */
#include "evolve_src.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/io.h"
#include "cub/keys.h"
#include "cub/pack.h"

static int ends_with(const char *s, const char *tail)
{
    size_t n = strlen(s), t = strlen(tail);
    return n >= t && !strcmp(s + n - t, tail);
}

static int fail(const cub_diag *d)
{
    char buf[600];
    fprintf(stderr, "cubtool evolve: parent: %s\n", cub_diag_str(d, buf, sizeof(buf)));
    return 1;
}

static int resampled(const char *what, const cub_clip *clip, double fps, cub_evolve_motion *out)
{
    cub_err err = cub_evolve_from_clip(clip, fps, out);
    if (err) fprintf(stderr, "cubtool evolve: %s: cannot resample (%s)\n", what, cub_err_str(err));
    return err != CUB_OK;
}

static int from_pack(const char *pack, const char *name, double fps, cub_evolve_motion *out)
{
    static cub_library lib;
    cub_diag d = {0};
    if (cub_pack_read(pack, &lib, &d)) return fail(&d);
    int i = cub_library_find(&lib, name), rc = 1;
    if (i < 0)
        fprintf(stderr, "cubtool evolve: %s: no clip named '%s'\n", pack, name);
    else
        rc = resampled(name, &lib.clips[i].clip, fps, out);
    cub_library_free(&lib);
    return rc;
}

/* Keys authored on a character: the character's skeleton carries them. */
static int from_keys(const char *xml, const char *keys, double fps, cub_evolve_motion *out,
                     cub_character *ch)
{
    static cub_keys_clip k;
    cub_diag d = {0};
    if (cub_character_load(xml, ch, &d) || cub_keys_load(keys, &ch->skel, &k, &d)) return fail(&d);
    int rc = resampled(keys, &k.clip, fps, out);
    cub_keys_free(&k);
    return rc;
}

static int from_bvh(const char *path, double fps, cub_evolve_motion *out, double *unit_mm)
{
    static cub_io_motion io;
    cub_diag d = {0};
    if (cub_io_load_bvh(path, NULL, &io, &d)) return fail(&d);
    *unit_mm = io.unit_mm;
    int rc = resampled(path, &io.clip, fps, out);
    cub_io_motion_free(&io);
    return rc;
}

int evolve_src_load(const char *spec, double fps, cub_evolve_motion *out, double *unit_mm,
                    cub_character *ch, int *has_ch)
{
    static cub_character own;
    char head[512];
    const char *colon = strrchr(spec, ':');
    fprintf(stderr, "cubtool evolve: reading %s\n", spec);
    *unit_mm = 10;
    if (has_ch) *has_ch = 0;
    if (!colon || ends_with(spec, ".bvh") || (size_t)(colon - spec) >= sizeof head)
        return from_bvh(spec, fps, out, unit_mm);
    snprintf(head, sizeof head, "%.*s", (int)(colon - spec), spec);
    if (ends_with(head, ".cubclips")) return from_pack(head, colon + 1, fps, out);
    if (!ends_with(head, ".xml") || !ends_with(colon + 1, ".keys")) {
        fprintf(stderr, "cubtool evolve: %s: not a .bvh, LIB.cubclips:NAME or "
                        "CHARACTER.xml:KEYS.keys\n", spec);
        return 1;
    }
    if (has_ch && ch) *has_ch = 1;
    return from_keys(head, colon + 1, fps, out, ch ? ch : &own);
}

/* ---- the child as a character ---------------------------------------------- */

static double mm(int32_t q16) { return q16 / 65536.0; }

static void colour(FILE *f, const float rgb[3])
{
    fprintf(f, " colour=\"#%02x%02x%02x\"/>\n", (int)lrintf(rgb[0] * 255),
            (int)lrintf(rgb[1] * 255), (int)lrintf(rgb[2] * 255));
}

static void part(FILE *f, const char *joint, const cub_character_part *p)
{
    fprintf(f, "    <part joint=\"%s\"", joint);
    if (p->shape == CUB_PART_ELLIPSOID)
        fprintf(f, " shape=\"ellipsoid\" centre=\"%g %g %g\" radii=\"%g %g %g\"",
                p->centre_mm[0], p->centre_mm[1], p->centre_mm[2], p->radii_mm[0],
                p->radii_mm[1], p->radii_mm[2]);
    else
        fprintf(f, " shape=\"capsule\" radius=\"%g\" end_radius=\"%g\"", p->radius_mm,
                p->end_radius_mm);
    colour(f, p->rgb);
}

/* The child joint parent 2's joint k became, or -1 (removed, or paired). */
static int from_p2(const cub_evolve_meta *meta, const cub_evolve_pop *pop, int k)
{
    for (int m = 0; m < meta->skel.joint_count; m++)
        if (meta->from[m] == 2 && meta->src[m] == k) return pop->child[m];
    return -1;
}

static void joints(FILE *f, const cub_skeleton *s, const cub_evolve_meta *meta,
                   const cub_evolve_pop *pop)
{
    fprintf(f, "  <skeleton>\n");
    for (int j = 0; j < s->joint_count; j++) {
        const cub_joint *jt = &s->joints[j];
        fprintf(f, "    <joint name=\"%s\" parent=\"%s\" offset=\"%g %g %g\"%s%s/>\n", jt->name,
                jt->parent >= 0 ? s->joints[jt->parent].name : "", mm(jt->offset_mm.x),
                mm(jt->offset_mm.y), mm(jt->offset_mm.z), jt->is_end_site ? " end=\"1\"" : "",
                meta->from[pop->meta[j]] == 2 ? " optional=\"1\"" : "");
    }
    fprintf(f, "  </skeleton>\n");
}

static void features(FILE *f, const cub_character *c1)
{
    const cub_fuzzy_body *b = &c1->body;
    const cub_skeleton *s = &c1->skel;
#define N(j) s->joints[j].name
    fprintf(f,
            "  <features hip_centre=\"%s\"%s%s%s shoulder_centre=\"%s\" head=\"%s\"\n"
            "            left_shoulder=\"%s\" left_elbow=\"%s\" left_wrist=\"%s\"\n"
            "            right_shoulder=\"%s\" right_elbow=\"%s\" right_wrist=\"%s\"\n"
            "            left_hip=\"%s\" left_knee=\"%s\" left_ankle=\"%s\"\n"
            "            right_hip=\"%s\" right_knee=\"%s\" right_ankle=\"%s\"/>\n",
            N(b->hip_centre), b->spine >= 0 ? " spine=\"" : "", b->spine >= 0 ? N(b->spine) : "",
            b->spine >= 0 ? "\"" : "", N(b->shoulder_centre), N(b->head), N(b->shoulder[0]),
            N(b->elbow[0]), N(b->wrist[0]), N(b->shoulder[1]), N(b->elbow[1]), N(b->wrist[1]),
            N(b->hip[0]), N(b->knee[0]), N(b->ankle[0]), N(b->hip[1]), N(b->knee[1]),
            N(b->ankle[1]));
#undef N
}

int evolve_character_write(const char *path, const char *name, const cub_skeleton *child,
                           const cub_evolve_meta *meta, const cub_evolve_pop *pop,
                           const cub_character *c1, const cub_character *c2)
{
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "cubtool evolve: cannot write %s\n", path);
        return 1;
    }
    fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
               "<!-- Made by `cubtool evolve` (docs/evolve.md): %s crossed with %s. Do not\n"
               "     edit; optional=\"1\": a joint from %s, drawn only while a clip moves it. -->\n"
               "<character name=\"%s\" version=\"1\">\n",
            c1->name, c2->name, c2->name, name);
    joints(f, child, meta, pop);
    features(f, c1);
    fprintf(f, "  <body>\n");
    for (int i = 0; i < c1->part_count; i++) {
        const char *jn = c1->skel.joints[c1->parts[i].joint].name;
        int j = cub_motion_skeleton_find(child, jn);
        if (j >= 0 && meta->from[pop->meta[j]] == 1) part(f, jn, &c1->parts[i]);
    }
    for (int i = 0; i < c2->part_count; i++) {
        int j = from_p2(meta, pop, c2->parts[i].joint);
        if (j >= 0) part(f, child->joints[j].name, &c2->parts[i]);
    }
    fprintf(f, "  </body>\n</character>\n");
    int bad = ferror(f) | (fclose(f) != 0);
    if (bad) fprintf(stderr, "cubtool evolve: cannot write %s\n", path);
    return bad;
}

/* render_bear — the character: its parts (cub_character_part) become lit
 * meshes in bind pose once, when a character is first shown, and follow
 * the pose through the bone slots every frame.
 *
 * Skinning: ellipsoids are rigid on their joint; a capsule's vertices blend
 * toward the parent joint near its start and toward the child near its end,
 * half and half at the joint, so an elbow or a knee bends as one surface
 * instead of two tubes crossing.
 *
 * The face: the dark ellipsoids on the head joint off the middle line are
 * the eyes. They stay out of the body range and come back in the happy and
 * worried faces (with a sparkle); the sleepy face has closed lids instead.
 * Mouths and brows are tubes laid on the muzzle's and the head's surface. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "render_internal.h"

#define BEAR_VERTS 30000
#define BEAR_INDICES 160000
#define DARK_MAX 0.25f /* a part darker than this in every channel is a feature */
#define MAX_EYES 2
#define CURVE_POINTS 9

static const float SPARKLE_RGB[3] = {1.0f, 1.0f, 1.0f};
static const float BLUSH_RGB[3] = {0.96f, 0.58f, 0.58f};

/* The head's parts the face is laid on. */
typedef struct face_parts {
    const cub_character_part *eye[MAX_EYES];
    int eyes;
    const cub_character_part *skull, *muzzle, *nose;
    float mouth_y;
    float line_rgb[3];
} face_parts;

static int is_dark(const cub_character_part *p)
{
    return p->rgb[0] < DARK_MAX && p->rgb[1] < DARK_MAX && p->rgb[2] < DARK_MAX;
}

static int is_eye(const cub_character *ch, const cub_character_part *p)
{
    return p->joint == ch->body.head && p->shape == CUB_PART_ELLIPSOID && is_dark(p) &&
           fabsf(p->centre_mm[0]) > 1.0f;
}

static float volume(const cub_character_part *p)
{
    return p->radii_mm[0] * p->radii_mm[1] * p->radii_mm[2];
}

static void find_face(const cub_character *ch, face_parts *f)
{
    memset(f, 0, sizeof *f);
    for (int i = 0; i < ch->part_count; i++) {
        const cub_character_part *p = &ch->parts[i];
        if (p->joint != ch->body.head || p->shape != CUB_PART_ELLIPSOID)
            continue;
        if (is_eye(ch, p) && f->eyes < MAX_EYES)
            f->eye[f->eyes++] = p;
        else if (is_dark(p) && fabsf(p->centre_mm[0]) <= 1.0f)
            f->nose = p;
        else if (!is_dark(p) && (!f->skull || volume(p) > volume(f->skull)))
            f->skull = p;
    }
    /* The muzzle: the foremost light part on the middle line, not the skull. */
    for (int i = 0; i < ch->part_count; i++) {
        const cub_character_part *p = &ch->parts[i];
        if (p->joint == ch->body.head && p->shape == CUB_PART_ELLIPSOID && p != f->skull &&
            !is_dark(p) && fabsf(p->centre_mm[0]) <= 1.0f &&
            (!f->muzzle || p->centre_mm[2] > f->muzzle->centre_mm[2]))
            f->muzzle = p;
    }
    const cub_character_part *m = f->muzzle ? f->muzzle : f->skull;
    f->mouth_y = m ? m->centre_mm[1] - 0.35f * m->radii_mm[1] : 0.0f;
    if (f->nose && f->nose->centre_mm[1] - f->nose->radii_mm[1] - 12.0f < f->mouth_y)
        f->mouth_y = f->nose->centre_mm[1] - f->nose->radii_mm[1] - 12.0f;
    const float *line = f->eyes ? f->eye[0]->rgb : f->nose ? f->nose->rgb : NULL;
    for (int k = 0; k < 3; k++)
        f->line_rgb[k] = line ? line[k] : 0.15f;
}

/* z of the front of ellipsoid e at (x, y), in the joint's frame. */
static float front_z(const cub_character_part *e, float x, float y)
{
    float u = (x - e->centre_mm[0]) / e->radii_mm[0], v = (y - e->centre_mm[1]) / e->radii_mm[1];
    float t = 1.0f - u * u - v * v;
    return e->centre_mm[2] + e->radii_mm[2] * sqrtf(t > 0.0f ? t : 0.0f);
}

/* A curve on surface e: x from x0 to x1, y = y(x) given by the shape
 * function, laid a little proud of the surface (lift mm). */
typedef float (*curve_y)(float u, float arg); /* u in -1..1 */

static void surface_curve(cub_render_mesh *m, const cub_character_part *e, float x0, float x1,
                          float y0, curve_y fy, float arg, float r, const float rgb[3])
{
    float pts[CURVE_POINTS][3];
    for (int k = 0; k < CURVE_POINTS; k++) {
        float u = -1.0f + 2.0f * (float)k / (CURVE_POINTS - 1);
        pts[k][0] = x0 + 0.5f * (u + 1.0f) * (x1 - x0);
        pts[k][1] = y0 + fy(u, arg);
        pts[k][2] = front_z(e, pts[k][0], pts[k][1]) + 0.3f * r;
    }
    cub_render_mesh_tube(m, (const float(*)[3])pts, CURVE_POINTS, r, rgb);
}

static float smile(float u, float depth) { return depth * (u * u - 1.0f); }
static float frown(float u, float h) { return -h * u * u + 0.25f * h * sinf(3.0f * 3.14159265f * u); }
static float lid(float u, float depth) { return -depth * (1.0f - u * u); }
static float slope(float u, float rise) { return rise * u; }

static void eyes_open(cub_render_mesh *m, const face_parts *f)
{
    for (int i = 0; i < f->eyes; i++) {
        const cub_character_part *e = f->eye[i];
        cub_render_mesh_ellipsoid(m, e->centre_mm, e->radii_mm, e->rgb);
        /* The sparkle sits toward the key light (upper left). */
        float c[3] = {e->centre_mm[0] - 0.3f * e->radii_mm[0],
                      e->centre_mm[1] + 0.35f * e->radii_mm[1],
                      e->centre_mm[2] + 0.8f * e->radii_mm[2]};
        float r[3] = {0.32f * e->radii_mm[0], 0.3f * e->radii_mm[1], 0.3f * e->radii_mm[2]};
        cub_render_mesh_ellipsoid(m, c, r, SPARKLE_RGB);
    }
}

static void cheeks(cub_render_mesh *m, const face_parts *f)
{
    if (!f->skull)
        return;
    for (int i = 0; i < f->eyes; i++) {
        const cub_character_part *e = f->eye[i];
        float x = e->centre_mm[0] * 1.35f, y = e->centre_mm[1] - 2.6f * e->radii_mm[1];
        float c[3] = {x, y, front_z(f->skull, x, y) - 4.0f}, r[3] = {22.0f, 13.0f, 10.0f};
        cub_render_mesh_ellipsoid(m, c, r, BLUSH_RGB);
    }
}

static void face(cub_render_mesh *m, const face_parts *f, cub_render_face which)
{
    const cub_character_part *mouth_on = f->muzzle ? f->muzzle : f->skull;
    float mw = mouth_on ? 0.38f * mouth_on->radii_mm[0] : 0.0f;
    if (which == CUB_RENDER_FACE_SLEEPY) {
        for (int i = 0; f->skull && i < f->eyes; i++) {
            const cub_character_part *e = f->eye[i];
            float w = 1.3f * e->radii_mm[0];
            surface_curve(m, f->skull, e->centre_mm[0] - w, e->centre_mm[0] + w,
                          e->centre_mm[1] - 0.1f * e->radii_mm[1], lid, 0.45f * e->radii_mm[1],
                          4.5f, f->line_rgb);
        }
        if (mouth_on) {
            float y = f->mouth_y + 4.0f;
            float c[3] = {0.0f, y, front_z(mouth_on, 0.0f, y) - 1.0f}, r[3] = {9.0f, 8.0f, 4.0f};
            cub_render_mesh_ellipsoid(m, c, r, f->line_rgb);
        }
        return;
    }
    eyes_open(m, f);
    if (which == CUB_RENDER_FACE_HAPPY) {
        cheeks(m, f);
        if (mouth_on)
            surface_curve(m, mouth_on, -mw, mw, f->mouth_y, smile, 10.0f, 5.0f, f->line_rgb);
        return;
    }
    /* Worried: brows lifted at the inner ends, a small wavering mouth. */
    for (int i = 0; f->skull && i < f->eyes; i++) {
        const cub_character_part *e = f->eye[i];
        float side = e->centre_mm[0] > 0.0f ? 1.0f : -1.0f;
        float inner = e->centre_mm[0] - side * 1.1f * e->radii_mm[0];
        float outer = e->centre_mm[0] + side * 1.2f * e->radii_mm[0];
        surface_curve(m, f->skull, inner, outer, e->centre_mm[1] + 1.9f * e->radii_mm[1], slope,
                      -0.45f * e->radii_mm[1], 4.5f, f->line_rgb);
    }
    if (mouth_on)
        surface_curve(m, mouth_on, -0.6f * mw, 0.6f * mw, f->mouth_y + 2.0f, frown, 6.0f, 4.5f,
                      f->line_rgb);
}

static int first_child(const cub_skeleton *s, int j)
{
    for (int c = j + 1; c < s->joint_count; c++)
        if (s->joints[c].parent == j)
            return c;
    return -1;
}

/* The parts on optional joints (optional 1) or the others (0), eyes aside. */
static void body(cub_render_mesh *m, const cub_character *ch, const cub_render_bear *b,
                 int optional)
{
    const cub_skeleton *s = &ch->skel;
    for (int i = 0; i < ch->part_count; i++) {
        const cub_character_part *p = &ch->parts[i];
        if (is_eye(ch, p) || ch->optional[p->joint] != optional)
            continue;
        m->slot = p->joint + 1;
        memcpy(m->origin, b->rest_mm[p->joint], sizeof m->origin);
        if (p->shape == CUB_PART_ELLIPSOID) {
            cub_render_mesh_ellipsoid(m, p->centre_mm, p->radii_mm, p->rgb);
            continue;
        }
        int child = first_child(s, p->joint), parent = s->joints[p->joint].parent;
        if (child < 0)
            continue; /* the loader refuses this; nothing to hang it on */
        float axis[3] = {s->joints[child].offset_mm.x / 65536.0f,
                         s->joints[child].offset_mm.y / 65536.0f,
                         s->joints[child].offset_mm.z / 65536.0f};
        cub_render_mesh_capsule(m, axis, p->radius_mm, p->end_radius_mm, p->rgb,
                                parent >= 0 ? parent + 1 : -1, child + 1);
    }
}

static void rest_positions(const cub_skeleton *s, float (*rest)[3])
{
    for (int j = 0; j < s->joint_count; j++) {
        int p = s->joints[j].parent;
        const cub_vec3 *o = &s->joints[j].offset_mm;
        float off[3] = {o->x / 65536.0f, o->y / 65536.0f, o->z / 65536.0f};
        for (int k = 0; k < 3; k++)
            rest[j][k] = (p >= 0 ? rest[p][k] : 0.0f) + off[k];
    }
}

static cub_err build(cub_render *r, const cub_character *ch)
{
    cub_render_bear *b = &r->bear;
    rest_positions(&ch->skel, b->rest_mm);
    cub_render_mesh m;
    if (!cub_render_mesh_init(&m, BEAR_VERTS, BEAR_INDICES)) {
        cub_render_mesh_free(&m);
        return CUB_ERR_NOMEM;
    }
    body(&m, ch, b, 0);
    b->body = (cub_render_range){0, m.ni};
    body(&m, ch, b, 1);
    b->optional = (cub_render_range){b->body.count, m.ni - b->body.count};
    face_parts f;
    find_face(ch, &f);
    int head = ch->body.head;
    m.slot = head + 1;
    memcpy(m.origin, b->rest_mm[head], sizeof m.origin);
    for (int e = 0; e < CUB_RENDER_FACE_COUNT; e++) {
        int first = m.ni;
        face(&m, &f, (cub_render_face)e);
        b->face[e] = (cub_render_range){first, m.ni - first};
    }
    if (m.full) {
        fprintf(stderr, "render: character '%s' has more parts than the renderer holds "
                        "(%d vertices)\n", ch->name, BEAR_VERTS);
        cub_render_mesh_free(&m);
        return CUB_ERR_ARG;
    }
    int bad = cub_render_lit_upload(&m, &b->vbo, &b->ibo);
    cub_render_mesh_free(&m);
    if (bad)
        return CUB_ERR_DEVICE;
    b->shown = ch;
    b->mapped_skel = NULL;
    return CUB_OK;
}

void cub_render_bear_free(cub_render_bear *b)
{
    glDeleteBuffers(1, &b->vbo);
    glDeleteBuffers(1, &b->ibo);
    b->vbo = b->ibo = 0;
    b->shown = NULL;
}

static cub_err check_character(const cub_character *ch)
{
    int n = ch->skel.joint_count;
    if (n <= 0 || n + 1 > CUB_RENDER_MAX_SLOTS) {
        fprintf(stderr, "render: character '%s' has %d joints; the renderer skins 1 to %d\n",
                ch->name, n, CUB_RENDER_MAX_SLOTS - 1);
        return CUB_ERR_ARG;
    }
    if (ch->body.head < 0 || ch->body.head >= n || ch->part_count < 0 ||
        ch->part_count > CUB_CHARACTER_MAX_PARTS)
        return CUB_ERR_ARG;
    for (int j = 0; j < n; j++)
        if (ch->skel.joints[j].parent >= j || ch->skel.joints[j].parent < -1)
            return CUB_ERR_ARG;
    for (int i = 0; i < ch->part_count; i++)
        if (ch->parts[i].joint < 0 || ch->parts[i].joint >= n)
            return CUB_ERR_ARG;
    return CUB_OK;
}

/* Character joint -> scene joint by name; redone only when the scene's
 * skeleton changes. */
static void map_joints(cub_render_bear *b, const cub_character *ch, const cub_skeleton *skel)
{
    if (b->mapped_skel == skel && b->mapped_count == skel->joint_count)
        return;
    b->mapped_any = 0;
    b->mapped_optional = 1;
    for (int j = 0; j < ch->skel.joint_count; j++) {
        b->map[j] = cub_motion_skeleton_find(skel, ch->skel.joints[j].name);
        b->mapped_any |= b->map[j] >= 0;
    }
    for (int i = 0; i < ch->part_count; i++)
        if (ch->optional[ch->parts[i].joint] && b->map[ch->parts[i].joint] < 0)
            b->mapped_optional = 0;
    b->mapped_skel = skel;
    b->mapped_count = skel->joint_count;
}

cub_err cub_render_bear_prepare(cub_render *r, const cub_render_scene *scene, int *drawn)
{
    *drawn = 0;
    const cub_character *ch = scene->character;
    if (!ch || !scene->skel || !scene->world_rot_xyzw)
        return CUB_OK;
    if ((unsigned)scene->face >= CUB_RENDER_FACE_COUNT)
        return CUB_ERR_ARG;
    if (r->bear.shown != ch) {
        cub_err e = check_character(ch);
        if (e)
            return e;
        cub_render_bear_free(&r->bear);
        e = build(r, ch);
        if (e)
            return e;
    }
    map_joints(&r->bear, ch, scene->skel);
    *drawn = r->bear.mapped_any;
    return CUB_OK;
}

static int finite_n(const float *v, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return 0;
    return 1;
}

static void qrot(const float q[4], const float v[3], float out[3])
{
    /* v + 2 q.xyz x (q.xyz x v + w v) */
    float t[3] = {q[1] * v[2] - q[2] * v[1] + q[3] * v[0], q[2] * v[0] - q[0] * v[2] + q[3] * v[1],
                  q[0] * v[1] - q[1] * v[0] + q[3] * v[2]};
    out[0] = v[0] + 2.0f * (q[1] * t[2] - q[2] * t[1]);
    out[1] = v[1] + 2.0f * (q[2] * t[0] - q[0] * t[2]);
    out[2] = v[2] + 2.0f * (q[0] * t[1] - q[1] * t[0]);
}

/* Each joint's slot: the rotation of its scene joint, and the translation
 * that takes its rest position to the scene position. A joint the scene
 * lacks (or has no finite value for) moves with its parent. */
static void fill_slots(cub_render *r, const cub_render_scene *scene)
{
    const cub_render_bear *b = &r->bear;
    const cub_skeleton *s = &b->shown->skel;
    for (int j = 0; j < s->joint_count; j++) {
        float *q = r->lit.rot + 4 * (j + 1), *t = r->lit.pos + 4 * (j + 1);
        int sj = b->map[j], p = s->joints[j].parent;
        const float *sq = sj >= 0 ? scene->world_rot_xyzw + 4 * sj : NULL;
        const float *sp = sj >= 0 ? scene->world_xyz_mm + 3 * sj : NULL;
        if (!sq || !finite_n(sq, 4) || !finite_n(sp, 3)) {
            const float *pq = p >= 0 ? q - 4 * (j - p) : NULL, *pt = p >= 0 ? t - 4 * (j - p) : NULL;
            for (int k = 0; k < 4; k++) {
                q[k] = pq ? pq[k] : k == 3 ? 1.0f : 0.0f;
                t[k] = pt ? pt[k] : 0.0f;
            }
            continue;
        }
        float moved[3];
        memcpy(q, sq, 4 * sizeof *q);
        qrot(q, b->rest_mm[j], moved);
        for (int k = 0; k < 3; k++)
            t[k] = sp[k] - moved[k];
    }
}

void cub_render_bear_draw(cub_render *r, const cub_render_scene *scene)
{
    fill_slots(r, scene);
    cub_render_lit_begin(r);
    cub_render_lit_draw(r, r->bear.vbo, r->bear.ibo, r->bear.body);
    /* Optional joints (the winged bear's wings) show only while the scene
     * moves them: a clip that lacks them would carry them stiffly. */
    if (r->bear.mapped_optional && r->bear.optional.count)
        cub_render_lit_draw(r, r->bear.vbo, r->bear.ibo, r->bear.optional);
    cub_render_lit_draw(r, r->bear.vbo, r->bear.ibo, r->bear.face[scene->face]);
}

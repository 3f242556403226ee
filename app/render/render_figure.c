/* render_figure — the coach as a stick figure: a thick quad per bone (from
 * each joint to its parent; GL_LINES widths above 1 are not portable), a
 * disc per joint and a bigger disc for the head.
 *
 * Camera: orthographic, looking from the front (+z toward the viewer, y up,
 * +x to the right). The view is figure_height_mm / 0.8 tall, so the figure
 * fills 80% of the height; the floor (y = 0) sits 7% above the bottom edge;
 * horizontally the view follows the root joint. Depth comes from z, so
 * nearer limbs cover farther ones. */
#include <ctype.h>
#include <math.h>
#include <stddef.h>

#include "render_internal.h"

#define DISC_SEGMENTS 16
#define FILL_SHARE 0.80f  /* share of the view height the figure fills */
#define FLOOR_SHARE 0.07f /* floor height above the bottom edge, share of the view */
#define DEPTH_RANGE_MM 3000.0f

static const float BONE_RGB[3] = {0.50f, 0.31f, 0.16f};
static const float JOINT_RGB[3] = {0.30f, 0.18f, 0.09f};
static const float HEAD_RGB[3] = {0.62f, 0.41f, 0.22f};

typedef struct camera {
    float cx_mm, cz_mm;    /* the point at the centre column, depth zero */
    float view_h_mm, view_w_mm;
    float bottom_mm;       /* world y at the bottom edge */
} camera;

static void to_ndc(const camera *c, float x, float y, float z, float out[3])
{
    out[0] = 2.0f * (x - c->cx_mm) / c->view_w_mm;
    out[1] = 2.0f * (y - c->bottom_mm) / c->view_h_mm - 1.0f;
    float d = -(z - c->cz_mm) / DEPTH_RANGE_MM; /* nearer = smaller depth */
    out[2] = d < -0.95f ? -0.95f : d > 0.95f ? 0.95f : d;
}

static cub_render_vtx vtx(const float p[3], const float rgb[3])
{
    return (cub_render_vtx){p[0], p[1], p[2], rgb[0], rgb[1], rgb[2], 1.0f};
}

/* A quad of half-width hw_mm from a to b, in the screen plane. */
static void bone(cub_render *r, const camera *c, const float *a, const float *b, float hw_mm)
{
    float dx = b[0] - a[0], dy = b[1] - a[1];
    float len = sqrtf(dx * dx + dy * dy);
    if (len < 1e-3f) /* pointing at the viewer: the joint discs cover it */
        return;
    float nx = -dy / len * hw_mm, ny = dx / len * hw_mm;
    float p[4][3];
    to_ndc(c, a[0] + nx, a[1] + ny, a[2], p[0]);
    to_ndc(c, a[0] - nx, a[1] - ny, a[2], p[1]);
    to_ndc(c, b[0] - nx, b[1] - ny, b[2], p[2]);
    to_ndc(c, b[0] + nx, b[1] + ny, b[2], p[3]);
    cub_render_batch_tri(&r->batch,
                         (cub_render_vtx[3]){vtx(p[0], BONE_RGB), vtx(p[1], BONE_RGB),
                                             vtx(p[2], BONE_RGB)});
    cub_render_batch_tri(&r->batch,
                         (cub_render_vtx[3]){vtx(p[0], BONE_RGB), vtx(p[2], BONE_RGB),
                                             vtx(p[3], BONE_RGB)});
}

/* A disc facing the viewer, pulled slightly nearer than the bones it caps. */
static void disc(cub_render *r, const camera *c, const float *m, float radius_mm,
                 const float rgb[3])
{
    float centre[3];
    to_ndc(c, m[0], m[1], m[2] + 20.0f, centre);
    for (int i = 0; i < DISC_SEGMENTS; i++) {
        float a0 = 6.2831853f * (float)i / DISC_SEGMENTS;
        float a1 = 6.2831853f * (float)(i + 1) / DISC_SEGMENTS;
        float p0[3], p1[3];
        to_ndc(c, m[0] + radius_mm * cosf(a0), m[1] + radius_mm * sinf(a0), m[2] + 20.0f, p0);
        to_ndc(c, m[0] + radius_mm * cosf(a1), m[1] + radius_mm * sinf(a1), m[2] + 20.0f, p1);
        cub_render_batch_tri(&r->batch, (cub_render_vtx[3]){vtx(centre, rgb), vtx(p0, rgb),
                                                            vtx(p1, rgb)});
    }
}

/* The joint named like "head" in any case ("Head", "head", "HEAD"), or -1.
 * An exact name wins over one that merely contains it ("HeadEnd"). */
static int find_head(const cub_skeleton *skel)
{
    int best = -1;
    for (int j = 0; j < skel->joint_count; j++) {
        const char *n = skel->joints[j].name;
        for (const char *p = n; *p; p++) {
            if (tolower((unsigned char)p[0]) == 'h' && tolower((unsigned char)p[1]) == 'e' &&
                tolower((unsigned char)p[2]) == 'a' && tolower((unsigned char)p[3]) == 'd') {
                if (p == n && n[4] == '\0')
                    return j;
                if (best < 0)
                    best = j;
                break;
            }
        }
    }
    return best;
}

static int finite3(const float *p)
{
    return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

static void draw_head(cub_render *r, const camera *c, const cub_skeleton *skel, int head,
                      const float *xyz, float radius_mm)
{
    if (head < 0 || !finite3(xyz + 3 * head))
        return;
    /* A BVH head joint sits at the base of the skull; with a child (its end
     * site) centre the disc between the two. */
    float centre[3] = {xyz[3 * head], xyz[3 * head + 1], xyz[3 * head + 2]};
    for (int j = head + 1; j < skel->joint_count; j++) {
        if (skel->joints[j].parent == head && finite3(xyz + 3 * j)) {
            for (int k = 0; k < 3; k++)
                centre[k] = 0.5f * (centre[k] + xyz[3 * j + k]);
            break;
        }
    }
    disc(r, c, centre, radius_mm, HEAD_RGB);
}

cub_err cub_render_figure_check(const cub_render_scene *scene)
{
    const cub_skeleton *skel = scene->skel;
    if (!skel)
        return CUB_OK;
    if (!scene->world_xyz_mm || skel->joint_count < 0 ||
        skel->joint_count > CUB_MOTION_MAX_JOINTS)
        return CUB_ERR_ARG;
    for (int j = 0; j < skel->joint_count; j++)
        if (skel->joints[j].parent >= j || skel->joints[j].parent < -1)
            return CUB_ERR_ARG; /* parents come before children */
    return CUB_OK;
}

void cub_render_figure(cub_render *r, const cub_render_scene *scene)
{
    const cub_skeleton *skel = scene->skel;
    const float *xyz = scene->world_xyz_mm;
    if (!skel || skel->joint_count == 0)
        return;

    float fh = r->figure_height_mm;
    camera c = {.view_h_mm = fh / FILL_SHARE};
    c.view_w_mm = c.view_h_mm * (float)r->w / (float)r->h;
    c.bottom_mm = -FLOOR_SHARE * c.view_h_mm;
    if (finite3(xyz)) {
        c.cx_mm = xyz[0];
        c.cz_mm = xyz[2];
    }
    /* The head disc stands for the head's children (its end site): their
     * bones and joint discs would only poke out of it. */
    int head = find_head(skel);
    for (int j = 0; j < skel->joint_count; j++) {
        int p = skel->joints[j].parent;
        if (p >= 0 && p != head && finite3(xyz + 3 * j) && finite3(xyz + 3 * p))
            bone(r, &c, xyz + 3 * p, xyz + 3 * j, 0.012f * fh);
    }
    for (int j = 0; j < skel->joint_count; j++)
        if ((head < 0 || skel->joints[j].parent != head) && finite3(xyz + 3 * j))
            disc(r, &c, xyz + 3 * j, 0.018f * fh, JOINT_RGB);
    draw_head(r, &c, skel, head, xyz, 0.062f * fh);
}

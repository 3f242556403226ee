/* BVH export: the hierarchy and every frame in the channel layout the
 * motion was read with (m->channels), lengths back in the source unit.
 * Positions come first in each CHANNELS list, then rotations in their
 * listed order; six decimals keep a round trip far below 0.1 mm. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "io_internal.h"

static void indent(FILE *f, int depth)
{
    for (int i = 0; i < depth; i++)
        fputc('\t', f);
}

static int axis_of(char c)
{
    return c == 'X' ? 0 : c == 'Y' ? 1 : c == 'Z' ? 2 : -1;
}

static void write_channels(FILE *f, const cub_io_channels *ch, int depth)
{
    indent(f, depth);
    fprintf(f, "CHANNELS %d", ch->count);
    for (const char *p = ch->pos_order; *p; p++)
        fprintf(f, " %cposition", *p);
    for (const char *r = ch->rot_order; *r; r++)
        fprintf(f, " %crotation", *r);
    fputc('\n', f);
}

static void write_joint(FILE *f, const cub_io_motion *m, int j, int depth)
{
    const cub_joint *jt = &m->skel.joints[j];
    indent(f, depth);
    if (j == 0)
        fprintf(f, "ROOT %s\n", jt->name);
    else if (jt->is_end_site)
        fprintf(f, "End Site\n");
    else
        fprintf(f, "JOINT %s\n", jt->name);
    indent(f, depth);
    fprintf(f, "{\n");
    indent(f, depth + 1);
    fprintf(f, "OFFSET %.6f %.6f %.6f\n", io_q16_to_mm(jt->offset_mm.x) / m->unit_mm,
            io_q16_to_mm(jt->offset_mm.y) / m->unit_mm, io_q16_to_mm(jt->offset_mm.z) / m->unit_mm);
    if (!jt->is_end_site)
        write_channels(f, &m->channels[j], depth + 1);
    for (int c = j + 1; c < m->skel.joint_count; c++)
        if (m->skel.joints[c].parent == j)
            write_joint(f, m, c, depth + 1);
    indent(f, depth);
    fprintf(f, "}\n");
}

/* The joints in the order write_joint visits them (depth first, children
 * in index order): a frame's channels must follow the hierarchy as written,
 * which is not the index order when a joint was added under an earlier one
 * (an evolved child's appended wings). Returns n + the joints written. */
static int hierarchy_order(const cub_skeleton *s, int j, int *order, int n)
{
    order[n++] = j;
    for (int c = j + 1; c < s->joint_count; c++)
        if (s->joints[c].parent == j)
            n = hierarchy_order(s, c, order, n);
    return n;
}

static void write_frame(FILE *f, const cub_io_motion *m, const int *order, int frame)
{
    const cub_clip *clip = &m->clip;
    int jn = m->skel.joint_count;
    const char *sep = "";
    for (int i = 0; i < jn; i++) {
        int j = order[i];
        const cub_io_channels *ch = &m->channels[j];
        if (m->skel.joints[j].is_end_site)
            continue;
        cub_vec3 p = m->skel.joints[j].offset_mm;
        if (j == 0)
            p = clip->root_mm[frame];
        else if (clip->trans_mm)
            p = clip->trans_mm[(size_t)frame * jn + j];
        for (const char *a = ch->pos_order; *a; a++) {
            int32_t v = *a == 'X' ? p.x : *a == 'Y' ? p.y : p.z;
            fprintf(f, "%s%.6f", sep, io_q16_to_mm(v) / m->unit_mm);
            sep = " ";
        }
        int axes[3], n = 0;
        double ang[3];
        for (const char *r = ch->rot_order; *r && n < 3; r++)
            axes[n++] = axis_of(*r);
        if (n == 0)
            continue;
        cub_dq q = cub_dq_from_fx(clip->rot[(size_t)frame * jn + j]);
        cub_dq_to_euler(q, axes, n, ang);
        for (int k = 0; k < n; k++) {
            fprintf(f, "%s%.6f", sep, ang[k] * (180.0 / CUB_VEC_PI));
            sep = " ";
        }
    }
    fputc('\n', f);
}

/* The layout must be one the writer can express and the reader re-read. */
static cub_err check_motion(const cub_io_motion *m, const char *path, cub_diag *diag)
{
    if (!m || !(m->unit_mm > 0) || !isfinite(m->unit_mm) || m->skel.joint_count < 1 ||
        m->skel.joint_count > CUB_MOTION_MAX_JOINTS || m->clip.frame_count < 1 ||
        !m->clip.rot || !m->clip.root_mm || m->clip.frame_ns == 0)
        return cub_diag_fail(diag, CUB_ERR_ARG, path, 0, "nothing to save (empty motion or unit)");
    if (cub_motion_skeleton_validate(&m->skel) != CUB_OK)
        return cub_diag_fail(diag, CUB_ERR_ARG, path, 0, "the skeleton is not a valid tree");
    for (int j = 0; j < m->skel.joint_count; j++) {
        const cub_io_channels *ch = &m->channels[j];
        const char *re = memchr(ch->rot_order, 0, sizeof(ch->rot_order));
        const char *pe = memchr(ch->pos_order, 0, sizeof(ch->pos_order));
        size_t nr = re ? (size_t)(re - ch->rot_order) : 0;
        size_t np = pe ? (size_t)(pe - ch->pos_order) : 0;
        int ok = re && pe && nr + np == ch->count;
        for (size_t k = 0; ok && k < nr; k++)
            ok = axis_of(ch->rot_order[k]) >= 0 && !memchr(ch->rot_order, ch->rot_order[k], k);
        for (size_t k = 0; ok && k < np; k++)
            ok = axis_of(ch->pos_order[k]) >= 0 && !memchr(ch->pos_order, ch->pos_order[k], k);
        if (!ok)
            return cub_diag_fail(diag, CUB_ERR_ARG, path, 0, "joint %d has a bad channel layout", j);
    }
    return CUB_OK;
}

cub_err cub_io_save_bvh(const char *path, const cub_io_motion *m, cub_diag *diag)
{
    cub_diag scratch;
    if (!diag)
        diag = &scratch;
    memset(diag, 0, sizeof(*diag));
    if (!path)
        return cub_diag_fail(diag, CUB_ERR_ARG, "(null)", 0, "no path");
    cub_err err = check_motion(m, path, diag);
    if (err)
        return err;
    FILE *f = fopen(path, "w");
    if (!f)
        return cub_diag_fail(diag, CUB_ERR_IO, path, 0, "cannot create: %s", strerror(errno));
    fprintf(f, "HIERARCHY\n");
    write_joint(f, m, 0, 0);
    fprintf(f, "MOTION\nFrames: %d\nFrame Time: %.9f\n", m->clip.frame_count,
            m->clip.frame_ns / 1e9);
    int order[CUB_MOTION_MAX_JOINTS];
    hierarchy_order(&m->skel, 0, order, 0);
    for (int fr = 0; fr < m->clip.frame_count; fr++)
        write_frame(f, m, order, fr);
    int bad = ferror(f);
    if (fclose(f) != 0 || bad)
        return cub_diag_fail(diag, CUB_ERR_IO, path, 0, "write failed");
    return CUB_OK;
}

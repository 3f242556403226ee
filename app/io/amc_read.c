/* AMC motion on an ASF skeleton, to a cub_skeleton + cub_clip.
 *
 * Skeleton: one joint per bone, placed at the bone's start (its parent's
 * end), so its rotation turns the bone; a leaf bone gets an End Site at its
 * end. Offsets are direction * length * unit_mm, with unit_mm = 25.4 /
 * (":units length") unless desc.unit_mm says otherwise (CMU: 0.45, so
 * mm = length / 0.45 * 25.4).
 * Rotations (the ASF spec): a bone's motion M is given in its own frame,
 * whose orientation C is its "axis"; in the rest (global) frame the local
 * rotation is C * M * C^-1. Euler orders such as "XYZ" or "rx ry rz" apply
 * the first listed axis first: M = Rz * Ry * Rx.
 * Frames: AMC stores no rate; CMU captured at 120 fps. */
#include <math.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "asf_internal.h"

#define AMC_FRAME_NS 8333333u /* 120 fps */

typedef struct amc_state {
    asf_skel asf;
    io_lex lx;
    cub_io_motion *m;
    int joint_of[ASF_MAX_BONES];
    cub_dq c[ASF_MAX_BONES], c_inv[ASF_MAX_BONES];
    double val[ASF_MAX_BONES][6];
    unsigned char seen[ASF_MAX_BONES];
    double rad_per_unit;
} amc_state;

/* Euler angles applied in the listed order: R = R[n-1] * ... * R[0]. */
static cub_dq asf_euler(const int *axes, const double *ang_rad, int n)
{
    cub_dq q = {1, 0, 0, 0};
    for (int i = 0; i < n; i++)
        q = cub_dq_mul(cub_dq_about(axes[i], ang_rad[i]), q);
    return q;
}

static cub_err add_joint(amc_state *a, const char *name, int parent, const double off[3],
                         int line, int *idx, cub_diag *diag)
{
    cub_vec3 v;
    int32_t *k[3] = {&v.x, &v.y, &v.z};
    for (int i = 0; i < 3; i++) {
        double mm = off[i] * a->m->unit_mm;
        if (!(fabs(mm) <= IO_MM_LIMIT))
            return cub_diag_fail(diag, CUB_ERR_FORMAT, a->lx.name, line,
                              "bone '%s' offset %.0f mm is beyond +-32 m", name, mm);
        *k[i] = io_mm_to_q16(mm);
    }
    if (a->m->skel.joint_count >= CUB_MOTION_MAX_JOINTS)
        return cub_diag_fail(diag, CUB_ERR_FORMAT, a->lx.name, line, "more than %d joints",
                          CUB_MOTION_MAX_JOINTS);
    if (cub_motion_skeleton_find(&a->m->skel, name) >= 0)
        return cub_diag_fail(diag, CUB_ERR_FORMAT, a->lx.name, line, "bone '%s' is defined twice",
                          name);
    cub_err err = cub_motion_skeleton_add(&a->m->skel, name, parent, v, idx);
    if (err)
        return cub_diag_fail(diag, CUB_ERR_FORMAT, a->lx.name, line, "bone '%s' refused: %s", name,
                          cub_err_str(err));
    return CUB_OK;
}

static cub_err add_bone(amc_state *a, int b, cub_diag *diag)
{
    const asf_bone *bone = &a->asf.bone[b];
    double off[3] = {0, 0, 0};
    int parent = -1, idx = -1, children = 0;
    if (b == 0) {
        memcpy(off, a->asf.root_pos, sizeof(off));
    } else {
        parent = a->joint_of[bone->parent];
        if (bone->parent != 0)
            for (int k = 0; k < 3; k++)
                off[k] = a->asf.bone[bone->parent].dir[k] * a->asf.bone[bone->parent].len;
    }
    cub_err err = add_joint(a, bone->name, parent, off, bone->line, &idx, diag);
    if (err)
        return err;
    a->joint_of[b] = idx;
    cub_io_channels *ch = &a->m->channels[idx];
    ch->count = b == 0 ? 6 : 3;
    ch->has_pos = b == 0;
    memcpy(ch->rot_order, "ZYX", 4); /* C*M*C^-1 is a general rotation */
    memcpy(ch->pos_order, b == 0 ? "XYZ" : "", b == 0 ? 4 : 1);
    for (int c = 1; c < a->asf.count && !err; c++)
        if (a->asf.bone[c].parent == b) {
            children++;
            err = add_bone(a, c, diag);
        }
    if (err || children || b == 0)
        return err;
    char end[CUB_MOTION_NAME_LEN];
    for (int k = 0; k < 3; k++)
        off[k] = bone->dir[k] * bone->len;
    snprintf(end, sizeof(end), "%.27s_end", bone->name);
    err = add_joint(a, end, idx, off, bone->line, &idx, diag);
    if (!err)
        a->m->skel.joints[idx].is_end_site = 1;
    return err;
}

static cub_err build_skeleton(amc_state *a, cub_diag *diag)
{
    const asf_skel *s = &a->asf;
    for (int b = 0; b < s->count; b++) {
        double ax[3];
        for (int k = 0; k < 3; k++)
            ax[k] = s->bone[b].axis[s->bone[b].axis_order[k]] * a->rad_per_unit;
        a->c[b] = asf_euler(s->bone[b].axis_order, ax, 3);
        a->c_inv[b] = cub_dq_conj(a->c[b]);
        a->joint_of[b] = -1;
    }
    cub_motion_skeleton_reset(&a->m->skel);
    cub_err err = add_bone(a, 0, diag);
    for (int b = 1; b < s->count && !err; b++)
        if (a->joint_of[b] < 0)
            err = cub_diag_fail(diag, CUB_ERR_FORMAT, a->lx.name, s->bone[b].line,
                             "bone '%s' does not hang from root (a cycle in :hierarchy)",
                             s->bone[b].name);
    return err;
}

/* Turn the dof values gathered for frame f into the clip's rotations. */
static cub_err finish_frame(amc_state *a, int f, int line)
{
    cub_clip *clip = &a->m->clip;
    int jn = a->m->skel.joint_count;
    for (int j = 0; j < jn; j++)
        clip->rot[(size_t)f * jn + j] = io_quat_to_fx((cub_dq){1, 0, 0, 0});
    for (int b = 0; b < a->asf.count; b++) {
        const asf_bone *bone = &a->asf.bone[b];
        int axes[3], n = 0;
        double ang[3], t[3];
        memcpy(t, a->asf.root_pos, sizeof(t));
        for (int d = 0; d < bone->ndof; d++) {
            double v = a->seen[b] ? a->val[b][d] : 0.0;
            if (bone->dof[d] < 3) {
                axes[n] = bone->dof[d];
                ang[n++] = v * a->rad_per_unit;
            } else {
                t[bone->dof[d] - 3] = v;
            }
        }
        cub_dq q = cub_dq_mul(cub_dq_mul(a->c[b], asf_euler(axes, ang, n)), a->c_inv[b]);
        clip->rot[(size_t)f * jn + a->joint_of[b]] = io_quat_to_fx(q);
        if (b != 0)
            continue;
        int32_t *k[3] = {&clip->root_mm[f].x, &clip->root_mm[f].y, &clip->root_mm[f].z};
        for (int i = 0; i < 3; i++) {
            double mm = t[i] * a->m->unit_mm;
            if (!(fabs(mm) <= IO_MM_LIMIT))
                return io_fail(&a->lx, line, "frame %d: root translation %.0f mm is beyond +-32 m",
                               f + 1, mm);
            *k[i] = io_mm_to_q16(mm);
        }
    }
    memset(a->seen, 0, sizeof(a->seen));
    return CUB_OK;
}

static int all_digits(const io_tok *t)
{
    for (size_t i = 0; i < t->n; i++)
        if (t->s[i] < '0' || t->s[i] > '9')
            return 0;
    return t->n > 0;
}

static int count_frames(const io_lex *start, int *last_line)
{
    io_lex lx = *start;
    io_tok t;
    int n = 0;
    while (io_lex_next(&lx, &t))
        if (t.first_on_line && all_digits(&t) && n < INT32_MAX)
            n++;
    *last_line = lx.line;
    return n;
}

static cub_err bone_line(amc_state *a, const io_tok *t, int f)
{
    io_lex *lx = &a->lx;
    io_tok v;
    char name[CUB_MOTION_NAME_LEN], shown[40], what[64];
    int b = io_tok_copy(t, name, sizeof(name)) ? asf_find(&a->asf, name) : -1;
    if (f < 0)
        return io_fail(lx, t->line, "bone data before the first frame number");
    if (b < 0)
        return io_fail(lx, t->line, "unknown bone %s", io_tok_show(t, shown, sizeof(shown)));
    if (a->seen[b])
        return io_fail(lx, t->line, "bone '%s' appears twice in frame %d", name, f + 1);
    a->seen[b] = 1;
    int count = 0;
    while (io_lex_next_same_line(lx, &v)) {
        if (count < a->asf.bone[b].ndof) {
            snprintf(what, sizeof(what), "frame %d bone '%s'", f + 1, name);
            cub_err err = io_tok_double(lx, &v, what, &a->val[b][count]);
            if (err)
                return err;
        }
        count++;
    }
    if (count != a->asf.bone[b].ndof)
        return io_fail(lx, t->line, "frame %d: bone '%s' has %d values, expected %d", f + 1, name,
                       count, a->asf.bone[b].ndof);
    return CUB_OK;
}

static cub_err parse_amc(amc_state *a)
{
    io_lex *lx = &a->lx;
    io_tok t;
    long num = 0, prev = 0;
    int f = -1, line = 1, frames = count_frames(lx, &line);
    if (frames == 0)
        return io_fail(lx, line, "no frames (no frame number lines)");
    cub_err err = io_clip_alloc(a->m, frames, AMC_FRAME_NS, 0, lx->name, 1, lx->diag);
    while (!err && io_lex_next(lx, &t)) {
        if (t.s[0] == ':') {
            if (io_tok_is_nocase(&t, ":RADIANS"))
                a->rad_per_unit = 1.0;
            else if (io_tok_is_nocase(&t, ":DEGREES"))
                a->rad_per_unit = CUB_VEC_PI / 180.0;
            io_lex_skip_line(lx);
        } else if (all_digits(&t)) {
            if ((err = io_tok_long(lx, &t, "the frame number", &num)))
                break;
            if (f >= 0 && (prev == LONG_MAX || num != prev + 1))
                err = io_fail(lx, t.line, "frame number %ld follows %ld", num, prev);
            if (f >= 0 && !err)
                err = finish_frame(a, f, line);
            prev = num, line = t.line, f++;
            if (!err && io_lex_next_same_line(lx, &t))
                err = io_fail(lx, t.line, "unexpected %s after the frame number",
                              io_tok_show(&t, (char[40]){0}, 40));
        } else {
            err = bone_line(a, &t, f);
        }
    }
    if (!err)
        err = finish_frame(a, f, line);
    return err;
}

static cub_err parse_both(amc_state *a, const char *asf, size_t asf_len, const char *asf_name,
                          const char *amc, size_t amc_len, const char *amc_name,
                          const cub_io_desc *desc, cub_diag *diag)
{
    cub_err err = asf_parse(&a->asf, asf ? asf : "", asf_len, asf_name, diag);
    if (err)
        return err;
    a->rad_per_unit = a->asf.angle_deg ? CUB_VEC_PI / 180.0 : 1.0;
    a->m->unit_mm = (desc && desc->unit_mm > 0) ? desc->unit_mm : 25.4 / a->asf.length_unit;
    if (!isfinite(a->m->unit_mm))
        return cub_diag_fail(diag, CUB_ERR_ARG, asf_name, 0, "unit_mm is not finite");
    io_lex_init(&a->lx, amc ? amc : "", amc_len, asf_name, diag);
    if ((err = build_skeleton(a, diag)))
        return err;
    io_lex_init(&a->lx, amc ? amc : "", amc_len, amc_name, diag);
    a->lx.hash_comments = 1;
    return parse_amc(a);
}

static cub_err asf_amc(const char *asf, size_t asf_len, const char *asf_name, const char *amc,
                       size_t amc_len, const char *amc_name, const cub_io_desc *desc,
                       cub_io_motion *out, cub_diag *diag)
{
    if (!out || (!asf && asf_len) || (!amc && amc_len))
        return cub_diag_fail(diag, CUB_ERR_ARG, asf_name, 0, "no text or output");
    memset(out, 0, sizeof(*out));
    amc_state *a = calloc(1, sizeof(*a));
    if (!a)
        return cub_diag_fail(diag, CUB_ERR_NOMEM, asf_name, 0, "out of memory");
    a->m = out;
    size_t asf_bom = cub_text_bom_len(asf, asf_len), amc_bom = cub_text_bom_len(amc, amc_len);
    asf += asf_bom;
    asf_len -= asf_bom;
    amc += amc_bom;
    amc_len -= amc_bom;
    cub_err err = parse_both(a, asf, asf_len, asf_name, amc, amc_len, amc_name, desc, diag);
    free(a);
    if (err) {
        cub_io_motion_free(out);
        memset(out, 0, sizeof(*out));
    }
    return err;
}

cub_err cub_io_parse_asf_amc(const char *asf, size_t asf_len, const char *amc, size_t amc_len,
                             const char *name, const cub_io_desc *desc, cub_io_motion *out,
                             cub_diag *diag)
{
    char asf_name[200], amc_name[200];
    cub_diag scratch;
    if (!diag)
        diag = &scratch;
    memset(diag, 0, sizeof(*diag));
    snprintf(asf_name, sizeof(asf_name), "%.190s.asf", name ? name : "(memory)");
    snprintf(amc_name, sizeof(amc_name), "%.190s.amc", name ? name : "(memory)");
    return asf_amc(asf, asf_len, asf_name, amc, amc_len, amc_name, desc, out, diag);
}

cub_err cub_io_load_asf_amc(const char *asf_path, const char *amc_path, const cub_io_desc *desc,
                            cub_io_motion *out, cub_diag *diag)
{
    char *asf = NULL, *amc = NULL;
    size_t asf_len = 0, amc_len = 0;
    cub_diag scratch;
    if (!diag)
        diag = &scratch;
    memset(diag, 0, sizeof(*diag));
    cub_text_src asf_src = {asf_path, "ASF file", CUB_TEXT_MAX_MOCAP},
                amc_src = {amc_path, "AMC file", CUB_TEXT_MAX_MOCAP};
    cub_err err = cub_text_read(&asf_src, &asf, &asf_len, diag);
    if (!err)
        err = cub_text_read(&amc_src, &amc, &amc_len, diag);
    if (!err)
        err = asf_amc(asf, asf_len, asf_path, amc, amc_len, amc_path, desc, out, diag);
    free(asf);
    free(amc);
    return err;
}

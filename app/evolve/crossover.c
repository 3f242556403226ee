/* Crossover (SEEDS.md § 004): the meta skeleton M_s = C_s1 ∪ C_s2. */
#include <stdio.h>
#include <string.h>

#include "cub/evolve.h"

/* b's joint jb in the meta skeleton: its partner's index when it has one
 * (parent 1's joints keep their indices), else where it was appended. */
static int meta_of_b(const cub_evolve_corr *corr, const int *appended_at, int jb)
{
    for (int i = 0; i < corr->pair_count; i++)
        if (corr->pair[i].b == jb) return corr->pair[i].a;
    return appended_at[jb];
}

static cub_err append(cub_evolve_meta *m, const cub_joint *jt, int parent, int src, cub_diag *diag)
{
    char name[CUB_MOTION_NAME_LEN];
    snprintf(name, sizeof name, "%s", jt->name);
    if (cub_motion_skeleton_find(&m->skel, name) >= 0) {
        char base[CUB_MOTION_NAME_LEN - 2];
        snprintf(base, sizeof base, "%s", jt->name);
        snprintf(name, sizeof name, "%s_2", base);
    }
    int at = -1;
    cub_err err = cub_motion_skeleton_add(&m->skel, name, parent, jt->offset_mm, &at);
    if (err)
        return cub_diag_fail(diag, err, "(crossover)", 0, "cannot add parent 2's joint \"%s\"%s",
                             jt->name, err == CUB_ERR_FULL ? ": more than 128 joints" : "");
    m->skel.joints[at].is_end_site = jt->is_end_site;
    m->from[at] = 2;
    m->src[at] = src;
    m->partner[at] = -1;
    m->appended++;
    return CUB_OK;
}

cub_err cub_evolve_crossover(const cub_skeleton *a, const cub_skeleton *b,
                             const cub_evolve_corr *corr, cub_evolve_meta *out, cub_diag *diag)
{
    if (!a || !b || !corr || !out)
        return cub_diag_fail(diag, CUB_ERR_ARG, "(crossover)", 0, "no input");
    memset(out, 0, sizeof(*out));
    out->skel = *a;
    for (int j = 0; j < a->joint_count; j++) {
        out->from[j] = 1;
        out->src[j] = j;
        out->partner[j] = cub_evolve_partner_of_a(corr, j);
    }
    for (int i = 0; i < corr->pair_count; i++) {
        int ja = corr->pair[i].a;
        if (out->partner_count[ja] < CUB_EVOLVE_MAP_SIDE)
            out->partners[ja][out->partner_count[ja]++] = corr->pair[i].b;
    }
    int appended_at[CUB_EVOLVE_MAX_JOINTS];
    for (int jb = 0; jb < b->joint_count; jb++) {
        appended_at[jb] = -1;
        if (cub_evolve_kind_of(corr, 2, jb) != CUB_EVOLVE_NONE) continue;
        int pb = b->joints[jb].parent;
        int parent = pb < 0 ? 0 : meta_of_b(corr, appended_at, pb);
        cub_err err = append(out, &b->joints[jb], parent, jb, diag);
        if (err) return err;
        appended_at[jb] = out->skel.joint_count - 1;
    }
    return CUB_OK;
}

/* Writing a clip as a 3ds Max ASCII export (cub/ase.h): the rest
 * transforms are frame 0's world transforms, so a reader that follows the
 * TM path (eqs. 4.2-4.3 of the seed) gets each bone's offset back; the
 * rotation track is the seed's: the first sample relative to the parent,
 * each later one relative to the previous frame. Units: mm. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cub/ase.h"
#include "io_internal.h"

typedef struct ase_world {
    cub_dv3 pos[CUB_MOTION_MAX_JOINTS];
    cub_dq rot[CUB_MOTION_MAX_JOINTS];
} ase_world;

static cub_dq local_rot(const cub_clip *c, int f, int j)
{
    return cub_dq_from_fx(c->rot[(size_t)f * (size_t)c->skel->joint_count + (size_t)j]);
}

static cub_dv3 local_pos(const cub_clip *c, int f, int j)
{
    if (j == 0) return cub_dv3_from_fx(c->root_mm[f]);
    if (c->trans_mm)
        return cub_dv3_from_fx(c->trans_mm[(size_t)f * (size_t)c->skel->joint_count + (size_t)j]);
    return cub_dv3_from_fx(c->skel->joints[j].offset_mm);
}

/* Frame f's world transforms, in doubles: M_i = M_parent T_i R_i. */
static void world_at(const cub_clip *c, int f, ase_world *w)
{
    for (int j = 0; j < c->skel->joint_count; j++) {
        int p = c->skel->joints[j].parent;
        cub_dq r = cub_dq_norm(local_rot(c, f, j));
        cub_dv3 t = local_pos(c, f, j);
        w->pos[j] = p < 0 ? t : cub_dv3_add(w->pos[p], cub_dq_rotate(w->rot[p], t));
        w->rot[j] = p < 0 ? r : cub_dq_norm(cub_dq_mul(w->rot[p], r));
    }
}

static void put_tm(FILE *f, const char *name, cub_dv3 pos, cub_dq q)
{
    cub_dv3 ax[3] = {cub_dq_rotate(q, cub_dv3_make(1, 0, 0)), cub_dq_rotate(q, cub_dv3_make(0, 1, 0)),
                     cub_dq_rotate(q, cub_dv3_make(0, 0, 1))};
    fprintf(f, "\t*NODE_TM {\n\t\t*NODE_NAME \"%s\"\n", name);
    for (int i = 0; i < 3; i++)
        fprintf(f, "\t\t*TM_ROW%d %.10f\t%.10f\t%.10f\n", i, ax[i].x, ax[i].y, ax[i].z);
    fprintf(f, "\t\t*TM_ROW3 %.6f\t%.6f\t%.6f\n", pos.x, pos.y, pos.z);
    fprintf(f, "\t\t*TM_POS %.6f\t%.6f\t%.6f\n", pos.x, pos.y, pos.z);
    fprintf(f, "\t\t*TM_QUATERNION %.10f\t%.10f\t%.10f\t%.10f\n\t}\n", q.x, q.y, q.z, q.w);
}

/* A rotation as a unit axis and an angle in [0, pi] (identity: 0 0 0 0). */
static void put_rot(FILE *f, long tick, cub_dq q)
{
    if (q.w < 0) q = (cub_dq){-q.w, -q.x, -q.y, -q.z};
    double s = sqrt(q.x * q.x + q.y * q.y + q.z * q.z);
    if (s < 1e-15) {
        fprintf(f, "\t\t\t*CONTROL_ROT_SAMPLE %ld\t0.0\t0.0\t0.0\t0.0\n", tick);
        return;
    }
    fprintf(f, "\t\t\t*CONTROL_ROT_SAMPLE %ld\t%.12f\t%.12f\t%.12f\t%.12f\n", tick, q.x / s,
            q.y / s, q.z / s, 2 * atan2(s, q.w));
}

static void put_tracks(FILE *f, const cub_clip *c, int j)
{
    const cub_joint *jt = &c->skel->joints[j];
    fprintf(f, "\t*TM_ANIMATION {\n\t\t*NODE_NAME \"%s\"\n", jt->name);
    if (j == 0 || c->trans_mm) {
        fprintf(f, "\t\t*CONTROL_POS_TRACK {\n");
        for (int k = 0; k < c->frame_count; k++) {
            cub_dv3 p = local_pos(c, k, j);
            fprintf(f, "\t\t\t*CONTROL_POS_SAMPLE %ld\t%.6f\t%.6f\t%.6f\n",
                    (long)k * CUB_ASE_TICKS_PER_FRAME, p.x, p.y, p.z);
        }
        fprintf(f, "\t\t}\n");
    }
    if (!jt->is_end_site) {
        fprintf(f, "\t\t*CONTROL_ROT_TRACK {\n");
        cub_dq prev = cub_dq_identity();
        for (int k = 0; k < c->frame_count; k++) {
            cub_dq q = cub_dq_norm(local_rot(c, k, j));
            put_rot(f, (long)k * CUB_ASE_TICKS_PER_FRAME, cub_dq_mul(cub_dq_conj(prev), q));
            prev = q;
        }
        fprintf(f, "\t\t}\n");
    }
    fprintf(f, "\t}\n");
}

static void put_file(FILE *f, const cub_io_motion *m, const ase_world *w)
{
    const cub_clip *c = &m->clip;
    fprintf(f, "*3DSMAX_ASCIIEXPORT\t200\n*COMMENT \"cubtool ase-export: units mm; rotation "
               "samples: unit axis, angle in radians\"\n");
    fprintf(f, "*SCENE {\n\t*SCENE_FILENAME \"cubdance\"\n\t*SCENE_FIRSTFRAME 0\n"
               "\t*SCENE_LASTFRAME %d\n\t*SCENE_FRAMESPEED %.9g\n\t*SCENE_TICKSPERFRAME %d\n}\n",
            c->frame_count - 1, 1e9 / c->frame_ns, CUB_ASE_TICKS_PER_FRAME);
    const cub_skeleton *sk = c->skel;
    for (int j = 0; j < sk->joint_count; j++) {
        const cub_joint *jt = &sk->joints[j];
        fprintf(f, "*HELPEROBJECT {\n\t*NODE_NAME \"%s\"\n", jt->name);
        if (jt->parent >= 0) fprintf(f, "\t*NODE_PARENT \"%s\"\n", sk->joints[jt->parent].name);
        fprintf(f, "\t*HELPER_CLASS \"%s\"\n", jt->is_end_site ? "Dummy" : "Bone");
        put_tm(f, jt->name, w->pos[j], w->rot[j]);
        put_tracks(f, c, j);
        fprintf(f, "}\n");
    }
}

cub_err cub_ase_save(const char *path, const cub_io_motion *m, cub_diag *diag)
{
    const char *file = path ? path : "(null)";
    if (!path || !m || m->clip.frame_count < 1 || !m->clip.skel ||
        m->clip.skel->joint_count < 1 || !m->clip.frame_ns)
        return cub_diag_fail(diag, CUB_ERR_ARG, file, 0, "no path or no clip to write");
    ase_world *w = malloc(sizeof(*w));
    if (!w) return cub_diag_fail(diag, CUB_ERR_NOMEM, file, 0, "out of memory");
    world_at(&m->clip, 0, w);
    FILE *f = fopen(path, "w");
    if (!f) {
        free(w);
        return cub_diag_fail(diag, CUB_ERR_IO, file, 0, "cannot create the file");
    }
    put_file(f, m, w);
    int ok = !ferror(f);
    ok = (fclose(f) == 0) && ok;
    free(w);
    return ok ? CUB_OK : cub_diag_fail(diag, CUB_ERR_IO, file, 0, "write failed");
}

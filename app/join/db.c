/* The motion database: each clip's world positions, foot contacts and
 * support masks, computed once when the clip is added. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "join_internal.h"

static void fill_defaults(cub_join_cfg *c)
{
    if (c->window_frames <= 0) c->window_frames = 5;
    if (c->min_frames <= 0) c->min_frames = 3 * c->window_frames;
    if (c->max_frames <= 0) c->max_frames = 90;
    if (c->blend_mm_per_frame <= 0) c->blend_mm_per_frame = 10;
    if (c->min_blend <= 0) c->min_blend = 3;
    if (c->max_blend <= 0) c->max_blend = 20;
}

cub_err cub_join_db_init(cub_join_db *db, const cub_skeleton *skel, const cub_join_cfg *cfg,
                         cub_diag *diag)
{
    memset(db, 0, sizeof *db);
    if (!skel) return CUB_ERR_ARG;
    cub_err e = cub_join_body_find(skel, &db->body, diag);
    if (e) return e;
    db->skel = skel;
    if (cfg) db->cfg = *cfg;
    fill_defaults(&db->cfg);
    return CUB_OK;
}

double join_dt_s(const cub_clip *clip)
{
    return clip->frame_ns ? clip->frame_ns * 1e-9 : 1.0 / 30;
}

void join_frame_world(const cub_clip *clip, int f, cub_dv3 *pos, cub_dq *rot)
{
    static cub_pose pose; /* large; host code, one thread */
    cub_vec3 w[CUB_MOTION_MAX_JOINTS];
    cub_quat r[CUB_MOTION_MAX_JOINTS];
    cub_motion_clip_get_frame(clip, f, &pose);
    cub_motion_forward(clip->skel, &pose, w, r);
    for (int j = 0; j < clip->skel->joint_count; j++) {
        pos[j] = cub_dv3_from_fx(w[j]);
        if (rot) rot[j] = cub_dq_norm(cub_dq_from_fx(r[j]));
    }
}

/* The lowest joint of a part per frame (its surface: pad below it). */
static void part_track(const cub_join_db *db, const cub_join_clip *c, int part, cub_dv3 *out)
{
    int nj = db->skel->joint_count, frames = c->clip->frame_count;
    for (int f = 0; f < frames; f++) {
        cub_dv3 low = {0, INFINITY, 0};
        for (int k = 0; k < CUB_JOIN_PART_JOINTS && db->body.part[part][k] >= 0; k++) {
            cub_dv3 p = c->pos[(size_t)f * nj + db->body.part[part][k]];
            if (p.y < low.y) low = p;
        }
        low.y -= db->body.pad_mm[part];
        out[f] = low;
    }
}

/* Contacts of every part, the floor being the lowest foot point. */
static cub_err find_supports(const cub_join_db *db, cub_join_clip *c)
{
    int frames = c->clip->frame_count;
    cub_dv3 *tr = malloc(sizeof(cub_dv3) * (size_t)frames);
    unsigned char *ct = malloc((size_t)frames);
    if (!tr || !ct) {
        free(tr), free(ct);
        return CUB_ERR_NOMEM;
    }
    cub_join_track t = {tr, 1, 1.0, frames, join_dt_s(c->clip)};
    c->floor_mm = INFINITY;
    for (int s = 0; s < 2; s++) {
        part_track(db, c, CUB_JOIN_LFOOT + s, tr);
        c->floor_mm = fmin(c->floor_mm, cub_join_track_lowest(&t));
    }
    for (int part = 0; part < CUB_JOIN_PARTS; part++) {
        part_track(db, c, part, tr);
        cub_join_contacts(&t, &db->cfg.contact, c->floor_mm, ct);
        for (int f = 0; f < frames; f++)
            c->support[f] |= (unsigned char)(ct[f] << part);
        if (part <= CUB_JOIN_RFOOT) memcpy(c->foot[part], ct, (size_t)frames);
    }
    free(tr), free(ct);
    return CUB_OK;
}

cub_err cub_join_db_add(cub_join_db *db, const char *name, const cub_clip *clip, int *index)
{
    if (!clip || clip->skel->joint_count != db->skel->joint_count ||
        clip->frame_count < 2 * db->cfg.window_frames)
        return CUB_ERR_ARG;
    for (int j = 0; j < db->skel->joint_count; j++)
        if (clip->skel->joints[j].parent != db->skel->joints[j].parent ||
            strcmp(clip->skel->joints[j].name, db->skel->joints[j].name))
            return CUB_ERR_ARG;
    if (db->count == db->cap) {
        int cap = db->cap ? db->cap * 2 : 16;
        cub_join_clip *m = realloc(db->clips, sizeof *m * (size_t)cap);
        if (!m) return CUB_ERR_NOMEM;
        db->clips = m, db->cap = cap;
    }
    cub_join_clip *c = &db->clips[db->count];
    memset(c, 0, sizeof *c);
    snprintf(c->name, sizeof c->name, "%s", name ? name : "");
    c->clip = clip;
    int frames = clip->frame_count, nj = db->skel->joint_count;
    c->pos = malloc(sizeof(cub_dv3) * (size_t)frames * nj);
    c->support = calloc((size_t)frames, 1);
    c->foot[0] = calloc((size_t)frames, 1);
    c->foot[1] = calloc((size_t)frames, 1);
    if (!c->pos || !c->support || !c->foot[0] || !c->foot[1]) {
        join_clip_free(c);
        return CUB_ERR_NOMEM;
    }
    for (int f = 0; f < frames; f++)
        join_frame_world(clip, f, c->pos + (size_t)f * nj, NULL);
    if (find_supports(db, c)) {
        join_clip_free(c);
        return CUB_ERR_NOMEM;
    }
    if (index) *index = db->count;
    db->count++;
    return CUB_OK;
}

void join_clip_free(cub_join_clip *c)
{
    free(c->pos), free(c->support), free(c->foot[0]), free(c->foot[1]);
    memset(c, 0, sizeof *c);
}

void cub_join_db_free(cub_join_db *db)
{
    for (int i = 0; i < db->count; i++)
        join_clip_free(&db->clips[i]);
    free(db->clips);
    memset(db, 0, sizeof *db);
}

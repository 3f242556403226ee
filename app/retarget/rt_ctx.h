/* The working state of one retarget run, shared by retarget.c (transfer),
 * source.c (sampling the source, frames of reference) and feet.c (floor,
 * contacts, leg IK). Not public. */
#ifndef CUB_RT_CTX_H
#define CUB_RT_CTX_H

#include "cub/retarget.h"
#include "rt_internal.h"

typedef struct rt_ctx {
    const cub_retarget_map *map;
    const cub_skeleton *tgt;
    const cub_clip *src;
    cub_retarget_desc d; /* defaults filled in */
    const char *name;
    cub_diag *diag;

    int links, tj, sj;   /* link count, target and source joint counts */
    int frames;          /* output frames */
    double dt_s;         /* output frame period */
    double src_dt_s;

    /* key target joints: hips, head, up_leg[2], leg[2], foot[2] */
    int hips, head, up_leg[2], leg[2], foot[2];
    int link_of[CUB_MOTION_MAX_JOINTS];   /* target joint -> link, or -1 */
    int aim_of[CUB_MOTION_MAX_JOINTS];    /* target joint -> linked child joint, or -1 */
    int partner[CUB_MOTION_MAX_JOINTS];   /* link -> its mirror link (itself if none) */
    cub_dq align_inv[CUB_MOTION_MAX_JOINTS];/* A_j^-1 per target joint */
    cub_dv3 tgt_rest_pos[CUB_MOTION_MAX_JOINTS];
    int is_foot[CUB_MOTION_MAX_JOINTS];   /* the feet and their descendants */

    cub_dq q0;         /* source rest frame -> target frame */
    cub_dq yaw;        /* turn about y after q0 (and mirroring) */
    double k;        /* leg ratio */

    /* per output frame, per link: source position (target axes, source
     * scale) and rotation G = Yaw * W * Q0^-1 */
    cub_dv3 *lpos;
    cub_dq *lrot;
    /* the result, per frame: root and local rotations */
    cub_dv3 *root;
    cub_dq *local;
    /* contacts per frame and foot */
    unsigned char *contact[2];

    /* scratch */
    cub_dq *s_rot, *s_wrot;
    cub_dv3 *s_trans, *s_wpos;
} rt_ctx;

/* source.c */
/* Sample the source at output frame f into per-link data (stage A: target
 * axes, no yaw, no mirror): pos[link], rot[link]. */
void rt_source_links_at(rt_ctx *c, double t_s, cub_dv3 *pos, cub_dq *rot);
/* The source rest pose as per-link data (stage A). */
void rt_source_links_rest(rt_ctx *c, cub_dv3 *pos, cub_dq *rot);
/* Apply mirroring (swap partners, reflect x) to per-link data in place. */
void rt_mirror_links(const rt_ctx *c, cub_dv3 *pos, cub_dq *rot);
/* Q0 and k from the rest poses; fails when the source is degenerate. */
cub_err rt_setup_frames(rt_ctx *c);

/* feet.c */
/* Place the floor, find contacts, pin the feet, fill the report. */
void rt_feet(rt_ctx *c, cub_retarget_report *rep);
/* Target world positions and rotations of frame f. */
void rt_target_world(const rt_ctx *c, int f, cub_dv3 *pos, cub_dq *rot);

#endif

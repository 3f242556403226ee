/* Contacts of one point with the floor, and the body's support parts found
 * by joint name. The contact rule is the retargeter's foot rule (low and
 * slow, in runs), shared: app/retarget/feet.c pins feet with it. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cub/join.h"

#define DEF_HEIGHT_MM 30
#define DEF_SPEED_MM_S 180
#define DEF_MIN_FRAMES 3

static double y_at(const cub_join_track *t, int f)
{
    return t->pos[(size_t)f * t->stride].y * (t->scale > 0 ? t->scale : 1.0);
}

double cub_join_track_lowest(const cub_join_track *t)
{
    double low = INFINITY;
    for (int f = 0; f < t->frames; f++)
        low = fmin(low, y_at(t, f));
    return low;
}

void cub_join_contacts(const cub_join_track *t, const cub_join_contact_cfg *cfg, double floor_mm,
                       unsigned char *out)
{
    double k = t->scale > 0 ? t->scale : 1.0;
    double hmax = cfg && cfg->height_mm > 0 ? cfg->height_mm : DEF_HEIGHT_MM;
    double vmax = cfg && cfg->speed_mm_s > 0 ? cfg->speed_mm_s : DEF_SPEED_MM_S;
    int run = cfg && cfg->min_frames > 0 ? cfg->min_frames : DEF_MIN_FRAMES;
    for (int f = 0; f < t->frames; f++) {
        int a = f > 0 ? f - 1 : f, b = f + 1 < t->frames ? f + 1 : f;
        cub_dv3 pa = t->pos[(size_t)a * t->stride], pb = t->pos[(size_t)b * t->stride];
        double v = b > a ? cub_dv3_len(cub_dv3_sub(pb, pa)) * k / ((b - a) * t->dt_s) : 0;
        double h = t->pos[(size_t)f * t->stride].y * k - floor_mm;
        out[f] = h < hmax && v < vmax;
    }
    for (int f = 0; f < t->frames;) {
        int e = f;
        while (e < t->frames && out[e] == out[f])
            e++;
        if (out[f] && e - f < run) memset(out + f, 0, (size_t)(e - f));
        f = e;
    }
}

/* ---- the body ------------------------------------------------------------- */

static const char *const PART_NAMES[CUB_JOIN_PARTS] = {"LF", "RF", "LH", "RH", "LK", "RK", "HIP"};

const char *cub_join_support_name(unsigned mask, char *buf, size_t size)
{
    if (!size) return buf;
    buf[0] = 0;
    size_t n = 0;
    /* Hip first, then hands, knees, feet: "HIP+LF+RF" reads as the seed's
     * "hip + two feet". */
    static const int order[CUB_JOIN_PARTS] = {CUB_JOIN_HIP,   CUB_JOIN_LHAND, CUB_JOIN_RHAND,
                                              CUB_JOIN_LKNEE, CUB_JOIN_RKNEE, CUB_JOIN_LFOOT,
                                              CUB_JOIN_RFOOT};
    for (int i = 0; i < CUB_JOIN_PARTS; i++)
        if (mask & (1u << order[i]))
            n += (size_t)snprintf(buf + (n < size ? n : size - 1), n < size ? size - n : 1, "%s%s",
                                  n ? "+" : "", PART_NAMES[order[i]]);
    if (!buf[0]) snprintf(buf, size, "air");
    return buf;
}

/* Joint index of a side's limb joint under the usual namings: CMU and the
 * bear ("LeftUpLeg", "LeftLeg", "LeftFoot", "LeftHand") and Bandai's
 * ("UpperLeg_L", "LowerLeg_L", "Foot_L", "Hand_L"). -1 when none. */
static int find_side(const cub_skeleton *s, int side, int limb)
{
    static const char *const cmu[4] = {"UpLeg", "Leg", "Foot", "Hand"};
    static const char *const bandai[4] = {"UpperLeg", "LowerLeg", "Foot", "Hand"};
    char name[CUB_MOTION_NAME_LEN];
    snprintf(name, sizeof name, "%s%s", side ? "Right" : "Left", cmu[limb]);
    int j = cub_motion_skeleton_find(s, name);
    if (j >= 0) return j;
    snprintf(name, sizeof name, "%s_%c", bandai[limb], side ? 'R' : 'L');
    return cub_motion_skeleton_find(s, name);
}

/* The joint j and what hangs below it (toes, end sites), up to the part's
 * room. */
static void part_from(const cub_skeleton *s, int j, int *out)
{
    int n = 0;
    for (int k = 0; k < CUB_JOIN_PART_JOINTS; k++)
        out[k] = -1;
    for (int k = j; k < s->joint_count && n < CUB_JOIN_PART_JOINTS; k++) {
        int a = k;
        while (a > j)
            a = s->joints[a].parent;
        if (a == j) out[n++] = k;
    }
}

static double bone_mm(const cub_skeleton *s, int j)
{
    return cub_dv3_len(cub_dv3_from_fx(s->joints[j].offset_mm));
}

cub_err cub_join_body_find(const cub_skeleton *skel, cub_join_body *out, cub_diag *diag)
{
    memset(out, 0, sizeof *out);
    static const char *const need[] = {"UpLeg", "Leg", "Foot", "Hand"};
    int idx[2][4];
    for (int side = 0; side < 2; side++)
        for (int i = 0; i < 4; i++) {
            idx[side][i] = find_side(skel, side, i);
            if (idx[side][i] < 0)
                return cub_diag_fail(diag, CUB_ERR_FORMAT, "skeleton", 0,
                                     "no joint %s%s: the join needs legs and hands",
                                     side ? "Right" : "Left", need[i]);
        }
    /* The pelvis: "Hips" where there is one (Bandai's root is a joint on
     * the floor below it), else the root. */
    out->hips = cub_motion_skeleton_find(skel, "Hips");
    out->hips = out->hips < 0 ? 0 : out->hips;
    for (int side = 0; side < 2; side++) {
        out->leg[side] = (cub_join_leg){idx[side][0], idx[side][1], idx[side][2]};
        part_from(skel, idx[side][2], out->part[CUB_JOIN_LFOOT + side]);
        part_from(skel, idx[side][3], out->part[CUB_JOIN_LHAND + side]);
        for (int k = 0; k < CUB_JOIN_PART_JOINTS; k++)
            out->part[CUB_JOIN_LKNEE + side][k] = k ? -1 : idx[side][1];
    }
    for (int k = 0; k < CUB_JOIN_PART_JOINTS; k++)
        out->part[CUB_JOIN_HIP][k] = k ? -1 : out->hips;
    /* Knee and seat are joints inside the body: their surfaces lie below
     * them by a share of the thigh (a guess from human proportions, not
     * tuned on any clip: the knee cap 1/8 of the thigh, the seat 1/3). */
    double thigh = 0.5 * (bone_mm(skel, idx[0][1]) + bone_mm(skel, idx[1][1]));
    out->pad_mm[CUB_JOIN_LKNEE] = out->pad_mm[CUB_JOIN_RKNEE] = thigh / 8;
    out->pad_mm[CUB_JOIN_HIP] = thigh / 3;
    return CUB_OK;
}

/* An actor: a mocap clip mapped to the 20 Kinect joints, by joint names per
 * skeleton family (a small table each), turned into a y-up frame (left +x,
 * facing +z) and scaled to a child's height. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "synth_internal.h"

/* A point = A + frac * (B - A); B NULL: A itself; B "+": A's first child
 * (a BVH End Site, e.g. the top of the head). */
typedef struct map_entry {
    const char *a, *b;
    float frac;
} map_entry;

typedef struct family {
    const char *name;
    const char *detect; /* a joint only this family has */
    map_entry e[CUB_KJ_COUNT];
} family;

#define LEGS(h, k, a, f)                                                                           \
    {h, NULL, 0}, {k, NULL, 0}, {a, NULL, 0},                                                      \
    {                                                                                              \
        f, NULL, 0                                                                                 \
    }
/* clang-format off */
static const family families[] = {
    /* before CMU cgspeed: it has an LHipJoint too */
    {"AnimatedDrawings CMU BVH (31 joints)", "LeftElbow", {
        {"Hips", NULL, 0}, {"Chest", NULL, 0}, {"lowerneck", NULL, 0}, {"Head", "+", 0.5f},
        {"LeftShoulder", NULL, 0}, {"LeftElbow", NULL, 0}, {"LeftWrist", NULL, 0},
        {"lhand", "LFingers", 0.8f},
        {"RightShoulder", NULL, 0}, {"RightElbow", NULL, 0}, {"RightWrist", NULL, 0},
        {"rhand", "RFingers", 0.8f},
        LEGS("LeftHip", "LeftKnee", "LeftAnkle", "LeftToe"),
        LEGS("RightHip", "RightKnee", "RightAnkle", "RightToe")}},
    {"CMU cgspeed BVH (31 joints)", "LHipJoint", {
        {"Hips", NULL, 0}, {"Spine", NULL, 0}, {"Neck", NULL, 0}, {"Head", "+", 0.5f},
        {"LeftArm", NULL, 0}, {"LeftForeArm", NULL, 0}, {"LeftHand", NULL, 0},
        {"LeftHand", "LeftHandIndex1", 0.6f},
        {"RightArm", NULL, 0}, {"RightForeArm", NULL, 0}, {"RightHand", NULL, 0},
        {"RightHand", "RightHandIndex1", 0.6f},
        LEGS("LeftUpLeg", "LeftLeg", "LeftFoot", "LeftToeBase"),
        LEGS("RightUpLeg", "RightLeg", "RightFoot", "RightToeBase")}},
    {"CMU ASF/AMC", "lhumerus", {
        {"root", NULL, 0}, {"upperback", NULL, 0}, {"lowerneck", NULL, 0}, {"head", "+", 0.5f},
        {"lhumerus", NULL, 0}, {"lradius", NULL, 0}, {"lwrist", NULL, 0},
        {"lhand", "lfingers", 0.8f},
        {"rhumerus", NULL, 0}, {"rradius", NULL, 0}, {"rwrist", NULL, 0},
        {"rhand", "rfingers", 0.8f},
        LEGS("lfemur", "ltibia", "lfoot", "ltoes"),
        LEGS("rfemur", "rtibia", "rfoot", "rtoes")}},
    {"AnimatedDrawings BVH (27 joints)", "Spine3", {
        {"Hips", NULL, 0}, {"Spine1", NULL, 0}, {"Neck", NULL, 0}, {"Head", "+", 0.5f},
        {"LeftArm", NULL, 0}, {"LeftForeArm", NULL, 0}, {"LeftHand", NULL, 0},
        {"LeftHand", "LeftHandEnd", 0.6f},
        {"RightArm", NULL, 0}, {"RightForeArm", NULL, 0}, {"RightHand", NULL, 0},
        {"RightHand", "RightHandEnd", 0.6f},
        LEGS("LeftUpLeg", "LeftLeg", "LeftFoot", "LeftToeBase"),
        LEGS("RightUpLeg", "RightLeg", "RightFoot", "RightToeBase")}},
    {"Rokoko BVH (60 joints)", "LeftHandMiddle1", {
        {"Hips", NULL, 0}, {"Spine1", NULL, 0}, {"Neck", NULL, 0}, {"Head", "+", 0.5f},
        {"LeftArm", NULL, 0}, {"LeftForeArm", NULL, 0}, {"LeftHand", NULL, 0},
        {"LeftHand", "LeftHandMiddle1", 0.8f},
        {"RightArm", NULL, 0}, {"RightForeArm", NULL, 0}, {"RightHand", NULL, 0},
        {"RightHand", "RightHandMiddle1", 0.8f},
        LEGS("LeftUpLeg", "LeftLeg", "LeftFoot", "LeftToeBase"),
        LEGS("RightUpLeg", "RightLeg", "RightFoot", "RightToeBase")}},
    {"Bandai BVH (22 joints)", "UpperArm_L", {
        {"Hips", NULL, 0}, {"Spine", NULL, 0}, {"Neck", NULL, 0}, {"Head", "+", 0.5f},
        {"UpperArm_L", NULL, 0}, {"LowerArm_L", NULL, 0}, {"Hand_L", NULL, 0},
        {"Hand_L", "+", 0.6f},
        {"UpperArm_R", NULL, 0}, {"LowerArm_R", NULL, 0}, {"Hand_R", NULL, 0},
        {"Hand_R", "+", 0.6f},
        LEGS("UpperLeg_L", "LowerLeg_L", "Foot_L", "Toes_L"),
        LEGS("UpperLeg_R", "LowerLeg_R", "Foot_R", "Toes_R")}},
    {"DAZ BVH (43 joints)", "lShldr", {
        {"hip", NULL, 0}, {"abdomen", NULL, 0}, {"neck", NULL, 0}, {"head", "+", 0.5f},
        {"lShldr", NULL, 0}, {"lForeArm", NULL, 0}, {"lHand", NULL, 0},
        {"lHand", "lMid1", 0.8f},
        {"rShldr", NULL, 0}, {"rForeArm", NULL, 0}, {"rHand", NULL, 0},
        {"rHand", "rMid1", 0.8f},
        LEGS("lThigh", "lShin", "lFoot", "lFoot_end"),
        LEGS("rThigh", "rShin", "rFoot", "rFoot_end")}},
};
/* clang-format on */

struct synth_actor {
    char name[256];
    cub_io_motion m;
    int ia[CUB_KJ_COUNT], ib[CUB_KJ_COUNT];
    float frac[CUB_KJ_COUNT];
    cub_fv3 basis[3]; /* source axes giving the actor's x (left), y (up), z (forward) */
    float scale;
    float height_mm;
    cub_pose pose;                         /* scratch */
    cub_vec3 world[CUB_MOTION_MAX_JOINTS]; /* scratch */
};

static cub_err fail(cub_diag *diag, const char *file, const char *fmt, const char *a, const char *b)
{
    if (diag) {
        memset(diag, 0, sizeof(*diag));
        snprintf(diag->file, sizeof(diag->file), "%.250s", file);
        snprintf(diag->msg, sizeof(diag->msg), fmt, a, b);
    }
    return CUB_ERR_FORMAT;
}

static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), k = strlen(suffix);
    return n >= k && strcmp(s + n - k, suffix) == 0;
}

/* A short name ("13_29") -> a path under data_dir/mocap. */
static int resolve(const char *clip, const char *data_dir, char *path, size_t size)
{
    if (strchr(clip, '/') || ends_with(clip, ".bvh") || ends_with(clip, ".amc")) {
        snprintf(path, size, "%s", clip);
        return 1;
    }
    static const char *where[] = {"cmu/%s.bvh",           "cmu/asfamc/%s.amc",
                                  "cmu/daz43/%s.bvh",     "animdraw/fair1/%s.bvh",
                                  "animdraw/cmu1/%s.bvh", "animdraw/rokoko/%s.bvh",
                                  "bandai/data/%s.bvh"};
    if (!data_dir) return 0;
    for (size_t i = 0; i < sizeof(where) / sizeof(where[0]); i++) {
        char rel[300];
        snprintf(rel, sizeof(rel), where[i], clip);
        snprintf(path, size, "%s/mocap/%s", data_dir, rel);
        if (access(path, R_OK) == 0) return 1;
    }
    return 0;
}

static cub_err load_motion(const char *path, cub_io_motion *m, cub_diag *diag)
{
    cub_io_desc io = {0};
    if (!ends_with(path, ".amc")) return cub_io_load_bvh(path, &io, m, diag);
    /* CMU: subject 13's motions 13_NN.amc share 13.asf in the same folder. */
    char asf[600];
    snprintf(asf, sizeof(asf), "%s", path);
    char *slash = strrchr(asf, '/');
    char *base = slash ? slash + 1 : asf;
    char *us = strchr(base, '_');
    if (!us) us = base + strlen(base) - 4;
    snprintf(us, sizeof(asf) - (size_t)(us - asf), ".asf");
    return cub_io_load_asf_amc(asf, path, &io, m, diag);
}

static int first_child(const cub_skeleton *sk, int j)
{
    for (int i = j + 1; i < sk->joint_count; i++)
        if (sk->joints[i].parent == j) return i;
    return -1;
}

static cub_err map_joints(synth_actor *a, cub_diag *diag)
{
    const cub_skeleton *sk = &a->m.skel;
    const family *fam = NULL;
    for (size_t f = 0; f < sizeof(families) / sizeof(families[0]) && !fam; f++)
        if (cub_motion_skeleton_find(sk, families[f].detect) >= 0) fam = &families[f];
    if (!fam)
        return fail(diag, a->name,
                    "unknown skeleton family%s%s (known: CMU BVH and ASF/AMC, AnimatedDrawings, "
                    "Rokoko, Bandai, DAZ)",
                    "", "");
    for (int j = 0; j < CUB_KJ_COUNT; j++) {
        const map_entry *e = &fam->e[j];
        a->ia[j] = cub_motion_skeleton_find(sk, e->a);
        if (a->ia[j] < 0)
            return fail(diag, a->name, "joint '%s' (for %s) missing", e->a,
                        cub_kinect_joint_name(j));
        a->ib[j] = -1;
        a->frac[j] = e->frac;
        if (!e->b) continue;
        a->ib[j] =
            strcmp(e->b, "+") == 0 ? first_child(sk, a->ia[j]) : cub_motion_skeleton_find(sk, e->b);
        if (a->ib[j] < 0)
            return fail(diag, a->name, "joint '%s' (for %s) missing",
                        strcmp(e->b, "+") == 0 ? "a child of the head" : e->b,
                        cub_kinect_joint_name(j));
    }
    return CUB_OK;
}

/* The source points (no basis, no scale) of the pose in a->pose. */
static void source_points(synth_actor *a, cub_fv3 out[CUB_KJ_COUNT])
{
    cub_motion_forward(&a->m.skel, &a->pose, a->world, NULL);
    for (int j = 0; j < CUB_KJ_COUNT; j++) {
        const cub_vec3 *pa = &a->world[a->ia[j]];
        cub_fv3 p = cub_fv3_make(pa->x / 65536.0f, pa->y / 65536.0f, pa->z / 65536.0f);
        if (a->ib[j] >= 0) {
            const cub_vec3 *pb = &a->world[a->ib[j]];
            cub_fv3 q = cub_fv3_make(pb->x / 65536.0f, pb->y / 65536.0f, pb->z / 65536.0f);
            p = cub_fv3_lerp(p, q, a->frac[j]);
        }
        out[j] = p;
    }
}

/* The nearest file axis (+-x, +-y, +-z) to v. */
static cub_fv3 snap_axis(cub_fv3 v)
{
    float ax = fabsf(v.x), ay = fabsf(v.y), az = fabsf(v.z);
    if (ax >= ay && ax >= az) return cub_fv3_make(v.x > 0 ? 1.0f : -1.0f, 0, 0);
    if (ay >= az) return cub_fv3_make(0, v.y > 0 ? 1.0f : -1.0f, 0);
    return cub_fv3_make(0, 0, v.z > 0 ? 1.0f : -1.0f);
}

static float dist(cub_fv3 a, cub_fv3 b)
{
    return cub_fv3_len(cub_fv3_sub(a, b));
}

/* Axes and scale from the first frame: some files (Rokoko) have a rest
 * pose that is no human pose at all. Up is hips -> shoulders and left is
 * right hip -> left hip, each snapped to the nearest file axis. */
static cub_err set_frame(synth_actor *a, cub_diag *diag)
{
    cub_fv3 p[CUB_KJ_COUNT];
    cub_motion_sample(&a->m.clip, 0, CUB_MOTION_CLAMP, &a->pose);
    source_points(a, p);
    cub_fv3 up = snap_axis(cub_fv3_sub(p[CUB_KJ_SHOULDER_CENTRE], p[CUB_KJ_HIP_CENTRE]));
    cub_fv3 left = snap_axis(cub_fv3_sub(p[CUB_KJ_HIP_L], p[CUB_KJ_HIP_R]));
    if (fabsf(cub_fv3_dot(up, left)) > 0.5f)
        return fail(diag, a->name, "first frame has no clear up and left directions%s%s", "", "");
    a->basis[0] = left;
    a->basis[1] = up;
    a->basis[2] = cub_fv3_cross(left, up); /* forward, right-handed */
    /* Shoulder height when standing straight, from bone lengths (they do
     * not depend on the pose; CMU's rest legs splay 20 degrees) and the
     * first frame's small vertical offsets (hip joints, feet). */
    float leg = 0, drop = 0;
    for (int k = CUB_KJ_HIP_L; k <= CUB_KJ_HIP_R; k += CUB_KJ_HIP_R - CUB_KJ_HIP_L) {
        cub_fv3 heel, toe;
        synth_body_foot_ends(p[k + 2], p[k + 3], &heel, &toe);
        float sole = fminf(cub_fv3_dot(heel, up), cub_fv3_dot(toe, up));
        leg += 0.5f * (dist(p[k], p[k + 1]) + dist(p[k + 1], p[k + 2]));
        drop += 0.5f * (cub_fv3_dot(cub_fv3_sub(p[CUB_KJ_HIP_CENTRE], p[k]), up) +
                        fmaxf(0, cub_fv3_dot(p[k + 2], up) - sole));
    }
    float shoulder = dist(p[CUB_KJ_SHOULDER_CENTRE], p[CUB_KJ_HIP_CENTRE]) + leg + drop;
    if (!(shoulder > 1.0f))
        return fail(diag, a->name, "first frame: shoulders not above the feet%s%s", "", "");
    /* Everything above the shoulder centre is the child's own head (body.c). */
    synth_body_shape shape = {.height_mm = a->height_mm, .build = 1};
    float above = synth_body_above_shoulders_mm(&shape);
    float below = synth_body_sole_mm(&shape);
    a->scale = (a->height_mm - above - below) / shoulder;
    return CUB_OK;
}

cub_err synth_actor_load(const char *clip, const char *data_dir, float height_mm, synth_actor **out,
                         cub_diag *diag)
{
    synth_actor *a = calloc(1, sizeof(*a));
    if (!a) return CUB_ERR_NOMEM;
    snprintf(a->name, sizeof(a->name), "%s", clip);
    a->height_mm = height_mm;
    char path[600];
    if (!resolve(clip, data_dir, path, sizeof(path))) {
        free(a);
        return fail(diag, clip,
                    "no such clip (give a .bvh/.amc path, or a short name found under %s/mocap)%s",
                    data_dir ? data_dir : "(no data dir: set CUB_DATA_DIR or --data)", "");
    }
    cub_err err = load_motion(path, &a->m, diag);
    if (!err) err = map_joints(a, diag);
    if (!err) err = set_frame(a, diag);
    if (err) {
        synth_actor_free(a);
        return err;
    }
    *out = a;
    return CUB_OK;
}

void synth_actor_free(synth_actor *a)
{
    if (!a) return;
    cub_io_motion_free(&a->m);
    free(a);
}

double synth_actor_duration_s(const synth_actor *a)
{
    return (double)cub_motion_clip_duration_us(&a->m.clip) / 1e6;
}

void synth_actor_points(const synth_actor *a_const, double t_s, cub_fv3 out[SP_COUNT])
{
    synth_actor *a = (synth_actor *)a_const; /* scratch buffers only */
    cub_fv3 p[CUB_KJ_COUNT];
    cub_motion_sample(&a->m.clip, (int64_t)(t_s * 1e6), CUB_MOTION_CLAMP, &a->pose);
    source_points(a, p);
    for (int j = 0; j < CUB_KJ_COUNT; j++)
        out[j] = cub_fv3_scale(
            cub_fv3_make(cub_fv3_dot(p[j], a->basis[0]), cub_fv3_dot(p[j], a->basis[1]),
                         cub_fv3_dot(p[j], a->basis[2])),
            a->scale);
    synth_body_shape shape = {.height_mm = a->height_mm, .build = 1};
    synth_body_head(&shape, out[CUB_KJ_SHOULDER_CENTRE], out[CUB_KJ_HEAD], &out[CUB_KJ_HEAD],
                    &out[SP_HEAD_TOP]);
    /* Source hands range from a wrist marker to a fingertip: keep their
     * direction, give the child's palm centre a child's distance. */
    for (int w = CUB_KJ_WRIST_L; w <= CUB_KJ_WRIST_R; w += CUB_KJ_WRIST_R - CUB_KJ_WRIST_L) {
        cub_fv3 dir = cub_fv3_sub(out[w + 1], out[w]);
        if (cub_fv3_len(dir) < 1.0f) dir = cub_fv3_sub(out[w], out[w - 1]);
        cub_fv3 u = cub_fv3_norm(dir, cub_fv3_make(0, 1, 0));
        out[w + 1] = cub_fv3_add(out[w], cub_fv3_scale(u, synth_body_hand_mm(&shape)));
    }
}

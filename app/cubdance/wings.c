/* wings — see wings.h. Floats: the picture only, nothing decides on it. */
#include "wings.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define WINGS_OPEN_S 0.4f /* unfolding (or folding) takes this long */
#define WINGS_FPS 30.0
/* A folded chain's first bone points down the back: this much down, this
 * much back (a direction, normalised). */
#define FOLD_DOWN 0.5f
#define FOLD_BACK 0.85f
#define FOLD_DOUBLE_DEG 165.0f /* a further bone doubled back on its parent */

static void qmul(const float a[4], const float b[4], float out[4])
{
    float r[4] = {a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
                  a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
                  a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
                  a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2]};
    memcpy(out, r, sizeof r);
}

static void qrot(const float q[4], const float v[3], float out[3])
{
    float p[4] = {v[0], v[1], v[2], 0}, c[4] = {-q[0], -q[1], -q[2], q[3]}, t[4];
    qmul(q, p, t);
    qmul(t, c, p);
    memcpy(out, p, 3 * sizeof *out);
}

/* Rotation by deg about the unit axis. */
static void qaxis(const float axis[3], float deg, float out[4])
{
    float h = deg * 3.14159265f / 360.0f, s = sinf(h);
    out[0] = axis[0] * s, out[1] = axis[1] * s, out[2] = axis[2] * s, out[3] = cosf(h);
}

/* Normalised lerp along the shorter way: enough for a fold. */
static void qblend(const float a[4], const float b[4], float t, float out[4])
{
    float dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3], sb = dot < 0 ? -t : t;
    float n = 0;
    for (int k = 0; k < 4; k++)
        out[k] = (1 - t) * a[k] + sb * b[k], n += out[k] * out[k];
    n = n > 0 ? 1.0f / sqrtf(n) : 0;
    for (int k = 0; k < 4; k++)
        out[k] *= n;
}

static void offset_of(const cub_skeleton *s, int j, float v[3])
{
    v[0] = s->joints[j].offset_mm.x / 65536.0f;
    v[1] = s->joints[j].offset_mm.y / 65536.0f;
    v[2] = s->joints[j].offset_mm.z / 65536.0f;
}

/* The shortest rotation taking unit vector a to unit vector b (not opposite). */
static void qfromto(const float a[3], const float b[3], float q[4])
{
    float c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    float w = 1 + a[0] * b[0] + a[1] * b[1] + a[2] * b[2], n = w * w;
    for (int k = 0; k < 3; k++)
        n += c[k] * c[k];
    n = 1.0f / sqrtf(n);
    q[0] = c[0] * n, q[1] = c[1] * n, q[2] = c[2] * n, q[3] = w * n;
}

/* The folded rotation of optional joint j of ch: the first bone of a
 * chain laid down the back (so unfolding swings it out from behind the
 * body, never over the head), each further bone doubled back on the one
 * before (about the vertical). */
static void fold_of(const cub_character *ch, int j, float q[4])
{
    const cub_skeleton *s = &ch->skel;
    int c = j + 1;
    while (c < s->joint_count && s->joints[c].parent != j)
        c++;
    float bone[3] = {1, 0, 0}, up[3] = {0, 1, 0};
    if (c < s->joint_count) offset_of(s, c, bone);
    float n = sqrtf(bone[0] * bone[0] + bone[1] * bone[1] + bone[2] * bone[2]);
    for (int k = 0; k < 3; k++)
        bone[k] = n > 0 ? bone[k] / n : k == 0;
    float side = bone[0] >= 0 ? 1.0f : -1.0f;
    float back[3] = {0.15f * side, -FOLD_DOWN, -FOLD_BACK};
    float bn = sqrtf(back[0] * back[0] + back[1] * back[1] + back[2] * back[2]);
    for (int k = 0; k < 3; k++)
        back[k] /= bn;
    if (!ch->optional[s->joints[j].parent]) qfromto(bone, back, q);
    else qaxis(up, side * FOLD_DOUBLE_DEG, q);
}

static int load(cub_wings *w, const char *xml, const char *bvh, char *err, size_t err_size)
{
    cub_diag d = {0};
    char buf[600];
    if (!cub_character_load(xml, &w->ch, &d) && !cub_io_load_bvh(bvh, NULL, &w->motion, &d))
        return 0;
    snprintf(err, err_size, "wings: %s", cub_diag_str(&d, buf, sizeof buf));
    return 1;
}

/* The optional joints after the library's, under parents it has. */
static int bind(cub_wings *w, const cub_skeleton *lib_skel, char *err, size_t err_size)
{
    const cub_skeleton *cs = &w->ch.skel;
    w->skel = *lib_skel;
    for (int j = 0; j < cs->joint_count; j++) {
        if (!w->ch.optional[j]) continue;
        const cub_joint *jt = &cs->joints[j];
        int p = cub_motion_skeleton_find(&w->skel, cs->joints[jt->parent].name), at = 0;
        w->src[w->extra] = cub_motion_skeleton_find(&w->motion.skel, jt->name);
        if (p < 0 || w->src[w->extra] < 0 ||
            cub_motion_skeleton_add(&w->skel, jt->name, p, jt->offset_mm, &at)) {
            snprintf(err, err_size, "wings: %s: joint '%s' has no place on the coach", w->ch.name,
                     jt->name);
            return 1;
        }
        w->skel.joints[at].is_end_site = jt->is_end_site;
        fold_of(&w->ch, j, w->fold[w->extra++]);
    }
    return 0;
}

int cub_wings_open(cub_wings *w, const char *character_path, const char *clip_name,
                   const cub_skeleton *lib_skel, int clip, char *err, size_t err_size)
{
    char xml[512], bvh[512];
    memset(w, 0, sizeof *w);
    w->move_clip = -1;
    const char *dot = strrchr(character_path, '.'), *slash = strrchr(character_path, '/');
    int stem = dot && (!slash || dot > slash) ? (int)(dot - character_path) : (int)strlen(character_path);
    int dir = slash ? (int)(slash - character_path + 1) : 0;
    snprintf(xml, sizeof xml, "%.*s_winged.xml", stem, character_path);
    snprintf(bvh, sizeof bvh, "%.*s%s.wings.bvh", dir, character_path, clip_name);
    FILE *f = fopen(xml, "r");
    if (!f || clip < 0) {
        if (f) fclose(f);
        return 0;
    }
    fclose(f);
    w->clip = clip;
    if (load(w, xml, bvh, err, err_size) || bind(w, lib_skel, err, err_size)) {
        cub_wings_close(w);
        return 1;
    }
    w->loaded = 1;
    return 0;
}

void cub_wings_close(cub_wings *w)
{
    cub_io_motion_free(&w->motion);
    w->loaded = 0;
}

void cub_wings_move(cub_wings *w, int move_clip)
{
    w->move_clip = move_clip;
}

/* Open or close a step toward whether clip (or the coach's move) is the
 * winged one; the frame follows the player in the winged clip, the clock
 * outside it (the wings beat on through a correction). */
static void step(cub_wings *w, int clip, int64_t pos_q16, int64_t t_us)
{
    float dt = w->last_us && t_us > w->last_us ? (float)(t_us - w->last_us) * 1e-6f : 0;
    w->last_us = t_us;
    int playing = clip == w->clip, in = playing || w->move_clip == w->clip;
    w->open += (in ? dt : -dt) / WINGS_OPEN_S;
    w->open = w->open < 0 ? 0 : w->open > 1 ? 1 : w->open;
    w->frame = playing ? pos_q16 / 65536.0 : w->frame + dt * WINGS_FPS;
}

/* World rotation and position of every optional joint at w->frame. */
static void hang(cub_wings *w)
{
    static cub_pose pose;
    int64_t t_us = (int64_t)(w->frame * 1e6 / WINGS_FPS);
    cub_motion_sample(&w->motion.clip, t_us, CUB_MOTION_LOOP, &pose);
    float t = w->open * w->open * (3 - 2 * w->open); /* smoothstep */
    int n = w->skel.joint_count - w->extra;
    for (int e = 0; e < w->extra; e++) {
        int j = n + e, p = w->skel.joints[j].parent;
        cub_quat fq = pose.rot[w->src[e]];
        const float one = (float)CUB_QUAT_ONE;
        float flap[4] = {fq.x / one, fq.y / one, fq.z / one, fq.w / one}, local[4], off[3];
        qblend(w->fold[e], flap, t, local);
        qmul(w->rot + 4 * p, local, w->rot + 4 * j);
        offset_of(&w->skel, j, off);
        qrot(w->rot + 4 * p, off, w->xyz + 3 * j);
        for (int k = 0; k < 3; k++)
            w->xyz[3 * j + k] += w->xyz[3 * p + k];
    }
}

int cub_wings_pose(cub_wings *w, int clip, int64_t pos_q16, int64_t t_us, const float *xyz,
                   const float *rot)
{
    if (!w->loaded) return 0;
    step(w, clip, pos_q16, t_us);
    if (w->open <= 0) return 0;
    int n = w->skel.joint_count - w->extra;
    memcpy(w->xyz, xyz, 3 * (size_t)n * sizeof *xyz);
    memcpy(w->rot, rot, 4 * (size_t)n * sizeof *rot);
    hang(w);
    return 1;
}

const float *cub_wings_icon(cub_wings *w, const float *icon)
{
    if (!icon) return NULL;
    int n = w->skel.joint_count - w->extra;
    memcpy(w->icon, icon, 3 * (size_t)n * sizeof *icon);
    for (int j = n; j < w->skel.joint_count; j++)
        memcpy(w->icon + 3 * j, w->icon + 3 * w->skel.joints[j].parent, 3 * sizeof *icon);
    return w->icon;
}

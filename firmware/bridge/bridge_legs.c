/* bridge: the player's leg phase — the inertial blend without sliding feet
 * (seed 002 § 5.1 (2), as app/join does it offline; docs/join.md). While
 * the offset fades, a foot that stands on both sides of the cut stays where
 * it stood, held by a two-bone leg IK, and the legs go over to the new
 * clip one at a time while the other stays planted. Fixed point. */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "bridge_internal.h"

/* app/join's contact rule (cub_join_contacts): a foot's lowest point within
 * this of the clip's floor (its lowest foot point), slower than this, in
 * runs of at least this many frames. */
#define CONTACT_HEIGHT_MM CUB_Q16_INT(30)
#define CONTACT_SPEED_MM_S 180
#define CONTACT_MIN_FRAMES 3
/* app/join's step: a foot with farther than STEP_MM to go is lifted by
 * half its travel, within [LIFT_MIN_MM, LIFT_MAX_MM], clearing the contact
 * height. */
#define STEP_MM CUB_Q16_INT(20)
#define LIFT_MIN_MM CUB_Q16_INT(50)
#define LIFT_MAX_MM CUB_Q16_INT(80)
/* Bit of a clip's first contact byte: its last frame runs into its first
 * (both ankles within STEP_MM), so its loop's wrap is no cut for the legs. */
#define SEAMLESS_BIT 4u

/* ---- the legs and the contacts ------------------------------------------ */

static int is_child(const cub_skeleton *sk, int j, int parent)
{
    return j >= 0 && j < sk->joint_count && parent >= 0 && sk->joints[j].parent == parent;
}

/* The ankle and what hangs below it (toes, end sites), in joint order. */
static void find_foot(const cub_skeleton *sk, int ankle, int16_t *out)
{
    int n = 0;
    for (int k = 0; k < CUB_BRIDGE_FOOT_JOINTS; k++)
        out[k] = -1;
    for (int k = ankle; k < sk->joint_count && n < CUB_BRIDGE_FOOT_JOINTS; k++) {
        int a = k;
        while (a > ankle)
            a = sk->joints[a].parent;
        if (a == ankle) out[n++] = (int16_t)k;
    }
}

static cub_vec3 foot_low(const cub_bridge_legs *l, const cub_vec3 *world, int s)
{
    cub_vec3 low = world[l->foot[s][0]];
    for (int k = 1; k < CUB_BRIDGE_FOOT_JOINTS && l->foot[s][k] >= 0; k++)
        if (world[l->foot[s][k]].y < low.y) low = world[l->foot[s][k]];
    return low;
}

/* Both feet's lowest points at frame f of clip. */
static void lows_at(cub_bridge_legs *l, const cub_clip *clip, int f, cub_vec3 out[2])
{
    cub_motion_clip_get_frame(clip, f, &l->raw);
    cub_motion_forward(clip->skel, &l->raw, l->world[0], NULL);
    out[0] = foot_low(l, l->world[0], 0);
    out[1] = foot_low(l, l->world[0], 1);
}

/* A run of standing frames shorter than the rule's is a foot passing low. */
static void drop_short_runs(uint8_t *bits, int n, int s)
{
    uint8_t m = (uint8_t)(1u << s);
    for (int f = 0; f < n;) {
        int e = f;
        while (e < n && (bits[e] & m) == (bits[f] & m))
            e++;
        if ((bits[f] & m) && e - f < CONTACT_MIN_FRAMES)
            for (int k = f; k < e; k++)
                bits[k] &= (uint8_t)~m;
        f = e;
    }
}

/* moved (Q16 mm) over frames frames of frame_ns each is slower than the
 * contact speed, in integers. */
static int slow(int64_t moved_q16, int frames, uint32_t frame_ns)
{
    return moved_q16 * 1000000000 <
           (int64_t)CONTACT_SPEED_MM_S * 65536 * frames * (int64_t)frame_ns;
}

/* The clip's last frame puts both ankles within STEP_MM of where its first
 * does: played in a loop, the feet go on without a step. */
static int runs_on_seamlessly(cub_bridge_legs *l, const cub_clip *clip)
{
    cub_vec3 low[2], last[2];
    lows_at(l, clip, clip->frame_count - 1, low);
    last[0] = l->world[0][l->ankle[0]], last[1] = l->world[0][l->ankle[1]];
    lows_at(l, clip, 0, low);
    for (int s = 0; s < 2; s++)
        if (cub_fx_vec3_length(cub_fx_vec3_sub(last[s], l->world[0][l->ankle[s]])) > STEP_MM)
            return 0;
    return 1;
}

/* Contacts of one clip: low (over the clip's floor) and slow (central
 * difference), then runs. Returns the floor. */
static cub_q16 clip_contacts(cub_bridge_legs *l, const cub_clip *clip, uint8_t *bits)
{
    int n = clip->frame_count;
    cub_vec3 low[3][2];
    cub_q16 floor = CUB_Q16_MAX;
    for (int f = 0; f < n; f++) {
        lows_at(l, clip, f, low[0]);
        for (int s = 0; s < 2; s++)
            if (low[0][s].y < floor) floor = low[0][s].y;
    }
    for (int f = 0; f < n; f++) {
        int a = f > 0 ? f - 1 : f, b = f + 1 < n ? f + 1 : f;
        lows_at(l, clip, a, low[0]);
        lows_at(l, clip, f, low[1]);
        lows_at(l, clip, b, low[2]);
        bits[f] = 0;
        for (int s = 0; s < 2; s++) {
            int64_t moved = cub_fx_vec3_length(cub_fx_vec3_sub(low[2][s], low[0][s]));
            int still = b == a || slow(moved, b - a, clip->frame_ns);
            int low_enough = (int64_t)low[1][s].y - floor < CONTACT_HEIGHT_MM;
            bits[f] |= (uint8_t)((still && low_enough) << s);
        }
    }
    drop_short_runs(bits, n, 0);
    drop_short_runs(bits, n, 1);
    if (runs_on_seamlessly(l, clip)) bits[0] |= SEAMLESS_BIT;
    return floor;
}

size_t cub_bridge_legs_mem_size(const cub_bridge_table *t)
{
    if (!t) return 0;
    return (size_t)t->desc.clip_count * sizeof(cub_q16) + (size_t)t->desc.frame_total + 4;
}

void cub_bridge_legs_init(cub_bridge_legs *l, const cub_bridge_table *t, void *mem)
{
    const cub_skeleton *sk = t->desc.skel;
    const cub_fuzzy_body *b = &t->desc.body;
    cub_q16 *floor = (cub_q16 *)(((uintptr_t)mem + 3) & ~(uintptr_t)3);
    uint8_t *bits = (uint8_t *)(floor + t->desc.clip_count);
    memset(floor, 0, sizeof(cub_q16) * (size_t)t->desc.clip_count);
    memset(bits, 0, (size_t)t->desc.frame_total);
    l->floor_mm = floor;
    l->contact = bits;
    l->ok = 0;
    for (int s = 0; s < 2; s++) {
        if (!is_child(sk, b->knee[s], b->hip[s]) || !is_child(sk, b->ankle[s], b->knee[s]))
            return; /* no two-bone legs: no leg phase */
        l->hip[s] = b->hip[s], l->knee[s] = b->knee[s], l->ankle[s] = b->ankle[s];
        find_foot(sk, b->ankle[s], l->foot[s]);
    }
    l->ok = 1;
    for (int c = 0; c < t->desc.clip_count; c++)
        floor[c] = clip_contacts(l, &t->clips[c].clip, bits + t->clips[c].first_frame);
}

/* ---- the two-bone IK ----------------------------------------------------- */

/* v / |v| (Q16 unit), or fallback for a zero vector. */
static cub_vec3 unit(cub_vec3 v, cub_vec3 fallback)
{
    int64_t len = cub_fx_vec3_length(v);
    if (len == 0) return fallback;
    return (cub_vec3){(cub_q16)((int64_t)v.x * 65536 / len), (cub_q16)((int64_t)v.y * 65536 / len),
                      (cub_q16)((int64_t)v.z * 65536 / len)};
}

/* The shortest rotation taking direction a onto direction b: (1 + a.b,
 * a x b) normalised, for unit a and b (Q32 products, shifted into Q2.29). */
static cub_quat arc(cub_vec3 a, cub_vec3 b)
{
    cub_vec3 ua = unit(a, (cub_vec3){0, CUB_Q16_ONE, 0}), ub = unit(b, ua);
    int64_t dot = (int64_t)ua.x * ub.x + (int64_t)ua.y * ub.y + (int64_t)ua.z * ub.z;
    int64_t cx = (int64_t)ua.y * ub.z - (int64_t)ua.z * ub.y;
    int64_t cy = (int64_t)ua.z * ub.x - (int64_t)ua.x * ub.z;
    int64_t cz = (int64_t)ua.x * ub.y - (int64_t)ua.y * ub.x;
    cub_quat q = {(int32_t)((((int64_t)1 << 32) + dot) >> 3), (int32_t)(cx >> 3),
                  (int32_t)(cy >> 3), (int32_t)(cz >> 3)};
    return cub_fx_quat_normalize(q);
}

typedef struct goal {
    cub_vec3 ankle_mm; /* where the ankle goes (world) */
    cub_quat foot;     /* the ankle's world rotation there */
    cub_vec3 forward;  /* the body's forward (unit): a straight knee bends toward it */
} goal;

/* The knee's bend direction, across the hip-to-ankle line u: where it
 * bends now; a nearly straight leg (less than a tenth of the thigh off the
 * line) leans toward the body's forward, so the plane does not come from
 * noise. Continuous in the bend, and no change for a bent leg: with the
 * goal where the leg already is, the IK gives the leg back. */
static cub_vec3 bend_dir(cub_vec3 hk, cub_vec3 u, cub_vec3 forward, cub_q16 l1)
{
    cub_vec3 b = cub_fx_vec3_sub(hk, cub_fx_vec3_scale(u, cub_fx_vec3_dot(hk, u)));
    cub_q16 off = cub_fx_vec3_length(b), want = l1 / 10;
    if (off < want) {
        cub_vec3 f = cub_fx_vec3_sub(forward, cub_fx_vec3_scale(u, cub_fx_vec3_dot(forward, u)));
        cub_vec3 fu = unit(f, (cub_vec3){0, 0, CUB_Q16_ONE});
        b = cub_fx_vec3_add(b, cub_fx_vec3_scale(fu, want - off));
    }
    return unit(b, (cub_vec3){0, 0, CUB_Q16_ONE});
}

/* Leg s of pose onto g: new local rotations of its hip, knee and ankle (the
 * law of cosines in the bend plane; the ankle as near as the leg reaches).
 * world, wrot: the pose's world positions and rotations now. */
static void leg_ik(const cub_bridge_legs *l, int s, const cub_skeleton *sk, const cub_vec3 *world,
                   const cub_quat *wrot, const goal *g, cub_pose *pose)
{
    int hj = l->hip[s], kj = l->knee[s], aj = l->ankle[s];
    cub_vec3 H = world[hj], K = world[kj], A = world[aj];
    cub_vec3 hk = cub_fx_vec3_sub(K, H);
    int64_t l1 = cub_fx_vec3_length(hk), l2 = cub_fx_vec3_length(cub_fx_vec3_sub(A, K));
    cub_vec3 ht = cub_fx_vec3_sub(g->ankle_mm, H);
    int64_t d = cub_fx_vec3_length(ht);
    cub_vec3 u = unit(ht, (cub_vec3){0, -CUB_Q16_ONE, 0});
    int64_t dmin = (l1 > l2 ? l1 - l2 : l2 - l1) + 66, dmax = (l1 + l2) * 65529 / 65536;
    d = d < dmin ? dmin : d > dmax ? dmax : d;
    if (l1 == 0 || d == 0) return;
    cub_vec3 b = bend_dir(hk, u, g->forward, (cub_q16)l1);
    /* cos of the hip's angle: (l1^2 + d^2 - l2^2) / (2 l1 d), Q16 */
    int64_t num = l1 * l1 + d * d - l2 * l2, den = (2 * l1 * d) >> 16;
    int64_t ca = den ? num / den : 0;
    ca = ca < -CUB_Q16_ONE ? -CUB_Q16_ONE : ca > CUB_Q16_ONE ? CUB_Q16_ONE : ca;
    cub_q16 sa = cub_fx_sqrt(CUB_Q16_ONE - cub_fx_mul((cub_q16)ca, (cub_q16)ca));
    cub_vec3 along = cub_fx_vec3_scale(u, cub_fx_mul((cub_q16)l1, (cub_q16)ca));
    cub_vec3 across = cub_fx_vec3_scale(b, cub_fx_mul((cub_q16)l1, sa));
    cub_vec3 K2 = cub_fx_vec3_add(H, cub_fx_vec3_add(along, across));
    cub_vec3 A2 = cub_fx_vec3_add(H, cub_fx_vec3_scale(u, (cub_q16)d));
    cub_quat wu = cub_fx_quat_mul(arc(hk, cub_fx_vec3_sub(K2, H)), wrot[hj]);
    cub_quat wl = cub_fx_quat_mul(wu, pose->rot[kj]);
    cub_vec3 off = pose->has_trans ? pose->trans_mm[aj] : sk->joints[aj].offset_mm;
    wl = cub_fx_quat_mul(arc(cub_fx_quat_rotate(wl, off), cub_fx_vec3_sub(A2, K2)), wl);
    int hp = sk->joints[hj].parent;
    cub_quat parent = hp >= 0 ? wrot[hp] : cub_fx_quat_identity();
    pose->rot[hj] = cub_fx_quat_normalize(cub_fx_quat_mul(cub_fx_quat_conj(parent), wu));
    pose->rot[kj] = cub_fx_quat_normalize(cub_fx_quat_mul(cub_fx_quat_conj(wu), wl));
    pose->rot[aj] = cub_fx_quat_normalize(cub_fx_quat_mul(cub_fx_quat_conj(wl), g->foot));
}

/* ---- the phase ------------------------------------------------------------ */

static int stands(const cub_bridge_legs *l, const cub_bridge_table *t, int clip, int frame, int s)
{
    const cub_bridge_clip *c = &t->clips[clip];
    int f = frame < 0 ? 0 : frame >= c->clip.frame_count ? c->clip.frame_count - 1 : frame;
    return (l->contact[c->first_frame + f] >> s) & 1;
}

/* Foot s stands on the shown side of the cut: low on the screen (within
 * the contact height of the playing clip's floor). Outside a blend that is
 * where the clip's standing feet are; a cut during a blend shows what the
 * offset and the legs make of the clip: a foot low there, moving or not,
 * would slide if the offset carried it, and a foot the clip stands on but
 * a running step has lifted is in the air (held there, it would hang). */
static int stands_shown(cub_bridge_legs *l, const cub_bridge_cut *c, int s)
{
    cub_vec3 now = foot_low(l, l->world[0], s);
    return (int64_t)now.y - l->floor_mm[c->src_clip] < CONTACT_HEIGHT_MM;
}

static int seamless(const cub_bridge_legs *l, const cub_bridge_table *t, int clip)
{
    return (l->contact[t->clips[clip].first_frame] & SEAMLESS_BIT) != 0;
}

/* How high a step lifts a foot that travels travel_mm. */
static cub_q16 lift_mm(cub_q16 travel_mm)
{
    cub_q16 half = travel_mm / 2;
    return half < LIFT_MIN_MM ? LIFT_MIN_MM : half > LIFT_MAX_MM ? LIFT_MAX_MM : half;
}

static cub_q16 horizontal_mm(cub_vec3 a, cub_vec3 b)
{
    return cub_fx_vec3_length((cub_vec3){a.x - b.x, 0, a.z - b.z});
}

/* Frames a leg gets for a step of far_mm. The step moves in 0.4 of its
 * phase, smoothstep (slope 1.5): 3.75 x far / len a frame at most; its
 * lift rises and falls as sin^2(pi u): pi x lift / len a frame at most.
 * Both within speed_mm. */
static int leg_frames(const cub_bridge_legs *l, cub_q16 far_mm)
{
    int64_t n = ((int64_t)far_mm * 15 / 4 + l->speed_mm - 1) / l->speed_mm;
    int64_t up = far_mm > STEP_MM ? lift_mm(far_mm) : 0;
    int64_t n_up = (up * CUB_Q16_PI / CUB_Q16_ONE + l->speed_mm - 1) / l->speed_mm;
    n = n < n_up ? n_up : n;
    n = n < l->min_frames ? l->min_frames : n;
    return n > CUB_BRIDGE_MAX_BLEND_FRAMES ? CUB_BRIDGE_MAX_BLEND_FRAMES : (int)n;
}

void cub_bridge_legs_begin(cub_bridge_legs *l, const cub_bridge_table *t, const cub_bridge_cut *c)
{
    const cub_skeleton *sk = t->desc.skel;
    /* The clip runs on into its own first frame: no cut for the feet; a
     * phase running goes on (its goals are the raw frames, continuous). */
    if (c->wrap && seamless(l, t, c->to_clip)) return;
    l->on = 0;
    l->planted = 0;
    if (!l->ok || !l->enabled) return;
    int lands = 0;
    cub_motion_forward(sk, c->src, l->world[0], l->wrot[0]);
    for (int s = 0; s < 2; s++) {
        for (int k = 0; k < l->min_frames; k++)
            lands |= stands(l, t, c->to_clip, c->to_frame + k, s);
        if (stands_shown(l, c, s)) l->planted |= (uint8_t)(1u << s);
    }
    /* No foot on the floor on either side, nor soon in the new clip (a
     * jump into a jump): the offset alone. */
    if (!lands && !l->planted) return;
    cub_motion_forward(sk, c->dst, l->world[1], NULL);
    cub_q16 travel[2];
    for (int s = 0; s < 2; s++) {
        l->hold_mm[s] = l->world[0][l->ankle[s]];
        l->hold_rot[s] = l->wrot[0][l->ankle[s]];
        travel[s] = horizontal_mm(l->world[0][l->ankle[s]], l->world[1][l->ankle[s]]);
    }
    /* The free leg first; with both planted or neither, the one with
     * farther to go. */
    int one = l->planted == 1 || l->planted == 2;
    l->first = one ? (l->planted & 1) : travel[1] > travel[0];
    l->len = leg_frames(l, travel[0] > travel[1] ? travel[0] : travel[1]);
    /* A loop whose pass is shorter than its phase (a clip that travels,
     * played in place) would never end one: each wrap's phase ends the
     * shortest blend before the next, its steps faster for it. A switch's
     * phase may run into the first wrap, which starts one from what is
     * shown (a foot a step has lifted is free there). */
    int legs = l->planted ? 2 : 1, room = c->pass_frames - l->min_frames;
    if (c->wrap && legs * l->len > room) {
        int fit = room / legs;
        l->len = fit > l->min_frames ? fit : l->min_frames;
    }
    l->from_q16 = c->from_q16;
    l->on = 1;
}

int64_t cub_bridge_legs_left_q16(const cub_bridge_legs *l, int64_t pos_q16)
{
    if (!l->on) return 0;
    int64_t left = ((int64_t)(l->planted ? 2 : 1) * l->len << 16) - (pos_q16 - l->from_q16);
    return left > 0 ? left : 0;
}

/* smoothstep of x (Q16), clamped to [0, 1]. */
static cub_q16 ease(int64_t x)
{
    if (x <= 0) return 0;
    if (x >= CUB_Q16_ONE) return CUB_Q16_ONE;
    cub_q16 s2 = cub_fx_mul((cub_q16)x, (cub_q16)x);
    return 3 * s2 - 2 * cub_fx_mul(s2, (cub_q16)x);
}

/* Leg s at its phase u (Q16, clamped to [0, 1]): to raw's ankle, lifted
 * by sin^2(pi u) when it has far to go (it leaves and meets the floor at
 * rest): a step, set down where it arrives.
 * A held foot leaves where it stood and goes over only in the middle of
 * its phase (u in [0.3, 0.7]): it is off the floor before it moves. A free
 * foot (off the floor at the cut) leaves where the offset puts it now and goes over
 * in the first half (ease(2u)): it is over its spot before it comes down,
 * instead of landing where the fading offset would slide it. */
static goal leg_goal(const cub_bridge_legs *l, int s, int64_t u)
{
    u = u < 0 ? 0 : u > CUB_Q16_ONE ? CUB_Q16_ONE : u;
    int aj = l->ankle[s];
    int held = (l->planted >> s) & 1;
    cub_vec3 a = held ? l->hold_mm[s] : l->world[0][aj], b = l->world[1][aj];
    cub_quat ar = held ? l->hold_rot[s] : l->wrot[0][aj];
    /* held: over u in [0.3, 0.7], where sin^2 lifts it above half its lift */
    cub_q16 w = ease(held ? (u - CUB_Q16_ONE * 3 / 10) * 5 / 2 : 2 * u);
    goal g;
    g.ankle_mm = cub_fx_vec3_lerp(a, b, w);
    cub_q16 travel = horizontal_mm(a, b);
    if (travel > STEP_MM) {
        cub_q16 sn = cub_fx_sin(cub_fx_mul((cub_q16)u, CUB_Q16_PI));
        g.ankle_mm.y += cub_fx_mul(lift_mm(travel), cub_fx_mul(sn, sn));
    }
    g.foot = cub_fx_quat_slerp(ar, l->wrot[1][aj], w);
    return g;
}

void cub_bridge_legs_apply(cub_bridge_legs *l, const cub_skeleton *sk, const cub_pose *raw,
                           int64_t pos_q16, cub_pose *out)
{
    if (!l->on) return;
    int64_t progress_q16 = pos_q16 - l->from_q16;
    /* world[0]: the pose with the offset on; world[1]: the new clip's own */
    cub_motion_forward(sk, out, l->world[0], l->wrot[0]);
    cub_motion_forward(sk, raw, l->world[1], l->wrot[1]);
    cub_vec3 forward = unit(cub_fx_quat_rotate(l->wrot[0][0], (cub_vec3){0, 0, CUB_Q16_ONE}),
                            (cub_vec3){0, 0, CUB_Q16_ONE});
    for (int i = 0; i < 2; i++) {
        int s = i ? 1 - l->first : l->first;
        /* One at a time while a foot is held; both at once when none is. */
        int64_t start = l->planted ? (int64_t)i * l->len << 16 : 0;
        int64_t u = (progress_q16 - start) / l->len;
        goal g = leg_goal(l, s, u);
        g.forward = forward;
        /* One leg's IK moves only that leg: the other's world stays valid. */
        leg_ik(l, s, sk, l->world[0], l->wrot[0], &g, out);
    }
}

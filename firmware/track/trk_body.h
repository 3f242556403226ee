/* The body model shared by the fitting stages (trk_head.c, trk_fit.c):
 * proportions in 1/1000 of stature (the synthetic child's skeleton of
 * cub/synth.h, measured on its truth for CMU clip 13_29, the tuning clip)
 * and small geometry helpers on grid cells and mm points. */
#ifndef CUB_TRK_BODY_H
#define CUB_TRK_BODY_H

#include "trk_internal.h"

/* Which side of the image the player's left lands on: -1 as the Kinect
 * mirrors its images (cub/synth.h): a player facing the camera shows the
 * left hand at smaller camera x. */
#define TRK_LEFT_SIGN (-1)

/* proportions, per mille of stature */
enum {
    P_HEAD_DOWN = 85,      /* head top to head centre along the face */
    P_NECK_DOWN = 200,     /* head top to shoulder centre */
    P_NECK_DOWN_MIN = 180, /* the shoulder centre joint no nearer the head top (the renders: 175-220) */
    P_NECK_DOWN_MAX = 220, /* nor farther */
    P_WIDEN = 150,         /* head top to where the silhouette widens (neck base) */
    P_BELOW_NECK = 40,     /* neck base to shoulder centre */
    P_SPINE = 120,         /* shoulder centre to spine */
    P_HIPC = 165,          /* shoulder centre to the pelvis' middle (the limbs' reference) */
    P_HIPC_JOINT = 215,    /* shoulder centre to the hip centre joint */
    P_SHOULDER_HALF = 100, /* half the shoulder width, when not measured */
    P_SHOULDER_MIN = 45,   /* the narrowest measured half width believed (Bandai's joints: 57) */
    P_SHOULDER_MAX = 140,  /* the widest */
    P_SHOULDER_RUN = 15,   /* shoulder centre to the row the joints' width is measured on */
    R_SHOULDER_EDGE = 33,  /* shoulder joint to the silhouette's edge at its height (round top) */
    P_ARM_ROOT_RUN = 50,   /* shoulder centre to the row the arms' roots are measured on */
    P_ARM_ROOT_MIN = 75,   /* the narrowest arms' roots believed */
    R_ARM_ROOT_EDGE = 15,  /* arm's root to the silhouette's edge there (the deltoid) */
    P_HIP_HALF = 47,       /* centre to a hip joint across the body (the renders: Bandai narrower, CMU 56) */
    P_HIP_DROP = 70,
    P_UPPER_ARM = 190,
    P_FOREARM = 130,
    P_HAND_REACH = 80, /* the hand's surface around the fingertip */
    P_WRIST_IN = 75,
    P_THIGH = 267,
    P_SHIN = 285,
    P_ANKLE_UP = 80,
    P_FOOT_UP = 40,
    R_HEAD = 55, /* surface to joint: the part's radius */
    R_TORSO = 60,
    R_HIP = 50,            /* the thigh's top */
    R_SHOULDER = 75,       /* the arms' root: surface to the shoulder's middle */
    R_SHOULDER_JOINT = 40, /* surface to the skeletons' shoulder joint */
    R_LIMB = 25,
};

static inline int32_t pm(int32_t stature, int32_t per_mille) { return stature * per_mille / 1000; }

/* A part's radius: proportional, but a grown-up's chest is not deeper than
 * what the joint conventions put inside the surface. */
static inline int32_t radius(int32_t stature, int32_t per_mille)
{
    int32_t r = pm(stature, per_mille);
    return r > 75 ? 75 : r;
}

static inline trk_p3 cell_p(const cub_tracker *t, int32_t i) { return (trk_p3){t->x[i], t->y[i], t->z[i]}; }

/* The grid cell p (mm, camera space, p.z > 0) projects to; may lie off the grid. */
static inline void grid_of(trk_p3 p, int32_t *gx, int32_t *gy)
{
    *gx = (CUB_KINECT_CX + p.x * CUB_KINECT_FOCAL_PX / p.z) / TRK_CELL_PX;
    *gy = (CUB_KINECT_CY - p.y * CUB_KINECT_FOCAL_PX / p.z) / TRK_CELL_PX;
}

static inline int32_t dist3(trk_p3 a, trk_p3 b) { return trk_len(a.x - b.x, a.y - b.y, a.z - b.z); }

static inline trk_p3 add_s(trk_p3 a, cub_vec3 dir_q16, int32_t mm)
{
    return (trk_p3){a.x + (int32_t)(((int64_t)dir_q16.x * mm) >> 16), a.y + (int32_t)(((int64_t)dir_q16.y * mm) >> 16),
                    a.z + (int32_t)(((int64_t)dir_q16.z * mm) >> 16)};
}

/* Surface point to the part's axis: back along the camera's ray. */
static inline trk_p3 inside(trk_p3 p, int32_t r_mm) { return (trk_p3){p.x, p.y, p.z + r_mm}; }

/* The cell on the path from tip toward the root where the straight-line
 * distance from the tip first reaches mm (the root if never). */
static inline int32_t path_at(const cub_tracker *t, int32_t tip, int32_t mm)
{
    trk_p3 p0 = cell_p(t, tip);
    int32_t i = tip;
    while (t->parent0[i] >= 0 && dist3(p0, cell_p(t, i)) < mm) i = t->parent0[i];
    return i;
}

/* The cell on the tip's path to the root that is base_mm of surface from
 * the root (the root if never). Where a limb joins the torso: an arm's
 * path enters through the shoulder, a leg's through the hip, whatever the
 * limb's pose (a leg kicked up to the side is still a leg). */
static inline int32_t path_base(const cub_tracker *t, int32_t tip, int32_t base_mm)
{
    int32_t i = tip;
    for (int32_t steps = 0; t->parent0[i] >= 0 && t->dist0[i] > base_mm && steps < TRK_PATH_STEPS; steps++)
        i = t->parent0[i];
    return i;
}

static inline void put(cub_track_skeleton *s, int j, trk_p3 p, cub_q16 conf)
{
    s->joint_mm[j] = (cub_vec3){p.x * 65536, p.y * 65536, p.z * 65536};
    s->confidence[j] = conf;
}

static inline trk_p3 got(const cub_track_skeleton *s, int j)
{
    return (trk_p3){s->joint_mm[j].x >> 16, s->joint_mm[j].y >> 16, s->joint_mm[j].z >> 16};
}

/* The arm's stretched length (shoulder to wrist) as learnt, the
 * proportions' before it is. */
static inline int32_t arm_reach_mm(const cub_tracker *t, int side, int32_t st)
{
    return t->reach_mm[side] ? t->reach_mm[side] : pm(st, P_UPPER_ARM + P_FOREARM);
}

/* The body's frame in this frame: where the torso is and how it stands,
 * computed once (trk_fit.c) after the head and stature, and read by every
 * later step instead of each taking the same values one by one. */
typedef struct trk_frame {
    const cub_tracker *t; /* the grid, the paths from the root, the state */
    int32_t root;         /* the root cell: the torso's thickest */
    int32_t st;           /* stature (mm), as learnt */
    int32_t head;         /* the head's index among the extremities, -1 none */
    trk_p3 head_c;        /* the head joint (its centre) */
    trk_p3 sc;            /* the shoulder centre from the neck base (the torso and the arms' roots hang from it) */
    trk_p3 sj;            /* the shoulder centre joint: its drop held to the proportions' range */
    trk_p3 hc;            /* the pelvis' middle, on the axis (the limbs' reference) */
    cub_vec3 axis;        /* up the torso, hc to sc (unit, Q16.16); up when there is no head */
    cub_vec3 lat;         /* across the torso, toward +x (the image's right) */
    cub_vec3 lft;         /* across the torso, toward the player's left */
    cub_vec3 down;        /* down the torso in the image's plane (the axis's tilt in depth mostly taken out) */
    trk_p3 arm_root[2];   /* the arms' roots (0 = left), from sc: what names the hands */
    trk_p3 fit_root[2];   /* the same level with the shoulder joints (sj): what the elbows hang from */
    int32_t joint_half;   /* the output shoulder joints' half width (mm, learnt per player) */
    int32_t reach_mm;     /* shoulder to fingertip with slack: an extremity farther is no hand */
    bool on_floor;        /* the body stands on the floor */
} trk_frame;

/* Which limb an extremity (not the head) ends. */
enum { TRK_ARM = 0, TRK_LEG = 1, TRK_NEITHER = 2 };

/* The hands' naming (trk_hands.c): its candidates and what each costs
 * per side, both hands then chosen at once as the least summed cost. */
typedef struct hand_naming {
    int32_t n, cell[TRK_MAX_EXTREMA];     /* the candidates: extremities classed TRK_ARM */
    int32_t cost[2][TRK_MAX_EXTREMA + 1]; /* [side][k], [side][n]: no hand; INT32_MAX: out of that arm's reach */
    int32_t gs[2][TRK_MAX_EXTREMA];       /* along the surface from its own arm's root (straight where cut off) */
    int32_t go[2][TRK_MAX_EXTREMA];       /* and from the other arm's */
    int32_t le[2][TRK_MAX_EXTREMA];       /* where its path from the root leaves the torso, out to that side (mm) */
} hand_naming;

/* The extremities picked for the limbs: what the resolvers read and
 * correct (trk_resolve.c). */
typedef struct limb_pick {
    int32_t cand[TRK_MAX_EXTREMA], ncand; /* the extremities but the head, in the extremities' order */
    uint8_t limb[TRK_MAX_EXTREMA];        /* cand k ends: TRK_ARM, TRK_LEG or TRK_NEITHER */
    int32_t hand[2], foot[2];             /* extremum cell per side (0 = left), -1 none */
    int32_t elbow[2];                     /* an elbow taken for the hand: its cell, else -1 */
    int32_t hang[2];                      /* an arm with no hand hanging against the thigh: its tip, else -1 */
    bool bent;                            /* the body bent toward the camera (a bow) */
    hand_naming nm;
} limb_pick;

/* trk_resolve.c: the special poses, one signature, one table. A resolver
 * reads the body's frame and corrects the limbs' pick; true when it
 * changed something. Each runs at one stage of the pick (below). */
typedef bool (*trk_resolver)(const trk_frame *f, limb_pick *lp);
typedef enum trk_stage {
    TRK_AT_FRAME,      /* the body's frame known, no limb named yet */
    TRK_AT_CLASSIFIED, /* each extremity classed an arm's or a leg's */
    TRK_AT_FEET,       /* the feet named, the hands' candidates known */
    TRK_AT_COSTED,     /* each candidate costed per side (lp->nm), the hands not chosen yet */
    TRK_AT_NAMED,      /* the hands named too */
} trk_stage;
typedef struct trk_resolver_entry {
    const char *name;
    trk_stage stage;
    trk_resolver run;
} trk_resolver_entry;
/* The table, in the order the resolvers run; *n its length. */
const trk_resolver_entry *trk_resolvers(int32_t *n);
/* Run the table's resolvers of one stage, in order. */
void trk_resolve(const trk_frame *f, limb_pick *lp, trk_stage stage);

/* trk_hands.c: the body bent toward the camera (the head's centre well before the root) */
bool trk_bent(const trk_frame *f);
/* surface distances from both arms' roots (f->arm_root) into t->dist_sh */
void trk_from_shoulders(cub_tracker *t, const trk_frame *f);
/* the hands' naming: each candidate classed TRK_ARM costed per side
 * (lp->nm), then the pair with the least cost chosen: lp->hand (both -1
 * when none) */
void trk_cost_hands(const trk_frame *f, limb_pick *lp);
void trk_choose_hands(limb_pick *lp);
/* extremity i lies on the torso's surface (a shoulder bump, an elbow) */
bool trk_on_torso(const trk_frame *f, int32_t i);
/* cell c lies on a leg: on a named foot's path (a knee raised aside) or
 * near its knee (a bent knee's tip): no hand */
bool trk_on_leg(const trk_frame *f, const limb_pick *lp, int32_t c);
/* a hand before the torso on this side: a cell, -1 none */
int32_t trk_hand_in_front(const trk_frame *f, const limb_pick *lp, int side);
/* an elbow taken for the hand: the fist beyond it (or a guard's fist above it), -1 none */
int32_t trk_hand_beyond(const trk_frame *f, const limb_pick *lp, int side);

#endif

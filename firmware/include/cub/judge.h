/* judge — from the player's skeleton (cub/track.h) to the coach's input
 * (SEEDS.md § 000, "Recognising the child's move"): a verdict per move
 * repetition, claps (the clap that wakes the coach), waves, and presence.
 *
 * Feed it every tracker frame with cub_judge_frame (t_us increasing).
 * Tell it what is taught with cub_judge_begin_rep. Each call fills a
 * cub_judge_out with the events of that frame; `ev` of each is the loop
 * event to post (CUB_EV_VERDICT / CUB_EV_CLAP / CUB_EV_PLAYER; a wave has
 * no coach event and carries CUB_EV_NONE). Integer only, no allocation:
 * the same frames and calls give the same events on every CPU.
 *
 * Verdicts, exactly:
 * - A repetition r has keys (feature, set), its window [start_us,
 *   end_us + beat_us) (a child one beat late still counts) and optionally
 *   the coach's expected fuzzy frame. When the next repetition begins,
 *   the open ones end: their windows close at most one beat after it.
 * - The child's features are the fuzzy features of SEEDS.md, except that
 *   the arm raise (RH, LH) is read along the whole arm, shoulder to wrist:
 *   the tracker places elbows least well, and an arm is raised as far as
 *   its wrist is; and a leg is out (RF, LF = outward) only as far as its
 *   foot is lifted: the membership is the lower of the abduction's and
 *   the lift's, the lift being the ankle's height above the other ankle
 *   (the body's lowest point, so the floor need not be known and a jump
 *   lifts both) in lengths of the legs (hip-knee-ankle, the mean of both),
 *   0 at kick_lift / 2 and 1 at 3/2 kick_lift. A foot out with both feet
 *   on the floor is a stance (golf, a bend, a throw), not a kick. And it is
 *   capped by the balance's: a leg held out stands on the other foot, the
 *   hip centre not past that ankle away from the lifted leg (its offset
 *   along the hips' line, in lengths of the legs: 0 at -kick_lift / 2, 1
 *   at +kick_lift / 2); a pelvis past it is a step or a weight shift.
 * - A frame MATCHES r when the tracker says CUB_TRACK_OK, every key's
 *   membership mu(feature, set) >= key_mu, and, if r has an expected
 *   frame, cub_fuzzy_distance(child, expected) <= pose_d_max.
 * - A run is a stretch of consecutive matching frames (any non-matching
 *   frame ends it); once a run has started, its keys need only stay at or
 *   above 4/5 of key_mu (hysteresis: the tracker's jitter at the top of a
 *   move does not end it). A run is HELD once t(last) - t(first) >= hold_ms.
 * - A held run credits the OLDEST open repetition whose window holds its
 *   frames and that is not yet right: that verdict (b = 1) is issued at
 *   once, in the frame where the run becomes held, but not before the
 *   repetition's first beat has passed (start_us + beat_us): in that beat
 *   a child one beat late is still finishing the previous repetition (the
 *   arms of a jumping jack on their way down pass "mid" again), which
 *   must not credit this one; a run held on past the beat does. One run
 *   credits one repetition: to credit another, the keys must drop (below
 *   4/5 of key_mu) and be reached again, or the run must go on a whole
 *   beat into a repetition that began after the credit (a pose held on,
 *   as in a sway, counts for each repetition it is held through; a late
 *   child's pose at the start of the next repetition counts for the late
 *   one, not for both).
 * - Early verdicts, from the coach's own clip (has_key, key_us: the bear's
 *   key moment, cub_judge_key_moment, measured from start_us), with the
 *   child's lag L (desc lag_ms: children follow a leader late) and S (desc
 *   sign_ms): a SIGN is a frame past start_us + L (before it the child may
 *   still be ending the previous repetition) where every key is at 4/5 of
 *   key_mu, held or not, credited to the previous repetition or not. The
 *   deadline is start_us + L + max(key_us, S): the key's moment plus the
 *   lag, and never less than S after the lag (a key the bear shows from
 *   its clip's start still needs the child's time to show it, and a move
 *   may leave its keys for a moment: a punch straightens the elbow). The
 *   first OK frame at or past it, the repetition still not right, no sign
 *   seen and the keys' joints seen (below) in most OK frames past the lag,
 *   gives the wrong verdict at once (why = missed). And with mirror_wrong
 *   (the keys' left/right mirror is a different set that the bear's clip
 *   never shows), the mirrored keys held (a run of hold_ms of frames with
 *   the mirror's joints CONFIDENT, past the lag) while the keys are not,
 *   is a wrong verdict at once (why = mirror: the other arm or leg). And
 *   each of `other` (another move's keys, which the bear's clip of this
 *   move never shows and which rule this move's keys out: the director
 *   gives those with a feature in a different set), held S past the lag
 *   (frames with its joints CONFIDENT, the keys not matched) with no sign
 *   of the keys yet, is a wrong verdict at once (why = other: the child
 *   does another move; its fault is the keys' own, as for missed). Frames
 *   the tracker is not sure of (not CUB_TRACK_OK) never give an early
 *   verdict.
 * - Guessed joints: a key's joints are SEEN in a frame when the tracker's
 *   confidence of each joint its feature reads is > 0 (cub/track.h: 0 =
 *   a guess, the limb's extremity not found). A window whose OK frames had
 *   the keys' joints guessed more often than seen gets, instead of a wrong
 *   verdict at its close, an unsure one (why = unsure, ev.type
 *   CUB_EV_NONE: logged, never posted, so never corrected; value: the
 *   share of the window's OK frames with the keys' joints CONFIDENT).
 * - The tracker's confidence: a key's joints are CONFIDENT in a frame when
 *   each joint its feature reads has confidence >= CUB_TRACK_CONFIDENT
 *   (the depth backs it, cub/track.h). A joint that is not confident
 *   decides no wrong pose: the mirror and other moves' keys above are read
 *   only where confident. A window whose signs of its keys (past the lag)
 *   were all in frames where their joints were not confident, and that
 *   was not right, is unsure at its close (as above, never corrected):
 *   the tracker glimpsed the move (a front kick's foot, fast and pointed
 *   at the camera) and can say neither that it was done nor that it was
 *   not. A sign in a confident frame, not held, stays wrong at the close.
 *   A child standing still shows no sign at all and is wrong, the joints
 *   confident or not: the tracker marks most still arms of a child facing
 *   it not confident (README, "the judge and the tracker's confidence"),
 *   and stillness is what a found joint shows well.
 * - A wrong verdict's fault (ev.c, cub_judge_fault_code) says what to fix:
 *   why = missed or other: how = missed, the key named (the weakest), and as the
 *   limbs to move those of the keys that never reached key_mu in the
 *   window, or of every key when each did, alone (the keys never came
 *   together: the whole move is missing); why = mirror: how = mirror, the
 *   key whose mirror was held (of those with a mirror of another set, the
 *   weakest) and its limb: the side that should have moved. No fault (c =
 *   0) for no_player and pose: nothing one limb can fix.
 * - A repetition still without a right verdict gets a wrong one (b = 0) in
 *   the first frame with t_us >= end_us + beat_us. Why: no_player when no
 *   frame of its window was CUB_TRACK_OK, pose when the keys were held but
 *   never close enough to the expected frame, else missed, naming the key
 *   with the lowest best membership (no key, no player, standing still:
 *   all wrong).
 * - cub_judge_cancel_reps drops open repetitions without a verdict (the
 *   coach abandoned them).
 *
 * Clap: the hands (HAND_L/R) come together fast and meet in front of the
 * body, then part; every length is a share of the shoulder width (a
 * child's clap is an adult's, scaled). Meet: hand gap < clap_meet of the
 * width (plus clap_slack of the last frame's closing: a contact between
 * two frames), the gap having been >= clap_open of it within the last
 * clap_approach_ms and closed from its widest there at clap_speed widths a
 * second or faster on average, both hands moving in (each at least a
 * quarter of the closing, along the line between them: a punch across the
 * body or a hand brought to a still one is no clap), closing side to side
 * (the change of the hand-to-hand vector within acos(sqrt(clap_side)) of
 * the shoulders' line: a hand brought down onto the other is no clap), the
 * hands in front of the trunk with the forearms reaching forward (see
 * clap_pose in firmware/judge/judge_gesture.c for the exact bounds, from
 * hip to a bit above shoulder height; hands meeting overhead with the
 * forearms up are a wave, hands clasped at the belt are not a clap). Part: the gap grows by clap_part of the width within
 * clap_part_ms of the meet. The clap is issued at the part (so hands
 * brought together and held, as when carrying something, are no clap);
 * after it none for clap_refractory_ms.
 * Wave: a hand above its elbow and its shoulder moves side to side (x,
 * relative to its shoulder) with at least wave_reversals reversals, each
 * swing at least wave_swing of the shoulder width, reversals at most
 * wave_gap_ms apart; a swing counts only when the hand rises during it no
 * more than it crosses (a loop, a throw or a serve restarts the count)
 * and took at least 80 ms (no arm waves 6 times a second: a faster turn
 * is a hit's recoil, and restarts the count too).
 * A hand that comes back up from below its elbow or shoulder starts its
 * swings afresh (drawing a big circle is no wave); a clap clears the
 * count. Both hands raised, each turning back (a swing of 80 ms or more,
 * sideways or not: arms swept up from the sides rise) within
 * wave_pair_ms of each other, is a two-hand wave at once (one arc of both
 * arms over the head): in mirror, or in step with the hands at least a
 * shoulder width apart (hands holding one thing move in step together).
 * One event per
 * waving episode (an episode ends when wave_gap_ms passes without a
 * reversal).
 * Presence: in view after present_frames CUB_TRACK_OK frames in a row, out
 * of view after absent_frames non-OK frames in a row (any other tracker
 * status counts as not seen). Starts out of view. A CUB_EV_PLAYER on each
 * change. A child too close (present_frames CUB_TRACK_TOO_CLOSE frames
 * with no OK frame between) is out of view at once, told by a
 * CUB_EV_PLAYER with a = 0, b = 1 (why too_close: the coach says "Step
 * back"), even when it was out of view already; a repetition whose window
 * saw a TOO_CLOSE frame gets no verdict (the child was not seen whole:
 * neither right nor wrong).
 *
 * Posture keys (sit, jump) read the CoG over the floor: desc floor_y_mm and
 * stand_cog_mm when known, else estimated online (floor from the lower
 * foot, standing CoG tracked slowly from the first frames in view). */
#ifndef CUB_JUDGE_H
#define CUB_JUDGE_H

#include <stddef.h>
#include <stdint.h>

#include "cub/err.h"
#include "cub/fuzzy.h"
#include "cub/fx.h"
#include "cub/loop.h"
#include "cub/track.h"

#define CUB_JUDGE_MAX_KEYS 4   /* key points per move (cub_song allows 4) */
#define CUB_JUDGE_MAX_OPEN 4   /* repetitions open at once (incl. late tails) */
#define CUB_JUDGE_MAX_EVENTS 8 /* events one frame can produce */
#define CUB_JUDGE_MAX_OTHER 4  /* other moves' key sets a repetition looks for */
#define CUB_JUDGE_NO_SLACK ((cub_q16)-1) /* cub_judge_desc.clap_slack: none */

/* Zero-initialised fields take the defaults shown. Ratios are Q16.16. */
typedef struct cub_judge_desc {
    uint16_t key_mu;           /* 16384 (0.5): a key is reached at this membership */
    int32_t hold_ms;           /* 100: a match held this long counts */
    cub_q16 pose_d_max;        /* 0.45: d to the expected frame, when given */
    int32_t present_frames;    /* 5 OK frames in a row: in view */
    int32_t absent_frames;     /* 30 non-OK frames in a row: out of view */
    cub_q16 clap_meet;         /* 0.55 of the shoulder width: hands meet */
    cub_q16 clap_open;         /* 1.0: the gap before the approach */
    int32_t clap_approach_ms;  /* 400 */
    cub_q16 clap_speed;        /* 3.0 shoulder widths a second: the least mean
                                  closing speed from the open gap to the meet */
    cub_q16 clap_slack;        /* 0.5: of the last frame's closing, allowed on
                                  top of clap_meet (contact between frames);
                                  CUB_JUDGE_NO_SLACK for none */
    cub_q16 clap_side;         /* 0.5: the least cos^2 of the angle between the
                                  hands' closing and the shoulders' line (45 deg) */
    cub_q16 clap_part;         /* 0.25: the gap growth that ends a clap */
    int32_t clap_part_ms;      /* 600 */
    int32_t clap_refractory_ms;/* 200 */
    cub_q16 wave_swing;        /* 0.25 */
    int32_t wave_reversals;    /* 2 */
    int32_t wave_gap_ms;       /* 2000 */
    int32_t wave_pair_ms;      /* 250: both hands turning back within this is a
                                  two-hand wave (mirrored or in step apart, one
                                  turn each) */
    cub_q16 floor_y_mm;        /* with stand_cog_mm > 0: fixed calibration */
    cub_q16 stand_cog_mm;      /* 0: estimate online */
    int32_t lag_ms;            /* 500: how late a child may follow the coach: the
                                  previous repetition's tail (no sign counts in it)
                                  and the time after the coach's key moment the keys
                                  may still come (measured: README "Early verdicts") */
    int32_t sign_ms;           /* 250: the least time after the lag in which a sign
                                  of the keys is looked for before an early verdict */
    cub_q16 kick_lift;         /* 0.10 of the leg's length: the lift of a foot above
                                  the other at which a leg-out key is half reached
                                  (a kick; a foot on the floor reads under 0.05) */
    cub_log *log;              /* optional: one line per event */
} cub_judge_desc;

/* One repetition of a move to judge. */
typedef struct cub_judge_key {
    int32_t feature; /* cub_fuzzy_feature */
    int32_t set;     /* index of the set (cub_fuzzy_set_name) */
} cub_judge_key;

/* A move's keys, all together. */
typedef struct cub_judge_keyset {
    int32_t count; /* 1..CUB_JUDGE_MAX_KEYS */
    cub_judge_key key[CUB_JUDGE_MAX_KEYS];
} cub_judge_keyset;

typedef struct cub_judge_rep {
    int32_t move, rep; /* song move index (the verdict's a) and repetition */
    int32_t key_count; /* 1..CUB_JUDGE_MAX_KEYS */
    cub_judge_key keys[CUB_JUDGE_MAX_KEYS];
    int64_t start_us, end_us; /* the repetition in loop time, end > start */
    int64_t beat_us;          /* the late allowance, >= 0 (one beat) */
    const cub_fuzzy_frame *expected; /* optional: the coach's pose (copied) */
    int has_key;     /* key_us is known: an early verdict is possible */
    int64_t key_us;  /* the coach's clip reaches every key this long after start_us, >= 0 */
    int mirror_wrong;/* the keys' mirror held instead is a wrong verdict at once */
    int32_t other_count; /* 0..CUB_JUDGE_MAX_OTHER (with has_key) */
    cub_judge_keyset other[CUB_JUDGE_MAX_OTHER]; /* other moves' keys the bear's clip
                                                   never shows: held instead, wrong */
} cub_judge_rep;

typedef enum cub_judge_kind {
    CUB_JUDGE_VERDICT = 1,
    CUB_JUDGE_CLAP,
    CUB_JUDGE_WAVE,
    CUB_JUDGE_PLAYER,
} cub_judge_kind;

typedef enum cub_judge_why {
    CUB_JUDGE_WHY_KEYS = 1, /* right: the keys were held */
    CUB_JUDGE_WHY_MISSED,   /* wrong: a key never held (key = the weakest) */
    CUB_JUDGE_WHY_POSE,     /* wrong: keys held, pose too far from expected */
    CUB_JUDGE_WHY_NO_PLAYER,/* wrong: nobody tracked in the window */
    CUB_JUDGE_WHY_CLAP,
    CUB_JUDGE_WHY_WAVE,
    CUB_JUDGE_WHY_IN_VIEW,
    CUB_JUDGE_WHY_OUT_OF_VIEW,
    CUB_JUDGE_WHY_MIRROR,   /* wrong: the keys' mirror held (the other arm) */
    CUB_JUDGE_WHY_UNSURE,   /* no verdict to act on: keys guessed, or glimpsed unconfidently */
    CUB_JUDGE_WHY_OTHER,    /* wrong: another move's keys held instead */
    CUB_JUDGE_WHY_TOO_CLOSE,/* out of view: the child stands too close (CUB_EV_PLAYER b = 1) */
} cub_judge_why;

/* What a wrong verdict says to fix: which key failed and how. */
typedef enum cub_judge_how {
    CUB_JUDGE_HOW_NONE = 0, /* no fault to name (nobody seen, the pose, a right verdict) */
    CUB_JUDGE_HOW_MISSED,   /* the key never came (its moment passed, or the window closed) */
    CUB_JUDGE_HOW_MIRROR,   /* the other side did it: the key's mirror was held instead */
    CUB_JUDGE_HOW_COUNT
} cub_judge_how;

typedef struct cub_judge_fault {
    int32_t how;     /* cub_judge_how */
    int32_t feature; /* the key that failed (cub_fuzzy_feature)... */
    int32_t set;     /* ...and its set: for a mirror, the side that should have moved */
    uint32_t limbs;  /* the limbs to move, bit (limb - 1) of each cub_judge_limb;
                        0: the key's own */
} cub_judge_fault;

/* The body part a fault is about, the one the child should move. */
typedef enum cub_judge_limb {
    CUB_JUDGE_LIMB_NONE = 0,
    CUB_JUDGE_LIMB_RIGHT_ARM, /* RH, RHE */
    CUB_JUDGE_LIMB_LEFT_ARM,  /* LH, LHE */
    CUB_JUDGE_LIMB_RIGHT_LEG, /* RF, RFK */
    CUB_JUDGE_LIMB_LEFT_LEG,  /* LF, LFK */
    CUB_JUDGE_LIMB_LEGS,      /* Posture: the body goes up or down on both legs */
    CUB_JUDGE_LIMB_TRUNK,     /* Trunk */
    CUB_JUDGE_LIMB_COUNT
} cub_judge_limb;

typedef struct cub_judge_event {
    cub_event ev;     /* ready to post (type CUB_EV_NONE for a wave or an unsure verdict) */
    int32_t kind;     /* cub_judge_kind */
    int32_t why;      /* cub_judge_why */
    int32_t move, rep;/* verdicts; -1 otherwise */
    int32_t feature;  /* verdicts: the key's feature (cub_fuzzy_feature)... */
    int32_t set;      /* ...and set concerned; -1 none */
    cub_q16 value;    /* verdict: the (failed) key's best membership (0..1) or min d;
                         clap: hand gap at the meet (mm); wave: reversals;
                         player: 1 / 0 */
    int32_t side;     /* wave: 0 left hand, 1 right hand; else -1 */
} cub_judge_event;

typedef struct cub_judge_out {
    int32_t count;
    cub_judge_event events[CUB_JUDGE_MAX_EVENTS];
} cub_judge_out;

typedef struct cub_judge cub_judge; /* lives in caller memory */

/* Bytes cub_judge_init needs (desc may be NULL: defaults). */
size_t cub_judge_mem_size(const cub_judge_desc *desc);
/* Set up a judge in mem (8-byte aligned). CUB_ERR_ARG (NULL, a negative
 * or absurd tunable), CUB_ERR_NOMEM (mem_size too small). */
cub_err cub_judge_init(const cub_judge_desc *desc, void *mem, size_t mem_size, cub_judge **out);

/* Open a repetition. CUB_ERR_ARG: bad key (feature or set out of range,
 * key_count outside 1..4), end_us <= start_us, beat_us < 0. CUB_ERR_FULL:
 * CUB_JUDGE_MAX_OPEN repetitions already open. */
cub_err cub_judge_begin_rep(cub_judge *j, const cub_judge_rep *rep);
/* Drop every open repetition without a verdict; returns how many. */
int32_t cub_judge_cancel_reps(cub_judge *j);

/* One tracker frame at t_us. Always fills *out (count may be 0). A frame
 * whose t_us is not after the previous one is ignored. CUB_ERR_ARG only
 * for NULL pointers. */
cub_err cub_judge_frame(cub_judge *j, int64_t t_us, const cub_track_skeleton *skel,
                        cub_judge_out *out);

/* The first of count frames where every key reaches its set at j's key_mu;
 * -1 none. */
int32_t cub_judge_first_match(const cub_judge *j, const cub_judge_key *keys, int32_t key_count,
                              const cub_fuzzy_frame *frames, int32_t count);
/* The coach's key moment in its clip: the first frame where the weakest
 * key is half way from key_mu to its peak over the clip (the bear shows
 * the keys clearly there; a bear whose rest pose already passes key_mu, as
 * its bent knees do, is not "there" at frame 0); -1 when the clip never
 * reaches the keys. */
int32_t cub_judge_key_moment(const cub_judge *j, const cub_judge_key *keys, int32_t key_count,
                             const cub_fuzzy_frame *frames, int32_t count);
/* The keys' left/right mirror (RH<->LH, RHE<->LHE, RF<->LF, RFK<->LFK, the
 * same sets); returns 1 when it differs from the keys as a set. */
int cub_judge_mirror_keys(const cub_judge_key *keys, int32_t key_count, cub_judge_key *mirror);

/* A fault as one number, for the loop event (cub_event c of a verdict):
 * limbs * 1000 + how * 100 + feature * 10 + set, so 3111 reads "both arms
 * (3), missed (1) RHE=true (1, 1)" at a glance; 0 for none or an invalid
 * fault (limbs beyond the six). */
int32_t cub_judge_fault_code(cub_judge_fault f);
/* The fault a code names; how = CUB_JUDGE_HOW_NONE for 0 or an invalid code. */
cub_judge_fault cub_judge_fault_of(int32_t code);
/* The limb a fault's key is about (CUB_JUDGE_LIMB_NONE for none). */
int32_t cub_judge_fault_limb(cub_judge_fault f);
/* The tracker joints (bit CUB_KJ_*) of every limb the fault asks to move:
 * its limbs, or its key's limb when it names none; 0 for no fault. */
uint32_t cub_judge_fault_joints(cub_judge_fault f);
/* The tracker joints of a limb as a bit mask (bit CUB_KJ_* set): those
 * whose bone to their parent belongs to the limb; 0 for none. */
uint32_t cub_judge_limb_joints(int32_t limb);
/* "missed", "mirror" ("none" for none); "right_arm", ... ("none"); "?"
 * out of range. */
const char *cub_judge_how_name(int32_t how);
const char *cub_judge_limb_name(int32_t limb);

/* The last frame's fuzzy features (zero before the first OK frame). */
const cub_fuzzy_frame *cub_judge_last_features(const cub_judge *j);

/* A log line for an event, e.g. "verdict move=3 rep=1 result=wrong
 * why=missed key=RHE=true best=0.420 fix=right_arm,left_arm" (fix: the
 * limbs a wrong verdict with a fault asks to move; only then); returns
 * its length (cut to size). */
size_t cub_judge_describe(const cub_judge_event *e, char *buf, size_t size);

/* "keys", "missed", ...; "?" out of range. */
const char *cub_judge_why_name(int32_t why);

#endif

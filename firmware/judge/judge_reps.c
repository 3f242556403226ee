/* judge: verdicts per move repetition (cub/judge.h, "Verdicts, exactly"). */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "cub/judge.h"
#include "judge_internal.h"

static int set_valid(const cub_judge_key *keys, int32_t n)
{
    if (n < 1 || n > CUB_JUDGE_MAX_KEYS) return 0;
    for (int k = 0; k < n; k++) {
        int32_t f = keys[k].feature;
        if (f < 0 || f >= CUB_FUZZY_FEATURE_COUNT) return 0;
        if (keys[k].set < 0 || keys[k].set >= cub_fuzzy_set_count(f)) return 0;
    }
    return 1;
}

static int keys_valid(const cub_judge_rep *r)
{
    if (!set_valid(r->keys, r->key_count)) return 0;
    if (!r->has_key) return 1; /* the others are read only with a key moment */
    if (r->other_count < 0 || r->other_count > CUB_JUDGE_MAX_OTHER) return 0;
    for (int i = 0; i < r->other_count; i++)
        if (!set_valid(r->other[i].key, r->other[i].count)) return 0;
    return 1;
}

static int32_t mirror_feature(int32_t f)
{
    switch (f) {
    case CUB_FUZZY_RH: return CUB_FUZZY_LH;
    case CUB_FUZZY_LH: return CUB_FUZZY_RH;
    case CUB_FUZZY_RHE: return CUB_FUZZY_LHE;
    case CUB_FUZZY_LHE: return CUB_FUZZY_RHE;
    case CUB_FUZZY_RF: return CUB_FUZZY_LF;
    case CUB_FUZZY_LF: return CUB_FUZZY_RF;
    case CUB_FUZZY_RFK: return CUB_FUZZY_LFK;
    case CUB_FUZZY_LFK: return CUB_FUZZY_RFK;
    default: return f; /* Posture, Trunk: the body's, no side */
    }
}

static int has_key(const cub_judge_key *keys, int32_t n, cub_judge_key k)
{
    for (int i = 0; i < n; i++)
        if (keys[i].feature == k.feature && keys[i].set == k.set) return 1;
    return 0;
}

int cub_judge_mirror_keys(const cub_judge_key *keys, int32_t key_count, cub_judge_key *mirror)
{
    if (!keys || !mirror || key_count < 0 || key_count > CUB_JUDGE_MAX_KEYS) return 0;
    int differs = 0;
    for (int i = 0; i < key_count; i++) {
        mirror[i] = (cub_judge_key){mirror_feature(keys[i].feature), keys[i].set};
        differs |= !has_key(keys, key_count, mirror[i]);
    }
    return differs;
}

/* Are the joints of every key in mask (judge_sure's found or confident)? */
static int keys_sure(const cub_judge_key *keys, int32_t n, uint32_t sure)
{
    for (int k = 0; k < n; k++)
        if (!(sure >> keys[k].feature & 1u)) return 0;
    return 1;
}

/* Do all keys reach their sets in f? */
static int keys_match(const cub_judge_key *keys, int32_t n, const cub_fuzzy_frame *f,
                      uint16_t key_mu)
{
    for (int k = 0; k < n; k++)
        if (f->mu[keys[k].feature][keys[k].set] < key_mu) return 0;
    return 1;
}

/* The weakest key's membership in f. */
static uint16_t weakest(const cub_judge_key *keys, int32_t n, const cub_fuzzy_frame *f)
{
    uint16_t w = CUB_FUZZY_ONE;
    for (int k = 0; k < n; k++)
        if (f->mu[keys[k].feature][keys[k].set] < w) w = f->mu[keys[k].feature][keys[k].set];
    return w;
}

int32_t cub_judge_first_match(const cub_judge *j, const cub_judge_key *keys, int32_t key_count,
                              const cub_fuzzy_frame *frames, int32_t count)
{
    if (!j || !keys || !frames || key_count < 1 || key_count > CUB_JUDGE_MAX_KEYS) return -1;
    for (int32_t i = 0; i < count; i++)
        if (keys_match(keys, key_count, &frames[i], j->d.key_mu)) return i;
    return -1;
}

int32_t cub_judge_key_moment(const cub_judge *j, const cub_judge_key *keys, int32_t key_count,
                             const cub_fuzzy_frame *frames, int32_t count)
{
    if (cub_judge_first_match(j, keys, key_count, frames, count) < 0) return -1;
    uint16_t peak = 0;
    for (int32_t i = 0; i < count; i++) {
        uint16_t w = weakest(keys, key_count, &frames[i]);
        if (w > peak) peak = w;
    }
    uint16_t clear = (uint16_t)(((uint32_t)j->d.key_mu + peak + 1) / 2);
    for (int32_t i = 0; i < count; i++)
        if (weakest(keys, key_count, &frames[i]) >= clear) return i;
    return -1; /* not reached: peak >= clear */
}

/* How long after a repetition's start the child may still be in the one
 * before: its lag (desc lag_ms). */
static int64_t lag_us(const cub_judge *j)
{
    return (int64_t)j->d.lag_ms * 1000;
}

/* The early deadline: the coach's key moment plus the child's lag, and at
 * least sign_ms after that lag (the child's own time to show the keys, which
 * a move may leave for a moment: a punch straightens the elbow). */
static void set_due(const cub_judge *j, rep_slot *s, const cub_judge_rep *r)
{
    if (!r->has_key || r->key_us < 0) return;
    int64_t sign = (int64_t)j->d.sign_ms * 1000;
    int64_t due = lag_us(j) + (r->key_us > sign ? r->key_us : sign);
    if (due > INT64_MAX - r->start_us) return;
    s->has_due = 1;
    s->due_us = r->start_us + due;
    if (r->mirror_wrong)
        s->has_mirror = cub_judge_mirror_keys(s->keys, s->key_count, s->mirror);
    s->other_count = r->other_count;
    memcpy(s->other, r->other, sizeof s->other);
}

cub_err cub_judge_begin_rep(cub_judge *j, const cub_judge_rep *r)
{
    if (!j || !r || !keys_valid(r) || r->end_us <= r->start_us || r->beat_us < 0) return CUB_ERR_ARG;
    if (r->end_us > INT64_MAX - r->beat_us || (r->has_key && r->key_us < 0)) return CUB_ERR_ARG;
    /* The bear's repetitions follow one another: when this one begins the
     * open ones are over, whatever their clip's length at its first speed
     * said (the coach re-times clips to the music), so their late
     * allowance runs from now. */
    for (int i = 0; i < CUB_JUDGE_MAX_OPEN; i++) {
        rep_slot *o = &j->reps[i];
        if (o->used && o->close_us > r->start_us + o->beat_us) o->close_us = r->start_us + o->beat_us;
    }
    rep_slot *s = NULL;
    for (int i = 0; i < CUB_JUDGE_MAX_OPEN && !s; i++)
        if (!j->reps[i].used) s = &j->reps[i];
    if (!s) return CUB_ERR_FULL;
    memset(s, 0, sizeof *s);
    s->used = 1;
    s->seq = j->next_seq++;
    s->move = r->move;
    s->rep = r->rep;
    s->key_count = r->key_count;
    memcpy(s->keys, r->keys, sizeof s->keys);
    s->start_us = r->start_us;
    s->close_us = r->end_us + r->beat_us;
    s->beat_us = r->beat_us;
    if (r->expected) {
        s->has_expected = 1;
        s->expected = *r->expected;
    }
    s->min_d = CUB_Q16_ONE;
    set_due(j, s, r);
    return CUB_OK;
}

int32_t cub_judge_cancel_reps(cub_judge *j)
{
    if (!j) return 0;
    int32_t n = 0;
    for (int i = 0; i < CUB_JUDGE_MAX_OPEN; i++) {
        n += j->reps[i].used;
        j->reps[i].used = 0;
    }
    return n;
}

static int same_keys(const cub_judge_key *a, int32_t na, const cub_judge_key *b, int32_t nb)
{
    return na == nb && memcmp(a, b, (size_t)na * sizeof *a) == 0;
}

/* Do credited keys still block repetition s at t_us? Not once the pose
 * has been held a beat into a repetition that began after the credit. */
static int is_consumed(const cub_judge *j, const rep_slot *s, int64_t t_us)
{
    for (int i = 0; i < CUB_JUDGE_MAX_OPEN; i++) {
        const consumed_keys *c = &j->consumed[i];
        if (!c->used || !same_keys(c->keys, c->key_count, s->keys, s->key_count)) continue;
        if (s->start_us > c->at_us && t_us >= s->start_us + s->beat_us) continue;
        return 1;
    }
    return 0;
}

static void consume(cub_judge *j, const rep_slot *s, int64_t t_us)
{
    for (int i = 0; i < CUB_JUDGE_MAX_OPEN; i++) /* a run credits again: renew its mark */
        if (j->consumed[i].used &&
            same_keys(j->consumed[i].keys, j->consumed[i].key_count, s->keys, s->key_count)) {
            j->consumed[i].at_us = t_us;
            return;
        }
    consumed_keys *c = &j->consumed[0]; /* the oldest is overwritten when full */
    for (int i = 0; i < CUB_JUDGE_MAX_OPEN; i++)
        if (!j->consumed[i].used) {
            c = &j->consumed[i];
            break;
        }
    c->used = 1;
    c->at_us = t_us;
    c->key_count = s->key_count;
    memcpy(c->keys, s->keys, sizeof c->keys);
}

/* Keys that dropped (or a frame without a player) may credit again. */
static void release_consumed(cub_judge *j, const cub_fuzzy_frame *f)
{
    for (int i = 0; i < CUB_JUDGE_MAX_OPEN; i++) {
        consumed_keys *c = &j->consumed[i];
        if (c->used && (!f || !keys_match(c->keys, c->key_count, f,
                                          (uint16_t)(j->d.key_mu - j->d.key_mu / 5))))
            c->used = 0;
    }
}

static cub_judge_event verdict(const rep_slot *s, int64_t t_us, int right, int32_t why)
{
    cub_judge_event e = {
        .ev = {.t_us = t_us, .type = CUB_EV_VERDICT, .a = s->move, .b = right},
        .kind = CUB_JUDGE_VERDICT,
        .why = why,
        .move = s->move,
        .rep = s->rep,
        .feature = -1,
        .set = -1,
        .side = -1,
    };
    return e;
}

/* The key a wrong verdict names: the weakest, and for a mirror the
 * weakest of those whose mirror is another key (the side that should have
 * moved; a Posture key of a mirrored move has no other side). */
static int failed_key(const rep_slot *s, int mirror)
{
    int weak = -1;
    for (int k = 0; k < s->key_count; k++) {
        if (mirror && has_key(s->keys, s->key_count, s->mirror[k])) continue;
        if (weak < 0 || s->best_mu[k] < s->best_mu[weak]) weak = k;
    }
    return weak < 0 ? 0 : weak;
}

/* The bit of a key's limb in a fault's limbs. */
static uint32_t limb_bit(cub_judge_key k)
{
    cub_judge_fault f = {CUB_JUDGE_HOW_MISSED, k.feature, k.set, 0};
    int32_t limb = cub_judge_fault_limb(f);
    return limb > CUB_JUDGE_LIMB_NONE ? 1u << (limb - 1) : 0;
}

/* The limbs to move when keys were missed: those of the keys that never
 * reached key_mu, or of every key when each did (alone: the keys never
 * came together, the whole move is what is missing). */
static uint32_t missed_limbs(const rep_slot *s, uint16_t key_mu)
{
    uint32_t lacking = 0, all = 0;
    for (int k = 0; k < s->key_count; k++) {
        all |= limb_bit(s->keys[k]);
        if (s->best_mu[k] < key_mu) lacking |= limb_bit(s->keys[k]);
    }
    return lacking ? lacking : all;
}

/* A wrong verdict: why (early_why, else as a closed window has it), which key
 * and, for missed and mirror, the fault to fix (ev.c). */
static cub_judge_event wrong(const rep_slot *s, int64_t t_us, int32_t early_why, uint16_t key_mu)
{
    int32_t why = early_why          ? early_why
                  : !s->seen         ? CUB_JUDGE_WHY_NO_PLAYER
                  : s->keys_held && s->has_expected ? CUB_JUDGE_WHY_POSE
                                                    : CUB_JUDGE_WHY_MISSED;
    cub_judge_event e = verdict(s, t_us, 0, why);
    if (why == CUB_JUDGE_WHY_POSE) {
        e.value = s->min_d;
        return e;
    }
    int k = failed_key(s, why == CUB_JUDGE_WHY_MIRROR);
    e.feature = s->keys[k].feature;
    e.set = s->keys[k].set;
    e.value = (cub_q16)s->best_mu[k] * 2; /* Q1.15 -> Q16.16 */
    if (why == CUB_JUDGE_WHY_MIRROR)
        e.ev.c = cub_judge_fault_code(
            (cub_judge_fault){CUB_JUDGE_HOW_MIRROR, e.feature, e.set, limb_bit(s->keys[k])});
    else if (why == CUB_JUDGE_WHY_MISSED || why == CUB_JUDGE_WHY_OTHER)
        e.ev.c = cub_judge_fault_code(
            (cub_judge_fault){CUB_JUDGE_HOW_MISSED, e.feature, e.set, missed_limbs(s, key_mu)});
    return e;
}

/* One frame of one open repetition inside its window; 1 when it is now
 * right. */
static int rep_step(cub_judge *j, rep_slot *s, int64_t t_us, const cub_fuzzy_frame *f,
                    const judge_sure *sure)
{
    if (!f) {
        s->run_on = s->keys_run_on = 0;
        return 0;
    }
    s->seen = 1;
    int past_lag = t_us >= s->start_us + lag_us(j);
    int confident = keys_sure(s->keys, s->key_count, sure->confident);
    s->confident_frames += confident;
    if (keys_sure(s->keys, s->key_count, sure->found)) {
        s->sure_frames++;
        s->sure_after_lag += past_lag;
    } else {
        s->unsure_frames++;
        s->unsure_after_lag += past_lag;
    }
    for (int k = 0; k < s->key_count; k++) {
        uint16_t mu = f->mu[s->keys[k].feature][s->keys[k].set];
        if (mu > s->best_mu[k]) s->best_mu[k] = mu;
    }
    /* Hysteresis: a run once started goes on while every key stays above
     * four fifths of key_mu, so a tracker's jitter at the top of a move
     * does not break it. */
    uint16_t th = s->keys_run_on ? (uint16_t)(j->d.key_mu - j->d.key_mu / 5) : j->d.key_mu;
    int keys = keys_match(s->keys, s->key_count, f, th);
    /* A sign of the move, even too short or taken by the previous
     * repetition: no early wrong verdict then, only the close's. Not in
     * the child's lag: there it may still be ending the one before.
     * Whether its joints were confident is kept: a sign seen only
     * unconfidently makes the close unsure (closing). */
    if (past_lag) {
        int sign = keys_match(s->keys, s->key_count, f, (uint16_t)(j->d.key_mu - j->d.key_mu / 5));
        s->sign |= sign;
        s->sign_confident |= sign && confident;
    }
    int close = 1;
    if (keys && s->has_expected) {
        cub_q16 d = cub_fuzzy_distance(f, &s->expected, NULL);
        if (d < s->min_d) s->min_d = d;
        close = d <= j->d.pose_d_max;
    }
    if (keys && !s->keys_run_on) s->keys_run_first_us = t_us;
    s->keys_run_on = keys;
    if (keys && t_us - s->keys_run_first_us >= (int64_t)j->d.hold_ms * 1000) s->keys_held = 1;
    int match = keys && close && !is_consumed(j, s, t_us);
    if (match && !s->run_on) s->run_first_us = t_us;
    s->run_on = match;
    /* Not in the repetition's first beat: a child a beat late is still
     * finishing the previous repetition there (which, if still open, takes
     * the credit as the older one); a pose held on past it counts. */
    return match && t_us - s->run_first_us >= (int64_t)j->d.hold_ms * 1000 &&
           t_us >= s->start_us + s->beat_us;
}

/* Is one of the other moves' keys held instead of s's: sign_ms past the
 * child's lag, its joints confident, s's keys not matched? */
static int other_held(const cub_judge *j, rep_slot *s, int64_t t_us, const cub_fuzzy_frame *f,
                      const judge_sure *sure)
{
    int held = 0;
    int64_t from = s->start_us + lag_us(j);
    for (int i = 0; i < s->other_count; i++) {
        const cub_judge_keyset *o = &s->other[i];
        int on = keys_sure(o->key, o->count, sure->confident) &&
                 keys_match(o->key, o->count, f, j->d.key_mu) &&
                 !keys_match(s->keys, s->key_count, f, j->d.key_mu);
        if (on && !s->other_run_on[i]) s->other_run_first_us[i] = t_us;
        s->other_run_on[i] = on;
        int64_t since = s->other_run_first_us[i] > from ? s->other_run_first_us[i] : from;
        held |= on && t_us - since >= (int64_t)j->d.sign_ms * 1000;
    }
    return held;
}

/* The evidence against a repetition not yet right, in an OK frame f:
 * CUB_JUDGE_WHY_MIRROR when its keys' mirror has been held past the
 * child's lag (their joints confident: a pose is wrong only when the
 * tracker is sure of it), CUB_JUDGE_WHY_MISSED when its deadline passed
 * with no sign of its keys after the lag; else 0. */
static int32_t early_wrong(const cub_judge *j, rep_slot *s, int64_t t_us, const cub_fuzzy_frame *f,
                           const judge_sure *sure)
{
    if (!f) {
        s->mirror_run_on = 0;
        memset(s->other_run_on, 0, sizeof s->other_run_on);
        return 0;
    }
    if (s->has_mirror) {
        int on = keys_sure(s->mirror, s->key_count, sure->confident) &&
                 keys_match(s->mirror, s->key_count, f, j->d.key_mu) &&
                 !keys_match(s->keys, s->key_count, f, j->d.key_mu);
        if (on && !s->mirror_run_on) s->mirror_run_first_us = t_us;
        s->mirror_run_on = on;
        if (on && t_us - s->mirror_run_first_us >= (int64_t)j->d.hold_ms * 1000 &&
            t_us >= s->start_us + lag_us(j))
            return CUB_JUDGE_WHY_MIRROR;
    }
    if (!s->sign && other_held(j, s, t_us, f, sure)) return CUB_JUDGE_WHY_OTHER;
    return s->has_due && t_us >= s->due_us && !s->sign && s->unsure_after_lag <= s->sure_after_lag
               ? CUB_JUDGE_WHY_MISSED
               : 0;
}

/* The open slot with the lowest seq above `after` (after = -1: any). */
static rep_slot *next_oldest(cub_judge *j, int64_t after)
{
    rep_slot *best = NULL;
    for (int i = 0; i < CUB_JUDGE_MAX_OPEN; i++) {
        rep_slot *s = &j->reps[i];
        if (s->used && (int64_t)s->seq > after && (!best || s->seq < best->seq)) best = s;
    }
    return best;
}

/* A closed window's wrong verdict, unless it is unsure: the keys' joints
 * were guessed in most of its frames, or the keys showed a sign past the
 * lag only where their joints were not confident (the tracker glimpsed
 * the move and cannot tell whether it was done: a fast kick's foot). An
 * unsure verdict is logged and not posted: nothing to correct on a guess.
 * Its value: the share of the window's frames whose keys' joints were
 * confident. A child standing still shows no sign at all: wrong. */
static cub_judge_event closing(const cub_judge *j, const rep_slot *s, int64_t t_us)
{
    cub_judge_event e = wrong(s, t_us, 0, j->d.key_mu);
    int guessed = s->unsure_frames > s->sure_frames;
    int glimpsed = s->sign && !s->sign_confident;
    if (!s->seen || (!guessed && !glimpsed)) return e;
    e.why = CUB_JUDGE_WHY_UNSURE;
    e.ev.type = CUB_EV_NONE;
    e.ev.c = 0;
    e.value = (cub_q16)((int64_t)s->confident_frames * CUB_Q16_ONE /
                        (s->sure_frames + s->unsure_frames));
    return e;
}

void judge_reps_frame(cub_judge *j, int64_t t_us, const cub_fuzzy_frame *f,
                      const judge_sure *sure, int too_close, cub_judge_out *out)
{
    release_consumed(j, f);
    for (rep_slot *s = next_oldest(j, -1); s; s = next_oldest(j, s->seq)) {
        if (too_close && t_us >= s->start_us) s->too_close = 1;
        if (t_us >= s->close_us) {
            if (!s->right && !s->too_close) {
                cub_judge_event e = closing(j, s, t_us);
                judge_emit(j, out, &e);
            }
            s->used = 0;
            continue;
        }
        if (s->right || t_us < s->start_us) continue;
        if (rep_step(j, s, t_us, f, sure)) {
            s->right = 1;
            consume(j, s, t_us);
            cub_judge_event e = verdict(s, t_us, 1, CUB_JUDGE_WHY_KEYS);
            e.feature = s->keys[0].feature;
            e.set = s->keys[0].set;
            e.value = (cub_q16)s->best_mu[0] * 2;
            judge_emit(j, out, &e);
            continue;
        }
        int32_t why = s->too_close ? 0 : early_wrong(j, s, t_us, f, sure);
        if (why) {
            /* missed early: told as the window's close would tell it */
            cub_judge_event e = wrong(s, t_us, why == CUB_JUDGE_WHY_MISSED ? 0 : why, j->d.key_mu);
            judge_emit(j, out, &e);
            s->used = 0;
        }
    }
}

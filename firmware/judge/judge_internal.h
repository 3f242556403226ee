/* judge internals shared by its files: the state in caller memory. */
#ifndef CUB_JUDGE_INTERNAL_H
#define CUB_JUDGE_INTERNAL_H

#include <stdint.h>

#include "cub/judge.h"

#define JUDGE_HIST 32 /* frames of hand-gap history (about 1 s at 30 fps) */

typedef struct rep_slot {
    int used;
    uint32_t seq; /* opening order: the oldest open repetition is credited first */
    int32_t move, rep, key_count;
    cub_judge_key keys[CUB_JUDGE_MAX_KEYS];
    int64_t start_us, close_us, beat_us;
    int has_expected;
    cub_fuzzy_frame expected;
    int right;          /* a right verdict was issued */
    int too_close;      /* the child stood too close in the window: not judged */
    int seen;           /* an OK frame fell in the window */
    int keys_held;      /* the keys alone were held once (for why=pose) */
    int run_on;         /* in a run of matching frames */
    int64_t run_first_us;
    int keys_run_on;    /* the same for the keys alone */
    int64_t keys_run_first_us;
    uint16_t best_mu[CUB_JUDGE_MAX_KEYS];
    cub_q16 min_d;
    int sign;           /* the keys were reached together once (4/5 of key_mu), held or not */
    int sign_confident; /* ... in a frame whose keys' joints were all confident */
    int has_due;        /* an early deadline (the coach's key moment + lag) */
    int64_t due_us;
    int has_mirror;     /* the mirrored keys held instead are wrong at once */
    cub_judge_key mirror[CUB_JUDGE_MAX_KEYS];
    int mirror_run_on;
    int32_t other_count;
    cub_judge_keyset other[CUB_JUDGE_MAX_OTHER];
    int other_run_on[CUB_JUDGE_MAX_OTHER];
    int64_t other_run_first_us[CUB_JUDGE_MAX_OTHER];
    int32_t sure_frames, unsure_frames; /* OK frames with the keys' joints seen, or guessed */
    int32_t sure_after_lag, unsure_after_lag; /* the same, past the child's lag */
    int32_t confident_frames; /* OK frames with the keys' joints all confident */
    int64_t mirror_run_first_us;
} rep_slot;

/* Keys just credited: a run of them credits no other repetition until the
 * keys drop (one run, one repetition), or until it has gone on a beat into
 * a repetition that began after the credit (a pose held on, as in a
 * sway: it counts again). */
typedef struct consumed_keys {
    int used;
    int64_t at_us; /* when the run was credited */
    int32_t key_count;
    cub_judge_key keys[CUB_JUDGE_MAX_KEYS];
} consumed_keys;

typedef struct clap_state {
    int64_t t_us[JUDGE_HIST];
    int32_t gap_mm[JUDGE_HIST];
    int32_t hand_mm[JUDGE_HIST][2][3]; /* left and right hand, x y z */
    int32_t n, head;  /* entries held, next slot */
    int met;          /* hands met, waiting for them to part */
    int64_t met_us;
    int32_t min_gap_mm;
    int64_t last_clap_us;
    int clapped;      /* last_clap_us is valid */
} clap_state;

typedef struct wave_state {
    int active, dir, fired;
    int dipped;       /* the hand went below its elbow or shoulder since the last frame */
    int32_t reversals;
    int32_t lo_mm, hi_mm, extreme_mm;
    int32_t from_mm;           /* x where the current swing began */
    int32_t ylo_mm, yhi_mm;    /* the hand's height range during it */
    int64_t last_us;  /* the last direction change */
    int64_t turn_us;  /* the last turn of a swing (sideways or not), the direction after it */
    int32_t turn_dir;
    int32_t swing_from_mm; /* x where the swing that ended at the last turn began */
    int crossed;      /* that swing was a sweep from outside the shoulder across the midline */
    int behind;       /* the raised hand went behind its shoulder (a throw's wind-up) */
} wave_state;

struct cub_judge {
    cub_judge_desc d;   /* defaults filled in */
    int64_t last_t_us;
    int have_t;
    int in_view;
    int32_t ok_run, bad_run;
    int32_t close_run;  /* TOO_CLOSE frames since the last OK one */
    int calibrated;     /* floor and standing CoG known */
    cub_fuzzy_body body;
    cub_fuzzy_frame last;
    uint32_t next_seq;
    rep_slot reps[CUB_JUDGE_MAX_OPEN];
    consumed_keys consumed[CUB_JUDGE_MAX_OPEN];
    int32_t width_mm;   /* shoulder width, smoothed; 0 = not yet seen */
    clap_state clap;
    wave_state wave[2];
};

/* Integer millimetres of a Q16.16 position component, rounded down. */
static inline int32_t judge_mm(cub_q16 v)
{
    return (int32_t)(v >> 16);
}

/* |a - b| in whole millimetres. */
int32_t judge_dist_mm(cub_vec3 a, cub_vec3 b);

/* Append an event to out (dropped when full) and log it. */
void judge_emit(cub_judge *j, cub_judge_out *out, const cub_judge_event *e);

/* judge_gesture.c: claps and waves of one OK frame; reset when not seen. */
void judge_gestures(cub_judge *j, int64_t t_us, const cub_track_skeleton *s, cub_judge_out *out);
void judge_gestures_reset(cub_judge *j);

/* What the tracker said of each feature's joints in a frame: bit f of
 * found when all of feature f's joints were found (not guessed), of
 * confident when all were confident (cub/track.h CUB_TRACK_CONFIDENT). */
typedef struct judge_sure {
    uint32_t found, confident;
} judge_sure;

/* judge_reps.c: the repetitions' verdicts for one frame; f NULL when the
 * frame is not OK; too_close: the child stands too close this frame. */
void judge_reps_frame(cub_judge *j, int64_t t_us, const cub_fuzzy_frame *f,
                      const judge_sure *sure, int too_close, cub_judge_out *out);

#endif

/* coach — the bear's behaviour (SEEDS.md § 000 "System", ARCHITECTURE.md
 * "Coach states") as a deterministic state machine, and the music-sync rule
 * (SEEDS.md § 000 "Music sync").
 *
 * Input: the loop's events (cub_event: START/STOP, clap, verdict, player,
 * clip done, music tag, song end) through cub_coach_handle, and the passing
 * of time through cub_coach_tick; both take the audio clock's position in
 * the song (music_ms, CUB_COACH_NO_MUSIC when nothing plays). The coach
 * keeps its deadlines (attract, doze) in its own state, so it runs and is
 * tested without a loop. Output: after every call, `actions` holds what the
 * app must do now, in order: play a clip, change the playing clip's speed,
 * start or stop the music, show a hint, and each state change. Every
 * action is also written to the event log, e.g.
 *   t=12.433 coach state from=dance to=correct reason=wrong move=3 rep=1
 *   t=12.433 coach request clip=head_shake speed=1.000 loop=0 reason=correct
 *   t=14.100 coach sync move=4 music_ms=14090 tag_ms=14100 speed=0.994 rep=0 rate=1.000
 * Music sync: the dance's song time is known at a move's first frame (its
 * music tag) and at the start of every repetition (tag + span * rep / reps).
 * There the coach compares it with the audio clock and sets the speed of
 * what plays next with cub_coach_sync_speed, aiming at the next tag (the
 * next repetition's start; after the last one, the next move's tag less
 * its lead_ms), using the music's rate against the loop clock as measured
 * since the music started, so a sound card 5 % slow is followed rather
 * than chased. The music plays on through a
 * correction; the dance resumes at the repetition nearest to the music.
 * Speeds are Q16.16, times microseconds (loop) or milliseconds (song).
 * Integer only, no allocation: the same events give the same actions.
 */
#ifndef CUB_COACH_H
#define CUB_COACH_H

#include <stdbool.h>
#include <stdint.h>

#include "cub/err.h"
#include "cub/fx.h"
#include "cub/loop.h"

#define CUB_COACH_NO_MUSIC (-1)  /* music_ms when no music plays */
#define CUB_COACH_MAX_ACTIONS 16 /* actions one call can produce (a few in practice) */

typedef enum cub_coach_state {
    CUB_COACH_IDLE = 0, /* waiting for a clap or START */
    CUB_COACH_WAKE,     /* the wake_up clip plays, then the song starts */
    CUB_COACH_DANCE,    /* leading the song, move by move */
    CUB_COACH_CORRECT,  /* correcting clip, then the move again, slower (watched,
                           not judged); the attempt after it is danced again */
    CUB_COACH_WORRIED,  /* several misses in a row: worried-but-cute, never scold */
    CUB_COACH_ATTRACT,  /* nobody interacted for a while: wave */
    CUB_COACH_DOZE,     /* nobody for longer: doze */
    CUB_COACH_CHEER,    /* the song ended */
    CUB_COACH_PAUSED,   /* mid-song, music paused: the camera is gone ("can't see you"),
                           or the child ("where are you?") */
    CUB_COACH_STATE_COUNT
} cub_coach_state;

/* Why an action happened; printed as reason=... in the log. */
typedef enum cub_coach_reason {
    CUB_COACH_WHY_INIT = 0,
    CUB_COACH_WHY_START, /* START button */
    CUB_COACH_WHY_CLAP,
    CUB_COACH_WHY_STOP,    /* STOP button */
    CUB_COACH_WHY_WOKE,    /* the wake_up clip ended */
    CUB_COACH_WHY_INTRO,   /* waiting for the first move's music tag */
    CUB_COACH_WHY_MOVE,    /* a move begins */
    CUB_COACH_WHY_REP,     /* the next repetition of the move */
    CUB_COACH_WHY_WRONG,   /* a wrong verdict */
    CUB_COACH_WHY_RIGHT,   /* a right verdict */
    CUB_COACH_WHY_CORRECT, /* the correcting clip (head shake, watch me) */
    CUB_COACH_WHY_DEMO,    /* the move demonstrated again, slower */
    CUB_COACH_WHY_MISSES,  /* N wrong verdicts in a row */
    CUB_COACH_WHY_WORRIED, /* the worried clip */
    CUB_COACH_WHY_CALMED,  /* the worried clip ended */
    CUB_COACH_WHY_RESUME,  /* back to the dance after a correction */
    CUB_COACH_WHY_SYNC,    /* speed set to follow the music */
    CUB_COACH_WHY_OUTRO,   /* all moves done, the music plays on */
    CUB_COACH_WHY_SONG_END,
    CUB_COACH_WHY_CHEER,   /* the cheer clip */
    CUB_COACH_WHY_CHEERED, /* the cheer clip ended */
    CUB_COACH_WHY_QUIET,   /* no interaction for attract_after / doze_after */
    CUB_COACH_WHY_PLAYER,  /* a player came into view or left */
    CUB_COACH_WHY_IDLE,    /* the idle clip */
    CUB_COACH_WHY_CAMERA,  /* the camera went or came back */
    CUB_COACH_WHY_MOVED_ON, /* the music left the corrected move: dance on with it */
    CUB_COACH_WHY_AWAY,     /* the child has been out of view mid-song for a while */
    CUB_COACH_WHY_WATCHED,  /* the slower demonstration was watched: the attempt now */
    CUB_COACH_WHY_GROOVE,   /* a span no move teaches: the bear's own dance to the music */
    CUB_COACH_WHY_COUNT
} cub_coach_reason;

typedef enum cub_coach_action_kind {
    CUB_COACH_ACT_CLIP = 1,    /* play clip at speed_q16, looping or once */
    CUB_COACH_ACT_SPEED,       /* set the playing clip's speed to speed_q16 */
    CUB_COACH_ACT_MUSIC_START, /* start the song from its beginning */
    CUB_COACH_ACT_MUSIC_STOP,
    CUB_COACH_ACT_HINT,  /* show hint: a move index or one of CUB_COACH_HINT_* */
    CUB_COACH_ACT_STATE, /* the state changed from -> to */
    CUB_COACH_ACT_MUSIC_PAUSE,  /* hold the music where it is (its clock stops too) */
    CUB_COACH_ACT_MUSIC_RESUME, /* go on from there */
} cub_coach_action_kind;

#define CUB_COACH_HINT_NONE (-1)        /* clear the hint */
#define CUB_COACH_HINT_COME_CLOSER (-2) /* nobody in view: "come closer" */
#define CUB_COACH_HINT_CANT_SEE (-3)    /* the camera is gone: "I can't see you" */
#define CUB_COACH_HINT_WHERE (-4)       /* the child left mid-song: "Where are you?" */
#define CUB_COACH_HINT_STEP_BACK (-5)   /* the child stands too close: "Step back" */

typedef struct cub_coach_action {
    int32_t kind;      /* cub_coach_action_kind */
    int32_t reason;    /* cub_coach_reason */
    int32_t clip;      /* ACT_CLIP: index in the clip library */
    cub_q16 speed_q16; /* ACT_CLIP, ACT_SPEED */
    bool loop;         /* ACT_CLIP: loop until the next request, else play once
                          (the player then posts CUB_EV_CLIP_DONE) */
    int32_t hint;      /* ACT_HINT */
    int32_t fault;     /* ACT_HINT with a move: what to fix in it (a wrong verdict's
                          cub_judge_fault_code, shown instead of the move's own
                          words while its correction runs); 0 = the move's words */
    int32_t from, to;  /* ACT_STATE: cub_coach_state */
    int32_t move, rep; /* the song position concerned, from 0; -1 when none */
} cub_coach_action;

/* One move of the song program (no parsing here: the app fills these). */
typedef struct cub_coach_move {
    int32_t clip;      /* index in the clip library */
    int32_t reps;      /* repetitions in a row, >= 2 (seed 000, Choreography) */
    cub_q16 speed_q16; /* playback speed at which one repetition lasts
                          span_ms / reps of song; 0 = 1.0 */
    int32_t tag_ms;    /* music time of the move's first frame */
    int32_t span_ms;   /* music time of all its repetitions; the next tag is
                          at tag_ms + span_ms or later */
    int32_t lead_ms;   /* optional: song time by which the move before should
                          end early so that the route into this one (bridge
                          frames, a tween) shows this move's content of
                          tag_ms on time: the route's length less the content
                          it skips (it may enter past the first frame), so it
                          may be negative. Used when the move follows the one
                          before without a gap; 0 = none */
    int32_t rep_lead_ms; /* optional: the same for the move's own next
                            repetition (from its last frame to its first
                            frames); 0 = none */
    int32_t entry_lead_ms; /* optional: the same for the move begun from
                              where the player is now, read while the coach
                              waits for its tag after an intro or a gap, so
                              that it begins that much early; whoever plays
                              the coach keeps it up to date (the director,
                              before each call); 0 = none */
} cub_coach_move;

/* A span of the song no move teaches (the intro, a gap, free bars, the
 * outro), danced by a clip made for it whose frame 0 is the span's start
 * on the music clock (issue 23, docs/groove.md "The box"). Untaught: never
 * a move, so never judged, corrected or hinted. */
typedef struct cub_coach_groove {
    int32_t clip;    /* index in the clip library (the table's clips) */
    int32_t tag_ms;  /* music time of the clip's first frame */
    int32_t span_ms; /* music time the clip lasts */
    int32_t beats;   /* optional: the meter's beats in the span (beat k starts at
                        tag_ms + span_ms * k / beats); 0: a span joined late is
                        not joined */
    int32_t entry_lead_ms; /* optional: how long the bridge into the clip takes
                              from where the player is now (the director keeps it
                              up to date, as a move's entry_lead_ms), so that a
                              span joined late is on screen at its beat; 0 = none */
} cub_coach_groove;

/* A groove span is joined at once when the coach finds itself at most this
 * late into it (its span began in the last tick, or a correction ended
 * just after). Later (after a correction, a pause) it is joined at the
 * first of its beats that the bridge into it (entry_lead_ms) can still
 * reach, with at least one beat of the span left after it; the idle clip
 * plays until then. Either way the clip enters at the music's frame. */
#define CUB_COACH_GROOVE_LATE_MS 500

/* The coach's own clips (indices in the clip library). No defaults: see
 * cub_coach_roles_by_name to find them by their names. */
typedef struct cub_coach_roles {
    int32_t idle, wake_up, attract, doze;
    int32_t head_shake, watch_me; /* the correcting clips, used in turn */
    int32_t worried, cheer;
} cub_coach_roles;

/* Zero-initialised tunables take the defaults shown. */
typedef struct cub_coach_desc {
    const cub_coach_move *moves; /* required, move_count of them */
    int32_t move_count;
    const cub_coach_groove *grooves; /* optional: groove_count spans, in music order;
                                        danced instead of the idle clip while the
                                        coach waits for a move's tag or the end */
    int32_t groove_count;
    cub_coach_roles roles;         /* required */
    int32_t clip_count;            /* clips in the library (> every index) */
    const char *const *clip_names; /* optional: clip_count names for the log */
    cub_log *log;                  /* optional: where lines go */
    uint32_t attract_after_ms;     /* default 20000: no interaction -> attract */
    uint32_t doze_after_ms;        /* default 60000 (> attract_after_ms) -> doze */
    uint32_t worried_after;        /* default 3 wrong verdicts in a row */
    cub_q16 demo_speed_q16;        /* default 0.7: the slower demonstration */
    cub_q16 sync_bound_q16;        /* default 0.15: speed stays in 1 +- bound */
} cub_coach_desc;

typedef struct cub_coach {
    cub_coach_desc desc;  /* with defaults filled in */
    int32_t state;        /* cub_coach_state */
    int32_t phase;        /* a step inside the state (coach.c) */
    int32_t move, rep;    /* the song position being danced or corrected */
    int32_t clip;         /* the clip last requested */
    int32_t groove;       /* the groove span last requested while waiting; -1 none */
    int32_t join_groove;  /* a span the music is in, joined late: which (-1 none) ... */
    int32_t join_ms;      /* ... and the beat it is joined on (-1: none left) */
    cub_q16 speed_q16;    /* ... at this speed */
    cub_q16 sync_q16;     /* music-sync factor applied to the move's speed */
    cub_q16 rate_q16;     /* music ms per loop ms, as measured */
    int32_t misses;       /* wrong verdicts in a row */
    int32_t paused_phase; /* the dance's phase when the song paused */
    int32_t paused_for;   /* why it paused: CUB_COACH_WHY_CAMERA or _AWAY */
    uint32_t corrections; /* correcting clips played (they alternate) */
    bool music_on, tag_pending, player_in_view;
    bool too_close; /* out of view because the child stands too close (CUB_EV_PLAYER b = 1) */
    bool show_again; /* correcting the move just left: demonstrate it once */
    int32_t hint; /* the hint last shown */
    int32_t fault; /* ... and its fault (0: none) */
    int32_t fix;   /* the fault the correction under way is about (0: none), shown
                      again when the child comes back into view */
    int64_t now_us, quiet_since_us, state_since_us;
    int64_t away_since_us;  /* the child last left the view (or the song began) */
    int64_t music_start_us; /* loop time the music was started */
    int64_t anchor_us;      /* first loop time the music clock was seen moving */
    int32_t anchor_ms;      /* ... and its song time then (-1: not yet) */
    cub_coach_action actions[CUB_COACH_MAX_ACTIONS]; /* this call's output */
    int32_t action_count;
    uint32_t actions_dropped; /* over CUB_COACH_MAX_ACTIONS (never expected) */
} cub_coach;

/* Check desc, fill defaults, start idle at now_us. The actions then hold
 * the idle clip's request. CUB_ERR_ARG for a NULL pointer, no moves (a
 * groove song, no moves but groove spans, is fine: it dances them), a move
 * with reps < 2, span_ms <= 0, tags that go back or overlap, a clip or
 * role index outside [0, clip_count), or doze_after_ms <= attract_after_ms. */
cub_err cub_coach_init(cub_coach *c, const cub_coach_desc *desc, int64_t now_us);

/* React to one event at ev->t_us (earlier times than the last call are
 * taken as the last call's time). What the coach reads from it:
 *   BUTTON_DOWN a = START (wake when resting) / STOP (idle, from anywhere)
 *   CLAP        wake when resting (idle, attract, doze)
 *   VERDICT     a = move, b = 1 right / 0 wrong, c = a wrong one's fault
 *               (shown as the hint through the correction it starts, until
 *               the dance resumes; 0 = the move's own words stay);
 *               during the slower demonstration: watched, not acted on
 *               (logged "coach watched"; the attempt after it counts);
 *               about another move: ignored,
 *               except a wrong one about the move just left while the next
 *               one's first repetition plays or is waited for (the last
 *               repetition's window closes a beat late): that move is
 *               corrected, then the dance resumes where the music is
 *   PLAYER      a = 0 shows "come closer", a = 1 takes it back; a child out
 *               of view mid-song for CUB_COACH_AWAY_PAUSE_MS pauses the song
 *               ("where are you?", as CAMERA a = 0 does) until a = 1
 *               resumes it where the music is
 *   CLIP_DONE   a = clip; only the clip last requested counts
 *   MUSIC_TAG   a = move, b = song ms of the frame reached (the tag of the
 *               repetition begun, or later if the player entered past its
 *               first frame); acted on once per repetition begun, with
 *               music_ms the audio clock: the music sync
 *   SONG_END    cheer
 *   CAMERA      a = 0 mid-song (dance, correct, worried): pause the music and
 *               the dance, show "can't see you"; a = 1 while paused: resume
 *               the music and the dance where the music is (as after a
 *               correction). Outside a song: ignored
 * Buttons, claps, verdicts and a player arriving count as interaction (they
 * restart the attract/doze countdown), except verdicts while nobody is in
 * view: those are set aside (no one to correct), so a child who walked
 * away brings attract_after_ms later the attract and the doze, as idle.
 * Other events are ignored (CUB_OK).
 * CUB_ERR_ARG for NULL; CUB_ERR_RANGE for a verdict or music tag naming a
 * move outside the song (nothing changes then). Moves and reps count from 0. */
cub_err cub_coach_handle(cub_coach *c, const cub_event *ev, int32_t music_ms);

/* Let time pass: the first move after the song's intro, attract, doze.
 * Call every tick. CUB_ERR_ARG for NULL. */
cub_err cub_coach_tick(cub_coach *c, int64_t now_us, int32_t music_ms);

/* The music-sync rule. The dance is at song time tag_ms (the tag of the
 * frame just reached) while the audio clock reads music_ms; the dance has
 * span_ms of song left to its target tag, and the music runs at rate_q16
 * music ms per loop ms. The speed factor that makes the dance reach its
 * target tag together with the music:
 *     speed = span_ms * rate / (span_ms + tag_ms - music_ms)
 * clamped to [1 - bound, 1 + bound]; music behind the tag gives < 1 (play
 * slower), ahead gives > 1. rate_q16 <= 0 means 1.0; bound_q16 <= 0 means
 * 0.15; span_ms <= 0 gives 1.0; music already past the target gives 1+bound. */
cub_q16 cub_coach_sync_speed(int32_t tag_ms, int32_t music_ms, int32_t span_ms, cub_q16 rate_q16,
                             cub_q16 bound_q16);
/* The bound cub_coach_sync_speed applies for bound_q16: 0.15 for <= 0,
 * at most 0.9 (the dance never stands still). */
cub_q16 cub_coach_sync_bound(cub_q16 bound_q16);

/* How long a child may be out of view mid-song before the song pauses and
 * the bear asks "Where are you?". The judge already waits a second of
 * frames without the child before it says so, and "Come closer!" shows at
 * once; pausing the music is the bigger step, so a child who only stepped
 * aside (a toy, a turn the camera lost) has about two bars of Twinkle
 * (4 s at 120 bpm) to come back with the music still playing. The longer
 * absence that ends the song is the config's attract_after (20 s). */
#define CUB_COACH_AWAY_PAUSE_MS 4000

/* Fill roles from clip names: idle, wake_up, wave (attract), doze,
 * head_shake, watch_me, worried, cheer. CUB_ERR_ARG for NULL or count <= 0;
 * CUB_ERR_FORMAT if a role's clip is missing (roles partly filled). */
cub_err cub_coach_roles_by_name(const char *const *names, int32_t count, cub_coach_roles *roles);

/* "idle", "dance", ...; "correct" ...; "?" when out of range. */
const char *cub_coach_state_name(int32_t state);
const char *cub_coach_reason_name(int32_t reason);

#endif

/* director — the tick's policy (SEEDS.md § 000 "Switching", "Music sync"):
 * owns the coach (what the bear should do), the bridge player (how it gets
 * there) and the judge's repetition windows (what the child should do), and
 * decides when and how each of the coach's requests is carried out.
 *
 * Input: the loop's events through cub_director_handle (buttons, verdicts,
 * claps, presence, camera, clip ends, music tags, song end), the passing of
 * time through cub_director_advance (the player moves on; its clip ends and
 * the music tags of the moves it enters are posted to the loop, for the
 * coach) and cub_director_tick (the coach's deadlines). Every call takes
 * the music clock in song ms (CUB_COACH_NO_MUSIC when nothing plays).
 * Output: after handle and tick, out[] holds what only the app can do, in
 * order: start, pause, resume or stop the music, show a hint. The rest the
 * director carries out itself and logs, e.g.
 *   t=12.433 bridge plan to=head_shake steps=1 wait_frames=0 via=direct
 *   t=12.433 bridge substitute requested=head_shake played=watch_me reason=sooner
 *   t=14.100 music tag move=4 tag_ms=14100 music_ms=14090
 *
 * The policy:
 * - A move (its start, a repetition, a resume, a slower demonstration) is
 *   entered at one of its first start_frames frames (desc), so it
 *   keeps its music time; a correction at any frame of its clip's front
 *   half that is close enough (the quickest way in), and by the other
 *   correcting clip when the one asked for is not on screen within
 *   react_frames (desc) and the other is sooner; when neither is, at the
 *   closest frame of the chosen one's front half reached within
 *   react_frames, beyond the threshold (logged as bridge reach: the blend
 *   covers the distance, a correction does not wait); anything else by the
 *   quickest switch. No route at all: a cut, logged.
 * - Leads: the song ms by which a move is asked for before its tag so that
 *   the route into it (bridge frames, a tween, less the content it skips)
 *   shows the tag's frame on time: planned at init from the last frame of
 *   the move before (lead_ms) and of itself (rep_lead_ms), and before each
 *   coach call from where the player is now for a move after an intro or a
 *   gap (entry_lead_ms).
 * - Searched routes (the table's, docs/join.md "Routes") play their C
 *   between the two moves, and that time must come out of the move
 *   before: its last repetition ends early by the lead, at most 1 + the
 *   coach's sync bound faster. A move that follows the one before at once
 *   enters by its route only when the route's lead is within half of what
 *   that bound can take from the repetition (the other half follows the
 *   music's clock), or no longer than the lead without it; else its lead
 *   and its request both go without routes (a `music route` line says
 *   which). A move after a gap takes a route freely (the wait pays for it:
 *   entry_lead_ms is planned with it); a resume, entered on the music with
 *   no lead, never does.
 * - Windows: a repetition of a move opens a judge window from its request
 *   for as long as its clip plays at its speed, plus one beat for a late
 *   child; anything else the coach asks for closes the open ones. Each
 *   window carries the coach's key moment: when the route into the clip
 *   and the clip at its speed first show every key of the move together
 *   (found at init in the clip's own fuzzy frames, a `judge keys` line per
 *   move), so that the judge can say wrong inside the repetition.
 * - Music tags: entering the clip of the move being danced, the song time
 *   of the frame shown (the move's tag + the repetitions done + the part of
 *   this one the player entered past).
 * - Scripted verdicts (a timeline) about move -1 speak of the move being
 *   taught now (cub_director_scripted; handle applies it too).
 * Times: loop us, song ms; speeds Q16.16. Integer only; memory: the
 * player's scratch in caller memory (cub_director_mem_size), nothing after
 * init. The director points its coach into itself: do not move it. */
#ifndef CUB_DIRECTOR_H
#define CUB_DIRECTOR_H

#include <stddef.h>
#include <stdint.h>

#include "cub/bridge.h"
#include "cub/coach.h"
#include "cub/err.h"
#include "cub/judge.h"
#include "cub/loop.h"

#define CUB_DIRECTOR_MAX_MOVES 64
#define CUB_DIRECTOR_MAX_GROOVES (3 * CUB_DIRECTOR_MAX_MOVES + 1) /* a song's spans, at most */
#define CUB_DIRECTOR_MAX_OUT CUB_COACH_MAX_ACTIONS
#define CUB_DIRECTOR_MAX_PLAYER_EVENTS 16 /* per advance; more are dropped */
#define CUB_DIRECTOR_REACT_FRAMES 5 /* default react_frames: a correction begins within 167 ms */

/* A move's key points for the judge. */
typedef struct cub_director_keys {
    int32_t count; /* 1..CUB_JUDGE_MAX_KEYS; 0: the move is not judged */
    cub_judge_key key[CUB_JUDGE_MAX_KEYS];
} cub_director_keys;

typedef struct cub_director_desc {
    const cub_bridge_table *table; /* required, finished: the coach's clips */
    /* Required: the coach's moves, roles, names, log and tunables. The
     * moves' leads are the director's to plan: what is given is ignored. */
    cub_coach_desc coach;
    const cub_director_keys *keys; /* optional: coach.move_count of them */
    int32_t bpm;                   /* the song's tempo: a beat of allowance; 0 = none */
    const char *song_name;         /* for the log; NULL = "" */
    int32_t song_length_ms;        /* for the log */
    cub_judge *judge;              /* optional: told what is taught */
    /* Zero-initialised tunables take the defaults shown. */
    int32_t start_frames; /* default 4: a move's "beginning", its first frames */
    /* default 5: a correction must be on screen within 6 ticks (200 ms); a
     * plan counts whole frames from the next one, so keep a tick for the
     * frame under way. */
    int32_t react_frames;
} cub_director_desc;

typedef enum cub_director_do {
    CUB_DIRECTOR_MUSIC_START = 1, /* start the song from its beginning */
    CUB_DIRECTOR_MUSIC_STOP,
    CUB_DIRECTOR_MUSIC_PAUSE,  /* hold the music where it is (its clock too) */
    CUB_DIRECTOR_MUSIC_RESUME, /* go on from there */
    CUB_DIRECTOR_HINT,         /* show hint: a move index or a CUB_COACH_HINT_* */
} cub_director_do;

typedef struct cub_director_out {
    int32_t what; /* cub_director_do */
    int32_t hint; /* HINT */
    int32_t fault; /* HINT: what to fix in the move (cub_coach_action fault); 0 none */
} cub_director_out;

typedef struct cub_director {
    cub_director_desc desc;
    cub_coach coach;
    cub_bridge_player player;
    cub_coach_move moves[CUB_DIRECTOR_MAX_MOVES]; /* the coach's, with their leads */
    cub_coach_groove grooves[CUB_DIRECTOR_MAX_GROOVES]; /* the coach's, with their entry leads */
    bool route_in[CUB_DIRECTOR_MAX_MOVES]; /* the move, asked for at the end of the one
                                              before, may enter by the table's searched
                                              route: its lead_ms was planned through it */
    int64_t now_us;                 /* where the player's time stands */
    int played_clip, requested_clip; /* a correction played in place of another */
    bool music_on, music_paused;    /* as asked of the app */
    int64_t music_start_us;         /* the time the music was asked to start at */
    int lead_clip, lead_loop;       /* the player's state the entry leads are for */
    int64_t lead_pos_q16;
    int32_t key_frame[CUB_DIRECTOR_MAX_MOVES]; /* the bear's key moment in each move's clip; -1 */
    bool mirror_wrong[CUB_DIRECTOR_MAX_MOVES]; /* the keys' mirror is a mistake (never shown) */
    uint64_t other_moves[CUB_DIRECTOR_MAX_MOVES]; /* bit o: move o's keys, never shown in this
                                                     move's clip, are a mistake here */
    uint32_t switch_count;          /* the player's switches so far ... */
    cub_bridge_step last_switch;    /* ... and the last (for a measure of what is shown) */
    cub_director_out out[CUB_DIRECTOR_MAX_OUT]; /* this call's output */
    int32_t out_count;
} cub_director;

/* Bytes of scratch memory the director needs (its player's); 0 without a table. */
size_t cub_director_mem_size(const cub_director_desc *desc);
/* Start the coach idle at now_us, its idle clip playing, and plan every
 * move's leads (a `music lead` line each); desc's tunables get their
 * defaults in d->desc. CUB_ERR_ARG for NULL, no table, a negative tunable,
 * more than CUB_DIRECTOR_MAX_MOVES moves or CUB_DIRECTOR_MAX_GROOVES grooves, or what cub_coach_init refuses;
 * CUB_ERR_NOMEM for too little memory. */
cub_err cub_director_init(cub_director *d, const cub_director_desc *desc, void *mem,
                          size_t mem_size, int64_t now_us);
/* One loop event at ev->t_us: the coach reacts, its requests are carried
 * out, out[] holds the rest. Errors as cub_coach_handle. */
cub_err cub_director_handle(cub_director *d, const cub_event *ev, int32_t music_ms);
/* Once per tick after the events: the coach's deadlines. Output as handle. */
cub_err cub_director_tick(cub_director *d, int64_t now_us, int32_t music_ms);
/* At the start of each loop step, before its events: the player moves on
 * to now_us, logging its switches and clip ends, and posts to loop the
 * clip ends (under the name the coach asked for) and the music tags (with
 * music_ms, the clock read after the music moved on) for the coach. */
cub_err cub_director_advance(cub_director *d, cub_loop *loop, int64_t now_us, int32_t music_ms);
/* What a scripted judge's event means: a verdict about move -1 is about
 * the move being taught now (move 0 before the dance, or when d is NULL). */
cub_event cub_director_scripted(const cub_director *d, const cub_event *ev);

#endif

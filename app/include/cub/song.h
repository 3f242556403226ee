/* song — a song's choreography (assets/songs/NAME.song.xml): which MIDI file
 * plays, its tempo and meter, and the kid moves the coach leads, in order,
 * each on a span of whole bars (SEEDS.md § 000, "Choreography").
 *
 *   <song version="1" name="Twinkle Twinkle Little Star" midi="twinkle.mid"
 *         faults="faults.words" bpm="96" meter="4/4" bars="40">
 *       <move clip="clap" reps="5" bar="15" bars="4" keys="RHE=true LHE=true"
 *             hint="Clap with me!" icon="clap"/>
 *       <free bar="19" bars="4"/>
 *   </song>
 *
 * faults (optional) names the words said when a key of a move fails
 * (cub/faults.h), a file beside the song like the MIDI; the app reads it.
 * bpm counts quarter notes (as MIDI does); meter is N/D, a bar lasting N
 * D-th notes. bar is where a move starts (1-based), bars how long it lasts.
 * keys are the move's key points for the judge: one or two (at most
 * CUB_SONG_MAX_KEYS) fuzzy features of cub/fuzzy.h that must reach a set.
 * <free bar="B" bars="N"/> marks bars where no move is taught and the bear
 * dances to the song's own notes (issue 23, docs/groove.md); so do the
 * bars no <move> covers (the intro, the gaps, the end): cub_song_spans
 * lists them all. <move>s and <free>s come in bar order and never overlap.
 * A song with no <move> at all is a groove song: it dances its whole length.
 *
 * Reading validates against the clip library the coach dances from and
 * stops at the first problem with "file:line: what": unknown element or
 * attribute, a missing one, a bad number, a clip the library lacks or that
 * is not a kid move (kind "dance"), reps < 2, a span that overlaps the
 * previous move or <free> or passes the song's end, a span the clip cannot fill at a
 * speed within ±CUB_SONG_SPEED_PCT % of 1 (reps × clip length vs the span),
 * fewer than CUB_SONG_MIN_MOVES (unless there is no move at all) or more than
 * CUB_SONG_MAX_DISTINCT different moves, an unknown key feature or set. Times are exact integers (µs). */
#ifndef CUB_SONG_H
#define CUB_SONG_H

#include <stdint.h>

#include "cub/err.h"
#include "cub/fuzzy.h"
#include "cub/io.h"
#include "cub/pack.h"

#define CUB_SONG_MAX_MOVES 64 /* moves in order (a clip may come back) */
#define CUB_SONG_MIN_MOVES 8  /* different moves a song uses, per the seed */
#define CUB_SONG_MAX_DISTINCT 12
#define CUB_SONG_MIN_REPS 2 /* each move at least twice in a row */
#define CUB_SONG_MAX_KEYS 4
#define CUB_SONG_SPEED_PCT 15 /* the coach's own ±15 % catch-up range */
#define CUB_SONG_TEXT_LEN 128
#define CUB_SONG_MAX_FREE 64 /* <free> spans */
#define CUB_SONG_MAX_SPANS (2 * CUB_SONG_MAX_MOVES + CUB_SONG_MAX_FREE + 1)

typedef struct cub_song_key {
    cub_fuzzy_feature feature;
    int set; /* index of the set (cub_fuzzy_set_name) the feature must reach */
} cub_song_key;

typedef struct cub_song_move {
    char clip[CUB_MOTION_NAME_LEN];
    int clip_index;           /* in the library the song was read with */
    int reps;                 /* times the clip plays in a row, >= 2 */
    int bar, bars;            /* span: starts at bar (1-based), lasts bars */
    int64_t start_us, end_us; /* the span in music time from the song's start */
    int speed_permille;       /* reps × clip length / span length, ×1000 */
    int key_count;
    cub_song_key keys[CUB_SONG_MAX_KEYS];
    char hint[CUB_SONG_TEXT_LEN]; /* shown under the coach */
    char icon[32];                /* icon name: [a-z0-9_]+ */
    int line;                     /* where it is in the file, for later messages */
} cub_song_move;

/* Bars the song marks free (<free>): the bear grooves, nobody is judged. */
typedef struct cub_song_free {
    int bar, bars;
    int64_t start_us, end_us;
    int line;
} cub_song_free;

/* What a stretch of the song holds (cub_song_spans). */
typedef enum cub_song_span_kind {
    CUB_SONG_SPAN_MOVE = 0, /* a taught move: index = its move */
    CUB_SONG_SPAN_INTRO,    /* before the first move (or the whole of a groove song) */
    CUB_SONG_SPAN_GAP,      /* unmarked bars between two moves */
    CUB_SONG_SPAN_FREE,     /* a <free> span: index = its free */
    CUB_SONG_SPAN_OUTRO,    /* after the last move: the cheer's music */
} cub_song_span_kind;

typedef struct cub_song_span {
    int kind;  /* cub_song_span_kind */
    int index; /* the move or free, -1 for intro, gap, outro */
    int bar, bars;
    int64_t start_us, end_us;
} cub_song_span;

typedef struct cub_song {
    char name[CUB_SONG_TEXT_LEN];
    char midi[256];           /* as written (relative to the song file) */
    char midi_path[512];      /* resolved: the song file's folder + midi */
    char faults[256];         /* optional: the fault words table (cub/faults.h) as written */
    char faults_path[512];    /* resolved like midi_path; "" without faults */
    int bpm;                  /* quarter notes per minute, 30..300 */
    int meter_num, meter_den; /* N/D, D in {2, 4, 8, 16} */
    int bars;                 /* the song's length */
    int move_count;
    int distinct_moves;
    cub_song_move moves[CUB_SONG_MAX_MOVES];
    int free_count;
    cub_song_free frees[CUB_SONG_MAX_FREE];
} cub_song;

/* Read and validate a song file against lib. midi_path is resolved
 * relative to the file's folder. Fails with CUB_ERR_FORMAT (or IO) and diag. */
cub_err cub_song_load(const char *path, const cub_library *lib, cub_song *out, cub_diag *diag);
/* The same from memory; name is the file name used in diagnostics and to
 * resolve the MIDI path. */
cub_err cub_song_parse(const char *text, size_t len, const char *name, const cub_library *lib,
                       cub_song *out, cub_diag *diag);

/* Music time of the start of bar (1-based; bars + 1 = the song's end), µs,
 * exact: (bar - 1) × meter_num × 240000000 / (meter_den × bpm), floored. */
int64_t cub_song_bar_us(const cub_song *song, int bar);
/* The song's length, µs (cub_song_bar_us(song, bars + 1)). */
int64_t cub_song_length_us(const cub_song *song);
/* The move playing at music time t_us, or -1 in a gap or past the end. */
int cub_song_move_at(const cub_song *song, int64_t t_us);

/* The whole song as consecutive spans in bar order, from bar 1 to the
 * end: moves, <free>s and the unmarked bars between (intro, gap, outro).
 * Every span but a MOVE is grooved. Returns the count (<= max; at most
 * CUB_SONG_MAX_SPANS for any song that reads). */
int cub_song_spans(const cub_song *song, cub_song_span *out, int max);
/* Spans the bear grooves (every kind but MOVE): their count in out. */
int cub_song_groove_spans(const cub_song *song, cub_song_span *out, int max);
/* The span kind's name for logs: "move", "intro", "gap", "free", "outro". */
const char *cub_song_span_name(int kind);

#endif

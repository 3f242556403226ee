/* song — a song's choreography (assets/songs/NAME.song.xml): which MIDI file
 * plays, its tempo and meter, and the kid moves the coach leads, in order,
 * each on a span of whole bars (SEEDS.md § 000, "Choreography").
 *
 *   <song version="1" name="Twinkle Twinkle Little Star" midi="twinkle.mid"
 *         faults="faults.words" bpm="96" meter="4/4" bars="40">
 *       <move clip="clap" reps="5" bar="15" bars="4" keys="RHE=true LHE=true"
 *             hint="Clap with me!" icon="clap"/>
 *   </song>
 *
 * faults (optional) names the words said when a key of a move fails
 * (cub/faults.h), a file beside the song like the MIDI; the app reads it.
 * bpm counts quarter notes (as MIDI does); meter is N/D, a bar lasting N
 * D-th notes. bar is where a move starts (1-based), bars how long it lasts.
 * keys are the move's key points for the judge: one or two (at most
 * CUB_SONG_MAX_KEYS) fuzzy features of cub/fuzzy.h that must reach a set.
 *
 * Reading validates against the clip library the coach dances from and
 * stops at the first problem with "file:line: what": unknown element or
 * attribute, a missing one, a bad number, a clip the library lacks or that
 * is not a kid move (kind "dance"), reps < 2, a span that overlaps the
 * previous move or passes the song's end, a span the clip cannot fill at a
 * speed within ±CUB_SONG_SPEED_PCT % of 1 (reps × clip length vs the span),
 * fewer than CUB_SONG_MIN_MOVES or more than CUB_SONG_MAX_DISTINCT different
 * moves, an unknown key feature or set. Times are exact integers (µs). */
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

#endif

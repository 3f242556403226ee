/* groove_tool — what cubtool groove and groove-eval share: a MIDI file to
 * a seed-001 plan (cub/groove.h), the bear's whole-song clip on the music
 * clock, and the song's beats through the tempo map. */
#ifndef CUB_GROOVE_TOOL_H
#define CUB_GROOVE_TOOL_H

#include "cub/groove.h"
#include "cub/music.h"

typedef struct groove_args {
    const char *path;
    int melody, rhythm, window; /* -1, -1, 0: the song decides */
    char set;                   /* 'a' or 'b' */
} groove_args;

typedef struct groove_song {
    cub_midi_groove midi;
    cub_groove_store mem;
    cub_groove_pick pick;
    cub_groove_plan plan;
    cub_groove_cost cost;
    int seg_count;
    double plan_ms; /* notes, DP, keys, handles, turns: one run, a figure */
} groove_song;

/* Read and plan; 0, or 1 after saying on stderr what is wrong with which
 * file ("cubtool <who>: FILE: ..."). Free with groove_song_free either way. */
int groove_song_load(const groove_args *a, const char *who, groove_song *s);
void groove_song_free(groove_song *s);

/* The bear (assets/bear/bear.xml)'s skeleton; 0 or 1 with the file's problem. */
int groove_bear(cub_skeleton *skel, const char *who);

/* The whole song on the bear at fps frames a second, from 0 to the song's
 * end; clip->rot etc. malloc'ed into *mem (free it). 0 or 1. */
int groove_song_clip(const groove_song *s, const cub_groove_rig *rig, int fps, cub_clip *clip,
                     void **mem);

/* The meter's beats through the tempo map, [0, end] in microseconds; a
 * malloc'ed array (free it) and its length in *count; NULL when out of memory. */
int64_t *groove_beats_us(const cub_groove_song *song, int *count);

/* 8 seconds from the melody's first note as a PNG: the wrist's path in key space (beat keys
 * red), and against time the notes, the meter's beats, each path's timing
 * curve and the wrist's speed. 0 or 1 with the problem on stderr. */
int groove_png(const groove_song *s, const char *path);

double groove_now_ms(void);

#endif

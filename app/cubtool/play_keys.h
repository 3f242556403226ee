/* play_keys — what each key does in `cubtool play`'s scene (the seed's
 * Motion Player, SEEDS.md § 002): a table of small handlers, one per key,
 * over the viewer's state. Keys are cub/keyscript.h's codes, so a window's
 * keys and a headless run's --keys script go through the same handlers. */
#ifndef CUB_CUBTOOL_PLAY_KEYS_H
#define CUB_CUBTOOL_PLAY_KEYS_H

#include <stdio.h>

#define PLAY_MAX_CHARACTERS 2

/* What the keys change. */
typedef struct play_view {
    int count;                             /* characters in the scene */
    int selected;                          /* the one I/J/K/L and C/V act on */
    float move_mm[PLAY_MAX_CHARACTERS][2]; /* x, z moved from its spot */
    float size[PLAY_MAX_CHARACTERS];       /* scale about its spot; 1 = as captured */
    float floor_mm;                        /* the floor's side */
    float yaw_deg, pitch_deg, zoom;        /* the camera */
    double speed;                          /* playback speed */
    int points;                            /* 1: points with bone numbers; 0: sticks */
    int paused;
} play_view;

typedef enum play_key_result {
    PLAY_KEY_DONE = 0, /* handled */
    PLAY_KEY_QUIT,     /* Esc */
    PLAY_KEY_UNUSED,   /* no handler: ignored */
} play_key_result;

/* The defaults for count characters. */
void play_view_init(play_view *v, int count);
/* Press a key (cub/keyscript.h's code). */
play_key_result play_key(play_view *v, int key);
/* One line per key for --help. */
void play_keys_help(FILE *f);
/* The state in one line ("selected=2 move2=300,0 ..."), for logs and tests. */
void play_view_print(const play_view *v, FILE *f);

#endif

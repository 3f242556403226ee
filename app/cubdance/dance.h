/* dance — the box leading a song: the glue between the firmware's coach
 * (what to do), its bridge player (how to switch clips at once, unnoticed),
 * the song (the moves and their music times) and the music (FluidSynth; its
 * clock is the music clock).
 *
 * Per event: the coach decides; its actions become player requests, speed
 * changes, music start/stop. Per tick: the music advances (from the audio
 * device, or under the virtual clock rendered right here so a replay is
 * exact), the player advances and reports switches (logged) and clip ends,
 * which go back to the coach as events, as do the music tags of the moves
 * the player enters. */
#ifndef CUB_APP_DANCE_H
#define CUB_APP_DANCE_H

#include <stdint.h>

#include "cub/board.h"
#include "cub/bridge.h"
#include "cub/coach.h"
#include "cub/coachlib.h"
#include "cub/loop.h"
#include "cub/music.h"
#include "cub/song.h"
#include "options.h"
#include "watch.h"

typedef struct cub_dance {
    cub_coachlib cl;
    cub_song song;
    cub_music *music;
    cub_board *board;
    int music_pull;          /* virtual clock: the tick renders the music */
    int music_started;       /* the song's music was started (and not stopped) */
    int song_end_sent;
    int music_paused;        /* held by the coach (the camera is gone) */
    int64_t paused_at_us;    /* ... since this loop time */
    int audio_open;          /* real clock: the board's audio device plays it */
    int64_t pull_origin_us;  /* loop time the pulled music started */
    uint32_t pull_scale_ppm; /* pulled frames per loop second, ppm of the rate */
    int16_t *pcm;            /* scratch for pulled rendering */
    cub_coach coach;
    cub_coach_move moves[CUB_SONG_MAX_MOVES];
    const char *clip_names[256];
    cub_bridge_player player;
    void *player_mem;
    cub_log *log;
    int64_t last_tick_us;
    int played_clip, requested_clip; /* a correction played in place of another */
    cub_watch *watch;                /* the judge to tell what is taught, or NULL */
    cub_pose pose;
    cub_vec3 world_mm[CUB_MOTION_MAX_JOINTS];
    /* What the TV shows besides the coach (the coach decided it; the
     * renderer draws it): the last hint, and the icon of the move hinted. */
    int32_t hint;     /* the coach's last ACT_HINT: a move or CUB_COACH_HINT_* */
    int icon_move;    /* the move icon_xyz shows, or -1 */
    float icon_xyz[3 * CUB_MOTION_MAX_JOINTS];
} cub_dance;

/* Load the coach's clips, the song and the music, and start the coach idle
 * at now_us. On failure a message naming the file and problem is in err. */
cub_err cub_dance_open(cub_dance *d, const cub_app_options *o, cub_board *board, cub_log *log,
                       int64_t now_us, char *err, size_t err_size);
void cub_dance_close(cub_dance *d);
/* An event from the loop (buttons, the judge's timeline, the player's own). */
void cub_dance_handle(cub_dance *d, cub_loop *loop, const cub_event *ev);
/* At the start of each loop step, before events are handled: the music and
 * the player move on to now_us, so a request made while handling an event
 * is carried out after it; the player's clip ends and music tags are posted
 * and handled in the same step. */
void cub_dance_poll(cub_dance *d, cub_loop *loop, int64_t now_us);
/* Once per tick, after the events: the coach's deadlines (intro, attract,
 * doze). */
void cub_dance_tick(cub_dance *d, cub_loop *loop, int64_t t_us);
/* The coach's skeleton and its pose now (world mm, 3 floats per joint). */
const cub_skeleton *cub_dance_skeleton(const cub_dance *d);
/* 1 while the coach waits for START (idle, attracting or dozing). */
int cub_dance_waiting(const cub_dance *d);
/* How tall the camera should frame the coach: its standing height and a
 * margin for raised paws and jumps (mm). */
float cub_dance_figure_height_mm(const cub_dance *d);
/* The coach's pose this tick: joint world positions (mm, 3 floats each)
 * into xyz and, unless rot_xyzw is NULL, joint world rotations (x y z w
 * floats each, for the renderer's skinning), from one forward pass. */
cub_err cub_dance_pose(cub_dance *d, float *xyz, float *rot_xyzw);
/* The hint the coach shows now: the move's own text, "Come closer!", "I
 * can't see you!", or NULL for none. */
const char *cub_dance_hint_text(const cub_dance *d);
/* The hinted move's icon pose (joint world positions of
 * cub_dance_skeleton, mm), or NULL when the hint is not a move's. */
const float *cub_dance_icon_xyz(const cub_dance *d);
/* How far the song's music has played, 0..1; -1 while it is not playing. */
float cub_dance_progress(const cub_dance *d);

#endif

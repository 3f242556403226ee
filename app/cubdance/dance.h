/* dance — the box leading a song: the assets (the coach's clips, the song,
 * the bear), the music (dance_music.h; its clock is the music clock) and
 * the firmware's director (cub/director.h), which decides everything else.
 *
 * Per event and per tick the director decides; what only the app can do
 * comes back from it and is done here: the music started, paused, resumed
 * or stopped, the hint shown (with its move's icon) and said. Per loop
 * step the music advances, then the director's player. Each hint is said
 * as the director shows it (a `speech say` line after its `coach hint`),
 * "Press START!" as the bear starts waiting or attracting, the cheer as
 * the song ends. */
#ifndef CUB_APP_DANCE_H
#define CUB_APP_DANCE_H

#include <stdint.h>

#include "cub/board.h"
#include "cub/coach.h"
#include "cub/coachlib.h"
#include "cub/director.h"
#include "cub/faults.h"
#include "cub/floor.h"
#include "cub/judge.h"
#include "cub/loop.h"
#include "cub/song.h"
#include "dance_music.h"
#include "options.h"
#include "groove_box.h"
#include "wings.h"

struct cub_walk_box;

typedef struct cub_dance {
    cub_coachlib cl;
    cub_song song;
    cub_faults faults; /* the song's fault words (empty without faults=) */
    cub_dance_music music;
    cub_director dir;
    void *dir_mem;
    cub_log *log;
    const char *clip_names[256];
    cub_director_keys keys[CUB_SONG_MAX_MOVES]; /* each move's, for the judge */
    cub_pose pose;
    cub_vec3 world_mm[CUB_MOTION_MAX_JOINTS];
    /* What the TV shows besides the coach (the director decided it; the
     * renderer draws it): the last hint, and the icon of the move hinted. */
    int32_t hint;     /* the last hint: a move or CUB_COACH_HINT_* */
    int32_t fault;    /* ... and what to fix in the move (cub_judge_fault_code); 0 none */
    int icon_move;    /* the move icon_xyz shows, or -1 */
    float icon_xyz[3 * CUB_MOTION_MAX_JOINTS];
    int speech;         /* the config's speech=1: words are said as shown */
    int32_t said_state; /* the coach state the last tick's words were for */
    cub_wings wings;    /* the bear's wings in bird_flying (picture only) */
    cub_groove_box *groove; /* the song's free bars, danced to its notes (owned) */
    cub_coach_groove grooves[CUB_SONG_MAX_SPANS]; /* its clips' spans, for the coach */
    int groove_span[CUB_SONG_MAX_SPANS];          /* each one's span in the groove box */
    int groove_count;
    struct cub_walk_box *walk; /* the bear's walks (walk_box.h; owned), or NULL */
} cub_dance;

/* Load the coach's clips, the song and the music (and the walk clip of
 * o->walk_path over floor, which may be NULL and must outlive d), and
 * start the coach idle at now_us; judge (or NULL) is told what is taught.
 * On failure a message naming the file and problem is in err. */
cub_err cub_dance_open(cub_dance *d, const cub_app_options *o, cub_board *board, cub_log *log,
                       cub_judge *judge, const cub_floor *floor, int64_t now_us, char *err,
                       size_t err_size);
void cub_dance_close(cub_dance *d);
/* An event from the loop (buttons, the judge's, the player's own). */
void cub_dance_handle(cub_dance *d, cub_loop *loop, const cub_event *ev);
/* At the start of each loop step, before events are handled: the music and
 * the director's player move on to now_us (the song's end, the player's
 * clip ends and music tags are posted and handled in the same step). */
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
/* The picture of the coach this tick: its character, skeleton, joint
 * positions and rotations (the bear's pose as cub_dance_pose gave it, with
 * the wings while bird_flying has them) and icon; fills what it changes. */
void cub_dance_picture(cub_dance *d, int64_t t_us, const cub_character **ch,
                       const cub_skeleton **skel, const float **xyz, const float **rot,
                       const float **icon);
/* The child's joints to draw marked (bit CUB_KJ_*): the limb the shown
 * fault asks to move, while its correction runs; 0 otherwise. */
uint32_t cub_dance_child_mark(const cub_dance *d);
/* The hinted move's icon pose (joint world positions of
 * cub_dance_skeleton, mm), or NULL when the hint is not a move's. */
const float *cub_dance_icon_xyz(const cub_dance *d);
/* The words under the coach now: the hint's (words.c), or the cheer while
 * the bear cheers; NULL for none. */
const char *cub_dance_words(const cub_dance *d);
/* How far the song's music has played, 0..1; -1 while it is not playing. */
float cub_dance_progress(const cub_dance *d);

#endif

/* play_scene — the one scene of `cubtool play` (the seed's Motion Player,
 * SEEDS.md § 002): each character on its own spot of one floor, side by
 * side, moved, scaled and selected as the keys say (play_keys.h), drawn by
 * cub_render_player_frame. A character's first frame stands on its spot:
 * its root (a clip) or its markers' middle (a .trc) at t = 0, over the
 * floor. */
#ifndef CUB_CUBTOOL_PLAY_SCENE_H
#define CUB_CUBTOOL_PLAY_SCENE_H

#include "cub/render.h"
#include "play_keys.h"
#include "play_src.h"

typedef struct play_scene {
    const play_src *src; /* [count] */
    int count;
    float home_mm[PLAY_MAX_CHARACTERS][2]; /* x, z at t = 0, taken off */
    float spot_mm[PLAY_MAX_CHARACTERS];    /* x of its spot */
    float height_mm;                       /* the tallest character */
    int16_t parent[PLAY_MAX_CHARACTERS][CUB_RENDER_PLAYER_MAX_POINTS];
    float xyz[PLAY_MAX_CHARACTERS][3 * CUB_RENDER_PLAYER_MAX_POINTS];
} play_scene;

/* Set the spots from the sources' first frames. 0, or 1 with a message. */
int play_scene_init(play_scene *s, const play_src *src, int count);
/* Draw the scene at clip time t_s as v says. */
cub_err play_scene_draw(play_scene *s, const play_view *v, double t_s, int once, cub_render *r);

#endif

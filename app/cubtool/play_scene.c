/* play_scene — building and drawing the player's one scene (play_scene.h). */
#include "play_scene.h"

#include <math.h>
#include <stdio.h>

#define SPACING 1.2f /* spots apart, in heights of the tallest character */

static const float RGB[PLAY_MAX_CHARACTERS][3] = {{0.35f, 0.65f, 1.00f}, {1.00f, 0.55f, 0.15f}};

/* x, z of the middle of the points there are. */
static void middle(const float *xyz, int n, float out[2])
{
    double x = 0.0, z = 0.0;
    int k = 0;
    for (int j = 0; j < n; j++)
        if (isfinite(xyz[3 * j])) x += xyz[3 * j], z += xyz[3 * j + 2], k++;
    out[0] = k ? (float)(x / k) : 0.0f;
    out[1] = k ? (float)(z / k) : 0.0f;
}

int play_scene_init(play_scene *s, const play_src *src, int count)
{
    s->src = src;
    s->count = count;
    s->height_mm = 0.0f;
    for (int i = 0; i < count; i++) {
        int n = play_src_sample(&src[i], 0.0, 1, s->xyz[i]);
        if (n <= 0) {
            fprintf(stderr, "cubtool play: %s: cannot pose its first frame\n", src[i].name);
            return 1;
        }
        if (src[i].clip) /* the root stands on the spot */
            s->home_mm[i][0] = s->xyz[i][0], s->home_mm[i][1] = s->xyz[i][2];
        else
            middle(s->xyz[i], n, s->home_mm[i]);
        for (int j = 0; j < n; j++)
            s->parent[i][j] = src[i].clip ? src[i].clip->skel->joints[j].parent : -1;
        s->height_mm = src[i].height_mm > s->height_mm ? src[i].height_mm : s->height_mm;
    }
    for (int i = 0; i < count; i++)
        s->spot_mm[i] = ((float)i - 0.5f * (float)(count - 1)) * SPACING * s->height_mm;
    return 0;
}

/* Character i's points where the view puts them: its spot, moved, scaled
 * about its spot. */
static void place(play_scene *s, const play_view *v, int i, int n)
{
    float *p = s->xyz[i], size = v->size[i];
    float gx = s->spot_mm[i] + v->move_mm[i][0], gz = v->move_mm[i][1];
    for (int j = 0; j < n; j++) {
        p[3 * j + 0] = gx + size * (p[3 * j + 0] - s->home_mm[i][0]);
        p[3 * j + 1] = size * p[3 * j + 1];
        p[3 * j + 2] = gz + size * (p[3 * j + 2] - s->home_mm[i][1]);
    }
}

cub_err play_scene_draw(play_scene *s, const play_view *v, double t_s, int once, cub_render *r)
{
    cub_render_player_figure fig[PLAY_MAX_CHARACTERS];
    for (int i = 0; i < s->count; i++) {
        int n = play_src_sample(&s->src[i], t_s, once, s->xyz[i]);
        if (n <= 0) return CUB_ERR_ARG;
        place(s, v, i, n);
        fig[i] = (cub_render_player_figure){
            .joint_count = n,
            .parent = s->src[i].clip ? s->parent[i] : NULL,
            .world_xyz_mm = s->xyz[i],
            .selected = s->count > 1 && i == v->selected,
            .ground_mm = {s->spot_mm[i] + v->move_mm[i][0], v->move_mm[i][1]}};
        for (int k = 0; k < 3; k++)
            fig[i].rgb[k] = RGB[i][k];
    }
    float h = s->height_mm, span = h * (1.0f + SPACING * (float)(s->count - 1));
    cub_render_player_scene scene = {.figures = fig,
                                     .figure_count = s->count,
                                     .points = v->points,
                                     .floor_mm = v->floor_mm,
                                     .target_mm = {0.0f, 0.5f * h, 0.0f},
                                     .yaw_deg = v->yaw_deg,
                                     .pitch_deg = v->pitch_deg,
                                     .distance_mm = 1.9f * span / v->zoom};
    return cub_render_player_frame(r, &scene);
}

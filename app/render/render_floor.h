/* render_floor — the forest floor's meshes (cub/floor.h): the rolling
 * ground as a lit heightfield, the logs as cylinders, the stones as
 * low-poly rocks, all at the heights of the one terrain cub_floor_terrain
 * makes, which the gait planner walks on. CPU only (no GL calls), so a
 * test can hold the meshes against cub_gait_height. Private to app/render. */
#ifndef CUB_RENDER_FLOOR_H
#define CUB_RENDER_FLOOR_H

#include "cub/floor.h"
#include "render_mesh.h"

/* The ground is drawn this far below the terrain, as the flat meadow is,
 * so a sole standing on it never flickers through it. */
#define CUB_RENDER_FLOOR_DROP_MM 2.0f
/* Heightfield vertices per grid cell along x and z: the bilinear ground
 * between samples, near enough in flat triangles. */
#define CUB_RENDER_FLOOR_SUB 3
/* Vertex lines along x or z at most: the grid's, and one past each end. */
#define CUB_RENDER_FLOOR_MAX_LINES ((CUB_FLOOR_MAX_SIDE - 1) * CUB_RENDER_FLOOR_SUB + 3)
/* How far past the grid the ground goes on (its edge heights held). */
#define CUB_RENDER_FLOOR_BEYOND_MM 20000.0f

/* The terrain's height (obstacles left out) at (x, z), in float mm. */
float cub_render_floor_y(const cub_gait_terrain *t, float x_mm, float z_mm);
/* The ground: vertices of the heightfield (and its skirt past the grid),
 * CUB_RENDER_FLOOR_DROP_MM below the terrain; rgb its colour. */
void cub_render_floor_ground(cub_render_mesh *m, const cub_floor *f, const cub_gait_terrain *t,
                             const float rgb[3]);
/* Thing k of f resting where t's obstacle k (cub_floor_terrain) has it:
 * on the box's bottom, its top at the box's top. */
void cub_render_floor_thing(cub_render_mesh *m, const cub_floor *f, int k,
                            const cub_gait_terrain *t);

#endif

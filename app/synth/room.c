/* The room around the player (world space: floor y = 0, the camera above
 * the origin looking along +z, the player at z = distance): always a floor;
 * furnished, a back wall, a sofa, a table and a plant - boxes, cylinders
 * and an ellipsoid, placed where they show beside and behind a child. */
#include "synth_internal.h"

static synth_prim box(float x0, float y0, float z0, float x1, float y1, float z1)
{
    synth_prim p = {
        .kind = PRIM_BOX,
        .owner = OWNER_ROOM,
        .a = cub_fv3_make(x0, y0, z0),
        .b = cub_fv3_make(x1, y1, z1)};
    synth_prim_bound(&p);
    return p;
}

static synth_prim cylinder(float x, float y0, float y1, float z, float r)
{
    synth_prim p = {
        .kind = PRIM_CYLINDER,
        .owner = OWNER_ROOM,
        .a = cub_fv3_make(x, y0, z),
        .b = cub_fv3_make(x, y1, z),
        .r = r};
    synth_prim_bound(&p);
    return p;
}

void synth_room_build(float d, int furnished, synth_prim *out, int *n)
{
    int k = 0;
    float wall = d + 1600.0f;
    synth_prim floor = {.kind = PRIM_FLOOR, .owner = OWNER_ROOM};
    floor.a = cub_fv3_make(-5000, 0, 0);
    floor.b = cub_fv3_make(5000, 0, furnished ? wall : 20000.0f);
    synth_prim_bound(&floor);
    out[k++] = floor;
    if (furnished) {
        out[k++] = box(-3000, 0, wall, 3000, 2600, wall + 100);
        /* sofa: seat, back, two arms */
        out[k++] = box(-1700, 0, d + 700, -700, 420, d + 1500);
        out[k++] = box(-1700, 420, d + 1300, -700, 850, d + 1500);
        out[k++] = box(-1700, 420, d + 700, -1550, 600, d + 1300);
        out[k++] = box(-850, 420, d + 700, -700, 600, d + 1300);
        /* table: top and four legs */
        out[k++] = box(800, 450, d + 100, 1400, 490, d + 700);
        out[k++] = cylinder(850, 0, 450, d + 150, 25);
        out[k++] = cylinder(1350, 0, 450, d + 150, 25);
        out[k++] = cylinder(850, 0, 450, d + 650, 25);
        out[k++] = cylinder(1350, 0, 450, d + 650, 25);
        /* plant: pot and foliage */
        out[k++] = cylinder(-950, 0, 320, d + 300, 150);
        synth_prim leaves = {
            .kind = PRIM_ELLIPSOID, .owner = OWNER_ROOM, .a = cub_fv3_make(-950, 650, d + 300)};
        leaves.axis[0] = cub_fv3_make(1, 0, 0);
        leaves.axis[1] = cub_fv3_make(0, 1, 0);
        leaves.axis[2] = cub_fv3_make(0, 0, 1);
        leaves.radii[0] = 260;
        leaves.radii[1] = 360;
        leaves.radii[2] = 260;
        synth_prim_bound(&leaves);
        out[k++] = leaves;
    }
    *n = k;
}

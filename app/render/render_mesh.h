/* render_mesh — lit, skinned triangle meshes built once on the CPU: rounded
 * shapes (ellipsoids, tapered capsules, tubes along a curve, lathed
 * profiles) in bind-pose space, each vertex tied to one or two bone slots.
 * Private to app/render. */
#ifndef CUB_RENDER_MESH_H
#define CUB_RENDER_MESH_H

#include <GLES2/gl2.h>

/* One vertex: bind-pose position (mm), normal, colour (0..1), and skinning:
 * bone slots a and b and the weight of b (slot 0 is the stage, which has
 * no bone). */
typedef struct cub_render_lvtx {
    float pos[3];
    float nrm[3];
    float rgb[3];
    float skin[3];
} cub_render_lvtx;

/* Vertices and 16-bit indices; arrays sized at init, never grown. A shape
 * that does not fit sets full and is left out whole. */
typedef struct cub_render_mesh {
    cub_render_lvtx *v;
    GLushort *idx;
    int nv, ni, cap_v, cap_i;
    int full;
    /* What the next shapes are tied to, and where their local origin sits
     * in bind-pose space (the joint's rest position). */
    float origin[3];
    int slot;
} cub_render_mesh;

int cub_render_mesh_init(cub_render_mesh *m, int cap_v, int cap_i);
void cub_render_mesh_free(cub_render_mesh *m);

/* An ellipsoid, rigid on m->slot. */
void cub_render_mesh_ellipsoid(cub_render_mesh *m, const float c[3], const float radii[3],
                               const float rgb[3]);
/* A capsule from the origin along axis (mm, its length is the bone's), radius r0
 * at the start and r1 at the end. Vertices near the start blend toward
 * parent_slot and near the end toward child_slot (halfway at the joint), so
 * two capsules meeting at a bending joint stay joined. -1 = no blend. */
void cub_render_mesh_capsule(cub_render_mesh *m, const float axis[3], float r0, float r1,
                             const float rgb[3], int parent_slot, int child_slot);
/* A round tube of radius r through n points (n >= 2), rigid on m->slot,
 * with round ends. */
void cub_render_mesh_tube(cub_render_mesh *m, const float (*pts)[3], int n, float r,
                          const float rgb[3]);
/* A surface of revolution about the vertical line through base: profile
 * points (radius, height) from bottom to top; radius 0 closes it. */
void cub_render_mesh_lathe(cub_render_mesh *m, const float base[3], const float (*prof)[2],
                           int n, const float rgb[3]);

/* Free-form pieces (the floor's heightfield and rocks): room for nv
 * vertices and ni indices, returning the first new vertex's index, or -1
 * (full set) when they do not fit; then the vertices, rigid on m->slot,
 * and the triangles by vertex index. */
int cub_render_mesh_room(cub_render_mesh *m, int nv, int ni);
void cub_render_mesh_vertex(cub_render_mesh *m, const float p[3], const float n[3],
                            const float rgb[3]);
void cub_render_mesh_tri(cub_render_mesh *m, int a, int b, int c);

#endif

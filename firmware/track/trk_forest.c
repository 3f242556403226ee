/* The forest's seam (docs/forest.md, "In the box"): when the box hands the
 * tracker a forest (cub_track_desc.forest), the player's pixels that the
 * tracker found are classified every TRK_FOREST_STRIDE-th pixel, every
 * part is proposed, and a joint the forest is confident of replaces the
 * tracker's in the output when the tracker is not confident of it (see
 * takes(); docs/forest.md, "In the box", has the figures). The tracker's own state (last frame's skeleton,
 * smoothing, reach) never sees the forest's joints: the seam is after the
 * whole heuristic pipeline and changes only what the caller reads.
 * Integers only, as the forest and the tracker are. */
#include "depth_table.h"
#include "trk_internal.h"

#define TRK_FOREST_STRIDE 4 /* one pixel a cell: the accuracy of every 2nd (docs/forest.md) */
/* A player of more cells than this (an adult near the camera: 3700-5600
 * cells in the real frames, a child at 2-3 m 300-1700) is read every 8th
 * pixel: its parts still hold hundreds of points, and the forest's time
 * stays that of a child's */
#define TRK_FOREST_CELLS 2400
#define TRK_FOREST_CAP (TRK_CELLS / 4) /* points: every 8th pixel of the image, or every 4th of TRK_FOREST_CELLS */
#define TRK_FOREST_NEAR_MM 200 /* a pixel of a player's cell is the player's within this of the cell */
#define TRK_NPIX (CUB_KINECT_WIDTH * CUB_KINECT_HEIGHT)

static size_t round16(size_t n)
{
    return (n + 15) & ~(size_t)15;
}

size_t trk_forest_mem(const cub_forest *f)
{
    if (!f) return 0;
    size_t per_point = 3 * sizeof(int32_t) + (size_t)f->classes * sizeof(uint16_t) + sizeof(int32_t);
    return round16(TRK_NPIX * sizeof(uint16_t)) + round16(TRK_FOREST_CAP * per_point) + 16;
}

void trk_forest_setup(cub_tracker *t, const cub_forest *f, uint8_t *mem)
{
    t->forest = f;
    if (!f) return;
    t->forest_mm = (uint16_t *)mem;
    mem += round16(TRK_NPIX * sizeof(uint16_t));
    cub_forest_points *p = &t->forest_pts;
    p->mm = (int32_t(*)[3])mem;
    mem += TRK_FOREST_CAP * 3 * sizeof(int32_t);
    p->part_pts = (int32_t *)mem;
    mem += TRK_FOREST_CAP * sizeof(int32_t);
    p->prob = (uint16_t *)mem;
    p->capacity = TRK_FOREST_CAP;
    p->classes = f->classes;
    p->stride = TRK_FOREST_STRIDE;
}

/* The player's depth in mm, every other pixel 0 (the forest was trained
 * on the player alone): the pixels of the player's cells near the cell's
 * depth (a cell on the silhouette's edge also holds the room behind). */
static int32_t player_depth(cub_tracker *t, const uint16_t *raw)
{
    int32_t cells = 0;
    memset(t->forest_mm, 0, TRK_NPIX * sizeof(uint16_t));
    for (int32_t i = 0; i < TRK_CELLS; i++) {
        if (!t->mask[i] || !t->z[i]) continue;
        cells++;
        int32_t x0 = i % TRK_GW * TRK_CELL_PX, y0 = i / TRK_GW * TRK_CELL_PX;
        for (int32_t y = y0; y < y0 + TRK_CELL_PX; y++)
            for (int32_t x = x0; x < x0 + TRK_CELL_PX; x++) {
                int32_t k = y * CUB_KINECT_WIDTH + x;
                int32_t mm = trk_raw_mm(raw[k]);
                if (mm && trk_abs(mm - t->z[i]) <= TRK_FOREST_NEAR_MM) t->forest_mm[k] = (uint16_t)mm;
            }
    }
    return cells;
}

/* Whether the forest's joint j replaces the tracker's: the forest is
 * confident of it and the tracker is not (its confident joints are 98 %
 * within 10 cm on the dev folds, the forest's 93 %: the confidence stays
 * the tracker's and stays honest). Not the feet: the floor's removal cuts
 * them off the box's mask (40 mm), and the forest then proposes the shin
 * (the dev folds: foot_l 87.7 -> 84.0 % with them). */
static bool takes(const cub_forest_joints *fj, int j, const cub_track_skeleton *out)
{
    if (j == CUB_KJ_FOOT_L || j == CUB_KJ_FOOT_R) return false;
    return fj->confident[j] && out->confidence[j] < CUB_TRACK_CONFIDENT;
}

void trk_forest_override(cub_tracker *t, const uint16_t *raw, cub_track_skeleton *out)
{
    int32_t stride = player_depth(t, raw) > TRK_FOREST_CELLS ? 2 * TRK_FOREST_STRIDE : TRK_FOREST_STRIDE;
    cub_forest_image im = {t->forest_mm, CUB_KINECT_WIDTH, CUB_KINECT_HEIGHT};
    cub_forest_gather(t->forest, &im, stride, &t->forest_pts);
    cub_forest_proposal prop[CUB_PART_COUNT];
    cub_forest_joints fj;
    cub_forest_propose_all(&t->forest_pts, prop);
    cub_forest_joints_of(prop, &fj);
    for (int j = 0; j < CUB_KJ_COUNT; j++)
        if (takes(&fj, j, out))
            out->joint_mm[j] = (cub_vec3){fj.mm[j][0] * 65536, fj.mm[j][1] * 65536, fj.mm[j][2] * 65536};
}

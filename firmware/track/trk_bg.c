/* The room's background, learnt per grid cell while the tracker runs (in
 * attract mode before START as well): what stays still and far. The room
 * is not assumed empty; a cell's background is the farthest depth that
 * stayed still there:
 *  - a cell with no background yet takes the first depth that stays
 *    (within bg_tol) for BG_LEARN_US; a frame with no reading there
 *    restarts the count;
 *  - a farther depth that stays BG_REVEAL_US replaces it at once: what
 *    stood before the background has gone (a parent got up from the sofa);
 *  - a nearer depth that stays BG_NEAR_US becomes the background too:
 *    furniture moved in, a parent who sat down and stays;
 *  - a cell a person covered in the last BG_PERSON_HOLD_US (the player's,
 *    or a person-like blob's that moves) takes BG_PERSON_US instead: a
 *    child who stands still is not absorbed into the room;
 *  - a cell the player covered in the last BG_PERSON_HOLD_US never takes a
 *    nearer depth (or a first one): the player is never the room, however
 *    long a part of the child stays still (the body during jumping jacks).
 * Most of the image changing at once (the camera bumped) forgets it all.
 * The model lives in the tracker's memory only: nothing is ever stored.
 * Learning needs time to pass between frames: frames with the same time
 * (single frames, tests) learn nothing, and with no background a cell is
 * foreground, as the tracker was before. */
#include "trk_internal.h"

#define BG_LEARN_US 1000000   /* a still cell with no background yet */
#define BG_REVEAL_US 500000   /* a farther depth where the background was */
#define BG_NEAR_US 5000000    /* a nearer depth where the background was */
#define BG_PERSON_US 30000000 /* a cell a person covered lately */
#define BG_PERSON_HOLD_US 2000000
#define BG_MAX_DT_US 200000 /* a longer gap counts as this */
#define BG_AGE_UNIT_US 10000 /* ages are kept in 10 ms units (uint16: 655 s) */

/* Depths this near are the same surface: the sensor's step grows with
 * depth (about 30 mm at 3 m), a breathing or swaying body moves more. */
static int32_t bg_tol(int32_t z) { return 60 + z / 40; }

int32_t trk_bg_margin(int32_t z) { return bg_tol(z); }

void trk_bg_reset(cub_tracker *t)
{
    memset(t->bg_mm, 0, sizeof t->bg_mm);
    memset(t->bg_cand_mm, 0, sizeof t->bg_cand_mm);
    memset(t->bg_age, 0, sizeof t->bg_age);
    for (int32_t i = 0; i < TRK_CELLS; i++)
        t->bg_person_age[i] = UINT16_MAX, t->bg_player_age[i] = UINT16_MAX;
    t->bg_resets++;
    t->bg_run_us = 0;
    t->room_known = 0;
}

bool trk_bg_room_new(const cub_tracker *t) { return t->room_known == 1; }

/* A person-like blob moves (a standing person sways, breathes, its edges
 * flicker): some of its cells took a new depth lately. Furniture shaped
 * like a person (a plant, a table's end) does not, and is learnt. */
#define BG_MOVED_US 300000
#define BG_MOVED_PM 20
static bool blob_moves(const cub_tracker *t, int32_t k)
{
    int32_t n = 0, moved = 0;
    if (t->bg_run_us < 2 * BG_MOVED_US) return false; /* every cell is new yet */
    for (int32_t i = 0; i < TRK_CELLS; i++) {
        if (t->label[i] != k) continue;
        n++;
        moved += (int32_t)t->bg_age[i] * BG_AGE_UNIT_US < BG_MOVED_US;
    }
    return n > 0 && moved * 1000 >= n * BG_MOVED_PM;
}

void trk_bg_mark_people(cub_tracker *t, const bool *person)
{
    bool moves[TRK_MAX_COMPS];
    for (int32_t k = 0; k < t->ncomps; k++) moves[k] = person[k] && blob_moves(t, k);
    for (int32_t i = 0; i < TRK_CELLS; i++) {
        if (t->mask[i]) t->bg_player_age[i] = 0;
        if (t->mask[i] || (t->label[i] >= 0 && moves[t->label[i]])) t->bg_person_age[i] = 0;
    }
}

/* The room is known once most cells with a reading have a background:
 * then the blobs are what stands before it. */
#define BG_ROOM_KNOWN_PM 500
static void update_room_known(cub_tracker *t)
{
    if (t->room_known) return;
    int32_t read = 0, known = 0;
    for (int32_t i = 0; i < TRK_CELLS; i++) read += t->z[i] != 0, known += t->z[i] && t->bg_mm[i];
    if (read > 0 && (int64_t)known * 1000 >= (int64_t)read * BG_ROOM_KNOWN_PM) t->room_known = 1;
}

static uint16_t age_add(uint16_t a, int32_t units)
{
    int32_t s = a + units;
    return (uint16_t)(s > UINT16_MAX ? UINT16_MAX : s);
}

static bool person_lately(const cub_tracker *t, int32_t i)
{
    return (int32_t)t->bg_person_age[i] * BG_AGE_UNIT_US < BG_PERSON_HOLD_US;
}

static bool player_lately(const cub_tracker *t, int32_t i)
{
    return (int32_t)t->bg_player_age[i] * BG_AGE_UNIT_US < BG_PERSON_HOLD_US;
}

/* The time a cell's candidate must stay before it becomes the background. */
static int32_t need_us(const cub_tracker *t, int32_t i)
{
    int32_t bg = t->bg_mm[i], cand = t->bg_cand_mm[i];
    bool nearer = bg == 0 || cand < bg;
    if (nearer && player_lately(t, i)) return INT32_MAX;
    if (nearer && person_lately(t, i)) return BG_PERSON_US;
    if (bg == 0) return BG_LEARN_US;
    return cand > bg ? BG_REVEAL_US : BG_NEAR_US;
}

/* One cell's reading z (> 0): follow the candidate, promote it when it
 * has stayed long enough. */
static void learn_cell(cub_tracker *t, int32_t i, int32_t z, int32_t units)
{
    int32_t cand = t->bg_cand_mm[i], tol = bg_tol(z);
    if (cand && trk_abs(z - cand) <= tol) {
        t->bg_cand_mm[i] = (int16_t)((3 * cand + z) / 4);
        t->bg_age[i] = age_add(t->bg_age[i], units);
    } else {
        t->bg_cand_mm[i] = (int16_t)z;
        t->bg_age[i] = 0;
    }
    int32_t bg = t->bg_mm[i];
    cand = t->bg_cand_mm[i];
    if (bg && trk_abs(cand - bg) <= tol) {
        t->bg_mm[i] = (int16_t)((7 * bg + cand) / 8); /* the same surface: follow it slowly */
        return;
    }
    if ((int64_t)t->bg_age[i] * BG_AGE_UNIT_US >= need_us(t, i)) t->bg_mm[i] = (int16_t)cand;
}

/* The camera was bumped: most cells with a background read another depth
 * (a person covers part of the view, never most of it; people's cells do
 * not count). */
static bool bumped(const cub_tracker *t)
{
    int32_t known = 0, changed = 0;
    for (int32_t i = 0; i < TRK_CELLS; i++) {
        if (!t->bg_mm[i] || !t->z[i] || person_lately(t, i)) continue;
        known++;
        changed += trk_abs(t->z[i] - t->bg_mm[i]) > bg_tol(t->bg_mm[i]);
    }
    return known >= TRK_CELLS / 8 && changed * 2 > known;
}

void trk_bg_learn(cub_tracker *t, int32_t dt_us)
{
    if (dt_us <= 0) return;
    if (bumped(t)) trk_bg_reset(t);
    int32_t units = (dt_us > BG_MAX_DT_US ? BG_MAX_DT_US : dt_us) / BG_AGE_UNIT_US;
    if (t->bg_run_us < INT32_MAX / 2) t->bg_run_us += units * BG_AGE_UNIT_US;
    for (int32_t i = 0; i < TRK_CELLS; i++) {
        t->bg_person_age[i] = age_add(t->bg_person_age[i], units);
        t->bg_player_age[i] = age_add(t->bg_player_age[i], units);
        if (t->z[i]) learn_cell(t, i, t->z[i], units);
        else t->bg_cand_mm[i] = 0, t->bg_age[i] = 0; /* nothing seen: it did not stay */
    }
    update_room_known(t);
}

/* Cells at their background depth (or behind it) go: the blobs are what
 * stands before the room. Cells with no background yet stay. */
void trk_bg_remove(cub_tracker *t)
{
    for (int32_t i = 0; i < TRK_CELLS; i++) {
        int32_t bg = t->bg_mm[i], z = t->z[i];
        if (bg && z && z >= bg - trk_bg_margin(bg)) t->z[i] = 0;
    }
}

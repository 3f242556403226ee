/* libFuzzer target: a MIDI file through seed 001's reader and pipeline
 * (app/music/midi_groove.c, then firmware/groove: track choice, notes, the
 * DP in small windows, wrist keys, then the whole plan and the bear's pose
 * at 16 times of the song). Checks what the callers rely on: a refusal
 * says why; accepted notes are sorted and end after they start; the melody
 * fits its bound; the segments tile the notes; every pose is made. Seeds:
 * the box's songs (assets/songs/). */
#include <stdint.h>
#include <stdlib.h>

#include "cub/music.h"
#include "fuzz_tally.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static cub_groove_work work;

static void check_song(const cub_groove_song *s)
{
    for (int i = 0; i < s->note_count; i++) {
        if (s->notes[i].off_tick < s->notes[i].on_tick || s->notes[i].pitch > 127) abort();
        if (i > 0 && s->notes[i].on_tick < s->notes[i - 1].on_tick) abort();
    }
    for (int i = 1; i < s->tempo_count; i++)
        if (s->tempos[i].tick < s->tempos[i - 1].tick) abort();
}

static cub_skeleton bear;
static cub_pose pose;

/* The joints the groove's rig needs, as the bear has them. */
static void build_bear(void)
{
    static const struct {
        const char *name;
        int parent, x, y;
    } j[] = {{"Hips", -1, 0, 285},      {"Spine", 0, 0, 115},      {"Chest", 1, 0, 125},
             {"Head", 2, 0, 140},       {"RightArm", 2, -125, 55}, {"RightForeArm", 4, -150, 0},
             {"RightHand", 5, -135, 0}, {"LeftArm", 2, 125, 55},   {"LeftForeArm", 7, 150, 0},
             {"LeftHand", 8, 135, 0}};
    int at;
    for (size_t i = 0; i < sizeof j / sizeof j[0]; i++)
        cub_motion_skeleton_add(&bear, j[i].name, j[i].parent,
                                (cub_vec3){CUB_Q16_INT(j[i].x), CUB_Q16_INT(j[i].y), 0}, &at);
}

/* The plan and 16 poses over the song (the store as the app sizes it). */
static void motion(const cub_groove_song *s, const cub_groove_pick *pick,
                   const cub_groove_params *p)
{
    int cap = 2 * s->note_count + 1;
    cub_groove_store m = {cap,
                          calloc((size_t)cap, sizeof(cub_groove_note)),
                          calloc((size_t)cap, sizeof(cub_groove_segment)),
                          calloc((size_t)cap, sizeof(cub_groove_key)),
                          calloc((size_t)cap, sizeof(cub_groove_handles)),
                          calloc((size_t)cap, sizeof(cub_groove_turn)),
                          calloc((size_t)cap, sizeof(cub_groove_turn)),
                          &work};
    if (!m.notes || !m.segs || !m.keys || !m.handles || !m.waist || !m.head) abort();
    cub_groove_plan plan;
    cub_groove_rig rig;
    if (bear.joint_count == 0) build_bear();
    if (cub_groove_plan_build(s, pick, p, 12, &m, &plan, NULL, NULL)) abort();
    if (cub_groove_rig_bind(&bear, &rig)) abort();
    for (int i = 0; i <= 16; i++)
        if (cub_groove_pose_at(&plan, &rig, plan.end_us / 16 * i, &pose)) abort();
    free(m.notes), free(m.segs), free(m.keys), free(m.handles), free(m.waist), free(m.head);
}

/* 0: no melody in it; 1: all the way to poses. */
static int groove(const cub_groove_song *s)
{
    cub_groove_pick pick;
    if (cub_groove_pick_tracks(s, -1, -1, &pick)) return 0;
    int cap = 2 * s->note_count + 1, n = 0, k = 0;
    cub_groove_note *notes = calloc((size_t)cap, sizeof(*notes));
    cub_groove_segment *segs = calloc((size_t)cap, sizeof(*segs));
    cub_groove_key *keys = calloc((size_t)cap, sizeof(*keys));
    cub_groove_params p;
    cub_groove_params_set(s->note_count % 2 ? 'a' : 'b', &p);
    if (!notes || !segs || !keys) abort();
    if (cub_groove_notes(s, &pick, notes, cap, &n) || n < 1) abort(); /* the pick promised notes */
    if (cub_groove_segment_notes(&p, notes, n, 12, &work, segs, cap, &k, NULL)) abort();
    for (int i = 0, at = 0; i < k; at = segs[i++].end)
        if (segs[i].first != at || segs[i].end <= at) abort();
    if (cub_groove_keys(&p, notes, n, segs, k, keys)) abort();
    free(notes), free(segs), free(keys);
    motion(s, &pick, &p);
    return 1;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    cub_midi_groove g;
    cub_diag d = {0};
    int read = cub_midi_groove_read(data, size, "fuzz.mid", &g, &d) == CUB_OK, grooved = 0;
    if (!read && !d.msg[0]) abort();
    if (read) {
        check_song(&g.song);
        grooved = groove(&g.song);
    }
    cub_midi_groove_free(&g);
    cub_fuzz_tally("fuzz_midi_groove", grooved);
    return 0;
}

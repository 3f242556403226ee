/* A clip made after the library was tagged (the box's groove clips, issue
 * 23) gets its bridge frames by the tagger's own rules (cub_tag_made_clip,
 * the library's frequent classes read from the bridge table): re-picked
 * that way, every shipped clip gets exactly the bridge frames of the
 * committed tags; a groove clip of Twinkle's bar 14 gets the frames the
 * rules give (a frequent class, the head still, thinned), not every frame.
 * Skips while the library is not built yet. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "bear_coachlib.h"
#include "cub/coachlib.h"
#include "cub/groove.h"
#include "cub/music.h"
#include "cub/tags.h"

typedef struct fixture {
    cub_coachlib cl;
    cub_tag_classes freq;
} fixture;

static fixture g;

static int setup(void **state)
{
    *state = NULL;
    int got = support_bear_coachlib(&g.cl, "made");
    if (got <= 0) return got; /* 0: the tests skip */
    if (cub_tag_table_classes(&g.cl.table, g.cl.lib.clip_count, &g.cl.tags.params, &g.freq))
        return -1;
    *state = &g;
    return 0;
}

static int teardown(void **state)
{
    if (*state) {
        free(g.freq.classes);
        cub_coachlib_free(&g.cl);
    }
    return 0;
}

/* The table's view of the library gives the tagger's own picks. */
static void test_library_clips_repicked_as_tagged(void **state)
{
    if (!*state) skip();
    assert_true(g.freq.count > 0);
    for (int c = 0; c < g.cl.lib.clip_count; c++) {
        const cub_clip *clip = &g.cl.lib.clips[c].clip;
        cub_tag_frame *frames = malloc(sizeof *frames * (size_t)clip->frame_count);
        cub_tag_clip got = {0};
        assert_non_null(frames);
        assert_int_equal(cub_tag_made_clip(clip, &g.cl.table.desc.body, &g.freq,
                                           &g.cl.tags.params, frames, &got),
                         CUB_OK);
        const cub_tag_clip *want = &g.cl.tags.clips[c];
        assert_int_equal(got.bridge_count, want->bridge_count);
        for (int b = 0; b < got.bridge_count; b++)
            assert_int_equal(got.bridges[b].frame, want->bridges[b].frame);
        free(got.bridges);
        free(frames);
    }
}

static int frequent(uint32_t c)
{
    for (int i = 0; i < g.freq.count; i++)
        if (g.freq.classes[i] == c) return 1;
    return 0;
}

/* Twinkle's bar 14 (32.5 s, 76 frames at 30 fps), as the box makes it. */
static void groove_clip(cub_clip *clip, void **mem, cub_midi_groove *midi, cub_groove_store *st)
{
    char path[1100];
    snprintf(path, sizeof path, "%s/assets/songs/twinkle.mid", support_src_dir());
    cub_diag d = {0};
    cub_groove_pick pick;
    cub_groove_params p;
    cub_groove_plan plan;
    cub_groove_rig rig;
    assert_int_equal(cub_midi_groove_load(path, midi, &d), CUB_OK);
    assert_int_equal(cub_groove_pick_tracks(&midi->song, -1, -1, &pick), CUB_OK);
    assert_int_equal(cub_groove_store_alloc(st, midi->song.note_count), CUB_OK);
    assert_int_equal(cub_groove_params_set('a', &p), CUB_OK);
    assert_int_equal(cub_groove_plan_build(&midi->song, &pick, &p, 0, st, &plan, NULL, NULL),
                     CUB_OK);
    assert_int_equal(cub_groove_rig_bind(&g.cl.lib.skel, &rig), CUB_OK);
    size_t size = cub_motion_clip_mem_size(g.cl.lib.skel.joint_count, 76, 0);
    *mem = malloc(size);
    assert_non_null(*mem);
    assert_int_equal(cub_motion_clip_init(clip, &g.cl.lib.skel, 76, 33333333u, 0, *mem, size),
                     CUB_OK);
    assert_int_equal(cub_groove_clip_fill(&plan, &rig, 32500000, clip), CUB_OK);
}

/* Every bridge frame is a candidate (frequent class, head still); every
 * candidate lies within a spacing window of one; within a run of
 * candidates no two are closer than the window; and not every frame. */
static void test_groove_clip_gets_the_rules_bridge_frames(void **state)
{
    if (!*state) skip();
    cub_clip clip;
    void *mem = NULL;
    cub_midi_groove midi;
    cub_groove_store st;
    groove_clip(&clip, &mem, &midi, &st);
    const cub_tag_params *p = &g.cl.tags.params;
    cub_tag_frame frames[76];
    cub_tag_clip got = {0};
    assert_int_equal(cub_tag_made_clip(&clip, &g.cl.table.desc.body, &g.freq, p, frames, &got),
                     CUB_OK);
    const int w = (int)(((int64_t)p->spacing_ms * 1000000 + clip.frame_ns / 2) / clip.frame_ns);
    int cand[76], is_bridge[76] = {0};
    for (int f = 0; f < 76; f++)
        cand[f] = frequent(frames[f].crisp_class) && frames[f].head_dps <= p->head_dps;
    for (int b = 0; b < got.bridge_count; b++) {
        int f = got.bridges[b].frame;
        assert_true(cand[f]);
        is_bridge[f] = 1;
        if (b > 0) {
            int prev = got.bridges[b - 1].frame, run = 1;
            for (int x = prev; x <= f; x++)
                run = run && cand[x];
            if (run) assert_true(f - prev >= w);
        }
    }
    for (int f = 0; f < 76; f++) {
        if (!cand[f]) continue;
        int near = 0;
        for (int x = f - w + 1; x <= f + w - 1; x++)
            near = near || (x >= 0 && x < 76 && is_bridge[x]);
        assert_true(near);
    }
    assert_true(got.bridge_count > 0);
    assert_true(got.bridge_count < 76);
    printf("groove bar 14: %d bridge frames of 76 (window %d frames)\n", got.bridge_count, w);
    free(got.bridges);
    free(mem);
    cub_groove_store_free(&st);
    cub_midi_groove_free(&midi);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_library_clips_repicked_as_tagged),
        cmocka_unit_test(test_groove_clip_gets_the_rules_bridge_frames),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}

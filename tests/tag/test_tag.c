/* Bridge-frame tagging (app/tag) on a small hand-made library: the head
 * rule, the thinning, the links (symmetric d, below the threshold, in
 * search order), reachability, and the tag file's byte-exact round trip. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/tags.h"
#include "synth_lib.h"

typedef struct fixture {
    cub_character bear;
    cub_library lib;
    cub_tags tags;
} fixture;

static int setup(void **state)
{
    static fixture f;
    if (synth_library(&f.bear, &f.lib)) return -1;
    if (cub_tag_library(&f.lib, "synth.cubclips", &f.bear.body, NULL, &f.tags, NULL, NULL))
        return -1;
    *state = &f;
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    cub_tags_free(&f->tags);
    synth_library_free(&f->lib);
    return 0;
}

static void test_tagging_rejects_bad_input(void **state)
{
    fixture *f = *state;
    cub_tags t;
    assert_int_equal(cub_tag_library(NULL, "x", &f->bear.body, NULL, &t, NULL, NULL), CUB_ERR_ARG);
    cub_tag_params bad = {.fuzzy.threshold = CUB_Q16_ONE + 1};
    assert_int_equal(cub_tag_library(&f->lib, "x", &f->bear.body, &bad, &t, NULL, NULL),
                     CUB_ERR_ARG);
    cub_fuzzy_body no_head = f->bear.body;
    no_head.head = -1;
    assert_int_equal(cub_tag_library(&f->lib, "x", &no_head, NULL, &t, NULL, NULL), CUB_ERR_ARG);
    /* A skeleton without the body's joints. */
    cub_skeleton other;
    cub_motion_skeleton_reset(&other);
    int j;
    assert_int_equal(cub_motion_skeleton_add(&other, "Root", -1, (cub_vec3){0}, &j), CUB_OK);
    cub_fuzzy_body mapped;
    cub_diag d = {0};
    assert_int_equal(cub_tag_map_body(&f->bear.skel, &f->bear.body, &other, &mapped, &d),
                     CUB_ERR_FORMAT);
    assert_non_null(strstr(d.msg, "no joint 'Hips'"));
    assert_int_equal(cub_tag_map_body(&f->bear.skel, &f->bear.body, &f->lib.skel, &mapped, &d),
                     CUB_OK);
    assert_memory_equal(&mapped, &f->bear.body, sizeof mapped);
}

static void test_defaults_are_documented_values(void **state)
{
    (void)state;
    cub_tag_params p = cub_tag_params_defaults(NULL);
    assert_int_equal(p.fuzzy.threshold, cub_fuzzy_config_defaults(NULL).threshold);
    assert_int_equal(p.class_share, CUB_Q16_ONE / 50);
    assert_int_equal(p.class_clips, 3);
    assert_int_equal(p.head_dps, CUB_Q16_INT(120));
    assert_int_equal(p.spacing_ms, 200);
    assert_int_equal(p.max_links, 3);
}

/* Step 2: no bridge frame where the head turns fast; the shake clip has
 * such frames (so the rule is exercised) and keeps bridges where it is still. */
static void test_bridges_skip_fast_head_motion(void **state)
{
    fixture *f = *state;
    int fast_total = 0;
    for (int c = 0; c < f->lib.clip_count; c++) {
        const cub_clip *clip = &f->lib.clips[c].clip;
        cub_tag_frame *m = malloc(sizeof *m * (size_t)clip->frame_count);
        assert_non_null(m);
        assert_int_equal(cub_tag_analyse_clip(clip, &f->bear.body, m), CUB_OK);
        int fast = 0;
        for (int i = 0; i < clip->frame_count; i++)
            fast += m[i].head_dps > f->tags.params.head_dps;
        for (int i = 0; i < f->tags.clips[c].bridge_count; i++) {
            const cub_tag_bridge *b = &f->tags.clips[c].bridges[i];
            assert_true(m[b->frame].head_dps <= f->tags.params.head_dps);
            assert_int_equal(b->crisp_class, m[b->frame].crisp_class);
        }
        if (c == SYNTH_HEAD_SHAKE) {
            int mid = clip->frame_count / 2;
            printf("tag: head_shake head speed at frame %d = %.1f deg/s (limit %.0f), fast "
                   "frames=%d\n",
                   mid, m[mid].head_dps / 65536.0, f->tags.params.head_dps / 65536.0, fast);
            assert_true(fast > clip->frame_count / 2);
            assert_true(f->tags.clips[c].bridge_count > 0);
        } else {
            assert_int_equal(fast, 0);
        }
        fast_total += fast;
        free(m);
    }
    assert_true(fast_total > 0);
}

/* Thinning (200 ms = 6 frames at 30 fps): bridge frames ascend, are not
 * crowded, and cover their run. */
static void test_bridges_are_thinned_and_spread(void **state)
{
    fixture *f = *state;
    for (int c = 0; c < f->tags.clip_count; c++) {
        const cub_tag_clip *tc = &f->tags.clips[c];
        int n = tc->frame_count, w = 6;
        printf("tag: synth clip %-10s frames=%d bridges=%d\n", tc->name, n, tc->bridge_count);
        assert_true(tc->bridge_count > 0);
        assert_true(tc->bridge_count <= (n + w - 1) / w * 2);
        for (int i = 1; i < tc->bridge_count; i++)
            assert_true(tc->bridges[i].frame > tc->bridges[i - 1].frame);
    }
    /* The idle clip is one run of candidates: bridge frames at least a
     * window apart, and every frame within a window of one. */
    const cub_tag_clip *idle = &f->tags.clips[SYNTH_IDLE];
    for (int i = 1; i < idle->bridge_count; i++)
        assert_true(idle->bridges[i].frame - idle->bridges[i - 1].frame >= 6);
    for (int fr = 0; fr < idle->frame_count; fr++) {
        int near = 0;
        for (int i = 0; i < idle->bridge_count; i++)
            near |= abs(idle->bridges[i].frame - fr) < 6;
        assert_true(near);
    }
}

static const cub_fuzzy_frame *frame_of(cub_tag_frame **m, int clip, int frame)
{
    return &m[clip][frame].fuzzy;
}

/* Step 3: every link's d is d(a, b) = d(b, a) recomputed, below the
 * threshold; links come by a, front half first, best first; self links
 * skip at least a quarter of the clip. */
static void test_links_are_symmetric_below_threshold_in_order(void **state)
{
    fixture *f = *state;
    int nc = f->lib.clip_count;
    cub_tag_frame *m[SYNTH_CLIPS];
    for (int c = 0; c < nc; c++) {
        m[c] = malloc(sizeof *m[c] * (size_t)f->lib.clips[c].clip.frame_count);
        assert_int_equal(cub_tag_analyse_clip(&f->lib.clips[c].clip, &f->bear.body, m[c]), CUB_OK);
    }
    long links = 0;
    cub_q16 worst = 0;
    for (int a = 0; a < nc; a++)
        for (int b = 0; b < nc; b++) {
            const cub_tag_pair *p = &f->tags.pairs[a * nc + b];
            for (int i = 0; i < p->link_count; i++) {
                const cub_tag_link *l = &p->links[i];
                cub_q16 ab = cub_fuzzy_distance(frame_of(m, a, l->a), frame_of(m, b, l->b),
                                                &f->tags.params.fuzzy);
                cub_q16 ba = cub_fuzzy_distance(frame_of(m, b, l->b), frame_of(m, a, l->a),
                                                &f->tags.params.fuzzy);
                assert_int_equal(ab, ba);
                assert_int_equal(ab, l->d);
                assert_true(l->d < f->tags.params.fuzzy.threshold);
                assert_int_equal(l->half, 2 * l->b < f->tags.clips[b].frame_count ? CUB_TAG_FRONT
                                                                                  : CUB_TAG_BACK);
                if (a == b) assert_true(abs(l->a - l->b) >= f->tags.clips[a].frame_count / 4);
                if (i > 0) {
                    const cub_tag_link *q = &p->links[i - 1];
                    assert_true(
                        q->a < l->a ||
                        (q->a == l->a &&
                         (q->half < l->half ||
                          (q->half == l->half && (q->d < l->d || (q->d == l->d && q->b < l->b))))));
                }
                worst = l->d > worst ? l->d : worst;
                links++;
            }
        }
    printf("tag: synth links=%ld largest d=%.5f (threshold %.3f), all symmetric\n", links,
           worst / 65536.0, f->tags.params.fuzzy.threshold / 65536.0);
    assert_true(links > 0);
    for (int c = 0; c < nc; c++)
        free(m[c]);
}

/* The dance clips of the synthetic library all share the arms-down pose:
 * each ordered pair is joined directly. */
static void test_dance_clips_are_joined(void **state)
{
    fixture *f = *state;
    int dance[] = {SYNTH_ARMS_UP, SYNTH_RIGHT_WAVE, SYNTH_SQUAT};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (i != j) assert_int_equal(cub_tags_chain_length(&f->tags, dance[i], dance[j]), 1);
}

/* Reachability on a hand-made graph 0 -> 1 -> 2, 3 alone, 2 -> 2. */
static void test_chain_length_counts_hops(void **state)
{
    (void)state;
    cub_tag_pair pairs[16] = {0};
    cub_tag_link one = {0, 0, 0, CUB_TAG_FRONT};
    pairs[0 * 4 + 1] = (cub_tag_pair){1, &one};
    pairs[1 * 4 + 2] = (cub_tag_pair){1, &one};
    pairs[2 * 4 + 2] = (cub_tag_pair){1, &one};
    cub_tags t = {.clip_count = 4, .pairs = pairs};
    assert_int_equal(cub_tags_chain_length(&t, 0, 1), 1);
    assert_int_equal(cub_tags_chain_length(&t, 0, 2), 2);
    assert_int_equal(cub_tags_chain_length(&t, 2, 2), 1);
    assert_int_equal(cub_tags_chain_length(&t, 0, 0), -1);
    assert_int_equal(cub_tags_chain_length(&t, 2, 0), -1);
    assert_int_equal(cub_tags_chain_length(&t, 0, 3), -1);
    assert_int_equal(cub_tags_chain_length(&t, 0, 4), -1);
    assert_int_equal(cub_tags_chain_length(NULL, 0, 0), -1);
}

/* Write -> read -> write gives the same bytes; the read tags equal the
 * written ones field by field; tagging twice gives the same bytes. */
static void test_tag_file_round_trips_byte_for_byte(void **state)
{
    fixture *f = *state;
    char *first = NULL, *second = NULL, *again = NULL;
    size_t n1 = 0, n2 = 0, n3 = 0;
    assert_int_equal(cub_tags_print(&f->tags, &first, &n1), CUB_OK);
    cub_tags back;
    cub_diag d = {0};
    cub_err e = cub_tags_parse(first, n1, "synth.tags.xml", &f->lib, &back, &d);
    if (e) fail_msg("%s:%d: %s", d.file, d.line, d.msg);
    assert_int_equal(cub_tags_print(&back, &second, &n2), CUB_OK);
    assert_int_equal(n1, n2);
    assert_memory_equal(first, second, n1);
    assert_memory_equal(&back.params, &f->tags.params, sizeof back.params);
    for (int i = 0; i < back.clip_count * back.clip_count; i++) {
        assert_int_equal(back.pairs[i].link_count, f->tags.pairs[i].link_count);
        if (back.pairs[i].link_count)
            assert_memory_equal(back.pairs[i].links, f->tags.pairs[i].links,
                                sizeof(cub_tag_link) * (size_t)back.pairs[i].link_count);
    }
    cub_tags fresh;
    assert_int_equal(
        cub_tag_library(&f->lib, "synth.cubclips", &f->bear.body, NULL, &fresh, NULL, NULL),
        CUB_OK);
    assert_int_equal(cub_tags_print(&fresh, &again, &n3), CUB_OK);
    assert_int_equal(n1, n3);
    assert_memory_equal(first, again, n1);
    printf("tag: synth tag file %zu bytes, round trip identical\n", n1);
    /* Through a file too. */
    char path[1024];
    const char *build = getenv("CUB_BUILD_DIR");
    snprintf(path, sizeof path, "%s/synth.tags.xml", build ? build : ".");
    assert_int_equal(cub_tags_write(path, &f->tags, &d), CUB_OK);
    cub_tags_free(&back);
    assert_int_equal(cub_tags_read(path, &f->lib, &back, &d), CUB_OK);
    cub_tags_free(&back);
    cub_tags_free(&fresh);
    free(first);
    free(second);
    free(again);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_tagging_rejects_bad_input),
        cmocka_unit_test(test_defaults_are_documented_values),
        cmocka_unit_test(test_bridges_skip_fast_head_motion),
        cmocka_unit_test(test_bridges_are_thinned_and_spread),
        cmocka_unit_test(test_links_are_symmetric_below_threshold_in_order),
        cmocka_unit_test(test_dance_clips_are_joined),
        cmocka_unit_test(test_chain_length_counts_hops),
        cmocka_unit_test(test_tag_file_round_trips_byte_for_byte),
    };
    return cmocka_run_group_tests_name("tag", tests, setup, teardown);
}

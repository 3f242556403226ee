/* The shipped library (assets/clips/bear.cubclips) and its committed tags
 * (assets/clips/bear.tags.xml): every clip has bridge frames, every ordered
 * pair of dance clips is joined directly or through a chain, the committed
 * file validates against the library and equals a fresh tagging byte for
 * byte (on this CPU too: the tagging is integer-only). Skips while the
 * library is not built yet. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "cub/character.h"
#include "cub/tags.h"

typedef struct fixture {
    cub_character bear;
    cub_library lib;
    cub_tags tags;
    char tags_path[1024];
} fixture;

static fixture g;

static int setup(void **state)
{
    char lib_path[1024], bear_path[1024], buf[600];
    const char *src = getenv("CUB_SOURCE_DIR");
    snprintf(lib_path, sizeof lib_path, "%s/assets/clips/bear.cubclips", src ? src : ".");
    snprintf(bear_path, sizeof bear_path, "%s/assets/bear/bear.xml", src ? src : ".");
    snprintf(g.tags_path, sizeof g.tags_path, "%s/assets/clips/bear.tags.xml", src ? src : ".");
    *state = NULL;
    if (access(lib_path, R_OK) != 0) return 0; /* the tests skip */
    cub_diag d = {0};
    cub_fuzzy_body body;
    if (cub_character_load(bear_path, &g.bear, &d) || cub_pack_read(lib_path, &g.lib, &d) ||
        cub_tag_map_body(&g.bear.skel, &g.bear.body, &g.lib.skel, &body, &d)) {
        fprintf(stderr, "shipped: %s\n", cub_diag_str(&d, buf, sizeof buf));
        return -1;
    }
    if (cub_tag_library(&g.lib, "bear.cubclips", &body, NULL, &g.tags, NULL, NULL)) return -1;
    *state = &g;
    return 0;
}

static int teardown(void **state)
{
    if (*state) {
        cub_tags_free(&g.tags);
        cub_library_free(&g.lib);
    }
    return 0;
}

static void test_every_clip_has_bridge_frames(void **state)
{
    fixture *f = *state;
    if (!f) skip();
    long frames = 0, bridges = 0, links = 0;
    int n = f->tags.clip_count;
    for (int c = 0; c < n; c++) {
        frames += f->tags.clips[c].frame_count;
        bridges += f->tags.clips[c].bridge_count;
        if (f->tags.clips[c].bridge_count == 0)
            fail_msg("clip '%s' has no bridge frame", f->tags.clips[c].name);
    }
    for (int i = 0; i < n * n; i++)
        links += f->tags.pairs[i].link_count;
    printf("tag: shipped clips=%d frames=%ld bridge_frames=%ld links=%ld\n", n, frames, bridges,
           links);
}

static void test_every_dance_pair_is_joined(void **state)
{
    fixture *f = *state;
    if (!f) skip();
    int n = f->tags.clip_count, pairs = 0, direct = 0, chained = 0, longest = 0;
    for (int a = 0; a < n; a++)
        for (int b = 0; b < n; b++) {
            if (a == b || strcmp(f->lib.clips[a].kind, "dance") ||
                strcmp(f->lib.clips[b].kind, "dance"))
                continue;
            int len = cub_tags_chain_length(&f->tags, a, b);
            if (len < 0)
                fail_msg("dance clips '%s' -> '%s' are not joined", f->lib.clips[a].name,
                         f->lib.clips[b].name);
            pairs++;
            direct += len == 1;
            chained += len > 1;
            longest = len > longest ? len : longest;
        }
    printf("tag: shipped dance pairs=%d direct=%d chained=%d unreachable=0 longest_chain=%d\n",
           pairs, direct, chained, longest);
    assert_true(pairs >= 10 * 9);
}

static void test_committed_tags_match_a_fresh_run(void **state)
{
    fixture *f = *state;
    if (!f) skip();
    cub_tags committed;
    cub_diag d = {0};
    char buf[600];
    if (cub_tags_read(f->tags_path, &f->lib, &committed, &d))
        fail_msg("%s", cub_diag_str(&d, buf, sizeof buf));
    cub_tags_free(&committed);
    char *fresh = NULL, *file = NULL;
    size_t fresh_len = 0, file_len = 0;
    assert_int_equal(cub_tags_print(&f->tags, &fresh, &fresh_len), CUB_OK);
    cub_text_src src = {f->tags_path, NULL, 0};
    assert_int_equal(cub_text_read(&src, &file, &file_len, &d), CUB_OK);
    size_t at = 0;
    while (at < fresh_len && at < file_len && fresh[at] == file[at])
        at++;
    if (fresh_len != file_len || at < fresh_len)
        fail_msg("%s differs from a fresh tagging at byte %zu (sizes %zu, %zu): re-run "
                 "`cubtool tag --out assets/clips/bear.tags.xml`",
                 f->tags_path, at, file_len, fresh_len);
    printf("tag: committed bear.tags.xml (%zu bytes) equals a fresh tagging\n", file_len);
    free(fresh);
    free(file);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_clip_has_bridge_frames),
        cmocka_unit_test(test_every_dance_pair_is_joined),
        cmocka_unit_test(test_committed_tags_match_a_fresh_run),
    };
    return cmocka_run_group_tests_name("tag_shipped", tests, setup, teardown);
}

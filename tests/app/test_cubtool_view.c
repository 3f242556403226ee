/* cubtool's viewer and renderer bench, run as the real binary (argv[1])
 * headless: bench-render prints its figures in the promised shape, and
 * play writes frames that move, fill both halves side by side, follow the
 * speed, and refuses bad files by name; its scene (the seed's Motion
 * Player), driven by a key script, moves the selected character and only
 * it, zooms, draws bone numbers in points mode and a TRC's markers as
 * numbered points. No timed assertions: the bench's numbers are only
 * checked for sign and for adding up. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/png.h"
#include "run_tool.h"

static const char *g_tool;
static char g_out[1024];

/* Run `cubtool ARGS` (stderr joined to stdout); its output into buf, exit
 * status returned. */
static int run_tool(char *buf, size_t size, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int st = cub_test_run_toolv(g_tool, buf, size, fmt, ap);
    va_end(ap);
    return st;
}

/* ---- bench-render ---------------------------------------------------------- */

static void read_part(const char *out, const char *part, double v[3])
{
    char key[64];
    snprintf(key, sizeof key, "bench-render: %-6s median=", part);
    const char *p = strstr(out, key);
    assert_non_null(p);
    assert_int_equal(sscanf(p + strlen(key) - strlen("median="), "median=%lf ms p95=%lf ms mean=%lf ms", &v[0],
                            &v[1], &v[2]),
                     3);
}

static void test_bench_render_prints_positive_parts_that_add_up(void **state)
{
    (void)state;
    static char out[16384];
    assert_int_equal(run_tool(out, sizeof out, "bench-render --frames 5 --warmup 1 --size 320x180"), 0);
    assert_non_null(strstr(out, "bench-render: 320x180 frames=5 warmup=1 gl_calls="));
    double own[3], drv[3], tot[3], gl[3], wrk[3];
    read_part(out, "own", own);
    read_part(out, "driver", drv);
    read_part(out, "total", tot);
    read_part(out, "gl", gl);
    read_part(out, "worker", wrk);
    for (int i = 0; i < 3; i++) {
        assert_true(own[i] > 0.0 && drv[i] > 0.0 && tot[i] > 0.0 && gl[i] > 0.0);
        assert_true(wrk[i] >= 0.0);
    }
    assert_true(own[1] >= own[0] && drv[1] >= drv[0] && tot[1] >= tot[0]); /* p95 >= median */
    /* Means add up exactly by construction, up to the printed rounding. */
    assert_true(own[2] + drv[2] - tot[2] < 0.002 + 0.001 * tot[2]);
    assert_true(tot[2] - own[2] - drv[2] < 0.002 + 0.001 * tot[2]);
    assert_true(own[2] < tot[2] && drv[2] < tot[2]);
    assert_non_null(strstr(out, "bench-render: own work median "));
    assert_true(strstr(out, " meets the 2 ms target") || strstr(out, " MISSES the 2 ms target"));
}

/* ---- play ------------------------------------------------------------------ */

typedef struct image {
    uint8_t *rgba;
    int w, h;
} image;

static image load_frame(const char *dir, int i)
{
    char path[8192];
    image im = {0};
    snprintf(path, sizeof path, "%s/frame_%05d.png", dir, i);
    if (cub_png_read(path, &im.rgba, &im.w, &im.h) != 0) fail_msg("cannot read %s", path);
    return im;
}

static int same_image(const image *a, const image *b)
{
    return a->w == b->w && a->h == b->h && !memcmp(a->rgba, b->rgba, (size_t)a->w * a->h * 4);
}

/* Pixels in columns [x0, x1) that are the stick figure's browns (bones
 * 128,79,41, joints 77,46,23, head 158,105,56): not sky, not grass. */
static int brown_pixels(const image *im, int x0, int x1)
{
    int n = 0;
    for (int y = 0; y < im->h; y++)
        for (int x = x0; x < x1; x++) {
            const uint8_t *p = im->rgba + ((size_t)y * im->w + x) * 4;
            n += p[0] > p[1] + 25 && p[1] > p[2] + 15 && p[0] >= 60 && p[0] <= 190;
        }
    return n;
}

static void out_dir(char *dir, size_t size, const char *name)
{
    snprintf(dir, size, "%s/%s", g_out, name);
}

/* The index of the last frame that differs from the one before it. */
static int last_change(const char *dir, int frames)
{
    int last = 0;
    image prev = load_frame(dir, 0);
    for (int i = 1; i < frames; i++) {
        image cur = load_frame(dir, i);
        if (!same_image(&prev, &cur)) last = i;
        free(prev.rgba);
        prev = cur;
    }
    free(prev.rgba);
    return last;
}

static void assert_moves(const char *dir, int a, int b)
{
    image f0 = load_frame(dir, a), f1 = load_frame(dir, b);
    assert_false(same_image(&f0, &f1));
    free(f0.rgba);
    free(f1.rgba);
}

static void test_play_pack_clip_on_the_bear_moves(void **state)
{
    (void)state;
    static char out[16384];
    char dir[4096];
    out_dir(dir, sizeof dir, "pack");
    assert_int_equal(run_tool(out, sizeof out, "play '%s/clips/bear.cubclips:jumping_jacks' --side-by-side --frames '%s' "
                                               "--size 160x90 --frame-count 12",
                              CUB_ASSETS_DIR, dir),
                     0);
    assert_non_null(strstr(out, "jumping_jacks: 24 joints, 61 frames"));
    assert_non_null(strstr(out, "on the bear"));
    assert_non_null(strstr(out, "wrote 12 frames"));
    assert_moves(dir, 0, 6);
    assert_moves(dir, 6, 11);
}

static void test_play_bvh_moves(void **state)
{
    (void)state;
    static char out[16384];
    char dir[4096];
    out_dir(dir, sizeof dir, "bvh");
    assert_int_equal(run_tool(out, sizeof out, "play '%s/clips/hello.bvh' --stick --frames '%s' --size 160x90",
                              CUB_ASSETS_DIR, dir),
                     0);
    /* hello.bvh lasts 1.75 s: one play-through is 54 frames at 30 fps. */
    assert_non_null(strstr(out, "wrote 54 frames"));
    assert_moves(dir, 0, 20);
    assert_moves(dir, 20, 40);
}

static void test_play_side_by_side_has_a_figure_in_each_half(void **state)
{
    (void)state;
    static char out[16384];
    char dir[4096];
    out_dir(dir, sizeof dir, "two");
    assert_int_equal(run_tool(out, sizeof out, "play '%s/clips/hello.bvh' '%s/clips/hello.bvh' --side-by-side --stick "
                                               "--frames '%s' --size 320x120 --frame-count 1",
                              CUB_ASSETS_DIR, CUB_ASSETS_DIR, dir),
                     0);
    image im = load_frame(dir, 0);
    assert_int_equal(im.w, 320);
    int left = brown_pixels(&im, 0, 160), right = brown_pixels(&im, 160, 320);
    /* The figure is centred in its half: none on the seam. */
    int seam = brown_pixels(&im, 150, 170);
    free(im.rgba);
    assert_true(left > 100 && right > 100);
    assert_true(left - right < left / 10 && right - left < left / 10); /* the same pose twice */
    assert_int_equal(seam, 0);
}

static void test_play_speed_two_plays_through_in_half_the_frames(void **state)
{
    (void)state;
    static char out[16384];
    char d1[4096], d2[4096];
    out_dir(d1, sizeof d1, "speed1");
    out_dir(d2, sizeof d2, "speed2");
    /* jumping_jacks: 61 frames, 2 s; --once holds the last frame after. */
    const char *clip = CUB_ASSETS_DIR "/clips/bear.cubclips:jumping_jacks";
    assert_int_equal(run_tool(out, sizeof out, "play '%s' --once --frames '%s' --size 96x54 --frame-count 70", clip, d1),
                     0);
    assert_int_equal(
        run_tool(out, sizeof out, "play '%s' --once --speed 2 --frames '%s' --size 96x54 --frame-count 40", clip, d2),
        0);
    int k1 = last_change(d1, 70), k2 = last_change(d2, 40);
    assert_in_range(k1, 55, 60);
    assert_true(abs(k1 - 2 * k2) <= 2);
}

static void test_play_bad_file_fails_naming_it(void **state)
{
    (void)state;
    static char out[16384];
    char dir[4096], bad[4096];
    out_dir(dir, sizeof dir, "bad");
    assert_int_not_equal(run_tool(out, sizeof out, "play '%s/no_such_clip.bvh' --frames '%s'", g_out, dir), 0);
    assert_non_null(strstr(out, "no_such_clip.bvh"));
    snprintf(bad, sizeof bad, "%s/broken.bvh", g_out);
    FILE *f = fopen(bad, "w");
    assert_non_null(f);
    fputs("HIERARCHY\nROOT Hips\n{\n  OFFSET 0 x 0\n", f);
    fclose(f);
    assert_int_equal(run_tool(out, sizeof out, "play '%s' --frames '%s'", bad, dir), 1);
    assert_non_null(strstr(out, "broken.bvh:4"));
    assert_int_equal(run_tool(out, sizeof out, "play '%s/clips/bear.cubclips:no_such_move' --frames '%s'",
                              CUB_ASSETS_DIR, dir),
                     1);
    assert_non_null(strstr(out, "bear.cubclips: no clip named 'no_such_move'"));
}

/* ---- play: the scene ------------------------------------------------------ */

/* Where the pixels of one kind lie: how many, and their mean column and row. */
typedef struct blob {
    int n;
    double x, y;
} blob;

typedef int (*pixel_kind)(const uint8_t *p);

/* The colours render_player.c draws: A blue, B orange, the selection ring
 * yellow, the bone numbers white (sky, floor and grid are none of these). */
static int is_blue(const uint8_t *p) { return p[2] > 200 && p[0] < 140 && p[1] > 120 && p[1] < 210; }
static int is_orange(const uint8_t *p) { return p[0] > 200 && p[1] > 100 && p[1] < 180 && p[2] < 90; }
static int is_yellow(const uint8_t *p) { return p[0] > 200 && p[1] > 190 && p[2] < 80; }
static int is_white(const uint8_t *p) { return p[0] > 235 && p[1] > 235 && p[2] > 235; }

static blob find(const image *im, pixel_kind kind)
{
    blob b = {0};
    for (int y = 0; y < im->h; y++)
        for (int x = 0; x < im->w; x++)
            if (kind(im->rgba + ((size_t)y * im->w + x) * 4)) b.n++, b.x += x, b.y += y;
    if (b.n) b.x /= b.n, b.y /= b.n;
    return b;
}

static blob find_in(const char *dir, int frame, pixel_kind kind)
{
    image im = load_frame(dir, frame);
    blob b = find(&im, kind);
    free(im.rgba);
    return b;
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static void test_play_scene_keys_select_move_zoom_and_number(void **state)
{
    (void)state;
    static char out[65536];
    char dir[4096], keys[4096];
    out_dir(dir, sizeof dir, "scene");
    snprintf(keys, sizeof keys, "%s/scene.keys", g_out);
    write_file(keys, "# pause, select B, move it right, numbers, zoom in\n"
                     "0 Space\n2 2 L L L L L\n4 N\n6 Up Up Up\n");
    assert_int_equal(run_tool(out, sizeof out,
                              "play '%s/clips/hello.bvh' '%s/clips/bear.cubclips:jumping_jacks' "
                              "--frames '%s' --size 480x270 --frame-count 8 --keys '%s'",
                              CUB_ASSETS_DIR, CUB_ASSETS_DIR, dir, keys),
                     0);
    assert_non_null(strstr(out, "play: frame 2 key L: selected=2 move1=0,0 size1=1.000 "
                                "move2=500,0"));
    assert_non_null(strstr(out, "play: frame 4 key N: "));
    assert_non_null(strstr(out, "zoom=1.331"));
    /* Frames 1 and 3: before and after the moves, paused, sticks. */
    blob a1 = find_in(dir, 1, is_blue), b1 = find_in(dir, 1, is_orange);
    blob a3 = find_in(dir, 3, is_blue), b3 = find_in(dir, 3, is_orange);
    assert_true(a1.n > 100 && b1.n > 100);
    assert_true(b3.x - b1.x > 10.0);            /* B went right */
    assert_true(fabs(a3.x - a1.x) < 0.5 && a3.n == a1.n); /* A stayed as it was */
    /* The ring went from A's feet to B's. */
    blob r1 = find_in(dir, 1, is_yellow), r3 = find_in(dir, 3, is_yellow);
    assert_true(r1.n > 20 && r3.n > 20);
    assert_true(fabs(r1.x - a1.x) < fabs(r1.x - b1.x));
    assert_true(fabs(r3.x - b3.x) < fabs(r3.x - a3.x));
    /* Numbers only in points mode. */
    assert_int_equal(find_in(dir, 3, is_white).n, 0);
    blob w5 = find_in(dir, 5, is_white);
    assert_true(w5.n > 50);
    /* Zoomed in: the two characters stand farther apart on the screen. */
    blob a5 = find_in(dir, 5, is_blue), b5 = find_in(dir, 5, is_orange);
    blob a7 = find_in(dir, 7, is_blue), b7 = find_in(dir, 7, is_orange);
    assert_true((b7.x - a7.x) > 1.15 * (b5.x - a5.x));
}

static void test_play_trc_markers_are_numbered_points(void **state)
{
    (void)state;
    static char out[16384];
    char dir[4096];
    out_dir(dir, sizeof dir, "trc");
    assert_int_equal(run_tool(out, sizeof out,
                              "play '%s/../tests/fuzz/seeds_trc/small_mm.trc' --frames '%s' "
                              "--size 480x270 --frame-count 2",
                              CUB_ASSETS_DIR, dir),
                     0);
    assert_non_null(strstr(out, "markers,"));
    assert_non_null(strstr(out, "as points"));
    image im = load_frame(dir, 0);
    blob pts = find(&im, is_blue), nums = find(&im, is_white);
    free(im.rgba);
    assert_true(pts.n > 10);
    assert_true(nums.n > 10); /* markers have no bones: numbered points */
}

static void test_play_bad_key_script_names_the_line(void **state)
{
    (void)state;
    static char out[16384];
    char dir[4096], keys[4096];
    out_dir(dir, sizeof dir, "badkeys");
    snprintf(keys, sizeof keys, "%s/bad.keys", g_out);
    write_file(keys, "0 Space\n# fine so far\n3 L Shift\n");
    assert_int_equal(run_tool(out, sizeof out, "play '%s/clips/hello.bvh' --frames '%s' --keys '%s'",
                              CUB_ASSETS_DIR, dir, keys),
                     1);
    assert_non_null(strstr(out, "bad.keys:3: unknown key \"Shift\""));
    write_file(keys, "5 L\n2 J\n");
    assert_int_equal(run_tool(out, sizeof out, "play '%s/clips/hello.bvh' --frames '%s' --keys '%s'",
                              CUB_ASSETS_DIR, dir, keys),
                     1);
    assert_non_null(strstr(out, "bad.keys:2: frame 2 after frame 5"));
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: test_cubtool_view CUBTOOL\n");
        return 2;
    }
    g_tool = argv[1];
    snprintf(g_out, sizeof g_out, "%s", CUB_TEST_OUT_DIR);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_play_bad_file_fails_naming_it),
        cmocka_unit_test(test_play_pack_clip_on_the_bear_moves),
        cmocka_unit_test(test_play_bvh_moves),
        cmocka_unit_test(test_play_side_by_side_has_a_figure_in_each_half),
        cmocka_unit_test(test_play_speed_two_plays_through_in_half_the_frames),
        cmocka_unit_test(test_play_scene_keys_select_move_zoom_and_number),
        cmocka_unit_test(test_play_trc_markers_are_numbered_points),
        cmocka_unit_test(test_play_bad_key_script_names_the_line),
        cmocka_unit_test(test_bench_render_prints_positive_parts_that_add_up),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* The real cubdance binary replayed the Skeltrack Kinect dump under fakenect
 * (run_cubdance.sh, the fixture of this test). From its event log: all 8
 * frames arrived, in order, with the recorded timestamps; each frame's
 * logged probes equal the recorded pixels; and raw->mm matches the data
 * README's formula mm = 123.6 * tan(raw / 2842.5 + 1.1863) within 1 mm.
 * With the virtual clock the whole log is exact: it must equal the one in
 * expected/, on x86-64 and on aarch64 alike (determinism across CPUs). To
 * accept a deliberate change, copy the new log over it and say why. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
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
#include "replay_log.h"

#define W 640
#define H 480
#define FRAMES 8

static const char *out_dir, *dump_dir, *expected_log;

typedef struct recorded {
    char file[512];
    unsigned timestamp;
    unsigned valid, near_raw, center_raw;
} recorded;

static double formula_mm(unsigned raw) { return 123.6 * tan(raw / 2842.5 + 1.1863); }

/* The dump's INDEX.txt lists d-<seconds>-<timestamp>.pgm files in order. */
static int read_index(recorded *rec, int max)
{
    char path[1024], line[512];
    snprintf(path, sizeof path, "%s/INDEX.txt", dump_dir);
    FILE *f = fopen(path, "r");
    if (!f) return -1;
    int n = 0;
    while (n < max && fgets(line, sizeof line, f)) {
        line[strcspn(line, "\r\n")] = '\0';
        double secs;
        if (line[0] != 'd' || sscanf(line, "d-%lf-%u.pgm", &secs, &rec[n].timestamp) != 2)
            continue;
        snprintf(rec[n].file, sizeof rec[n].file, "%s", line);
        n++;
    }
    fclose(f);
    return n;
}

/* Header "P5 640 480 65535" then little-endian uint16 raw disparity. */
static int read_pgm_stats(recorded *r)
{
    char path[2048];
    int n = snprintf(path, sizeof path, "%s/%s", dump_dir, r->file);
    if (n < 0 || (size_t)n >= sizeof path) return -1;
    FILE *f = fopen(path, "rb");
    if (!f) return -1;
    int w, h, maxv;
    if (fscanf(f, "P5 %d %d %d", &w, &h, &maxv) != 3 || w != W || h != H) {
        fclose(f);
        return -1;
    }
    fgetc(f); /* the single whitespace after the header */
    static uint8_t bytes[W * H * 2];
    size_t got = fread(bytes, 1, sizeof bytes, f);
    fclose(f);
    if (got != sizeof bytes) return -1;
    r->valid = 0;
    r->near_raw = 2047;
    for (int i = 0; i < W * H; i++) {
        unsigned v = bytes[2 * i] | (unsigned)bytes[2 * i + 1] << 8;
        if (v >= 2047) continue;
        r->valid++;
        if (v < r->near_raw) r->near_raw = v;
    }
    int c = (H / 2) * W + W / 2;
    r->center_raw = bytes[2 * c] | (unsigned)bytes[2 * c + 1] << 8;
    return 0;
}

static recorded rec[FRAMES + 1];
static int rec_count;

static int setup(void **s)
{
    rec_count = read_index(rec, FRAMES + 1);
    if (rec_count < 0) return 0; /* the tests skip */
    for (int i = 0; i < rec_count; i++)
        if (read_pgm_stats(&rec[i])) return -1;
    return replay_load_log(out_dir);
}

static void need_data(void)
{
    replay_need_dump(rec_count >= 0, dump_dir);
}

static void test_all_eight_frames_arrive_in_order_with_timestamps(void **s)
{
    need_data();
    assert_int_equal(rec_count, FRAMES);
    assert_int_equal(logread_count(&events, "depth", "frame"), FRAMES);
    int line = -1;
    double last_t = -1;
    for (int i = 0; i < FRAMES; i++) {
        line = logread_find(&events, line + 1, "depth", "frame");
        assert_true(line >= 0);
        assert_int_equal((int)field(line, "seq"), i);
        assert_int_equal((unsigned)field(line, "ts"), rec[i].timestamp);
        assert_true(events.lines[line].t_s >= last_t);
        last_t = events.lines[line].t_s;
    }
    int end = logread_find(&events, 0, "depth", "end");
    assert_true(end > line);
    assert_int_equal((int)field(end, "frames"), FRAMES);
    printf("replay: %d frames in order, timestamps %u..%u as recorded\n", FRAMES,
           rec[0].timestamp, rec[FRAMES - 1].timestamp);
}

static void test_logged_probes_match_the_recorded_pixels(void **s)
{
    need_data();
    for (int i = 0, line = -1; i < FRAMES; i++) {
        line = logread_find(&events, line + 1, "depth", "frame");
        assert_true(line >= 0);
        assert_int_equal((unsigned)field(line, "valid"), rec[i].valid);
        assert_int_equal((unsigned)field(line, "near_raw"), rec[i].near_raw);
        assert_int_equal((unsigned)field(line, "center_raw"), rec[i].center_raw);
        assert_true(rec[i].valid > 1000); /* a person is in every frame */
    }
}

static void test_raw_to_mm_matches_the_formula_within_1mm(void **s)
{
    need_data();
    double worst = 0;
    int checked = 0;
    for (int i = 0, line = -1; i < FRAMES; i++) {
        line = logread_find(&events, line + 1, "depth", "frame");
        const char *probes[][2] = {{"near_raw", "near_mm"}, {"center_raw", "center_mm"}};
        for (int p = 0; p < 2; p++) {
            unsigned raw = (unsigned)field(line, probes[p][0]);
            double mm = field(line, probes[p][1]);
            if (raw >= 2047) {
                assert_true(mm == 0.0); /* no reading */
                continue;
            }
            double err = fabs(mm - formula_mm(raw));
            if (err > worst) worst = err;
            checked++;
            assert_true(err <= 1.0);
        }
    }
    printf("replay: raw->mm max_abs_err=%.4f mm over %d logged probes (limit 1 mm)\n", worst,
           checked);
    assert_true(checked >= FRAMES);
}

static void test_start_plays_and_stop_returns_to_waiting(void **s)
{
    need_data();
    int down = logread_find(&events, 0, "button", "down");
    assert_true(down >= 0);
    int play = logread_find(&events, down, "app", "state");
    assert_true(play >= 0);
    char buf[32];
    assert_string_equal(logread_field(&events.lines[play], "to", buf, sizeof buf), "playing");
    int stop = logread_find(&events, play + 1, "app", "state");
    assert_true(stop >= 0);
    assert_string_equal(logread_field(&events.lines[stop], "to", buf, sizeof buf), "waiting");
    assert_true(events.lines[stop].t_s > events.lines[play].t_s + 0.9);
    assert_true(logread_find(&events, stop, "app", "end") > stop);
}

static void test_headless_frames_were_written(void **s)
{
    need_data();
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/frames", out_dir);
    DIR *d = opendir(dir);
    assert_non_null(d);
    int pngs = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (!strstr(e->d_name, ".png")) continue;
        char path[2048];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        uint8_t *rgba = NULL;
        int w = 0, h = 0;
        assert_int_equal(cub_png_read(path, &rgba, &w, &h), CUB_OK);
        assert_int_equal(w, 320);
        assert_int_equal(h, 240);
        free(rgba);
        pngs++;
    }
    closedir(d);
    int end = logread_find(&events, 0, "app", "end");
    assert_true(end >= 0);
    assert_int_equal(pngs, (int)field(end, "frames_written"));
    assert_true(pngs >= 3);
}

static void test_event_log_is_the_same_on_every_machine(void **s)
{
    need_data();
    logread want;
    assert_int_equal(logread_load(expected_log, &want), 0);
    int n = want.count < events.count ? want.count : events.count;
    for (int i = 0; i < n; i++) {
        const logread_line *a = &want.lines[i], *b = &events.lines[i];
        if (a->t_s != b->t_s || strcmp(a->source, b->source) || strcmp(a->event, b->event) ||
            strcmp(a->rest, b->rest)) {
            printf("replay: line %d differs\n  expected: t=%.3f %s %s %s\n  got:      "
                   "t=%.3f %s %s %s\n",
                   i + 1, a->t_s, a->source, a->event, a->rest, b->t_s, b->source, b->event,
                   b->rest);
            logread_free(&want);
            fail();
        }
    }
    assert_int_equal(events.count, want.count);
    printf("replay: event log identical to %s (%d lines)\n", expected_log, want.count);
    logread_free(&want);
}

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: %s OUT_DIR DUMP_DIR EXPECTED_LOG\n", argv[0]);
        return 2;
    }
    out_dir = argv[1];
    dump_dir = argv[2];
    expected_log = argv[3];
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_all_eight_frames_arrive_in_order_with_timestamps),
        cmocka_unit_test(test_logged_probes_match_the_recorded_pixels),
        cmocka_unit_test(test_raw_to_mm_matches_the_formula_within_1mm),
        cmocka_unit_test(test_start_plays_and_stop_returns_to_waiting),
        cmocka_unit_test(test_headless_frames_were_written),
        cmocka_unit_test(test_event_log_is_the_same_on_every_machine),
    };
    return cmocka_run_group_tests_name("replay_skeltrack", tests, setup, replay_teardown);
}

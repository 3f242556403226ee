/* The real cubdance binary replayed a dump shaped like fakenect-record's
 * (make_accel_dump.sh: a colour frame and five accelerometer lines beside
 * every depth frame) under fakenect and the virtual clock. From its event
 * log: every depth frame arrived, in order, each at its recorded time (the
 * Kinect timestamp's distance from the first frame's); the camera was never
 * taken for lost before the dump ended; no line's time is earlier than the
 * line before it; and the level camera's reading reached the tracker as
 * gravity from the first frame that had one before it. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "replay_log.h"

#define MAX_FRAMES 4096

static const char *out_dir, *dump_dir;
static unsigned timestamps[MAX_FRAMES];
static int frame_count = -1; /* depth lines in the dump's INDEX.txt; -1: no dump */
static int accel_lines;

/* INDEX.txt: d-<seconds>-<timestamp>.pgm, a-...dump, r-...ppm lines. */
static int read_index(void)
{
    char path[1024], line[512];
    snprintf(path, sizeof path, "%s/INDEX.txt", dump_dir);
    FILE *f = fopen(path, "r");
    if (!f) return -1;
    int n = 0;
    double secs;
    while (n < MAX_FRAMES && fgets(line, sizeof line, f)) {
        if (line[0] == 'a') accel_lines++;
        if (line[0] == 'd' && sscanf(line, "d-%lf-%u.pgm", &secs, &timestamps[n]) == 2) n++;
    }
    fclose(f);
    return n;
}

static int setup(void **s)
{
    frame_count = read_index();
    if (frame_count < 0) return 0; /* the tests skip */
    return replay_load_log(out_dir);
}

static void need_data(void)
{
    replay_need_dump(frame_count >= 0, dump_dir);
}

/* Recorded time of frame i in ms since the first, as the log prints it:
 * the timestamp's 60 MHz ticks, to whole microseconds, truncated to ms. */
static long recorded_ms(int i)
{
    return (long)((uint32_t)(timestamps[i] - timestamps[0]) / 60 / 1000);
}

static void test_every_depth_frame_arrives_at_its_recorded_time(void **s)
{
    need_data();
    assert_true(frame_count > 30);
    assert_true(accel_lines >= 2 * frame_count); /* several a- lines a frame */
    assert_int_equal(logread_count(&events, "depth", "frame"), frame_count);
    int line = -1;
    for (int i = 0; i < frame_count; i++) {
        line = logread_find(&events, line + 1, "depth", "frame");
        assert_true(line >= 0);
        assert_int_equal((int)field(line, "seq"), i);
        assert_int_equal((unsigned)field(line, "ts"), timestamps[i]);
        long t_ms = (long)(events.lines[line].t_s * 1000 + 0.5);
        if (t_ms != recorded_ms(i))
            fail_msg("frame %d logged at %ld ms, recorded at %ld ms", i, t_ms, recorded_ms(i));
    }
    int end = logread_find(&events, 0, "depth", "end");
    assert_true(end > line);
    assert_int_equal((int)field(end, "frames"), frame_count);
    printf("replay: %d depth frames (beside %d accelerometer lines) each at its recorded time\n",
           frame_count, accel_lines);
}

static void test_camera_is_not_lost_before_the_dump_ends(void **s)
{
    need_data();
    int end = logread_find(&events, 0, "depth", "end");
    assert_true(end >= 0);
    for (int i = logread_find(&events, 0, "watch", "camera"); i >= 0 && i < end;
         i = logread_find(&events, i + 1, "watch", "camera"))
        fail_msg("log line %d: %s before the dump's end", i + 1, events.lines[i].rest);
}

static void test_log_times_never_go_backwards(void **s)
{
    need_data();
    for (int i = 1; i < events.count; i++)
        if (events.lines[i].t_s < events.lines[i - 1].t_s)
            fail_msg("log line %d (t=%.3f %s %s) is earlier than the line before (t=%.3f)", i + 1,
                     events.lines[i].t_s, events.lines[i].source, events.lines[i].event,
                     events.lines[i - 1].t_s);
}

/* The first depth frame comes before any a- line (fakenect-record writes
 * one only once a frame has arrived): gravity is known from the second. */
static void test_accelerometer_reaches_the_tracker(void **s)
{
    need_data();
    assert_int_equal(logread_count(&events, "watch", "gravity"), 1);
    int g = logread_find(&events, 0, "watch", "gravity");
    char buf[64];
    assert_string_equal(logread_field(&events.lines[g], "state", buf, sizeof buf), "known");
    assert_string_equal(logread_field(&events.lines[g], "accel", buf, sizeof buf), "0,819,0");
    int second = logread_find(&events, logread_find(&events, 0, "depth", "frame") + 1, "depth",
                              "frame");
    assert_true(second >= 0);
    assert_true(events.lines[g].t_s == events.lines[second].t_s);
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: %s OUT_DIR DUMP_DIR\n", argv[0]);
        return 2;
    }
    out_dir = argv[1];
    dump_dir = argv[2];
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_depth_frame_arrives_at_its_recorded_time),
        cmocka_unit_test(test_camera_is_not_lost_before_the_dump_ends),
        cmocka_unit_test(test_log_times_never_go_backwards),
        cmocka_unit_test(test_accelerometer_reaches_the_tracker),
    };
    return cmocka_run_group_tests_name("replay_accel", tests, setup, replay_teardown);
}

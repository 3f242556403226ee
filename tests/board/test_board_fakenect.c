/* The libfreenect depth source under fakenect, replaying the real skeltrack
 * dump ($CUB_DATA_DIR/depth/skeltrack): the calls the box makes to a live
 * Kinect. CMake runs this with LD_LIBRARY_PATH=<fakenect dir> and
 * FAKENECT_PATH=<the dump>. Every frame must arrive, in order, with the
 * dump's timestamps and exactly the dump's pixels, then CUB_ERR_END.
 * Broken dumps: a missing accelerometer file, a short colour frame, or no
 * good depth frame are refused with INDEX.txt:line; truncated and missing
 * depth frames among real ones replay as frames without readings (run with
 * the argument "mended", in a process of its own); with accelerometer lines
 * between the frames, as fakenect-record writes them, every frame arrives
 * with the reading before it (argument "accel"). */
#define _GNU_SOURCE /* realpath, symlink, mkdtemp, popen */

#include <fcntl.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "clock.h"
#include "depth.h"

#include <libfreenect.h>

#define MAX_FRAMES 64
#define FRAME_PIXELS (CUB_DEPTH_W * CUB_DEPTH_H)

typedef struct dump {
    int count;
    char name[MAX_FRAMES][256];
    uint32_t timestamp[MAX_FRAMES]; /* from the file name: d-<time>-<timestamp>.pgm */
} dump;

static cub_board_clock real_clock; /* started at 0: a real clock */

static const char *dump_dir(void)
{
    const char *dir = getenv("FAKENECT_PATH");
    char path[1024];
    if (!dir) {
        return NULL;
    }
    snprintf(path, sizeof path, "%s/INDEX.txt", dir);
    return access(path, R_OK) == 0 ? dir : NULL;
}

static void read_index(const char *dir, dump *d)
{
    char path[1024], line[256];
    snprintf(path, sizeof path, "%s/INDEX.txt", dir);
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    d->count = 0;
    while (fgets(line, sizeof line, f) && d->count < MAX_FRAMES) {
        line[strcspn(line, "\r\n")] = '\0';
        double t;
        unsigned ts;
        if (line[0] == 'd' && sscanf(line, "d-%lf-%u", &t, &ts) == 2) {
            snprintf(d->name[d->count], sizeof d->name[0], "%s", line);
            d->timestamp[d->count++] = ts;
        }
    }
    fclose(f);
}

/* The frame's pixels: little-endian uint16 after the one-line header. */
static void read_pgm(const char *dir, const char *name, uint16_t *px)
{
    char path[1024], header[64];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    assert_non_null(fgets(header, sizeof header, f));
    assert_int_equal(strncmp(header, "P5 640 480", 10), 0);
    uint8_t *bytes = malloc(FRAME_PIXELS * 2);
    assert_int_equal(fread(bytes, 2, FRAME_PIXELS, f), FRAME_PIXELS);
    fclose(f);
    for (int i = 0; i < FRAME_PIXELS; i++) {
        px[i] = (uint16_t)(bytes[2 * i] | bytes[2 * i + 1] << 8);
    }
    free(bytes);
}

/* The next poll that is not CUB_ERR_EMPTY. Under the real clock a reader
 * thread takes fakenect's sleeps, so a poll never waits: poll every 1 ms
 * (a frame comes every 33) for up to 10 s. polls counts every poll. */
static cub_err next_frame(cub_depth *src, cub_depth_frame *f, int *polls)
{
    int64_t give_up = cub_clock_mono_us() + 10000000;
    for (;;) {
        ++*polls;
        cub_err e = cub_depth_poll(src, f);
        if (e != CUB_ERR_EMPTY || cub_clock_mono_us() > give_up) return e;
        cub_clock_sleep_until_mono_us(cub_clock_mono_us() + 1000);
    }
}

static void test_replay_gives_every_frame_then_end(void **state)
{
    const char *dir = dump_dir();
    if (!dir) {
        const char *env = getenv("FAKENECT_PATH");
        printf("fakenect: skipped: no dump at FAKENECT_PATH=%s "
               "(needs $CUB_DATA_DIR/depth/skeltrack)\n",
               env ? env : "(unset)");
        skip();
    }
    dump d;
    read_index(dir, &d);
    assert_true(d.count > 0);

    cub_board_clock clock;
    cub_board_clock_start(&clock, 0);
    int64_t origin = clock.origin_mono_us;
    cub_depth *src;
    char err[512];
    cub_err e = cub_depth_open(CUB_DEPTH_FREENECT, &clock, &src, err, sizeof err);
    if (e) {
        fail_msg("depth open: %s: %s (is LD_LIBRARY_PATH the fakenect dir?)", cub_err_str(e), err);
    }
    assert_string_equal(cub_depth_name(src), "fakenect");

    uint16_t *want = malloc(FRAME_PIXELS * sizeof *want);
    int got = 0, polls = 0;
    int64_t t_prev = -1;
    uint32_t ts_prev = 0;
    cub_depth_frame f;
    while ((e = next_frame(src, &f, &polls)) == CUB_OK) {
        assert_true(got < d.count);
        assert_int_equal(f.seq, (uint32_t)got);
        assert_int_equal(f.timestamp, d.timestamp[got]);
        assert_true(got == 0 || f.timestamp > ts_prev);
        assert_true(f.t_us > t_prev);
        read_pgm(dir, d.name[got], want);
        int diff = 0;
        for (int i = 0; i < FRAME_PIXELS; i++) {
            diff += f.raw[i] != want[i];
        }
        if (diff) {
            fail_msg("frame %d (%s): %d pixels differ from the dump", got, d.name[got], diff);
        }
        ts_prev = f.timestamp;
        t_prev = f.t_us;
        got++;
    }
    assert_int_equal(e, CUB_ERR_END);
    assert_int_equal(got, d.count);
    printf("fakenect: %d/%d frames in order, pixels exact, end after %d polls, %.3f s, "
           "accel=%d,%d,%d\n",
           got, d.count, polls, (cub_clock_mono_us() - origin) / 1e6, f.accel[0], f.accel[1],
           f.accel[2]);
    assert_int_equal(cub_depth_poll(src, &f), CUB_ERR_END); /* and stays ended */
    free(want);
    cub_depth_close(src);
}

/* Open the freenect source on the dump in dir (FAKENECT_PATH set for the
 * call, then put back as it was). */
static cub_err open_dump(const char *dir, cub_depth **src, char *err, size_t err_size)
{
    char *saved = getenv("FAKENECT_PATH") ? strdup(getenv("FAKENECT_PATH")) : NULL;
    setenv("FAKENECT_PATH", dir, 1);
    cub_err e = cub_depth_open(CUB_DEPTH_FREENECT, &real_clock, src, err, err_size);
    if (saved) {
        setenv("FAKENECT_PATH", saved, 1);
        free(saved);
    }
    return e;
}

/* A dump naming a missing accelerometer file is refused with
 * INDEX.txt:line, before fakenect could exit() the program (only depth
 * frames are mended). Refusals never reach fakenect, so they may run before
 * the replay: fakenect 0.5.3 replays one dump per process (it reads
 * FAKENECT_PATH and opens INDEX.txt at its first event, once). */
static void test_broken_dump_is_refused_with_line(void **state)
{
    char dir[] = "/tmp/cub_dump_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char path[256];
    snprintf(path, sizeof path, "%s/INDEX.txt", dir);
    FILE *f = fopen(path, "w");
    fputs("a-1300000000.000000-0.dump\nd-1300000000.000000-1000.pgm\n", f);
    fclose(f);
    cub_depth *src = NULL;
    char err[512];
    cub_err e = open_dump(dir, &src, err, sizeof err);
    unlink(path);
    rmdir(dir);
    if (e == CUB_ERR_DEVICE && strstr(err, "no Kinect")) {
        fail_msg("fakenect is not loaded (LD_LIBRARY_PATH?): %s", err);
    }
    printf("fakenect: broken dump: %s\n", err);
    assert_int_equal(e, CUB_ERR_FORMAT);
    assert_null(src);
    assert_non_null(strstr(err, "INDEX.txt:1: cannot open a-1300000000.000000-0.dump"));
}


static void write_file(const char *dir, const char *name, const char *text)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

/* Files and directories directly in dir (the views a test's TMPDIR holds). */
static int count_entries(const char *dir)
{
    char cmd[1100];
    snprintf(cmd, sizeof cmd, "ls -A '%s' | wc -l", dir);
    FILE *p = popen(cmd, "r");
    int n = -1;
    assert_non_null(p);
    assert_int_equal(fscanf(p, "%d", &n), 1);
    pclose(p);
    return n;
}

static void remove_tree(const char *dir)
{
    char cmd[1100];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    assert_int_equal(system(cmd), 0);
}

/* A short colour frame would be read past its end: still refused. */
static void test_short_colour_frame_is_refused(void **state)
{
    char dir[] = "/tmp/cub_dump_XXXXXX";
    assert_non_null(mkdtemp(dir));
    write_file(dir, "INDEX.txt", "r-1300000000.000000-1000.ppm\n");
    write_file(dir, "r-1300000000.000000-1000.ppm", "P6 640 480 255\n0123456789");
    cub_depth *src = NULL;
    char err[512];
    cub_err e = open_dump(dir, &src, err, sizeof err);
    remove_tree(dir);
    printf("fakenect: short colour frame: %s\n", err);
    assert_int_equal(e, CUB_ERR_FORMAT);
    assert_null(src);
    assert_non_null(
        strstr(err, "INDEX.txt:1: r-1300000000.000000-1000.ppm is not a 640x480 frame"));
}

/* Every depth frame bad (one truncated, one missing): nothing to replay,
 * refused naming the first bad file, and no view is left behind. */
static void test_dump_of_only_bad_frames_is_refused(void **state)
{
    char dir[] = "/tmp/cub_dump_XXXXXX", tmp[] = "/tmp/cub_tmp_XXXXXX";
    assert_non_null(mkdtemp(dir));
    assert_non_null(mkdtemp(tmp));
    write_file(dir, "INDEX.txt", "d-1300000000.000000-1000.pgm\nd-1300000000.033333-3000.pgm\n");
    write_file(dir, "d-1300000000.000000-1000.pgm", "P5 640 480 65535\n0123456789");
    char *saved_tmp = getenv("TMPDIR") ? strdup(getenv("TMPDIR")) : NULL;
    setenv("TMPDIR", tmp, 1);
    cub_depth *src = NULL;
    char err[512];
    cub_err e = open_dump(dir, &src, err, sizeof err);
    saved_tmp ? setenv("TMPDIR", saved_tmp, 1) : unsetenv("TMPDIR");
    free(saved_tmp);
    int left = count_entries(tmp);
    remove_tree(dir);
    remove_tree(tmp);
    printf("fakenect: only bad frames: %s\n", err);
    assert_int_equal(e, CUB_ERR_FORMAT);
    assert_null(src);
    assert_non_null(strstr(err, "INDEX.txt:1: d-1300000000.000000-1000.pgm: truncated: 27 of "
                                "614417 bytes; no good depth frame"));
    assert_int_equal(left, 0);
}

/* The real dump FAKENECT_PATH names, its frames read into d; skips the
 * test without it. */
static const char *real_dump(dump *d)
{
    const char *real = dump_dir();
    if (!real) {
        printf("fakenect: skipped: no real dump (needs $CUB_DATA_DIR/depth/skeltrack)\n");
        skip();
    }
    read_index(real, d);
    return real;
}

/* The mended-dump test: the real frames with line BAD_SHORT + 1 cut short
 * and line BAD_MISSING + 1 gone. */
#define BAD_SHORT 3
#define BAD_MISSING 5
#define SHORT_BYTES 1234

static void make_mended_dump(const char *src, const dump *d, const char *dir)
{
    char real[1024], index[64 * 64] = "", from[2048], to[2048];
    assert_non_null(realpath(src, real));
    for (int k = 0; k < d->count; k++) {
        strcat(index, d->name[k]);
        strcat(index, "\n");
        snprintf(from, sizeof from, "%s/%s", real, d->name[k]);
        snprintf(to, sizeof to, "%s/%s", dir, d->name[k]);
        if (k == BAD_SHORT) {
            char bytes[SHORT_BYTES];
            FILE *in = fopen(from, "rb"), *out = fopen(to, "wb");
            assert_true(in && out);
            assert_int_equal(fread(bytes, 1, sizeof bytes, in), sizeof bytes);
            assert_int_equal(fwrite(bytes, 1, sizeof bytes, out), sizeof bytes);
            fclose(in);
            fclose(out);
        } else if (k != BAD_MISSING) {
            assert_int_equal(symlink(from, to), 0);
        }
    }
    write_file(dir, "INDEX.txt", index);
}

/* stderr into path until put back (the board's warnings are the test's). */
static int capture_stderr(const char *path)
{
    fflush(stderr);
    int saved = dup(2), fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    assert_true(saved >= 0 && fd >= 0);
    dup2(fd, 2);
    close(fd);
    return saved;
}

static void put_back_stderr(int saved)
{
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
}

/* The warnings the open printed: one line per bad file, naming it. */
static void check_warnings(const char *path, const dump *d)
{
    char line[1024], want[512];
    int warnings = 0, short_seen = 0, missing_seen = 0;
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    while (fgets(line, sizeof line, f)) {
        if (!strstr(line, "replayed as a frame without readings")) continue;
        warnings++;
        printf("fakenect: warning: %s", line);
        snprintf(want, sizeof want, "INDEX.txt:%d: %s: truncated: %d of 614417 bytes",
                 BAD_SHORT + 1, d->name[BAD_SHORT], SHORT_BYTES);
        short_seen += strstr(line, want) != NULL;
        snprintf(want, sizeof want, "INDEX.txt:%d: %s: missing", BAD_MISSING + 1,
                 d->name[BAD_MISSING]);
        missing_seen += strstr(line, want) != NULL;
    }
    fclose(f);
    assert_int_equal(warnings, 2);
    assert_int_equal(short_seen, 1);
    assert_int_equal(missing_seen, 1);
}

static int valid_pixels(const uint16_t *raw)
{
    int n = 0;
    for (int i = 0; i < FRAME_PIXELS; i++) n += raw[i] != CUB_DEPTH_NO_READING;
    return n;
}

/* Replays the mended dump to its end: every frame in order, the bad ones
 * without a single reading, the good ones (also those after the bad ones)
 * exactly the real frames. Returns the frames delivered. */
static int replay_mended(cub_depth *src, const char *real, const dump *d, const char *dump_dir)
{
    uint16_t *want = malloc(FRAME_PIXELS * sizeof *want);
    cub_depth_frame f;
    cub_err e = CUB_OK;
    int got = 0, polls = 0;
    while ((e = next_frame(src, &f, &polls)) == CUB_OK) {
        /* fakenect has read FAKENECT_PATH: the caller's value is back. */
        assert_string_equal(getenv("FAKENECT_PATH"), dump_dir);
        assert_true(got < d->count);
        assert_int_equal(f.seq, (uint32_t)got);
        assert_int_equal(f.timestamp, d->timestamp[got]);
        if (got == BAD_SHORT || got == BAD_MISSING) {
            assert_int_equal(valid_pixels(f.raw), 0);
        } else {
            read_pgm(real, d->name[got], want);
            assert_memory_equal(f.raw, want, FRAME_PIXELS * sizeof *want);
        }
        got++;
    }
    free(want);
    assert_int_equal(e, CUB_ERR_END);
    return got;
}

/* A truncated and a missing frame in the middle of real frames: the dump
 * opens, the bad frames come as frames without readings, the real frames
 * after them come back, and the private view is gone after close. */
static void test_truncated_and_missing_frames_replay_without_readings(void **state)
{
    dump d;
    const char *real = real_dump(&d);
    assert_true(d.count > BAD_MISSING + 1);
    char dir[] = "/tmp/cub_dump_XXXXXX", tmp[] = "/tmp/cub_tmp_XXXXXX", log[64];
    assert_non_null(mkdtemp(dir));
    assert_non_null(mkdtemp(tmp));
    make_mended_dump(real, &d, dir);
    snprintf(log, sizeof log, "%s.stderr", dir);
    /* FAKENECT_PATH stays set until the end: fakenect reads it at its first
     * event, in the first poll. */
    char *saved = strdup(real);
    setenv("FAKENECT_PATH", dir, 1);
    setenv("TMPDIR", tmp, 1);
    int err_fd = capture_stderr(log);
    cub_depth *src = NULL;
    char err[512];
    cub_err e = cub_depth_open(CUB_DEPTH_FREENECT, &real_clock, &src, err, sizeof err);
    put_back_stderr(err_fd);
    if (e) fail_msg("mended dump refused: %s: %s", cub_err_str(e), err);
    check_warnings(log, &d);
    int views = count_entries(tmp);
    int got = replay_mended(src, real, &d, dir);
    cub_depth_close(src);
    int views_after = count_entries(tmp);
    setenv("FAKENECT_PATH", saved, 1);
    free(saved);
    unlink(log);
    remove_tree(dir);
    remove_tree(tmp);
    printf("fakenect: mended dump: %d/%d frames in order; truncated (line %d) and missing "
           "(line %d) without readings, the %d real frames exact; views in TMPDIR: %d open, "
           "%d after close\n",
           got, d.count, BAD_SHORT + 1, BAD_MISSING + 1, d.count - 2, views, views_after);
    assert_int_equal(got, d.count);
    assert_int_equal(views, 1);
    assert_int_equal(views_after, 0);
}

/* The accelerometer test: fakenect-record's shape, ACCEL_LINES a- lines
 * after every depth frame, the last one after frame k reading (k, 819, -k);
 * the first after frame EMPTY_ACCEL_AFTER is empty (a recording cut off). */
#define ACCEL_LINES 3
#define EMPTY_ACCEL_AFTER 2

static void truncate_file(const char *dir, const char *name)
{
    char path[2048];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fclose(f);
}

static void write_tilt(const char *dir, const char *name, int16_t x, int16_t y, int16_t z)
{
    char path[2048];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    freenect_raw_tilt_state st = {.accelerometer_x = x, .accelerometer_y = y, .accelerometer_z = z};
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(&st, sizeof st, 1, f), 1);
    fclose(f);
}

static void make_accel_dump(const char *src, const dump *d, const char *dir)
{
    char real[1024], index[64 * 64 * (ACCEL_LINES + 1)] = "", from[2048], to[2048], name[128];
    assert_non_null(realpath(src, real));
    for (int k = 0; k < d->count; k++) {
        snprintf(from, sizeof from, "%s/%s", real, d->name[k]);
        snprintf(to, sizeof to, "%s/%s", dir, d->name[k]);
        assert_int_equal(symlink(from, to), 0);
        strcat(strcat(index, d->name[k]), "\n");
        double t_s;
        sscanf(d->name[k], "d-%lf", &t_s);
        for (int i = 1; i <= ACCEL_LINES; i++) {
            snprintf(name, sizeof name, "a-%f-%u.dump", t_s + 0.008 * i, d->timestamp[k]);
            write_tilt(dir, name, (int16_t)(i == ACCEL_LINES ? k : 99), 819, (int16_t)-k);
            if (k == EMPTY_ACCEL_AFTER && i == 1) truncate_file(dir, name);
            strcat(strcat(index, name), "\n");
        }
    }
    write_file(dir, "INDEX.txt", index);
}

/* Under the real clock (a reader thread drains fakenect), with several
 * accelerometer lines between depth frames: every frame arrives, each with
 * the reading of the last a- line before it (none before the first). An
 * empty a- file, which would end fakenect's replay, is mended. */
static void test_accel_lines_between_frames_every_frame_arrives(void **state)
{
    dump d;
    const char *real = real_dump(&d);
    char dir[] = "/tmp/cub_dump_XXXXXX";
    assert_non_null(mkdtemp(dir));
    make_accel_dump(real, &d, dir);
    cub_depth *src = NULL;
    char err[512];
    int64_t t0 = cub_clock_mono_us();
    /* Set until the end: fakenect reads it at its first event, in the
     * first poll. */
    setenv("FAKENECT_PATH", dir, 1);
    cub_err e = cub_depth_open(CUB_DEPTH_FREENECT, &real_clock, &src, err, sizeof err);
    if (e) fail_msg("accelerometer dump refused: %s: %s", cub_err_str(e), err);
    cub_depth_frame f;
    int got = 0, polls = 0;
    while ((e = next_frame(src, &f, &polls)) == CUB_OK) {
        assert_true(got < d.count);
        assert_int_equal(f.seq, (uint32_t)got);
        assert_int_equal(f.timestamp, d.timestamp[got]);
        int16_t want_x = (int16_t)(got - 1), want_y = got ? 819 : 0, want_z = (int16_t)(1 - got);
        if (!got) want_x = want_z = 0;
        assert_int_equal(f.accel[0], want_x);
        assert_int_equal(f.accel[1], want_y);
        assert_int_equal(f.accel[2], want_z);
        got++;
    }
    cub_depth_close(src);
    remove_tree(dir);
    assert_int_equal(e, CUB_ERR_END);
    assert_int_equal(got, d.count);
    printf("fakenect: %d/%d frames among %d accelerometer lines, each with the reading before "
           "it, in %.3f s (recorded: %.3f s)\n",
           got, d.count, d.count * ACCEL_LINES, (cub_clock_mono_us() - t0) / 1e6,
           (uint32_t)(d.timestamp[d.count - 1] - d.timestamp[0]) / 60e6);
}

/* fakenect replays one dump per process: the mended-dump and accelerometer
 * replays run in processes of their own (ctest test_board_fakenect_mended,
 * _accel: argument "mended", "accel"). */
int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_broken_dump_is_refused_with_line),
        cmocka_unit_test(test_short_colour_frame_is_refused),
        cmocka_unit_test(test_dump_of_only_bad_frames_is_refused),
        cmocka_unit_test(test_replay_gives_every_frame_then_end),
    };
    const struct CMUnitTest mended[] = {
        cmocka_unit_test(test_truncated_and_missing_frames_replay_without_readings),
    };
    const struct CMUnitTest accel[] = {
        cmocka_unit_test(test_accel_lines_between_frames_every_frame_arrives),
    };
    if (argc > 1 && !strcmp(argv[1], "mended")) return cmocka_run_group_tests(mended, NULL, NULL);
    if (argc > 1 && !strcmp(argv[1], "accel")) return cmocka_run_group_tests(accel, NULL, NULL);
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* The libfreenect depth source under fakenect, replaying the real skeltrack
 * dump ($CUB_DATA_DIR/depth/skeltrack): the calls the box makes to a live
 * Kinect. CMake runs this with LD_LIBRARY_PATH=<fakenect dir> and
 * FAKENECT_PATH=<the dump>. Every frame must arrive, in order, with the
 * dump's timestamps and exactly the dump's pixels, then CUB_ERR_END. */
#define _POSIX_C_SOURCE 200809L

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
    /* fakenect sleeps inside each poll until the next recorded frame time;
     * the poll bound only keeps a broken replay from running forever. */
    for (e = CUB_OK; polls < 10000; polls++) {
        e = cub_depth_poll(src, &f);
        if (e == CUB_ERR_EMPTY) {
            continue;
        }
        if (e != CUB_OK) {
            break;
        }
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
           got, d.count, polls + 1, (cub_clock_mono_us() - origin) / 1e6, f.accel[0], f.accel[1],
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

/* A dump naming a missing file is refused with INDEX.txt:line, before
 * fakenect could exit() the program. Runs first: fakenect reads
 * FAKENECT_PATH once, at freenect_init. */
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

/* A frame file too short for a 640x480 frame would make fakenect read past
 * its buffer: refused up front. */
static void test_short_frame_is_refused(void **state)
{
    char dir[] = "/tmp/cub_dump_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char index[256], frame[256];
    snprintf(index, sizeof index, "%s/INDEX.txt", dir);
    snprintf(frame, sizeof frame, "%s/d-1300000000.000000-1000.pgm", dir);
    FILE *f = fopen(index, "w");
    fputs("d-1300000000.000000-1000.pgm\n", f);
    fclose(f);
    f = fopen(frame, "w");
    fputs("P5 640 480 65535\n0123456789", f);
    fclose(f);
    cub_depth *src = NULL;
    char err[512];
    cub_err e = open_dump(dir, &src, err, sizeof err);
    unlink(frame);
    unlink(index);
    rmdir(dir);
    printf("fakenect: short frame: %s\n", err);
    assert_int_equal(e, CUB_ERR_FORMAT);
    assert_non_null(
        strstr(err, "INDEX.txt:1: d-1300000000.000000-1000.pgm is not a 640x480 frame"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_broken_dump_is_refused_with_line),
        cmocka_unit_test(test_short_frame_is_refused),
        cmocka_unit_test(test_replay_gives_every_frame_then_end),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* libFuzzer target: a whole fakenect dump (built from the input as
 * fuzz_dump_build.h says), checked by the box's dump check
 * (board/common/fakenect_dump.c) and then replayed by fakenect itself.
 * When the check accepts the dump, fakenect (dlopened from
 * CUB_FAKENECT_DIR, fresh per input: it keeps its INDEX.txt open in static
 * state and has no reset) replays up to 40 lines, each depth frame copied
 * whole as the box's on_depth does, so ASan sees a frame fakenect reads
 * past its file. fakenect calls exit() on what it cannot read: libFuzzer
 * reports that as a crash, i.e. a dump the check should have refused or
 * mended. Its sleeps to the recorded times are made no-ops here (the
 * fuzzer must not wait for wall-clock time; the box's virtual clock does
 * not either, see depth_freenect.c), as tests/soak/fakenect_nosleep.c does.
 * Whatever the input: no crash, no view left behind, FAKENECT_PATH back. */
#define _GNU_SOURCE /* setenv, usleep, dlopen */

#include <dirent.h>
#include <dlfcn.h>
#include <fcntl.h>
#include <libfreenect.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fakenect_dump.h"
#include "fuzz_dump_build.h"
#include "fuzz_tally.h"

#define DEPTH_BYTES (640 * 480 * 2)
#define MAX_LINES 40
#define MAX_FDS 256

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

unsigned int sleep(unsigned int s)
{
    (void)s;
    return 0;
}

int usleep(useconds_t us)
{
    (void)us;
    return 0;
}

/* ---- fakenect, as board/common/depth_freenect.c drives it ---------------- */

typedef struct fakenect {
    void *lib;
    int (*init)(freenect_context **, freenect_usb_context *);
    int (*open)(freenect_context *, freenect_device **, int);
    freenect_frame_mode (*find_mode)(freenect_resolution, freenect_depth_format);
    int (*set_mode)(freenect_device *, const freenect_frame_mode);
    void (*set_cb)(freenect_device *, freenect_depth_cb);
    int (*start)(freenect_device *);
    int (*process)(freenect_context *);
    freenect_raw_tilt_state *(*tilt)(freenect_device *);
    int (*stop)(freenect_device *);
    int (*close)(freenect_device *);
    int (*shutdown)(freenect_context *);
} fakenect;

static unsigned long frames_seen, pixel_sum;

static void on_depth(freenect_device *dev, void *depth, uint32_t timestamp)
{
    static uint16_t copy[DEPTH_BYTES / 2];
    memcpy(copy, depth, DEPTH_BYTES); /* what the box copies */
    pixel_sum += copy[0] + copy[DEPTH_BYTES / 2 - 1] + timestamp;
    frames_seen++;
}

static int load(fakenect *f)
{
    /* Debian's fakenect: its soname, else the development link. */
    f->lib = dlopen(CUB_FAKENECT_DIR "/libfreenect.so.0.5", RTLD_NOW | RTLD_LOCAL);
    if (!f->lib) f->lib = dlopen(CUB_FAKENECT_DIR "/libfreenect.so", RTLD_NOW | RTLD_LOCAL);
    if (!f->lib) {
        fprintf(stderr, "fuzz_fakenect_dump: %s\n", dlerror());
        abort();
    }
#define SYM(field, name) *(void **)&f->field = dlsym(f->lib, name)
    SYM(init, "freenect_init");
    SYM(open, "freenect_open_device");
    SYM(find_mode, "freenect_find_depth_mode");
    SYM(set_mode, "freenect_set_depth_mode");
    SYM(set_cb, "freenect_set_depth_callback");
    SYM(start, "freenect_start_depth");
    SYM(process, "freenect_process_events");
    SYM(tilt, "freenect_get_tilt_state");
    SYM(stop, "freenect_stop_depth");
    SYM(close, "freenect_close_device");
    SYM(shutdown, "freenect_shutdown");
#undef SYM
    return f->init && f->open && f->find_mode && f->set_mode && f->set_cb && f->start &&
           f->process && f->tilt && f->stop && f->close && f->shutdown;
}

/* The descriptors open now, so that those fakenect leaves open (it never
 * closes its INDEX.txt) can be closed after it is unloaded. */
static void open_fds(char open[MAX_FDS])
{
    for (int fd = 0; fd < MAX_FDS; fd++) open[fd] = fcntl(fd, F_GETFD) != -1;
}

static void replay(cub_fakenect_view *v, int lines)
{
    char before[MAX_FDS], after[MAX_FDS];
    open_fds(before);
    fakenect f;
    if (!load(&f)) abort();
    freenect_context *ctx = NULL;
    freenect_device *dev = NULL;
    if (f.init(&ctx, NULL) < 0 || f.open(ctx, &dev, 0) < 0) abort();
    f.set_mode(dev, f.find_mode(FREENECT_RESOLUTION_MEDIUM, FREENECT_DEPTH_11BIT));
    f.set_cb(dev, on_depth);
    f.start(dev);
    for (int i = 0; i < lines + 1 && i < MAX_LINES; i++) {
        int got = f.process(ctx);
        cub_fakenect_dump_restore_env(v);
        freenect_raw_tilt_state *st = f.tilt(dev);
        pixel_sum += st ? (unsigned)st->accelerometer_x : 0;
        if (got < 0) break;
    }
    f.stop(dev);
    f.close(dev);
    f.shutdown(ctx);
    dlclose(f.lib);
    open_fds(after);
    for (int fd = 0; fd < MAX_FDS; fd++)
        if (after[fd] && !before[fd]) close(fd);
}

static int dir_is_empty(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return 0;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d))) n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
    closedir(d);
    return n == 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *dump_dir = cub_fuzz_dump_dir("fuzz_fakenect_dump");
    int lines = cub_fuzz_dump_make(data, size);
    setenv("FAKENECT_PATH", dump_dir, 1);
    cub_fakenect_view v;
    memset(&v, 0, sizeof v);
    char err[512] = "";
    cub_err e = cub_fakenect_dump_prepare(&v, err, sizeof err);
    if (e && strncmp(err, "fakenect dump ", 14) != 0) { /* a refusal names the dump */
        fprintf(stderr, "fuzz_fakenect_dump: refused as \"%s\"\n", err);
        abort();
    }
    unsigned long seen = frames_seen;
    if (!e) replay(&v, lines);
    cub_fuzz_tally("fuzz_fakenect_dump", !e && frames_seen > seen); /* accepted, frames replayed */
    cub_fakenect_dump_release(&v);
    const char *p = getenv("FAKENECT_PATH");
    if (!p || strcmp(p, dump_dir) != 0) abort();
    if (!dir_is_empty(cub_fuzz_dump_tmp())) abort();
    return 0;
}

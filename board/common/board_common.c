/* board_common — the cub_board functions both boards share. */
#include "board_impl.h"
#include "clock.h"
#include "keys_sdl.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

cub_board_desc cub_board_desc_defaults(const cub_board_desc *desc)
{
    cub_board_desc d = {0};
    if (desc) {
        d = *desc;
    }
    if (d.width <= 0 || d.height <= 0) {
        d.width = 1280;
        d.height = 720;
    }
    if (d.audio_rate <= 0) {
        d.audio_rate = 44100;
    }
    if (!d.storage_dir || !d.storage_dir[0]) {
        d.storage_dir = ".";
    }
    return d;
}

cub_err cub_board_common_open(const cub_board_desc *desc, cub_board **out, char *err,
                              size_t err_size)
{
    *out = NULL;
    cub_board *b = calloc(1, sizeof *b);
    if (!b) {
        snprintf(err, err_size, "board: out of memory");
        return CUB_ERR_NOMEM;
    }
    b->desc = cub_board_desc_defaults(desc);
    size_t n = strlen(b->desc.storage_dir);
    if (n >= sizeof b->storage_dir) {
        snprintf(err, err_size, "board: storage directory name too long (%zu bytes)", n);
        free(b);
        return CUB_ERR_ARG;
    }
    memcpy(b->storage_dir, b->desc.storage_dir, n + 1);
    while (n > 1 && b->storage_dir[n - 1] == '/') {
        b->storage_dir[--n] = '\0';
    }
    if (b->desc.audio_driver) {
        snprintf(b->audio_driver, sizeof b->audio_driver, "%s", b->desc.audio_driver);
    }
    /* The desc's strings belong to the caller: only copies are kept. */
    b->desc.storage_dir = b->storage_dir;
    b->desc.audio_driver = b->audio_driver[0] ? b->audio_driver : NULL;
    if (b->desc.video_driver) {
        snprintf(b->video_driver, sizeof b->video_driver, "%s", b->desc.video_driver);
    }
    b->desc.video_driver = b->video_driver[0] ? b->video_driver : NULL;
    b->desc.button_script = NULL;
    b->desc.gpio = NULL;
    cub_err e = CUB_OK;
    if (desc && desc->button_script) {
        e = cub_button_script_load(desc->button_script, &b->script, err, err_size);
    }
    if (e) {
        cub_board_common_close(b);
        return e;
    }
    *out = b;
    return CUB_OK;
}

/* The board's time starts here, once the slow parts (the display's EGL or
 * SDL set-up) are done, so that t=0 is when the program can first act and a
 * scripted press at 0.1 s happens 0.1 s into the run. */
cub_err cub_board_common_start(cub_board *b, char *err, size_t err_size)
{
    cub_board_clock_start(&b->clock, b->desc.virtual_clock);
    return cub_depth_open(b->desc.depth, &b->clock, &b->depth, err, err_size);
}

void cub_board_common_close(cub_board *b)
{
    if (!b) {
        return;
    }
    cub_audio_sdl_close(b->audio);
    if (b->close_buttons) {
        b->close_buttons(b->buttons);
    }
    cub_button_script_free(b->script);
    if (b->display) {
        cub_display_close(b->display);
    }
    cub_depth_close(b->depth);
    free(b);
}

/* ---- clock ------------------------------------------------------------- */

int64_t cub_board_now_us(cub_board *b)
{
    return cub_board_clock_now_us(&b->clock);
}

void cub_board_sleep_until_us(cub_board *b, int64_t t_us)
{
    cub_board_clock_sleep_until_us(&b->clock, t_us);
}

/* ---- buttons ----------------------------------------------------------- */

void cub_board_poll_buttons(cub_board *b, cub_loop *loop, int64_t now_us)
{
    if (!b || !loop) {
        return;
    }
    if (b->script) {
        cub_button_script_poll(b->script, loop, now_us);
    } else if (b->poll_buttons) {
        b->poll_buttons(b->buttons, loop, now_us);
    }
    if (b->display && !cub_display_is_headless(b->display)) {
        /* SDL wants its queue drained while a window is open; window close
         * is QUIT either way, keys are buttons only without a script. */
        cub_keys_sdl_poll(loop, now_us, b->script == NULL);
    }
}

/* ---- depth ------------------------------------------------------------- */

cub_err cub_board_depth_poll(cub_board *b, cub_depth_frame *out)
{
    cub_err e = cub_depth_poll(b->depth, out);
    if (e == CUB_OK && b->depth_tap) {
        b->depth_tap(b->depth_tap_user, out);
    }
    return e;
}

void cub_board_set_depth_tap(cub_board *b, cub_board_depth_tap tap, void *user)
{
    b->depth_tap = tap;
    b->depth_tap_user = user;
}

const char *cub_board_depth_source(cub_board *b)
{
    return cub_depth_name(b->depth);
}

/* ---- display ----------------------------------------------------------- */

int cub_board_display_active(cub_board *b)
{
    return b->display != NULL;
}

int cub_board_display_headless(cub_board *b)
{
    return b->display && cub_display_is_headless(b->display);
}

void cub_board_display_size(cub_board *b, int *w, int *h)
{
    int dw = 0, dh = 0;
    if (b->display) {
        cub_display_size(b->display, &dw, &dh);
    }
    if (w) {
        *w = dw;
    }
    if (h) {
        *h = dh;
    }
}

void cub_board_display_swap(cub_board *b)
{
    if (b->display) {
        cub_display_swap(b->display);
    }
}

const char *cub_board_display_lost(cub_board *b)
{
    return b->display ? cub_display_lost(b->display) : NULL;
}

cub_err cub_board_display_read_rgba(cub_board *b, uint8_t *rgba, size_t size)
{
    if (!b->display) {
        return CUB_ERR_DEVICE;
    }
    return cub_display_read_rgba(b->display, rgba, size);
}

void cub_board_set_ready(cub_board *b, int ready)
{
    if (b && b->set_ready && !b->script) {
        b->set_ready(b->buttons, ready);
    }
}

/* ---- audio ------------------------------------------------------------- */

cub_err cub_board_audio_start(cub_board *b, cub_audio_fill fill, void *user)
{
    if (!b || !fill) {
        return CUB_ERR_ARG;
    }
    cub_board_audio_stop(b);
    b->audio_frames_done = 0;
    /* The "disk" driver writes the PCM stream; keep it with the logs. */
    char disk_file[CUB_BOARD_PATH_MAX];
    const char *disk = NULL;
    if (cub_board_storage_path(b, "audio.raw", disk_file, sizeof disk_file) == CUB_OK) {
        disk = disk_file;
    }
    char err[512];
    int volume = b->desc.audio_volume == CUB_BOARD_MUTE ? 0
                 : b->desc.audio_volume > 0          ? b->desc.audio_volume
                                                     : 100;
    cub_err e = cub_audio_sdl_open(b->desc.audio_driver, disk, b->desc.audio_rate, volume, fill,
                                   user, &b->audio, err, sizeof err);
    if (e) {
        /* board.h has no message channel here; the app carries on silent. */
        fprintf(stderr, "cubdance: %s (running without sound)\n", err);
    }
    return e;
}

void cub_board_audio_stop(cub_board *b)
{
    if (b && b->audio) {
        b->audio_frames_done = cub_audio_sdl_frames(b->audio);
        cub_audio_sdl_close(b->audio);
        b->audio = NULL;
    }
}

uint64_t cub_board_audio_frames(cub_board *b)
{
    return b->audio ? cub_audio_sdl_frames(b->audio) : b->audio_frames_done;
}

int cub_board_audio_rate(cub_board *b)
{
    return b->desc.audio_rate;
}

/* ---- storage ----------------------------------------------------------- */

/* Names stay inside the storage directory: relative, no ".." step. */
static int name_ok(const char *name)
{
    if (!name[0] || name[0] == '/') {
        return 0;
    }
    for (const char *c = name; *c;) {
        size_t n = strcspn(c, "/");
        if (n == 2 && c[0] == '.' && c[1] == '.') {
            return 0;
        }
        c += n;
        c += *c == '/';
    }
    return 1;
}

cub_err cub_board_storage_path(cub_board *b, const char *name, char *buf, size_t size)
{
    if (!b || !name || !buf || size == 0 || !name_ok(name)) {
        return CUB_ERR_ARG;
    }
    int n = snprintf(buf, size, "%s/%s", b->storage_dir, name);
    if (n < 0 || (size_t)n >= size) {
        buf[0] = '\0';
        return CUB_ERR_NOMEM;
    }
    return CUB_OK;
}

/* ---- opening a board of a kind ------------------------------------------ */

/* The desc's driver, else the board's; its size, or 0x0 for the screen's.
 * A failure says "no display", the board's hint, and SDL's own words. */
static cub_err open_window(const cub_board_kind *kind, cub_board *b, char *err, size_t err_size)
{
    const cub_board_desc *d = &b->desc;
    const char *driver = d->video_driver ? d->video_driver : kind->video_driver;
    int w = d->fit_screen ? 0 : d->width, h = d->fit_screen ? 0 : d->height;
    char why[400] = "";
    cub_err e = cub_display_open_screen(w, h, driver, d->fullscreen, &b->display, why, sizeof why);
    if (e)
        snprintf(err, err_size, "no display: %s%s",
                 kind->no_display_hint ? kind->no_display_hint : "", why);
    return e;
}

static cub_err open_display(const cub_board_kind *kind, cub_board *b, char *err,
                            size_t err_size)
{
    const cub_board_desc *d = &b->desc;
    switch (d->display) {
    case CUB_DISPLAY_NONE: return CUB_OK;
    case CUB_DISPLAY_HEADLESS:
        return cub_display_open_headless(d->width, d->height, &b->display, err, err_size);
    case CUB_DISPLAY_WINDOW:
        return open_window(kind, b, err, err_size);
    case CUB_DISPLAY_AUTO:
        if (kind->window_required) return open_window(kind, b, err, err_size);
        if ((!kind->probe_window || cub_display_window_available()) &&
            open_window(kind, b, err, err_size) == CUB_OK)
            return CUB_OK;
        return cub_display_open_headless(d->width, d->height, &b->display, err, err_size);
    }
    snprintf(err, err_size, "board: unknown display mode %d", (int)d->display);
    return CUB_ERR_ARG;
}

cub_err cub_board_open_kind(const cub_board_kind *kind, const cub_board_desc *desc,
                            cub_board **out, char *err_msg, size_t err_size)
{
    char local[512];
    if (!err_msg || err_size == 0) {
        err_msg = local;
        err_size = sizeof local;
    }
    err_msg[0] = '\0';
    if (!out) {
        snprintf(err_msg, err_size, "board: no place for the board (out is NULL)");
        return CUB_ERR_ARG;
    }
    *out = NULL;
    cub_board *b = NULL;
    cub_err e = cub_board_common_open(desc, &b, err_msg, err_size);
    if (e) return e;
    e = open_display(kind, b, err_msg, err_size);
    if (!e) e = cub_board_common_start(b, err_msg, err_size);
    /* Buttons last: a debouncer starts from the board's clock. */
    if (!e && !b->script && kind->open_buttons) e = kind->open_buttons(b, desc, err_msg, err_size);
    if (e) {
        cub_board_common_close(b);
        return e;
    }
    *out = b;
    return CUB_OK;
}

/* The sim board's glue: open/close with each part chosen by the desc, the
 * board clock, scripted buttons through cub_board_poll_buttons, the depth
 * source, storage paths, and SDL audio on the "dummy" driver. */
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

#include <SDL.h>

#include "cub/board.h"
#include "keys_sdl.h"

static char script_path[64];

static int write_script(void **state)
{
    snprintf(script_path, sizeof script_path, "/tmp/cub_sim_script_XXXXXX");
    int fd = mkstemp(script_path);
    assert_true(fd >= 0);
    const char *text = "0.05 start\n0.3 stop down\n0.35 stop up\n";
    assert_int_equal(write(fd, text, strlen(text)), (ssize_t)strlen(text));
    close(fd);
    return 0;
}

static int remove_script(void **state)
{
    unlink(script_path);
    return 0;
}

static cub_board *open_quiet(const char *script)
{
    cub_board_desc desc = {
        .display = CUB_DISPLAY_NONE,
        .depth = CUB_DEPTH_EMPTY,
        .button_script = script,
        .audio_driver = "dummy",
        .storage_dir = "/tmp/cubstore/",
    };
    cub_board *b = NULL;
    char err[256];
    cub_err e = cub_board_open(&desc, &b, err, sizeof err);
    if (e) {
        fail_msg("board open: %s: %s", cub_err_str(e), err);
    }
    return b;
}

static void test_open_reports_bad_script_and_args(void **state)
{
    cub_board_desc desc = {.display = CUB_DISPLAY_NONE, .depth = CUB_DEPTH_OFF,
                           .button_script = "/nonexistent/buttons.txt"};
    cub_board *b = (cub_board *)1;
    char err[256];
    assert_int_equal(cub_board_open(&desc, &b, err, sizeof err), CUB_ERR_IO);
    assert_null(b);
    assert_non_null(strstr(err, "/nonexistent/buttons.txt"));
    assert_int_equal(cub_board_open(&desc, NULL, NULL, 0), CUB_ERR_ARG);
    assert_string_equal(cub_board_name(), "sim");
}

static void test_scripted_buttons_arrive_through_the_board(void **state)
{
    cub_board *b = open_quiet(script_path);
    assert_int_equal(cub_board_display_active(b), 0);
    cub_loop_desc ld = {0};
    size_t size = cub_loop_mem_size(&ld);
    void *mem = malloc(size);
    cub_loop loop;
    assert_int_equal(cub_loop_init(&loop, &ld, mem, size), CUB_OK);

    /* Tick at 30 Hz of board time until the last edge (0.35 s) is due. */
    int64_t t = 0;
    for (int tick = 0; t < 400000; tick++) {
        t = (int64_t)tick * 1000000 / 30;
        cub_board_sleep_until_us(b, t);
        int64_t now = cub_board_now_us(b);
        assert_true(now >= t);
        cub_board_poll_buttons(b, &loop, now);
    }
    int64_t want_t[4] = {50000, 150000, 300000, 350000};
    int32_t want_type[4] = {CUB_EV_BUTTON_DOWN, CUB_EV_BUTTON_UP, CUB_EV_BUTTON_DOWN,
                            CUB_EV_BUTTON_UP};
    int32_t want_a[4] = {CUB_BUTTON_START, CUB_BUTTON_START, CUB_BUTTON_STOP, CUB_BUTTON_STOP};
    cub_event ev;
    for (int i = 0; i < 4; i++) {
        assert_int_equal(cub_queue_pop(&loop.queue, &ev), CUB_OK);
        assert_int_equal(ev.t_us, want_t[i]);
        assert_int_equal(ev.type, want_type[i]);
        assert_int_equal(ev.a, want_a[i]);
    }
    assert_int_equal(cub_queue_pop(&loop.queue, &ev), CUB_ERR_EMPTY);
    free(mem);
    cub_board_close(b);
}

static void test_depth_and_storage(void **state)
{
    cub_board *b = open_quiet(NULL);
    assert_string_equal(cub_board_depth_source(b), "empty");
    cub_depth_frame f;
    cub_board_sleep_until_us(b, 40000);
    assert_int_equal(cub_board_depth_poll(b, &f), CUB_OK);
    assert_int_equal(f.raw[0], CUB_DEPTH_NO_READING);

    char path[64];
    assert_int_equal(cub_board_storage_path(b, "logs/events.log", path, sizeof path), CUB_OK);
    assert_string_equal(path, "/tmp/cubstore/logs/events.log");
    assert_int_equal(cub_board_storage_path(b, "/etc/passwd", path, sizeof path), CUB_ERR_ARG);
    assert_int_equal(cub_board_storage_path(b, "../up", path, sizeof path), CUB_ERR_ARG);
    assert_int_equal(cub_board_storage_path(b, "a/../../up", path, sizeof path), CUB_ERR_ARG);
    assert_int_equal(cub_board_storage_path(b, "", path, sizeof path), CUB_ERR_ARG);
    assert_int_equal(cub_board_storage_path(b, "..hidden", path, sizeof path), CUB_OK);
    char tiny[8];
    assert_int_equal(cub_board_storage_path(b, "events.log", tiny, sizeof tiny), CUB_ERR_NOMEM);
    cub_board_close(b);

    cub_board_desc off = {.display = CUB_DISPLAY_NONE, .depth = CUB_DEPTH_OFF};
    char err[128];
    assert_int_equal(cub_board_open(&off, &b, err, sizeof err), CUB_OK);
    assert_string_equal(cub_board_depth_source(b), "off");
    assert_int_equal(cub_board_depth_poll(b, &f), CUB_ERR_DEVICE);
    assert_int_equal(cub_board_audio_rate(b), 44100);
    assert_int_equal(cub_board_storage_path(b, "x", path, sizeof path), CUB_OK);
    assert_string_equal(path, "./x");
    cub_board_close(b);
}

/* AUTO depth: libfreenect if a Kinect opens, else the empty scene (build
 * machines have no Kinect). */
static void test_auto_depth_falls_back_to_empty(void **state)
{
    cub_board_desc desc = {.display = CUB_DISPLAY_NONE};
    cub_board *b;
    char err[256];
    cub_err e = cub_board_open(&desc, &b, err, sizeof err);
    if (e) {
        fail_msg("board open: %s: %s", cub_err_str(e), err);
    }
    const char *src = cub_board_depth_source(b);
    printf("board: depth auto -> %s\n", src);
    assert_true(strcmp(src, "empty") == 0 || strcmp(src, "freenect") == 0);
    cub_board_close(b);
}

/* The display glue: a headless (EGL surfaceless) display of the asked size. */
static void test_headless_display_glue(void **state)
{
    cub_board_desc desc = {.display = CUB_DISPLAY_HEADLESS, .depth = CUB_DEPTH_OFF,
                           .width = 64, .height = 48};
    cub_board *b;
    char err[256];
    cub_err e = cub_board_open(&desc, &b, err, sizeof err);
    if (e) {
        fail_msg("board open headless: %s: %s", cub_err_str(e), err);
    }
    assert_int_equal(cub_board_display_active(b), 1);
    assert_int_equal(cub_board_display_headless(b), 1);
    int w, h;
    cub_board_display_size(b, &w, &h);
    assert_int_equal(w, 64);
    assert_int_equal(h, 48);
    cub_board_display_swap(b);
    uint8_t *rgba = malloc(64 * 48 * 4);
    assert_int_equal(cub_board_display_read_rgba(b, rgba, 64 * 48 * 4), CUB_OK);
    free(rgba);
    cub_board_close(b);
}

static void push_key(Uint32 type, SDL_Keycode key, int repeat)
{
    SDL_Event e = {0};
    e.type = type;
    e.key.keysym.sym = key;
    e.key.repeat = (Uint8)repeat;
    assert_int_equal(SDL_PushEvent(&e), 1);
}

/* The window's keys: Space/Enter/S = START, Escape/Backspace/X = STOP,
 * key repeat ignored, other keys ignored, window close = QUIT. Fed through
 * SDL's own event queue (no window needed for that). */
static void test_keys_map_to_buttons_and_quit(void **state)
{
    assert_int_equal(SDL_InitSubSystem(SDL_INIT_EVENTS), 0);
    cub_loop_desc ld = {0};
    size_t size = cub_loop_mem_size(&ld);
    void *mem = malloc(size);
    cub_loop loop;
    assert_int_equal(cub_loop_init(&loop, &ld, mem, size), CUB_OK);
    push_key(SDL_KEYDOWN, SDLK_SPACE, 0);
    push_key(SDL_KEYDOWN, SDLK_SPACE, 1);
    push_key(SDL_KEYUP, SDLK_SPACE, 0);
    push_key(SDL_KEYDOWN, SDLK_a, 0);
    push_key(SDL_KEYDOWN, SDLK_ESCAPE, 0);
    push_key(SDL_KEYUP, SDLK_x, 0);
    SDL_Event quit = {.type = SDL_QUIT};
    SDL_PushEvent(&quit);
    cub_keys_sdl_poll(&loop, 1234, 1);
    int32_t want_type[5] = {CUB_EV_BUTTON_DOWN, CUB_EV_BUTTON_UP, CUB_EV_BUTTON_DOWN,
                            CUB_EV_BUTTON_UP, CUB_EV_QUIT};
    int32_t want_a[5] = {CUB_BUTTON_START, CUB_BUTTON_START, CUB_BUTTON_STOP, CUB_BUTTON_STOP, 0};
    cub_event ev;
    for (int i = 0; i < 5; i++) {
        assert_int_equal(cub_queue_pop(&loop.queue, &ev), CUB_OK);
        assert_int_equal(ev.type, want_type[i]);
        assert_int_equal(ev.a, want_a[i]);
        assert_int_equal(ev.t_us, 1234);
    }
    assert_int_equal(cub_queue_pop(&loop.queue, &ev), CUB_ERR_EMPTY);
    /* While a script drives the buttons, keys are drained but ignored. */
    push_key(SDL_KEYDOWN, SDLK_RETURN, 0);
    cub_keys_sdl_poll(&loop, 2000, 0);
    assert_int_equal(cub_queue_pop(&loop.queue, &ev), CUB_ERR_EMPTY);
    SDL_QuitSubSystem(SDL_INIT_EVENTS);
    free(mem);
}

typedef struct tone {
    int calls;
    int64_t frames;
} tone;

/* SDL's audio thread: a square wave, so the buffer is not silence. */
static void fill_tone(void *user, int16_t *stereo, int frames)
{
    tone *t = user;
    for (int i = 0; i < frames; i++) {
        int16_t v = ((t->frames + i) / 50) % 2 ? 3000 : -3000;
        stereo[2 * i] = stereo[2 * i + 1] = v;
    }
    t->frames += frames;
    t->calls++;
}

static void test_audio_dummy_driver_runs_the_music_clock(void **state)
{
    cub_board *b = open_quiet(NULL);
    tone t = {0};
    assert_int_equal(cub_board_audio_frames(b), 0);
    cub_err e = cub_board_audio_start(b, fill_tone, &t);
    assert_int_equal(e, CUB_OK);
    /* The dummy driver consumes in real time; wait (at most 10 s, for qemu)
     * for a tenth of a second of sound. */
    int64_t until = cub_board_now_us(b) + 10000000;
    while (cub_board_audio_frames(b) < 4410 && cub_board_now_us(b) < until) {
        cub_board_sleep_until_us(b, cub_board_now_us(b) + 10000);
    }
    cub_board_audio_stop(b);
    uint64_t frames = cub_board_audio_frames(b);
    printf("audio dummy: %llu frames in %d callbacks\n", (unsigned long long)frames, t.calls);
    assert_true(frames >= 4410);
    assert_int_equal(frames, (uint64_t)t.frames); /* the clock counts what was filled */
    assert_int_equal(cub_board_audio_frames(b), frames); /* frozen after stop */
    cub_board_close(b);
}

/* Play the tone through the "disk" driver at a volume (0 = the default)
 * into dir until 2048 frames (or 10 s) have played; the file's path into
 * path, the frames the callback filled as the result. */
static uint64_t play_tone_to_disk(const char *dir, int volume, char *path, size_t path_size)
{
    cub_board_desc desc = {.display = CUB_DISPLAY_NONE, .depth = CUB_DEPTH_OFF,
                           .audio_driver = "disk", .audio_rate = 22050, .storage_dir = dir,
                           .audio_volume = volume};
    cub_board *b;
    char err[128];
    assert_int_equal(cub_board_open(&desc, &b, err, sizeof err), CUB_OK);
    assert_int_equal(cub_board_audio_rate(b), 22050);
    tone t = {0};
    assert_int_equal(cub_board_audio_start(b, fill_tone, &t), CUB_OK);
    int64_t until = cub_board_now_us(b) + 10000000;
    while (cub_board_audio_frames(b) < 2048 && cub_board_now_us(b) < until) {
        cub_board_sleep_until_us(b, cub_board_now_us(b) + 10000);
    }
    cub_board_audio_stop(b);
    uint64_t frames = cub_board_audio_frames(b);
    assert_int_equal(cub_board_storage_path(b, "audio.raw", path, path_size), CUB_OK);
    cub_board_close(b);
    return frames;
}

/* The "disk" driver writes the stream into the storage directory. */
static void test_audio_disk_driver_writes_storage_file(void **state)
{
    char dir[] = "/tmp/cub_audio_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char path[128];
    uint64_t frames = play_tone_to_disk(dir, 0, path, sizeof path);
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    /* SDL writes silence while the device is paused, so the tone may start
     * after a silent buffer: find its first sample, and count its samples. */
    fseek(f, 0, SEEK_SET);
    int16_t sample[2];
    long silent = 0, tone_frames = 0;
    int16_t first = 0;
    while (fread(sample, sizeof sample[0], 2, f) == 2) {
        if (!first && sample[0] == 0) silent++;
        else if (!first) first = sample[0];
        if (sample[0] == 3000 || sample[0] == -3000) tone_frames++;
    }
    fclose(f);
    printf("audio disk: %llu frames, %ld bytes (%ld silent frames first, %ld tone frames) in %s\n",
           (unsigned long long)frames, size, silent, tone_frames, path);
    assert_true(frames >= 2048);
    assert_int_equal(first, -3000); /* the tone's first sample */
    /* Every frame the callback filled is in the file: closing the device
     * joins SDL's thread, which writes each buffer it filled. */
    assert_true((uint64_t)tone_frames >= frames);
    unlink(path);
    rmdir(dir);
}

/* Play the tone through the disk driver at a volume; the largest sample
 * magnitude the file holds and how many frames were filled. */
static int disk_peak_at_volume(int volume, uint64_t *frames)
{
    char dir[] = "/tmp/cub_volume_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char path[128];
    *frames = play_tone_to_disk(dir, volume, path, sizeof path);
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    int16_t s;
    int peak = 0;
    while (fread(&s, sizeof s, 1, f) == 1) {
        if (abs(s) > peak) peak = abs(s);
    }
    fclose(f);
    unlink(path);
    rmdir(dir);
    return peak;
}

/* The config's volume reaches the samples the device plays. */
static void test_audio_volume_scales_the_samples(void **state)
{
    uint64_t frames;
    int full = disk_peak_at_volume(0, &frames); /* 0 = the default, full */
    int half = disk_peak_at_volume(50, &frames);
    int mute = disk_peak_at_volume(CUB_BOARD_MUTE, &frames);
    printf("audio volume: peak %d at 100 %%, %d at 50 %%, %d muted (%llu frames)\n", full, half,
           mute, (unsigned long long)frames);
    assert_int_equal(full, 3000);
    assert_int_equal(half, 1500);
    assert_int_equal(mute, 0);
    assert_true(frames >= 2048); /* muted, the music clock still runs */
}

static void test_audio_bad_driver_is_a_device_error(void **state)
{
    cub_board_desc desc = {.display = CUB_DISPLAY_NONE, .depth = CUB_DEPTH_OFF,
                           .audio_driver = "no-such-driver"};
    cub_board *b;
    char err[128];
    assert_int_equal(cub_board_open(&desc, &b, err, sizeof err), CUB_OK);
    tone t = {0};
    assert_int_equal(cub_board_audio_start(b, fill_tone, &t), CUB_ERR_DEVICE);
    assert_int_equal(cub_board_audio_frames(b), 0);
    assert_int_equal(cub_board_audio_start(b, NULL, &t), CUB_ERR_ARG);
    cub_board_close(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_open_reports_bad_script_and_args),
        cmocka_unit_test(test_scripted_buttons_arrive_through_the_board),
        cmocka_unit_test(test_depth_and_storage),
        cmocka_unit_test(test_auto_depth_falls_back_to_empty),
        cmocka_unit_test(test_headless_display_glue),
        cmocka_unit_test(test_keys_map_to_buttons_and_quit),
        cmocka_unit_test(test_audio_dummy_driver_runs_the_music_clock),
        cmocka_unit_test(test_audio_disk_driver_writes_storage_file),
        cmocka_unit_test(test_audio_bad_driver_is_a_device_error),
        cmocka_unit_test(test_audio_volume_scales_the_samples),
    };
    return cmocka_run_group_tests(tests, write_script, remove_script);
}

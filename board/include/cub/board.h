/* board — the one hardware interface the app sees. Two implementations
 * link against it: board/sim (a PC) and board/pi (the box). Pick one at
 * build time (CUB_BOARD=sim|pi).
 *
 *   buttons  START and STOP, debounced, delivered as loop events
 *   depth    640x480 raw 11-bit Kinect frames from libfreenect (live, or
 *            replayed by fakenect from a dump: same calls either way)
 *   display  an OpenGL ES 2 context: an SDL2 window (KMSDRM on the box),
 *            or headless EGL (surfaceless Mesa) with pixel read-back
 *   audio    a PCM sink the app fills from a callback; its sample position
 *            is the music clock
 *   clock    monotonic microseconds
 *   storage  where config, logs and (opt-in) recordings live
 *
 * Nothing here opens a network port or stores camera data by itself.
 */
#ifndef CUB_BOARD_H
#define CUB_BOARD_H

#include <stddef.h>
#include <stdint.h>

#include "cub/boxconf.h"
#include "cub/err.h"
#include "cub/loop.h"

#define CUB_DEPTH_W 640
#define CUB_DEPTH_H 480
#define CUB_DEPTH_NO_READING 2047 /* raw value meaning "no depth here" */

typedef enum cub_display_mode {
    CUB_DISPLAY_AUTO = 0, /* a window if a display exists, else headless */
    CUB_DISPLAY_WINDOW,   /* SDL2 window (sim) or SDL2 KMSDRM full screen (pi) */
    CUB_DISPLAY_HEADLESS, /* EGL surfaceless, off-screen, read back as RGBA */
    CUB_DISPLAY_NONE,     /* no GL at all (tools, some tests) */
} cub_display_mode;

typedef enum cub_depth_mode {
    CUB_DEPTH_AUTO = 0, /* libfreenect; if no Kinect, the built-in empty scene */
    CUB_DEPTH_FREENECT, /* libfreenect only (live device or fakenect replay) */
    CUB_DEPTH_EMPTY,    /* built-in empty scene: every pixel "no reading" */
    CUB_DEPTH_OFF,      /* no depth source at all */
} cub_depth_mode;

typedef struct cub_board_desc {
    cub_display_mode display;   /* default AUTO */
    int width, height;          /* display size; default 1280x720 */
    int fit_screen;             /* 1: a window takes the screen's own mode (headless:
                                   width x height) */
    int fullscreen;             /* 0 = the board's way (pi: full screen on KMSDRM;
                                   sim: a window), 1 = full screen at width x height,
                                   -1 = a window */
    const char *video_driver;   /* SDL video driver for a window; NULL = the board's */
    cub_depth_mode depth;       /* default AUTO */
    const char *button_script;  /* sim: a timeline file of presses; NULL = keyboard */
    const cub_boxconf_gpio *gpio; /* pi: the button and LED lines; NULL = built-in */
    const char *audio_driver;   /* SDL audio driver ("dummy", "disk"); NULL = default */
    int audio_volume;           /* percent 1..100, CUB_BOARD_MUTE = silent; 0 = 100 */
    int audio_rate;             /* default 44100 */
    const char *storage_dir;    /* default "." */
    int virtual_clock;          /* 1: time moves only when the loop sleeps, by
                                   whole ticks, as fast as the machine goes:
                                   for replays, so that a recording gives the
                                   same event log on every machine */
} cub_board_desc;

#define CUB_BOARD_MUTE (-1)

typedef struct cub_board cub_board; /* opaque */

typedef struct cub_depth_frame {
    const uint16_t *raw;  /* CUB_DEPTH_W * CUB_DEPTH_H raw 11-bit values, row-major */
    uint32_t seq;         /* 0, 1, 2 ... in arrival order */
    uint32_t timestamp;   /* libfreenect's timestamp (60 MHz ticks) */
    int64_t t_us;         /* board clock when it arrived */
    int16_t accel[3];     /* raw accelerometer (gravity), 0 when unknown */
} cub_depth_frame;

/* Open the board. Fills a clear message into err_msg (may be NULL) on
 * failure. The board owns everything it opens; close releases it all. */
cub_err cub_board_open(const cub_board_desc *desc, cub_board **out, char *err_msg,
                       size_t err_size);
void cub_board_close(cub_board *board);
/* "sim" or "pi". */
const char *cub_board_name(void);

/* ---- clock ------------------------------------------------------------- */
int64_t cub_board_now_us(cub_board *board);
void cub_board_sleep_until_us(cub_board *board, int64_t t_us);

/* ---- buttons ----------------------------------------------------------- */
/* Push debounced button edges (and QUIT when the window closes) that are due
 * by now_us into the loop. */
void cub_board_poll_buttons(cub_board *board, cub_loop *loop, int64_t now_us);
/* Show whether the box is ready for START (pi: the LED of led_line; close
 * puts it out). Nothing on boards without one. */
void cub_board_set_ready(cub_board *board, int ready);

/* ---- depth ------------------------------------------------------------- */
/* The newest frame since the last call: CUB_OK and *out filled (valid until
 * the next call), CUB_ERR_EMPTY if none yet, CUB_ERR_END when a replay has
 * run out, CUB_ERR_DEVICE if no source is open. */
cub_err cub_board_depth_poll(cub_board *board, cub_depth_frame *out);
/* What the depth source is: "freenect" (a live Kinect), "fakenect" (a dump
 * replayed through libfreenect's replay library), "empty" or "off". */
const char *cub_board_depth_source(cub_board *board);
/* Hand every frame cub_board_depth_poll returns to tap as well (NULL: none).
 * The board itself stores nothing; the app's recorder (opt-in) is the tap. */
typedef void (*cub_board_depth_tap)(void *user, const cub_depth_frame *frame);
void cub_board_set_depth_tap(cub_board *board, cub_board_depth_tap tap, void *user);

/* ---- display ----------------------------------------------------------- */
/* A current GLES2 context exists after open unless display == NONE. */
int cub_board_display_active(cub_board *board);
int cub_board_display_headless(cub_board *board);
void cub_board_display_size(cub_board *board, int *w, int *h);
void cub_board_display_swap(cub_board *board);
/* NULL while the display works; once it is gone (a failed swap, the
 * driver's "display disconnected", the HDMI connector unplugged) why, e.g.
 * "KMSDRM: HDMI-A-1 disconnected". It does not come back: the app ends. */
const char *cub_board_display_lost(cub_board *board);
/* Read the current frame as RGBA8, top row first (w*h*4 bytes). */
cub_err cub_board_display_read_rgba(cub_board *board, uint8_t *rgba, size_t size);

/* ---- audio ------------------------------------------------------------- */
/* Called from the audio thread to fill interleaved stereo int16 frames. */
typedef void (*cub_audio_fill)(void *user, int16_t *stereo, int frames);
cub_err cub_board_audio_start(cub_board *board, cub_audio_fill fill, void *user);
void cub_board_audio_stop(cub_board *board);
/* Frames handed to the audio device so far. This runs ahead of what the
 * speaker plays by the device's buffer (about 1024 frames, 23 ms at
 * 44.1 kHz) plus its output latency: subtract those for the music clock. */
uint64_t cub_board_audio_frames(cub_board *board);
int cub_board_audio_rate(cub_board *board);

/* ---- storage ----------------------------------------------------------- */
/* Join the storage directory and a relative name into buf. */
cub_err cub_board_storage_path(cub_board *board, const char *name, char *buf, size_t size);

#endif

/* boxconf — the box's config file, /etc/cubdance/cubdance.conf (the
 * documented copy with every key at its default is board/pi/cubdance.conf).
 *
 * One `key=value` per line, `#` starts a comment, blanks around either side
 * are ignored. Every key is optional: cub_boxconf_defaults holds the value
 * of each, and a test checks that the shipped file says the same. Keys are
 * flat; their prefix-free names are grouped in the file by what they set:
 * GPIO (buttons, ready LED), display, audio, timings, asset paths and
 * recording.
 *
 * Errors stop the program with "file:line: problem": an unknown key (with
 * the nearest known one), a repeated key (with the line it was first set
 * on), a key with no value or a value out of range (with the allowed ones).
 * The parser allocates nothing and never reads past len. */
#ifndef CUB_BOXCONF_H
#define CUB_BOXCONF_H

#include <stddef.h>

#include "cub/err.h"

#define CUB_BOXCONF_DEFAULT_PATH "/etc/cubdance/cubdance.conf"
#define CUB_BOXCONF_NAME_MAX 64
#define CUB_BOXCONF_PATH_MAX 256

/* Indexes into cub_boxconf_gpio.line / line_at. */
enum { CUB_BOXCONF_LINE_START, CUB_BOXCONF_LINE_STOP, CUB_BOXCONF_LINE_LED, CUB_BOXCONF_LINES };

typedef struct cub_boxconf_gpio {
    char file[CUB_BOXCONF_PATH_MAX];    /* the file the values came from, for messages */
    char chip[CUB_BOXCONF_NAME_MAX];    /* default "gpiochip0" */
    /* START (default GPIO17), STOP (GPIO27), the ready LED (default "": none) */
    char line[CUB_BOXCONF_LINES][CUB_BOXCONF_NAME_MAX];
    int line_at[CUB_BOXCONF_LINES]; /* the config line naming it; 0 = the default */
    int active_low;                 /* buttons short the line to ground; default 1 */
    int debounce_ms;                /* default 30, 0..1000 */
    int led_active_low;             /* the LED lights when the line is low; default 0 */
} cub_boxconf_gpio;

typedef struct cub_boxconf {
    cub_boxconf_gpio gpio;
    /* display */
    char video_driver[16]; /* auto (default: KMSDRM on the box), kmsdrm, x11, wayland */
    int width, height;     /* default 1280x720; 0x0 = auto: the screen's own mode */
    int fullscreen;        /* default 1 */
    /* audio */
    int volume;            /* percent, 0..100, default 80 */
    char audio_driver[16]; /* auto (default: SDL's choice, ALSA on the box), alsa, pulseaudio,
                              pipewire, dummy, disk */
    int speech;            /* the bear says its words too (over the music); default 1 */
    /* timings (seconds without anyone moving or pressing) */
    int attract_after_s;   /* default 20, 1..3600 */
    int doze_after_s;      /* default 60, 2..86400, > attract_after_s */
    /* assets: "" = the built-in place */
    char assets_dir[CUB_BOXCONF_PATH_MAX]; /* "" = where the program was installed with */
    char songs_dir[CUB_BOXCONF_PATH_MAX];  /* "" = <assets_dir>/songs */
    char song[CUB_BOXCONF_NAME_MAX];       /* lead <songs_dir>/<song>.song.xml; "" = none */
    /* the coach: <assets_dir>/<coach>/<coach>.xml, clips/<coach>.cubclips and
     * clips/<coach>.tags.xml; default bear (seal: docs/evolve.md) */
    char coach[CUB_BOXCONF_NAME_MAX];
    char soundfont[CUB_BOXCONF_PATH_MAX];  /* default /usr/share/sounds/sf2/TimGM6mb.sf2 */
    /* the TV's text; default /usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf */
    char font[CUB_BOXCONF_PATH_MAX];
    /* recording: the box stores camera data only when this is 1 */
    int recording;                            /* default 0 */
    char recording_dir[CUB_BOXCONF_PATH_MAX]; /* default /var/lib/cubdance/recordings */
    int recording_max_mb;  /* what recording_dir may hold in all, MB; default 2048 */
    /* the event log: rotated to <log>.1 when it reaches this; default 10240, 0 = never */
    int log_max_kb;
} cub_boxconf;

void cub_boxconf_defaults(cub_boxconf *cfg);
/* Parse key=value text over the defaults. CUB_ERR_FORMAT with
 * "file:line: problem" in err on a bad line or a bad combination. */
cub_err cub_boxconf_parse(const char *text, size_t len, const char *file, cub_boxconf *cfg,
                          char *err, size_t err_size);
/* Read a file and parse it: CUB_ERR_IO naming the file if it cannot be read. */
cub_err cub_boxconf_load(const char *path, cub_boxconf *cfg, char *err, size_t err_size);

/* The keys, for documentation checks: how many, the k-th's name, and its
 * value in cfg written as the file would say it. */
int cub_boxconf_key_count(void);
const char *cub_boxconf_key_name(int k);
void cub_boxconf_value_str(const cub_boxconf *cfg, int k, char *buf, size_t size);

#endif

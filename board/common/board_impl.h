/* board_impl — the board object both boards share (private to board/).
 *
 * board_common.c implements every cub_board_* function that is the same on
 * both boards (clock, depth, display, audio, storage, button dispatch).
 * Each board (board/sim, board/pi) implements cub_board_open/close/name:
 * it describes itself as a cub_board_kind (video driver, display fallback,
 * its own buttons) and calls cub_board_open_kind. */
#ifndef CUB_BOARD_IMPL_H
#define CUB_BOARD_IMPL_H

#include <stddef.h>
#include <stdint.h>

#include "audio_sdl.h"
#include "buttons_script.h"
#include "cub/board.h"
#include "depth.h"
#include "display.h"

#define CUB_BOARD_PATH_MAX 4096

struct cub_board {
    cub_board_desc desc;         /* with defaults filled in */
    char storage_dir[CUB_BOARD_PATH_MAX];
    char audio_driver[64];       /* "" = SDL's choice */
    char video_driver[64];       /* "" = the board's choice */
    cub_board_clock clock;       /* board time */
    cub_depth *depth;            /* NULL when depth is off */
    cub_display *display;        /* NULL when display is NONE */
    cub_audio_sdl *audio;        /* NULL until audio starts */
    uint64_t audio_frames_done;  /* the music clock where audio last stopped */
    cub_button_script *script;   /* NULL: the board's own buttons */
    cub_board_depth_tap depth_tap; /* sees every frame handed out, or NULL */
    void *depth_tap_user;
    /* The board's own buttons (pi: GPIO), used when there is no script. */
    void *buttons;
    void (*poll_buttons)(void *buttons, cub_loop *loop, int64_t now_us);
    void (*close_buttons)(void *buttons);
    void (*set_ready)(void *buttons, int ready); /* NULL: nothing shows it */
};

/* desc with zero fields replaced by their defaults (desc NULL: all defaults). */
cub_board_desc cub_board_desc_defaults(const cub_board_desc *desc);
/* Allocate the board and open what both boards share: the clock origin,
 * storage, the depth source and the button script. */
cub_err cub_board_common_open(const cub_board_desc *desc, cub_board **out, char *err,
                              size_t err_size);
/* What makes a board itself; board_common.c does the rest of opening it. */
typedef struct cub_board_kind {
    const char *video_driver; /* SDL's video driver for a window; NULL = SDL's choice */
    int probe_window;         /* AUTO: open a window only if one can open here
                                 (a PC may have no display at all) */
    int window_required;      /* AUTO: no window is an error, never headless (the
                                 box is for the TV: drawing unseen helps nobody) */
    const char *no_display_hint; /* said first when the window fails ("" = none) */
    /* The board's own buttons, opened last (after the clock starts) unless a
     * button script replaces them; NULL = none beyond the window's keys. */
    cub_err (*open_buttons)(cub_board *b, const cub_board_desc *desc, char *err,
                            size_t err_size);
} cub_board_kind;

/* cub_board_open for a board of this kind: common parts, display, clock and
 * depth, then its buttons; on failure everything is closed again. */
cub_err cub_board_open_kind(const cub_board_kind *kind, const cub_board_desc *desc,
                            cub_board **out, char *err_msg, size_t err_size);
/* Start the board's clock (t = 0 from now) and open the depth source. */
cub_err cub_board_common_start(cub_board *board, char *err, size_t err_size);
/* Release everything the board holds (safe on a half-open board). */
void cub_board_common_close(cub_board *board);

#endif

/* board_sim — the PC board: libfreenect (live or fakenect replay), an SDL2
 * window or headless EGL, the keyboard or a scripted timeline for buttons,
 * SDL audio. Everything but open/close lives in board/common. */
#include "board_impl.h"

/* A PC: SDL picks the video driver; with no display, headless. Buttons: a
 * script (common) if given, else the window's keys (polled by common); no
 * window and no script means no buttons at all. */
static const cub_board_kind sim_kind = {.probe_window = 1};

cub_err cub_board_open(const cub_board_desc *desc, cub_board **out, char *err_msg, size_t err_size)
{
    return cub_board_open_kind(&sim_kind, desc, out, err_msg, err_size);
}

void cub_board_close(cub_board *board)
{
    cub_board_common_close(board);
}

const char *cub_board_name(void)
{
    return "sim";
}

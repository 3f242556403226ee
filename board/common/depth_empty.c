/* depth_empty — the built-in empty scene: every pixel "no reading", a frame
 * every 1/30 s of board time. Lets the program run (and be tested) with no
 * Kinect: the tracker sees nobody, the coach asks the child to come closer. */
#include "clock.h"
#include "depth.h"

#include <stdlib.h>

struct cub_depth_empty {
    uint16_t raw[CUB_DEPTH_W * CUB_DEPTH_H];
    const cub_board_clock *clock;
    int64_t next_k; /* index of the next frame not yet handed out */
    uint32_t seq;
};

static int64_t due_us(int64_t k)
{
    return k * CUB_DEPTH_EMPTY_PERIOD_NUM_US / CUB_DEPTH_EMPTY_PERIOD_DEN;
}

cub_err cub_depth_empty_open(const cub_board_clock *clock, cub_depth_empty **out)
{
    cub_depth_empty *s = malloc(sizeof *s);
    if (!s) {
        return CUB_ERR_NOMEM;
    }
    for (size_t i = 0; i < CUB_DEPTH_W * CUB_DEPTH_H; i++) {
        s->raw[i] = CUB_DEPTH_NO_READING;
    }
    s->clock = clock;
    s->next_k = 0;
    s->seq = 0;
    *out = s;
    return CUB_OK;
}

cub_err cub_depth_empty_poll(cub_depth_empty *s, cub_depth_frame *out)
{
    int64_t now_us = cub_board_clock_now_us(s->clock);
    if (now_us < due_us(s->next_k)) {
        return CUB_ERR_EMPTY;
    }
    /* Only the newest due frame is handed out, as with a live Kinect when
     * the caller polls late: the largest k with due_us(k) <= now. (Flooring
     * now * DEN / NUM instead gave frame k-1 again at the microsecond frame
     * k falls due on, since due_us rounds down.) */
    int64_t k = ((now_us + 1) * CUB_DEPTH_EMPTY_PERIOD_DEN - 1) / CUB_DEPTH_EMPTY_PERIOD_NUM_US;
    s->next_k = k + 1;
    out->raw = s->raw;
    out->seq = s->seq++;
    out->t_us = due_us(k);
    out->timestamp = (uint32_t)(out->t_us * 60); /* the Kinect's 60 MHz tick */
    out->accel[0] = out->accel[1] = out->accel[2] = 0;
    return CUB_OK;
}

void cub_depth_empty_close(cub_depth_empty *s)
{
    free(s);
}

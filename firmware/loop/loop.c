/* The fixed-tick super-loop and its software timers.
 *
 * Ticks sit on a fixed grid (start + n * tick_us), whatever the real time of
 * wake-up, so that everything decided in a tick is stamped with the same
 * time on every machine. A loop that falls more than a few ticks behind
 * (a stall) skips the missed grid points and says so in the log instead of
 * running a burst of catch-up ticks. */
#include <string.h>

#include "cub/loop.h"

#define DEFAULT_TICK_US 33333u
#define DEFAULT_QUEUE_CAPACITY 64u
#define MAX_CATCH_UP_TICKS 3
/* Timers and delays beyond ~292 years are a caller's mistake, and keeping
 * them below this keeps every sum of times far from int64 overflow. */
#define MAX_TIMER_US ((int64_t)1 << 62)

static cub_loop_desc with_defaults(const cub_loop_desc *desc)
{
    cub_loop_desc d = {0};
    if (desc) d = *desc;
    if (d.tick_us == 0) d.tick_us = DEFAULT_TICK_US;
    if (d.queue_capacity == 0) d.queue_capacity = DEFAULT_QUEUE_CAPACITY;
    return d;
}

size_t cub_loop_mem_size(const cub_loop_desc *desc)
{
    cub_loop_desc d = with_defaults(desc);
    return (size_t)d.queue_capacity * sizeof(cub_event);
}

cub_err cub_loop_init(cub_loop *loop, const cub_loop_desc *desc, void *mem, size_t mem_size)
{
    if (!loop || !mem) return CUB_ERR_ARG;
    cub_loop_desc d = with_defaults(desc);
    if (mem_size < cub_loop_mem_size(&d)) return CUB_ERR_NOMEM;
    memset(loop, 0, sizeof *loop);
    loop->desc = d;
    cub_err err = cub_queue_init(&loop->queue, (cub_event *)mem, d.queue_capacity);
    if (err) return err;
    loop->log.sink = d.log_sink;
    loop->log.user = d.log_user;
    loop->next_tick_us = -1; /* first step takes its time from the clock */
    loop->running = 1;
    return CUB_OK;
}

cub_err cub_loop_post(cub_loop *loop, const cub_event *ev)
{
    if (!loop || !ev) return CUB_ERR_ARG;
    cub_err err = cub_queue_push(&loop->queue, ev);
    if (err == CUB_ERR_FULL) {
        cub_log_event(&loop->log, ev->t_us, "loop", "dropped", "type=%s dropped=%u",
                      cub_loop_event_name(ev->type), loop->queue.dropped);
    }
    return err;
}

/* ---- timers ------------------------------------------------------------ */

static cub_timer *find_timer(cub_loop *loop, int32_t id)
{
    for (int i = 0; i < CUB_LOOP_MAX_TIMERS; i++)
        if (loop->timers[i].id == id) return &loop->timers[i];
    return NULL;
}

cub_err cub_loop_timer_start(cub_loop *loop, int32_t id, int64_t now_us, int64_t delay_us,
                             int64_t period_us)
{
    if (!loop || id == 0 || delay_us < 0 || period_us < 0 || delay_us > MAX_TIMER_US ||
        period_us > MAX_TIMER_US || now_us > MAX_TIMER_US || now_us < -MAX_TIMER_US)
        return CUB_ERR_ARG;
    cub_timer *t = find_timer(loop, id);
    if (!t) t = find_timer(loop, 0);
    if (!t) return CUB_ERR_FULL;
    t->id = id;
    t->due_us = now_us + delay_us;
    t->period_us = period_us;
    return CUB_OK;
}

void cub_loop_timer_stop(cub_loop *loop, int32_t id)
{
    if (!loop || id == 0) return;
    cub_timer *t = find_timer(loop, id);
    if (t) t->id = 0;
}

/* The earliest due timer at or before t_us, or NULL. Earliest first keeps
 * timer events in time order when several fall into one tick. */
static cub_timer *next_due(cub_loop *loop, int64_t t_us)
{
    cub_timer *best = NULL;
    for (int i = 0; i < CUB_LOOP_MAX_TIMERS; i++) {
        cub_timer *t = &loop->timers[i];
        if (t->id && t->due_us <= t_us && (!best || t->due_us < best->due_us)) best = t;
    }
    return best;
}

/* Each due timer fires once per tick. A periodic timer that fell behind
 * (a stall, or a period shorter than the tick) fires once, with b = the
 * number of periods it missed, and moves past this tick in one step:
 * firing once per missed period could flood the queue without bound. */
static void fire_timers(cub_loop *loop, int64_t t_us)
{
    cub_timer *t;
    while ((t = next_due(loop, t_us)) != NULL) {
        cub_event ev = {.t_us = t->due_us, .type = CUB_EV_TIMER, .a = t->id};
        if (t->period_us > 0) {
            int64_t periods = (t_us - t->due_us) / t->period_us + 1;
            ev.b = periods - 1 > INT32_MAX ? INT32_MAX : (int32_t)(periods - 1);
            t->due_us += periods * t->period_us;
        } else {
            t->id = 0;
        }
        cub_loop_post(loop, &ev);
    }
}

/* ---- the tick ---------------------------------------------------------- */

/* Choose this tick's grid time; skip grid points lost to a stall. */
static int64_t advance_grid(cub_loop *loop, int64_t now_us)
{
    int64_t tick = loop->desc.tick_us;
    if (loop->next_tick_us < 0) loop->next_tick_us = now_us;
    int64_t behind = now_us - loop->next_tick_us;
    if (behind > MAX_CATCH_UP_TICKS * tick) {
        int64_t skipped = behind / tick;
        cub_log_event(&loop->log, loop->next_tick_us, "loop", "overrun", "skipped_ticks=%lld",
                      (long long)skipped);
        loop->next_tick_us += skipped * tick;
    }
    int64_t t = loop->next_tick_us;
    loop->next_tick_us += tick;
    return t;
}

static void drain(cub_loop *loop, const cub_loop_hooks *h)
{
    cub_event ev;
    /* Only what was queued before draining started: events posted while
     * handling belong to the next tick, so one tick's work stays bounded. */
    uint32_t n = cub_queue_count(&loop->queue);
    while (n-- > 0 && cub_queue_pop(&loop->queue, &ev) == CUB_OK) {
        if (h->handle) h->handle(h->user, loop, &ev);
        if (ev.type == CUB_EV_QUIT) loop->running = 0;
    }
}

cub_err cub_loop_step(cub_loop *loop, const cub_loop_hooks *h)
{
    if (!loop || !h || !h->now_us) return CUB_ERR_ARG;
    if (!loop->running) return CUB_ERR_END;
    if (loop->next_tick_us >= 0 && h->wait_until) h->wait_until(h->user, loop->next_tick_us);
    int64_t now = h->now_us(h->user);
    int64_t t = advance_grid(loop, now);
    if (h->poll) h->poll(h->user, loop, now);
    fire_timers(loop, t);
    drain(loop, h);
    if (h->tick) h->tick(h->user, loop, t);
    loop->tick_count++;
    return loop->running ? CUB_OK : CUB_ERR_END;
}

cub_err cub_loop_run(cub_loop *loop, const cub_loop_hooks *h, uint64_t max_ticks)
{
    cub_err err = CUB_OK;
    for (uint64_t n = 0; max_ticks == 0 || n < max_ticks; n++) {
        err = cub_loop_step(loop, h);
        if (err) break;
    }
    return err == CUB_ERR_END ? CUB_OK : err;
}

void cub_loop_stop(cub_loop *loop)
{
    if (loop) loop->running = 0;
}

/* ---- names ------------------------------------------------------------- */

const char *cub_loop_button_name(cub_button b)
{
    switch (b) {
    case CUB_BUTTON_START: return "start";
    case CUB_BUTTON_STOP: return "stop";
    default: return "unknown";
    }
}

const char *cub_loop_event_name(int32_t type)
{
    switch (type) {
    case CUB_EV_NONE: return "none";
    case CUB_EV_BUTTON_DOWN: return "button_down";
    case CUB_EV_BUTTON_UP: return "button_up";
    case CUB_EV_DEPTH_FRAME: return "depth_frame";
    case CUB_EV_TIMER: return "timer";
    case CUB_EV_QUIT: return "quit";
    case CUB_EV_VERDICT: return "verdict";
    case CUB_EV_CLAP: return "clap";
    case CUB_EV_PLAYER: return "player";
    case CUB_EV_CLIP_DONE: return "clip_done";
    case CUB_EV_CAMERA: return "camera";
    case CUB_EV_MUSIC_TAG: return "music_tag";
    case CUB_EV_SONG_END: return "song_end";
    default: return type >= CUB_EV_USER ? "user" : "unknown";
    }
}

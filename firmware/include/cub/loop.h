/* loop — the microcontroller-style core: an event queue (a ring buffer, no
 * heap), software timers, the fixed-tick super-loop, and the event log.
 *
 * The firmware owns no clock and does no I/O: the board supplies "now"
 * through the hooks, and the event log hands finished lines to a sink the
 * app provides (a file, stderr). Times are microseconds since the loop
 * started (`t_us`); the log prints them as seconds with millisecond
 * precision, e.g. `t=12.433 button down name=start`.
 */
#ifndef CUB_LOOP_H
#define CUB_LOOP_H

#include <stddef.h>
#include <stdint.h>

#include "cub/err.h"

/* ---- events ------------------------------------------------------------ */

typedef enum cub_event_type {
    CUB_EV_NONE = 0,
    CUB_EV_BUTTON_DOWN, /* a = cub_button */
    CUB_EV_BUTTON_UP,   /* a = cub_button */
    CUB_EV_DEPTH_FRAME, /* a = frame sequence number */
    CUB_EV_TIMER,       /* a = timer id, b = periods missed (a late periodic timer) */
    CUB_EV_QUIT,        /* the board or the user asked the program to end */
    /* The dance (issue 4 on): */
    CUB_EV_VERDICT,     /* the judge: a = move index in the song, b = 1 right / 0 wrong,
                           c = a wrong one's fault (cub_judge_fault_code), 0 none */
    CUB_EV_CLAP,        /* the child clapped (wakes the coach like START) */
    CUB_EV_PLAYER,      /* a = 1 a player is in view, 0 nobody */
    CUB_EV_CLIP_DONE,   /* the coach's clip played to its end: a = clip index */
    CUB_EV_MUSIC_TAG,   /* playback reached a music time tag: a = move index, b = tag ms */
    CUB_EV_SONG_END,    /* the song's music finished */
    CUB_EV_CAMERA,      /* a = 0 depth frames stopped coming (the Kinect is gone), 1 they are back */
    CUB_EV_USER,        /* first value free for app-defined events */
} cub_event_type;

typedef enum cub_button {
    CUB_BUTTON_START = 0,
    CUB_BUTTON_STOP = 1,
    CUB_BUTTON_COUNT
} cub_button;

typedef struct cub_event {
    int64_t t_us;  /* when it happened (loop time) */
    int32_t type;  /* cub_event_type */
    int32_t a, b;  /* meaning depends on type (see above) */
    int32_t c;     /* a third value where the type says so; else 0 */
} cub_event;

/* Name of a button ("start", "stop") or event type ("button_down", ...). */
const char *cub_loop_button_name(cub_button b);
const char *cub_loop_event_name(int32_t type);

/* ---- the event queue: a fixed ring buffer ------------------------------ */

typedef struct cub_queue {
    cub_event *slots;
    uint32_t capacity; /* a power of two */
    uint32_t head, tail; /* free-running; count = tail - head */
    uint32_t dropped;    /* events refused because the queue was full */
} cub_queue;

/* capacity must be a power of two >= 2; slots is caller memory. */
cub_err cub_queue_init(cub_queue *q, cub_event *slots, uint32_t capacity);
/* CUB_ERR_FULL (and dropped++) when full. */
cub_err cub_queue_push(cub_queue *q, const cub_event *ev);
/* CUB_ERR_EMPTY when empty. */
cub_err cub_queue_pop(cub_queue *q, cub_event *out);
uint32_t cub_queue_count(const cub_queue *q);

/* ---- the event log ----------------------------------------------------- */

/* Receives one finished line (no trailing newline) at a time. */
typedef void (*cub_log_sink)(void *user, const char *line, size_t len);

#define CUB_LOG_LINE_MAX 512

typedef struct cub_log {
    cub_log_sink sink; /* NULL: lines are counted but go nowhere */
    void *user;
    uint32_t lines;    /* lines written so far */
} cub_log;

/* Write `t=S.mmm <source> <event>` followed by the formatted details.
 * fmt understands a small, OS-free subset of printf:
 *   %d %i (int)  %u (unsigned)  %ld %lld %lu %llu  %x  %s  %c  %%
 *   %q  a Q16.16 value printed as a decimal with 3 places (e.g. 0.400)
 * Unknown conversions are copied through; an over-long line is cut. */
void cub_log_event(cub_log *log, int64_t t_us, const char *source, const char *event,
                   const char *fmt, ...);

/* The same formatter into a buffer (always NUL-terminated when size > 0).
 * Returns the length written. */
size_t cub_log_format(char *buf, size_t size, const char *fmt, ...);

/* ---- timers ------------------------------------------------------------ */

#define CUB_LOOP_MAX_TIMERS 16

typedef struct cub_timer {
    int32_t id;        /* caller's id, delivered in CUB_EV_TIMER.a; 0 = free slot */
    int64_t due_us;
    int64_t period_us; /* 0 = one-shot */
} cub_timer;

/* ---- the super-loop ---------------------------------------------------- */

typedef struct cub_loop cub_loop;

/* The board and the app plug into the loop through these; every hook but
 * now_us may be NULL. */
typedef struct cub_loop_hooks {
    void *user;
    int64_t (*now_us)(void *user);                          /* the clock */
    void (*poll)(void *user, cub_loop *loop, int64_t now_us); /* push board events */
    void (*handle)(void *user, cub_loop *loop, const cub_event *ev);
    void (*tick)(void *user, cub_loop *loop, int64_t tick_t_us); /* sample, render */
    void (*wait_until)(void *user, int64_t t_us);            /* sleep until then */
} cub_loop_hooks;

typedef struct cub_loop_desc {
    uint32_t tick_us;        /* default 33333 (30 Hz, the Kinect's rate) */
    uint32_t queue_capacity; /* default 64; a power of two */
    cub_log_sink log_sink;   /* may be NULL */
    void *log_user;
} cub_loop_desc;

struct cub_loop {
    cub_loop_desc desc;
    cub_queue queue;
    cub_log log;
    cub_timer timers[CUB_LOOP_MAX_TIMERS];
    uint64_t tick_count;
    int64_t next_tick_us;
    int running;
};

/* Bytes of event storage for this desc (after defaults). */
size_t cub_loop_mem_size(const cub_loop_desc *desc);
cub_err cub_loop_init(cub_loop *loop, const cub_loop_desc *desc, void *mem, size_t mem_size);

/* Queue an event from inside the loop (judge, coach) or a board poll. */
cub_err cub_loop_post(cub_loop *loop, const cub_event *ev);
/* Start a timer: fires CUB_EV_TIMER with a = id after delay_us, then every
 * period_us if non-zero (at most once per tick: see CUB_EV_TIMER's b). id
 * must be non-zero; re-using an id restarts it. Times beyond 2^62 us are
 * refused (CUB_ERR_ARG). */
cub_err cub_loop_timer_start(cub_loop *loop, int32_t id, int64_t now_us, int64_t delay_us,
                             int64_t period_us);
void cub_loop_timer_stop(cub_loop *loop, int32_t id);

/* One tick: wait for the tick time, poll, fire due timers, drain the queue
 * into handle(), then tick(). Returns CUB_ERR_END once cub_loop_stop was
 * called (or a CUB_EV_QUIT was handled). */
cub_err cub_loop_step(cub_loop *loop, const cub_loop_hooks *hooks);
/* Step until stopped or max_ticks (0 = no limit) ticks have run. */
cub_err cub_loop_run(cub_loop *loop, const cub_loop_hooks *hooks, uint64_t max_ticks);
void cub_loop_stop(cub_loop *loop);

#endif

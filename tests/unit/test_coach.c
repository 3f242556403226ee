/* coach: the behaviour state machine and the music-sync rule. Bad input
 * first, then every transition, the sync formula, a simulated player
 * following a music clock 5 % slow or fast, and a scripted song whose
 * whole event log is pinned. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/coach.h"

/* ---- fixture: a clip library, a three-move song, a log recorder ------- */

enum {
    C_IDLE,
    C_WAKE,
    C_WAVE,
    C_DOZE,
    C_SHAKE,
    C_WATCH,
    C_WORRIED,
    C_CHEER,
    C_CLAP,
    C_SWAY,
    C_ROBOT,
    C_COUNT
};
static const char *const names[C_COUNT] = {"idle",       "wake_up",  "wave",    "doze",
                                           "head_shake", "watch_me", "worried", "cheer",
                                           "clap",       "sway",     "robot"};

/* clap: 4 reps of 2 s; sway: 2 reps of 2 s at its own speed 1.25; a 1 s
 * gap; robot: 3 reps of 2 s. */
static const cub_coach_move song[3] = {
    {.clip = C_CLAP, .reps = 4, .tag_ms = 0, .span_ms = 8000},
    {.clip = C_SWAY, .reps = 2, .speed_q16 = 81920, .tag_ms = 8000, .span_ms = 4000},
    {.clip = C_ROBOT, .reps = 3, .tag_ms = 13000, .span_ms = 6000},
};

#define MAX_LINES 400
#define SESSION_LOG_FNV 0x27bdcbe9u /* the scripted session's whole log, pinned */
typedef struct recorder {
    char lines[MAX_LINES][160];
    int n;
} recorder;
static recorder rec;
static cub_log log_to_rec;

static void rec_sink(void *u, const char *line, size_t len)
{
    recorder *r = u;
    if (r->n < MAX_LINES) snprintf(r->lines[r->n++], sizeof r->lines[0], "%.*s", (int)len, line);
}

static cub_coach_desc make_desc(void)
{
    memset(&rec, 0, sizeof rec);
    log_to_rec = (cub_log){.sink = rec_sink, .user = &rec};
    cub_coach_desc d = {.moves = song,
                        .move_count = 3,
                        .clip_count = C_COUNT,
                        .clip_names = names,
                        .log = &log_to_rec};
    assert_int_equal(cub_coach_roles_by_name(names, C_COUNT, &d.roles), CUB_OK);
    return d;
}

static void send(cub_coach *c, int64_t t_ms, int32_t type, int32_t a, int32_t b, int32_t music_ms)
{
    cub_event ev = {.t_us = t_ms * 1000, .type = type, .a = a, .b = b};
    assert_int_equal(cub_coach_handle(c, &ev, music_ms), CUB_OK);
}

static void tick(cub_coach *c, int64_t t_ms, int32_t music_ms)
{
    assert_int_equal(cub_coach_tick(c, t_ms * 1000, music_ms), CUB_OK);
}

/* The n-th action of kind in this call's output (0-based), or NULL. */
static const cub_coach_action *act(const cub_coach *c, int32_t kind, int n)
{
    for (int i = 0; i < c->action_count; i++)
        if (c->actions[i].kind == kind && n-- == 0) return &c->actions[i];
    return NULL;
}

static void expect_clip(const cub_coach *c, int32_t clip, cub_q16 speed, bool loop, int32_t reason)
{
    const cub_coach_action *a = act(c, CUB_COACH_ACT_CLIP, 0);
    assert_non_null(a);
    assert_int_equal(a->clip, clip);
    if (speed) assert_int_equal(a->speed_q16, speed);
    assert_int_equal(a->loop, loop);
    assert_int_equal(a->reason, reason);
}

static bool logged(const char *needle)
{
    for (int i = 0; i < rec.n; i++)
        if (strstr(rec.lines[i], needle)) return true;
    return false;
}

/* Idle -> START at t_ms -> wake_up done 1 s later -> dancing move 0. */
static void to_dance(cub_coach *c, int64_t t_ms)
{
    send(c, t_ms, CUB_EV_BUTTON_DOWN, CUB_BUTTON_START, 0, CUB_COACH_NO_MUSIC);
    send(c, t_ms + 1000, CUB_EV_CLIP_DONE, C_WAKE, 0, CUB_COACH_NO_MUSIC);
    assert_int_equal(c->state, CUB_COACH_DANCE);
}

/* A coach made from make_desc() and led into the dance at t_ms. */
static void start_dancing(cub_coach *c, int64_t t_ms)
{
    cub_coach_desc d = make_desc();
    assert_int_equal(cub_coach_init(c, &d, 0), CUB_OK);
    to_dance(c, t_ms);
}

/* ---- bad input ----------------------------------------------------------- */

static void test_bad_desc_is_refused(void **s)
{
    cub_coach c;
    cub_coach_desc d = make_desc();
    cub_coach_move bad[3];
    assert_int_equal(cub_coach_init(NULL, &d, 0), CUB_ERR_ARG);
    assert_int_equal(cub_coach_init(&c, NULL, 0), CUB_ERR_ARG);

    cub_coach_desc e = d;
    e.moves = NULL;
    assert_int_equal(cub_coach_init(&c, &e, 0), CUB_ERR_ARG);
    e = d;
    e.move_count = 0;
    assert_int_equal(cub_coach_init(&c, &e, 0), CUB_ERR_ARG);
    e = d;
    e.roles.cheer = C_COUNT; /* a role outside the library */
    assert_int_equal(cub_coach_init(&c, &e, 0), CUB_ERR_ARG);
    e = d;
    e.attract_after_ms = 70000; /* after the default doze (60 s) */
    assert_int_equal(cub_coach_init(&c, &e, 0), CUB_ERR_ARG);

    struct {
        int field;
        int32_t value;
    } cases[] = {
        {0, -1},   {0, C_COUNT}, /* clip */
        {1, 1},    {1, 0},       /* reps < 2 */
        {2, 0},    {2, -5},      /* span */
        {3, 7999},               /* move 1 starts before move 0 ends */
        {4, -1},                 /* negative speed */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        memcpy(bad, song, sizeof bad);
        cub_coach_move *m = cases[i].field == 3 ? &bad[1] : &bad[0];
        if (cases[i].field == 0) m->clip = cases[i].value;
        if (cases[i].field == 1) m->reps = cases[i].value;
        if (cases[i].field == 2) m->span_ms = cases[i].value;
        if (cases[i].field == 3) m->tag_ms = cases[i].value;
        if (cases[i].field == 4) m->speed_q16 = cases[i].value;
        e = d;
        e.moves = bad;
        assert_int_equal(cub_coach_init(&c, &e, 0), CUB_ERR_ARG);
    }
    cub_coach_roles r;
    const char *few[] = {"idle", "wave"};
    assert_int_equal(cub_coach_roles_by_name(NULL, 3, &r), CUB_ERR_ARG);
    assert_int_equal(cub_coach_roles_by_name(few, 0, &r), CUB_ERR_ARG);
    assert_int_equal(cub_coach_roles_by_name(few, 2, &r), CUB_ERR_FORMAT);
    assert_int_equal(r.attract, 1);
    assert_int_equal(r.cheer, -1);
}

static void test_bad_events_change_nothing(void **s)
{
    cub_coach c;
    cub_coach_desc d = make_desc();
    assert_int_equal(cub_coach_init(&c, &d, 0), CUB_OK);
    cub_event ev = {.type = CUB_EV_VERDICT, .a = 3, .b = 0};
    assert_int_equal(cub_coach_handle(NULL, &ev, 0), CUB_ERR_ARG);
    assert_int_equal(cub_coach_handle(&c, NULL, 0), CUB_ERR_ARG);
    assert_int_equal(cub_coach_tick(NULL, 0, 0), CUB_ERR_ARG);
    to_dance(&c, 1000);
    assert_int_equal(cub_coach_handle(&c, &ev, 0), CUB_ERR_RANGE);
    assert_int_equal(c.action_count, 0); /* the last call's actions are not repeated */
    ev.a = -1;
    assert_int_equal(cub_coach_handle(&c, &ev, 0), CUB_ERR_RANGE);
    ev = (cub_event){.type = CUB_EV_MUSIC_TAG, .a = 99, .b = 0};
    assert_int_equal(cub_coach_handle(&c, &ev, 0), CUB_ERR_RANGE);
    assert_int_equal(c.state, CUB_COACH_DANCE);
    /* Events the coach does not use, and a clip-done of a clip it did not
     * ask for, leave it dancing with no action. */
    int32_t other[] = {CUB_EV_DEPTH_FRAME, CUB_EV_TIMER, CUB_EV_QUIT, CUB_EV_BUTTON_UP, 12345};
    for (size_t i = 0; i < sizeof other / sizeof other[0]; i++) {
        send(&c, 3000, other[i], 0, 0, 500);
        assert_int_equal(c.action_count, 0);
    }
    send(&c, 3000, CUB_EV_CLIP_DONE, C_ROBOT, 0, 500);
    assert_int_equal(c.action_count, 0);
    assert_true(logged("coach ignore event=clip_done a=10"));
    /* Time going backwards is taken as no time passing. */
    send(&c, 10, CUB_EV_PLAYER, 0, 0, 500);
    assert_int_equal(c.now_us, 3000000);
    assert_int_equal(c.state, CUB_COACH_DANCE);
}

/* ---- transitions --------------------------------------------------------- */

static void test_init_idles_and_start_wakes_into_the_dance(void **s)
{
    cub_coach c;
    cub_coach_desc d = make_desc();
    assert_int_equal(cub_coach_init(&c, &d, 0), CUB_OK);
    assert_int_equal(c.state, CUB_COACH_IDLE);
    expect_clip(&c, C_IDLE, CUB_Q16_ONE, true, CUB_COACH_WHY_IDLE);
    assert_int_equal(c.desc.attract_after_ms, 20000);
    assert_int_equal(c.desc.worried_after, 3);

    send(&c, 1000, CUB_EV_BUTTON_DOWN, CUB_BUTTON_START, 0, CUB_COACH_NO_MUSIC);
    assert_int_equal(c.state, CUB_COACH_WAKE);
    assert_int_equal(act(&c, CUB_COACH_ACT_STATE, 0)->reason, CUB_COACH_WHY_START);
    expect_clip(&c, C_WAKE, CUB_Q16_ONE, false, CUB_COACH_WHY_START);

    send(&c, 2500, CUB_EV_CLIP_DONE, C_WAKE, 0, CUB_COACH_NO_MUSIC);
    assert_int_equal(c.state, CUB_COACH_DANCE);
    assert_non_null(act(&c, CUB_COACH_ACT_MUSIC_START, 0));
    expect_clip(&c, C_CLAP, CUB_Q16_ONE, false, CUB_COACH_WHY_MOVE);
    assert_int_equal(act(&c, CUB_COACH_ACT_HINT, 0)->hint, 0);
    assert_true(logged("t=2.500 coach state from=wake to=dance reason=woke move=0 rep=0"));
    assert_true(
        logged("t=2.500 coach request clip=clap speed=1.000 loop=0 reason=move move=0 rep=0"));
}

static void test_clap_wakes_from_idle_attract_and_doze(void **s)
{
    cub_coach c;
    cub_coach_desc d = make_desc();
    d.attract_after_ms = 5000;
    d.doze_after_ms = 9000;
    const int64_t at_ms[] = {0, 5000, 9000}; /* idle, attract, doze */
    for (int i = 0; i < 3; i++) {
        assert_int_equal(cub_coach_init(&c, &d, 0), CUB_OK);
        tick(&c, at_ms[i], CUB_COACH_NO_MUSIC);
        if (i == 2) tick(&c, at_ms[i] + 1, CUB_COACH_NO_MUSIC); /* attract first, then doze */
        send(&c, at_ms[i] + 10, CUB_EV_CLAP, 0, 0, CUB_COACH_NO_MUSIC);
        assert_int_equal(c.state, CUB_COACH_WAKE);
        expect_clip(&c, C_WAKE, CUB_Q16_ONE, false, CUB_COACH_WHY_CLAP);
    }
    /* A clap while dancing does not restart anything. */
    to_dance(&c, 20000);
    send(&c, 22000, CUB_EV_CLAP, 0, 0, 1000);
    assert_int_equal(c.action_count, 0);
}

static void test_wrong_verdict_corrects_in_the_same_call(void **s)
{
    cub_coach c;
    start_dancing(&c, 1000);
    send(&c, 3500, CUB_EV_VERDICT, 0, 0, 1500);
    assert_int_equal(c.state, CUB_COACH_CORRECT);
    const cub_coach_action *st = act(&c, CUB_COACH_ACT_STATE, 0);
    assert_int_equal(st->from, CUB_COACH_DANCE);
    assert_int_equal(st->to, CUB_COACH_CORRECT);
    assert_true(st < act(&c, CUB_COACH_ACT_CLIP, 0)); /* state first, then the clip */
    expect_clip(&c, C_SHAKE, CUB_Q16_ONE, false, CUB_COACH_WHY_CORRECT);
    assert_true(logged("t=3.500 coach state from=dance to=correct reason=wrong move=0 rep=0"));
    assert_true(logged("t=3.500 coach request clip=head_shake speed=1.000 loop=0 reason=correct"));
    /* A verdict about another move (late, from before a switch) is set aside. */
    send(&c, 3600, CUB_EV_VERDICT, 2, 0, 1600);
    assert_int_equal(c.action_count, 0);
    assert_int_equal(c.misses, 1);
}

/* The last repetition's window closes a beat into the next move, so its
 * wrong verdict comes after the coach moved on: that move is still
 * corrected and shown again once, then the dance goes on where the music
 * is. Later, or about an older move, such a verdict is set aside. */
static void test_last_repetition_wrong_after_the_next_move_began(void **s)
{
    cub_coach c;
    start_dancing(&c, 1000);
    send(&c, 1500, CUB_EV_PLAYER, 1, 0, 500);
    for (int i = 0; i < 4; i++) send(&c, 4000 + 2000 * i, CUB_EV_CLIP_DONE, C_CLAP, 0, 2000 + 2000 * i);
    expect_clip(&c, C_SWAY, 0, false, CUB_COACH_WHY_MOVE); /* sway rep 0 began at 8 s */
    send(&c, 10400, CUB_EV_VERDICT, 0, 0, 8400);           /* clap's rep 3: wrong */
    assert_int_equal(c.state, CUB_COACH_CORRECT);
    assert_int_equal(c.move, 0);
    assert_int_equal(c.rep, 3);
    expect_clip(&c, C_SHAKE, CUB_Q16_ONE, false, CUB_COACH_WHY_CORRECT);
    assert_true(logged("t=10.400 coach hint show=move move=0"));
    /* clap's music is over, yet it is shown again, slower */
    send(&c, 11400, CUB_EV_CLIP_DONE, C_SHAKE, 0, 9400);
    expect_clip(&c, C_CLAP, 45875, false, CUB_COACH_WHY_DEMO);
    /* after that one demonstration: on with sway where the music is */
    send(&c, 13000, CUB_EV_CLIP_DONE, C_CLAP, 0, 9900);
    assert_int_equal(c.state, CUB_COACH_DANCE);
    assert_int_equal(c.move, 1);
    assert_int_equal(c.rep, 1);
    /* a wrong verdict about clap now (sway's rep 1) is set aside */
    send(&c, 13100, CUB_EV_VERDICT, 0, 0, 10000);
    assert_int_equal(c.action_count, 0);
    assert_int_equal(c.state, CUB_COACH_DANCE);
    /* sway ends, the coach waits for robot in the gap: sway's last
     * repetition judged wrong then is corrected too */
    send(&c, 14700, CUB_EV_CLIP_DONE, C_SWAY, 0, 12000);
    expect_clip(&c, C_IDLE, CUB_Q16_ONE, true, CUB_COACH_WHY_IDLE);
    send(&c, 15000, CUB_EV_VERDICT, 1, 0, 12300);
    assert_int_equal(c.state, CUB_COACH_CORRECT);
    assert_int_equal(c.move, 1);
    assert_int_equal(c.rep, 1);
}

/* The slower demonstration is watched, not judged (SEEDS.md § 000): a
 * verdict during it, wrong or right, is logged and changes nothing; when it
 * ends the dance resumes where the music is and that attempt is judged as
 * usual: wrong corrects again (so the demonstration repeats until the
 * child gets it), right dances on. */
static void test_demonstration_is_watched_and_the_attempt_counts(void **s)
{
    cub_coach c;
    start_dancing(&c, 1000);
    send(&c, 2000, CUB_EV_VERDICT, 0, 0, 1000);
    send(&c, 3000, CUB_EV_CLIP_DONE, C_SHAKE, 0, 2000);
    const cub_q16 demo = 45875; /* 0.7 */
    expect_clip(&c, C_CLAP, demo, false, CUB_COACH_WHY_DEMO);
    send(&c, 3500, CUB_EV_VERDICT, 0, 0, 2500); /* wrong while watching */
    assert_int_equal(c.action_count, 0);
    assert_int_equal(c.state, CUB_COACH_CORRECT);
    assert_int_equal(c.misses, 1);
    assert_true(logged("t=3.500 coach watched move=0 result=wrong fault=0"));
    send(&c, 4000, CUB_EV_VERDICT, 0, 1, 3000); /* right while watching */
    assert_int_equal(c.action_count, 0);
    assert_int_equal(c.state, CUB_COACH_CORRECT);
    assert_int_equal(c.misses, 1);
    assert_true(logged("t=4.000 coach watched move=0 result=right fault=0"));

    /* The demonstration ends at music 5.1 s: move 0 (0..8 s, 2 s a rep) at
     * its rep 3 (6 s) is nearest; the attempt resumes there at the sync
     * factor of the moment and, once the player shows its first frame (the
     * music tag), slower: the music is behind that repetition's tag. */
    const cub_q16 factor = c.sync_q16;
    send(&c, 6000, CUB_EV_CLIP_DONE, C_CLAP, 0, 5100);
    assert_int_equal(c.state, CUB_COACH_DANCE);
    assert_int_equal(c.move, 0);
    assert_int_equal(c.rep, 3);
    const cub_coach_action *a = act(&c, CUB_COACH_ACT_CLIP, 0);
    assert_int_equal(a->clip, C_CLAP);
    assert_int_equal(a->reason, CUB_COACH_WHY_RESUME);
    assert_int_equal(a->speed_q16, factor);
    assert_true(logged("coach state from=correct to=dance reason=watched move=0 rep=3"));
    send(&c, 6030, CUB_EV_MUSIC_TAG, 0, 6000, 5130);
    a = act(&c, CUB_COACH_ACT_SPEED, 0);
    assert_non_null(a);
    assert_int_equal(a->speed_q16, cub_coach_sync_speed(6000, 5130, 2000, c.rate_q16, 0));
    assert_true(a->speed_q16 < CUB_Q16_ONE);

    /* The attempt is wrong: corrected again (watch_me in turn), and the
     * demonstration again; one ending past clap's span hands over to sway,
     * whose attempt is right: dance on. */
    send(&c, 7000, CUB_EV_VERDICT, 0, 0, 6100);
    assert_int_equal(c.state, CUB_COACH_CORRECT);
    assert_int_equal(c.misses, 2);
    expect_clip(&c, C_WATCH, CUB_Q16_ONE, false, CUB_COACH_WHY_CORRECT);
    send(&c, 8000, CUB_EV_CLIP_DONE, C_WATCH, 0, 7000);
    expect_clip(&c, C_CLAP, demo, false, CUB_COACH_WHY_DEMO);
    send(&c, 10000, CUB_EV_CLIP_DONE, C_CLAP, 0, 8600);
    assert_int_equal(c.state, CUB_COACH_DANCE);
    assert_int_equal(c.move, 1);
    assert_int_equal(c.rep, 0);
    expect_clip(&c, C_SWAY, 0, false, CUB_COACH_WHY_RESUME);
    send(&c, 11000, CUB_EV_VERDICT, 1, 1, 9600);
    assert_int_equal(c.state, CUB_COACH_DANCE);
    assert_int_equal(c.misses, 0);
    assert_null(act(&c, CUB_COACH_ACT_CLIP, 0));

    /* The demonstration of sway runs at 0.7 of the move's own speed 1.25. */
    send(&c, 11500, CUB_EV_VERDICT, 1, 0, 10000);
    send(&c, 12000, CUB_EV_CLIP_DONE, C_SHAKE, 0, 10500);
    expect_clip(&c, C_SWAY, cub_fx_mul(81920, demo), false, CUB_COACH_WHY_DEMO);
}

/* A wrong verdict with a fault (c) shows the fault in place of the move's
 * words, in the same call as the correcting clip, through the slower
 * demonstration; a second fault replaces it; the dance's resume brings
 * the move's words back. A wrong verdict without a fault leaves the
 * move's words. */
static void test_fault_is_the_hint_while_its_correction_runs(void **s)
{
    cub_coach c;
    start_dancing(&c, 1000);
    cub_event ev = {.t_us = 2000000, .type = CUB_EV_VERDICT, .a = 0, .b = 0, .c = 211};
    assert_int_equal(cub_coach_handle(&c, &ev, 1000), CUB_OK);
    expect_clip(&c, C_SHAKE, CUB_Q16_ONE, false, CUB_COACH_WHY_CORRECT);
    const cub_coach_action *h = act(&c, CUB_COACH_ACT_HINT, 0);
    assert_non_null(h);
    assert_int_equal(h->hint, 0);
    assert_int_equal(h->fault, 211);
    assert_int_equal(h->reason, CUB_COACH_WHY_WRONG);
    assert_true(logged("coach hint show=fault move=0 how=mirror key=RHE=true reason=wrong"));
    send(&c, 3000, CUB_EV_CLIP_DONE, C_SHAKE, 0, 2000);
    expect_clip(&c, C_CLAP, 0, false, CUB_COACH_WHY_DEMO);
    assert_null(act(&c, CUB_COACH_ACT_HINT, 0)); /* the fault stays */
    ev = (cub_event){.t_us = 3500000, .type = CUB_EV_VERDICT, .a = 0, .b = 0, .c = 111};
    assert_int_equal(cub_coach_handle(&c, &ev, 2500), CUB_OK); /* watched: no new hint */
    assert_null(act(&c, CUB_COACH_ACT_HINT, 0));
    assert_true(logged("coach watched move=0 result=wrong fault=111"));
    send(&c, 3800, CUB_EV_CLIP_DONE, C_CLAP, 0, 2800); /* the attempt: clap's words */
    assert_int_equal(c.state, CUB_COACH_DANCE);
    ev = (cub_event){.t_us = 4000000, .type = CUB_EV_VERDICT, .a = 0, .b = 0, .c = 111};
    assert_int_equal(cub_coach_handle(&c, &ev, 3000), CUB_OK);
    assert_int_equal(act(&c, CUB_COACH_ACT_HINT, 0)->fault, 111);
    send(&c, 4500, CUB_EV_PLAYER, 0, 0, 3500); /* away, and back: the fault again */
    assert_int_equal(act(&c, CUB_COACH_ACT_HINT, 0)->hint, CUB_COACH_HINT_COME_CLOSER);
    send(&c, 4600, CUB_EV_PLAYER, 1, 0, 3600);
    assert_int_equal(act(&c, CUB_COACH_ACT_HINT, 0)->fault, 111);
    send(&c, 6000, CUB_EV_VERDICT, 0, 1, 4100); /* right during watch_me */
    assert_int_equal(c.state, CUB_COACH_DANCE);
    h = act(&c, CUB_COACH_ACT_HINT, 0);
    assert_non_null(h);
    assert_int_equal(h->hint, 0);
    assert_int_equal(h->fault, 0);
    assert_true(logged("coach hint show=move move=0 reason=resume"));
    send(&c, 7000, CUB_EV_VERDICT, 0, 0, 5000); /* no fault: the move's words stay */
    assert_int_equal(c.state, CUB_COACH_CORRECT);
    assert_null(act(&c, CUB_COACH_ACT_HINT, 0));
}

/* The Kinect goes mid-song: the music and the dance hold with "can't see
 * you"; verdicts are set aside; when frames come back the music goes on
 * and the dance resumes where the music is. Outside a song nothing
 * happens; STOP and a long wait still work from the pause. */
static void test_camera_loss_pauses_the_song_and_resumes_it(void **s)
{
    cub_coach c;
    cub_coach_desc d = make_desc();
    assert_int_equal(cub_coach_init(&c, &d, 0), CUB_OK);
    send(&c, 100, CUB_EV_CAMERA, 0, 0, CUB_COACH_NO_MUSIC); /* idle: nothing to pause */
    assert_int_equal(c.state, CUB_COACH_IDLE);
    assert_null(act(&c, CUB_COACH_ACT_MUSIC_PAUSE, 0));
    to_dance(&c, 200);
    send(&c, 3000, CUB_EV_CLIP_DONE, C_CLAP, 0, 1800); /* rep 1 of clap */
    send(&c, 3500, CUB_EV_CAMERA, 0, 0, 2300);
    assert_int_equal(c.state, CUB_COACH_PAUSED);
    assert_non_null(act(&c, CUB_COACH_ACT_MUSIC_PAUSE, 0));
    expect_clip(&c, C_IDLE, CUB_Q16_ONE, true, CUB_COACH_WHY_CAMERA);
    const cub_coach_action *h = act(&c, CUB_COACH_ACT_HINT, 0);
    assert_non_null(h);
    assert_int_equal(h->hint, CUB_COACH_HINT_CANT_SEE);
    assert_true(logged("coach state from=dance to=paused reason=camera move=0 rep=1"));
    assert_true(logged("coach hint show=cant_see reason=camera"));
    send(&c, 4000, CUB_EV_VERDICT, 0, 0, 2300); /* the music holds: 2.3 s */
    assert_int_equal(c.state, CUB_COACH_PAUSED);
    send(&c, 9000, CUB_EV_CAMERA, 1, 0, 2300);
    assert_int_equal(c.state, CUB_COACH_DANCE);
    assert_non_null(act(&c, CUB_COACH_ACT_MUSIC_RESUME, 0));
    assert_int_equal(c.move, 0);
    assert_int_equal(c.rep, 1); /* 2.3 s: nearest repetition start 2 s */
    assert_true(logged("coach state from=paused to=dance reason=camera move=0 rep=1"));
    /* Paused again, then STOP: idle, the music stops. */
    send(&c, 9500, CUB_EV_CAMERA, 0, 0, 2800);
    send(&c, 9600, CUB_EV_BUTTON_DOWN, CUB_BUTTON_STOP, 0, 2800);
    assert_int_equal(c.state, CUB_COACH_IDLE);
    assert_non_null(act(&c, CUB_COACH_ACT_MUSIC_STOP, 0));
    /* Paused during the intro and back: wait for the move's tag again. */
    static cub_coach_move late[3];
    memcpy(late, song, sizeof late);
    for (int i = 0; i < 3; i++) late[i].tag_ms += 2000; /* a 2 s intro */
    d.moves = late;
    assert_int_equal(cub_coach_init(&c, &d, 0), CUB_OK);
    to_dance(&c, 0);
    send(&c, 1500, CUB_EV_CAMERA, 0, 0, 400);
    send(&c, 1600, CUB_EV_CAMERA, 1, 0, 400);
    assert_int_equal(c.state, CUB_COACH_DANCE);
    assert_int_equal(c.phase, 1); /* COACH_PH_WAIT: the idle clip until 2 s of music */
    expect_clip(&c, C_IDLE, CUB_Q16_ONE, true, CUB_COACH_WHY_INTRO);
    /* Paused for longer than attract_after: attract (the song is over). */
    send(&c, 1700, CUB_EV_CAMERA, 0, 0, 500);
    tick(&c, 1700 + c.desc.attract_after_ms + 10, 500);
    assert_int_equal(c.state, CUB_COACH_ATTRACT);
    assert_non_null(act(&c, CUB_COACH_ACT_MUSIC_STOP, 0));
}

/* A child who does not get it is not held on one move for the rest of
 * the song: a correcting clip that ends after the music has left the move's
 * span hands over to the dance where the music is. */
static void test_correction_gives_way_when_the_music_moves_on(void **s)
{
    cub_coach c;
    start_dancing(&c, 1000);
    send(&c, 7000, CUB_EV_VERDICT, 0, 0, 7500);
    send(&c, 8000, CUB_EV_CLIP_DONE, C_SHAKE, 0, 8600); /* music in sway's span now */
    assert_int_equal(c.state, CUB_COACH_DANCE);
    assert_int_equal(c.move, 1);
    assert_int_equal(c.rep, 0);
    assert_true(logged("coach state from=correct to=dance reason=moved_on move=1 rep=0"));
    expect_clip(&c, C_SWAY, 0, false, CUB_COACH_WHY_RESUME);
}

static void test_resume_follows_the_music_past_the_move(void **s)
{
    cub_coach c;
    cub_coach_desc d = make_desc();
    struct {
        int32_t music_ms;
        int32_t move, rep, state_phase;
    } cases[] = {
        {8900, 1, 0, 0},    /* early in sway: rep 0 */
        {10900, 1, 1, 0},   /* rep 1 of sway */
        {11900, -1, -1, 1}, /* sway nearly over, robot at 13 s: wait in idle */
        {13200, 2, 0, 0},   /* robot rep 0 */
        {18800, -1, -1, 2}, /* robot nearly over, last move: outro */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        assert_int_equal(cub_coach_init(&c, &d, 0), CUB_OK);
        to_dance(&c, 0);
        c.move = 1; /* corrected sway */
        send(&c, 2000, CUB_EV_VERDICT, 1, 0, 8200);
        send(&c, 3000, CUB_EV_VERDICT, 1, 1, cases[i].music_ms);
        assert_int_equal(c.state, CUB_COACH_DANCE);
        const cub_coach_action *a = act(&c, CUB_COACH_ACT_CLIP, 0);
        if (cases[i].state_phase == 0) {
            assert_int_equal(c.move, cases[i].move);
            assert_int_equal(c.rep, cases[i].rep);
            assert_int_equal(a->clip, song[cases[i].move].clip);
        } else {
            assert_int_equal(a->clip, C_IDLE);
            assert_true(a->loop);
            assert_int_equal(a->reason,
                             cases[i].state_phase == 1 ? CUB_COACH_WHY_IDLE : CUB_COACH_WHY_OUTRO);
        }
    }
    /* While waiting for robot's tag the tick starts it on time. */
    assert_int_equal(cub_coach_init(&c, &d, 0), CUB_OK);
    to_dance(&c, 0);
    c.move = 1;
    send(&c, 2000, CUB_EV_VERDICT, 1, 0, 8200);
    send(&c, 3000, CUB_EV_VERDICT, 1, 1, 11900);
    tick(&c, 3900, 12990);
    assert_int_equal(c.action_count, 0);
    tick(&c, 3933, 13010);
    expect_clip(&c, C_ROBOT, 0, false, CUB_COACH_WHY_MOVE);
}

static void test_attract_then_doze_after_the_configured_quiet(void **s)
{
    cub_coach c;
    cub_coach_desc d = make_desc();
    d.attract_after_ms = 5000;
    d.doze_after_ms = 9000;
    assert_int_equal(cub_coach_init(&c, &d, 0), CUB_OK);
    tick(&c, 4999, CUB_COACH_NO_MUSIC);
    assert_int_equal(c.state, CUB_COACH_IDLE);
    tick(&c, 5000, CUB_COACH_NO_MUSIC);
    assert_int_equal(c.state, CUB_COACH_ATTRACT);
    expect_clip(&c, C_WAVE, CUB_Q16_ONE, true, CUB_COACH_WHY_QUIET);
    tick(&c, 8999, CUB_COACH_NO_MUSIC);
    assert_int_equal(c.state, CUB_COACH_ATTRACT);
    tick(&c, 9000, CUB_COACH_NO_MUSIC);
    assert_int_equal(c.state, CUB_COACH_DOZE);
    expect_clip(&c, C_DOZE, CUB_Q16_ONE, true, CUB_COACH_WHY_QUIET);
    /* A child walking in makes the dozing bear wave. */
    send(&c, 9500, CUB_EV_PLAYER, 1, 0, CUB_COACH_NO_MUSIC);
    assert_int_equal(c.state, CUB_COACH_ATTRACT);

    /* In the dance, verdicts are the interaction: without them, attract
     * (and the music stops); with them, the dance goes on. */
    assert_int_equal(cub_coach_init(&c, &d, 0), CUB_OK);
    to_dance(&c, 0); /* quiet since 0: the START */
    send(&c, 4000, CUB_EV_VERDICT, 0, 1, 3000);
    tick(&c, 8999, 7999);
    assert_int_equal(c.state, CUB_COACH_DANCE);
    tick(&c, 9000, 8000);
    assert_int_equal(c.state, CUB_COACH_ATTRACT);
    assert_non_null(act(&c, CUB_COACH_ACT_MUSIC_STOP, 0));
    assert_true(logged("t=9.000 coach state from=dance to=attract reason=quiet move=0 rep=0"));
}

static void test_worried_after_n_misses_then_back_to_correcting(void **s)
{
    cub_coach c;
    start_dancing(&c, 0);
    send(&c, 2000, CUB_EV_VERDICT, 0, 0, 1000);
    expect_clip(&c, C_SHAKE, CUB_Q16_ONE, false, CUB_COACH_WHY_CORRECT);
    send(&c, 2500, CUB_EV_VERDICT, 0, 0, 1500); /* during the head shake: counted only */
    assert_null(act(&c, CUB_COACH_ACT_CLIP, 0));
    assert_int_equal(c.misses, 2);
    send(&c, 2600, CUB_EV_VERDICT, 0, 1, 1600); /* right: back to dancing */
    assert_int_equal(c.state, CUB_COACH_DANCE);
    send(&c, 2700, CUB_EV_VERDICT, 0, 0, 1700);
    expect_clip(&c, C_WATCH, CUB_Q16_ONE, false, CUB_COACH_WHY_CORRECT); /* in turn */
    send(&c, 2800, CUB_EV_CLIP_DONE, C_WATCH, 0, 1800);
    expect_clip(&c, C_CLAP, 45875, false, CUB_COACH_WHY_DEMO);
    send(&c, 3000, CUB_EV_VERDICT, 0, 0, 2000); /* wrong during the demo: watched */
    assert_null(act(&c, CUB_COACH_ACT_CLIP, 0));
    assert_int_equal(c.misses, 1);
    send(&c, 3200, CUB_EV_CLIP_DONE, C_CLAP, 0, 2200); /* the attempt */
    assert_int_equal(c.state, CUB_COACH_DANCE);
    send(&c, 3300, CUB_EV_VERDICT, 0, 0, 2300); /* wrong: correct again */
    expect_clip(&c, C_SHAKE, CUB_Q16_ONE, false, CUB_COACH_WHY_CORRECT);
    assert_int_equal(c.state, CUB_COACH_CORRECT);
    send(&c, 4000, CUB_EV_VERDICT, 0, 0, 3000);
    assert_int_equal(c.state, CUB_COACH_WORRIED);
    assert_int_equal(act(&c, CUB_COACH_ACT_STATE, 0)->reason, CUB_COACH_WHY_MISSES);
    expect_clip(&c, C_WORRIED, CUB_Q16_ONE, false, CUB_COACH_WHY_WORRIED);
    send(&c, 4500, CUB_EV_VERDICT, 0, 0, 3500); /* wrong while worried: no scolding */
    assert_int_equal(act(&c, CUB_COACH_ACT_CLIP, 0), NULL);
    send(&c, 5000, CUB_EV_CLIP_DONE, C_WORRIED, 0, 4000);
    assert_int_equal(c.state, CUB_COACH_CORRECT);
    expect_clip(&c, C_CLAP, 45875, false, CUB_COACH_WHY_DEMO);
    /* The count starts again: the attempt after the demonstration is
     * wrong, corrected; right during the head shake resets it. */
    send(&c, 5600, CUB_EV_CLIP_DONE, C_CLAP, 0, 4600);
    assert_int_equal(c.state, CUB_COACH_DANCE);
    send(&c, 6000, CUB_EV_VERDICT, 0, 0, 5000);
    assert_int_equal(c.state, CUB_COACH_CORRECT);
    assert_int_equal(c.misses, 1);
    send(&c, 6500, CUB_EV_VERDICT, 0, 0, 5500);
    assert_int_equal(c.state, CUB_COACH_CORRECT);
    send(&c, 7000, CUB_EV_VERDICT, 0, 1, 6000); /* right resets it */
    assert_int_equal(c.misses, 0);
    assert_int_equal(c.state, CUB_COACH_DANCE);
}

static void test_song_end_cheers_then_idles(void **s)
{
    cub_coach c;
    start_dancing(&c, 0);
    send(&c, 20000, CUB_EV_SONG_END, 0, 0, 19000);
    assert_int_equal(c.state, CUB_COACH_CHEER);
    expect_clip(&c, C_CHEER, CUB_Q16_ONE, false, CUB_COACH_WHY_CHEER);
    assert_int_equal(act(&c, CUB_COACH_ACT_HINT, 0)->hint, CUB_COACH_HINT_NONE);
    send(&c, 23000, CUB_EV_CLIP_DONE, C_CHEER, 0, CUB_COACH_NO_MUSIC);
    assert_int_equal(c.state, CUB_COACH_IDLE);
    expect_clip(&c, C_IDLE, CUB_Q16_ONE, true, CUB_COACH_WHY_IDLE);
    assert_null(act(&c, CUB_COACH_ACT_MUSIC_STOP, 0)); /* it ended by itself */
}

/* ---- groove spans (issue 23) --------------------------------------------- */

#define C_GROOVE C_COUNT /* the gap's groove clip, after the library's */
static const char *const groove_names[C_COUNT + 1] = {
    "idle",  "wake_up", "wave", "doze",  "head_shake",   "watch_me",
    "worried", "cheer", "clap", "sway", "robot", "groove_gap_7"};
static const cub_coach_groove gap_groove = {.clip = C_GROOVE, .tag_ms = 12000, .span_ms = 1000};

/* Dance to the end of sway (move 1, the gap after it) with groove span g
 * in the gap; the music stands at gap_ms when sway ends. */
static void dance_to_groove(cub_coach *c, const cub_coach_groove *g, int32_t gap_ms)
{
    cub_coach_desc d = make_desc();
    d.grooves = g;
    d.groove_count = 1;
    d.clip_count = C_COUNT + 1;
    d.clip_names = groove_names;
    assert_int_equal(cub_coach_init(c, &d, 0), CUB_OK);
    to_dance(c, 0);
    for (int rep = 1; rep <= 4; rep++) /* clap's repetitions, then sway */
        send(c, 1000 + 2000 * rep, CUB_EV_CLIP_DONE, C_CLAP, 0, 2000 * rep);
    send(c, 11000, CUB_EV_CLIP_DONE, C_SWAY, 0, 10000);
    send(c, 1000 + gap_ms, CUB_EV_CLIP_DONE, C_SWAY, 0, gap_ms);
}

static void dance_to_gap(cub_coach *c, int32_t gap_ms)
{
    dance_to_groove(c, &gap_groove, gap_ms);
}

static void test_gap_dances_its_groove_then_the_next_move(void **s)
{
    (void)s;
    cub_coach c;
    dance_to_gap(&c, 12000);
    assert_int_equal(c.state, CUB_COACH_DANCE);
    expect_clip(&c, C_GROOVE, CUB_Q16_ONE, false, CUB_COACH_WHY_GROOVE);
    assert_int_equal(c.move, 2); /* waiting for robot: the groove is no move */
    assert_true(logged("coach request clip=groove_gap_7 speed=1.000 loop=0 reason=groove "
                       "move=2 rep=0"));
    tick(&c, 13500, 12500); /* once per span */
    assert_null(act(&c, CUB_COACH_ACT_CLIP, 0));
    send(&c, 13990, CUB_EV_CLIP_DONE, C_GROOVE, 0, 12990); /* its end: idle till the tag */
    expect_clip(&c, C_IDLE, CUB_Q16_ONE, true, CUB_COACH_WHY_IDLE);
    tick(&c, 14000, 13000);
    expect_clip(&c, C_ROBOT, 0, false, CUB_COACH_WHY_MOVE);
}

/* The gap's span, 1 s of 4 beats (12000, 12250, 12500, 12750). */
static const cub_coach_groove gap_beats = {
    .clip = C_GROOVE, .tag_ms = 12000, .span_ms = 1000, .beats = 4};

/* A span found more than CUB_COACH_GROOVE_LATE_MS late (a correction
 * ended in it) is joined on its next beat, not left to the idle clip. */
static void test_groove_joined_late_on_its_next_beat(void **s)
{
    (void)s;
    cub_coach c;
    cub_coach_groove g = gap_beats;
    dance_to_groove(&c, &g, 12000 + CUB_COACH_GROOVE_LATE_MS + 20); /* 12520 */
    expect_clip(&c, C_IDLE, CUB_Q16_ONE, true, CUB_COACH_WHY_IDLE);
    tick(&c, 13700, 12700);
    assert_null(act(&c, CUB_COACH_ACT_CLIP, 0));
    tick(&c, 13750, 12750); /* the next beat */
    expect_clip(&c, C_GROOVE, CUB_Q16_ONE, false, CUB_COACH_WHY_GROOVE);
    tick(&c, 13800, 12800); /* once */
    assert_null(act(&c, CUB_COACH_ACT_CLIP, 0));
    tick(&c, 14000, 13000);
    expect_clip(&c, C_ROBOT, 0, false, CUB_COACH_WHY_MOVE);
}

/* The bridge's lead: asked for that much before the beat, and a beat the
 * bridge cannot reach any more is passed for the next. */
static void test_groove_joined_late_leaves_room_for_the_bridge(void **s)
{
    (void)s;
    cub_coach c;
    cub_coach_groove g = gap_beats;
    g.entry_lead_ms = 100;
    dance_to_groove(&c, &g, 12000 + CUB_COACH_GROOVE_LATE_MS + 20); /* 12520 */
    tick(&c, 13640, 12640);
    assert_null(act(&c, CUB_COACH_ACT_CLIP, 0));
    tick(&c, 13650, 12650); /* 12750 - 100 */
    expect_clip(&c, C_GROOVE, CUB_Q16_ONE, false, CUB_COACH_WHY_GROOVE);

    g.entry_lead_ms = 240; /* 12750 is out of reach from 12520: no beat with room is left */
    dance_to_groove(&c, &g, 12520);
    for (int32_t t = 12530; t < 13000; t += 10) {
        tick(&c, 1000 + t, t);
        assert_null(act(&c, CUB_COACH_ACT_CLIP, 0));
    }
}

/* Without beats a span found late idles (the song gave no meter). */
static void test_groove_without_beats_is_not_begun_late(void **s)
{
    (void)s;
    cub_coach c;
    dance_to_gap(&c, 12000 + CUB_COACH_GROOVE_LATE_MS);
    expect_clip(&c, C_IDLE, CUB_Q16_ONE, true, CUB_COACH_WHY_IDLE);
    tick(&c, 13600, 12600);
    assert_null(act(&c, CUB_COACH_ACT_CLIP, 0));
}

/* A groove song: no move, one span for the whole song, danced from the
 * music's start; the song's end cheers as after any song. */
static void test_groove_song_dances_its_span_then_cheers(void **s)
{
    (void)s;
    static const cub_coach_groove whole = {.clip = C_GROOVE, .tag_ms = 0, .span_ms = 20000};
    cub_coach c;
    cub_coach_desc d = make_desc();
    d.moves = NULL;
    d.move_count = 0;
    assert_int_equal(cub_coach_init(&c, &d, 0), CUB_ERR_ARG); /* no move, no groove */
    d.grooves = &whole;
    d.groove_count = 1;
    d.clip_count = C_COUNT + 1;
    d.clip_names = groove_names;
    assert_int_equal(cub_coach_init(&c, &d, 0), CUB_OK);
    to_dance(&c, 0);
    assert_non_null(act(&c, CUB_COACH_ACT_MUSIC_START, 0));
    expect_clip(&c, C_GROOVE, CUB_Q16_ONE, false, CUB_COACH_WHY_GROOVE);
    assert_int_equal(c.move, -1);
    tick(&c, 5000, 4000);
    assert_null(act(&c, CUB_COACH_ACT_CLIP, 0));
    send(&c, 21000, CUB_EV_SONG_END, 0, 0, 20000);
    assert_int_equal(c.state, CUB_COACH_CHEER);
    expect_clip(&c, C_CHEER, CUB_Q16_ONE, false, CUB_COACH_WHY_CHEER);
}

static void test_bad_groove_is_refused(void **s)
{
    (void)s;
    cub_coach c;
    cub_coach_desc d = make_desc();
    d.grooves = &gap_groove;
    d.groove_count = 1; /* its clip is outside the library */
    assert_int_equal(cub_coach_init(&c, &d, 0), CUB_ERR_ARG);
    d.grooves = NULL;
    assert_int_equal(cub_coach_init(&c, &d, 0), CUB_ERR_ARG);
    cub_coach_groove g = gap_beats;
    d.grooves = &g;
    d.clip_count = C_COUNT + 1;
    d.clip_names = groove_names;
    assert_int_equal(cub_coach_init(&c, &d, 0), CUB_OK);
    g.beats = -1;
    assert_int_equal(cub_coach_init(&c, &d, 0), CUB_ERR_ARG);
    g.beats = g.span_ms + 1; /* a beat shorter than a ms */
    assert_int_equal(cub_coach_init(&c, &d, 0), CUB_ERR_ARG);
}

/* Bring a fresh coach into state s. */
static void drive_to(cub_coach *c, int s)
{
    cub_coach_desc d = make_desc();
    d.attract_after_ms = 5000;
    d.doze_after_ms = 9000;
    assert_int_equal(cub_coach_init(c, &d, 0), CUB_OK);
    switch (s) {
    case CUB_COACH_WAKE: send(c, 100, CUB_EV_BUTTON_DOWN, CUB_BUTTON_START, 0, -1); break;
    case CUB_COACH_DANCE: to_dance(c, 100); break;
    case CUB_COACH_CORRECT:
        to_dance(c, 100);
        send(c, 2000, CUB_EV_VERDICT, 0, 0, 900);
        break;
    case CUB_COACH_WORRIED:
        to_dance(c, 100);
        for (int i = 0; i < 3; i++)
            send(c, 2000 + i, CUB_EV_VERDICT, 0, 0, 900);
        break;
    case CUB_COACH_ATTRACT: tick(c, 5000, -1); break;
    case CUB_COACH_DOZE:
        tick(c, 5000, -1);
        tick(c, 9000, -1);
        break;
    case CUB_COACH_CHEER:
        to_dance(c, 100);
        send(c, 2000, CUB_EV_SONG_END, 0, 0, 900);
        break;
    case CUB_COACH_PAUSED:
        to_dance(c, 100);
        send(c, 2000, CUB_EV_CAMERA, 0, 0, 900);
        break;
    default: break;
    }
    assert_int_equal(c->state, s);
}

static void test_stop_returns_to_idle_from_every_state(void **s)
{
    cub_coach c;
    for (int st = 0; st < CUB_COACH_STATE_COUNT; st++) {
        drive_to(&c, st);
        const bool music = c.music_on;
        send(&c, 9500, CUB_EV_BUTTON_DOWN, CUB_BUTTON_STOP, 0, 1000);
        assert_int_equal(c.state, CUB_COACH_IDLE);
        assert_false(c.music_on);
        if (st == CUB_COACH_IDLE) continue; /* already there: nothing to do */
        expect_clip(&c, C_IDLE, CUB_Q16_ONE, true, CUB_COACH_WHY_IDLE);
        assert_int_equal(act(&c, CUB_COACH_ACT_STATE, 0)->reason, CUB_COACH_WHY_STOP);
        assert_int_equal(act(&c, CUB_COACH_ACT_MUSIC_STOP, 0) != NULL, music);
        assert_int_equal(c.move, -1);
    }
}

static void test_player_away_shows_come_closer(void **s)
{
    cub_coach c;
    start_dancing(&c, 0);
    send(&c, 2000, CUB_EV_PLAYER, 0, 0, 1000);
    assert_int_equal(act(&c, CUB_COACH_ACT_HINT, 0)->hint, CUB_COACH_HINT_COME_CLOSER);
    assert_true(logged("t=2.000 coach hint show=come_closer reason=player"));
    send(&c, 3000, CUB_EV_CLIP_DONE, C_CLAP, 0, 2000); /* next rep: the hint stays */
    assert_null(act(&c, CUB_COACH_ACT_HINT, 0));
    send(&c, 4000, CUB_EV_PLAYER, 1, 0, 3000);
    assert_int_equal(act(&c, CUB_COACH_ACT_HINT, 0)->hint, 0);
}

/* A child too close (the judge's CUB_EV_PLAYER a = 0, b = 1): "Step back",
 * not "Come closer!"; still too close when the song pauses, "Step back"
 * again instead of "Where are you?"; the judge's verdicts are none (see
 * test_judge), and one that came would be set aside. Back in view: the
 * move's words. */
static void test_too_close_shows_step_back(void **s)
{
    cub_coach c;
    start_dancing(&c, 0);
    send(&c, 2000, CUB_EV_PLAYER, 0, 1, 1000);
    assert_int_equal(act(&c, CUB_COACH_ACT_HINT, 0)->hint, CUB_COACH_HINT_STEP_BACK);
    assert_true(logged("t=2.000 coach hint show=step_back reason=player"));
    send(&c, 2500, CUB_EV_VERDICT, 0, 0, 1500);
    assert_int_equal(c.state, CUB_COACH_DANCE); /* nobody corrected */
    tick(&c, 2000 + CUB_COACH_AWAY_PAUSE_MS, 1000 + CUB_COACH_AWAY_PAUSE_MS);
    assert_int_equal(c.state, CUB_COACH_PAUSED);
    assert_int_equal(c.hint, CUB_COACH_HINT_STEP_BACK); /* not "Where are you?" */
    send(&c, 8000, CUB_EV_PLAYER, 1, 0, 1000 + CUB_COACH_AWAY_PAUSE_MS);
    assert_int_equal(c.state, CUB_COACH_DANCE);
    assert_true(act(&c, CUB_COACH_ACT_HINT, 0)->hint != CUB_COACH_HINT_STEP_BACK);
    assert_false(c.too_close);
}

/* A child who steps out of view mid-song: "Come closer!" at once, the
 * music on for CUB_COACH_AWAY_PAUSE_MS; then the song pauses with "Where
 * are you?". Verdicts meanwhile are set aside, a right one included (no
 * one is there to credit). Back in view: the music and the dance go on
 * where the music is. */
static void test_child_gone_briefly_pauses_then_resumes(void **s)
{
    cub_coach c;
    start_dancing(&c, 0); /* the dance from 1 s; music time = loop time - 1 s */
    send(&c, 2000, CUB_EV_VERDICT, 0, 0, 1000); /* the child there, wrong: corrected */
    assert_int_equal(c.state, CUB_COACH_CORRECT);
    send(&c, 2500, CUB_EV_PLAYER, 0, 0, 1500);
    assert_int_equal(act(&c, CUB_COACH_ACT_HINT, 0)->hint, CUB_COACH_HINT_COME_CLOSER);
    send(&c, 3000, CUB_EV_VERDICT, 0, 1, 2000); /* right, after "no player": not acted on */
    assert_int_equal(c.state, CUB_COACH_CORRECT);
    assert_null(act(&c, CUB_COACH_ACT_STATE, 0));
    assert_true(logged("coach ignore"));
    tick(&c, 2500 + CUB_COACH_AWAY_PAUSE_MS - 10, 5490);
    assert_int_equal(c.state, CUB_COACH_CORRECT); /* the grace: the music plays on */
    tick(&c, 2500 + CUB_COACH_AWAY_PAUSE_MS, 5500);
    assert_int_equal(c.state, CUB_COACH_PAUSED);
    assert_non_null(act(&c, CUB_COACH_ACT_MUSIC_PAUSE, 0));
    expect_clip(&c, C_IDLE, CUB_Q16_ONE, true, CUB_COACH_WHY_AWAY);
    assert_int_equal(act(&c, CUB_COACH_ACT_HINT, 0)->hint, CUB_COACH_HINT_WHERE);
    assert_true(logged("t=6.500 coach state from=correct to=paused reason=away"));
    assert_true(logged("t=6.500 coach hint show=where reason=away"));
    send(&c, 7000, CUB_EV_VERDICT, 0, 1, 5500); /* still nobody: set aside */
    send(&c, 7500, CUB_EV_CAMERA, 1, 0, 5500);  /* not what it waits for */
    assert_int_equal(c.state, CUB_COACH_PAUSED);
    send(&c, 9000, CUB_EV_PLAYER, 1, 0, 5500);
    assert_int_equal(c.state, CUB_COACH_DANCE);
    assert_non_null(act(&c, CUB_COACH_ACT_MUSIC_RESUME, 0));
    assert_int_equal(c.move, 0);
    assert_int_equal(c.rep, 3); /* 5.5 s of clap's 8: its 4th repetition (6 s) is nearest */
    assert_true(logged("t=9.000 coach state from=paused to=dance reason=player move=0 rep=3"));
    tick(&c, 9000 + CUB_COACH_AWAY_PAUSE_MS + 10, 9500); /* in view: no pause */
    assert_int_equal(c.state, CUB_COACH_DANCE);
}

/* A child gone for good: the song pauses, and the judge's "no player"
 * verdicts (one a repetition) no longer count as interaction, so the
 * attract comes attract_after the child's last verdict, the doze
 * doze_after it, as when idle. */
static void test_child_gone_long_attracts_then_dozes(void **s)
{
    cub_coach c;
    start_dancing(&c, 0);
    send(&c, 2000, CUB_EV_VERDICT, 0, 1, 1000); /* the last interaction */
    send(&c, 2500, CUB_EV_PLAYER, 0, 0, 1500);
    const int64_t attract = 2000 + c.desc.attract_after_ms, doze = 2000 + c.desc.doze_after_ms;
    for (int64_t t = 3000; t < attract; t += 2000) {
        send(&c, t, CUB_EV_VERDICT, 0, 0, 2000); /* wrong, nobody seen: no correction */
        assert_true(c.state == CUB_COACH_DANCE || c.state == CUB_COACH_PAUSED);
        tick(&c, t + 500, 2000);
    }
    assert_int_equal(c.state, CUB_COACH_PAUSED);
    tick(&c, attract - 10, 2000);
    assert_int_equal(c.state, CUB_COACH_PAUSED);
    tick(&c, attract, 2000);
    assert_int_equal(c.state, CUB_COACH_ATTRACT);
    assert_non_null(act(&c, CUB_COACH_ACT_MUSIC_STOP, 0));
    expect_clip(&c, C_WAVE, CUB_Q16_ONE, true, CUB_COACH_WHY_QUIET);
    tick(&c, doze - 10, CUB_COACH_NO_MUSIC);
    assert_int_equal(c.state, CUB_COACH_ATTRACT);
    tick(&c, doze, CUB_COACH_NO_MUSIC);
    assert_int_equal(c.state, CUB_COACH_DOZE);
    assert_false(logged("to=correct"));
}

/* ---- music sync ---------------------------------------------------------- */

static void test_sync_speed_behind_ahead_and_bounded(void **s)
{
    const cub_q16 one = CUB_Q16_ONE;
    assert_int_equal(cub_coach_sync_speed(4000, 4000, 4000, one, 0), one); /* on time */
    /* Music 200 ms behind: 4000 ms of dance in 4200 ms of music. */
    assert_int_equal(cub_coach_sync_speed(4000, 3800, 4000, one, 0), 62415); /* 0.952 */
    assert_int_equal(cub_coach_sync_speed(4000, 4200, 4000, one, 0), 68985); /* 1.053 */
    /* Bounded to 1 -+ 0.15 (9830/65536), or a bound given. */
    assert_int_equal(cub_coach_sync_speed(4000, 2000, 4000, one, 0), one - 9830);
    assert_int_equal(cub_coach_sync_speed(4000, 6000, 4000, one, 0), one + 9830);
    assert_int_equal(cub_coach_sync_speed(4000, 3000, 4000, one, 3277), one - 3277);
    assert_int_equal(cub_coach_sync_speed(4000, 9000, 4000, one, 0), one + 9830); /* past */
    /* A music clock running 5 % slow: the dance slows to it. */
    assert_int_equal(cub_coach_sync_speed(4000, 4000, 4000, 62259, 0), 62259);
    assert_int_equal(cub_coach_sync_speed(4000, 3900, 4000, 62259, 0), 60740);
    /* Degenerate input: no span, unknown rate, absurd bound. */
    assert_int_equal(cub_coach_sync_speed(4000, 3000, 0, one, 0), one);
    assert_int_equal(cub_coach_sync_speed(4000, 3800, 4000, 0, 0), 62415);
    assert_true(cub_coach_sync_speed(4000, 0, 4000, one, 5 * one) > 0);
    assert_int_equal(cub_coach_sync_speed(INT32_MAX, INT32_MIN, INT32_MAX, INT32_MAX, 0),
                     one + 9830);
    assert_int_equal(cub_coach_sync_speed(INT32_MIN, INT32_MAX, INT32_MAX, 1, 0), one + 9830);
    printf("coach: sync speed behind200=%.4f ahead200=%.4f bounded=%.4f/%.4f slow5%%=%.4f\n",
           62415 / 65536.0, 68985 / 65536.0, (one - 9830) / 65536.0, (one + 9830) / 65536.0,
           62259 / 65536.0);
}

static void test_music_tag_sets_the_moves_speed(void **s)
{
    cub_coach c;
    cub_coach_desc d = make_desc();
    assert_int_equal(cub_coach_init(&c, &d, 0), CUB_OK);
    to_dance(&c, 0);                                   /* music starts at 1.000 */
    tick(&c, 1100, 60);                                /* the audio clock moves: anchor */
    send(&c, 3100, CUB_EV_CLIP_DONE, C_CLAP, 0, 2000); /* rate 1940/2000 = 0.97 */
    send(&c, 9000, CUB_EV_CLIP_DONE, C_CLAP, 0, 0);
    send(&c, 9001, CUB_EV_CLIP_DONE, C_CLAP, 0, 0);
    send(&c, 9002, CUB_EV_CLIP_DONE, C_CLAP, 0, 7800); /* sway starts at 7.8 s of music */
    assert_true(c.tag_pending);
    send(&c, 9040, CUB_EV_MUSIC_TAG, 1, 8000, 7840);
    const cub_coach_action *a = act(&c, CUB_COACH_ACT_SPEED, 0);
    assert_non_null(a);
    /* Aimed at the next tag: sway's rep 1 at 10 s. */
    cub_q16 f = cub_coach_sync_speed(8000, 7840, 2000, c.rate_q16, 0);
    assert_true(f < CUB_Q16_ONE); /* the music is behind the tag: slower */
    assert_int_equal(a->speed_q16, cub_fx_mul(81920, f));
    assert_true(logged("t=9.040 coach sync move=1 music_ms=7840 tag_ms=8000 speed="));
    /* Only once per repetition begun. */
    send(&c, 9050, CUB_EV_MUSIC_TAG, 1, 8000, 7850);
    assert_null(act(&c, CUB_COACH_ACT_SPEED, 0));
    /* The last repetition aims at the move's end less the next move's lead
     * (its route lands on its tag): clap's rep 3 (6..8 s), sway 300 ms. */
    static cub_coach_move led[3];
    memcpy(led, d.moves, sizeof led);
    led[1].lead_ms = 300;
    d.moves = led;
    assert_int_equal(cub_coach_init(&c, &d, 0), CUB_OK);
    to_dance(&c, 0);
    for (int rep = 1; rep <= 3; rep++)
        send(&c, 1100 + rep, CUB_EV_CLIP_DONE, C_CLAP, 0, 0);
    send(&c, 1105, CUB_EV_MUSIC_TAG, 0, 6000, 6000);
    a = act(&c, CUB_COACH_ACT_SPEED, 0);
    assert_non_null(a);
    assert_int_equal(a->speed_q16, cub_coach_sync_speed(5700, 6000, 2000, c.rate_q16, 0));
    assert_true(a->speed_q16 > CUB_Q16_ONE); /* 2 s of clap in 1.7 s of music */
}

/* A scripted input at t_ms: a = -1 means "the move being danced". */
typedef struct script_ev {
    int32_t t_ms, type, a, b;
} script_ev;

typedef struct session {
    const cub_coach_move *moves;
    int32_t move_count;
    int rate_permille;       /* the music clock against the loop clock */
    const script_ev *script; /* in time order */
    int script_count;
    bool record;            /* log into the recorder */
    cub_q16 sync_bound_q16; /* 0: the default */
    /* out */
    int64_t worst_us, worst_tag_us; /* |music - dance| while moves play / at first frames */
    int32_t song_ms;
    int32_t end_state;
} session;

static int64_t clip_len_us(const session *ss, const cub_coach_action *a)
{
    if (a->reason == CUB_COACH_WHY_MOVE || a->reason == CUB_COACH_WHY_REP ||
        a->reason == CUB_COACH_WHY_RESUME || a->reason == CUB_COACH_WHY_DEMO)
        return (int64_t)ss->moves[a->move].span_ms * 1000 / ss->moves[a->move].reps;
    return a->loop ? 1000000 : 1500000; /* idle loops; wake_up, head_shake, cheer... */
}

static void note_error(int64_t err_us, int64_t *worst_us)
{
    if (err_us < 0) err_us = -err_us;
    if (err_us > *worst_us) *worst_us = err_us;
}

/* A small player, all integer so that every CPU gives the same log: plays
 * what the coach asks at the asked speed, posts clip-done at a clip's end
 * and the music tag at each repetition's first frame; the music clock runs at
 * rate_permille of the loop clock after a 60 ms start-up and ends the song
 * at the last move's end. START at the first tick. */
static void run_session(session *ss)
{
    const cub_coach_move *last = &ss->moves[ss->move_count - 1];
    ss->song_ms = last->tag_ms + last->span_ms;
    ss->worst_us = ss->worst_tag_us = 0;
    cub_coach c;
    cub_coach_desc d = make_desc();
    d.moves = ss->moves;
    d.move_count = ss->move_count;
    if (!ss->record) d.log = NULL;
    d.attract_after_ms = 100000; /* the sync runs give no verdicts */
    d.doze_after_ms = 200000;
    d.sync_bound_q16 = ss->sync_bound_q16;
    assert_int_equal(cub_coach_init(&c, &d, 0), CUB_OK);
    int64_t now = 0, music_start_us = -1;
    int64_t pos_us = 0, len_us = 1000000; /* song time into the clip */
    int32_t clip = C_IDLE;
    cub_q16 speed = CUB_Q16_ONE;
    cub_q16 base = CUB_Q16_ONE; /* the move's own speed: song time runs at speed/base */
    bool loop = true, dancing = false, started = false;
    int next = 0;
    for (int step = 0; step < 9000; step++) {
        now += 33333;
        int64_t music_us = -1;
        if (music_start_us >= 0)
            music_us = now < music_start_us + 60000
                           ? 0
                           : (now - music_start_us - 60000) * ss->rate_permille / 1000;
        const int32_t music_ms = music_us < 0 ? CUB_COACH_NO_MUSIC : (int32_t)(music_us / 1000);
        pos_us += (int64_t)33333 * speed / base;
        const bool done = !loop && pos_us >= len_us;
        if (pos_us >= len_us) pos_us -= len_us; /* the next clip or pass goes on from there */
        cub_event ev = {.t_us = now};
        if (!started) {
            ev = (cub_event){.t_us = now, .type = CUB_EV_BUTTON_DOWN, .a = CUB_BUTTON_START};
            started = true;
        } else if (next < ss->script_count && ss->script[next].t_ms * 1000 <= now) {
            const script_ev *e = &ss->script[next++];
            ev =
                (cub_event){.t_us = now, .type = e->type, .a = e->a < 0 ? c.move : e->a, .b = e->b};
        } else if (music_us >= (int64_t)ss->song_ms * 1000) {
            ev.type = CUB_EV_SONG_END;
            music_start_us = -1;
        } else if (done) {
            ev = (cub_event){.t_us = now, .type = CUB_EV_CLIP_DONE, .a = clip};
        }
        if (ev.type)
            assert_int_equal(cub_coach_handle(&c, &ev, music_ms), CUB_OK);
        else
            assert_int_equal(cub_coach_tick(&c, now, music_ms), CUB_OK);
        const cub_coach_action *move_start = NULL;
        for (int i = 0; i < c.action_count; i++) {
            const cub_coach_action *a = &c.actions[i];
            if (a->kind == CUB_COACH_ACT_MUSIC_START) music_start_us = now;
            if (a->kind == CUB_COACH_ACT_MUSIC_STOP) music_start_us = -1;
            if (a->kind == CUB_COACH_ACT_SPEED) speed = a->speed_q16;
            if (a->kind != CUB_COACH_ACT_CLIP) continue;
            if (!done) pos_us = 0; /* a switch mid-clip starts the new one afresh */
            clip = a->clip;
            speed = a->speed_q16;
            loop = a->loop;
            len_us = clip_len_us(ss, a);
            base = CUB_Q16_ONE;
            if (a->move >= 0 && a->clip == ss->moves[a->move].clip && !a->loop)
                base = ss->moves[a->move].speed_q16 ? ss->moves[a->move].speed_q16 : CUB_Q16_ONE;
            dancing = a->reason == CUB_COACH_WHY_MOVE || a->reason == CUB_COACH_WHY_REP ||
                      a->reason == CUB_COACH_WHY_RESUME;
            if (dancing) move_start = a;
        }
        if (move_start) { /* its first frame: the app posts the repetition's tag */
            const cub_coach_move *m = &ss->moves[move_start->move];
            const int64_t tag_us =
                (int64_t)m->tag_ms * 1000 + (int64_t)m->span_ms * 1000 * move_start->rep / m->reps;
            const int64_t music_now_us = music_us < 0 ? 0 : music_us; /* started this step */
            note_error(music_now_us - tag_us - pos_us, &ss->worst_tag_us);
            cub_event tag = {.t_us = now, .type = CUB_EV_MUSIC_TAG, .a = move_start->move,
                             .b = (int32_t)((tag_us + pos_us) / 1000)};
            assert_int_equal(cub_coach_handle(&c, &tag, (int32_t)(music_now_us / 1000)), CUB_OK);
            const cub_coach_action *a = act(&c, CUB_COACH_ACT_SPEED, 0);
            if (a) speed = a->speed_q16;
        }
        if (c.state == CUB_COACH_DANCE && dancing && music_us >= 0) {
            const cub_coach_move *m = &ss->moves[c.move];
            const int64_t rep_us =
                (int64_t)m->tag_ms * 1000 + (int64_t)m->span_ms * 1000 * c.rep / m->reps;
            note_error(music_us - rep_us - pos_us, &ss->worst_us);
        }
        if (c.state == CUB_COACH_IDLE && step > 10) break;
    }
    ss->end_state = c.state;
}

static void test_sync_keeps_the_dance_on_a_skewed_music_clock(void **s)
{
    static cub_coach_move moves[8];
    const int32_t rep_ms[8] = {2000, 1500, 2500, 2000, 1800, 2200, 2000, 1600};
    int32_t t_ms = 2000; /* a 2 s intro */
    for (int i = 0; i < 8; i++) {
        moves[i] = (cub_coach_move){.clip = C_CLAP + i % 3, .reps = 2 + i % 3, .tag_ms = t_ms};
        moves[i].span_ms = moves[i].reps * rep_ms[i];
        t_ms += moves[i].span_ms;
    }
    const int rates[] = {950, 1000, 1050};
    for (int i = 0; i < 3; i++) {
        session ss = {.moves = moves, .move_count = 8, .rate_permille = rates[i]};
        run_session(&ss);
        printf("coach: music clock x%.2f: dance vs music max %.1f ms (%.2f frames), at move "
               "starts %.1f ms, over a %d s song of 8 moves\n",
               rates[i] / 1000.0, ss.worst_us / 1000.0, ss.worst_us / 33333.0,
               ss.worst_tag_us / 1000.0, (int)(ss.song_ms / 1000));
        assert_int_equal(ss.end_state, CUB_COACH_IDLE); /* danced, cheered, rested */
        assert_true(ss.worst_tag_us <= 66667);          /* within 2 frames of every tag */
        assert_true(ss.worst_us <= 66667);
        /* The same without sync (a bound of 1/65536): the drift it removes. */
        session off = {
            .moves = moves, .move_count = 8, .rate_permille = rates[i], .sync_bound_q16 = 1};
        run_session(&off);
        printf("coach: music clock x%.2f without sync: max %.1f ms\n", rates[i] / 1000.0,
               off.worst_us / 1000.0);
        if (rates[i] != 1000) assert_true(off.worst_us > 10 * ss.worst_us);
    }
}

/* FNV-1a over the log, line by line. */
static uint32_t log_hash(void)
{
    uint32_t h = 2166136261u;
    for (int i = 0; i < rec.n; i++)
        for (const char *p = rec.lines[i];; p++) {
            h = (h ^ (uint8_t)*p) * 16777619u;
            if (!*p) break;
        }
    return h;
}

static const script_ev session_script[] = {
    {3000, CUB_EV_VERDICT, -1, 1},
    {4500, CUB_EV_VERDICT, -1, 0},  /* head_shake, then the slow demo */
    {7000, CUB_EV_VERDICT, -1, 1},  /* right while the demo plays: watched, not judged */
    {9200, CUB_EV_VERDICT, -1, 1},  /* the attempt after it (sway, where the music is) */
    {9500, CUB_EV_VERDICT, -1, 0},  /* watch_me this time, then the demo */
    {12000, CUB_EV_PLAYER, 0, 0},   /* the child steps out of view ... */
    {12500, CUB_EV_VERDICT, -1, 1}, /* (the judge's last word: nobody to credit) */
    {13000, CUB_EV_PLAYER, 1, 0},   /* ... and back */
    {15000, CUB_EV_VERDICT, -1, 0},
    {15100, CUB_EV_VERDICT, -1, 0},
    {15200, CUB_EV_VERDICT, -1, 0}, /* three in a row: worried */
    {17500, CUB_EV_VERDICT, -1, 1}, /* during robot's demonstration: watched */
};

/* The state changes of the scripted session, in order. */
static const char *const session_states[] = {
    "coach state from=idle to=wake reason=start",
    "coach state from=wake to=dance reason=woke move=0 rep=0",
    "coach state from=dance to=correct reason=wrong move=0 rep=1",
    /* the demonstration watched, the attempt where the music is: sway */
    "coach state from=correct to=dance reason=watched move=1 rep=0",
    "coach state from=dance to=correct reason=wrong move=1 rep=0",
    /* the right verdict while the child was out of view is set aside; the
     * demonstration ends past sway's span: the attempt is robot's */
    "coach state from=correct to=dance reason=watched move=2 rep=0",
    "coach state from=dance to=correct reason=wrong move=2 rep=0",
    "coach state from=correct to=worried reason=misses move=2 rep=0",
    "coach state from=worried to=correct reason=calmed move=2 rep=0",
    "coach state from=correct to=dance reason=watched move=2 rep=2",
    "coach state from=dance to=cheer reason=song_end",
    "coach state from=cheer to=idle reason=cheered",
};

static void test_scripted_session_gives_the_same_log_every_time(void **s)
{
    session ss = {.moves = song,
                  .move_count = 3,
                  .rate_permille = 1000,
                  .script = session_script,
                  .script_count = (int)(sizeof session_script / sizeof session_script[0]),
                  .record = true};
    run_session(&ss);
    assert_int_equal(ss.end_state, CUB_COACH_IDLE);
    static recorder first;
    first = rec;
    uint32_t h1 = log_hash();
    run_session(&ss);
    assert_int_equal(rec.n, first.n);
    for (int i = 0; i < rec.n; i++)
        assert_string_equal(rec.lines[i], first.lines[i]);
    assert_int_equal(log_hash(), h1);

    int k = 0;
    const int want = (int)(sizeof session_states / sizeof session_states[0]);
    for (int i = 0; i < rec.n; i++) printf("coach trace: %s\n", rec.lines[i]);
    for (int i = 0; i < rec.n; i++) {
        if (!strstr(rec.lines[i], " coach state ")) continue;
        assert_true(k < want);
        assert_non_null(strstr(rec.lines[i], session_states[k]));
        k++;
    }
    assert_int_equal(k, want);
    printf("coach: scripted session %d log lines, fnv1a=%08x\n", rec.n, (unsigned)h1);
    assert_int_equal(h1, SESSION_LOG_FNV);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_desc_is_refused),
        cmocka_unit_test(test_bad_events_change_nothing),
        cmocka_unit_test(test_init_idles_and_start_wakes_into_the_dance),
        cmocka_unit_test(test_clap_wakes_from_idle_attract_and_doze),
        cmocka_unit_test(test_wrong_verdict_corrects_in_the_same_call),
        cmocka_unit_test(test_demonstration_is_watched_and_the_attempt_counts),
        cmocka_unit_test(test_fault_is_the_hint_while_its_correction_runs),
        cmocka_unit_test(test_last_repetition_wrong_after_the_next_move_began),
        cmocka_unit_test(test_resume_follows_the_music_past_the_move),
        cmocka_unit_test(test_camera_loss_pauses_the_song_and_resumes_it),
        cmocka_unit_test(test_correction_gives_way_when_the_music_moves_on),
        cmocka_unit_test(test_attract_then_doze_after_the_configured_quiet),
        cmocka_unit_test(test_worried_after_n_misses_then_back_to_correcting),
        cmocka_unit_test(test_song_end_cheers_then_idles),
        cmocka_unit_test(test_stop_returns_to_idle_from_every_state),
        cmocka_unit_test(test_player_away_shows_come_closer),
        cmocka_unit_test(test_too_close_shows_step_back),
        cmocka_unit_test(test_child_gone_briefly_pauses_then_resumes),
        cmocka_unit_test(test_child_gone_long_attracts_then_dozes),
        cmocka_unit_test(test_sync_speed_behind_ahead_and_bounded),
        cmocka_unit_test(test_music_tag_sets_the_moves_speed),
        cmocka_unit_test(test_sync_keeps_the_dance_on_a_skewed_music_clock),
        cmocka_unit_test(test_scripted_session_gives_the_same_log_every_time),
        cmocka_unit_test(test_gap_dances_its_groove_then_the_next_move),
        cmocka_unit_test(test_groove_joined_late_on_its_next_beat),
        cmocka_unit_test(test_groove_joined_late_leaves_room_for_the_bridge),
        cmocka_unit_test(test_groove_without_beats_is_not_begun_late),
        cmocka_unit_test(test_bad_groove_is_refused),
        cmocka_unit_test(test_groove_song_dances_its_span_then_cheers),
    };
    return cmocka_run_group_tests_name("coach", tests, NULL, NULL);
}

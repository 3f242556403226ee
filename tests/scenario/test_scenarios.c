/* Issue 4's acceptance, read from the event logs of the real cubdance
 * binary (run_scenario.sh, the fixtures of this test): the coach reacts to
 * a wrong verdict at once, corrects until right, resumes the same move,
 * attracts and dozes on time, STOP always returns to idle, START and a clap
 * wake it. (The dance following a music clock 5 % off is not asserted yet:
 * moves entered through a late bridge frame start seconds ahead of their
 * music; see the issue note.) */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "logread.h"

#define TICK_S (1.0 / 30)

static const char *out_dir, *demo_log;

static void load(const char *name, logread *log)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s.log", out_dir, name);
    if (logread_load(path, log) != 0) fail_msg("no event log %s (did its run fail?)", path);
}

static const char *field(const logread *log, int i, const char *key, char *buf, size_t size)
{
    const char *v = logread_field(&log->lines[i], key, buf, size);
    if (!v) fail_msg("line %d (%s %s %s) has no %s=", i + 1, log->lines[i].source,
                     log->lines[i].event, log->lines[i].rest, key);
    return v;
}

static double number(const logread *log, int i, const char *key)
{
    int ok;
    double v = logread_number(&log->lines[i], key, &ok);
    if (!ok) fail_msg("line %d has no number %s=", i + 1, key);
    return v;
}

/* Next `coach state` line at or after `from` whose to= is `to`; -1 if none. */
static int next_state(const logread *log, int from, const char *to)
{
    char buf[64];
    for (int i = logread_find(log, from, "coach", "state"); i >= 0;
         i = logread_find(log, i + 1, "coach", "state"))
        if (!strcmp(field(log, i, "to", buf, sizeof buf), to)) return i;
    return -1;
}

/* Next verdict line with this result at or after from; -1 if none. */
static int next_verdict(const logread *log, int from, const char *result)
{
    char buf[32];
    for (int i = logread_find(log, from, "judge", "verdict"); i >= 0;
         i = logread_find(log, i + 1, "judge", "verdict"))
        if (!strcmp(field(log, i, "result", buf, sizeof buf), result)) return i;
    return -1;
}

static int is_correcting(const char *to)
{
    return !strncmp(to, "head_shake@", 11) || !strncmp(to, "watch_me@", 9) ||
           !strncmp(to, "worried@", 8);
}

static void test_wrong_verdict_reaches_a_correcting_clip_within_6_ticks(void **s)
{
    logread log;
    load("correct", &log);
    int wrongs = 0;
    for (int w = next_verdict(&log, 0, "wrong"); w >= 0; w = next_verdict(&log, w + 1, "wrong")) {
        /* The first switch into a correcting clip after the verdict. */
        char to[64], via[16];
        int i = logread_find(&log, w, "bridge", "switch");
        while (i >= 0 && !is_correcting(field(&log, i, "to", to, sizeof to)))
            i = logread_find(&log, i + 1, "bridge", "switch");
        assert_true(i >= 0);
        double latency = log.lines[i].t_s - log.lines[w].t_s;
        double d = number(&log, i, "d");
        field(&log, i, "via", via, sizeof via);
        printf("scenario: wrong at %.3f s -> %s at %.3f s: %.0f ms (%.1f ticks), d=%.3f via=%s\n",
               log.lines[w].t_s, to, log.lines[i].t_s, latency * 1000, latency / TICK_S, d, via);
        assert_true(latency <= 6 * TICK_S + 1e-6);
        assert_true(d < 0.4 || !strcmp(via, "tween"));
        wrongs++;
    }
    assert_true(wrongs >= 2);
    logread_free(&log);
}

static void test_correction_repeats_until_right(void **s)
{
    logread log;
    load("correct", &log);
    int w = next_verdict(&log, 0, "wrong");
    int r = next_verdict(&log, w, "right");
    assert_true(w >= 0 && r > w);
    int demos = 0;
    char buf[32];
    for (int i = logread_find(&log, w, "coach", "request"); i >= 0 && i < r;
         i = logread_find(&log, i + 1, "coach", "request"))
        demos += !strcmp(field(&log, i, "reason", buf, sizeof buf), "demo");
    printf("scenario: %d slower demonstrations between the first wrong (%.1f s) and right "
           "(%.1f s)\n", demos, log.lines[w].t_s, log.lines[r].t_s);
    assert_true(demos >= 2);
    /* No return to the dance before the right verdict. */
    int back = next_state(&log, w, "dance");
    assert_true(back > r);
    logread_free(&log);
}

static void test_dance_resumes_in_the_same_move(void **s)
{
    logread log;
    load("correct", &log);
    int w = next_verdict(&log, 0, "wrong");
    int r = next_verdict(&log, w, "right");
    int back = next_state(&log, r, "dance");
    assert_true(w >= 0 && r > w && back >= r);
    char reason[32];
    assert_string_equal(field(&log, back, "reason", reason, sizeof reason), "right");
    int move = (int)number(&log, w, "move");
    printf("scenario: wrong in move %d, resumed in move %d\n", move,
           (int)number(&log, back, "move"));
    assert_int_equal((int)number(&log, back, "move"), move);
    logread_free(&log);
}

static void test_idle_attract_doze_on_time(void **s)
{
    logread log;
    load("quiet", &log);
    int a = next_state(&log, 0, "attract");
    int d = next_state(&log, 0, "doze");
    assert_true(a >= 0 && d > a);
    printf("scenario: attract at %.3f s (configured 3), doze at %.3f s (configured 6)\n",
           log.lines[a].t_s, log.lines[d].t_s);
    assert_true(fabs(log.lines[a].t_s - 3.0) <= TICK_S);
    assert_true(fabs(log.lines[d].t_s - 6.0) <= TICK_S);
    logread_free(&log);
}

static void test_stop_returns_to_idle_from_every_state(void **s)
{
    logread log;
    load("stop", &log);
    static const char *const expected_from[] = {"dance", "correct", "attract"};
    int stops = 0;
    char from[32], reason[32], name[16];
    for (int b = logread_find(&log, 0, "button", "down"); b >= 0;
         b = logread_find(&log, b + 1, "button", "down")) {
        if (strcmp(field(&log, b, "name", name, sizeof name), "stop") != 0) continue;
        int i = next_state(&log, b, "idle");
        assert_true(i >= 0);
        assert_true(log.lines[i].t_s - log.lines[b].t_s < 1e-6); /* at once */
        assert_string_equal(field(&log, i, "reason", reason, sizeof reason), "stop");
        field(&log, i, "from", from, sizeof from);
        printf("scenario: STOP at %.3f s: %s -> idle\n", log.lines[b].t_s, from);
        assert_true(stops < 3);
        assert_string_equal(from, expected_from[stops]);
        stops++;
    }
    assert_int_equal(stops, 3);
    logread_free(&log);
}

static void test_start_and_clap_wake_the_coach(void **s)
{
    logread log;
    load("wake", &log);
    char reason[16], from[16];
    int clap = next_state(&log, 0, "wake");
    assert_true(clap >= 0);
    assert_string_equal(field(&log, clap, "reason", reason, sizeof reason), "clap");
    int doze = next_state(&log, clap, "doze");
    assert_true(doze >= 0);
    int start = next_state(&log, doze, "wake");
    assert_true(start >= 0);
    assert_string_equal(field(&log, start, "reason", reason, sizeof reason), "start");
    assert_string_equal(field(&log, start, "from", from, sizeof from), "doze");
    printf("scenario: clap woke the coach at %.3f s; START woke it from doze at %.3f s\n",
           log.lines[clap].t_s, log.lines[start].t_s);
    logread_free(&log);
}

/* The demo's song gives exactly the committed log (docs/demo_twinkle.log):
 * the whole dance is deterministic, on every CPU. Regenerate it after a
 * deliberate change with the demo's options and --clock virtual (README). */
static void test_demo_song_log_is_the_committed_one(void **s)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/demo.log", out_dir);
    FILE *f = fopen(path, "r");
    if (!f) {
        print_message("SKIP: no demo run (the Skeltrack dump is absent)\n");
        skip();
    }
    fclose(f);
    logread got, want;
    load("demo", &got);
    assert_int_equal(logread_load(demo_log, &want), 0);
    for (int i = 0; i < got.count && i < want.count; i++) {
        const logread_line *a = &want.lines[i], *b = &got.lines[i];
        if (a->t_s != b->t_s || strcmp(a->source, b->source) || strcmp(a->event, b->event) ||
            strcmp(a->rest, b->rest))
            fail_msg("line %d differs:\n  committed: t=%.3f %s %s %s\n  got:       t=%.3f %s %s %s",
                     i + 1, a->t_s, a->source, a->event, a->rest, b->t_s, b->source, b->event,
                     b->rest);
    }
    assert_int_equal(got.count, want.count);
    printf("scenario: the demo song's %d log lines equal %s\n", got.count, demo_log);
    logread_free(&got);
    logread_free(&want);
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: %s OUT_DIR DEMO_LOG\n", argv[0]);
        return 2;
    }
    out_dir = argv[1];
    demo_log = argv[2];
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_wrong_verdict_reaches_a_correcting_clip_within_6_ticks),
        cmocka_unit_test(test_correction_repeats_until_right),
        cmocka_unit_test(test_dance_resumes_in_the_same_move),
        cmocka_unit_test(test_idle_attract_doze_on_time),
        cmocka_unit_test(test_stop_returns_to_idle_from_every_state),
        cmocka_unit_test(test_start_and_clap_wake_the_coach),
        cmocka_unit_test(test_demo_song_log_is_the_committed_one),
    };
    return cmocka_run_group_tests_name("scenarios", tests, NULL, NULL);
}

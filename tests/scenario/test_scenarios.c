/* Issue 4's acceptance, read from the event logs of the real cubdance
 * binary (run_scenario.sh, the fixtures of this test): the coach reacts to
 * a wrong verdict at once, corrects until right (the slower demonstration
 * watched, the attempt after it judged), resumes the same move,
 * attracts and dozes on time, STOP always returns to idle, START and a clap
 * wake it; with the music clock 5 % slow or fast the dance stays within two
 * frames of the music tags over every song. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "logread.h"

#define TICK_S (1.0 / 30)

static const char *out_dir, *demo_log, *groove_log;
static char sync_songs[256]; /* comma-separated: the songs run with a skewed music clock */

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

/* The coach watched verdict w (it came during the slower demonstration):
 * its `coach watched` line follows at the same time. */
static int watched(const logread *log, int w)
{
    int i = logread_find(log, w, "coach", "watched");
    return i >= 0 && log->lines[i].t_s == log->lines[w].t_s;
}

static int is_correcting(const char *to)
{
    return !strncmp(to, "head_shake@", 11) || !strncmp(to, "watch_me@", 9) ||
           !strncmp(to, "worried@", 8);
}

static void wrong_reaches_a_correcting_clip(const char *name)
{
    logread log;
    load(name, &log);
    int wrongs = 0;
    for (int w = next_verdict(&log, 0, "wrong"); w >= 0; w = next_verdict(&log, w + 1, "wrong")) {
        if (watched(&log, w)) continue; /* during a demonstration: no correction */
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

static void test_wrong_verdict_reaches_a_correcting_clip_within_6_ticks(void **s)
{
    wrong_reaches_a_correcting_clip("correct");
}

/* A request that only fills the time before a move (the idle clip, a
 * groove): the seal cannot groove (no arms), so it idles where the bear
 * dances the song's notes. */
static bool waiting_request(const logread *log, int i)
{
    char why[16];
    field(log, i, "reason", why, sizeof why);
    return !strcmp(why, "groove") || !strcmp(why, "intro") || !strcmp(why, "idle") ||
           !strcmp(why, "outro");
}

static int next_led(const logread *log, int from)
{
    int i = logread_find(log, from, "coach", "request");
    while (i >= 0 && waiting_request(log, i))
        i = logread_find(log, i + 1, "coach", "request");
    return i;
}

/* The same clip, reason, move and repetition; the time within 150 ms (out
 * of a groove clip the bear's route differs from the seal's out of idle). */
static void same_request(const logread *bear, int a, const logread *seal, int b)
{
    static const char *const keys[] = {"clip", "reason", "move", "rep"};
    char x[40], y[40];
    for (int k = 0; k < 4; k++) { /* a wake-up names no move */
        const char *u = logread_field(&bear->lines[a], keys[k], x, sizeof x);
        const char *v = logread_field(&seal->lines[b], keys[k], y, sizeof y);
        assert_string_equal(u ? u : "-", v ? v : "-");
    }
    assert_true(fabs(bear->lines[a].t_s - seal->lines[b].t_s) < 0.15);
}

/* The second coach (--coach seal, docs/evolve.md) leads the song as the
 * bear does: the same state changes at the same ticks, and the same moves,
 * repetitions and corrections asked for (the seal idles where the bear
 * grooves); a wrong verdict reaches a correcting clip as fast. */
static void test_the_seal_leads_the_song_as_the_bear(void **s)
{
    logread bear, seal;
    load("correct", &bear);
    load("seal", &seal);
    int a = logread_find(&bear, 0, "coach", "state"), b = logread_find(&seal, 0, "coach", "state");
    int n = 0;
    for (; a >= 0 && b >= 0; n++) {
        assert_true(fabs(bear.lines[a].t_s - seal.lines[b].t_s) < 1e-9);
        assert_string_equal(bear.lines[a].rest, seal.lines[b].rest);
        a = logread_find(&bear, a + 1, "coach", "state");
        b = logread_find(&seal, b + 1, "coach", "state");
    }
    assert_true(a < 0 && b < 0);
    printf("scenario: seal and bear: %d coach state lines alike\n", n);
    a = next_led(&bear, 0);
    b = next_led(&seal, 0);
    for (n = 0; a >= 0 && b >= 0; n++) {
        same_request(&bear, a, &seal, b);
        a = next_led(&bear, a + 1);
        b = next_led(&seal, b + 1);
    }
    assert_true(a < 0 && b < 0);
    printf("scenario: seal and bear: %d coach requests of moves and corrections alike\n", n);
    logread_free(&bear);
    logread_free(&seal);
    wrong_reaches_a_correcting_clip("seal");
}

/* The slower demonstration is watched, not judged: a wrong verdict while
 * it plays is logged as watched and starts no correction; when it ends the
 * dance resumes (reason=watched) and that attempt is judged: wrong, it is
 * corrected again, so the correction repeats until the child gets it. */
static void test_correction_repeats_until_right(void **s)
{
    logread log;
    load("correct", &log);
    int w = next_verdict(&log, 0, "wrong");
    int r = next_verdict(&log, w, "right");
    assert_true(w >= 0 && r > w);
    int demos = 0, corrections = 0, watched_wrong = 0;
    char buf[32];
    for (int i = logread_find(&log, w, "coach", "request"); i >= 0 && i < r;
         i = logread_find(&log, i + 1, "coach", "request")) {
        demos += !strcmp(field(&log, i, "reason", buf, sizeof buf), "demo");
        corrections += !strcmp(buf, "correct");
    }
    for (int i = next_verdict(&log, w, "wrong"); i >= 0 && i < r;
         i = next_verdict(&log, i + 1, "wrong"))
        watched_wrong += watched(&log, i);
    int attempt = next_state(&log, w, "dance");
    printf("scenario: first wrong %.1f s, %d correction(s), %d slower demonstration(s), %d wrong "
           "verdict(s) watched, the attempt at %.3f s, right %.1f s\n", log.lines[w].t_s,
           corrections, demos, watched_wrong, log.lines[attempt].t_s, log.lines[r].t_s);
    assert_true(demos >= 1 && watched_wrong >= 1 && corrections >= 2);
    assert_true(attempt > w && attempt < r);
    assert_string_equal(field(&log, attempt, "reason", buf, sizeof buf), "watched");
    /* The attempt's wrong verdict corrects again. */
    int again = next_state(&log, attempt, "correct");
    assert_true(again > attempt && again < r);
    assert_string_equal(field(&log, again, "reason", buf, sizeof buf), "wrong");
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
/* The whole song with the music clock off by `scale`: every repetition the
 * coach begins is reached on its music tag (the `coach sync` line the app's
 * tag gives, music_ms against tag_ms) within 2 frames, every move is
 * danced, and the song plays to its end. */
static double worst_sync_frames(const char *name, int *reps_out)
{
    logread log;
    load(name, &log);
    int moves = logread_count(&log, "music", "lead"), reps = 0;
    assert_true(moves >= 8);
    assert_true(logread_find(&log, 0, "music", "end") >= 0); /* the song ran out */
    double worst_frames = 0;
    char why[32];
    for (int i = logread_find(&log, 0, "coach", "request"); i >= 0;
         i = logread_find(&log, i + 1, "coach", "request")) {
        field(&log, i, "reason", why, sizeof why);
        if (strcmp(why, "move") && strcmp(why, "rep")) continue;
        const int move = (int)number(&log, i, "move"), rep = (int)number(&log, i, "rep");
        /* Its sync line: the next one, before anything else is asked. */
        int sync = logread_find(&log, i + 1, "coach", "sync");
        int next = logread_find(&log, i + 1, "coach", "request");
        if (next >= 0 && log.lines[next].t_s > log.lines[i].t_s && sync > next) sync = -1;
        if (sync < 0 && logread_find(&log, i + 1, "music", "end") >= 0 &&
            logread_find(&log, i + 1, "music", "end") < next)
            continue; /* the song ended while the route was under way */
        if (sync < 0) fail_msg("%s: move %d rep %d begun (line %d) but never synced", name, move,
                               rep, i + 1);
        assert_int_equal((int)number(&log, sync, "move"), move);
        assert_int_equal((int)number(&log, sync, "rep"), rep);
        double off = fabs(number(&log, sync, "music_ms") - number(&log, sync, "tag_ms"));
        double frames = off / (1000.0 * TICK_S);
        if (frames > worst_frames) worst_frames = frames;
        if (move == moves - 1) *reps_out = -1; /* the last move was reached */
        reps++;
    }
    if (*reps_out == -1) *reps_out = reps;
    else fail_msg("%s: the last move (%d) was never danced", name, moves - 1);
    logread_free(&log);
    return worst_frames;
}

static void test_dance_follows_a_music_clock_5_percent_off(void **s)
{
    int runs = 0;
    char songs[sizeof sync_songs];
    memcpy(songs, sync_songs, sizeof songs);
    for (char *song = strtok(songs, ","); song; song = strtok(NULL, ","))
        for (int fast = 0; fast <= 1; fast++) {
            char name[128];
            snprintf(name, sizeof name, "sync_%s_%s", song, fast ? "fast" : "slow");
            int reps = 0;
            double worst = worst_sync_frames(name, &reps);
            printf("scenario: %s: %d repetitions, dance vs music tags max %.2f frames (limit 2)\n",
                   name, reps, worst);
            assert_true(worst <= 2.0);
            runs++;
        }
    assert_true(runs >= 2);
}

/* The Kinect stops mid-song (make_gap_dump.sh: no frames from 7 s to 10 s
 * of the replay) and comes back: the coach pauses the song within a
 * second and a half of the last frame, with "can't see you" and the music
 * held; the first frame back resumes the music where it stood and the
 * dance. */
static void test_camera_loss_pauses_the_song_until_frames_return(void **s)
{
    char path[1024], buf[64];
    snprintf(path, sizeof path, "%s/camera.log", out_dir);
    FILE *f = fopen(path, "r");
    if (!f) {
        print_message("SKIP: no camera run (the Skeltrack dump is absent)\n");
        skip();
    }
    fclose(f);
    logread log;
    load("camera", &log);
    int last = -1; /* the last frame before the gap */
    for (int i = logread_find(&log, 0, "depth", "frame"); i >= 0 && log.lines[i].t_s < 7.0;
         i = logread_find(&log, i + 1, "depth", "frame"))
        last = i;
    assert_true(last >= 0);
    int lost = logread_find(&log, last, "watch", "camera");
    assert_true(lost >= 0);
    assert_string_equal(field(&log, lost, "state", buf, sizeof buf), "lost");
    const double t_lost = log.lines[lost].t_s, t_last = log.lines[last].t_s;
    assert_true(t_lost - t_last <= 1.5);
    int paused = next_state(&log, lost, "paused");
    assert_true(paused >= 0 && log.lines[paused].t_s == t_lost);
    int hint = logread_find(&log, paused, "coach", "hint");
    assert_true(hint >= 0);
    assert_string_equal(field(&log, hint, "show", buf, sizeof buf), "cant_see");
    int hold = logread_find(&log, paused, "music", "pause");
    assert_true(hold >= 0);
    int back = logread_find(&log, lost + 1, "watch", "camera");
    assert_true(back >= 0);
    assert_string_equal(field(&log, back, "state", buf, sizeof buf), "back");
    assert_true(log.lines[back].t_s >= 10.0 && log.lines[back].t_s < 10.1);
    int resumed = next_state(&log, back, "dance");
    assert_true(resumed >= 0 && log.lines[resumed].t_s == log.lines[back].t_s);
    int go_on = logread_find(&log, back, "music", "resume");
    assert_true(go_on >= 0);
    assert_true(number(&log, go_on, "music_ms") == number(&log, hold, "music_ms"));
    printf("scenario: camera gone after %.3f s: paused at %.3f s (%.0f ms after the last "
           "frame), music held at %.0f ms; frames back at %.3f s: dance resumed at once\n",
           t_last, t_lost, (t_lost - t_last) * 1000, number(&log, hold, "music_ms"),
           log.lines[back].t_s);
    logread_free(&log);
}

/* Garbage frames (make_garbage_dump.sh: 2-3 s no reading, 3-4 s zeros,
 * 4-5 s random values; a truncated frame file at 6.0 s and a missing one at
 * 6.5 s) in a replay: the box runs on, the tracker says no player from the
 * first garbage frame and finds the player again with the first good frame;
 * each bad file is one frame without readings: no player for that frame,
 * the player again at the next. */
static void test_garbage_frames_give_no_player_and_recover(void **s)
{
    char path[1024], buf[64], before[64] = "";
    snprintf(path, sizeof path, "%s/garbage.log", out_dir);
    FILE *f = fopen(path, "r");
    if (!f) {
        print_message("SKIP: no garbage run (the Skeltrack dump is absent)\n");
        skip();
    }
    fclose(f);
    logread log;
    load("garbage", &log);
    int none = -1, again = -1;
    for (int i = logread_find(&log, 0, "track", "status"); i >= 0;
         i = logread_find(&log, i + 1, "track", "status")) {
        field(&log, i, "to", buf, sizeof buf);
        if (log.lines[i].t_s < 2.0) snprintf(before, sizeof before, "%s", buf);
        if (none < 0 && !strcmp(buf, "no_player")) none = i;
        if (none >= 0 && again < 0 && strcmp(buf, "no_player")) again = i;
    }
    assert_true(before[0] && strcmp(before, "no_player"));
    assert_true(none >= 0 && again >= 0);
    assert_true(log.lines[none].t_s >= 2.0 && log.lines[none].t_s < 2.04);
    assert_true(log.lines[again].t_s >= 5.0 && log.lines[again].t_s < 5.04);
    assert_string_equal(field(&log, again, "to", buf, sizeof buf), before);
    const double bad_s[2] = {6.0, 6.5}; /* the truncated frame, the missing one */
    double lost_s[2], back_s[2];
    for (int b = 0; b < 2; b++) {
        int lost = -1, back = -1;
        for (int i = logread_find(&log, again, "track", "status"); i >= 0 && back < 0;
             i = logread_find(&log, i + 1, "track", "status")) {
            if (log.lines[i].t_s < bad_s[b]) continue;
            field(&log, i, "to", buf, sizeof buf);
            if (lost < 0 && !strcmp(buf, "no_player")) lost = i;
            else if (lost >= 0 && strcmp(buf, "no_player")) back = i;
        }
        assert_true(lost >= 0 && back >= 0);
        lost_s[b] = log.lines[lost].t_s;
        back_s[b] = log.lines[back].t_s;
        assert_true(lost_s[b] >= bad_s[b] && lost_s[b] < bad_s[b] + 0.01); /* that frame */
        assert_true(back_s[b] > lost_s[b] && back_s[b] < bad_s[b] + 0.05);  /* the next one */
        assert_string_equal(field(&log, back, "to", buf, sizeof buf), before);
    }
    assert_true(logread_find(&log, again, "app", "end") >= 0); /* ran to its end */
    printf("scenario: garbage frames 2-5 s: no player from %.3f s, the player (%s) again at "
           "%.3f s, the run went on to its end\n",
           log.lines[none].t_s, before, log.lines[again].t_s);
    printf("scenario: truncated frame at 6.0 s: no player at %.3f s, the player again at "
           "%.3f s; missing frame at 6.5 s: no player at %.3f s, the player again at %.3f s\n",
           lost_s[0], back_s[0], lost_s[1], back_s[1]);
    logread_free(&log);
}

/* The bear says what it shows (issue 19): every hint with words is said
 * at the tick it is shown, the voice pack lacks none of them (no `speech
 * missing`), and "Press START!" is the first thing said. */
/* The line of the state change to `to` at or after from, at t_s (within a
 * tick) and for why; fails otherwise. */
static int state_at(const logread *log, int from, const char *to, double t_s, const char *why)
{
    char buf[32];
    int i = next_state(log, from, to);
    if (i < 0) fail_msg("no coach state to=%s after line %d", to, from + 1);
    printf("scenario: away: to=%s reason=%s at %.3f s (expected %.1f)\n", to,
           field(log, i, "reason", buf, sizeof buf), log->lines[i].t_s, t_s);
    assert_true(fabs(log->lines[i].t_s - t_s) <= TICK_S);
    assert_string_equal(field(log, i, "reason", buf, sizeof buf), why);
    return i;
}

/* A child out of view mid-song: the song pauses 4 s later with "Where are
 * you?" and resumes when the child is back; gone for good, the verdicts
 * are set aside and the attract and doze come as when idle. */
static void test_child_who_walks_away_pauses_then_attracts(void **s)
{
    logread log;
    load("away", &log);
    int p = state_at(&log, 0, "paused", 10.0, "away");
    int hint = logread_find(&log, p, "coach", "hint");
    assert_true(hint >= 0 && log.lines[hint].t_s == log.lines[p].t_s);
    assert_non_null(strstr(log.lines[hint].rest, "show=where"));
    int music = logread_find(&log, p, "coach", "music");
    assert_non_null(strstr(log.lines[music].rest, "action=pause"));
    int back = state_at(&log, p, "dance", 11.0, "player");
    p = state_at(&log, back, "paused", 17.0, "away");
    int a = state_at(&log, p, "attract", 22.0, "quiet");
    state_at(&log, a, "doze", 26.0, "quiet");
    assert_true(next_state(&log, back, "correct") < 0); /* "wrong" while nobody is there */
    assert_true(logread_find(&log, back, "coach", "ignore") >= 0);
    logread_free(&log);
}

static void test_every_hint_shown_is_said_at_its_tick(void **s)
{
    (void)s;
    static const char *names[] = {"correct", "quiet", "stop", "wake", "away"};
    int said = 0;
    char show[32];
    for (size_t n = 0; n < sizeof names / sizeof *names; n++) {
        logread log;
        load(names[n], &log);
        int missing = logread_find(&log, 0, "speech", "missing");
        if (missing >= 0)
            fail_msg("%s line %d: no voice for %s", names[n], missing + 1, log.lines[missing].rest);
        int first = logread_find(&log, 0, "speech", "say");
        assert_true(first >= 0);
        assert_non_null(strstr(log.lines[first].rest, "text=\"Press START!\""));
        for (int i = logread_find(&log, 0, "coach", "hint"); i >= 0;
             i = logread_find(&log, i + 1, "coach", "hint")) {
            if (!strcmp(field(&log, i, "show", show, sizeof show), "none")) continue;
            int say = logread_find(&log, i + 1, "speech", "say");
            int next = logread_find(&log, i + 1, "coach", "hint");
            if (say < 0 || log.lines[say].t_s != log.lines[i].t_s || (next >= 0 && say > next))
                fail_msg("%s line %d: hint show=%s at %.3f s is not said at its tick", names[n],
                         i + 1, show, log.lines[i].t_s);
            said++;
        }
        logread_free(&log);
    }
    printf("scenario: %d hints shown and said at their tick, none missing from the voice\n", said);
}

/* Run `name` gave exactly the committed log `want_path`, line by line. */
static void expect_committed_log(const char *name, const char *want_path)
{
    logread got, want;
    load(name, &got);
    assert_int_equal(logread_load(want_path, &want), 0);
    for (int i = 0; i < got.count && i < want.count; i++) {
        const logread_line *a = &want.lines[i], *b = &got.lines[i];
        if (a->t_s != b->t_s || strcmp(a->source, b->source) || strcmp(a->event, b->event) ||
            strcmp(a->rest, b->rest))
            fail_msg("line %d differs:\n  committed: t=%.3f %s %s %s\n  got:       t=%.3f %s %s %s",
                     i + 1, a->t_s, a->source, a->event, a->rest, b->t_s, b->source, b->event,
                     b->rest);
    }
    assert_int_equal(got.count, want.count);
    printf("scenario: %s: its %d log lines equal %s\n", name, got.count, want_path);
    logread_free(&got);
    logread_free(&want);
}

/* The demo's run needs the Skeltrack dump: without it, the test skips. */
#define NEED_DEMO()                                                                                \
    do {                                                                                           \
        char path_[1024];                                                                          \
        snprintf(path_, sizeof path_, "%s/demo.log", out_dir);                                     \
        FILE *f_ = fopen(path_, "r");                                                              \
        if (!f_) {                                                                                 \
            print_message("SKIP: no demo run (the Skeltrack dump is absent)\n");                   \
            skip();                                                                                \
        }                                                                                          \
        fclose(f_);                                                                                \
    } while (0)

static void test_demo_song_log_is_the_committed_one(void **s)
{
    NEED_DEMO();
    expect_committed_log("demo", demo_log);
}

/* A foot taken above the flat clearing between log lines from and to. */
static int raised_steps(const logread *log, int from, int to)
{
    int raised = 0;
    for (int i = logread_find(log, from, "walk", "taken"); i >= 0 && i < to;
         i = logread_find(log, i + 1, "walk", "taken"))
        raised += number(log, i, "y") > 0;
    return raised;
}

/* The bear's walks in the demo (issue 24): in from among the trees (2 m
 * and more from its place), arriving before the dance begins (within the
 * wake) with its feet on the dance's (the farther ankle within 50 mm),
 * handed into the dance's first clip at the frame the bridge planner
 * gave, once the dance has begun; after the cheer, off from the frame the
 * planner gave for the walk's first pose, over the rolling floor (a foot
 * taken above the flat clearing). */
static void test_the_bear_walks_in_and_off_through_bridge_frames(void **s)
{
    NEED_DEMO();
    logread log;
    load("demo", &log);
    char clip[48], want[48], why[16];
    int in = logread_find(&log, 0, "walk", "start");
    assert_true(in >= 0);
    assert_string_equal(field(&log, in, "why", why, sizeof why), "in");
    double fx = number(&log, in, "from_x"), fz = number(&log, in, "from_z");
    assert_true(sqrt(fx * fx + fz * fz) >= 2000);
    int stop = logread_find(&log, in, "walk", "stop");
    assert_true(stop > in);
    int dance = next_state(&log, in, "dance");
    int first = logread_find(&log, dance, "coach", "request");
    int bridge = logread_find(&log, stop, "walk", "bridge");
    int enter = logread_find(&log, stop, "walk", "enter");
    assert_true(dance > 0 && first > 0 && bridge > 0 && enter > bridge);
    assert_true(log.lines[bridge].t_s >= log.lines[dance].t_s);
    assert_true(log.lines[stop].t_s < log.lines[dance].t_s);
    assert_true(number(&log, enter, "foot_mm") <= 50);
    /* it arrives in the dance's first pose, turned and with its arms (303
     * mm off before), and no joint turns faster arriving than any does
     * walking (the walk's own knees pass the clip's p99) */
    assert_true(number(&log, enter, "joint_mm") <= 50);
    assert_true(number(&log, enter, "blend_ms") <= 100);
    assert_true(number(&log, enter, "arrive_dpf") <= number(&log, enter, "walk_dpf"));
    field(&log, first, "clip", want, sizeof want);
    assert_string_equal(field(&log, enter, "clip", clip, sizeof clip), want);
    printf("scenario: demo: walk in from %.0f mm, stops %.3f s before the dance, into %s at "
           "frame %.0f (feet %.0f mm off, every joint within %.0f mm, faded %.0f ms; fastest "
           "joint turn arriving %.1f deg/frame, walking %.1f, the walk clip's p99 %.1f), %.3f s "
           "after START's wake\n", sqrt(fx * fx + fz * fz), log.lines[dance].t_s - log.lines[stop].t_s,
           clip, number(&log, enter, "frame"), number(&log, enter, "foot_mm"),
           number(&log, enter, "joint_mm"), number(&log, enter, "blend_ms"),
           number(&log, enter, "arrive_dpf"), number(&log, enter, "walk_dpf"),
           number(&log, enter, "p99_dpf"),
           log.lines[enter].t_s - log.lines[in].t_s);
    int cheered = next_state(&log, enter, "idle");
    int off = logread_find(&log, cheered, "walk", "bridge");
    int go = logread_find(&log, cheered, "walk", "start");
    assert_true(cheered > 0 && off > 0 && go > off);
    assert_string_equal(field(&log, go, "why", why, sizeof why), "off");
    assert_string_equal(field(&log, off, "dir", why, sizeof why), "off");
    int raised = raised_steps(&log, go, log.count);
    printf("scenario: demo: walk off, %d feet above the clearing\n", raised);
    assert_true(raised > 0);
    logread_free(&log);
}

/* START, STOP, and START again once the walk off has reached the trees:
 * the second walk in comes from as far out as one ever does (2.36 m; the
 * first from 2.12 m), at the 3x cap. It stops after the dance has begun
 * (the figure is printed), and still enters it in its first pose (every
 * joint within 50 mm). */
static void test_a_walk_in_after_a_walk_off_enters_the_dance_in_its_pose(void **s)
{
    logread log;
    load("return", &log);
    char why[16];
    int off = logread_find(&log, 0, "walk", "stop");
    while (off >= 0 && strcmp(field(&log, off, "why", why, sizeof why), "off"))
        off = logread_find(&log, off + 1, "walk", "stop");
    int in = logread_find(&log, off, "walk", "start");
    assert_true(off > 0 && in > off);
    assert_string_equal(field(&log, in, "why", why, sizeof why), "in");
    double fx = number(&log, in, "from_x"), fz = number(&log, in, "from_z");
    int stop = logread_find(&log, in, "walk", "stop");
    int dance = next_state(&log, in, "dance");
    int enter = logread_find(&log, stop, "walk", "enter");
    assert_true(stop > in && dance > in && enter > stop);
    printf("scenario: return: walk in from %.0f mm at rate %.3f, stops %.3f s after the dance "
           "began, enters %.3f s after it (every joint within %.0f mm, feet %.0f mm, faded %.0f "
           "ms; fastest joint turn arriving %.1f deg/frame)\n", sqrt(fx * fx + fz * fz),
           number(&log, in, "rate"), log.lines[stop].t_s - log.lines[dance].t_s,
           log.lines[enter].t_s - log.lines[dance].t_s, number(&log, enter, "joint_mm"),
           number(&log, enter, "foot_mm"), number(&log, enter, "blend_ms"),
           number(&log, enter, "arrive_dpf"));
    assert_true(sqrt(fx * fx + fz * fz) >= 2300);
    assert_true(number(&log, enter, "joint_mm") <= 50);
    /* Arriving while the coach has switched from wake_up into the groove,
     * it follows the pose the box shows (the switch's blend on), not the
     * clip's raw frame, which jumped (51.4 degrees a frame): no joint turns
     * faster than the first walk in's walking did. */
    int first = logread_find(&log, 0, "walk", "enter");
    assert_true(number(&log, enter, "arrive_dpf") <= number(&log, first, "walk_dpf"));
    logread_free(&log);
}

/* Is there a run's log by this name (the demo's needs the Skeltrack dump)? */
static bool have_log(const char *name)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s.log", out_dir, name);
    FILE *f = fopen(path, "r");
    if (f) fclose(f);
    return f != NULL;
}

/* No walk in turns a joint faster arriving (from its first end step)
 * than it turned walking before (walk_dpf; the walk's own knees pass the
 * clip's p99 at each strike). A walk in that arrives at once (stop's
 * second: its first step is an end step) has no walking frames, walk_dpf
 * 0: it is held to the fastest walking of the log's walk ins before it,
 * the same walk clip through the same walker. Before, the first end
 * strike's knee turned out of its hinge (the thighs and shins eased to
 * the end pose before the solve; docs/gait.md): return's second 39.1
 * against 36.9, wake's second 42.6 against 34.2. */
static void test_every_walk_in_arrives_no_faster_than_it_walks(void **s)
{
    static const char *const names[] = {"demo", "return", "wake", "stop"};
    int checked = 0;
    for (size_t n = 0; n < sizeof names / sizeof names[0]; n++) {
        if (!have_log(names[n])) continue; /* the demo without its dump */
        logread log;
        load(names[n], &log);
        double walked = 0;
        for (int i = logread_find(&log, 0, "walk", "enter"); i >= 0;
             i = logread_find(&log, i + 1, "walk", "enter"), checked++) {
            double arrive = number(&log, i, "arrive_dpf"), walk = number(&log, i, "walk_dpf");
            double limit = walk > 0 ? walk : walked;
            printf("scenario: %s: walk in at %.3f s arrives at %.1f deg/frame, walks at %.1f "
                   "(held to %.1f)\n", names[n], log.lines[i].t_s, arrive, walk, limit);
            assert_true(limit > 0);
            assert_true(arrive <= limit);
            if (walk > walked) walked = walk;
        }
        logread_free(&log);
    }
    assert_true(checked >= 5); /* return's, wake's and stop's two each at least */
}

/* The coach's requests for a groove clip whose name begins with prefix. */
static int groove_requests(const logread *log, const char *prefix)
{
    int n = 0;
    char why[16], clip[40];
    for (int i = logread_find(log, 0, "coach", "request"); i >= 0;
         i = logread_find(log, i + 1, "coach", "request"))
        if (!strcmp(field(log, i, "reason", why, sizeof why), "groove") &&
            !strncmp(field(log, i, "clip", clip, sizeof clip), prefix, strlen(prefix)))
            n++;
    return n;
}

/* A song with <free> bars: one groove clip per span no move teaches (the
 * intro, the <free>s), each logged with its frames and a hash of their
 * fuzzy memberships, then the dance; all of it the committed log, on every
 * CPU (issue 23). */
static void test_free_bars_groove_log_is_the_committed_one(void **s)
{
    logread log;
    load("groove_free", &log);
    int spans = logread_count(&log, "groove", "span");
    char kind[16];
    int free_spans = 0;
    for (int i = logread_find(&log, 0, "groove", "span"); i >= 0;
         i = logread_find(&log, i + 1, "groove", "span"))
        free_spans += !strcmp(field(&log, i, "kind", kind, sizeof kind), "free");
    printf("scenario: groove_free: %d groove spans, %d of them <free>\n", spans, free_spans);
    assert_int_equal(spans, 4);
    assert_int_equal(free_spans, 3);
    /* danced: the intro's and bar 14's (26 and 39 lie past the 40 s) */
    assert_int_equal(groove_requests(&log, "groove_free_"), 1);
    assert_int_equal(groove_requests(&log, "groove_intro_"), 1);
    assert_int_equal(groove_requests(&log, ""), 2);
    logread_free(&log);
    expect_committed_log("groove_free", groove_log);
}

/* Out of each groove (the intro, a gap, free bars) straight into the next
 * move, on its tag: the
 * coach's request after a groove's is the move's (no frame of the idle
 * clip between, as there was when the move's entry lead left out the wait
 * to the player's next frame), and its first music tag is on the music
 * within 2 ms (it was a frame, 33 ms, behind). */
static void groove_then_move_on_its_tag(const char *name)
{
    logread log;
    load(name, &log);
    char why[16], clip[40];
    int gaps = 0;
    for (int i = logread_find(&log, 0, "coach", "request"); i >= 0;
         i = logread_find(&log, i + 1, "coach", "request")) {
        if (strcmp(field(&log, i, "reason", why, sizeof why), "groove") ||
            !strncmp(field(&log, i, "clip", clip, sizeof clip), "groove_outro_", 13))
            continue; /* the outro's groove ends on the song's end: the cheer */
        int next = logread_find(&log, i + 1, "coach", "request");
        assert_true(next > i);
        assert_string_equal(field(&log, next, "reason", why, sizeof why), "move");
        int tag = logread_find(&log, next, "music", "tag");
        assert_true(tag > next);
        double late_ms = number(&log, tag, "music_ms") - number(&log, tag, "tag_ms");
        printf("scenario: %s: %s at %.3f s, then %s, its tag %.0f ms behind the music\n", name,
               clip, log.lines[i].t_s, field(&log, next, "clip", why, sizeof why), late_ms);
        assert_true(late_ms <= 2 && late_ms >= -2);
        gaps++;
    }
    assert_true(gaps >= 1);
    logread_free(&log);
}

static void test_a_gap_groove_hands_over_to_the_move_on_its_tag(void **s)
{
    groove_then_move_on_its_tag("groove_free");
    NEED_DEMO();
    groove_then_move_on_its_tag("demo");
}

/* Every groove the coach joins shows the music's frame: the `groove enter`
 * line's late_ms within a millisecond (rounding). The intro, asked for in
 * the call that starts the music, was a frame behind (late_ms=33): its
 * clock was taken as 0 where the music had already played to the player's
 * time. Returns how many grooves were entered. */
static int grooves_on_the_music(const char *name)
{
    logread log;
    load(name, &log);
    int n = 0;
    char clip[40];
    for (int i = logread_find(&log, 0, "groove", "enter"); i >= 0;
         i = logread_find(&log, i + 1, "groove", "enter"), n++) {
        const double late_ms = number(&log, i, "late_ms");
        printf("scenario: %s: %s entered at frame %.0f, %.0f ms behind the music\n", name,
               field(&log, i, "clip", clip, sizeof clip), number(&log, i, "frame"), late_ms);
        assert_true(late_ms >= -1 && late_ms <= 1);
    }
    logread_free(&log);
    return n;
}

static void test_every_groove_is_entered_on_the_music(void **s)
{
    assert_int_equal(grooves_on_the_music("groove_free"), 2); /* the intro, bar 14 */
    assert_int_equal(grooves_on_the_music("groove_song"), 1); /* the intro: the whole song */
    NEED_DEMO();
    assert_int_equal(grooves_on_the_music("demo"), 4); /* the intro, gaps 14, 26, the outro */
}

/* cubdance --bridge-speed's sum line for kind (the file the run wrote):
 * bridges, ticks with a joint over the library's p99, the fastest. */
static void speed_sums(const char *name, const char *kind, int *bridges, int *over_ticks,
                       double *max_mm_s)
{
    char path[1024], line[512], want[64];
    snprintf(path, sizeof path, "%s/%s.speed", out_dir, name);
    snprintf(want, sizeof want, "sum %s bridges=", kind);
    FILE *f = fopen(path, "r");
    if (!f) fail_msg("no %s (did its run fail?)", path);
    int found = 0, over_bridges = 0, ticks = 0;
    while (!found && fgets(line, sizeof line, f))
        found = !strncmp(line, want, strlen(want)) &&
                sscanf(line + strlen(want), "%d over_bridges=%d ticks=%d over_ticks=%d max_mm_s=%lf",
                       bridges, &over_bridges, &ticks, over_ticks, max_mm_s) == 5;
    fclose(f);
    if (!found) fail_msg("%s: no line '%s...'", path, want);
    printf("scenario: %s: %d bridges %s, %d ticks over the library's p99, fastest joint %.0f mm/s\n",
           name, *bridges, kind, *over_ticks, *max_mm_s);
}

/* Issue 23: no joint of what the box shows faster than the clip library's
 * p99 (1664 mm/s), measured on the bridges into the grooves too (the
 * switch's tick to its blend's end). Out of a groove the cheer's own
 * motion passes it (3016 mm/s unblended): that is the taught clip's. */
static void test_bridges_into_grooves_stay_under_the_library_p99(void **s)
{
    int bridges = 0, over = 0;
    double top = 0;
    speed_sums("groove_free", "into_groove", &bridges, &over, &top);
    assert_int_equal(bridges, 2);
    assert_int_equal(over, 0);
    speed_sums("groove_free", "out_of_groove", &bridges, &over, &top);
    assert_int_equal(bridges, 2);
    assert_int_equal(over, 0);
    NEED_DEMO();
    speed_sums("demo", "into_groove", &bridges, &over, &top);
    assert_int_equal(bridges, 4);
    assert_int_equal(over, 0);
}

/* A groove song (no <move>): the whole song one span, danced from the
 * music's start; no move is begun, nothing judged. */
static void test_groove_song_is_danced(void **s)
{
    logread log;
    load("groove_song", &log);
    assert_int_equal(logread_count(&log, "groove", "span"), 1);
    assert_int_equal(groove_requests(&log, "groove_intro_1"), 1);
    assert_int_equal(logread_count(&log, "judge", "window"), 0);
    int i = logread_find(&log, 0, "coach", "request");
    char why[16];
    for (; i >= 0; i = logread_find(&log, i + 1, "coach", "request"))
        assert_string_not_equal(field(&log, i, "reason", why, sizeof why), "move");
    logread_free(&log);
}

int main(int argc, char **argv)
{
    if (argc < 5) {
        fprintf(stderr, "usage: %s OUT_DIR DEMO_LOG SYNC_SONG[,SYNC_SONG...] GROOVE_LOG\n",
                argv[0]);
        return 2;
    }
    out_dir = argv[1];
    demo_log = argv[2];
    groove_log = argv[4];
    snprintf(sync_songs, sizeof sync_songs, "%s", argv[3]);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_wrong_verdict_reaches_a_correcting_clip_within_6_ticks),
        cmocka_unit_test(test_the_seal_leads_the_song_as_the_bear),
        cmocka_unit_test(test_correction_repeats_until_right),
        cmocka_unit_test(test_dance_resumes_in_the_same_move),
        cmocka_unit_test(test_idle_attract_doze_on_time),
        cmocka_unit_test(test_stop_returns_to_idle_from_every_state),
        cmocka_unit_test(test_start_and_clap_wake_the_coach),
        cmocka_unit_test(test_dance_follows_a_music_clock_5_percent_off),
        cmocka_unit_test(test_camera_loss_pauses_the_song_until_frames_return),
        cmocka_unit_test(test_garbage_frames_give_no_player_and_recover),
        cmocka_unit_test(test_child_who_walks_away_pauses_then_attracts),
        cmocka_unit_test(test_every_hint_shown_is_said_at_its_tick),
        cmocka_unit_test(test_the_bear_walks_in_and_off_through_bridge_frames),
        cmocka_unit_test(test_a_walk_in_after_a_walk_off_enters_the_dance_in_its_pose),
        cmocka_unit_test(test_every_walk_in_arrives_no_faster_than_it_walks),
        cmocka_unit_test(test_demo_song_log_is_the_committed_one),
        cmocka_unit_test(test_free_bars_groove_log_is_the_committed_one),
        cmocka_unit_test(test_groove_song_is_danced),
        cmocka_unit_test(test_a_gap_groove_hands_over_to_the_move_on_its_tag),
        cmocka_unit_test(test_every_groove_is_entered_on_the_music),
        cmocka_unit_test(test_bridges_into_grooves_stay_under_the_library_p99),
    };
    return cmocka_run_group_tests_name("scenarios", tests, NULL, NULL);
}

/* test_groove_motion — seed 001's motion (cub/groove.h): the Bézier
 * handles and their tangents at non-beat and beat keys, the timing curves,
 * the waist's and head's turns (fig. 10), the left hand, and the bear's
 * pose (arms by IK reach the wrist's target, the feet stay put). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cub/groove.h"

#define ONE CUB_Q16_ONE
#define Q(x) ((cub_q16)lround((x) * 65536.0))
#define MM(x, y, z) ((cub_vec3){Q(x), Q(y), Q(z)})

static double d(cub_q16 v)
{
    return v / 65536.0;
}

/* A note of a song at 120 beats a minute (the meter's grid: a beat every
 * 500 ms from 0). */
static cub_groove_note note(int64_t start_us, double beats, bool beat, int intensity)
{
    return (cub_groove_note){start_us,           0,     Q(beats), 60, (uint8_t)intensity, beat,
                             -(int32_t)(start_us % 500000), 500000};
}

static cub_groove_params set_a(void)
{
    cub_groove_params p;
    cub_groove_params_set('a', &p);
    return p;
}

/* Cross product of two 2-D vectors, mm^2: 0 when parallel. */
static double cross2(cub_groove_key a, cub_groove_key b)
{
    return d(a.x_mm) * d(b.y_mm) - d(a.y_mm) * d(b.x_mm);
}

/* sin of the angle between a and b. */
static double sin_between(cub_groove_key a, cub_groove_key b)
{
    return cross2(a, b) / (hypot(d(a.x_mm), d(a.y_mm)) * hypot(d(b.x_mm), d(b.y_mm)));
}

static cub_groove_key sub(cub_groove_key a, cub_groove_key b)
{
    return (cub_groove_key){a.x_mm - b.x_mm, a.y_mm - b.y_mm};
}

static void test_non_beat_tangents_follow_prev_to_next(void **state)
{
    (void)state;
    cub_groove_params p = set_a();
    cub_groove_note n[3] = {note(0, 1, false, 90), note(500000, 1, false, 90),
                            note(1000000, 1, false, 90)};
    cub_groove_key k[3] = {{0, 0}, {Q(100), Q(50)}, {Q(200), Q(20)}};
    cub_groove_handles h[3];
    assert_int_equal(cub_groove_handles_make(&p, n, 3, k, h), CUB_OK);
    cub_groove_key along = sub(k[2], k[0]);
    /* in and out on the line through key 1 along key 0 -> key 2, 100 apart */
    assert_true(fabs(cross2(sub(h[1].out_mm, k[1]), along)) < 0.5);
    assert_true(fabs(cross2(sub(k[1], h[1].in_mm), along)) < 0.5);
    cub_groove_key gap = sub(h[1].out_mm, h[1].in_mm);
    assert_true(fabs(hypot(d(gap.x_mm), d(gap.y_mm)) - 100) < 0.01);
    assert_true(gap.x_mm > 0); /* out toward the next key */
    /* The Bézier's tangents: into key 1 and out of it, one direction (a
     * step of 0.01: Q16 bases round to 1e-5 of a 100 mm handle). */
    const cub_groove_key into[4] = {k[0], h[0].out_mm, h[1].in_mm, k[1]};
    const cub_groove_key outof[4] = {k[1], h[1].out_mm, h[2].in_mm, k[2]};
    cub_groove_key end = cub_groove_bezier(into, ONE), start = cub_groove_bezier(outof, 0);
    assert_int_equal(end.x_mm, k[1].x_mm), assert_int_equal(start.y_mm, k[1].y_mm);
    cub_groove_key t_in = sub(end, cub_groove_bezier(into, ONE - Q(0.01)));
    cub_groove_key t_out = sub(cub_groove_bezier(outof, Q(0.01)), start);
    assert_true(fabs(sin_between(t_in, along)) < 0.01 && fabs(sin_between(t_out, along)) < 0.01);
    assert_true(t_in.x_mm > 0 && t_out.x_mm > 0);
}

static void test_non_beat_speed_is_continuous_through_a_key(void **state)
{
    (void)state;
    cub_groove_params p = set_a();
    /* a long note then a short one: the handles share smooth 3 : 1 (the
     * keys far enough apart that the chord cap leaves them) */
    cub_groove_note n[3] = {note(0, 1.5, false, 90), note(750000, 0.5, false, 90),
                            note(1000000, 1, false, 90)};
    cub_groove_key k[3] = {{0, 0}, {Q(200), Q(100)}, {Q(400), Q(40)}};
    cub_groove_handles h[3];
    cub_groove_handles_make(&p, n, 3, k, h);
    cub_groove_key in = sub(k[1], h[1].in_mm), out = sub(h[1].out_mm, k[1]);
    double li = hypot(d(in.x_mm), d(in.y_mm)), lo = hypot(d(out.x_mm), d(out.y_mm));
    assert_true(fabs(li - 75) < 0.01 && fabs(lo - 25) < 0.01);
    /* mm per second on either side of key 1: 3 |handle| / the path's time */
    assert_true(fabs(3 * li / 0.75 - 3 * lo / 0.25) < 0.1);
}

static void test_beat_handles_by_intensity_and_reflectance(void **state)
{
    (void)state;
    cub_groove_params p = set_a(); /* L1 85, L2 50, reflectance 1 */
    cub_groove_note n[2] = {note(0, 1, false, 90), note(500000, 1.5, true, 120)};
    cub_groove_key k[2] = {{Q(300), 0}, {Q(100), Q(10)}};
    cub_groove_handles h[2];
    cub_groove_handles_make(&p, n, 2, k, h);
    /* intensity 120: G1, L1 x 1.5 beats straight above the key */
    assert_int_equal(h[1].in_mm.x_mm, k[1].x_mm);
    assert_true(fabs(d(h[1].in_mm.y_mm) - (10 + 85 * 1.5)) < 0.01);
    /* reflectance 1: out is in mirrored about the key's vertical (here itself) */
    assert_int_equal(h[1].out_mm.x_mm, h[1].in_mm.x_mm);
    assert_int_equal(h[1].out_mm.y_mm, h[1].in_mm.y_mm);
    /* intensity 0: G2, L2 horizontally toward the previous key (+x here) */
    n[1].intensity = 0;
    cub_groove_handles_make(&p, n, 2, k, h);
    assert_true(fabs(d(h[1].in_mm.x_mm) - 150) < 0.01 && h[1].in_mm.y_mm == k[1].y_mm);
    assert_true(fabs(d(h[1].out_mm.x_mm) - 50) < 0.01); /* mirrored: 50 on the other side */
    /* intensity 60 halfway; reflectance 0.12 (set b) pulls out toward the key */
    cub_groove_params_set('b', &p);
    n[1].intensity = 60;
    cub_groove_handles_make(&p, n, 2, k, h);
    double in_dx = d(h[1].in_mm.x_mm) - 100, out_dx = d(h[1].out_mm.x_mm) - 100;
    assert_true(fabs(in_dx - 58 / 2.0) < 0.01);
    assert_true(fabs(out_dx + 0.12 * in_dx) < 0.01);
    /* the path into a beat key comes down from above at full intensity */
    n[1].intensity = 120;
    cub_groove_handles_make(&p, n, 2, k, h);
    const cub_groove_key into[4] = {k[0], h[0].out_mm, h[1].in_mm, k[1]};
    cub_groove_key before = cub_groove_bezier(into, ONE - Q(0.01));
    assert_true(before.y_mm > k[1].y_mm && abs(before.x_mm - k[1].x_mm) < Q(0.05));
}

static void test_pace_pulls_keys_and_handles_in(void **state)
{
    (void)state;
    cub_groove_params p = set_a(); /* pace 1200 mm/s */
    cub_groove_note n[3] = {note(0, 0.2, false, 90), note(100000, 2, true, 120),
                            note(1100000, 1, false, 90)};
    cub_groove_key k[3] = {{0, 0}, {Q(300), Q(400)}, {Q(310), Q(400)}};
    cub_groove_keys_pace(&p, n, 3, k);
    /* 500 mm in 0.1 s is too fast: 120 mm along the same line */
    assert_true(abs(k[1].x_mm - Q(72)) <= 2 && abs(k[1].y_mm - Q(96)) <= 2);
    assert_true(abs(k[2].x_mm - Q(310)) <= 2); /* 238 mm in 1 s: kept */
    cub_groove_handles h[3];
    cub_groove_handles_make(&p, n, 3, k, h);
    /* the beat key's handle in (L1 x 2 beats = 170 mm above) keeps within
     * 1200 x 0.1 / 3 = 40 mm; its handle out (a 1 s path) is not pulled */
    assert_true(abs(h[1].in_mm.y_mm - k[1].y_mm - Q(40)) <= 2);
    assert_true(abs(h[1].out_mm.y_mm - k[1].y_mm - Q(170)) <= 2);
    /* no times (equal starts): nothing moves */
    cub_groove_note same[2] = {note(0, 1, false, 90), note(0, 1, false, 90)};
    cub_groove_key far[2] = {{0, 0}, {Q(900), 0}};
    cub_groove_keys_pace(&p, same, 2, far);
    assert_int_equal(far[1].x_mm, Q(900));
}

static void test_bezier_midpoint(void **state)
{
    (void)state;
    const cub_groove_key pt[4] = {{0, 0}, {Q(10), Q(40)}, {Q(30), Q(40)}, {Q(40), 0}};
    cub_groove_key m = cub_groove_bezier(pt, ONE / 2);
    /* (p0 + 3 p1 + 3 p2 + p3) / 8 = (20, 30) */
    assert_true(abs(m.x_mm - Q(20)) <= 2 && abs(m.y_mm - Q(30)) <= 2);
}

static double slope(cub_groove_timing kind, double tau)
{
    double h = 0.002;
    return (d(cub_groove_timing_at(kind, Q(tau + h))) - d(cub_groove_timing_at(kind, Q(tau)))) / h;
}

static void test_timing_curves(void **state)
{
    (void)state;
    for (int kind = CUB_GROOVE_UNIFORM; kind <= CUB_GROOVE_ACCENT; kind++) {
        assert_int_equal(cub_groove_timing_at(kind, 0), 0);
        assert_int_equal(cub_groove_timing_at(kind, ONE), ONE);
        cub_q16 last = 0; /* monotone */
        for (int i = 1; i <= 200; i++) {
            cub_q16 u = cub_groove_timing_at(kind, ONE * i / 200);
            assert_true(u >= last);
            last = u;
        }
    }
    assert_int_equal(cub_groove_timing_at(CUB_GROOVE_UNIFORM, Q(0.3)), Q(0.3));
    /* ease-in: from rest, reaching the uniform speed at the end */
    assert_true(slope(CUB_GROOVE_EASE_IN, 0) < 0.05);
    assert_true(fabs(slope(CUB_GROOVE_EASE_IN, 0.995) - 1) < 0.05);
    /* accent: fast start dropping quickly, gentle, speeding up, then a
     * stop over the last 30 % (at rest on the next key) */
    double start = slope(CUB_GROOVE_ACCENT, 0), gentle = slope(CUB_GROOVE_ACCENT, 0.05),
           fast = slope(CUB_GROOVE_ACCENT, 0.69), end = slope(CUB_GROOVE_ACCENT, 0.997);
    assert_true(start > 2.2 && gentle < 0.8 && fast > 1.4 && end < 0.05);
    assert_true(slope(CUB_GROOVE_ACCENT, 0.1) < start && slope(CUB_GROOVE_ACCENT, 0.7) > gentle);
    /* the pieces join without a jump in speed */
    assert_true(fabs(slope(CUB_GROOVE_ACCENT, 0.048) - slope(CUB_GROOVE_ACCENT, 0.05)) < 0.1);
    assert_true(fabs(slope(CUB_GROOVE_ACCENT, 0.697) - slope(CUB_GROOVE_ACCENT, 0.701)) < 0.1);
    /* which curve a note's path takes */
    cub_groove_note n[3] = {note(0, 1, true, 90), note(1, 1, false, 90), note(2, 1, false, 90)};
    assert_int_equal(cub_groove_timing_of(n, 0), CUB_GROOVE_ACCENT);
    assert_int_equal(cub_groove_timing_of(n, 1), CUB_GROOVE_EASE_IN);
    assert_int_equal(cub_groove_timing_of(n, 2), CUB_GROOVE_UNIFORM);
}

static void test_turns_return_rotate_alternate(void **state)
{
    (void)state;
    /* 0: beat, 1 beat, full; 1, 2: short; 3: beat, 2 beats, half intensity */
    cub_groove_note n[4] = {note(0, 1, true, 120), note(500000, 0.5, false, 90),
                            note(750000, 0.5, false, 90), note(1000000, 2, true, 60)};
    cub_groove_turn t[4];
    int count = 0;
    assert_int_equal(cub_groove_turns(n, 4, 2000000, Q(7), t, &count), CUB_OK);
    assert_int_equal(count, 2);
    assert_true(t[0].start_us == 0 && t[0].turn_us == 0 && t[0].end_us == 500000);
    assert_true(t[0].from_deg == 0 && t[0].to_deg == Q(7));
    /* back to rest over notes 1 and 2 (the accumulated time), then -3.5 */
    assert_true(t[1].start_us == 500000 && t[1].turn_us == 1000000 && t[1].end_us == 2000000);
    assert_true(t[1].from_deg == Q(7) && abs(t[1].to_deg + Q(3.5)) <= 1);
    assert_int_equal(cub_groove_turn_at(t, count, 500000), Q(7));
    assert_int_equal(cub_groove_turn_at(t, count, 1000000), 0);
    assert_true(abs(cub_groove_turn_at(t, count, 5000000) + Q(3.5)) <= 1);
    cub_q16 mid = cub_groove_turn_at(t, count, 750000);
    assert_true(mid > 0 && mid < Q(7));
    /* the swing starts from rest on the beat (10 ms in: under 0.3 % of
     * the way, -3.5 deg), is fast after (over 80 % by half the note) and
     * settles at its end */
    assert_true(abs(cub_groove_turn_at(t, count, 1010000)) < Q(0.01));
    assert_true(cub_groove_turn_at(t, count, 1500000) < Q(-2.8));
    assert_true(cub_groove_turn_at(t, count, 1990000) - Q(-3.5) < Q(0.01));
}

/* The bear's skeleton (assets/bear/bear.xml). */
static cub_skeleton bear;
static void build_bear(void)
{
    static const struct {
        const char *name;
        int parent;
        double x, y, z;
    } j[] = {{"Hips", -1, 0, 285, 0},
             {"Spine", 0, 0, 115, 0},
             {"Chest", 1, 0, 125, 0},
             {"Neck", 2, 0, 85, 0},
             {"Head", 3, 0, 55, 0},
             {"Head_end", 4, 0, 270, 0},
             {"LeftShoulder", 2, 45, 55, 0},
             {"LeftArm", 6, 80, 0, 0},
             {"LeftForeArm", 7, 150, 0, 0},
             {"LeftHand", 8, 135, 0, 0},
             {"RightShoulder", 2, -45, 55, 0},
             {"RightArm", 10, -80, 0, 0},
             {"RightForeArm", 11, -150, 0, 0},
             {"RightHand", 12, -135, 0, 0},
             {"LeftUpLeg", 0, 85, -20, 0},
             {"LeftLeg", 14, 0, -125, 0},
             {"LeftFoot", 15, 0, -115, 0}};
    cub_motion_skeleton_reset(&bear);
    for (size_t i = 0; i < sizeof j / sizeof j[0]; i++) {
        int at;
        cub_motion_skeleton_add(&bear, j[i].name, j[i].parent, MM(j[i].x, j[i].y, j[i].z), &at);
    }
}

static double dist(cub_vec3 a, cub_vec3 b)
{
    return sqrt(pow(d(a.x - b.x), 2) + pow(d(a.y - b.y), 2) + pow(d(a.z - b.z), 2));
}

static void test_pose_reaches_keys_and_keeps_feet(void **state)
{
    (void)state;
    build_bear();
    cub_groove_rig rig;
    cub_skeleton empty = {0};
    assert_int_equal(cub_groove_rig_bind(&empty, &rig), CUB_ERR_FORMAT);
    assert_int_equal(cub_groove_rig_bind(&bear, &rig), CUB_OK);
    cub_groove_note n[3] = {note(0, 1, true, 100), note(500000, 1, false, 80),
                            note(1000000, 2, true, 120)};
    cub_groove_key k[3] = {{0, 0}, {Q(130), Q(70)}, {Q(260), Q(-40)}};
    cub_groove_handles h[3];
    cub_groove_turn waist[3], head[3];
    cub_groove_plan plan = {set_a(), n, 3, k, h, waist, head, 0, 0, 2000000};
    cub_groove_handles_make(&plan.params, n, 3, k, h);
    cub_groove_turns(n, 3, plan.end_us, Q(7), waist, &plan.waist_count);
    cub_groove_turns(n, 3, plan.end_us, Q(10), head, &plan.head_count);
    /* at a beat key's time the wrist is on it (a non-beat key is passed
     * on the way, test_non_beat_key_passed_at_speed) */
    cub_groove_key w = cub_groove_wrist_at(&plan, 1000000);
    assert_true(w.x_mm == k[2].x_mm && w.y_mm == k[2].y_mm);
    static cub_pose pose, rest;
    cub_vec3 world[CUB_MOTION_MAX_JOINTS], rest_w[CUB_MOTION_MAX_JOINTS];
    cub_quat rot[CUB_MOTION_MAX_JOINTS];
    cub_motion_pose_rest(&bear, &rest);
    rest.root_mm = bear.joints[0].offset_mm;
    cub_motion_forward(&bear, &rest, rest_w, NULL);
    for (int64_t t = 0; t <= 2000000; t += 250000) {
        assert_int_equal(cub_groove_pose_at(&plan, &rig, t, &pose), CUB_OK);
        cub_motion_forward(&bear, &pose, world, rot);
        assert_true(dist(world[16], rest_w[16]) == 0); /* a foot, planted */
        /* the right wrist: its key about its home in the chest's frame */
        cub_groove_key at = cub_groove_wrist_at(&plan, cub_groove_clock(&plan, t));
        cub_vec3 local = {Q(-210) + (cub_q16)((int64_t)at.x_mm * 2 / 5),
                          Q(-40) + (cub_q16)((int64_t)at.y_mm * 2 / 5), Q(160)};
        cub_vec3 want = cub_fx_vec3_add(world[2], cub_fx_quat_rotate(rot[2], local));
        assert_true(dist(world[13], want) < 0.5);
        assert_true(world[12].y < world[11].y); /* the elbow hangs */
    }
}

/* Off-beat keys 40 mm apart, set a's smooth 100 mm: each handle is kept
 * within half its path's chord (no loop); a beat key keeps its handles. */
static void test_non_beat_handles_within_half_the_chord(void **state)
{
    (void)state;
    cub_groove_params p = set_a();
    cub_groove_note n[4] = {note(0, 0.25, false, 90), note(200000, 0.25, false, 90),
                            note(400000, 0.25, false, 90), note(600000, 1, true, 120)};
    cub_groove_key k[4] = {{0, 0}, {Q(40), 0}, {Q(80), 0}, {Q(200), 0}};
    cub_groove_handles h[4];
    cub_groove_handles_make(&p, n, 4, k, h);
    assert_true(abs(h[1].in_mm.x_mm - Q(20)) < Q(0.1) && abs(h[1].out_mm.x_mm - Q(60)) < Q(0.1));
    /* both scaled by the shorter side's 20 / 50: the time shares kept */
    assert_true(abs(h[2].out_mm.x_mm - Q(100)) < Q(0.1));
    /* the beat key keeps its handle in (G1 above it, to the pace: 80 mm), not half the chord */
    assert_true(h[3].in_mm.y_mm > Q(79));
}

static void test_stretch_runs_beat_to_beat(void **state)
{
    (void)state;
    cub_groove_note n[40];
    for (int i = 0; i < 40; i++) /* beats on 0, 4, 8; none from 9 on */
        n[i] = note(i * 100000, 0.25, i < 9 && i % 4 == 0, 90);
    int a, b;
    cub_groove_stretch_of(n, 40, 1, &a, &b);
    assert_true(a == 0 && b == 4);
    cub_groove_stretch_of(n, 40, 4, &a, &b);
    assert_true(a == 4 && b == 8);
    /* note 16 has a beat (8) among the 15 before it: no break there; note
     * 32 has none: a stretch with no beat breaks at every 16th note */
    cub_groove_stretch_of(n, 40, 10, &a, &b);
    assert_true(a == 8 && b == 32);
    cub_groove_stretch_of(n, 40, 37, &a, &b); /* the last stretch ends on the last key */
    assert_true(a == 32 && b == 39);
}

static void test_path_u_inverts_arc_length(void **state)
{
    (void)state;
    /* a straight line with its handles at thirds: arc length = u x 90 */
    const cub_groove_key line[4] = {{0, 0}, {Q(30), 0}, {Q(60), 0}, {Q(90), 0}};
    assert_true(fabs(d(cub_groove_path_length(line)) - 90) < 0.01);
    assert_true(abs(cub_groove_path_u(line, Q(45)) - ONE / 2) <= 4);
    /* a curve with long handles: the point at u(s) is s along, monotone */
    const cub_groove_key pt[4] = {{0, 0}, {Q(0), Q(80)}, {Q(100), Q(80)}, {Q(100), 0}};
    double len = d(cub_groove_path_length(pt)), along = 0, prev_u = 0;
    cub_groove_key last = pt[0];
    for (int i = 1; i <= 20; i++) {
        cub_q16 u = cub_groove_path_u(pt, Q(len * i / 20));
        cub_groove_key at = cub_groove_bezier(pt, u);
        along += hypot(d(at.x_mm - last.x_mm), d(at.y_mm - last.y_mm));
        last = at;
        assert_true(d(u) > prev_u);
        prev_u = d(u);
        assert_true(fabs(along - len * i / 20) < len * 0.01 + 0.5); /* chords under arcs */
    }
    assert_true(prev_u > 0.999);
}

/* A beat, two off-beat notes, a beat: the wrist passes the off-beat keys
 * without slowing; its only speed minima are the accent's, on the beats
 * (and its drop, within the first 5 % of the stretch). */
static void test_non_beat_key_passed_at_speed(void **state)
{
    (void)state;
    cub_groove_note n[4] = {note(0, 1, true, 100), note(300000, 0.5, false, 80),
                            note(450000, 0.5, false, 80), note(600000, 1, true, 100)};
    /* the wrist rises to the off-beat keys and comes down on the beat key
     * (its handle in above it): no reversal on the way */
    cub_groove_key k[4] = {{0, 0}, {Q(150), Q(60)}, {Q(260), Q(80)}, {Q(360), Q(20)}};
    cub_groove_handles h[4];
    cub_groove_plan plan = {set_a(), n, 4, k, h, NULL, NULL, 0, 0, 1200000};
    cub_groove_handles_make(&plan.params, n, 4, k, h);
    double v[37], near1 = 1e9;
    cub_groove_key prev = cub_groove_wrist_at(&plan, 0);
    for (int t = 1; t <= 36; t++) { /* frames at 60 fps over the stretch */
        cub_groove_key at = cub_groove_wrist_at(&plan, t * 1000000 / 60);
        v[t] = hypot(d(at.x_mm - prev.x_mm), d(at.y_mm - prev.y_mm));
        double to1 = hypot(d(at.x_mm - k[1].x_mm), d(at.y_mm - k[1].y_mm));
        near1 = to1 < near1 ? to1 : near1;
        prev = at;
    }
    assert_true(near1 < 5); /* the off-beat key is on the way (frames 8 mm apart) */
    int minima = 0;
    for (int t = 4; t < 36; t++) /* after the drop (5 % = 30 ms), to the stop */
        minima += v[t] < v[t - 1] && v[t] < v[t + 1];
    assert_int_equal(minima, 0);
    assert_true(v[36] < v[18] / 3); /* it stops on the beat */
}

/* The wrist's fastest along its path (music time, 1 ms steps), mm/s. */
static double wrist_peak_mm_s(const cub_groove_plan *plan, int64_t end_us)
{
    double most = 0;
    cub_groove_key prev = cub_groove_wrist_at(plan, 0);
    for (int64_t t = 1000; t <= end_us; t += 1000) {
        cub_groove_key at = cub_groove_wrist_at(plan, t);
        double v = hypot(d(at.x_mm - prev.x_mm), d(at.y_mm - prev.y_mm)) * 1000;
        most = v > most ? v : most;
        prev = at;
    }
    return most;
}

/* The speed bound: sixteenth notes at 120 a minute whose keys zig-zag
 * 28 cm apart ask the wrist for several times CUB_GROOVE_PEAK_MM_S; after
 * cub_groove_stretch_limit it never runs faster, and each stretch keeps
 * its first key (drawn in about it). */
static void test_stretch_limit_bounds_the_wrist(void **state)
{
    (void)state;
    enum { N = 9 };
    cub_groove_note n[N];
    cub_groove_key k[N];
    cub_groove_handles h[N];
    for (int i = 0; i < N; i++) {
        n[i] = note(i * 125000, 0.25, i % 4 == 0, 100);
        k[i] = (cub_groove_key){Q(150 * i), Q(i % 2 ? 120 : -120)};
    }
    cub_groove_plan plan = {set_a(), n, N, k, h, NULL, NULL, 0, 0, N * 125000};
    assert_int_equal(cub_groove_handles_make(&plan.params, n, N, k, h), CUB_OK);
    double before = wrist_peak_mm_s(&plan, (N - 1) * 125000);
    cub_groove_stretch_limit(&plan.params, n, N, k, h);
    double after = wrist_peak_mm_s(&plan, (N - 1) * 125000);
    double bound = d(CUB_GROOVE_PEAK_MM_S);
    printf("wrist peak %.0f -> %.0f mm/s (bound %.0f)\n", before, after, bound);
    assert_true(before > 2 * bound);
    assert_true(after <= bound * 1.01);
    assert_true(after > bound / 4); /* drawn in, not stopped */
    assert_true(k[0].x_mm == 0 && k[0].y_mm == Q(-120));
}

/* The speed bound on the waist: a full-intensity beat of one beat (0.5 s)
 * asked for 90 degrees turns only as far as 90 deg/s at the swing's
 * steepest (2.24 x its mean) allows, about 20; the angle never changes
 * faster than that. */
static void test_turn_capped_by_its_time(void **state)
{
    (void)state;
    cub_groove_note n[2] = {note(0, 1, true, 120), note(500000, 4, false, 90)};
    cub_groove_turn t[2];
    int count = 0;
    assert_int_equal(cub_groove_turns(n, 2, 2500000, Q(90), t, &count), CUB_OK);
    assert_int_equal(count, 1);
    double to = d(t[0].to_deg), most_v = 0;
    for (int64_t us = 1000; us <= 500000; us += 1000) {
        cub_q16 a = cub_groove_turn_at(t, count, us - 1000), b = cub_groove_turn_at(t, count, us);
        double v = fabs(d(b - a));
        most_v = v * 1000 > most_v ? v * 1000 : most_v;
    }
    printf("turn asked 90 deg, made %.2f deg, fastest %.1f deg/s\n", to, most_v);
    assert_true(to > 19.5 && to < 20.2);
    assert_true(most_v <= 90 * 1.02);
}

/* The speed bound on the left hand: a staccato 32nd note (31 ms) lifts
 * the hand less than its 60 mm, as high as the bound lets it in that time,
 * and the hand never moves faster than CUB_GROOVE_PEAK_MM_S. */
static void test_staccato_lift_capped_by_its_time(void **state)
{
    (void)state;
    cub_groove_note n[3] = {note(0, 1, true, 100), note(500000, 0.0625, false, 100),
                            note(531250, 0.0625, false, 0)};
    n[2].pitch = CUB_GROOVE_REST;
    cub_groove_plan plan = {set_a(), n, 3, NULL, NULL, NULL, NULL, 0, 0, 562500};
    double top = 0, most_v = 0;
    cub_groove_key prev = cub_groove_left_at(&plan, 490000);
    for (int64_t us = 490500; us <= 562500; us += 500) {
        cub_groove_key at = cub_groove_left_at(&plan, us);
        double v = hypot(d(at.x_mm - prev.x_mm), d(at.y_mm - prev.y_mm)) * 2000;
        most_v = v > most_v ? v : most_v;
        top = d(at.y_mm) > top ? d(at.y_mm) : top;
        prev = at;
    }
    printf("staccato lift %.1f mm (60 asked), fastest %.0f mm/s\n", top, most_v);
    assert_true(top > 25 && top < 40);
    assert_true(most_v <= d(CUB_GROOVE_PEAK_MM_S) * 1.03);
}

/* The beat stop: every beat of the grid, the three inside a four-beat
 * note too, keeps its time; the clock stands still on it, runs faster
 * between, never backwards; with no stop it is the music's own time. */
static void stop_keeps_beats(cub_groove_plan *plan, int k)
{
    plan->params.stop_power = k;
    for (int64_t b = 0; b <= 2500000; b += 500000) {
        assert_true(cub_groove_clock(plan, b) == b);
        /* 10 ms either side of the beat: the clock moves under 10 % of that */
        assert_true(cub_groove_clock(plan, b + 10000) - b < 1000);
        if (b > 0) assert_true(b - cub_groove_clock(plan, b - 10000) < 1000);
    }
    for (int64_t t = 1, last = 0; t <= 2500000; t += 997) {
        int64_t c = cub_groove_clock(plan, t);
        assert_true(c >= last);
        last = c;
    }
}

static void test_beat_stop_on_every_beat(void **state)
{
    (void)state;
    cub_groove_note n[2] = {note(0, 4, true, 100), note(2000000, 1, true, 100)};
    cub_groove_plan plan = {set_a(), n, 2, NULL, NULL, NULL, NULL, 0, 0, 2500000};
    plan.params.stop_before = plan.params.stop_after = Q(0.2);
    for (int k = 1; k <= 3; k++)
        stop_keeps_beats(&plan, k);
    /* k = 3 (set a's): mid-beat the level, 1 / (1 - (0.2 + 0.2) x 3 / 4) = 1.43 */
    int64_t mid = cub_groove_clock(&plan, 760000) - cub_groove_clock(&plan, 740000);
    assert_true(mid >= 28500 && mid <= 28650);
    plan.params = set_a(); /* 0.1 before, 0.2 after */
    stop_keeps_beats(&plan, 3);
    plan.params.stop_before = plan.params.stop_after = 0;
    assert_true(cub_groove_clock(&plan, 740000) == 740000);
    n[0].beat_us = 0; /* no grid: no stop */
    plan.params.stop_before = Q(0.2);
    assert_true(cub_groove_clock(&plan, 740000) == 740000);
}

/* The clock's speed at t, over 20 ms. */
static double clock_speed(const cub_groove_plan *plan, int64_t t)
{
    return (cub_groove_clock(plan, t + 10000) - cub_groove_clock(plan, t - 10000)) / 20000.0;
}

/* A note on a 1.5 s beat grid (the grid starts at 0). */
static cub_groove_note slow_note(int64_t start_us, bool beat)
{
    cub_groove_note n = note(start_us, 1, beat, 100);
    n.beat_us = 1500000, n.grid_us = -(int32_t)(start_us % 1500000);
    return n;
}

/* Round 8's cruise cap: in a 1.5 s beat with at most one key inside, the
 * level would last 1.05 s; the ramps take the whole beat instead (1/3
 * before, 2/3 after, straight): the speed rises to 2 at 1 s and falls to 0
 * on the next beat, no level; the beats keep their times. A 1.5 s beat
 * with three keys inside (a reel's eighths) and a 0.5 s beat keep their
 * level, 1 / (1 - 0.3 x 3 / 4) = 1.29. */
static void test_slow_flat_beat_has_no_cruise(void **state)
{
    (void)state;
    cub_groove_note n[3] = {slow_note(0, true), slow_note(750000, false), slow_note(6000000, true)};
    cub_groove_plan plan = {set_a(), n, 3, NULL, NULL, NULL, NULL, 0, 0, 7500000};
    for (int64_t b = 0; b <= 6000000; b += 1500000)
        assert_true(cub_groove_clock(&plan, b) == b);
    const double t_ms[5] = {250, 500, 1000, 1250, 1400}, want[5] = {0.5, 1, 2, 1, 0.4};
    for (int i = 0; i < 5; i++) {
        double v = clock_speed(&plan, (int64_t)(t_ms[i] * 1000));
        printf("1.5 s flat beat: clock speed %.3f at %.0f ms (%.2f)\n", v, t_ms[i], want[i]);
        assert_true(fabs(v - want[i]) < 0.03);
    }
    assert_true(fabs(clock_speed(&plan, 3750000) - 1.5) < 0.03); /* inside the long note */
    cub_groove_note busy[5] = {slow_note(0, true), slow_note(375000, false), slow_note(750000, false),
                               slow_note(1125000, false), slow_note(1500000, true)};
    plan.notes = busy, plan.n = 5;
    printf("1.5 s beat, 3 keys inside: clock speed %.3f at 750 ms\n", clock_speed(&plan, 750000));
    assert_true(fabs(clock_speed(&plan, 750000) - 1 / (1 - 0.3 * 3 / 4.0)) < 0.01);
    cub_groove_note fast[2] = {note(0, 4, true, 100), note(2000000, 1, true, 100)};
    plan.notes = fast, plan.n = 2;
    assert_true(fabs(clock_speed(&plan, 250000) - 1 / (1 - 0.3 * 3 / 4.0)) < 0.01);
}

/* The speed bound with the cap: keys 1.2 m apart on slow flat beats; after
 * cub_groove_stretch_limit the wrist, on the clock (the hump peaks at
 * twice the mean), never runs faster than CUB_GROOVE_PEAK_MM_S. */
static void test_slow_flat_beat_bounded(void **state)
{
    (void)state;
    cub_groove_note n[4] = {slow_note(0, true), slow_note(1500000, true), slow_note(3000000, true),
                            slow_note(4500000, true)};
    cub_groove_key k[4] = {{0, 0}, {Q(1200), Q(100)}, {0, Q(-100)}, {Q(1200), 0}};
    cub_groove_handles h[4];
    cub_groove_plan plan = {set_a(), n, 4, k, h, NULL, NULL, 0, 0, 6000000};
    assert_int_equal(cub_groove_handles_make(&plan.params, n, 4, k, h), CUB_OK);
    cub_groove_stretch_limit(&plan.params, n, 4, k, h);
    double most = 0;
    cub_groove_key prev = cub_groove_wrist_at(&plan, 0);
    for (int64_t t = 1000; t <= 4500000; t += 1000) {
        cub_groove_key at = cub_groove_wrist_at(&plan, cub_groove_clock(&plan, t));
        double v = hypot(d(at.x_mm - prev.x_mm), d(at.y_mm - prev.y_mm)) * 1000;
        most = v > most ? v : most;
        prev = at;
    }
    double bound = d(CUB_GROOVE_PEAK_MM_S);
    printf("slow flat beats: wrist peak on the clock %.0f mm/s (bound %.0f)\n", most, bound);
    assert_true(most <= bound * 1.01);
    assert_true(most > bound / 4);
}

/* The poses of a small song at 300 times, hashed (FNV-1a over every joint's
 * rotation): the pinned value must come out on x86-64 and aarch64 alike
 * (the whole path is integer). */
#define POSE_HASH 0x21f5229d441d96b0ull

static void test_poses_are_bit_identical_across_cpus(void **state)
{
    (void)state;
    build_bear();
    cub_groove_rig rig;
    cub_groove_rig_bind(&bear, &rig);
    cub_groove_note n[6] = {note(0, 1, true, 100),        note(500000, 0.5, false, 70),
                            note(750000, 0.5, false, 90), note(1000000, 2, true, 120),
                            note(2000000, 0.5, true, 40), note(2250000, 1.5, false, 60)};
    cub_groove_key k[6] = {{0, 0},          {Q(90), Q(40)},   {Q(170), Q(-30)},
                           {Q(260), Q(70)}, {Q(200), Q(-90)}, {Q(120), Q(10)}};
    cub_groove_handles h[6];
    cub_groove_turn waist[6], head[6];
    cub_groove_plan plan = {set_a(), n, 6, k, h, waist, head, 0, 0, 3000000};
    cub_groove_keys_pace(&plan.params, n, 6, k);
    cub_groove_handles_make(&plan.params, n, 6, k, h);
    cub_groove_turns(n, 6, plan.end_us, Q(7), waist, &plan.waist_count);
    cub_groove_turns(n, 6, plan.end_us, Q(10), head, &plan.head_count);
    static cub_pose pose;
    uint64_t hash = 0xcbf29ce484222325u;
    for (int f = 0; f < 300; f++) {
        assert_int_equal(cub_groove_pose_at(&plan, &rig, (int64_t)f * 10007, &pose), CUB_OK);
        for (int j = 0; j < bear.joint_count; j++) {
            const int32_t c[4] = {pose.rot[j].w, pose.rot[j].x, pose.rot[j].y, pose.rot[j].z};
            for (int i = 0; i < 4; i++)
                for (int b = 0; b < 32; b += 8)
                    hash = (hash ^ (uint8_t)((uint32_t)c[i] >> b)) * 0x100000001b3u;
        }
    }
    print_message("groove: pose hash 0x%016llx\n", (unsigned long long)hash);
    assert_true(hash == POSE_HASH);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_non_beat_tangents_follow_prev_to_next),
        cmocka_unit_test(test_non_beat_speed_is_continuous_through_a_key),
        cmocka_unit_test(test_beat_handles_by_intensity_and_reflectance),
        cmocka_unit_test(test_pace_pulls_keys_and_handles_in),
        cmocka_unit_test(test_bezier_midpoint),
        cmocka_unit_test(test_timing_curves),
        cmocka_unit_test(test_turns_return_rotate_alternate),
        cmocka_unit_test(test_pose_reaches_keys_and_keeps_feet),
        cmocka_unit_test(test_non_beat_handles_within_half_the_chord),
        cmocka_unit_test(test_stretch_runs_beat_to_beat),
        cmocka_unit_test(test_path_u_inverts_arc_length),
        cmocka_unit_test(test_non_beat_key_passed_at_speed),
        cmocka_unit_test(test_stretch_limit_bounds_the_wrist),
        cmocka_unit_test(test_turn_capped_by_its_time),
        cmocka_unit_test(test_staccato_lift_capped_by_its_time),
        cmocka_unit_test(test_beat_stop_on_every_beat),
        cmocka_unit_test(test_slow_flat_beat_has_no_cruise),
        cmocka_unit_test(test_slow_flat_beat_bounded),
        cmocka_unit_test(test_poses_are_bit_identical_across_cpus),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

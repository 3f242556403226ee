/* evolve (cub/evolve.h), the motion side: the survivor's blend, the floor
 * step, foot slide, BVH export, then a real pair (a CMU human and a dog;
 * tests only) when CUB_DATA_DIR has it. Skeletons: evolve_fixture.h. */
#include "evolve_fixture.h"

/* ---- survivor -------------------------------------------------------------- */

/* Joint j's mean rotation over m (as survivor.c takes it). */
static cub_dq mean_rot(const cub_evolve_motion *m, int j)
{
    cub_dq first = *cub_evolve_rot(m, 0, j), sum = {0, 0, 0, 0};
    for (int f = 0; f < m->frames; f++) {
        cub_dq q = *cub_evolve_rot(m, f, j);
        double k = cub_dq_dot(q, first) < 0 ? -1 : 1;
        sum = (cub_dq){sum.w + k * q.w, sum.x + k * q.x, sum.y + k * q.y, sum.z + k * q.z};
    }
    return cub_dq_norm(sum);
}

static void test_survivor_blend_zero_is_parent_one(void **state)
{
    (void)state;
    cross(-1, 50, 30);
    fx.mut.count = 0;
    assert_int_equal(cub_evolve_mutate(&fx.m, &fx.p1, &fx.p2, &fx.mut, &fx.pop, NULL), CUB_OK);
    static cub_evolve_motion child;
    cub_evolve_survivor_cfg cfg = {0, 0, 0};
    assert_int_equal(cub_evolve_survivor(&fx.m, &fx.pop, &fx.p1, &fx.p2, &cfg, &child, NULL, NULL),
                     CUB_OK);
    assert_int_equal(child.frames, 50); /* the longer parent */
    for (int f = 0; f < fx.p1.frames; f++) {
        assert_memory_equal(&child.root_mm[f], &fx.p1.root_mm[f], sizeof(cub_dv3));
        for (int j = 0; j < fx.a.joint_count; j++)
            assert_memory_equal(cub_evolve_rot(&child, f, fx.pop.child[j]),
                                cub_evolve_rot(&fx.p1, f, j), sizeof(cub_dq));
    }
    cub_evolve_motion_free(&child);
    /* a shorter parent 1 loops: the same rotations, the root walking on */
    cross(-1, 20, 50);
    assert_int_equal(cub_evolve_mutate(&fx.m, &fx.p1, &fx.p2, &fx.mut, &fx.pop, NULL), CUB_OK);
    assert_int_equal(cub_evolve_survivor(&fx.m, &fx.pop, &fx.p1, &fx.p2, &cfg, &child, NULL, NULL),
                     CUB_OK);
    assert_int_equal(child.frames, 50);
    for (int f = 20; f < 50; f++) {
        assert_true(fabs(child.root_mm[f].z - 10.0 * (f % 20 + 19 * (f / 20))) < 1e-9);
        assert_true(child.root_mm[f].y == fx.p1.root_mm[f % 20].y);
        for (int j = 0; j < fx.a.joint_count; j++)
            assert_memory_equal(cub_evolve_rot(&child, f, fx.pop.child[j]),
                                cub_evolve_rot(&fx.p1, f % 20, j), sizeof(cub_dq));
    }
    cub_evolve_motion_free(&child);
}

static void test_survivor_finds_the_window_and_blends(void **state)
{
    (void)state;
    /* parent 2 is parent 1 (same skeleton) started 7 frames later */
    cross(-1, 40, 30);
    static cub_evolve_motion p2;
    assert_int_equal(cub_evolve_motion_alloc(&fx.a, 40, 30, &p2), CUB_OK);
    for (int f = 0; f < 40; f++) {
        p2.root_mm[f] = fx.p1.root_mm[f];
        for (int j = 0; j < fx.a.joint_count; j++)
            *cub_evolve_rot(&p2, f, j) = *cub_evolve_rot(&fx.p1, (f + 40 - 7) % 40, j);
    }
    static cub_evolve_corr c;
    static cub_evolve_meta m;
    static cub_evolve_pop pop;
    static cub_evolve_motion child;
    assert_int_equal(cub_evolve_correspond(&fx.a, &fx.a, NULL, &c, NULL), CUB_OK);
    assert_int_equal(cub_evolve_crossover(&fx.a, &fx.a, &c, &m, NULL), CUB_OK);
    assert_int_equal(m.appended, 0);
    assert_int_equal(cub_evolve_mutate(&m, &fx.p1, &p2, &(cub_evolve_mutation){0}, &pop, NULL),
                     CUB_OK);
    cub_evolve_survivor_report rep;
    cub_evolve_survivor_cfg cfg = {-0.5, 0, 0};
    assert_int_equal(cub_evolve_survivor(&m, &pop, &fx.p1, &p2, &cfg, &child, &rep, NULL), CUB_OK);
    assert_int_equal(rep.offset, 7);
    assert_true(rep.energy < 1e-12);
    /* the same motion aligned: d = 0, so any x gives parent 1 back */
    for (int f = 0; f < 40; f++)
        for (int j = 1; j < fx.a.joint_count; j++)
            assert_true(cub_dq_angle_between(*cub_evolve_rot(&child, f, j),
                                             *cub_evolve_rot(&fx.p1, f, j)) < 1e-6);
    cub_evolve_motion_free(&child);
    /* in time (a coach's clips, timed to the music): no search, parent 2
     * from its frame 0, the 7 frames' mismatch reported as energy */
    cfg.in_time = 1;
    assert_int_equal(cub_evolve_survivor(&m, &pop, &fx.p1, &p2, &cfg, &child, &rep, NULL), CUB_OK);
    assert_int_equal(rep.offset, 0);
    assert_true(rep.energy > 1e-6);
    cfg.in_time = 0;
    cub_evolve_motion_free(&child);
    /* x = 1 against a different parent 2: parent 1's mean pose moving as
     * the partner moves, i.e. D1 becomes D2 */
    cross(-1, 40, 40);
    assert_int_equal(
        cub_evolve_mutate(&fx.m, &fx.p1, &fx.p2, &(cub_evolve_mutation){0}, &fx.pop, NULL), CUB_OK);
    cfg.blend = 1;
    assert_int_equal(cub_evolve_survivor(&fx.m, &fx.pop, &fx.p1, &fx.p2, &cfg, &child, &rep, NULL),
                     CUB_OK);
    int s1 = joint(&fx.a, "Spine"), s2 = joint(&fx.b, "Spine");
    cub_dq m1 = mean_rot(&fx.p1, s1), m2 = mean_rot(&fx.p2, s2);
    for (int f = 0; f < 40; f++) {
        cub_dq d1 = cub_dq_mul(cub_dq_conj(m1), *cub_evolve_rot(&child, f, s1));
        cub_dq d2 = cub_dq_mul(cub_dq_conj(m2), *cub_evolve_rot(&fx.p2, (f + rep.offset) % 40, s2));
        assert_true(cub_dq_angle_between(d1, d2) < 1e-6);
    }
    cub_evolve_motion_free(&child);
    cub_evolve_motion_free(&p2);
}

/* Many-to-one: a fish's Spine for a horse's Spine and Neck (a chain: their
 * product), its Tail for both thighs (siblings: their mean). Parent 1
 * holding its partners' mean pose, x = 1 in time gives exactly that. */
static void test_survivor_combines_several_partners(void **state)
{
    (void)state;
    static cub_skeleton a, b;
    static cub_evolve_map map;
    static cub_evolve_corr c;
    static cub_evolve_meta m;
    static cub_evolve_pop pop;
    static cub_evolve_motion p1, p2, child;
    static cub_dq mean[CUB_EVOLVE_MAX_JOINTS];
    memset(&a, 0, sizeof a), memset(&b, 0, sizeof b);
    build(&a, fish, COUNT(fish));
    build(&b, horse, COUNT(horse));
    const char *text = "Spine = Spine Neck\nTail = LeftUpLeg RightUpLeg\n";
    assert_int_equal(cub_evolve_map_parse(text, strlen(text), "t.map", &map, NULL), CUB_OK);
    assert_int_equal(cub_evolve_correspond(&a, &b, &map, &c, NULL), CUB_OK);
    assert_int_equal(cub_evolve_crossover(&a, &b, &c, &m, NULL), CUB_OK);
    animate(&b, 30, -1, &p2);
    animate(&a, 30, -1, &p1);
    cub_evolve_partner_means(&m, &p2, mean);
    for (int f = 0; f < 30; f++)
        for (int j = 1; j < a.joint_count; j++)
            if (m.partner_count[j]) *cub_evolve_rot(&p1, f, j) = mean[j];
    assert_int_equal(cub_evolve_mutate(&m, &p1, &p2, &(cub_evolve_mutation){0}, &pop, NULL),
                     CUB_OK);
    cub_evolve_survivor_cfg cfg = {1, 0, 1};
    assert_int_equal(cub_evolve_survivor(&m, &pop, &p1, &p2, &cfg, &child, NULL, NULL), CUB_OK);
    int spine = joint(&a, "Spine"), tail = joint(&a, "Tail");
    int s2 = joint(&b, "Spine"), n2 = joint(&b, "Neck");
    int l2 = joint(&b, "LeftUpLeg"), r2 = joint(&b, "RightUpLeg");
    assert_int_equal(m.partner_count[spine], 2);
    for (int f = 0; f < 30; f++) {
        cub_dq chain = cub_dq_mul(*cub_evolve_rot(&p2, f, s2), *cub_evolve_rot(&p2, f, n2));
        cub_dq l = *cub_evolve_rot(&p2, f, l2), r = *cub_evolve_rot(&p2, f, r2);
        double k = cub_dq_dot(l, r) < 0 ? -1 : 1;
        cub_dq avg = cub_dq_norm((cub_dq){l.w + k * r.w, l.x + k * r.x, l.y + k * r.y,
                                          l.z + k * r.z});
        assert_true(cub_dq_angle_between(*cub_evolve_rot(&child, f, spine), chain) < 1e-6);
        assert_true(cub_dq_angle_between(*cub_evolve_rot(&child, f, tail), avg) < 1e-6);
    }
    cub_evolve_motion_free(&child), cub_evolve_motion_free(&p1), cub_evolve_motion_free(&p2);
}

static void test_survivor_refuses_different_rates(void **state)
{
    (void)state;
    cross(-1, 20, 20);
    fx.p2.fps = 60;
    cub_diag d = {0};
    static cub_evolve_motion child;
    assert_int_equal(cub_evolve_survivor(&fx.m, &fx.pop, &fx.p1, &fx.p2, NULL, &child, NULL, &d),
                     CUB_ERR_ARG);
    assert_non_null(strstr(d.msg, "rates differ"));
}

/* ---- the floor step -------------------------------------------------------- */

static void test_floor_step_lifts_by_ik_and_keeps_bones(void **state)
{
    (void)state;
    /* hips 500 mm up, a leg 600 mm tall, the knee a little forward: the
     * foot 100 mm below (a straight leg is the Jacobian's singular case) */
    static const bone leg[] = {{"Hips", NULL, 0, 500, 0},
                               {"UpLeg", "Hips", 100, 0, 0},
                               {"Leg", "UpLeg", 0, -300, 40},
                               {"Foot", "Leg", 0, -300, -40},
                               {"Toe", "Foot", 0, 0, 120}};
    static cub_skeleton s;
    build(&s, leg, COUNT(leg));
    static cub_evolve_motion m;
    assert_int_equal(cub_evolve_motion_alloc(&s, 10, 30, &m), CUB_OK);
    for (int f = 0; f < 10; f++)
        m.root_mm[f] = cub_dv3_make(0, 500 + 20 * f, 0); /* frame 5 on: above */
    cub_evolve_floor_report rep;
    cub_evolve_floor(&m, &rep);
    assert_true(rep.below_before >= 5 * 2);
    assert_int_equal(rep.below_after, 0);
    assert_int_equal(rep.frames_lifted, 0); /* the IK did it, not the root */
    assert_int_equal(rep.frames_ik, 5);
    assert_true(fabs(rep.deepest_mm + 100) < 1e-6);
    cub_dv3 w[8];
    for (int f = 0; f < 10; f++) {
        cub_evolve_forward(&m, f, w);
        assert_true(fabs(m.root_mm[f].y - (500 + 20 * f)) < 1e-12);
        for (int j = 0; j < s.joint_count; j++)
            assert_true(w[j].y >= -1e-6);
        for (int j = 1; j < s.joint_count; j++) {
            double rest = cub_dv3_len(cub_dv3_from_fx(s.joints[j].offset_mm));
            assert_true(fabs(cub_dv3_len(cub_dv3_sub(w[j], w[s.joints[j].parent])) - rest) < 1e-6);
        }
    }
    cub_evolve_motion_free(&m);
}

static void test_floor_step_raises_the_root_when_ik_cannot(void **state)
{
    (void)state;
    static const bone low[] = {{"Hips", NULL, 0, 0, 0}, {"Belly", "Hips", 0, -50, 0}};
    static cub_skeleton s;
    build(&s, low, COUNT(low));
    static cub_evolve_motion m;
    assert_int_equal(cub_evolve_motion_alloc(&s, 3, 30, &m), CUB_OK);
    cub_evolve_floor_report rep;
    cub_evolve_floor(&m, &rep);
    assert_int_equal(rep.below_after, 0);
    assert_int_equal(rep.frames_lifted, 3);
    assert_true(fabs(m.root_mm[0].y - 50) < 1e-9);
    cub_evolve_motion_free(&m);
}

static void test_slide_of_a_standing_and_a_sliding_foot(void **state)
{
    (void)state;
    static const bone two[] = {{"Hips", NULL, 0, 0, 0}, {"Foot", "Hips", 0, 0, 0}};
    static cub_skeleton s;
    build(&s, two, COUNT(two));
    static cub_evolve_motion m;
    assert_int_equal(cub_evolve_motion_alloc(&s, 20, 30, &m), CUB_OK);
    cub_evolve_slide_report rep;
    assert_int_equal(cub_evolve_slide(&m, 1, &rep), CUB_OK);
    assert_int_equal(rep.contact_frames, 19);
    assert_true(rep.mean_mm == 0 && rep.max_mm == 0);
    for (int f = 0; f < 20; f++)
        m.root_mm[f] = cub_dv3_make(f * 3.0, 0, f * 4.0); /* 150 mm/s */
    assert_int_equal(cub_evolve_slide(&m, 1, &rep), CUB_OK);
    assert_int_equal(rep.contact_frames, 19);
    assert_true(fabs(rep.mean_mm - 5) < 1e-9 && fabs(rep.max_mm - 5) < 1e-9);
    for (int f = 0; f < 20; f++)
        m.root_mm[f].y = 100; /* in the air: no contact... */
    m.root_mm[0].y = 0;       /* ...but the lowest point is the floor */
    assert_int_equal(cub_evolve_slide(&m, 1, &rep), CUB_OK);
    assert_int_equal(rep.contact_frames, 0);
    assert_int_equal(cub_evolve_slide(&m, 2, &rep), CUB_ERR_ARG);
    cub_evolve_motion_free(&m);
}

/* ---- export ---------------------------------------------------------------- */

static void test_child_exports_as_bvh_and_reads_back(void **state)
{
    (void)state;
    cross(-1, 12, 20);
    fx.mut.count = 2;
    assert_int_equal(cub_evolve_mutate(&fx.m, &fx.p1, &fx.p2, &fx.mut, &fx.pop, NULL), CUB_OK);
    static cub_evolve_motion child, back;
    cub_evolve_survivor_cfg cfg = {0.5, 0, 0};
    assert_int_equal(cub_evolve_survivor(&fx.m, &fx.pop, &fx.p1, &fx.p2, &cfg, &child, NULL, NULL),
                     CUB_OK);
    static cub_io_motion io, in;
    assert_int_equal(cub_evolve_to_io(&child, 10, &io), CUB_OK);
    char path[512];
    const char *dir = getenv("CUB_BUILD_DIR");
    snprintf(path, sizeof path, "%s/evolve_child_test.bvh", dir ? dir : ".");
    cub_diag d = {0};
    assert_int_equal(cub_io_save_bvh(path, &io, &d), CUB_OK);
    assert_int_equal(cub_io_load_bvh(path, &(cub_io_desc){10}, &in, &d), CUB_OK);
    assert_int_equal(in.skel.joint_count, child.skel.joint_count);
    assert_int_equal(in.clip.frame_count, child.frames);
    assert_int_equal(cub_evolve_from_clip(&in.clip, 30, &back), CUB_OK);
    assert_int_equal(back.frames, child.frames);
    cub_dv3 w1[CUB_EVOLVE_MAX_JOINTS], w2[CUB_EVOLVE_MAX_JOINTS];
    for (int f = 0; f < child.frames; f++) {
        cub_evolve_forward(&child, f, w1);
        cub_evolve_forward(&back, f, w2);
        for (int j = 0; j < child.skel.joint_count; j++) {
            assert_string_equal(in.skel.joints[j].name, child.skel.joints[j].name);
            assert_true(cub_dv3_len(cub_dv3_sub(w1[j], w2[j])) < 0.1); /* mm: the file's decimals */
        }
    }
    remove(path);
    cub_io_motion_free(&io);
    cub_io_motion_free(&in);
    cub_evolve_motion_free(&child);
    cub_evolve_motion_free(&back);
}

/* The whole pipeline on p1 x p2 (no map, 2 mutations, x = 0.5, the floor
 * step); asserts the invariants: no joint below the floor after the step,
 * kept bones their rest length. */
static void evolve_checked(const cub_evolve_motion *p1, const cub_evolve_motion *p2,
                           cub_evolve_motion *child)
{
    static cub_evolve_corr c;
    static cub_evolve_meta m;
    static cub_evolve_pop pop;
    assert_int_equal(cub_evolve_correspond(&p1->skel, &p2->skel, NULL, &c, NULL), CUB_OK);
    assert_int_equal(cub_evolve_crossover(&p1->skel, &p2->skel, &c, &m, NULL), CUB_OK);
    assert_int_equal(cub_evolve_mutate(&m, p1, p2, &(cub_evolve_mutation){.count = 2}, &pop, NULL),
                     CUB_OK);
    assert_int_equal(pop.removed_count, 2);
    cub_evolve_survivor_cfg cfg = {0.5, 0, 0};
    assert_int_equal(cub_evolve_survivor(&m, &pop, p1, p2, &cfg, child, NULL, NULL), CUB_OK);
    cub_evolve_floor_report rep;
    cub_evolve_floor(child, &rep);
    assert_int_equal(rep.below_after, 0);
    cub_dv3 w[CUB_EVOLVE_MAX_JOINTS];
    for (int f = 0; f < child->frames; f++) {
        cub_evolve_forward(child, f, w);
        for (int j = 0; j < child->skel.joint_count; j++)
            assert_true(w[j].y >= -1e-6);
    }
    assert_true(cub_evolve_bone_error_mm(child, &pop, &m) < 1e-3);
}

/* "The child can be evolved again": a child written as BVH, read back and
 * crossed with a parent (its own parent 2, the fish) obeys the same floor
 * and bone-length invariants as its first cross. */
static void test_child_read_back_evolves_again(void **state)
{
    (void)state;
    cross(-1, 24, 30);
    static cub_evolve_motion child, back, grandchild;
    evolve_checked(&fx.p1, &fx.p2, &child);
    static cub_io_motion io, in;
    assert_int_equal(cub_evolve_to_io(&child, 10, &io), CUB_OK);
    char path[512];
    const char *dir = getenv("CUB_BUILD_DIR");
    snprintf(path, sizeof path, "%s/evolve_child_again.bvh", dir ? dir : ".");
    cub_diag d = {0};
    assert_int_equal(cub_io_save_bvh(path, &io, &d), CUB_OK);
    assert_int_equal(cub_io_load_bvh(path, &(cub_io_desc){10}, &in, &d), CUB_OK);
    assert_int_equal(cub_evolve_from_clip(&in.clip, 30, &back), CUB_OK);
    evolve_checked(&back, &fx.p2, &grandchild);
    assert_int_equal(grandchild.frames, 30); /* the longer parent's length */
    assert_true(grandchild.skel.joint_count >= back.skel.joint_count - 2);
    remove(path);
    cub_io_motion_free(&io);
    cub_io_motion_free(&in);
    cub_evolve_motion_free(&child);
    cub_evolve_motion_free(&back);
    cub_evolve_motion_free(&grandchild);
}

/* A joint appended under an earlier one (as a crossed child's wings under
 * the chest, after the legs): the file lists it in the hierarchy before
 * the legs, and each frame's channels must follow that order. Read back,
 * every joint (found by name) is where it was. */
static void test_bvh_keeps_channels_of_a_joint_added_under_an_earlier_one(void **state)
{
    (void)state;
    static const bone winged[] = {
        {"Hips", NULL, 0, 900, 0},          {"Spine", "Hips", 0, 100, 0},
        {"LeftUpLeg", "Hips", 100, -400, 0}, {"LeftLeg", "LeftUpLeg", 0, -400, 0},
        {"Wing", "Spine", 100, 50, -50},     {"WingTip", "Wing", 300, 0, 0},
    };
    static cub_skeleton s;
    static cub_evolve_motion m, back;
    static cub_io_motion io, in;
    build(&s, winged, COUNT(winged));
    animate(&s, 10, -1, &m);
    assert_int_equal(cub_evolve_to_io(&m, 10, &io), CUB_OK);
    char path[512];
    const char *dir = getenv("CUB_BUILD_DIR");
    snprintf(path, sizeof path, "%s/evolve_wing_order_test.bvh", dir ? dir : ".");
    assert_int_equal(cub_io_save_bvh(path, &io, NULL), CUB_OK);
    assert_int_equal(cub_io_load_bvh(path, &(cub_io_desc){10}, &in, NULL), CUB_OK);
    assert_string_equal(in.skel.joints[2].name, "Wing"); /* hierarchy order */
    assert_int_equal(cub_evolve_from_clip(&in.clip, 30, &back), CUB_OK);
    cub_dv3 w1[CUB_EVOLVE_MAX_JOINTS], w2[CUB_EVOLVE_MAX_JOINTS];
    for (int f = 0; f < m.frames; f++) {
        cub_evolve_forward(&m, f, w1);
        cub_evolve_forward(&back, f, w2);
        for (int j = 0; j < m.skel.joint_count; j++) {
            int k = cub_motion_skeleton_find(&back.skel, m.skel.joints[j].name);
            assert_true(k >= 0);
            assert_true(cub_dv3_len(cub_dv3_sub(w1[j], w2[k])) < 0.1);
        }
    }
    remove(path);
    cub_io_motion_free(&io);
    cub_io_motion_free(&in);
    cub_evolve_motion_free(&m);
    cub_evolve_motion_free(&back);
}

/* ---- a real pair ----------------------------------------------------------- */

static int load(const char *rel, cub_evolve_motion *out)
{
    char path[512];
    const char *dir = getenv("CUB_DATA_DIR");
    snprintf(path, sizeof path, "%s/mocap/%s", dir ? dir : "../shared/data", rel);
    static cub_io_motion io;
    if (cub_io_load_bvh(path, NULL, &io, NULL) != CUB_OK) return 0;
    assert_int_equal(cub_evolve_from_clip(&io.clip, 30, out), CUB_OK);
    cub_io_motion_free(&io);
    if (out->frames > 151) out->frames = 151;
    return 1;
}

static void test_cmu_human_crossed_with_a_dog(void **state)
{
    (void)state;
    static cub_evolve_motion human, dog, child;
    if (!load("cmu/02_01.bvh", &human) || !load("dog/D1_001_KAN01_001.bvh", &dog)) {
        cub_evolve_motion_free(&human);
        skip(); /* no ../shared/data/mocap here */
    }
    static cub_evolve_corr c;
    static cub_evolve_meta m;
    static cub_evolve_pop pop;
    assert_int_equal(cub_evolve_correspond(&dog.skel, &human.skel, NULL, &c, NULL), CUB_OK);
    assert_true(c.pair_count >= 15); /* the dog's joints carry human names */
    assert_int_equal(cub_evolve_kind_of(&c, 1, joint(&dog.skel, "Tail")), CUB_EVOLVE_NONE);
    assert_int_equal(cub_evolve_crossover(&dog.skel, &human.skel, &c, &m, NULL), CUB_OK);
    cub_evolve_mutation mut = {.count = CUB_EVOLVE_MUTATIONS_DEFAULT};
    assert_int_equal(cub_evolve_mutate(&m, &dog, &human, &mut, &pop, NULL), CUB_OK);
    assert_int_equal(pop.removed_count, 5);
    cub_evolve_survivor_cfg cfg = {0.5, 0, 0};
    assert_int_equal(cub_evolve_survivor(&m, &pop, &dog, &human, &cfg, &child, NULL, NULL), CUB_OK);
    cub_evolve_floor_report rep;
    cub_evolve_floor(&child, &rep);
    assert_int_equal(rep.below_after, 0);
    assert_true(cub_evolve_bone_error_mm(&child, &pop, &m) < 1e-3);
    cub_evolve_motion_free(&human);
    cub_evolve_motion_free(&dog);
    cub_evolve_motion_free(&child);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_survivor_blend_zero_is_parent_one),
        cmocka_unit_test(test_survivor_finds_the_window_and_blends),
        cmocka_unit_test(test_survivor_combines_several_partners),
        cmocka_unit_test(test_survivor_refuses_different_rates),
        cmocka_unit_test(test_floor_step_lifts_by_ik_and_keeps_bones),
        cmocka_unit_test(test_floor_step_raises_the_root_when_ik_cannot),
        cmocka_unit_test(test_slide_of_a_standing_and_a_sliding_foot),
        cmocka_unit_test(test_child_exports_as_bvh_and_reads_back),
        cmocka_unit_test(test_child_read_back_evolves_again),
        cmocka_unit_test(test_bvh_keeps_channels_of_a_joint_added_under_an_earlier_one),
        cmocka_unit_test(test_cmu_human_crossed_with_a_dog),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    free_fixture();
    return rc;
}

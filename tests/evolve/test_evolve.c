/* evolve (cub/evolve.h), the skeleton side: first what bad map files get,
 * then correspondence, crossover and mutation on small hand-made
 * skeletons (evolve_fixture.h). The motion side: test_evolve_motion.c. */
#include "evolve_fixture.h"

static void parse_map(const char *text, cub_evolve_map *map)
{
    cub_diag d = {0};
    assert_int_equal(cub_evolve_map_parse(text, strlen(text), "test.map", map, &d), CUB_OK);
}

/* ---- bad map files --------------------------------------------------------- */

static void expect_map_error(const char *text, const char *want)
{
    static cub_evolve_map map;
    cub_diag d = {0};
    char buf[600];
    assert_int_equal(cub_evolve_map_parse(text, strlen(text), "x.map", &map, &d), CUB_ERR_FORMAT);
    cub_diag_str(&d, buf, sizeof buf);
    if (!strstr(buf, want)) fail_msg("\"%s\" not in \"%s\"", want, buf);
}

static void test_map_errors_name_file_and_line(void **state)
{
    (void)state;
    expect_map_error("", "x.map: no rows");
    expect_map_error("# only a comment\n", "no rows");
    expect_map_error("Head = Head\nNeck Collar\n", "x.map:2: expected");
    expect_map_error("A B = C D\n", "x.map:1: many joints on both sides");
    expect_map_error("Head = Head\n\nHead = Spine\n",
                     "x.map:3: parent 1's joint \"Head\" already mapped on line 1");
    expect_map_error("Head = Skull Skull\n", "parent 2's joint \"Skull\" already mapped on line 1");
    expect_map_error("- = -\n", "'-' on both sides");
    expect_map_error("Head =\n", "nothing on the right");
    expect_map_error("Head = = Head\n", "more than one '='");
    expect_map_error("A B C D E = F\n", "more than 4 joints on the left");
    expect_map_error("Head - = Head\n", "'-' beside joint names");
    expect_map_error("Head = AVeryLongJointNameThatGoesOnAndOnForever\n", "too long");
    /* names are bound against the skeletons: an unknown one names the row */
    static cub_skeleton a, b;
    build(&a, horse, COUNT(horse));
    build(&b, fish, COUNT(fish));
    static cub_evolve_map map;
    parse_map("# ok\nHorn = -\nLeftUpLeg RightUpLeg = Fin\n", &map);
    static cub_evolve_corr c;
    cub_diag d = {0};
    char buf[600];
    assert_int_equal(cub_evolve_correspond(&a, &b, &map, &c, &d), CUB_ERR_FORMAT);
    assert_string_equal(cub_diag_str(&d, buf, sizeof buf),
                        "test.map:3: no joint \"Fin\" in parent 2");
}

/* ---- correspondence -------------------------------------------------------- */

static void test_correspond_by_name_and_structure(void **state)
{
    (void)state;
    static cub_skeleton a, b;
    build(&a, horse, COUNT(horse));
    build(&b, fish, COUNT(fish));
    static cub_evolve_corr c;
    cub_diag d = {0};
    assert_int_equal(cub_evolve_correspond(&a, &b, NULL, &c, &d), CUB_OK);
    /* names: Hips, Spine, Head; structure: Neck is Spine's only unmatched
     * child as Collar is; the legs and the tail stay apart (two unmatched
     * children of Hips against one: ambiguous) */
    assert_int_equal(cub_evolve_partner_of_a(&c, joint(&a, "Hips")), joint(&b, "Hips"));
    assert_int_equal(cub_evolve_partner_of_a(&c, joint(&a, "Head")), joint(&b, "Head"));
    assert_int_equal(cub_evolve_partner_of_a(&c, joint(&a, "Neck")), joint(&b, "Collar"));
    assert_int_equal(cub_evolve_kind_of(&c, 1, joint(&a, "Neck")), CUB_EVOLVE_ONE_TO_ONE);
    assert_int_equal(cub_evolve_kind_of(&c, 1, joint(&a, "Horn")), CUB_EVOLVE_NONE);
    assert_int_equal(cub_evolve_kind_of(&c, 1, joint(&a, "LeftUpLeg")), CUB_EVOLVE_NONE);
    assert_int_equal(cub_evolve_kind_of(&c, 2, joint(&b, "Tail")), CUB_EVOLVE_NONE);
    assert_int_equal(c.pair_count, 4);
}

static void test_correspond_loose_names(void **state)
{
    (void)state;
    static const bone cmu[] = {{"Hips", NULL, 0, 900, 0},
                               {"LHipJoint", "Hips", 80, 0, 0},
                               {"LeftUpLeg", "LHipJoint", 20, -50, 0}};
    static const bone other[] = {{"hips", NULL, 0, 900, 0},
                                 {"left_hip_joint", "hips", 80, 0, 0},
                                 {"LEFTUPLEG", "left_hip_joint", 20, -50, 0}};
    static cub_skeleton a, b;
    build(&a, cmu, 3);
    build(&b, other, 3);
    static cub_evolve_corr c;
    assert_int_equal(cub_evolve_correspond(&a, &b, NULL, &c, NULL), CUB_OK);
    for (int j = 0; j < 3; j++)
        assert_int_equal(cub_evolve_partner_of_a(&c, j), j);
}

static void test_correspond_map_many_to_one_and_none(void **state)
{
    (void)state;
    static cub_skeleton a, b;
    build(&a, horse, COUNT(horse));
    build(&b, fish, COUNT(fish));
    static cub_evolve_map map;
    parse_map("LeftUpLeg RightUpLeg = Tail\nHead = -\n", &map);
    static cub_evolve_corr c;
    assert_int_equal(cub_evolve_correspond(&a, &b, &map, &c, NULL), CUB_OK);
    assert_int_equal(cub_evolve_partner_of_a(&c, joint(&a, "LeftUpLeg")), joint(&b, "Tail"));
    assert_int_equal(cub_evolve_partner_of_a(&c, joint(&a, "RightUpLeg")), joint(&b, "Tail"));
    assert_int_equal(cub_evolve_kind_of(&c, 1, joint(&a, "LeftUpLeg")), CUB_EVOLVE_MANY_TO_ONE);
    assert_int_equal(cub_evolve_kind_of(&c, 2, joint(&b, "Tail")), CUB_EVOLVE_ONE_TO_MANY);
    /* the map's "none" beats the names; LeftLeg follows its parent's match */
    assert_int_equal(cub_evolve_kind_of(&c, 1, joint(&a, "Head")), CUB_EVOLVE_NONE);
    assert_int_equal(cub_evolve_partner_of_a(&c, joint(&a, "LeftLeg")),
                     -1); /* no structure below a many-to-one pair */
}

/* ---- crossover ------------------------------------------------------------- */

static void test_crossover_keeps_common_joints_once(void **state)
{
    (void)state;
    static cub_skeleton a, b;
    build(&a, horse, COUNT(horse));
    build(&b, fish, COUNT(fish));
    static cub_evolve_map map;
    parse_map("- = Head\n", &map); /* the fish's head stays the fish's: a second head */
    static cub_evolve_corr c;
    static cub_evolve_meta m;
    assert_int_equal(cub_evolve_correspond(&a, &b, &map, &c, NULL), CUB_OK);
    assert_int_equal(cub_evolve_crossover(&a, &b, &c, &m, NULL), CUB_OK);
    /* parent 1 whole and in order, then Head (renamed), Tail, Tail1 */
    assert_int_equal(m.skel.joint_count, COUNT(horse) + 3);
    assert_int_equal(m.appended, 3);
    for (int j = 0; j < COUNT(horse); j++) {
        assert_string_equal(m.skel.joints[j].name, a.joints[j].name);
        assert_int_equal(m.from[j], 1);
        assert_int_equal(m.src[j], j);
    }
    int head2 = joint(&m.skel, "Head_2"), tail = joint(&m.skel, "Tail"),
        tail1 = joint(&m.skel, "Tail1");
    assert_int_equal(m.skel.joints[head2].parent, joint(&m.skel, "Neck")); /* Collar's partner */
    assert_int_equal(m.skel.joints[tail].parent, 0);
    assert_int_equal(m.skel.joints[tail1].parent, tail);
    assert_int_equal(m.from[tail1], 2);
    assert_int_equal(m.src[tail1], joint(&b, "Tail1"));
    assert_int_equal(m.partner[joint(&m.skel, "Spine")], joint(&b, "Spine"));
    assert_int_equal(cub_motion_skeleton_validate(&m.skel), CUB_OK);
}

/* ---- mutation -------------------------------------------------------------- */

static void test_activity_of_a_still_joint_is_zero(void **state)
{
    (void)state;
    cross(6, 40, 30); /* LeftLeg (6) held still */
    double act[CUB_EVOLVE_MAX_JOINTS];
    cub_evolve_activity(&fx.p1, act);
    assert_true(act[6] == 0);
    for (int j = 1; j < fx.a.joint_count; j++)
        if (j != 6) assert_true(act[j] > 1.0); /* degrees */
}

static void test_mutation_removes_the_still_joint_first(void **state)
{
    (void)state;
    int leg = 6;
    cross(leg, 40, 30);
    fx.mut.count = 1;
    assert_int_equal(cub_evolve_mutate(&fx.m, &fx.p1, &fx.p2, &fx.mut, &fx.pop, NULL), CUB_OK);
    assert_int_equal(fx.pop.removed_count, 1);
    assert_true(fx.pop.removed[leg]);
    assert_true(fx.pop.score[leg] == 0); /* the least active of the meta skeleton */
    assert_int_equal(fx.pop.skel.joint_count, fx.m.skel.joint_count - 1);
    assert_int_equal(fx.pop.child[leg], -1);
    assert_int_equal(cub_motion_skeleton_find(&fx.pop.skel, "LeftLeg"), -1);
    /* the root is never removed, whatever the count */
    fx.mut.count = 100;
    assert_int_equal(cub_evolve_mutate(&fx.m, &fx.p1, &fx.p2, &fx.mut, &fx.pop, NULL), CUB_OK);
    assert_int_equal(fx.pop.skel.joint_count, 1);
    assert_string_equal(fx.pop.skel.joints[0].name, "Hips");
}

static void test_mutation_weight_minus_two_forces_the_joint(void **state)
{
    (void)state;
    cross(6, 40, 30);
    int horn = joint(&fx.m.skel, "Horn");
    fx.mut.count = 1;
    fx.mut.weight[horn] = -2;
    assert_int_equal(cub_evolve_mutate(&fx.m, &fx.p1, &fx.p2, &fx.mut, &fx.pop, NULL), CUB_OK);
    assert_int_equal(fx.pop.removed_count, 1);
    assert_true(fx.pop.removed[horn]);
    assert_false(fx.pop.removed[6]); /* the still leg stays */
    /* +2 protects: with the still leg weighted up, another joint goes */
    memset(fx.mut.weight, 0, sizeof fx.mut.weight);
    fx.mut.weight[6] = 2;
    assert_int_equal(cub_evolve_mutate(&fx.m, &fx.p1, &fx.p2, &fx.mut, &fx.pop, NULL), CUB_OK);
    assert_false(fx.pop.removed[6]);
    assert_int_equal(fx.pop.removed_count, 1);
}

static void test_mutation_relinks_to_the_nearest_kept_ancestor(void **state)
{
    (void)state;
    cross(-1, 40, 30);
    int neck = joint(&fx.m.skel, "Neck");
    fx.mut.count = 1;
    fx.mut.weight[neck] = -2;
    assert_int_equal(cub_evolve_mutate(&fx.m, &fx.p1, &fx.p2, &fx.mut, &fx.pop, NULL), CUB_OK);
    const cub_skeleton *p = &fx.pop.skel;
    int head = joint(p, "Head");
    assert_int_equal(p->joints[head].parent, joint(p, "Spine"));
    assert_int_equal(fx.pop.relinked, 1);
    /* the rest pose is unchanged: Head's offset is Neck's plus its own */
    cub_dv3 off = cub_dv3_from_fx(p->joints[head].offset_mm);
    assert_true(fabs(off.y - 200) < 1e-3 && fabs(off.z - 300) < 1e-3);
    assert_int_equal(cub_motion_skeleton_validate(p), CUB_OK);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_map_errors_name_file_and_line),
        cmocka_unit_test(test_correspond_by_name_and_structure),
        cmocka_unit_test(test_correspond_loose_names),
        cmocka_unit_test(test_correspond_map_many_to_one_and_none),
        cmocka_unit_test(test_crossover_keeps_common_joints_once),
        cmocka_unit_test(test_activity_of_a_still_joint_is_zero),
        cmocka_unit_test(test_mutation_removes_the_still_joint_first),
        cmocka_unit_test(test_mutation_weight_minus_two_forces_the_joint),
        cmocka_unit_test(test_mutation_relinks_to_the_nearest_kept_ancestor),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    free_fixture();
    return rc;
}

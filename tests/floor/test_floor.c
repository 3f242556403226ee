/* The forest floor (issue 24): the shipped asset is gentle and flat where
 * the bear dances, the ground the renderer draws is the ground the gait
 * planner sees (cub_gait_height on cub_floor_terrain), its logs and stones
 * stand in the boxes the planner steps around, and a bad file is refused
 * naming its file and line. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/floor_file.h"
#include "render_floor.h"

static const float GRASS[3] = {0.5f, 0.76f, 0.35f};

static cub_floor g_floor;
static cub_gait_terrain g_t;

static int load_shipped(void **state)
{
    (void)state;
    char path[1024];
    const char *src = getenv("CUB_SOURCE_DIR");
    snprintf(path, sizeof path, "%s/assets/%s", src ? src : ".", CUB_FLOOR_ASSET);
    cub_diag d = {0};
    if (cub_floor_load(path, &g_floor, &d) || cub_floor_terrain(&g_floor, &g_t)) {
        fprintf(stderr, "test_floor: %s:%d: %s\n", d.file, d.line, d.msg);
        return -1;
    }
    return 0;
}

static cub_q16 q(float mm)
{
    return (cub_q16)lroundf(mm * 65536.0f);
}

static float terrain_mm(cub_q16 h)
{
    return (float)h / 65536.0f;
}

/* Flat (0 mm) within 1.4 m of the dancing spot, nothing on the ground
 * within 1.1 m of it, hills no higher than 0.25 m, a log and stones. */
static void test_shipped_floor_is_flat_where_the_bear_dances(void **state)
{
    (void)state;
    float top = 0.0f;
    for (float z = -1400.0f; z <= 1400.0f; z += 50.0f)
        for (float x = -1400.0f; x <= 1400.0f; x += 50.0f) {
            float r = sqrtf(x * x + z * z);
            if (r <= 1400.0f) assert_int_equal(cub_gait_ground_height(&g_t, q(x), q(z)), 0);
            if (r <= 1100.0f) assert_int_equal(cub_gait_height(&g_t, q(x), q(z)), 0);
        }
    for (int i = 0; i < g_floor.nx * g_floor.nz; i++)
        top = fmaxf(top, fabsf(terrain_mm(g_floor.heights_mm[i])));
    int logs = 0, stones = 0;
    for (int k = 0; k < g_floor.thing_count; k++)
        *(g_floor.things[k].kind == CUB_FLOOR_LOG ? &logs : &stones) += 1;
    printf("floor: %dx%d samples of %d mm, highest |height| %.0f mm, %d log(s), %d stones\n",
           g_floor.nx, g_floor.nz, g_floor.cell_mm, top, logs, stones);
    assert_true(top > 100.0f && top <= 250.0f);
    assert_true(logs >= 1 && stones >= 2);
}

/* Every vertex of the drawn ground is the planner's height (less the
 * drop that keeps soles from flickering), and so is the ground halfway
 * along every triangle, near enough: the drawn ground is flat triangles
 * over the planner's bilinear cells. */
static void test_drawn_ground_is_the_planners(void **state)
{
    (void)state;
    cub_render_mesh m;
    assert_true(cub_render_mesh_init(&m, 25000, 130000));
    cub_render_floor_ground(&m, &g_floor, &g_t, GRASS);
    assert_false(m.full);
    float worst_vertex = 0.0f, worst_mid = 0.0f;
    for (int i = 0; i < m.nv; i++) {
        const float *p = m.v[i].pos;
        float planned = terrain_mm(cub_gait_ground_height(&g_t, q(p[0]), q(p[2])));
        worst_vertex = fmaxf(worst_vertex, fabsf(p[1] + CUB_RENDER_FLOOR_DROP_MM - planned));
    }
    for (int i = 0; i < m.ni; i += 3) {
        float c[3] = {0, 0, 0};
        for (int k = 0; k < 3; k++)
            for (int a = 0; a < 3; a++)
                c[a] += m.v[m.idx[i + k]].pos[a] / 3.0f;
        float planned = terrain_mm(cub_gait_ground_height(&g_t, q(c[0]), q(c[2])));
        worst_mid = fmaxf(worst_mid, fabsf(c[1] + CUB_RENDER_FLOOR_DROP_MM - planned));
    }
    printf("floor: %d vertices, %d triangles; drawn - planned: at most %.4f mm at a vertex, "
           "%.2f mm at a triangle's middle\n", m.nv, m.ni / 3, worst_vertex, worst_mid);
    assert_true(worst_vertex < 0.01f);
    assert_true(worst_mid < 2.0f);
    cub_render_mesh_free(&m);
}

/* At a few named points: the dancing spot, the hillock the golden image
 * bear_on_forest_floor stands on, a dip and past the grid's edge. */
static void test_drawn_and_planned_heights_at_named_points(void **state)
{
    (void)state;
    static const struct {
        float x, z, mm;
    } AT[] = {{0, 0, 0}, {3000, -2000, 177}, {3000, -500, -84}, {-40000, -40000, 0}};
    for (size_t i = 0; i < sizeof AT / sizeof AT[0]; i++) {
        float drawn = cub_render_floor_y(&g_t, AT[i].x, AT[i].z);
        float planned = terrain_mm(cub_gait_height(&g_t, q(AT[i].x), q(AT[i].z)));
        printf("floor: at x=%.0f z=%.0f drawn %.2f mm, planned %.2f mm\n", AT[i].x, AT[i].z,
               drawn, planned);
        assert_true(fabsf(drawn - planned) < 0.01f);
        if (fabsf(AT[i].x) < 30000.0f) assert_true(fabsf(drawn - AT[i].mm) < 0.01f);
    }
}

/* Each log and stone is drawn inside the box the planner steps around,
 * its top at the box's top (a log along its top line, a stone at its peak). */
static void test_things_are_the_planners_boxes(void **state)
{
    (void)state;
    for (int k = 0; k < g_floor.thing_count; k++) {
        cub_render_mesh m;
        assert_true(cub_render_mesh_init(&m, 2000, 6000));
        cub_render_floor_thing(&m, &g_floor, k, &g_t);
        assert_false(m.full);
        assert_true(m.nv > 0);
        const cub_gait_box *b = &g_t.obstacles[k];
        float top = -1e9f;
        for (int i = 0; i < m.nv; i++) {
            const float *p = m.v[i].pos;
            assert_true(p[0] >= terrain_mm(b->min_mm.x) - 0.01f);
            assert_true(p[0] <= terrain_mm(b->max_mm.x) + 0.01f);
            assert_true(p[2] >= terrain_mm(b->min_mm.z) - 0.01f);
            assert_true(p[2] <= terrain_mm(b->max_mm.z) + 0.01f);
            top = fmaxf(top, p[1]);
        }
        const cub_floor_thing *th = &g_floor.things[k];
        float planned = terrain_mm(cub_gait_height(&g_t, q((float)th->x_mm), q((float)th->z_mm)));
        printf("floor: %s %d at x=%d z=%d: drawn top %.2f mm, the planner's %.2f mm\n",
               th->kind == CUB_FLOOR_LOG ? "log" : "stone", k, th->x_mm, th->z_mm, top, planned);
        assert_true(fabsf(top - terrain_mm(b->max_mm.y)) < 0.5f);
        assert_true(fabsf(planned - terrain_mm(b->max_mm.y)) < 0.01f);
        cub_render_mesh_free(&m);
    }
}

static void refused(const char *text, int line, const char *what)
{
    cub_floor f;
    cub_diag d = {0};
    assert_int_equal(cub_floor_parse(text, strlen(text), "bad.floor", &f, &d), CUB_ERR_FORMAT);
    printf("floor: refused: %s:%d: %s\n", d.file, d.line, d.msg);
    assert_string_equal(d.file, "bad.floor");
    assert_int_equal(d.line, line);
    assert_non_null(strstr(d.msg, what));
    assert_int_equal(f.nx, 0); /* zeroed */
}

#define HEAD "cubfloor 1\ngrid 2 2 500 0 0\n"
#define ROWS "row 0 0\nrow 0 10\n"

static void test_bad_floor_files_name_file_and_line(void **state)
{
    (void)state;
    refused("", 0, "no 'cubfloor 1'");
    refused("cubfloor 2\n", 1, "version '2'");
    refused("# a floor\nground 1\n", 2, "the first line must be 'cubfloor 1'");
    refused(HEAD "row 0 0\nrow 0\n", 4, "row 2 has 1 heights");
    refused(HEAD "row 0 0\n", 3, "1 rows, the grid has NZ = 2");
    refused(HEAD ROWS "row 0 0\n", 5, "more than NZ = 2 rows");
    refused("cubfloor 1\nrow 0 0\n", 2, "a row before the grid");
    refused(HEAD "log 0 0 400 50 x\n", 3, "before the grid's 2 rows");
    refused(HEAD ROWS "grid 2 2 500 0 0\n", 5, "a second grid");
    refused(HEAD ROWS "log 0 0 400 50 y\n", 5, "along x or z, not 'y'");
    refused(HEAD ROWS "log 0 0 80 50 x\n", 5, "shorter than it is thick");
    refused(HEAD ROWS "stone 0 0 100 100\n", 5, "stone needs");
    refused(HEAD ROWS "stone 29990 0 100 100 50\n", 5, "reaches past 30000 mm");
    refused("cubfloor 1\ngrid 2 2 5000 29000 0\n", 2, "reaches past 30000 mm");
    refused(HEAD "row 0 2001\n", 3, "height 2001 is not within -2000..2000");
    refused(HEAD "row 0 1.5\n", 3, "height '1.5' is not a whole number");
    refused(HEAD ROWS "tree 0 0\n", 5, "unknown keyword 'tree'");
}

/* The smallest floor and the crlf, BOM and comments a hand-edited file may have. */
static void test_small_floor_is_read(void **state)
{
    (void)state;
    const char text[] = "\xef\xbb\xbf# tiny\r\ncubfloor 1\r\ngrid 2 2 100 -50 -50 # corner\r\n"
                        "row 0 0\r\nrow 0 -5\r\nstone 0 0 20 20 10\r\n";
    cub_floor f;
    cub_gait_terrain t;
    cub_diag d = {0};
    assert_int_equal(cub_floor_parse(text, sizeof text - 1, "tiny.floor", &f, &d), CUB_OK);
    assert_int_equal(f.nx * f.nz, 4);
    assert_int_equal(f.heights_mm[3], CUB_Q16_INT(-5));
    assert_int_equal(cub_floor_terrain(&f, &t), CUB_OK);
    /* the stone rests on the lowest ground under it, -5 mm at its corner (50, 50)... */
    assert_int_equal(t.obstacles[0].min_mm.y, cub_gait_ground_height(&t, q(20), q(20)));
    assert_int_equal(cub_gait_height(&t, 0, 0), t.obstacles[0].max_mm.y);
    f.nx = 1;
    assert_int_equal(cub_floor_terrain(&f, &t), CUB_ERR_ARG);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shipped_floor_is_flat_where_the_bear_dances),
        cmocka_unit_test(test_drawn_ground_is_the_planners),
        cmocka_unit_test(test_drawn_and_planned_heights_at_named_points),
        cmocka_unit_test(test_things_are_the_planners_boxes),
        cmocka_unit_test(test_bad_floor_files_name_file_and_line),
        cmocka_unit_test(test_small_floor_is_read),
    };
    return cmocka_run_group_tests_name("floor", tests, load_shipped, NULL);
}

#define _DEFAULT_SOURCE /* mkdtemp */
/* The body-part labels of synth-depth (a classifier's training truth, see
 * docs/forest.md) on a real CMU clip (skipped without $CUB_DATA_DIR): every
 * labelled pixel is the body's and every body pixel is labelled; head above
 * chest above belly above thighs above feet; the sides named by the body's
 * own left, facing the camera and with its back to it; the dump writes one
 * label image beside each depth frame, equal to the render's. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "cub/kinect.h"
#include "cub/synth.h"
#include "synth_data.h"

#define W CUB_KINECT_WIDTH
#define H CUB_KINECT_HEIGHT
#define NPIX (W * H)

static const char *data_dir(void)
{
    return synth_data_dir("02_01");
}

/* 02_01: a CMU walk; yaw_deg turns the child. */
static cub_synth *open_walk(float yaw_deg)
{
    cub_synth_desc d = {.clean = 1, .seed = 1, .yaw_deg = yaw_deg, .pin = 1};
    d.data_dir = data_dir();
    cub_synth_segment seg = {.from_s = 0, .to_s = 1};
    snprintf(seg.clip, sizeof(seg.clip), "02_01");
    cub_synth *s = NULL;
    cub_diag diag;
    assert_int_equal(cub_synth_open(&d, &seg, 1, &s, &diag), CUB_OK);
    return s;
}

typedef struct part_stats {
    long n[CUB_PART_COUNT];
    double u[CUB_PART_COUNT], v[CUB_PART_COUNT]; /* mean column, row */
} part_stats;

static part_stats render_parts(cub_synth *s, int frame, uint8_t *part)
{
    static uint16_t raw[NPIX];
    static float depth[NPIX];
    static uint8_t owner[NPIX];
    assert_int_equal(cub_synth_render(s, frame, raw, NULL, depth, owner), CUB_OK);
    assert_int_equal(cub_synth_parts(s, part), CUB_OK);
    part_stats st = {0};
    for (int i = 0; i < NPIX; i++) {
        /* labelled exactly where the body is */
        assert_int_equal(part[i] != CUB_PART_NONE, owner[i] == 1);
        assert_true(part[i] < CUB_PART_COUNT);
        if (part[i]) assert_true(depth[i] > 0);
        st.n[part[i]]++;
        st.u[part[i]] += i % W;
        st.v[part[i]] += i / W;
    }
    for (int p = 0; p < CUB_PART_COUNT; p++)
        if (st.n[p]) st.u[p] /= st.n[p], st.v[p] /= st.n[p];
    return st;
}

static void labels_sit_on_the_body(void **state)
{
    (void)state;
    if (!data_dir()) skip();
    static uint8_t part[NPIX];
    int sides[2] = {0, 180};
    for (int k = 0; k < 2; k++) {
        cub_synth *s = open_walk((float)sides[k]);
        part_stats st = render_parts(s, 10, part);
        printf("synth parts (yaw %d): pixels", sides[k]);
        for (int p = 1; p < CUB_PART_COUNT; p++)
            printf(" %s %ld", cub_synth_part_name(p), st.n[p]);
        printf("\n");
        for (int p = 1; p < CUB_PART_COUNT; p++)
            assert_true(st.n[p] > 20); /* every part seen */
        int down[] = {CUB_PART_HEAD, CUB_PART_TORSO_UPPER, CUB_PART_TORSO_LOWER,
                      CUB_PART_THIGH_L, CUB_PART_SHIN_L, CUB_PART_FOOT_L};
        for (int i = 1; i < 6; i++)
            assert_true(st.v[down[i - 1]] < st.v[down[i]]);
        /* the body's left shows on the image's left facing the camera, on
         * its right with the back to the camera */
        double dl = st.u[CUB_PART_THIGH_R] - st.u[CUB_PART_THIGH_L];
        double dt = st.u[CUB_PART_UPPER_ARM_R] - st.u[CUB_PART_UPPER_ARM_L];
        assert_true(sides[k] ? dl < 0 && dt < 0 : dl > 0 && dt > 0);
        cub_synth_close(s);
    }
}

static void dump_writes_the_labels(void **state)
{
    (void)state;
    if (!data_dir()) skip();
    char dir[] = "/tmp/cub_parts_XXXXXX";
    assert_non_null(mkdtemp(dir));
    cub_synth *s = open_walk(0);
    cub_diag diag;
    assert_int_equal(cub_synth_write_dump(s, dir, 3, CUB_SYNTH_DUMP_PARTS, &diag), CUB_OK);
    static uint8_t want[NPIX], got[NPIX];
    render_parts(s, 2, want);
    char name[96], path[700], head[32];
    cub_synth_frame_name(2, 30, name, sizeof(name), NULL, NULL);
    snprintf(path, sizeof(path), "%s/p-%s", dir, name + 2);
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    assert_non_null(fgets(head, sizeof(head), f));
    assert_string_equal(head, "P5 640 480 255\n");
    assert_int_equal(fread(got, 1, NPIX, f), NPIX);
    fclose(f);
    assert_memory_equal(got, want, NPIX);
    cub_synth_close(s);
    char cmd[128];
    snprintf(cmd, sizeof(cmd), "rm -r %s", dir);
    assert_int_equal(system(cmd), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(labels_sit_on_the_body),
        cmocka_unit_test(dump_writes_the_labels),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

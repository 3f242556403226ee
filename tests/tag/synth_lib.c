/* The hand-made library of synth_lib.h. Angles are set in floating point
 * here (test set-up only) and stored as the firmware's Q2.30 quaternions. */
#include "synth_lib.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FPS 30
#define FRAME_NS 33333333u
#define PI 3.14159265358979

typedef struct spec {
    const char *name, *kind;
    int frames;
} spec;

static const spec SPECS[SYNTH_CLIPS] = {
    {"arms_up", "dance", 90},    {"right_wave", "dance", 90}, {"squat", "dance", 90},
    {"head_shake", "coach", 90}, {"idle", "coach", 60},
};

static cub_quat axis_deg(double x, double y, double z, double deg)
{
    cub_vec3 axis = {(cub_q16)lround(x * 65536), (cub_q16)lround(y * 65536),
                     (cub_q16)lround(z * 65536)};
    return cub_fx_quat_from_axis_angle(axis, (cub_q16)lround(deg * PI / 180.0 * 65536));
}

static void set_rot(const cub_skeleton *s, cub_pose *p, const char *joint, cub_quat q)
{
    int j = cub_motion_skeleton_find(s, joint);
    if (j >= 0) p->rot[j] = q;
}

/* Arm raise in degrees from hanging down (0) to straight up (180). */
static void arms(const cub_skeleton *s, cub_pose *p, double left_deg, double right_deg)
{
    set_rot(s, p, "LeftArm", axis_deg(0, 0, 1, left_deg - 90));
    set_rot(s, p, "RightArm", axis_deg(0, 0, 1, 90 - right_deg));
}

static void pose_at(const cub_skeleton *s, int clip, int f, int n, cub_pose *p)
{
    double t = (double)f / (n - 1), sec = (double)f / FPS;
    cub_motion_pose_rest(s, p);
    p->root_mm = (cub_vec3){0, CUB_Q16_INT(285), 0};
    arms(s, p, 5, 5);
    switch (clip) {
    case SYNTH_ARMS_UP: {
        double up = 170 * pow(sin(PI * t), 2);
        arms(s, p, 5 + up, 5 + up);
        break;
    }
    case SYNTH_RIGHT_WAVE: arms(s, p, 5, 5 + 85 * pow(sin(2 * PI * t), 2)); break;
    case SYNTH_SQUAT: {
        double bend = 70 * pow(sin(PI * t), 2), r = bend * PI / 180;
        set_rot(s, p, "LeftUpLeg", axis_deg(1, 0, 0, -bend));
        set_rot(s, p, "RightUpLeg", axis_deg(1, 0, 0, -bend));
        set_rot(s, p, "LeftLeg", axis_deg(1, 0, 0, 2 * bend));
        set_rot(s, p, "RightLeg", axis_deg(1, 0, 0, 2 * bend));
        /* thigh 125 + shin 115 mm: keep the feet on the floor. */
        p->root_mm.y = (cub_q16)lround((285 - 240 * (1 - cos(r))) * 65536);
        break;
    }
    case SYNTH_HEAD_SHAKE:
        if (f >= SYNTH_SHAKE_STILL && f < n - SYNTH_SHAKE_STILL)
            set_rot(s, p, "Head",
                    axis_deg(0, 1, 0, 40 * sin(2 * PI * 2.0 * (sec - SYNTH_SHAKE_STILL / 30.0))));
        break;
    case SYNTH_IDLE: arms(s, p, 5 + 3 * sin(2 * PI * t), 5 + 3 * sin(2 * PI * t)); break;
    }
}

int synth_library(cub_character *bear, cub_library *out)
{
    char path[1024];
    const char *src = getenv("CUB_SOURCE_DIR");
    cub_diag d = {0};
    snprintf(path, sizeof path, "%s/assets/bear/bear.xml", src ? src : ".");
    if (cub_character_load(path, bear, &d)) {
        char buf[600];
        fprintf(stderr, "synth: %s\n", cub_diag_str(&d, buf, sizeof buf));
        return -1;
    }
    memset(out, 0, sizeof *out);
    out->skel = bear->skel;
    out->clip_count = SYNTH_CLIPS;
    out->clips = calloc(SYNTH_CLIPS, sizeof *out->clips);
    size_t total = 0;
    for (int c = 0; c < SYNTH_CLIPS; c++)
        total += cub_motion_clip_mem_size(out->skel.joint_count, SPECS[c].frames, 0);
    out->mem = malloc(total);
    if (!out->clips || !out->mem) return -1;
    static cub_pose pose;
    char *mem = out->mem;
    for (int c = 0; c < SYNTH_CLIPS; c++) {
        cub_library_clip *lc = &out->clips[c];
        snprintf(lc->name, sizeof lc->name, "%s", SPECS[c].name);
        snprintf(lc->kind, sizeof lc->kind, "%s", SPECS[c].kind);
        size_t size = cub_motion_clip_mem_size(out->skel.joint_count, SPECS[c].frames, 0);
        if (cub_motion_clip_init(&lc->clip, &out->skel, SPECS[c].frames, FRAME_NS, 0, mem, size))
            return -1;
        mem += size;
        for (int f = 0; f < SPECS[c].frames; f++) {
            pose_at(&out->skel, c, f, SPECS[c].frames, &pose);
            if (cub_motion_clip_set_frame(&lc->clip, f, &pose)) return -1;
        }
    }
    return 0;
}

void synth_library_free(cub_library *lib)
{
    free(lib->clips);
    free(lib->mem);
    memset(lib, 0, sizeof *lib);
}

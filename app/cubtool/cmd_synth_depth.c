/* cubtool synth-depth: a synthetic child, rendered as a Kinect v1 would see
 * it, written as a fakenect dump plus truth.txt (see cub/synth.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "commands.h"
#include "cub/synth.h"

static void help(FILE *f)
{
    fprintf(f, "usage: cubtool synth-depth (--clip CLIP [--from S] [--to S] [--mirror] |\n"
               "                            --sequence FILE) --out DIR [options]\n"
               "\n"
               "Renders a child-sized body driven by mocap into Kinect v1 raw depth\n"
               "(640x480, 11-bit disparity, 2047 = no reading) and writes a fakenect dump:\n"
               "DIR/INDEX.txt, DIR/d-<time>-<timestamp>.pgm, each followed by the\n"
               "accelerometer (a-<time>-<timestamp>.dump, the camera's gravity) as\n"
               "fakenect-record writes it, and DIR/truth.txt with the true 20 joints per\n"
               "frame (camera space, mm, visibility; format in app/include/cub/synth.h).\n"
               "\n"
               "what the child does:\n"
               "  --clip CLIP          a .bvh or .amc file (its subject's .asf beside it), or a\n"
               "                       short name under DATA/mocap: 13_29, 141_16, 13_17, dab,\n"
               "                       jumping_jacks, jesse_dance, dataset-1_bye_childish_001 ...\n"
               "  --from S, --to S     seconds of the clip [0, its end]\n"
               "  --mirror             left <-> right (the wrong arm)\n"
               "  --sequence FILE      segments played one after another, blended over 0.3 s;\n"
               "                       one a line: `clip from_s to_s [mirror]` (to_s may be\n"
               "                       `end`); '#' starts a comment line\n"
               "  --track FILE         a joint track (cub/synth.h): a performance written by\n"
               "                       --write-track, rendered without its mocap\n"
               "  --write-track FILE   write the performance of --clip / --sequence as a joint\n"
               "                       track instead of rendering it (--out not needed)\n"
               "  --track-unit MM      the track's resolution [0.25]\n"
               "  --frames N           at most N frames of the performance [the whole clip or\n"
               "                       sequence] (after the prelude's)\n"
               "  --fps F              frames per second [30]\n"
               "\n"
               "the child:\n"
               "  --height MM          [1150]\n"
               "  --build B            slim | average | sturdy [average]\n"
               "  --loose              loose clothes: wider torso and thighs, a skirt hem\n"
               "  --loose-clothes      looser still: that, plus a loose shirt, wide sleeves and\n"
               "                       baggy trouser legs\n"
               "\n"
               "turning and travel (yaw: about the body's vertical axis, + = turned towards\n"
               "its left, 0 = facing the camera, 180 = its back to the camera):\n"
               "  --yaw DEG            the whole performance turned by DEG [0]\n"
               "  --spin DEG_PER_S     and the body keeps turning about its hips [0]\n"
               "  --yaw-segments S     every S seconds a new yaw in [-180, 180), drawn from\n"
               "                       --seed, turned to in 0.5 s (S >= 0.1) [off]\n"
               "  --start-yaw-max DEG  with --yaw-segments: the first yaw in [-DEG, DEG)\n"
               "                       instead (a child starts facing the TV: 45); the later\n"
               "                       yaws stay the seed's [180: any]\n"
               "  --max-travel MM      the clip's own travel about its mean spot is kept, softly\n"
               "                       clamped (tanh) to +-MM on each floor axis [not clamped]\n"
               "  --pin                no travel: the hips stay over one spot\n"
               "\n"
               "the scene:\n"
               "  --distance MM        from the camera to the child [2200]\n"
               "  --camera-height MM   above the floor [800]\n"
               "  --tilt DEG           camera pitch, + = up [0]; gravity goes in truth.txt\n"
               "  --room               a back wall, a sofa, a table and a plant\n"
               "  --second-person CLIP another person, driven by CLIP; its true joints go to\n"
               "                       DIR/truth_second.txt (eval-track tells who is who)\n"
               "  --second-mode MODE   behind: stands behind and beside the child [default];\n"
               "                       walk-in: walks in from the right (1 m/s, from 1 s) to\n"
               "                       that spot and stays; cross: walks across in front of\n"
               "                       the child (0.7 m nearer the camera), right to left,\n"
               "                       passing it mid-way; sibling: a child of similar height\n"
               "                       (+8 %%) beside the child where it starts (0.65 m to\n"
               "                       the side away from the image's centre)\n"
               "  --second-height MM   [1650; sibling: the child's + 8 %%]\n"
               "  --second-x MM, --second-dz MM   its offset right / farther [700, 900;\n"
               "                       cross: 0, -700; sibling: +-650 from the child's start,\n"
               "                       100]\n"
               "  --second-speed MM_S  walk-in and cross walk this fast [1000]\n"
               "  --prelude S          S seconds of the room before the child, as the box sees\n"
               "                       it in attract mode before START: the child not there,\n"
               "                       the second person standing (behind, sibling) or yet to\n"
               "                       walk in or cross; then the child is at its start spot\n"
               "                       and the performance begins (its clock starts then).\n"
               "                       Those frames have no line in the truth files [0]\n"
               "  --clean              no projector shadow, edge noise or holes\n"
               "                       (quantisation and the 0.5-4 m range stay)\n"
               "  --seed N             noise seed [1]; the same seed gives the same bytes\n"
               "  --parts              also DIR/p-<time>-<timestamp>.pgm beside each depth\n"
               "                       frame: 8-bit body-part labels of the clean render\n"
               "                       (0 none, 1 head ... 15 right foot: cub/synth.h)\n"
               "\n"
               "  --out DIR            the dump folder (created)\n"
               "  --data DIR           the shared data [$CUB_DATA_DIR or the build's default]\n"
               "  --help               this text\n"
               "\n"
               "example: cubtool synth-depth --clip 13_29 --from 0 --to 5 --out /tmp/synth_jj\n");
}

typedef struct opts {
    cub_synth_desc d;
    cub_synth_segment one;
    int have_clip;
    const char *sequence, *out, *track, *write_track;
    double track_unit;
    int frames, parts;
} opts;

static int num(const char *opt, const char *v, double lo, double hi, double *out)
{
    char *end;
    double x = v ? strtod(v, &end) : 0;
    if (!v || !*v || *end || !(x >= lo && x <= hi)) {
        fprintf(stderr, "synth-depth: %s needs a number in [%g, %g], got '%s'\n", opt, lo, hi,
                v ? v : "(nothing)");
        return 0;
    }
    *out = x;
    return 1;
}

static int second_mode(const char *v, int *mode)
{
    static const char *names[] = {"behind", "walk-in", "cross", "sibling"};
    for (int k = 0; k < 4; k++)
        if (!strcmp(v, names[k])) {
            *mode = k;
            return 1;
        }
    fprintf(stderr, "synth-depth: --second-mode is behind, walk-in, cross or sibling, not '%s'\n", v);
    return 0;
}

/* One option at argv[*i]; 0 on a usage error. */
static int parse_opt(opts *o, int argc, char **argv, int *i)
{
    const char *a = argv[*i], *v = *i + 1 < argc ? argv[*i + 1] : NULL;
    double x = 0;
    int used = 1, ok = 1;
    if (!strcmp(a, "--clip") && v) {
        snprintf(o->one.clip, sizeof(o->one.clip), "%s", v);
        o->have_clip = 1;
    } else if (!strcmp(a, "--from"))
        ok = num(a, v, 0, 1e6, &o->one.from_s);
    else if (!strcmp(a, "--to"))
        ok = num(a, v, 0, 1e6, &o->one.to_s);
    else if (!strcmp(a, "--sequence") && v)
        o->sequence = v;
    else if (!strcmp(a, "--out") && v)
        o->out = v;
    else if (!strcmp(a, "--track") && v)
        o->track = v;
    else if (!strcmp(a, "--write-track") && v)
        o->write_track = v;
    else if (!strcmp(a, "--track-unit"))
        ok = num(a, v, 0.001, 100, &o->track_unit);
    else if (!strcmp(a, "--data") && v)
        o->d.data_dir = v;
    else if (!strcmp(a, "--second-person") && v)
        o->d.second_clip = v;
    else if (!strcmp(a, "--second-mode") && v)
        ok = second_mode(v, &o->d.second_mode);
    else if (!strcmp(a, "--build") && v) {
        o->d.build = !strcmp(v, "slim")     ? CUB_SYNTH_SLIM
                     : !strcmp(v, "sturdy") ? CUB_SYNTH_STURDY
                                            : 0;
        ok = o->d.build || !strcmp(v, "average");
        if (!ok) fprintf(stderr, "synth-depth: --build is slim, average or sturdy, not '%s'\n", v);
    } else if (!strcmp(a, "--frames") && (ok = num(a, v, 1, 1e7, &x)))
        o->frames = (int)x;
    else if (!strcmp(a, "--fps") && (ok = num(a, v, 1, 120, &x)))
        o->d.fps = (float)x;
    else if (!strcmp(a, "--seed") && (ok = num(a, v, 0, 1e15, &x)))
        o->d.seed = (uint64_t)x;
    else if (!strcmp(a, "--height") && (ok = num(a, v, 600, 2200, &x)))
        o->d.height_mm = (float)x;
    else if (!strcmp(a, "--distance") && (ok = num(a, v, 300, 8000, &x)))
        o->d.distance_mm = (float)x;
    else if (!strcmp(a, "--camera-height") && (ok = num(a, v, 50, 3000, &x)))
        o->d.camera_height_mm = (float)x;
    else if (!strcmp(a, "--tilt") && (ok = num(a, v, -45, 45, &x)))
        o->d.tilt_deg = (float)x;
    else if (!strcmp(a, "--yaw") && (ok = num(a, v, -3600, 3600, &x)))
        o->d.yaw_deg = (float)x;
    else if (!strcmp(a, "--spin") && (ok = num(a, v, -1440, 1440, &x)))
        o->d.spin_deg_s = (float)x;
    else if (!strcmp(a, "--yaw-segments") && (ok = num(a, v, 0.1, 1e4, &x)))
        o->d.yaw_segment_s = (float)x;
    else if (!strcmp(a, "--start-yaw-max") && (ok = num(a, v, 0, 180, &x)))
        o->d.start_yaw_max_deg = (float)x;
    else if (!strcmp(a, "--max-travel") && (ok = num(a, v, 1, 10000, &x)))
        o->d.max_travel_mm = (float)x;
    else if (!strcmp(a, "--second-height") && (ok = num(a, v, 600, 2200, &x)))
        o->d.second_height_mm = (float)x;
    else if (!strcmp(a, "--second-x") && (ok = num(a, v, -5000, 5000, &x)))
        o->d.second_x_mm = (float)x;
    else if (!strcmp(a, "--second-dz") && (ok = num(a, v, -5000, 5000, &x)))
        o->d.second_dz_mm = (float)x;
    else if (!strcmp(a, "--second-speed") && (ok = num(a, v, 100, 5000, &x)))
        o->d.second_speed_mm_s = (float)x;
    else if (!strcmp(a, "--prelude") && (ok = num(a, v, 0, 600, &x)))
        o->d.prelude_s = (float)x;
    else {
        used = 0;
        if (!strcmp(a, "--mirror"))
            o->one.mirror = 1;
        else if (!strcmp(a, "--loose"))
            o->d.loose_clothes = 1;
        else if (!strcmp(a, "--loose-clothes"))
            o->d.loose_clothes = 2;
        else if (!strcmp(a, "--pin"))
            o->d.pin = 1;
        else if (!strcmp(a, "--room"))
            o->d.room = 1;
        else if (!strcmp(a, "--clean"))
            o->d.clean = 1;
        else if (!strcmp(a, "--parts"))
            o->parts = 1;
        else {
            /* not when a number was refused above: that said why */
            if (ok) fprintf(stderr, "synth-depth: unknown option or missing value: %s\n", a);
            return 0;
        }
    }
    *i += used;
    return ok;
}

static int load_sequence(const char *path, cub_synth_segment **segs, int *n)
{
    char *text, buf[600];
    size_t len;
    cub_diag diag;
    cub_text_src src = {path, "sequence", CUB_TEXT_MAX_TIMELINE};
    cub_err err = cub_text_read(&src, &text, &len, &diag);
    if (!err) {
        err = cub_synth_sequence_parse(text, len, path, segs, n, &diag);
        free(text);
    }
    if (err) fprintf(stderr, "synth-depth: %s\n", cub_diag_str(&diag, buf, sizeof(buf)));
    return !err;
}

static int fail(const cub_diag *diag)
{
    char buf[600];
    fprintf(stderr, "synth-depth: %s\n", cub_diag_str(diag, buf, sizeof(buf)));
    return 1;
}

static int check_opts(const opts *o)
{
    int sources = o->have_clip + !!o->sequence + !!o->track;
    if (sources != 1 || !(o->out || o->write_track) || (o->write_track && o->track)) {
        fprintf(stderr, "synth-depth: give one of --clip / --sequence / --track, and --out "
                        "(or --write-track with --clip / --sequence) (see --help)\n");
        return 0;
    }
    if (o->write_track && o->d.prelude_s > 0) {
        fprintf(stderr, "synth-depth: --prelude renders the room before the child; a joint track "
                        "(--write-track) has no room: leave one out\n");
        return 0;
    }
    if (o->d.second_mode && !o->d.second_clip) {
        fprintf(stderr, "synth-depth: --second-mode needs --second-person CLIP\n");
        return 0;
    }
    return 1;
}

/* The scene of o: its clips loaded, or its joint track (in *track). */
static int open_scene(opts *o, cub_synth_jtrack *track, cub_synth **s)
{
    cub_diag diag;
    cub_synth_segment *segs = &o->one;
    int n = 1;
    if (o->track) {
        if (cub_synth_jtrack_read(o->track, track, &diag)) return !fail(&diag);
        o->d.track = track;
        n = 0;
    } else if (o->sequence && !load_sequence(o->sequence, &segs, &n))
        return 0;
    cub_err err = cub_synth_open(&o->d, segs, n, s, &diag);
    if (segs != &o->one) free(segs);
    if (!err) return 1;
    cub_synth_jtrack_free(track);
    return !fail(&diag);
}

static int write_track(const opts *o, const cub_synth *s)
{
    char comment[600];
    cub_diag diag;
    snprintf(comment, sizeof(comment),
             "# cubtool synth-depth --write-track: the performance of %.500s\n",
             o->sequence ? o->sequence : o->one.clip);
    float unit = o->track_unit > 0 ? (float)o->track_unit : 0.25f;
    if (cub_synth_write_jtrack(s, o->write_track, unit, comment, &diag)) return fail(&diag);
    printf("synth-depth: %d frames -> %s (joint track, %g mm)\n", cub_synth_frame_count(s),
           o->write_track, unit);
    return 0;
}

int cub_cmd_synth_depth(int argc, char **argv)
{
    opts o = {.d = {.seed = 1}};
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            help(stdout);
            return 0;
        }
        if (!parse_opt(&o, argc, argv, &i)) return 2;
    }
    if (!check_opts(&o)) return 2;
    if (!o.d.data_dir)
        o.d.data_dir = getenv("CUB_DATA_DIR") ? getenv("CUB_DATA_DIR") : CUB_DATA_DIR_DEFAULT;
    cub_synth *s = NULL;
    cub_synth_jtrack track = {0};
    if (!open_scene(&o, &track, &s)) return 1;
    if (o.write_track) {
        int rc = write_track(&o, s);
        cub_synth_close(s);
        return rc;
    }
    int frames = cub_synth_frame_count(s);
    if (o.frames > 0 && o.frames < frames - cub_synth_prelude_frames(s))
        frames = cub_synth_prelude_frames(s) + o.frames;
    struct timespec t0, t1;
    cub_diag diag;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    cub_err err = cub_synth_write_dump(
        s, o.out, frames, CUB_SYNTH_DUMP_VERBOSE | (o.parts ? CUB_SYNTH_DUMP_PARTS : 0), &diag);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    cub_synth_close(s);
    cub_synth_jtrack_free(&track);
    if (err) return fail(&diag);
    double ms = (t1.tv_sec - t0.tv_sec) * 1e3 + (t1.tv_nsec - t0.tv_nsec) / 1e6;
    printf("synth-depth: %d frames -> %s (%.1f ms/frame)\n", frames, o.out,
           frames ? ms / frames : 0.0);
    return 0;
}

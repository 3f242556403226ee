/* cubtool retarget — a human clip (BVH, or ASF + AMC) onto the bear, written
 * as a BVH a person can open in any viewer. See cub/retarget.h. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "cub/character.h"
#include "cub/retarget.h"

static void usage(FILE *f)
{
    fprintf(f,
            "usage: cubtool retarget SRC.bvh --map FILE [options]\n"
            "       cubtool retarget SRC.asf SRC.amc --map FILE [options]\n"
            "\n"
            "Maps a human motion clip onto the bear and writes it as BVH (centimetres,\n"
            "30 fps): bone directions follow the source, the stride is scaled by the\n"
            "leg ratio, feet sit on the floor and are pinned during contacts.\n"
            "\n"
            "  --map FILE      mapping table (assets/retarget/cmu31.map, cmu_asf.map, ...)\n"
            "  --from S        start in the source, seconds (default 0)\n"
            "  --to S          end in the source, seconds (default: the end)\n"
            "  --out FILE      output BVH (default retarget.bvh)\n"
            "  --bear FILE     the character (default %s/bear/bear.xml)\n"
            "  --speed X       playback speed (default 1)\n"
            "  --mirror        swap left and right\n"
            "  --turn DEG      extra turn about the vertical after facing the viewer\n"
            "  --sheet FILE    also write a PNG contact sheet (front and side views)\n"
            "  --help          this text\n"
            "\n"
            "Prints one line of figures on stdout: frames, leg ratio, contacts, foot slide.\n",
            CUB_ASSETS_DIR);
}

typedef struct retarget_args {
    const char *src, *amc, *map, *out, *bear, *sheet;
    cub_retarget_desc desc;
} retarget_args;

static int number(const char *s, double *out)
{
    char *e = NULL;
    *out = strtod(s, &e);
    return e != s && !*e;
}

/* 0 ok, 1 help shown, 2 bad usage. */
static int parse_args(int argc, char **argv, retarget_args *a)
{
    memset(a, 0, sizeof(*a));
    a->out = "retarget.bvh";
    a->bear = CUB_ASSETS_DIR "/bear/bear.xml";
    for (int i = 1; i < argc; i++) {
        const char *o = argv[i];
        int has = i + 1 < argc;
        double *num = !strcmp(o, "--from")    ? &a->desc.start_s
                      : !strcmp(o, "--to")    ? &a->desc.end_s
                      : !strcmp(o, "--speed") ? &a->desc.speed
                      : !strcmp(o, "--turn")  ? &a->desc.turn_deg
                                              : NULL;
        const char **str = !strcmp(o, "--map")     ? &a->map
                           : !strcmp(o, "--out")   ? &a->out
                           : !strcmp(o, "--bear")  ? &a->bear
                           : !strcmp(o, "--sheet") ? &a->sheet
                                                   : NULL;
        if (!strcmp(o, "--help") || !strcmp(o, "-h")) {
            usage(stdout);
            return 1;
        } else if (!strcmp(o, "--mirror")) {
            a->desc.mirror = 1;
        } else if (num && has) {
            if (!number(argv[++i], num)) {
                fprintf(stderr, "cubtool retarget: %s needs a number, got '%s'\n", o, argv[i]);
                return 2;
            }
        } else if (str && has) {
            *str = argv[++i];
        } else if (o[0] == '-' || (a->src && a->amc)) {
            fprintf(stderr, "cubtool retarget: unexpected '%s'\n", o);
            return 2;
        } else if (!a->src) {
            a->src = o;
        } else {
            a->amc = o;
        }
    }
    size_t n = a->src ? strlen(a->src) : 0;
    int is_asf = n > 4 && !strcmp(a->src + n - 4, ".asf");
    if (!a->src || !a->map || (is_asf && !a->amc) || (!is_asf && a->amc)) {
        fprintf(stderr, "cubtool retarget: need SRC.bvh (or SRC.asf SRC.amc) and --map\n");
        usage(stderr);
        return 2;
    }
    return 0;
}

static int fail(const char *what, const cub_diag *d)
{
    char buf[600];
    fprintf(stderr, "cubtool retarget: %s: %s\n", what, cub_diag_str(d, buf, sizeof(buf)));
    return 1;
}

static int run(const retarget_args *a, cub_character *bear, cub_retarget_map *map)
{
    cub_diag d;
    memset(&d, 0, sizeof(d));
    cub_io_motion src, out;
    memset(&src, 0, sizeof(src));
    memset(&out, 0, sizeof(out));
    if (cub_character_load(a->bear, bear, &d))
        return fail("bear", &d);
    if (cub_retarget_map_load(a->map, map, &d))
        return fail("map", &d);
    fprintf(stderr, "cubtool retarget: reading %s\n", a->src);
    if (cub_retarget_load_source(a->src, a->amc, &src, &d))
        return fail("source", &d);
    cub_retarget_report rep;
    cub_retarget_desc desc = a->desc;
    desc.name = a->src;
    int rc = 1;
    if (cub_retarget_map_bind(map, &bear->skel, &src.skel, &d))
        fail("map", &d);
    else if (cub_retarget_clip(map, &bear->skel, &src.clip, &desc, &out, &rep, &d))
        fail("retarget", &d);
    else if (cub_io_save_bvh(a->out, &out, &d))
        fail("write", &d);
    else if (a->sheet && cub_retarget_sheet_png(a->sheet, &out.clip, 8))
        fprintf(stderr, "cubtool retarget: cannot write %s\n", a->sheet);
    else
        rc = 0;
    if (!rc)
        printf("retarget: %s frames=%d leg_ratio=%.4f yaw_deg=%.1f contacts=%d/%d "
               "contact_ankle_mm=%.1f slide_mean_mm=%.3f slide_max_mm=%.3f max_ang_deg=%.1f\n",
               a->out, rep.frames, rep.leg_ratio, rep.yaw_deg, rep.contact_frames[0],
               rep.contact_frames[1], rep.contact_ankle_mm, rep.slide_mean_mm, rep.slide_max_mm,
               rep.max_ang_deg);
    cub_io_motion_free(&src);
    cub_io_motion_free(&out);
    return rc;
}

int cub_cmd_retarget(int argc, char **argv)
{
    retarget_args a;
    int rc = parse_args(argc, argv, &a);
    if (rc)
        return rc == 1 ? 0 : 2;
    /* Big structs on the heap: a skeleton is ~6 KB, a map ~40 KB. */
    cub_character *bear = calloc(1, sizeof(*bear));
    cub_retarget_map *map = calloc(1, sizeof(*map));
    rc = bear && map ? run(&a, bear, map) : 1;
    free(bear);
    free(map);
    return rc;
}

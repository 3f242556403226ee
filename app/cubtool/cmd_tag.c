/* cubtool tag — tag the bridge frames of a clip library (SEEDS.md § 000),
 * write the tag file, print a summary and draw a contact sheet per clip.
 *
 *   cubtool tag [--library FILE] [--character FILE] [--out TAGS.xml]
 *               [--sheets DIR] [--threshold D]
 *
 * Progress goes to stderr; the summary to stdout: clips, frames, bridge
 * frames per clip, links, the ordered clip pairs with no direct bridge (and
 * the chain that joins them, if any), and the dance pairs no chain joins
 * (there must be none for the shipped library). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "tool_util.h"
#include "cub/board.h"
#include "cub/character.h"
#include "cub/pack.h"
#include "cub/png.h"
#include "cub/render.h"
#include "cub/tags.h"

#define TILE_W 160
#define TILE_H 200
#define SHEET_COLS 8
#define BEAR_VIEW_MM 1100.0f /* the bear stands about 0.95 m tall */

typedef struct options {
    const char *library, *character, *out, *sheets;
    double threshold;
} options;

static void usage(FILE *f)
{
    fprintf(f,
            "usage: cubtool tag [--library FILE] [--character FILE] [--out TAGS.xml]\n"
            "                   [--sheets DIR] [--threshold D]\n\n"
            "Tags the bridge frames of a clip library (SEEDS.md § 000, three steps) with\n"
            "the firmware's fixed-point fuzzy features, links every ordered clip pair,\n"
            "and prints a summary.\n\n"
            "  --library FILE    the clip library (default %s/clips/bear.cubclips)\n"
            "  --character FILE  whose fuzzy body to use (default %s/bear/bear.xml)\n"
            "  --out TAGS.xml    write the tag file (schema: README, \"Bridge tags (XML)\")\n"
            "  --sheets DIR      write DIR/contact_<clip>.png: each clip's bridge frames\n"
            "  --threshold D     switch threshold on d, in (0, 1] (default 0.4)\n",
            CUB_ASSETS_DIR, CUB_ASSETS_DIR);
}

static int parse_options(int argc, char **argv, options *o)
{
    *o = (options){CUB_ASSETS_DIR "/clips/bear.cubclips", CUB_ASSETS_DIR "/bear/bear.xml", NULL,
                   NULL, 0.0};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return 0;
        }
        const char **slot = !strcmp(a, "--library")     ? &o->library
                            : !strcmp(a, "--character") ? &o->character
                            : !strcmp(a, "--out")       ? &o->out
                            : !strcmp(a, "--sheets")    ? &o->sheets
                                                        : NULL;
        int is_thr = !strcmp(a, "--threshold");
        if (!slot && !is_thr) {
            fprintf(stderr, "cubtool tag: unknown option '%s'\n", a);
            usage(stderr);
            return 2;
        }
        if (i + 1 >= argc) {
            fprintf(stderr, "cubtool tag: %s needs a value\n", a);
            return 2;
        }
        if (slot) {
            *slot = argv[++i];
            continue;
        }
        char *end = NULL;
        o->threshold = strtod(argv[++i], &end);
        if (!end || *end || !(o->threshold > 0.0 && o->threshold <= 1.0)) {
            fprintf(stderr, "cubtool tag: --threshold '%s' is not a number in (0, 1]\n", argv[i]);
            return 2;
        }
    }
    return -1;
}

static void progress(void *user, const char *step, int done, int total)
{
    const cub_library *lib = user;
    if (done < total && lib && done < lib->clip_count && strcmp(step, "bridges") != 0)
        fprintf(stderr, "tag: %s %d/%d %s\n", step, done + 1, total, lib->clips[done].name);
    else if (done < total)
        fprintf(stderr, "tag: %s\n", step);
}

static const char *base_name(const char *path)
{
    const char *s = strrchr(path, '/');
    return s ? s + 1 : path;
}

/* ---- summary ------------------------------------------------------------ */

static void print_summary(const cub_library *lib, const cub_tags *t)
{
    int n = t->clip_count;
    long frames = 0, bridges = 0, links = 0;
    for (int c = 0; c < n; c++) {
        frames += t->clips[c].frame_count;
        bridges += t->clips[c].bridge_count;
    }
    for (int i = 0; i < n * n; i++)
        links += t->pairs[i].link_count;
    printf("tag: library=%s clips=%d frames=%ld bridge_frames=%ld links=%ld threshold=%.3f\n",
           t->library, n, frames, bridges, links, t->params.fuzzy.threshold / 65536.0);
    for (int c = 0; c < n; c++) {
        int out_pairs = 0;
        for (int to = 0; to < n; to++)
            out_pairs += t->pairs[c * n + to].link_count > 0;
        printf("tag: clip %-16s kind=%-5s frames=%4d bridges=%3d linked_to=%d/%d\n",
               t->clips[c].name, lib->clips[c].kind, t->clips[c].frame_count,
               t->clips[c].bridge_count, out_pairs, n);
    }
    int direct = 0, chained = 0, none = 0, dance_pairs = 0, dance_unreachable = 0;
    for (int a = 0; a < n; a++)
        for (int b = 0; b < n; b++) {
            int len = cub_tags_chain_length(t, a, b);
            int dance =
                !strcmp(lib->clips[a].kind, "dance") && !strcmp(lib->clips[b].kind, "dance");
            direct += len == 1;
            chained += len > 1;
            none += len < 0;
            if (dance && a != b) {
                dance_pairs++;
                dance_unreachable += len < 0;
            }
            if (len > 1)
                printf("tag: no direct bridge %s -> %s: chain of %d\n", t->clips[a].name,
                       t->clips[b].name, len);
            else if (len < 0)
                printf("tag: no direct bridge %s -> %s: unreachable\n", t->clips[a].name,
                       t->clips[b].name);
        }
    printf("tag: ordered pairs=%d direct=%d chained=%d unreachable=%d\n", n * n, direct, chained,
           none);
    printf("tag: dance pairs=%d unreachable=%d\n", dance_pairs, dance_unreachable);
}

/* ---- contact sheets ----------------------------------------------------- */

typedef struct sheet_ctx {
    cub_board *board;
    cub_render *render;
    uint8_t *tile;
} sheet_ctx;

static cub_err draw_frame(sheet_ctx *s, const cub_clip *clip, int frame)
{
    static cub_pose pose;
    static cub_vec3 world[CUB_MOTION_MAX_JOINTS];
    static float xyz[3 * CUB_MOTION_MAX_JOINTS];
    cub_err e = cub_motion_clip_get_frame(clip, frame, &pose);
    if (!e) e = cub_motion_forward(clip->skel, &pose, world, NULL);
    if (e) return e;
    cub_motion_world_to_float(world, clip->skel->joint_count, xyz);
    cub_render_scene scene = {.skel = clip->skel, .world_xyz_mm = xyz};
    e = cub_render_frame(s->render, &scene);
    if (!e) e = cub_board_display_read_rgba(s->board, s->tile, (size_t)TILE_W * TILE_H * 4);
    cub_board_display_swap(s->board);
    return e;
}

static cub_err write_sheet(sheet_ctx *s, const cub_clip *clip, const cub_tag_clip *tc,
                           const char *path)
{
    int count = tc->bridge_count ? tc->bridge_count : 1;
    int cols = count < SHEET_COLS ? count : SHEET_COLS, rows = (count + cols - 1) / cols;
    int w = cols * TILE_W, h = rows * TILE_H;
    uint8_t *sheet = calloc((size_t)w * (size_t)h, 4);
    if (!sheet) return CUB_ERR_NOMEM;
    memset(sheet, 255, (size_t)w * (size_t)h * 4);
    cub_err e = CUB_OK;
    for (int i = 0; !e && i < tc->bridge_count; i++) {
        e = draw_frame(s, clip, tc->bridges[i].frame);
        int x0 = (i % cols) * TILE_W, y0 = (i / cols) * TILE_H;
        for (int y = 0; !e && y < TILE_H; y++) {
            memcpy(sheet + ((size_t)(y0 + y) * (size_t)w + (size_t)x0) * 4,
                   s->tile + (size_t)y * TILE_W * 4, TILE_W * 4);
            /* A white rule between tiles. */
            memset(sheet + ((size_t)(y0 + y) * (size_t)w + (size_t)x0) * 4, 255, 4);
        }
        memset(sheet + (size_t)y0 * (size_t)w * 4 + (size_t)x0 * 4, 255, TILE_W * 4);
    }
    if (!e) e = cub_png_write(path, sheet, w, h);
    free(sheet);
    return e;
}

static int write_sheets(const cub_library *lib, const cub_tags *t, const char *dir)
{
    sheet_ctx s = {0};
    char msg[512] = "";
    cub_board_desc desc = {.display = CUB_DISPLAY_HEADLESS,
                           .width = TILE_W,
                           .height = TILE_H,
                           .depth = CUB_DEPTH_OFF,
                           .audio_driver = "dummy"};
    if (cub_board_open(&desc, &s.board, msg, sizeof msg)) {
        fprintf(stderr, "cubtool tag: no headless display for the contact sheets: %s\n", msg);
        return 1;
    }
    cub_render_desc rd = {.width = TILE_W, .height = TILE_H, .figure_height_mm = BEAR_VIEW_MM};
    s.tile = malloc((size_t)TILE_W * TILE_H * 4);
    int rc = !s.tile || cub_render_create(&rd, &s.render) ? 1 : 0;
    for (int c = 0; !rc && c < t->clip_count; c++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/contact_%s.png", dir, t->clips[c].name);
        cub_err e = write_sheet(&s, &lib->clips[c].clip, &t->clips[c], path);
        if (e) {
            fprintf(stderr, "cubtool tag: %s: %s\n", path, cub_err_str(e));
            rc = 1;
        } else {
            fprintf(stderr, "tag: wrote %s (%d bridge frames)\n", path, t->clips[c].bridge_count);
        }
    }
    if (s.render) cub_render_destroy(s.render);
    free(s.tile);
    cub_board_close(s.board);
    return rc;
}

/* ---- the command -------------------------------------------------------- */

static int fail_diag(const char *what, cub_err e, const cub_diag *d)
{
    char buf[600];
    fprintf(stderr, "cubtool tag: %s: %s\n", what,
            d->msg[0] ? cub_diag_str(d, buf, sizeof buf) : cub_err_str(e));
    return 1;
}

int cub_cmd_tag(int argc, char **argv)
{
    options o;
    int rc = parse_options(argc, argv, &o);
    if (rc >= 0) return rc;
    static cub_character ch;
    cub_library lib = {0};
    cub_diag d = {0};
    cub_err e = cub_character_load(o.character, &ch, &d);
    if (e) return fail_diag("character", e, &d);
    e = cub_pack_read(o.library, &lib, &d);
    if (e) return fail_diag("library", e, &d);
    cub_fuzzy_body body;
    e = cub_tag_map_body(&ch.skel, &ch.body, &lib.skel, &body, &d);
    if (e) {
        snprintf(d.file, sizeof d.file, "%s", o.library);
        cub_library_free(&lib);
        return fail_diag("library", e, &d);
    }
    cub_tag_params p = {0};
    p.fuzzy.threshold = (cub_q16)floor(o.threshold * 65536.0 + 0.5);
    cub_tags tags;
    e = cub_tag_library(&lib, base_name(o.library), &body, &p, &tags, progress, &lib);
    if (e) {
        fprintf(stderr, "cubtool tag: tagging %s failed: %s\n", o.library, cub_err_str(e));
        cub_library_free(&lib);
        return 1;
    }
    print_summary(&lib, &tags);
    rc = 0;
    if (o.out) {
        e = cub_tags_write(o.out, &tags, &d);
        if (e)
            rc = fail_diag("writing tags", e, &d);
        else
            fprintf(stderr, "tag: wrote %s\n", o.out);
    }
    if (!rc && o.sheets)
        rc = cub_tool_make_dir(o.sheets, "cubtool tag") ? 1 : write_sheets(&lib, &tags, o.sheets);
    cub_tags_free(&tags);
    cub_library_free(&lib);
    return rc;
}

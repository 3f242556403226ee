/* groove_png — cubtool groove --png: the first seconds of a song's motion
 * drawn against its notes (see groove_tool.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cub/png.h"
#include "groove_tool.h"

#define W 1000
#define H 760
#define SPAN_US 8000000 /* 8 seconds from the melody's first note */

static int64_t start_us; /* the melody's first note */
#define STEP_US 5000

static const uint8_t INK[3] = {30, 30, 30}, GREY[3] = {200, 200, 200}, RED[3] = {210, 40, 40},
                     BLUE[3] = {40, 90, 200}, GREEN[3] = {40, 150, 70};

typedef struct box {
    int x, y, w, h;
    double x0, x1, y0, y1; /* data ranges */
} box;

static double px(const box *b, double v)
{
    return b->x + (v - b->x0) / (b->x1 - b->x0) * b->w;
}

static double py(const box *b, double v)
{
    return b->y + b->h - (v - b->y0) / (b->y1 - b->y0) * b->h;
}

static void line(cub_png_canvas *c, const box *b, const double d[4], const uint8_t rgb[3])
{
    const double xy[4] = {px(b, d[0]), py(b, d[1]), px(b, d[2]), py(b, d[3])};
    cub_png_line(c, xy, 0, rgb);
}

static int last_note(const cub_groove_plan *p)
{
    int i = 0;
    while (i + 1 < p->n && p->notes[i + 1].start_us <= start_us + SPAN_US)
        i++;
    return i;
}

/* The wrist's path in key space, its keys (beats red) and handles. */
static void draw_path(cub_png_canvas *c, const cub_groove_plan *p)
{
    box b = {40, 30, 600, 300, 1e9, -1e9, 1e9, -1e9};
    int last = last_note(p);
    for (int64_t t = start_us; t <= p->notes[last].start_us; t += STEP_US) {
        cub_groove_key k = cub_groove_wrist_at(p, t);
        double x = k.x_mm / 65536.0, y = k.y_mm / 65536.0;
        b.x0 = x < b.x0 ? x : b.x0, b.x1 = x > b.x1 ? x : b.x1;
        b.y0 = y < b.y0 ? y : b.y0, b.y1 = y > b.y1 ? y : b.y1;
    }
    b.x0 -= 20, b.x1 += 20, b.y0 -= 20, b.y1 += 20;
    cub_png_text(c, 40, 8, 2, "WRIST PATH (KEY SPACE, MM)", INK);
    cub_groove_key prev = cub_groove_wrist_at(p, start_us);
    for (int64_t t = start_us + STEP_US; t <= p->notes[last].start_us; t += STEP_US) {
        cub_groove_key k = cub_groove_wrist_at(p, t);
        const double d[4] = {prev.x_mm / 65536.0, prev.y_mm / 65536.0, k.x_mm / 65536.0,
                             k.y_mm / 65536.0};
        line(c, &b, d, INK);
        prev = k;
    }
    for (int i = 0; i <= last; i++) {
        cub_groove_key k = p->keys[i];
        cub_png_dot(c, (int)px(&b, k.x_mm / 65536.0), (int)py(&b, k.y_mm / 65536.0), 4,
                    p->notes[i].is_beat ? RED : BLUE);
    }
}

/* Against time: the notes, the beats, each path's timing curve, the speed. */
static void draw_time(cub_png_canvas *c, const groove_song *s)
{
    const cub_groove_plan *p = &s->plan;
    double end = (double)(start_us + SPAN_US);
    box notes = {40, 380, 920, 110, (double)start_us, end, 30, 100};
    box curve = {40, 510, 920, 100, (double)start_us, end, 0, 1};
    box speed = {40, 630, 920, 100, (double)start_us, end, 0, 1500};
    cub_png_text(c, 40, 356, 2, "NOTES (BEATS RED), METER BEATS, TIMING CURVES, WRIST SPEED", INK);
    int nb = 0;
    int64_t *beats = groove_beats_us(&s->midi.song, &nb);
    for (int i = 0; beats && i < nb && beats[i] <= start_us + SPAN_US; i++) {
        if (beats[i] < start_us) continue;
        const double xy[4] = {px(&notes, beats[i]), 380, px(&notes, beats[i]), 730};
        cub_png_line(c, xy, 0, GREY);
    }
    free(beats);
    int last = last_note(p);
    for (int i = 0; i <= last && i + 1 < p->n; i++) {
        double t0 = p->notes[i].start_us, t1 = p->notes[i + 1].start_us;
        if (p->notes[i].pitch != CUB_GROOVE_REST) {
            const double d[4] = {t0, p->notes[i].pitch, t1, p->notes[i].pitch};
            const double xy[4] = {px(&notes, d[0]), py(&notes, d[1]), px(&notes, d[2]),
                                  py(&notes, d[3])};
            cub_png_line(c, xy, 2, p->notes[i].is_beat ? RED : BLUE);
        }
        cub_groove_timing kind = cub_groove_timing_of(p->notes, i);
        for (int k = 0; k < 40; k++) {
            double a = k / 40.0, z = (k + 1) / 40.0;
            const double d[4] = {
                t0 + a * (t1 - t0), cub_groove_timing_at(kind, (cub_q16)(a * 65536)) / 65536.0,
                t0 + z * (t1 - t0), cub_groove_timing_at(kind, (cub_q16)(z * 65536)) / 65536.0};
            line(c, &curve, d, kind == CUB_GROOVE_ACCENT ? RED : GREEN);
        }
    }
    cub_groove_key prev = cub_groove_wrist_at(p, start_us);
    double prev_v = 0;
    for (int64_t t = start_us + STEP_US; t <= start_us + SPAN_US; t += STEP_US) {
        cub_groove_key k = cub_groove_wrist_at(p, t);
        double dx = (k.x_mm - prev.x_mm) / 65536.0, dy = (k.y_mm - prev.y_mm) / 65536.0;
        double v = sqrt(dx * dx + dy * dy) / (STEP_US / 1e6);
        const double d[4] = {(double)(t - STEP_US), prev_v, (double)t, v};
        line(c, &speed, d, INK);
        prev = k, prev_v = v;
    }
}

int groove_png(const groove_song *s, const char *path)
{
    cub_png_canvas c = {calloc((size_t)W * H, 4), W, H};
    if (!c.px) return 1;
    for (size_t i = 0; i < (size_t)W * H; i++)
        c.px[4 * i] = c.px[4 * i + 1] = c.px[4 * i + 2] = c.px[4 * i + 3] = 255;
    start_us = s->plan.notes[0].start_us;
    draw_path(&c, &s->plan);
    draw_time(&c, s);
    cub_err e = cub_png_write(path, c.px, W, H);
    free(c.px);
    if (e)
        fprintf(stderr, "cubtool groove: cannot write %s (%s)\n", path, cub_err_str(e));
    else
        printf("png %s\n", path);
    return e != CUB_OK;
}

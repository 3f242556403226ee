/* play_keys — one small handler per key (see play_keys.h). */
#include "play_keys.h"

#include <math.h>

#include "cub/keyscript.h"

#define MOVE_STEP_MM 100.0f
#define YAW_STEP_DEG 10.0f
#define PITCH_STEP_DEG 5.0f
#define PITCH_MAX_DEG 85.0f
#define ZOOM_STEP 1.1f
#define SPEED_STEP 1.25
#define SIZE_STEP 1.1f
#define FLOOR_STEP 1.25f
#define FLOOR_DEFAULT_MM 6000.0f
#define PITCH_DEFAULT_DEG 15.0f

void play_view_init(play_view *v, int count)
{
    *v = (play_view){.count = count,
                     .floor_mm = FLOOR_DEFAULT_MM,
                     .pitch_deg = PITCH_DEFAULT_DEG,
                     .zoom = 1.0f,
                     .speed = 1.0};
    for (int i = 0; i < PLAY_MAX_CHARACTERS; i++)
        v->size[i] = 1.0f;
}

static float clampf(float x, float lo, float hi)
{
    return x < lo ? lo : x > hi ? hi : x;
}

static void select_next(play_view *v)
{
    v->selected = (v->selected + 1) % v->count;
}
static void select_first(play_view *v)
{
    v->selected = 0;
}
static void select_second(play_view *v)
{
    v->selected = v->count > 1 ? 1 : 0;
}
static void move_away(play_view *v)
{
    v->move_mm[v->selected][1] -= MOVE_STEP_MM;
}
static void move_near(play_view *v)
{
    v->move_mm[v->selected][1] += MOVE_STEP_MM;
}
static void move_left(play_view *v)
{
    v->move_mm[v->selected][0] -= MOVE_STEP_MM;
}
static void move_right(play_view *v)
{
    v->move_mm[v->selected][0] += MOVE_STEP_MM;
}
static void camera_up(play_view *v)
{
    v->pitch_deg = clampf(v->pitch_deg + PITCH_STEP_DEG, -PITCH_MAX_DEG, PITCH_MAX_DEG);
}
static void camera_down(play_view *v)
{
    v->pitch_deg = clampf(v->pitch_deg - PITCH_STEP_DEG, -PITCH_MAX_DEG, PITCH_MAX_DEG);
}
static void camera_left(play_view *v)
{
    v->yaw_deg = fmodf(v->yaw_deg - YAW_STEP_DEG, 360.0f);
}
static void camera_right(play_view *v)
{
    v->yaw_deg = fmodf(v->yaw_deg + YAW_STEP_DEG, 360.0f);
}
static void zoom_in(play_view *v)
{
    v->zoom = clampf(v->zoom * ZOOM_STEP, 0.1f, 10.0f);
}
static void zoom_out(play_view *v)
{
    v->zoom = clampf(v->zoom / ZOOM_STEP, 0.1f, 10.0f);
}
static void toggle_points(play_view *v)
{
    v->points = !v->points;
}
static void faster(play_view *v)
{
    v->speed = fmin(v->speed * SPEED_STEP, 100.0);
}
static void slower(play_view *v)
{
    v->speed = fmax(v->speed / SPEED_STEP, 0.01);
}
static void smaller(play_view *v)
{
    v->size[v->selected] = clampf(v->size[v->selected] / SIZE_STEP, 0.1f, 10.0f);
}
static void larger(play_view *v)
{
    v->size[v->selected] = clampf(v->size[v->selected] * SIZE_STEP, 0.1f, 10.0f);
}
static void floor_smaller(play_view *v)
{
    v->floor_mm = clampf(v->floor_mm / FLOOR_STEP, 1000.0f, 100000.0f);
}
static void floor_larger(play_view *v)
{
    v->floor_mm = clampf(v->floor_mm * FLOOR_STEP, 1000.0f, 100000.0f);
}
static void pause_toggle(play_view *v)
{
    v->paused = !v->paused;
}
static void camera_reset(play_view *v)
{
    v->yaw_deg = 0.0f, v->pitch_deg = PITCH_DEFAULT_DEG, v->zoom = 1.0f;
}

static const struct {
    int key;
    void (*run)(play_view *v);
    const char *keys, *help; /* keys: set on the first of a group, for --help */
} HANDLERS[] = {
    {CUB_KEY_TAB, select_next, "Tab 1 2", "select the next / the first / the second character"},
    {'1', select_first, NULL, NULL},
    {'2', select_second, NULL, NULL},
    {'I', move_away, "I J K L", "move the selected character away / left / nearer / right (10 cm)"},
    {'J', move_left, NULL, NULL},
    {'K', move_near, NULL, NULL},
    {'L', move_right, NULL, NULL},
    {'W', camera_up, "W A S D", "camera: orbit up / left / down / right"},
    {'A', camera_left, NULL, NULL},
    {'S', camera_down, NULL, NULL},
    {'D', camera_right, NULL, NULL},
    {CUB_KEY_UP, zoom_in, "Up Down", "zoom in / out (PageUp / PageDown too)"},
    {CUB_KEY_DOWN, zoom_out, NULL, NULL},
    {CUB_KEY_PAGEUP, zoom_in, NULL, NULL},
    {CUB_KEY_PAGEDOWN, zoom_out, NULL, NULL},
    {'N', toggle_points, "N", "sticks / points with bone numbers"},
    {CUB_KEY_PLUS, faster, "+ -", "playback speed up / down (x1.25)"},
    {CUB_KEY_MINUS, slower, NULL, NULL},
    {'C', smaller, "C V", "the selected character smaller / larger (x1.1)"},
    {'V', larger, NULL, NULL},
    {'F', floor_smaller, "F G", "the floor smaller / larger (x1.25)"},
    {'G', floor_larger, NULL, NULL},
    {CUB_KEY_SPACE, pause_toggle, "Space", "pause / play"},
    {CUB_KEY_HOME, camera_reset, "Home", "reset the camera"},
};
#define HANDLER_COUNT ((int)(sizeof HANDLERS / sizeof HANDLERS[0]))

play_key_result play_key(play_view *v, int key)
{
    if (key == CUB_KEY_ESC) return PLAY_KEY_QUIT;
    for (int i = 0; i < HANDLER_COUNT; i++)
        if (HANDLERS[i].key == key) {
            HANDLERS[i].run(v);
            return PLAY_KEY_DONE;
        }
    return PLAY_KEY_UNUSED;
}

void play_keys_help(FILE *f)
{
    for (int i = 0; i < HANDLER_COUNT; i++)
        if (HANDLERS[i].keys) fprintf(f, "  %-9s %s\n", HANDLERS[i].keys, HANDLERS[i].help);
    fprintf(f, "  %-9s %s\n", "Esc", "quit");
}

void play_view_print(const play_view *v, FILE *f)
{
    fprintf(f, "selected=%d", v->selected + 1);
    for (int i = 0; i < v->count; i++)
        fprintf(f, " move%d=%.0f,%.0f size%d=%.3f", i + 1, v->move_mm[i][0], v->move_mm[i][1],
                i + 1, v->size[i]);
    fprintf(f, " floor=%.0f yaw=%.0f pitch=%.0f zoom=%.3f speed=%.3f %s%s\n", v->floor_mm,
            v->yaw_deg, v->pitch_deg, v->zoom, v->speed, v->points ? "points" : "sticks",
            v->paused ? " paused" : "");
}

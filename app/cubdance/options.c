/* The command line: every option documented in usage(), parsed by hand so
 * that each error can say which option and why. */
#include "options.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

#ifndef CUB_VOICE_PATH
#define CUB_VOICE_PATH "voice/bear.cubvoice"
#endif
#ifndef CUB_ASSETS_DIR
#define CUB_ASSETS_DIR "assets"
#endif
#ifndef CUB_VERSION
#define CUB_VERSION "0"
#endif

static void usage(FILE *f, const char *prog)
{
    fprintf(f,
"usage: %s [options]\n"
"\n"
"cubdance, the dancing-bear coach. Waits for START, plays the coach's clip,\n"
"shows the Kinect depth image small in a corner; STOP returns to waiting.\n"
"\n"
"Display\n"
"  --window               an SDL2 window (KMSDRM full screen on the box)\n"
"  --headless             no window: render off-screen with EGL (surfaceless)\n"
"                         (default: a window if a display exists, else headless)\n"
"  --size WxH             display size in pixels (default 1280x720)\n"
"  --frames DIR           write rendered frames as PNG files into DIR\n"
"  --frame-every N        write every Nth tick's frame (default 30 = 1 per second)\n"
"  --draw-every N         headless: draw only every Nth tick (default 1); the\n"
"                         event log is the same, the renderer decides nothing.\n"
"                         For slow emulated GL; --frame-every must be a multiple\n"
"  --font PATH            the TrueType font of the text on the TV (default the\n"
"                         config's font, else DejaVu Sans Bold of fonts-dejavu-core)\n"
"\n"
"Depth camera\n"
"  --replay DIR           replay a fakenect dump (INDEX.txt + d-*.pgm) through\n"
"                         libfreenect, exactly as a live Kinect is read\n"
"  --depth MODE           auto (Kinect if present, else an empty scene),\n"
"                         freenect, empty or off (default auto)\n"
"\n"
"Buttons, sound, content\n"
"  --buttons FILE         press buttons from a timeline file instead of the\n"
"                         keyboard / GPIO: lines `<seconds> <start|stop> [press|down|up]`\n"
"  --config FILE          the box's settings (default " CUB_BOXCONF_DEFAULT_PATH "\n"
"                         if it exists): GPIO lines, display, volume, timings,\n"
"                         asset paths, recording; options here win over it\n"
"  --gpio-config FILE     the same as --config (its old name)\n"
"  --audio-driver NAME    SDL audio driver (e.g. dummy, disk, alsa)\n"
"  --clip FILE            the coach's clip, a BVH file\n"
"                         (default " CUB_ASSETS_DIR "/clips/hello.bvh)\n"
"\n"
"The dance\n"
"  --song FILE            lead this song (assets/songs/*.song.xml): the coach\n"
"                         teaches its moves, corrects, cheers at the end\n"
"  --timeline FILE        scripted judge: lines `<seconds> wrong|right|nobody|player|clap`\n"
"  --library FILE         clip library (default " CUB_ASSETS_DIR "/clips/bear.cubclips)\n"
"  --tags FILE            its bridge tags (default " CUB_ASSETS_DIR "/clips/bear.tags.xml)\n"
"  --character FILE       the coach (default " CUB_ASSETS_DIR "/bear/bear.xml)\n"
"  --coach NAME           the coach by name: bear (default) or seal; its character\n"
"                         <assets>/NAME/NAME.xml, its clips <assets>/clips/NAME.cubclips\n"
"                         and NAME.tags.xml (the config's coach=; --library, --tags\n"
"                         and --character win over it)\n"
"  --forest FILE|off      the body-part forest the tracker also reads (default\n"
"                         " CUB_ASSETS_DIR "/forest/body.forest, docs/forest.md):\n"
"                         its confident joints replace the tracker's unsure ones\n"
"  --floor FILE|off       the forest floor the coach stands on (default\n"
"                         " CUB_ASSETS_DIR "/floor/forest.floor; off: a flat meadow)\n"
"  --walk FILE|off        the bear's walk clip: it walks in at START, off after a\n"
"                         song, about while attracting (default\n"
"                         " CUB_ASSETS_DIR "/clips/bear_walk.bvh; off: it stands)\n"
"  --voice FILE           the bear's spoken words (default " CUB_VOICE_PATH ");\n"
"                         speech=0 in the config keeps it quiet\n"
"  --attract-after S      attract after S seconds without interaction\n"
"  --doze-after S         doze after S seconds without interaction\n"
"  --music-clock-scale K  a sound card K times as fast as it should be (tests: 0.95,\n"
"                         1.05): rendered music (--clock virtual) plays K times as\n"
"                         fast; a real audio device only has its clock scaled\n"
"\n"
"Run\n"
"  --log FILE             write the event log to FILE (default: stderr); moved to\n"
"                         FILE.1 when it reaches the config's log_max_kb, and at\n"
"                         the start when it holds the run before (a restart)\n"
"  --record DIR           record the Kinect's depth frames (and accelerometer) of\n"
"                         this whole run as a fakenect dump into a new folder\n"
"                         under DIR (the box never records without this or\n"
"                         recording=1 in the config)\n"
"  --seconds S            stop after S seconds (default: run until quit)\n"
"  --clock MODE           real (default) or virtual: time moves by whole ticks\n"
"                         as fast as the machine goes, so a replay gives the\n"
"                         same event log on every machine\n"
"  --stats                print at the end how much CPU each tick took (median,\n"
"                         p95, max; tracker, judge, coach, render: the whole tick),\n"
"                         the box's own memory apart from the GL driver's and the\n"
"                         allocations per tick; and a line at each song start (rss,\n"
"                         open descriptors, heap). See docs/memory.md\n"
"  --bridge-speed FILE    measure what the coach shows: every joint's speed each\n"
"                         tick against the clip library's p99, per bridge (into a\n"
"                         groove, out of one, between taught clips) and outside\n"
"                         them, written to FILE at the end (docs/groove.md)\n"
"  --help                 this text\n"
"  --version              the version\n"
"\n"
"Keys in a window: Space or Enter = START, Escape or Backspace = STOP.\n"
"The event log has one line per event: `t=<seconds> <source> <event> key=value ...`.\n",
            prog);
}

static int parse_int(const char *s, int lo, int hi, int *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (errno || end == s || *end || v < lo || v > hi) return -1;
    *out = (int)v;
    return 0;
}

static int parse_size(const char *s, int *w, int *h)
{
    char buf[32];
    const char *x = strchr(s, 'x');
    if (!x || (size_t)(x - s) >= sizeof buf) return -1;
    memcpy(buf, s, (size_t)(x - s));
    buf[x - s] = '\0';
    return parse_int(buf, 16, 8192, w) || parse_int(x + 1, 16, 8192, h) ? -1 : 0;
}

static int parse_depth(const char *s, cub_depth_mode *out)
{
    static const struct { const char *name; cub_depth_mode mode; } modes[] = {
        {"auto", CUB_DEPTH_AUTO}, {"freenect", CUB_DEPTH_FREENECT},
        {"empty", CUB_DEPTH_EMPTY}, {"off", CUB_DEPTH_OFF}};
    for (size_t i = 0; i < sizeof modes / sizeof *modes; i++)
        if (strcmp(s, modes[i].name) == 0) return *out = modes[i].mode, 0;
    return -1;
}

/* Options that take a value: which field it fills and how it is checked. */
static int apply_valued(cub_app_options *o, const char *opt, const char *val, FILE *err)
{
    char *end;
    if (!strcmp(opt, "--size")) {
        if (parse_size(val, &o->width, &o->height) == 0) return 0;
        fprintf(err, "cubdance: --size wants WxH, e.g. 1280x720, got '%s'\n", val);
    } else if (!strcmp(opt, "--frame-every")) {
        if (parse_int(val, 1, 1000000, &o->frame_every) == 0) return 0;
        fprintf(err, "cubdance: --frame-every wants a whole number >= 1, got '%s'\n", val);
    } else if (!strcmp(opt, "--draw-every")) {
        if (parse_int(val, 1, 1000000, &o->draw_every) == 0) return 0;
        fprintf(err, "cubdance: --draw-every wants a whole number >= 1, got '%s'\n", val);
    } else if (!strcmp(opt, "--seconds")) {
        o->seconds = strtod(val, &end);
        if (end != val && !*end && o->seconds > 0 && o->seconds < 1e7) return 0;
        fprintf(err, "cubdance: --seconds wants a positive number, got '%s'\n", val);
    } else if (!strcmp(opt, "--attract-after") || !strcmp(opt, "--doze-after")) {
        double *slot = !strcmp(opt, "--attract-after") ? &o->attract_after_s : &o->doze_after_s;
        *slot = strtod(val, &end);
        if (end != val && !*end && *slot > 0 && *slot < 1e6) return 0;
        fprintf(err, "cubdance: %s wants a positive number of seconds, got '%s'\n", opt, val);
    } else if (!strcmp(opt, "--music-clock-scale")) {
        o->music_clock_scale = strtod(val, &end);
        if (end != val && !*end && o->music_clock_scale >= 0.5 && o->music_clock_scale <= 2)
            return 0;
        fprintf(err, "cubdance: --music-clock-scale wants a number in [0.5, 2], got '%s'\n",
                val);
    } else if (!strcmp(opt, "--clock")) {
        if (!strcmp(val, "real") || !strcmp(val, "virtual")) {
            o->virtual_clock = !strcmp(val, "virtual");
            return 0;
        }
        fprintf(err, "cubdance: --clock wants real or virtual, got '%s'\n", val);
    } else if (!strcmp(opt, "--depth")) {
        if (parse_depth(val, &o->depth) == 0) return 0;
        fprintf(err, "cubdance: --depth wants auto, freenect, empty or off, got '%s'\n", val);
    } else {
        const char **slot = !strcmp(opt, "--frames")         ? &o->frames_dir
                            : !strcmp(opt, "--replay")       ? &o->replay_dir
                            : !strcmp(opt, "--buttons")      ? &o->button_script
                            : !strcmp(opt, "--gpio-config")  ? &o->config_path
                            : !strcmp(opt, "--config")       ? &o->config_path
                            : !strcmp(opt, "--audio-driver") ? &o->audio_driver
                            : !strcmp(opt, "--clip")         ? &o->clip_path
                            : !strcmp(opt, "--log")          ? &o->log_path
                            : !strcmp(opt, "--record")       ? &o->record_dir
                            : !strcmp(opt, "--song")         ? &o->song_path
                            : !strcmp(opt, "--timeline")     ? &o->timeline_path
                            : !strcmp(opt, "--library")      ? &o->library_path
                            : !strcmp(opt, "--tags")         ? &o->tags_path
                            : !strcmp(opt, "--character")    ? &o->character_path
                            : !strcmp(opt, "--coach")        ? &o->coach
                            : !strcmp(opt, "--forest")       ? &o->forest_path
                            : !strcmp(opt, "--floor")        ? &o->floor_path
                            : !strcmp(opt, "--walk")         ? &o->walk_path
                            : !strcmp(opt, "--font")         ? &o->font_path
                            : !strcmp(opt, "--voice")        ? &o->voice_path
                            : !strcmp(opt, "--bridge-speed") ? &o->bridge_speed_path
                                                             : NULL;
        if (slot) return *slot = val, 0;
        fprintf(err, "cubdance: unknown option '%s' (see --help)\n", opt);
    }
    return -1;
}

static int takes_value(const char *opt)
{
    static const char *const valued[] = {"--size", "--frame-every", "--draw-every", "--seconds", "--clock",
                                         "--depth", "--frames", "--replay", "--buttons",
                                         "--gpio-config", "--config", "--audio-driver", "--clip", "--log",
                                         "--song", "--timeline", "--library", "--tags",
                                         "--character", "--coach", "--forest", "--floor", "--walk", "--font", "--voice", "--attract-after", "--doze-after",
                                         "--music-clock-scale", "--record", "--bridge-speed"};
    for (size_t i = 0; i < sizeof valued / sizeof *valued; i++)
        if (!strcmp(opt, valued[i])) return 1;
    return 0;
}

cub_app_parse cub_app_parse_options(int argc, char **argv, cub_app_options *o, FILE *err,
                                    FILE *help_out)
{
    memset(o, 0, sizeof *o);
    o->frame_every = 30;
    o->draw_every = 1;
    o->music_clock_scale = 1.0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(help_out, argv[0]);
            return CUB_APP_EXIT_OK;
        } else if (!strcmp(a, "--version")) {
            fprintf(help_out, "cubdance %s\n", CUB_VERSION);
            return CUB_APP_EXIT_OK;
        } else if (!strcmp(a, "--window")) {
            o->display = CUB_DISPLAY_WINDOW;
        } else if (!strcmp(a, "--headless")) {
            o->display = CUB_DISPLAY_HEADLESS;
        } else if (!strcmp(a, "--stats")) {
            o->stats = 1;
        } else if (takes_value(a)) {
            if (i + 1 >= argc) {
                fprintf(err, "cubdance: %s needs a value (see --help)\n", a);
                return CUB_APP_EXIT_BAD;
            }
            if (apply_valued(o, a, argv[++i], err)) return CUB_APP_EXIT_BAD;
        } else {
            fprintf(err, "cubdance: unknown option '%s' (see --help)\n", a);
            return CUB_APP_EXIT_BAD;
        }
    }
    if (o->frame_every % o->draw_every) {
        fprintf(err, "cubdance: --frame-every %d must be a multiple of --draw-every %d\n",
                o->frame_every, o->draw_every);
        return CUB_APP_EXIT_BAD;
    }
    if (o->replay_dir) {
        if (o->depth == CUB_DEPTH_EMPTY || o->depth == CUB_DEPTH_OFF) {
            fprintf(err, "cubdance: --replay needs the freenect depth source, not --depth %s\n",
                    o->depth == CUB_DEPTH_EMPTY ? "empty" : "off");
            return CUB_APP_EXIT_BAD;
        }
        o->depth = CUB_DEPTH_FREENECT;
    }
    return CUB_APP_RUN;
}

/* dir + "/" + rel into buf (slot of o->path_buf); NULL if too long. */
static const char *join(cub_app_options *o, int slot, const char *dir, const char *rel,
                        const char *suffix)
{
    char *buf = o->path_buf[slot];
    int n = snprintf(buf, sizeof o->path_buf[slot], "%s/%s%s", dir, rel, suffix);
    return n < 0 || (size_t)n >= sizeof o->path_buf[slot] ? NULL : buf;
}

/* An asset the box runs without: where it is by default under the assets,
 * its name in the message, and what runs without it. */
typedef struct optional_asset {
    int slot; /* of o->path_buf */
    const char *rel, *what, *without;
} optional_asset;

/* *path as given (--forest FILE, "off": none), else the assets' own when
 * it is there; assets without it (an old tree) run without it and say so. */
static int default_optional(cub_app_options *o, const char *assets, const optional_asset *a,
                            const char **path, FILE *err)
{
    if (*path) {
        if (!strcmp(*path, "off")) *path = NULL;
        return 0;
    }
    const char *p = join(o, a->slot, assets, a->rel, "");
    if (!p) {
        fprintf(err, "cubdance: assets_dir %s: path too long\n", assets);
        return -1;
    }
    FILE *f = fopen(p, "rb");
    if (f) fclose(f), *path = p;
    else fprintf(err, "cubdance: no %s at %s: %s\n", a->what, p, a->without);
    return 0;
}

/* The tracker's body-part forest (docs/forest.md, "In the box": it
 * measured better on every held-out fold), the forest floor the coach
 * stands on (cub/floor_file.h, CUB_FLOOR_ASSET; docs/floor.md) and the
 * bear's walk over it (docs/gait.md). */
static int default_forests(cub_app_options *o, const char *assets, FILE *err)
{
    static const optional_asset forest = {6, "forest/body.forest", "forest",
                                          "the tracker runs without it"};
    static const optional_asset floor = {7, "floor/forest.floor", "floor",
                                         "the coach stands on a flat meadow"};
    static const optional_asset walk = {8, "clips/bear_walk.bvh", "walk clip",
                                        "the bear stands at its place"};
    if (default_optional(o, assets, &forest, &o->forest_path, err)) return -1;
    if (default_optional(o, assets, &walk, &o->walk_path, err)) return -1;
    return default_optional(o, assets, &floor, &o->floor_path, err);
}

/* The coach's name (--coach, else the config's coach=): letters, digits
 * and '_', and a character file in the assets; -1 with a message naming
 * where the name came from. */
static int check_coach(const char *coach, const char *from, const char *assets, FILE *err)
{
    char path[CUB_BOXCONF_PATH_MAX + 160];
    size_t n = strlen(coach);
    int ok = n > 0 && n < 64;
    for (size_t i = 0; ok && i < n; i++)
        ok = (coach[i] >= 'a' && coach[i] <= 'z') || (coach[i] >= '0' && coach[i] <= '9') ||
             coach[i] == '_';
    if (!ok) {
        fprintf(err, "cubdance: %s%s: not a coach's name (a-z, 0-9, _), e.g. bear or seal\n",
                from, coach);
        return -1;
    }
    snprintf(path, sizeof path, "%s/%s/%s.xml", assets, coach, coach);
    FILE *f = fopen(path, "rb");
    if (f) return fclose(f), 0;
    fprintf(err, "cubdance: %s%s: no such coach (no character file %s); the coaches: bear, "
                 "seal\n", from, coach, path);
    return -1;
}

/* The coach's library, tags and character (slots 1..3) under assets. */
static int coach_paths(cub_app_options *o, const cub_boxconf *c, const char *assets, FILE *err)
{
    const char *coach = o->coach ? o->coach : c->coach[0] ? c->coach : "bear";
    char from[CUB_BOXCONF_PATH_MAX + 16];
    snprintf(from, sizeof from, "%s%s", o->coach ? "--coach " : c->gpio.file,
             o->coach ? "" : ": coach=");
    if (strcmp(coach, "bear") && check_coach(coach, from, assets, err)) return -1;
    char rel[3][160];
    snprintf(rel[0], sizeof rel[0], "clips/%s.cubclips", coach);
    snprintf(rel[1], sizeof rel[1], "clips/%s.tags.xml", coach);
    snprintf(rel[2], sizeof rel[2], "%s/%s.xml", coach, coach);
    const char **slot[3] = {&o->library_path, &o->tags_path, &o->character_path};
    for (int i = 0; i < 3; i++)
        if (!*slot[i] && !(*slot[i] = join(o, i + 1, assets, rel[i], ""))) {
            fprintf(err, "cubdance: assets_dir %s: path too long\n", assets);
            return -1;
        }
    return 0;
}

static int apply_assets(cub_app_options *o, const cub_boxconf *c, const char *builtin,
                        FILE *err)
{
    const char *assets = c->assets_dir[0] ? c->assets_dir : builtin;
    if (!o->clip_path && !(o->clip_path = join(o, 0, assets, "clips/hello.bvh", ""))) {
        fprintf(err, "cubdance: assets_dir %s: path too long\n", assets);
        return -1;
    }
    if (coach_paths(o, c, assets, err)) return -1;
    if (!o->voice_path) /* built with the program, not in the source's assets */
        o->voice_path = c->assets_dir[0] ? join(o, 5, assets, "voice/bear.cubvoice", "")
                                         : CUB_VOICE_PATH;
    if (!o->voice_path) {
        fprintf(err, "cubdance: assets_dir %s: path too long\n", assets);
        return -1;
    }
    if (default_forests(o, assets, err)) return -1;
    if (!o->song_path && c->song[0]) {
        char songs[CUB_BOXCONF_PATH_MAX + 16];
        snprintf(songs, sizeof songs, "%s%s", c->songs_dir[0] ? c->songs_dir : assets,
                 c->songs_dir[0] ? "" : "/songs");
        if (!(o->song_path = join(o, 4, songs, c->song, ".song.xml"))) {
            fprintf(err, "cubdance: songs_dir %s: path too long\n", songs);
            return -1;
        }
    }
    return 0;
}

int cub_app_apply_config(cub_app_options *o, const cub_boxconf *c, int from_file,
                         const char *builtin_assets, FILE *err)
{
    if (apply_assets(o, c, builtin_assets, err)) return -1;
    if (o->attract_after_s == 0) o->attract_after_s = c->attract_after_s;
    if (o->doze_after_s == 0) o->doze_after_s = c->doze_after_s;
    if (!o->audio_driver && strcmp(c->audio_driver, "auto") != 0) o->audio_driver = c->audio_driver;
    o->audio_volume = c->volume == 0 ? CUB_BOARD_MUTE : c->volume;
    o->soundfont = c->soundfont;
    o->speech = c->speech;
    if (!o->font_path && c->font[0]) o->font_path = c->font;
    o->gpio = &c->gpio;
    o->record_max_mb = c->recording_max_mb;
    o->log_max_kb = c->log_max_kb;
    if (!o->record_dir && c->recording) {
        o->record_dir = c->recording_dir;
        o->record_each_dance = 1;
    }
    if (!from_file) return 0;
    /* The display only from a file: with none, a PC keeps its window. */
    if (o->width == 0) {
        o->width = c->width;
        o->height = c->height;
        o->fit_screen = c->width == 0;
    }
    o->fullscreen = c->fullscreen ? 1 : -1;
    if (!strcmp(c->video_driver, "kmsdrm")) o->video_driver = "KMSDRM";
    else if (strcmp(c->video_driver, "auto") != 0) o->video_driver = c->video_driver;
    return 0;
}

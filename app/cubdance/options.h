/* options — the command line of the box program (see --help). */
#ifndef CUB_APP_OPTIONS_H
#define CUB_APP_OPTIONS_H

#include <stdio.h>

#include "cub/board.h"
#include "cub/boxconf.h"

typedef struct cub_app_options {
    cub_display_mode display;
    int width, height;          /* 0 = the board's default */
    cub_depth_mode depth;
    const char *replay_dir;     /* a fakenect dump to replay, or NULL */
    const char *button_script;  /* a button timeline, or NULL */
    const char *config_path;    /* --config (alias --gpio-config); NULL = the default file */
    const char *audio_driver;
    const char *clip_path;      /* the coach's clip (BVH) */
    const char *log_path;       /* NULL or "-" = stderr */
    const char *frames_dir;     /* headless PNG frames go here, or NULL */
    int frame_every;            /* write every Nth tick (default 30 = 1 per second) */
    int draw_every;             /* headless: draw every Nth tick only (default 1) */
    double seconds;             /* stop after this long; 0 = run until quit */
    int virtual_clock;          /* --clock virtual */
    int stats;                  /* --stats: tick CPU time, memory, allocations (mem_stats.h) */
    const char *bridge_speed_path; /* --bridge-speed FILE (bridge_speed.h), or NULL */
    /* The dance (issue 4): with a song the coach leads it. */
    const char *song_path;      /* a choreography (a .song.xml in assets/songs), or NULL */
    const char *timeline_path;  /* scripted verdicts / presence / claps, or NULL */
    const char *library_path;   /* the clip library (default assets/clips/bear.cubclips) */
    const char *tags_path;      /* its bridge tags (default assets/clips/bear.tags.xml) */
    const char *character_path; /* the coach (default assets/bear/bear.xml) */
    const char *coach;          /* --coach NAME: the three above by name (NULL: the config's) */
    const char *forest_path;    /* the body-part forest the tracker takes joints from (default
                                 * assets/forest/body.forest when there; "off": none), or NULL */
    const char *floor_path;     /* the forest floor the coach stands on (--floor; default
                                 * assets/floor/forest.floor when there; "off"), or NULL: the meadow */
    const char *walk_path;      /* the bear's walk clip (--walk; default assets/clips/bear_walk.bvh
                                 * when there; "off"), or NULL: the bear does not walk */
    double attract_after_s;     /* 0 = the coach's default */
    double doze_after_s;        /* 0 = the coach's default */
    double music_clock_scale;   /* 1 = true; 0.95 / 1.05 simulate a drifting audio clock */
    /* From the config file only (cub_app_apply_config). */
    int fit_screen, fullscreen; /* as in cub_board_desc */
    const char *video_driver;   /* NULL = the board's choice */
    int audio_volume;           /* as in cub_board_desc */
    const char *soundfont;      /* NULL = the music module's default */
    const char *font_path;      /* --font or the config's font; NULL = the renderer's default */
    const char *voice_path;     /* --voice or <assets_dir>/voice/bear.cubvoice or the built one */
    int speech;                 /* the config's speech (1: the bear says its words) */
    const cub_boxconf_gpio *gpio;
    /* Recording (record.h): --record DIR records the whole run into a new
     * folder under DIR; recording=1 in the config records each dance. */
    const char *record_dir;     /* --record DIR, or recording_dir with recording=1 */
    int record_each_dance;      /* 1: from the config (a folder per dance) */
    int record_max_mb;          /* recording_max_mb */
    int log_max_kb;             /* the event log's cap (log_max_kb); 0 = none */
    char path_buf[9][CUB_BOXCONF_PATH_MAX + 64]; /* joined asset paths */
} cub_app_options;

typedef enum cub_app_parse {
    CUB_APP_RUN = 0,  /* options are good: run */
    CUB_APP_EXIT_OK,  /* --help or --version was printed */
    CUB_APP_EXIT_BAD, /* a bad option; the message went to err */
} cub_app_parse;

cub_app_parse cub_app_parse_options(int argc, char **argv, cub_app_options *out, FILE *err,
                                    FILE *help_out);
/* Fill what the command line left unset from the config c (which must
 * outlive o); from_file = 0 when no file was read (the display then stays
 * the board's way). Asset paths not given resolve against c's assets_dir,
 * else builtin_assets. -1 with a message to err when a path is too long. */
int cub_app_apply_config(cub_app_options *o, const cub_boxconf *c, int from_file,
                         const char *builtin_assets, FILE *err);

#endif

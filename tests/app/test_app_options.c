/* cubdance's options: bad input first, then what good input sets. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "options.h"

static char err_text[4096], help_text[8192];

/* Parse argv (NULL-terminated), capturing what goes to err and help. */
static cub_app_parse parse(cub_app_options *o, const char **args)
{
    char *argv[32];
    int argc = 0;
    argv[argc++] = "cubdance";
    while (*args && argc < 31) argv[argc++] = (char *)*args++;
    argv[argc] = NULL;
    FILE *err = fmemopen(err_text, sizeof err_text, "w");
    FILE *help = fmemopen(help_text, sizeof help_text, "w");
    cub_app_parse r = cub_app_parse_options(argc, argv, o, err, help);
    fclose(err);
    fclose(help);
    return r;
}

static void expect_refused(const char **args, const char *needle)
{
    cub_app_options o;
    memset(err_text, 0, sizeof err_text);
    assert_int_equal(parse(&o, args), CUB_APP_EXIT_BAD);
    if (!strstr(err_text, needle)) fail_msg("error '%s' does not mention '%s'", err_text, needle);
}

static void test_bad_options_are_refused_with_the_option_named(void **s)
{
    expect_refused((const char *[]){"--bogus", NULL}, "--bogus");
    expect_refused((const char *[]){"--size", "big", NULL}, "--size");
    expect_refused((const char *[]){"--size", "1280x", NULL}, "--size");
    expect_refused((const char *[]){"--size", "99999x720", NULL}, "--size");
    expect_refused((const char *[]){"--frame-every", "0", NULL}, "--frame-every");
    expect_refused((const char *[]){"--frame-every", "3x", NULL}, "--frame-every");
    expect_refused((const char *[]){"--draw-every", "0", NULL}, "--draw-every");
    expect_refused((const char *[]){"--draw-every", "4", NULL}, "multiple of --draw-every");
    expect_refused((const char *[]){"--seconds", "-1", NULL}, "--seconds");
    expect_refused((const char *[]){"--seconds", "soon", NULL}, "--seconds");
    expect_refused((const char *[]){"--depth", "lidar", NULL}, "--depth");
    expect_refused((const char *[]){"--clock", "fast", NULL}, "--clock");
    expect_refused((const char *[]){"--attract-after", "0", NULL}, "--attract-after");
    expect_refused((const char *[]){"--doze-after", "x", NULL}, "--doze-after");
    expect_refused((const char *[]){"--music-clock-scale", "3", NULL}, "--music-clock-scale");
    expect_refused((const char *[]){"--log", NULL}, "--log needs a value");
    expect_refused((const char *[]){"--replay", "/x", "--depth", "empty", NULL}, "--replay");
}

static void test_help_documents_every_option(void **s)
{
    cub_app_options o;
    assert_int_equal(parse(&o, (const char *[]){"--help", NULL}), CUB_APP_EXIT_OK);
    const char *opts[] = {"--window", "--headless", "--size", "--frames", "--frame-every", "--draw-every",
                          "--replay", "--depth", "--buttons", "--gpio-config", "--config", "--audio-driver",
                          "--clip", "--log", "--seconds", "--clock", "--song", "--timeline",
                          "--library", "--tags", "--character", "--coach", "--forest", "--attract-after",
                          "--doze-after", "--music-clock-scale", "--help", "--version"};
    for (size_t i = 0; i < sizeof opts / sizeof *opts; i++)
        if (!strstr(help_text, opts[i])) fail_msg("--help does not mention %s", opts[i]);
}

static void test_good_options_set_their_fields(void **s)
{
    cub_app_options o;
    const char *args[] = {"--headless", "--size", "320x240", "--frames", "f", "--frame-every",
                          "5", "--draw-every", "5", "--replay", "dump", "--buttons", "b.txt", "--log", "e.log",
                          "--seconds", "2.5", "--clock", "virtual", NULL};
    assert_int_equal(parse(&o, args), CUB_APP_RUN);
    assert_int_equal(o.display, CUB_DISPLAY_HEADLESS);
    assert_int_equal(o.width, 320);
    assert_int_equal(o.height, 240);
    assert_string_equal(o.frames_dir, "f");
    assert_int_equal(o.frame_every, 5);
    assert_int_equal(o.draw_every, 5);
    assert_string_equal(o.replay_dir, "dump");
    assert_int_equal(o.depth, CUB_DEPTH_FREENECT); /* a replay reads through libfreenect */
    assert_string_equal(o.button_script, "b.txt");
    assert_string_equal(o.log_path, "e.log");
    assert_true(o.seconds > 2.49 && o.seconds < 2.51);
    assert_int_equal(o.virtual_clock, 1);
}

static void test_defaults(void **s)
{
    cub_app_options o;
    assert_int_equal(parse(&o, (const char *[]){NULL}), CUB_APP_RUN);
    assert_null(o.config_path);
    assert_null(o.clip_path); /* until the config (or its absence) is applied */
    static cub_boxconf none;
    cub_boxconf_defaults(&none);
    assert_int_equal(cub_app_apply_config(&o, &none, 0, "/assets", stderr), 0);
    assert_int_equal(o.width, 0); /* no file: the board's own display */
    assert_int_equal(o.fullscreen, 0);
    assert_null(o.video_driver);
    assert_int_equal(o.audio_volume, 80);
    assert_int_equal(o.display, CUB_DISPLAY_AUTO);
    assert_int_equal(o.depth, CUB_DEPTH_AUTO);
    assert_int_equal(o.frame_every, 30);
    assert_int_equal(o.draw_every, 1);
    assert_string_equal(o.clip_path, "/assets/clips/hello.bvh");
    assert_null(o.log_path);
    assert_true(o.seconds == 0);
    assert_int_equal(o.virtual_clock, 0);
    assert_null(o.song_path);
    assert_string_equal(o.library_path, "/assets/clips/bear.cubclips");
    assert_true(o.music_clock_scale == 1.0);
    assert_int_equal(o.speech, 1); /* the bear speaks unless told not to */
    assert_string_equal(o.voice_path, "/build/voice/bear.cubvoice"); /* the built pack */
    assert_null(o.forest_path); /* no /assets/forest/body.forest here: the tracker alone */
}

/* The tracker's forest: the assets' own when there, a given file, or off. */
static void test_the_forest_is_the_assets_own_unless_told(void **s)
{
    static cub_boxconf none;
    cub_boxconf_defaults(&none);
    char dir[] = "/tmp/cub_opts_XXXXXX", sub[64], file[96];
    assert_non_null(mkdtemp(dir));
    snprintf(sub, sizeof sub, "%s/forest", dir);
    snprintf(file, sizeof file, "%s/body.forest", sub);
    assert_int_equal(mkdir(sub, 0700), 0);
    FILE *f = fopen(file, "wb");
    assert_non_null(f);
    fclose(f);
    cub_app_options o;
    assert_int_equal(parse(&o, (const char *[]){NULL}), CUB_APP_RUN);
    assert_int_equal(cub_app_apply_config(&o, &none, 0, dir, stderr), 0);
    assert_string_equal(o.forest_path, file);
    assert_int_equal(parse(&o, (const char *[]){"--forest", "off", NULL}), CUB_APP_RUN);
    assert_int_equal(cub_app_apply_config(&o, &none, 0, dir, stderr), 0);
    assert_null(o.forest_path);
    assert_int_equal(parse(&o, (const char *[]){"--forest", "my.forest", NULL}), CUB_APP_RUN);
    assert_int_equal(cub_app_apply_config(&o, &none, 0, dir, stderr), 0);
    assert_string_equal(o.forest_path, "my.forest");
    remove(file), rmdir(sub), rmdir(dir);
}

/* The file fills what the command line left unset; the command line wins. */
static void test_config_fills_unset_options_only(void **s)
{
    static cub_boxconf c;
    const char *text = "assets_dir=/opt/a\nsong=twinkle\nvolume=0\nresolution=1920x1080\n"
                       "fullscreen=0\nvideo_driver=kmsdrm\naudio_driver=dummy\n"
                       "attract_after_s=7\ndoze_after_s=9\nsoundfont=/sf/x.sf2\nled_line=GPIO22\n"
                       "speech=0\n";
    char err[256];
    assert_int_equal(cub_boxconf_parse(text, strlen(text), "c.conf", &c, err, sizeof err), CUB_OK);
    cub_app_options o;
    assert_int_equal(parse(&o, (const char *[]){"--config", "c.conf", "--library", "/my/lib",
                                               "--doze-after", "30", NULL}),
                     CUB_APP_RUN);
    assert_string_equal(o.config_path, "c.conf");
    assert_int_equal(cub_app_apply_config(&o, &c, 1, "/assets", stderr), 0);
    assert_string_equal(o.clip_path, "/opt/a/clips/hello.bvh");
    assert_string_equal(o.character_path, "/opt/a/bear/bear.xml");
    assert_string_equal(o.library_path, "/my/lib");
    assert_string_equal(o.song_path, "/opt/a/songs/twinkle.song.xml");
    assert_int_equal(o.audio_volume, CUB_BOARD_MUTE);
    assert_int_equal(o.width, 1920);
    assert_int_equal(o.height, 1080);
    assert_int_equal(o.fullscreen, -1);
    assert_string_equal(o.video_driver, "KMSDRM");
    assert_string_equal(o.audio_driver, "dummy");
    assert_true(o.attract_after_s == 7);
    assert_true(o.doze_after_s == 30);
    assert_string_equal(o.soundfont, "/sf/x.sf2");
    assert_string_equal(o.gpio->line[CUB_BOXCONF_LINE_LED], "GPIO22");
    assert_int_equal(o.speech, 0);
    assert_string_equal(o.voice_path, "/opt/a/voice/bear.cubvoice"); /* beside the assets */
    /* The old name still works; --size beats the file's resolution. */
    assert_int_equal(parse(&o, (const char *[]){"--gpio-config", "g.conf", "--size", "640x480",
                                               "--song", "/s.song.xml", NULL}),
                     CUB_APP_RUN);
    assert_string_equal(o.config_path, "g.conf");
    assert_int_equal(cub_app_apply_config(&o, &c, 1, "/assets", stderr), 0);
    assert_int_equal(o.width, 640);
    assert_string_equal(o.song_path, "/s.song.xml");
    assert_int_equal(parse(&o, (const char *[]){"--voice", "/v.cubvoice", NULL}), CUB_APP_RUN);
    assert_int_equal(cub_app_apply_config(&o, &c, 1, "/assets", stderr), 0);
    assert_string_equal(o.voice_path, "/v.cubvoice");
    /* songs_dir moves the songs only. */
    text = "songs_dir=/songs\nsong=twinkle\n";
    assert_int_equal(cub_boxconf_parse(text, strlen(text), "c.conf", &c, err, sizeof err), CUB_OK);
    assert_int_equal(parse(&o, (const char *[]){NULL}), CUB_APP_RUN);
    assert_int_equal(cub_app_apply_config(&o, &c, 1, "/assets", stderr), 0);
    assert_string_equal(o.song_path, "/songs/twinkle.song.xml");
    assert_string_equal(o.tags_path, "/assets/clips/bear.tags.xml");
    assert_int_equal(o.fit_screen, 0);
}

/* Apply c (from c.conf) after parsing args; the return and the error text. */
static int apply_with(const cub_boxconf *c, const char **args, const char *assets,
                      cub_app_options *o)
{
    assert_int_equal(parse(o, args), CUB_APP_RUN);
    memset(err_text, 0, sizeof err_text);
    FILE *err = fmemopen(err_text, sizeof err_text, "w");
    int rc = cub_app_apply_config(o, c, 1, assets, err);
    fclose(err);
    return rc;
}

/* The coach by name: --coach, else the config's coach=, else the bear; the
 * three files follow the name; a name with no character file, or not a
 * name, is refused naming where it came from. */
static void test_the_coach_is_chosen_by_name(void **s)
{
    static cub_boxconf c;
    char err[256], dir[] = "/tmp/cub_coach_XXXXXX", sub[64], file[96];
    assert_non_null(mkdtemp(dir));
    snprintf(sub, sizeof sub, "%s/seal", dir);
    snprintf(file, sizeof file, "%s/seal.xml", sub);
    assert_int_equal(mkdir(sub, 0700), 0);
    FILE *f = fopen(file, "wb");
    assert_non_null(f);
    fclose(f);
    const char *text = "coach=seal\n";
    assert_int_equal(cub_boxconf_parse(text, strlen(text), "c.conf", &c, err, sizeof err), CUB_OK);
    cub_app_options o;
    assert_int_equal(apply_with(&c, (const char *[]){NULL}, dir, &o), 0);
    assert_string_equal(o.character_path, file);
    assert_non_null(strstr(o.library_path, "/clips/seal.cubclips"));
    assert_non_null(strstr(o.tags_path, "/clips/seal.tags.xml"));
    /* --coach beats the file; --character beats --coach */
    assert_int_equal(apply_with(&c, (const char *[]){"--coach", "bear", "--character", "/b.xml",
                                                     NULL}, dir, &o), 0);
    assert_string_equal(o.character_path, "/b.xml");
    assert_non_null(strstr(o.library_path, "/clips/bear.cubclips"));
    assert_int_equal(apply_with(&c, (const char *[]){"--coach", "walrus", NULL}, dir, &o), -1);
    assert_non_null(strstr(err_text, "--coach walrus: no such coach"));
    assert_int_equal(apply_with(&c, (const char *[]){"--coach", "../seal", NULL}, dir, &o), -1);
    assert_non_null(strstr(err_text, "not a coach's name"));
    text = "coach=walrus\n";
    assert_int_equal(cub_boxconf_parse(text, strlen(text), "c.conf", &c, err, sizeof err), CUB_OK);
    assert_int_equal(apply_with(&c, (const char *[]){NULL}, dir, &o), -1);
    assert_non_null(strstr(err_text, "c.conf: coach=walrus: no such coach"));
    remove(file), rmdir(sub), rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_options_are_refused_with_the_option_named),
        cmocka_unit_test(test_help_documents_every_option),
        cmocka_unit_test(test_good_options_set_their_fields),
        cmocka_unit_test(test_defaults),
        cmocka_unit_test(test_the_forest_is_the_assets_own_unless_told),
        cmocka_unit_test(test_config_fills_unset_options_only),
        cmocka_unit_test(test_the_coach_is_chosen_by_name),
    };
    return cmocka_run_group_tests_name("app_options", tests, NULL, NULL);
}

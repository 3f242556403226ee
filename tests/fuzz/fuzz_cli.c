/* libFuzzer target: the command lines. Byte 0 picks the parser, the rest
 * is the arguments, separated by NUL bytes (argv[0] is added):
 *   'c' the box's config text, applied over the options as cubdance does
 *       (cub_boxconf_parse + cub_app_apply_config)
 *   'r' cubtool retarget, 'b' cubtool build, 's' cubtool synth-depth
 *   anything else: cubdance's options (app/cubdance/options.c)
 * Seeds: seeds_cli/. Whatever the arguments: no crash; options that parse
 * hold values in their documented ranges. Help and messages go to
 * /dev/null (the ctest run closes stdout and stderr too). */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/boxconf.h"
#include "options.h"
#include "fuzz_tally.h"

#define MAX_ARGS 64

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int cub_fuzz_cli_retarget(int argc, char **argv);
int cub_fuzz_cli_build(int argc, char **argv);
int cub_fuzz_cli_synth_depth(int argc, char **argv);

static FILE *null_out;

static void check_box(int argc, char **argv)
{
    cub_app_options o;
    int ok = cub_app_parse_options(argc, argv, &o, null_out, null_out) == CUB_APP_RUN;
    cub_fuzz_tally("fuzz_cli", ok);
    if (!ok) return;
    if (o.width < 0 || o.height < 0 || (o.width == 0) != (o.height == 0)) abort();
    if (!(o.seconds >= 0) || o.frame_every < 1 || o.draw_every < 1) abort();
}

static void check_config(const char *text, size_t len)
{
    static cub_boxconf c;
    char err[300];
    int ok = cub_boxconf_parse(text, len, "fuzz.conf", &c, err, sizeof err) == CUB_OK;
    cub_fuzz_tally("fuzz_cli", ok);
    if (!ok) return;
    char *argv[] = {"cubdance", "--headless", NULL};
    cub_app_options o;
    if (cub_app_parse_options(2, argv, &o, null_out, null_out) != CUB_APP_RUN) abort();
    /* refused (e.g. coach= names no coach under /assets): the box stops there */
    if (cub_app_apply_config(&o, &c, 1, "/assets", null_out) != 0) return;
    if (o.audio_volume != CUB_BOARD_MUTE && (o.audio_volume < 1 || o.audio_volume > 100)) abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!null_out && !(null_out = fopen("/dev/null", "w"))) abort();
    if (size < 1) return 0;
    char *text = malloc(size); /* the arguments, each NUL-terminated */
    if (!text) return 0;
    memcpy(text, data + 1, size - 1);
    text[size - 1] = '\0';
    if (data[0] == 'c') {
        check_config(text, size - 1);
        free(text);
        return 0;
    }
    char *argv[MAX_ARGS + 2] = {"cub"};
    int argc = 1;
    for (size_t at = 0; at < size && argc <= MAX_ARGS; at += strlen(text + at) + 1) {
        if (at == size - 1 && argc > 1) break; /* the terminator added above */
        argv[argc++] = text + at;
    }
    argv[argc] = NULL;
    switch (data[0]) {
    case 'r': cub_fuzz_tally("fuzz_cli", cub_fuzz_cli_retarget(argc, argv) == 0); break;
    case 'b': cub_fuzz_tally("fuzz_cli", cub_fuzz_cli_build(argc, argv) == 0); break;
    case 's': cub_fuzz_tally("fuzz_cli", cub_fuzz_cli_synth_depth(argc, argv) == 0); break;
    default: check_box(argc, argv); break;
    }
    free(text);
    return 0;
}

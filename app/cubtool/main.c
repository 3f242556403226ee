/* cubtool — the host tool for content makers: turns motion capture and
 * keyframes into the bear's clip library, and tags its bridge frames.
 *   cubtool <command> [options]      cubtool <command> --help */
#include <stdio.h>
#include <string.h>

#include "commands.h"

typedef struct command {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *summary;
} command;

static const command commands[] = {
    {"retarget", cub_cmd_retarget, "map a human clip (BVH, ASF/AMC) onto the bear"},
    {"build", cub_cmd_build, "rebuild the clip library from its recipe and ../shared/data"},
    {"tag", cub_cmd_tag, "tag bridge frames across a clip library; summary + contact sheets"},
    {"bench-bridge", cub_cmd_bench_bridge, "measure clip switching: reaction latency, joint jumps"},
    {"tween", cub_cmd_tween, "the seed's tween clip from the library's bridge frames, as BVH"},
    {"eval-track", cub_cmd_eval_track, "the tracker on a depth dump: joint errors, statuses, fps"},
    {"bench-track", cub_cmd_bench_track, "the tracker's ms per frame and memory"},
    {"synth-depth", cub_cmd_synth_depth, "a synthetic child as Kinect v1 depth: fakenect dump + truth"},
    {"train-forest", cub_cmd_train_forest, "the body-part forest, trained on synth-depth renders"},
    {"eval-forest", cub_cmd_eval_forest, "the body-part forest's per-part accuracy on renders"},
    {"bench-render", cub_cmd_bench_render, "the renderer's CPU per frame: own work vs the GL driver"},
    {"play", cub_cmd_play, "play clips or BVHs on the bear or a stick figure, side by side"},
    {"encode", cub_cmd_encode, "compress a clip with the folk-dance seed's codec (.cubseed)"},
    {"decode", cub_cmd_decode, "decode a .cubseed stream as the box does, to BVH"},
    {"codec-figures", cub_cmd_codec_figures, "the seed's codec: Squad vs Slerp vs Catmull-Rom, IK, ratio"},
    {"bench-codec", cub_cmd_bench_codec, "ours vs ACL vs the seed's codec: ratio, error, decode"},
    {"trc-info", cub_cmd_trc_info, "a TRC marker file: its markers, frames, rate, lost markers"},
    {"groove", cub_cmd_groove, "seed 001 on a MIDI file: melody, segments, keys; the bear dancing it (BVH, PNG)"},
    {"groove-eval", cub_cmd_groove_eval, "seed 001 figures: beat alignment (FACT, Bailando), joint speed, time"},
    {"gait", cub_cmd_gait, "seed 003: a captured walk over a terrain (PNG frames, footholds drawn)"},
    {"gait-eval", cub_cmd_gait_eval, "seed 003 figures: penetration, slide, clearance, ... vs a foot-IK baseline"},
    {"join", cub_cmd_join, "join two clips through a searched transition, feet planted; --all: the table"},
    {"graph", cub_cmd_graph, "the motion graph by support points (feet, hands, knees, hip); --png"},
    {"evolve", cub_cmd_evolve, "cross two clips of different skeletons into a child (seed 004), as BVH"},
    {"coach", cub_cmd_coach, "a second coach's clip library and tags from the bear's, through evolve"},
    {"wings", cub_cmd_wings, "rebuild the winged bear (bird_flying's wings) through evolve"},
    {"ase-export", cub_cmd_ase_export, "a clip (BVH, ASF+AMC, ASE) as a 3ds Max ASCII export"},
};

static void usage(FILE *f)
{
    fprintf(f, "usage: cubtool <command> [options]\n\ncommands:\n");
    for (size_t i = 0; i < sizeof commands / sizeof *commands; i++)
        fprintf(f, "  %-10s %s\n", commands[i].name, commands[i].summary);
    fprintf(f, "\n`cubtool <command> --help` documents each command.\n");
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return 0;
    }
    for (size_t i = 0; i < sizeof commands / sizeof *commands; i++)
        if (!strcmp(argv[1], commands[i].name)) return commands[i].run(argc - 1, argv + 1);
    fprintf(stderr, "cubtool: unknown command '%s'\n\n", argv[1]);
    usage(stderr);
    return 2;
}

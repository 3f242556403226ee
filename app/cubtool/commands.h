/* The cubtool commands, one file each (cmd_<name>.c). Each gets argv with
 * argv[0] = the command's name, returns the process exit code (0 ok, 1 the
 * work failed, 2 bad usage), prints progress to stderr and results to
 * stdout, and documents itself under --help. */
#ifndef CUB_CUBTOOL_COMMANDS_H
#define CUB_CUBTOOL_COMMANDS_H

int cub_cmd_retarget(int argc, char **argv); /* a human clip -> the bear */
int cub_cmd_build(int argc, char **argv);    /* rebuild the clip library from its recipe */
int cub_cmd_tag(int argc, char **argv);      /* tag bridge frames across a library */
int cub_cmd_bench_bridge(int argc, char **argv); /* measure clip switching */
int cub_cmd_tween(int argc, char **argv);        /* the seed's tween clip, as BVH */
int cub_cmd_eval_track(int argc, char **argv);  /* the tracker on a depth dump: accuracy */
int cub_cmd_bench_track(int argc, char **argv); /* the tracker: ms per frame, memory */
int cub_cmd_synth_depth(int argc, char **argv); /* a synthetic child as Kinect depth */
int cub_cmd_bench_render(int argc, char **argv); /* the renderer: CPU per frame, ours vs GL */
int cub_cmd_play(int argc, char **argv);         /* the content maker's viewer */
int cub_cmd_encode(int argc, char **argv);       /* a clip -> the seed's codec stream */
int cub_cmd_decode(int argc, char **argv);       /* a codec stream -> BVH, as the box decodes */
int cub_cmd_codec_figures(int argc, char **argv); /* the seed's codec: errors and ratio */
int cub_cmd_bench_codec(int argc, char **argv);   /* ours, the seed's and ACL, side by side */
int cub_cmd_ase_export(int argc, char **argv);   /* a clip as a 3ds Max ASCII export */
int cub_cmd_trc_info(int argc, char **argv);     /* a TRC marker file: markers, frames, rate */
int cub_cmd_train_forest(int argc, char **argv); /* the body-part forest from synth renders */
int cub_cmd_eval_forest(int argc, char **argv);  /* its per-part accuracy on renders */
int cub_cmd_join(int argc, char **argv);         /* join two clips without sliding feet */
int cub_cmd_graph(int argc, char **argv);        /* the motion graph by support points */
int cub_cmd_evolve(int argc, char **argv);       /* two skeletons crossed into a child (seed 004) */
int cub_cmd_coach(int argc, char **argv);        /* a second coach's library from the bear's */
int cub_cmd_wings(int argc, char **argv);        /* the winged bear's assets, through evolve */
int cub_cmd_groove(int argc, char **argv);       /* seed 001: a MIDI melody, its segments, keys */
int cub_cmd_groove_eval(int argc, char **argv);  /* seed 001: beat alignment, speed, time */
int cub_cmd_gait(int argc, char **argv);         /* seed 003: a walk over a terrain, PNG frames */
int cub_cmd_gait_eval(int argc, char **argv);    /* seed 003: the figures, vs the baseline */

#endif

#!/usr/bin/env bash
# The demo: install what is missing, build, and run the box's main job on
# the simulator board: the bear leads a whole song (Twinkle Twinkle Little
# Star) for a child it watches through a replayed Kinect recording.
#
# The child is synthetic (scripts/make_child.py, scripts/child/twinkle.*):
# a child-sized body driven by motion capture follows the bear, rendered as
# Kinect v1 depth into a fakenect dump (cubtool synth-depth; ~2 GB in a
# temporary folder, deleted at the end). It gets five repetitions wrong on
# purpose (the wrong arm, no clap, no jump, standing still); the box tracks
# it, judges every repetition and corrects. START is pressed from
# scripts/demo.buttons. At the end the demo prints, per repetition, what
# was planted, the verdict and whether the coach corrected, then per
# planted mistake the latency from the mistake showing to the correcting
# clip's first frame (make_child.py score), and the counts.
#
# Headless (PNG frames + the event log, under the virtual clock: the run
# is exact and takes about a minute) unless a display exists (a window,
# real time).
#
# The child's performance ships with the project as a joint track
# (scripts/child/twinkle.jtrack, cut from CMU and AnimatedDrawings motion
# capture by scripts/make_demo_child.sh), so a fresh clone with nothing
# beside it runs the same demo, event log for event log, as one with
# ../shared/data.
#   scripts/demo.sh [--mocap | --scripted] [SECONDS]   default 110 (the song and the cheer)
#   --mocap     cut the child from ../shared/data's mocap and render it
#               from the clips, as scripts/e2e_child.sh does (its log, which
#               differs a little: see scripts/make_demo_child.sh)
#   --scripted  no child: a scripted judge (scripts/demo.timeline) over the
#               real Skeltrack frames when ../shared/data has them, else an
#               empty depth image
set -euo pipefail
cd "$(dirname "$0")/.."
child=track
case ${1:-} in
    --mocap) child=mocap; shift ;;
    --scripted) child=scripted; shift ;;
    -*) echo "usage: scripts/demo.sh [--mocap | --scripted] [SECONDS]" >&2; exit 2 ;;
esac
seconds=${1:-110}
scripts/setup.sh --host
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)" --target cubdance cubtool cub_fakenect_nosleep

out="$PWD/out/demo"
rm -rf "$out"
mkdir -p "$out"
data="${CUB_DATA_DIR:-$PWD/../shared/data}"
song=assets/songs/twinkle.song.xml
tool=./build/release/app/cubtool/cubtool
args=(--song "$song" --buttons scripts/demo.buttons --log "$out/events.log"
      --seconds "$seconds")
work=""
cleanup() { if [ -n "$work" ]; then rm -rf "$work"; fi; }
trap cleanup EXIT INT TERM

if [ "$child" = mocap ] && [ ! -d "$data/mocap" ]; then
    echo "demo: --mocap: no motion capture under $data (set CUB_DATA_DIR)" >&2
    exit 1
fi
if [ "$child" != scripted ]; then
    work=$(mktemp -d "${TMPDIR:-/tmp}/cubdance_demo.XXXXXX")
    plan=(assets/songs/twinkle.song.xml scripts/child/twinkle.plan "$work")
    if [ "$child" = mocap ]; then
        echo "demo: cutting the child from $data/mocap (scripts/child/twinkle.plan)"
        python3 scripts/make_child.py sequence "${plan[@]}" scripts/child/twinkle.cues
        source=(--sequence "$work/child.seq" --data "$data")
    else
        # scored against what the coach does with this child (see
        # scripts/make_demo_child.sh): twinkle_demo.cues
        echo "demo: the child: scripts/child/twinkle.jtrack (scripts/child/twinkle.plan)"
        python3 scripts/make_child.py expect "${plan[@]}" scripts/child/twinkle_demo.cues
        source=(--track scripts/child/twinkle.jtrack)
    fi
    echo "demo: rendering it as Kinect depth into $work/dump (about 2 GB, half a minute)"
    "$tool" synth-depth "${source[@]}" --out "$work/dump" 2>/dev/null | tail -n 1
    export FAKENECT_PATH="$work/dump"
    args+=(--replay "$work/dump")
else
    dump="$data/depth/skeltrack"
    echo "demo: --scripted: a scripted judge (scripts/demo.timeline)"
    args+=(--timeline scripts/demo.timeline)
    if [ -f "$dump/INDEX.txt" ]; then
        export FAKENECT_PATH="$dump"
        args+=(--replay "$dump")
    else
        args+=(--depth empty)
    fi
fi
if [ -n "${FAKENECT_PATH:-}" ]; then
    fakenect=$(ls -d /usr/lib/*/fakenect | head -n 1)
    export LD_LIBRARY_PATH="$fakenect${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
fi
if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
    echo "demo: a display exists: opening a window (Space = START, Escape = STOP)"
    args+=(--window)
else
    echo "demo: no display: running headless under the virtual clock"
    export EGL_PLATFORM=surfaceless
    # fakenect's sleeps would only hold the virtual clock to the wall's
    nosleep=build/release/tests/soak/libcub_fakenect_nosleep.so
    if [ -n "${FAKENECT_PATH:-}" ] && [ -f "$nosleep" ]; then
        export LD_PRELOAD="$PWD/$nosleep${LD_PRELOAD:+:$LD_PRELOAD}"
    fi
    args+=(--headless --clock virtual --size 960x540 --frames "$out/frames" --frame-every 90)
fi
export SDL_AUDIODRIVER="${SDL_AUDIODRIVER:-dummy}"
./build/release/app/cubdance/cubdance "${args[@]}"
echo
if [ -n "$work" ]; then
    echo "demo: what the coach saw and did, per repetition the child was led through:"
    python3 scripts/make_child.py score "$work/expect.txt" "$out/events.log" || true
    echo
fi
echo "demo: event log: $out/events.log ($(wc -l < "$out/events.log") lines)"
if [ -d "$out/frames" ]; then
    echo "demo: frames:    $out/frames ($(ls "$out/frames" | wc -l) PNG files)"
fi
